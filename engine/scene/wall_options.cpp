#include "engine/scene/wall_options.hpp"

#include "engine/scene/loader_support.hpp"
#include "engine/store/walls.hpp"

namespace loom {

void read_wall(SceneSpec& s, const TableReader& t) {
  WallSpec w;
  w.name = read_name(t);
  w.where = t.where();
  if (find_by_name(s.walls, w.name) != kNoIndex) t.error("name", "a wall named \"" + w.name + "\" already exists");
  if (is_mpm(s.scene.method))
    t.error("", "[[wall]] acts on mesh nodes (methods fem, pfem, es_pfem); method mpm's walls are grid boundaries with a displacement");
  const bool plane = t.has("point") || t.has("normal");
  if (plane && t.has("box")) t.error("box", "give either point and normal (a plane) or box, not both");
  if (!plane && !t.has("box") && t.present()) t.error("", "missing key point and normal (a plane) or box");
  if (plane) {
    if (!t.has("point")) t.error("", "missing key point (the plane passes through it)");
    if (!t.has("normal")) t.error("", "missing key normal (the plane's normal, pointing to the side the material occupies)");
    const Vec2 n = t.vec2("normal");
    if (t.has("normal") && !(n.norm() > 0.0)) t.error("normal", "the normal must not be zero");
    if (n.norm() > 0.0) w.planes.push_back({t.vec2("point"), n.normalized()});
  } else if (t.has("box")) {
    const auto b = t.box("box");
    if (!(b[1].x() > b[0].x() && b[1].y() > b[0].y())) t.error("box", "expected [[xmin, ymin], [xmax, ymax]] with xmin < xmax and ymin < ymax");
    // The material stays inside: left, right, bottom, top sides with inward normals.
    w.planes = {{b[0], Vec2(1, 0)}, {b[1], Vec2(-1, 0)}, {b[0], Vec2(0, 1)}, {b[1], Vec2(0, -1)}};
  }
  std::size_t planes = w.planes.size();
  for (const WallSpec& other : s.walls) planes += other.planes.size();
  if (planes > std::size_t(kMaxWallPlanes))
    t.error(w.planes.size() == 4 ? "box" : "normal", "the walls have " + std::to_string(planes) + " planes in all, at most " +
                                                         std::to_string(kMaxWallPlanes) + " are supported (a box is four)");
  if (t.has("body")) {
    const std::string body = t.string("body");
    w.body = find_by_name(s.bodies, body);
    if (w.body == kNoIndex) t.error("body", "no [[body]] named \"" + body + "\" (known: " + names_of(s.bodies) + ")");
  }
  w.penalty = t.real("penalty");
  w.stick = t.string("slip") == "stick";
  w.spacing = t.real("spacing");
  if (w.spacing > 0.0 && s.scene.method != Method::pfem && s.scene.method != Method::es_pfem)
    t.error("spacing", "the remesh spacing at a wall is used by methods pfem and es_pfem (they insert and remove particles)");
  w.spacing_ramp = t.real("spacing_ramp");
  if (w.spacing_ramp > 0.0 && !(w.spacing > 0.0))
    t.error("spacing_ramp", "a ramp grades the wall's spacing, which is not given (set spacing > 0)");
  s.walls.push_back(w);
}

}  // namespace loom
