#include "engine/scene/inlet_options.hpp"

#include <cmath>

#include "engine/scene/loader_support.hpp"

namespace loom {
namespace {

// A 3D inlet: the disc (centre, radius) normal to the velocity, moving at section_velocity.
void read_disc(InletSpec& in, const TableReader& t) {
  for (const char* k : {"from", "to"})
    if (t.has(k)) t.error(k, std::string(k) + " is a key of a 2D inlet (a segment); a 3D inlet is a disc: centre, radius");
  if (t.has("from") || t.has("to")) return;
  if (!t.has("radius")) t.error("", "missing key radius (a 3D inlet is a disc: centre, radius)");
  in.centre = Vec3(t.component("centre", 0), t.component("centre", 1), t.component("centre", 2));
  in.radius = t.real("radius");
  in.velocity_z = t.component("velocity", 2);
  in.section_velocity = Vec3(t.component("section_velocity", 0), t.component("section_velocity", 1), t.component("section_velocity", 2));
  const Vec3 v(in.velocity.x(), in.velocity.y(), in.velocity_z);
  if (t.has("velocity") && !(v.norm() > 0.0)) t.error("velocity", "the velocity must not be zero (it is the disc's normal)");
  else if (std::abs(in.section_velocity.dot(v)) > 1e-9 * in.section_velocity.norm() * v.norm())
    t.error("section_velocity", "the section moves in its own plane: section_velocity must be perpendicular to velocity");
}

}  // namespace

void read_inlet(SceneSpec& s, const TableReader& t) {
  InletSpec in;
  in.name = read_name(t);
  in.where = t.where();
  if (find_by_name(s.inlets, in.name) != kNoIndex) t.error("name", "an inlet named \"" + in.name + "\" already exists");
  if (s.scene.method != Method::pfem && s.scene.method != Method::es_pfem)
    t.error("", std::string("[[inlet]] adds particles to a remeshed body (methods pfem, es_pfem); method ") + method_name(s.scene.method) +
                    " keeps its particles or mesh");
  if (t.has("body")) {
    const std::string body = t.string("body");
    in.body = find_by_name(s.bodies, body);
    if (in.body == kNoIndex) t.error("body", "no [[body]] named \"" + body + "\" (known: " + names_of(s.bodies) + ")");
  } else if (s.bodies.size() != 1) {
    t.error("", "missing key body (the scene has several bodies)");
  }
  in.velocity = t.vec2("velocity");
  in.start = t.real("start");
  in.duration = t.real("duration");
  in.spacing = t.real("spacing");
  if (s.scene.dimension == 3) {
    read_disc(in, t);
    s.inlets.push_back(in);
    return;
  }
  for (const char* k : {"centre", "radius", "section_velocity"})
    if (t.has(k)) t.error(k, std::string(k) + " is a key of a 3D inlet (a disc); a 2D inlet is the segment from `from` to `to`");
  in.from = t.vec2("from");
  in.to = t.vec2("to");
  const Vec2 section = in.to - in.from;
  if (t.has("from") && t.has("to") && !(section.norm() > 0.0)) t.error("to", "the section has zero length (from and to coincide)");
  // The velocity must carry material across the section: its normal component relative to its own size.
  const double across = std::abs(section.x() * in.velocity.y() - section.y() * in.velocity.x());
  if (t.has("velocity") && section.norm() > 0.0 && !(across > 1e-6 * section.norm() * in.velocity.norm()))
    t.error("velocity", in.velocity.norm() > 0.0 ? "the velocity is parallel to the section: nothing would flow in" : "the velocity must not be zero");
  s.inlets.push_back(in);
}

}  // namespace loom
