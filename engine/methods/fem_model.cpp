#include "engine/methods/fem_model.hpp"

#include <sstream>

#include "engine/core/errors.hpp"
#include "engine/methods/build_boundary_conditions.hpp"
#include "engine/methods/build_mesh.hpp"
#include "engine/methods/memory_estimate.hpp"
#include "systems/assemble/compute_geometry.hpp"
#include "systems/update/lumped_mass.hpp"

namespace loom {
namespace {

bool has_mixed_bodies(const SceneSpec& scene) {
  for (const auto& b : scene.bodies)
    if (has_dilatation(b.element)) return true;
  return false;
}

// The mixed u-phi tangent is not symmetric (seed 000 eqs 40-42): CHOLMOD, which reads one triangle,
// cannot take it.
LinearSolverKind linear_solver_for(const SceneSpec& scene) {
  if (!has_mixed_bodies(scene)) return scene.solver.linear;
  LOOM_CHECK(scene.solver.linear != LinearSolverKind::cholmod, InputError,
             scene.file << ": error: solver.linear: cholmod needs a symmetric tangent, and element p1p1_uphi has none; use umfpack or auto");
  return LinearSolverKind::umfpack;
}

}  // namespace

FemModel::FemModel(const SceneSpec& spec) : scene(spec) {
  check_memory(scene);
  // 1. Columns: dynamic integrators need velocities and accelerations, lumped mass its column, mixed
  //    elements the dilatation.
  const bool dynamic = scene.time.integrator == Integrator::euler_backward;
  for (auto* c : {&nodes.v, &nodes.v_n, &nodes.a, &nodes.a_n}) c->use(dynamic);
  nodes.lumped_mass.use(dynamic && scene.time.mass == MassKind::lumped);
  mixed = has_mixed_bodies(scene);
  nodes.phi.use(mixed);
  nodes.phi_n.use(mixed);
  linear_solver = linear_solver_for(scene);

  // 2. Mesh, quadrature points and the reference geometry.
  node_body = build_mesh(scene, nodes, cells, &regions);
  materials = body_materials(scene);
  allocate_quad_points(cells, quad);
  if (compute_geometry(nodes, cells, quad) != 0) {
    // compute_geometry does not say which body: with one body, point at its mesh.
    std::ostringstream where;
    if (scene.bodies.size() == 1) where << scene.bodies[0].mesh.where << ": error: body[0].mesh";
    else where << scene.file << ": error: body mesh";
    throw InputError(where.str() + ": the generated mesh has inverted or degenerate cells (size or scale too extreme?)");
  }
  if (nodes.lumped_mass.used()) compute_lumped_mass(cells, quad, materials, nodes);

  // 3. Boundary conditions, dof numbering, sparsity and scatter.
  const int per_node = mixed ? 3 : 2;  // u_x, u_y (, phi)
  bc = build_boundary_conditions(scene, nodes, cells, node_body, regions, per_node, /*tie_mid_nodes=*/scene.scene.method == Method::pfem);
  system.dofs.build(per_node, dof_kinds(bc, cells, nodes.size(), per_node), bc.ties);
  std::vector<const Cells*> blocks;
  for (const auto& c : cells) blocks.push_back(&c);
  build_pattern(blocks, system.dofs, system.pattern);
  system.scatter.resize(cells.size());
  for (std::size_t b = 0; b < cells.size(); ++b) build_scatter(cells[b], system.dofs, system.pattern, system.scatter[b]);
  system.resize_vectors();

}

}  // namespace loom
