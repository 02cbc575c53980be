// The stores of a 3D MPM run (seed 003 §6.3-6.4): a background grid of linear tetrahedra (a Kuhn box, an
// extruded plane mesh or a gmsh file), material points at a symmetric tetrahedral rule in every cell of each
// body's tetrahedral mesh (engine/mesh/tet_particles.hpp), the grid's boundary conditions, point-probe tracers.
// 3D runs take method mpm with the grid Newmark scheme and no ghost penalty; the 2D-only members of MpmModelT
// stay empty. Tractions act at traction points on the loaded boundary faces of the body mesh.
#include <Eigen/Geometry>
#include <sstream>

#include "engine/core/errors.hpp"
#include "engine/graph/step_context.hpp"
#include "engine/mesh/tet_background_grid.hpp"
#include "engine/mesh/tet_particles.hpp"
#include "engine/mesh/triangle_rules.hpp"
#include "engine/methods/model/build_boundary_conditions.hpp"
#include "engine/methods/model/build_solid_3d.hpp"
#include "engine/methods/model/initial_velocity.hpp"
#include "engine/methods/model/memory_estimate.hpp"
#include "engine/methods/model/mpm_model.hpp"
#include "systems/locate/activate_grid.hpp"
#include "systems/locate/locate_points.hpp"

namespace loom {
namespace {

// The background grid; a box generated undistorted is located by arithmetic over its cubes.
void build_grid_3d(const SceneSpec& scene, Formulation element, Nodes<3>& nodes, Cells& grid, GridLayoutT<3>& layout) {
  const MeshSpec& gm = scene.grid.mesh;
  try {
    const TetMeshData mesh = tet4_mesh_of(gm);
    BoxSpec box;
    box.origin = Vec3(gm.origin.x(), gm.origin.y(), gm.origin_z) * gm.scale;
    box.size = Vec3(gm.size.x(), gm.size.y(), gm.size_z) * gm.scale;
    box.nx = gm.nx, box.ny = gm.ny, box.nz = gm.nz;
    const bool structured = gm.generator == MeshGenerator::box && gm.distortion == 0.0;
    build_tet_grid(mesh, structured ? &box : nullptr, element, nodes, grid, layout);
  } catch (const InputError& e) {
    const std::string what = e.what();
    if (what.find(": error: ") != std::string::npos) throw;  // a mesh file's own message names it
    std::ostringstream os;
    os << gm.where << ": error: grid: " << what;
    throw InputError(os.str());
  }
}

// Material points of every body: the points of a tetrahedral rule in each cell of the body's mesh.
void build_material_points_3d(const SceneSpec& scene, Points<3>& particles) {
  std::vector<Vec3> X;
  std::vector<double> volume, mass;
  std::vector<Index> body;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const BodySpec& spec = scene.bodies[b];
    const double density = scene.materials[std::size_t(spec.material)].density;
    TetParticles t;
    try {
      t = place_tet_particles(tet4_mesh_of(spec.mesh), spec.particles_per_cell, density);
    } catch (const InputError& e) {
      const std::string what = e.what();
      if (what.find(": error: ") != std::string::npos) throw;
      std::ostringstream os;
      os << spec.mesh.where << ": error: body[" << b << "].mesh: " << what;
      throw InputError(os.str());
    }
    X.insert(X.end(), t.X.begin(), t.X.end());
    volume.insert(volume.end(), t.volume.begin(), t.volume.end());
    mass.insert(mass.end(), t.mass.begin(), t.mass.end());
    body.insert(body.end(), t.X.size(), Index(b));
  }
  particles.resize(Index(X.size()));
  for (Index p = 0; p < particles.X.size(); ++p) {
    const auto k = std::size_t(p);
    particles.X[p] = X[k], particles.volume[p] = volume[k], particles.mass[p] = mass[k], particles.body[p] = body[k];
  }
}

// Traction points: the three-point (degree 2) triangle rule on every boundary face of the body's tetrahedral mesh
// with its three corners in the region's box: exact for the grid's linear shape functions times a linear
// traction on the face. Weight: the point's share of the face's reference area (the 2D edges' counterpart).
void build_traction_points_3d(const SceneSpec& scene, Points<3>& points, BoundaryConditions<3>& bc) {
  std::vector<Vec3> X;
  std::vector<double> weight;
  std::vector<Index> body;
  const std::vector<TrianglePoint>& rule = triangle_rule(3);
  for (std::size_t k = 0; k < scene.boundaries.size(); ++k) {
    const BoundarySpec& spec = scene.boundaries[k];
    if (!spec.has_traction) continue;
    const TetMeshData mesh = tet4_mesh_of(scene.bodies[std::size_t(spec.body)].mesh);
    Vec3 lo = mesh.X[0], hi = mesh.X[0];
    for (const auto& x : mesh.X) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
    const double tol = 1e-9 * std::max(1.0, (hi - lo).norm());
    const Vec3 bmin(spec.box_min.x(), spec.box_min.y(), spec.box_min_z), bmax(spec.box_max.x(), spec.box_max.y(), spec.box_max_z);
    auto inside = [&](Index i) { return (mesh.X[std::size_t(i)] - bmin).minCoeff() >= -tol && (bmax - mesh.X[std::size_t(i)]).minCoeff() >= -tol; };
    std::array<Index, 3> expr{kNoIndex, kNoIndex, kNoIndex};
    for (int d = 0; d < 3; ++d)
      if (spec.traction[d]) expr[std::size_t(d)] = add_expression(bc, *spec.traction[d]), bc.has_loads = true;
    // region.normal: boundary_faces orients every face outward ((x1 - x0) x (x2 - x0) points out of the body).
    const std::optional<Vec3> direction = region_normal<3>(spec);
    std::size_t n_faces = 0, n_in_region = 0;  // loaded; in the region, before region.normal's filter
    for (const BoundaryFace& f : boundary_faces(mesh.tets)) {
      if (!inside(f.nodes[0]) || !inside(f.nodes[1]) || !inside(f.nodes[2])) continue;
      ++n_in_region;
      const Vec3 &x0 = mesh.X[std::size_t(f.nodes[0])], &x1 = mesh.X[std::size_t(f.nodes[1])], &x2 = mesh.X[std::size_t(f.nodes[2])];
      const Vec3 outward = (x1 - x0).cross(x2 - x0);
      if (direction && !faces_direction<3>(outward, *direction)) continue;
      ++n_faces;
      const double area = 0.5 * outward.norm();
      for (const TrianglePoint& q : rule) {
        X.push_back(q.l[0] * x0 + q.l[1] * x1 + q.l[2] * x2);
        weight.push_back(q.w * area);
        body.push_back(spec.body);
        bc.traction_point_expression.push_back(expr);
      }
    }
    check_traction_support(scene, k, n_faces, n_in_region, "boundary faces of the body mesh with every corner in the region");
  }
  points.resize(Index(X.size()));
  for (Index q = 0; q < points.X.size(); ++q) {
    const auto i = std::size_t(q);
    points.X[q] = X[i], points.volume[q] = weight[i], points.body[q] = body[i];
  }
}

}  // namespace

