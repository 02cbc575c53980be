#include "engine/scene/dimension_options.hpp"

#include <algorithm>

namespace loom {

void check_element_dimension(int dimension, Method method, const std::string& element, const TableReader& body) {
  if (dimension == 2 && element == "tet10")
    body.error("element", "tet10 is a tetrahedron: it needs scene.dimension = 3 (the quadratic triangle is tri6)");
  if (dimension == 3 && method == Method::mpm) {
    if (element != "p1" && element != "p1p1_up")
      body.error("element", "a 3D mpm grid is linear tetrahedra: element p1 (displacement) or p1p1_up (mixed u-p); " + element +
                                " is not an element of method mpm in 3D");
    return;
  }
  const bool smoothed = element == "es_up" || element == "es_u" || element == "fem_up" || element == "fem_u";
  if (dimension == 3 && smoothed && method != Method::fem && method != Method::es_pfem)
    body.error("element", "element " + element + " on tetrahedra (face-based smoothing) runs with methods fem and es_pfem; method " +
                              method_name(method) + " in 3D takes p1, tet10 or p1p1_uphi");
  if (dimension == 3 && !smoothed && element != "p1" && element != "tet10" && element != "p1p1_uphi")
    body.error("element", "element " + element + " is two-dimensional; in 3D (scene.dimension = 3) the elements are p1 (linear "
                          "tetrahedron), tet10 (quadratic tetrahedron), p1p1_uphi (mixed linear tetrahedron) and the smoothed "
                          "es_up, es_u, fem_up, fem_u (methods fem and es_pfem)" +
                          (element == "tri6" ? std::string(": tri6's counterpart is tet10") : std::string()));
}

void read_mesh_dimension(int dimension, const TableReader& mesh, MeshSpec& m) {
  if (!mesh.present()) return;
  const bool box = mesh.string("generator") == "box";
  if (dimension == 2 && mesh.has("lattice")) mesh.error("lattice", "lattice is a choice of the 3D generator box (scene.dimension = 3)");
  if (dimension == 2) {
    if (box) mesh.error("generator", "box is a 3D generator (scene.dimension = 3); in 2D use rectangle");
    if (mesh.has("depth")) mesh.error("depth", "depth extrudes a mesh into 3D: it needs scene.dimension = 3");
    return;
  }
  if (m.generator == MeshGenerator::file) return;  // tetrahedra from the file (read_mesh refused the generators' keys)
  if (box) {
    m.generator = MeshGenerator::box;
    m.origin_z = mesh.component("origin", 2);
    m.size_z = mesh.component("size", 2);
    if (mesh.has("size") && !(m.size_z > 0)) mesh.error("size", "the box's size must be > 0 along x, y and z");
    m.nz = int(mesh.component("divisions", 2));
    if (mesh.has("divisions") && m.nz < 1) mesh.error("divisions", "divisions must be >= 1");
    if (mesh.has("divisions") && double(m.nx) * m.ny * m.nz * 6 > 5e7) mesh.error("divisions", "more than 5e7 tetrahedra requested");
    for (const char* k : {"depth", "pattern"})
      if (mesh.has(k)) mesh.error(k, std::string(k) + " is not used by generator = \"box\" (its cells are Kuhn tetrahedra or a BCC lattice)");
    m.bcc = mesh.has("lattice") && mesh.string("lattice") == "bcc";
    return;
  }
  if (mesh.has("lattice")) mesh.error("lattice", "lattice is a choice of generator = \"box\"");
  // rectangle and cooks_membrane: the plane mesh extruded along z.
  if (!mesh.has("depth")) mesh.error("", "missing key depth: in 3D a rectangle or cooks_membrane mesh is extruded along z (or use generator = \"box\")");
  m.depth = mesh.real("depth");
  m.layers = int(mesh.component("divisions", 2));
  if (mesh.has("divisions") && m.layers < 1) mesh.error("divisions", "divisions must be >= 1 (the third: layers along z)");
  if (mesh.has("origin") && mesh.component("origin", 2) != 0.0)
    mesh.error("origin", "an extruded mesh spans z from 0 to depth: give origin's z as 0");
  if (mesh.has("size") && mesh.component("size", 2) != m.depth) mesh.error("size", "an extruded mesh spans z from 0 to depth: give size's z as depth");
  if (double(m.nx) * m.ny * m.layers * 6 > 5e7) mesh.error("divisions", "more than 5e7 tetrahedra requested");
}

void check_dimension_support(const SceneSpec& s, const TableReader& root) {
  if (s.scene.dimension != 3) return;
  const auto scene = root.table("scene");
  if (s.scene.method == Method::mpm_fem)
    scene.error("method", std::string("scene.dimension = 3 is implemented for methods fem, pfem, es_pfem and mpm; method ") +
                              method_name(s.scene.method) + " is two-dimensional");
  if (s.scene.method == Method::mpm) {
    const auto grid = root.table("grid");
    if (grid.has("cells")) grid.error("cells", "a 3D grid is linear tetrahedra (tet4): leave cells out");
    if (grid.has("ghost_penalty")) grid.error("ghost_penalty", "the face ghost penalty belongs to 2D quadrilateral grids");
    const auto mpm = root.table("mpm");
    if (mpm.string("scheme") == "particle_newmark")  // read_mpm_options, which sets s.mpm.scheme, runs after this
      mpm.error("scheme", "scheme = \"particle_newmark\" is two-dimensional; 3D runs the grid Newmark scheme of [Moreno et al.]");
    const auto bodies = root.array("body");
    for (std::size_t b = 0; b < bodies.size() && b < s.bodies.size(); ++b)
      if (s.bodies[b].particles.kind != ParticleGenerator::none)
        bodies[b].error("particles", "generated particle sets are two-dimensional; a 3D mpm body samples its tetrahedral mesh (particles_per_cell)");
  }
  if (s.scene.method == Method::pfem || s.scene.method == Method::es_pfem) {
    // A body one cell across has no particle inside: its every cell touches the surface, the remesh has nothing to hold
    // it by (a lattice of at least two cells each way).
    const auto bodies = root.array("body");
    for (std::size_t b = 0; b < bodies.size() && b < s.bodies.size(); ++b) {
      const MeshSpec& m = s.bodies[b].mesh;
      if (m.generator == MeshGenerator::box && std::min({m.nx, m.ny, m.nz}) < 2)
        bodies[b].table("mesh").error("divisions", "methods pfem and es_pfem in 3D need at least two cells of the lattice along x, y and z (one layer "
                                                   "has no particle inside for the remesh to hold the body by)");
    }
  }
  // Walls are planes in 3D (point, normal or a box of six); inlets discs. A new layer's particles are appended after
  // the others, where a tet10 body keeps its mid-nodes.
  const auto inlets = root.array("inlet");
  for (std::size_t k = 0; k < s.inlets.size() && k < inlets.size(); ++k)
    if (s.bodies[std::size_t(s.inlets[k].body)].element == Formulation::tri6)
      inlets[k].error("body", "inflow in 3D takes linear tetrahedra (p1, p1p1_uphi, es_up, es_u, fem_up, fem_u); body \"" +
                                  s.bodies[std::size_t(s.inlets[k].body)].name + "\" is tet10");
  const auto probes = root.array("probe");
  for (std::size_t k = 0; k < probes.size() && k < s.probes.size(); ++k) {
    const ProbeKind kind = s.probes[k].kind;
    const auto& t = probes[k];
    if (kind == ProbeKind::pressure_jump)
      t.error("kind", "kind = \"pressure_jump\" reads triangles and quadrilaterals: two-dimensional");
    if (kind == ProbeKind::angular_momentum && !t.has("component"))
      t.error("", "missing key component: in 3D an angular_momentum probe reads one component (x, y or z) of sum m r x v");
  }
}

}  // namespace loom
