#include "engine/methods/model/fem_model.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "engine/core/errors.hpp"
#include "engine/methods/model/build_boundary_conditions.hpp"
#include "engine/methods/model/build_domains.hpp"
#include "engine/methods/model/build_mesh.hpp"
#include "engine/methods/model/build_solid_3d.hpp"
#include "engine/methods/model/build_walls.hpp"
#include "engine/methods/model/initial_velocity.hpp"
#include "engine/methods/model/memory_estimate.hpp"
#include "engine/store/history_columns.hpp"
#include "systems/assemble/compute_geometry.hpp"
#include "systems/update/lumped_mass.hpp"

namespace loom {
namespace {

bool has_body(const SceneSpec& scene, bool (*test)(Formulation)) {
  for (const auto& b : scene.bodies)
    if (test(b.element)) return true;
  return false;
}

bool mixed_formulation(Formulation f) { return has_dilatation(f) || has_pressure(f); }

// The mixed tangents are not symmetric (u-phi: seed 000 eqs 40-42; u-p: seed 001 eqs 60-61), nor is non-associated
// plasticity's: CHOLMOD, which reads one triangle, cannot take them.
LinearSolverKind linear_solver_for(const SceneSpec& scene) {
  if (has_unsymmetric_material(scene) && scene.solver.linear != LinearSolverKind::petsc) {
    LOOM_CHECK(!needs_spd(scene.solver.linear), InputError,
               scene.solver.linear_where << ": error: solver.linear: " << linear_solver_key(scene.solver.linear)
                          << " needs a symmetric tangent, and drucker_prager's non-associated flow (dilatancy_angle != friction_angle) "
                          << "makes it unsymmetric; use umfpack or auto");
    return LinearSolverKind::umfpack;
  }
  // petsc takes the mixed systems too (a Schur-complement fieldsplit, engine/linalg/petsc_solver.cpp).
  if (!has_body(scene, mixed_formulation) || scene.solver.linear == LinearSolverKind::petsc) return scene.solver.linear;
  const char* element = has_body(scene, has_dilatation) ? "p1p1_uphi" : has_body(scene, has_pressure) ? "es_up or fem_up" : "";
  LOOM_CHECK(!needs_spd(scene.solver.linear), InputError,
             scene.solver.linear_where << ": error: solver.linear: " << linear_solver_key(scene.solver.linear)
                        << " needs a symmetric tangent, and element " << element << " has none; use umfpack or auto");
  return LinearSolverKind::umfpack;
}

// Materials with history (a yielding hencky_perzyna, drucker_prager) at the points of the displacement elements p1, tri6 (tet10) and
// quad9 of methods fem and pfem carry b^e_n and the iterate's b^e per point (engine/store/history_columns.hpp; pfem's
// remesh carries them on: engine/methods/pfem/point_history_transfer.hpp). The smoothed elements carry it on their
// domains; the mixed elements refuse such materials.
std::vector<Formulation> formulations_carrying_history(const SceneSpec& scene) {
  std::vector<Formulation> f;
  if (scene.scene.method != Method::fem && scene.scene.method != Method::pfem) return f;
  for (const BodySpec& b : scene.bodies)
    if ((b.element == Formulation::p1 || b.element == Formulation::tri6 || b.element == Formulation::quad9) &&
        has_history(scene.materials[std::size_t(b.material)]))  // elastic Hencky (no tau0): a function of F
      f.push_back(b.element);
  return f;
}

}  // namespace

template <int D>
FemModelT<D>::FemModelT(const SceneSpec& spec) : scene(spec) {
  check_memory(scene);
  // 1. Columns: dynamic integrators need velocities and accelerations, lumped mass its column, mixed
  //    elements the dilatation.
  const bool dynamic = scene.time.integrator != Integrator::static_;
  for (auto* c : {&nodes.v, &nodes.v_n, &nodes.a, &nodes.a_n}) c->use(dynamic);
  nodes.lumped_mass.use(dynamic && scene.time.mass == MassKind::lumped);
  mixed = has_body(scene, mixed_formulation);
  const bool dilatation = has_body(scene, has_dilatation), pressure = has_body(scene, has_pressure);
  nodes.phi.use(dilatation);
  nodes.phi_n.use(dilatation);
  nodes.p.use(pressure);
  nodes.p_n.use(pressure);
  for (const auto& b : scene.bodies) j_projection.push_back(b.j_projection);
  nodes.J_node.use(scene.scene.method == Method::es_pfem || std::count(j_projection.begin(), j_projection.end(), 1) > 0);
  nodes.in_contact.use(!scene.walls.empty());
  nodes.contact_share.use(!scene.walls.empty());
  nodes.contact_point.use(!scene.walls.empty());
  linear_solver = linear_solver_for(scene);

  // 2. Mesh, quadrature points and the reference geometry.
  if constexpr (D == 2) node_body = build_mesh(scene, nodes, cells, &regions);
  else node_body = build_mesh_3d(scene, nodes, cells, &regions);
  materials = body_materials(scene);
  allocate_quad_points(cells, quad);
  use_history_columns(formulations_carrying_history(scene), cells, quad);
  if (compute_geometry(nodes, cells, quad) != 0) {
    // compute_geometry does not say which body: with one body, point at its mesh.
    std::ostringstream where;
    if (scene.bodies.size() == 1) where << scene.bodies[0].mesh.where << ": error: body[0].mesh";
    else where << scene.file << ": error: body mesh";
    throw InputError(where.str() + ": the generated mesh has inverted or degenerate cells (size or scale too extreme?)");
  }
  build_domains(nodes, cells, j_projection, edges);
  for (auto& e : edges)
    e.reference_geometry = e.size() > 0 && scene.materials[std::size_t(scene.bodies[std::size_t(e.stencil.body[0])].material)].model ==
                                                MaterialModel::linear_elastic;
  set_reference_areas(nodes, cells);
  if (nodes.lumped_mass.used()) compute_lumped_mass(cells, quad, materials, nodes);
  walls = build_walls(scene, nodes, cells, node_body);
  if (dynamic)
    for_each_initial_velocity<D>(
        scene, nodes.size(), [&](Index i) { return node_body[std::size_t(i)]; }, [&](Index i) { return Vec<D>(nodes.X[i]); },
        [&](Index i, const Vec<D>& v) { nodes.v[i] = v, nodes.v_n[i] = v; });

  // 3. Boundary conditions, dof numbering, sparsity and scatter.
  const int per_node = mixed ? D + 1 : D;  // the displacement components (, phi or p)
  if constexpr (D == 2)
    bc = build_boundary_conditions(scene, nodes, cells, node_body, regions, per_node, /*tie_mid_nodes=*/scene.scene.method == Method::pfem);
  else
    bc = build_boundary_conditions_3d(scene, nodes, cells, node_body, regions, per_node, /*tie_mid_nodes=*/scene.scene.method == Method::pfem);
  system.dofs.build(per_node, dof_kinds(bc, cells, nodes.size(), per_node), bc.ties);
  std::vector<const Cells*> blocks;
  for (const auto& c : cells) blocks.push_back(&c);
  for (const auto& e : edges) blocks.push_back(&e.stencil);
  build_pattern(blocks, system.dofs, system.pattern);
  system.scatter.resize(cells.size());
  for (std::size_t b = 0; b < cells.size(); ++b) build_scatter(cells[b], system.dofs, system.pattern, system.scatter[b]);
  system.domain_scatter.resize(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e) build_scatter(edges[e].stencil, system.dofs, system.pattern, system.domain_scatter[e]);
  system.resize_vectors();
}

template struct FemModelT<2>;
template struct FemModelT<3>;

}  // namespace loom
