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
  const bool three_d = s.scene.dimension == 3;
  if (plane) {
    if (!t.has("point")) t.error("", "missing key point (the plane passes through it)");
    if (!t.has("normal")) t.error("", "missing key normal (the plane's normal, pointing to the side the material occupies)");
    if (three_d) {
      const Vec3 n(t.component("normal", 0), t.component("normal", 1), t.component("normal", 2));
      if (t.has("normal") && !(n.norm() > 0.0)) t.error("normal", "the normal must not be zero");
      if (n.norm() > 0.0) w.planes.push_back({Vec3(t.component("point", 0), t.component("point", 1), t.component("point", 2)), n.normalized()});
    } else {
      const Vec2 n = t.vec2("normal");
      if (t.has("normal") && !(n.norm() > 0.0)) t.error("normal", "the normal must not be zero");
      const Vec2 point = t.vec2("point"), unit = n.normalized();
      if (n.norm() > 0.0) w.planes.push_back({Vec3(point.x(), point.y(), 0.0), Vec3(unit.x(), unit.y(), 0.0)});
    }
  } else if (t.has("box")) {
    // The material stays inside: the sides (left, right, bottom, top, then back and front) with inward normals.
    const int D = three_d ? 3 : 2;
    Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
    for (int i = 0; i < D; ++i) lo[i] = t.box_component("box", 0, i), hi[i] = t.box_component("box", 1, i);
    if (!((hi - lo).head(D).minCoeff() > 0.0))
      t.error("box", three_d ? "expected [[xmin, ymin, zmin], [xmax, ymax, zmax]] with min < max along x, y and z"
                             : "expected [[xmin, ymin], [xmax, ymax]] with xmin < xmax and ymin < ymax");
    for (int i = 0; i < D; ++i) {
      Vec3 inward = Vec3::Zero(), back = Vec3::Zero();  // no negative zeros: the 2D gaps stay bit for bit
      inward[i] = 1.0, back[i] = -1.0;
      w.planes.push_back({lo, inward}), w.planes.push_back({hi, back});
    }
  }
  std::size_t planes = w.planes.size();
  for (const WallSpec& other : s.walls) planes += other.planes.size();
  if (planes > std::size_t(kMaxWallPlanes))
    t.error(w.planes.size() > 1 ? "box" : "normal", "the walls have " + std::to_string(planes) + " planes in all, at most " +
                                                        std::to_string(kMaxWallPlanes) + " are supported (a box is four, six in 3D)");
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
