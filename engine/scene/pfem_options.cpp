#include "engine/scene/pfem_options.hpp"

#include <cstdlib>

namespace loom {

void read_pfem_options(SceneSpec& s, const TableReader& root) {
  const auto remesh = root.table("remesh"), map = root.table("map");
  const bool es = s.scene.method == Method::es_pfem;
  if (s.scene.method != Method::pfem && !es) {
    if (remesh.present()) root.error("remesh", "[remesh] is used by methods pfem and es_pfem only");
    if (map.present()) root.error("map", "[map] is used by method = \"pfem\" only");
    return;
  }
  // es_pfem transfers b^e from the nearest old edge and J from the particles (seed 001 §3.5): no choice.
  if (es && map.present()) root.error("map", "[map] is used by method = \"pfem\"; es_pfem transfers its edges' history itself");
  s.pfem.alpha = remesh.real("alpha");
  s.pfem.every = int(remesh.integer("every"));
  if (const auto l = remesh.expression("lchar"); l && remesh.has("lchar")) {
    char* end = nullptr;
    const double v = std::strtod(l->text.c_str(), &end);
    if (l->text == "local") {
      s.pfem.local = true;
    } else if (end && *end == '\0' && end != l->text.c_str() && v > 0.0) {
      s.pfem.local = false, s.pfem.lchar = v;
    } else {
      remesh.error("lchar", "expected a length > 0 or \"local\", got \"" + l->text + "\"");
    }
  }
  s.pfem.constrained_surface = remesh.string("surface") == "constrained";
  s.pfem.insert_above = remesh.real("insert_above");
  s.pfem.remove_below = remesh.real("remove_below");
  s.pfem.spacing = remesh.real("spacing");
  // Removal below r h0 and insertion above i h0 must leave room between them, or an inserted particle could be
  // removed again at the next remesh (its two half edges would be shorter than r h0).
  if (s.pfem.insert_above > 0.0 && s.pfem.remove_below > 0.0 && !(s.pfem.insert_above > 2.0 * s.pfem.remove_below))
    remesh.error("insert_above", "must exceed twice remesh.remove_below (" + std::to_string(s.pfem.remove_below) +
                                     "): the halves of a split edge would be removed again");
  // Named at the wall's key: remesh.insert_above may well be absent from the file.
  const auto walls = root.array("wall");
  for (std::size_t i = 0; i < s.walls.size() && i < walls.size(); ++i)
    if (s.walls[i].spacing > 0.0 && !(s.pfem.insert_above > 0.0))
      walls[i].error("spacing", "a spacing at the wall is made by particle insertion, which is off (set remesh.insert_above > 0)");
  s.pfem.keep_delaunay = remesh.boolean("keep_delaunay");
  s.pfem.repair = remesh.boolean("repair");
  // Measured with es_pfem (docs/pfem_3d.md §2): the slump flow's first half second diverges at step 107 (a cell
  // inverts after a repair), the printed layer stands 15 % taller than with the triangulating remesh.
  if (es && s.pfem.repair)
    remesh.error("repair", "remesh.repair is for method pfem: es_pfem's free-surface flows ran worse on repaired meshes (a slump "
                           "diverged, a printed layer stood 15 % too tall)");
  s.pfem.flip_quality = remesh.real("flip_quality");
  s.pfem.max_new_material = remesh.real("max_new_material");
  if (s.scene.dimension == 3) {
    // The 3D remesh keeps the cells inside the previous mesh (systems/remesh/remesh_3d.hpp): no constrained Delaunay to
    // choose between; particles are inserted (engine/methods/pfem/particle_insertion_3d.hpp), not removed yet.
    for (const char* k : {"surface", "remove_below", "spacing"})
      if (remesh.has(k)) remesh.error(k, std::string("remesh.") + k + " is two-dimensional (scene.dimension = 3 keeps the cells inside the "
                                                                       "previous mesh, inserts particles by remesh.insert_above and removes none)");
    // A new particle is appended after the others, where a tet10 body keeps its mid-nodes.
    const auto bodies = root.array("body");
    for (std::size_t b = 0; b < s.bodies.size() && b < bodies.size() && s.pfem.insert_above > 0.0; ++b)
      if (s.bodies[b].element == Formulation::tri6)
        remesh.error("insert_above", "particle insertion in 3D takes linear tetrahedra (p1, p1p1_uphi, es_up, es_u, fem_up, fem_u); body \"" +
                                         s.bodies[b].name + "\" is tet10");
    for (std::size_t i = 0; i < s.walls.size() && i < walls.size(); ++i)
      if (s.walls[i].spacing > 0.0) walls[i].error("spacing", "a wall's own spacing is two-dimensional (scene.dimension = 3 inserts at one spacing per body)");
    // A tetrahedron of a regular lattice has a circumradius about its edge length: below alpha = 1 the alpha test
    // would tear every body apart.
    if (s.pfem.alpha < 1.0) remesh.error("alpha", "in 3D alpha must be >= 1: below, the alpha test tears a regular lattice's cells apart");
  } else {
    for (const char* k : {"keep_delaunay", "repair", "flip_quality"})
      if (remesh.has(k)) remesh.error(k, std::string("remesh.") + k + " is used by the 3D remesh (scene.dimension = 3) only");
  }
  s.pfem.btm = map.string("scheme") == "btm";
  s.pfem.iso = int(map.integer("iso"));
  if (!s.pfem.btm && map.has("iso") && s.pfem.iso != 0) map.error("iso", "iso is used by scheme = \"btm\" only (CPM copies F as it is)");
}

}  // namespace loom
