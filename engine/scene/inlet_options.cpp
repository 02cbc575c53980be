#include "engine/scene/inlet_options.hpp"

#include <cmath>

#include "engine/scene/loader_support.hpp"

namespace loom {

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
  in.from = t.vec2("from");
  in.to = t.vec2("to");
  in.velocity = t.vec2("velocity");
  in.start = t.real("start");
  in.duration = t.real("duration");
  in.spacing = t.real("spacing");
  const Vec2 section = in.to - in.from;
  if (t.has("from") && t.has("to") && !(section.norm() > 0.0)) t.error("to", "the section has zero length (from and to coincide)");
  // The velocity must carry material across the section: its normal component relative to its own size.
  const double across = std::abs(section.x() * in.velocity.y() - section.y() * in.velocity.x());
  if (t.has("velocity") && section.norm() > 0.0 && !(across > 1e-6 * section.norm() * in.velocity.norm()))
    t.error("velocity", in.velocity.norm() > 0.0 ? "the velocity is parallel to the section: nothing would flow in" : "the velocity must not be zero");
  s.inlets.push_back(in);
}

}  // namespace loom