template <>
MpmModelT<3>::MpmModelT(const SceneSpec& spec) : scene(spec) {
  check_memory(scene);
  const BodySpec& body = scene.bodies.at(std::size_t(mpm_body_index(scene)));
  // 1. Columns the scene needs.
  set_columns(body);

  // 2. Grid, particles, probe tracers, conditions.
  build_grid_3d(scene, body.element, grid_nodes, grid, layout);
  materials = body_materials(scene);
  build_material_points_3d(scene, particles);
  if (dynamic)
    for_each_initial_velocity<3>(
        scene, particles.X.size(), [&](Index p) { return particles.body[p]; }, [&](Index p) { return Vec3(particles.X[p]); },
        [&](Index p, const Vec3& v) { particles.v[p] = v; });
  bc.per_node = mixed ? 4 : 3;
  build_traction_points_3d(scene, traction_points, bc);
  std::vector<Vec3> tracers;
  for (const auto& p : scene.probes)
    if (p.kind == ProbeKind::point) tracers.emplace_back(p.at.x(), p.at.y(), p.at_z);
  probe_points.resize(Index(tracers.size()));
  for (Index k = 0; k < probe_points.X.size(); ++k) probe_points.X[k] = tracers[std::size_t(k)];
  build_grid_conditions(scene, grid_nodes, layout, bc);
  finish_conditions();

  // 3. Where the points are, and the active grid.
  StepContext ctx;
  ctx.scene = &scene;
  const MeshSpec& gm = scene.grid.mesh;
  try {
    locate_points(ctx, layout, grid, grid_nodes, particles, particle_loc);
    locate_points(ctx, layout, grid, grid_nodes, traction_points, traction_loc);
  } catch (const RunError& e) {
    std::ostringstream os;
    os << gm.where << ": error: grid: the body does not fit in the background grid at t = 0: " << e.what();
    throw InputError(os.str());
  }
  locate_probe_points(ctx);
  activate_grid(ctx, grid, particle_loc, bc, activity, system);
}

}  // namespace loom
