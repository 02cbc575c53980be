#include "engine/methods/model/mpm_model.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "engine/core/errors.hpp"
#include "engine/graph/step_context.hpp"
#include "engine/mesh/background_grid.hpp"
#include "engine/mesh/quad9_grid.hpp"
#include "engine/methods/model/build_boundary_conditions.hpp"
#include "engine/methods/model/build_mesh.hpp"
#include "engine/methods/model/build_particles.hpp"
#include "engine/methods/model/initial_velocity.hpp"
#include "engine/methods/model/memory_estimate.hpp"
#include "systems/locate/activate_grid.hpp"
#include "systems/locate/contact_flags.hpp"
#include "systems/locate/locate_points.hpp"

namespace loom {
namespace {

// A node's position as text, for messages.
template <int D>
std::string point_text(const Vec<D>& X, const char* open = "(", const char* close = ")") {
  std::ostringstream os;
  os << open << X.x() << ", " << X.y();
  if constexpr (D == 3) os << ", " << X.z();
  os << close;
  return os.str();
}

}  // namespace

// Prescribed dofs on the grid nodes of each [[boundary]] region; body-force expressions per body.
template <int D>
void build_grid_conditions(const SceneSpec& scene, const Nodes<D>& nodes, const GridLayoutT<D>& layout, BoundaryConditions<D>& bc) {
  const int pn = bc.per_node;
  const double tol = 1e-9 * std::max(1.0, layout.width());
  std::map<Index, std::size_t> prescribed_at;
  for (std::size_t k = 0; k < scene.boundaries.size(); ++k) {
    const BoundarySpec& spec = scene.boundaries[k];
    std::vector<Index> selected;
    for (Index i = 0; i < nodes.size(); ++i) {
      const Vec<D>& X = nodes.X[i];
      bool in = X.x() >= spec.box_min.x() - tol && X.x() <= spec.box_max.x() + tol && X.y() >= spec.box_min.y() - tol &&
                X.y() <= spec.box_max.y() + tol;
      if constexpr (D == 3) in = in && X.z() >= spec.box_min_z - tol && X.z() <= spec.box_max_z + tol;
      if (in) selected.push_back(i);
    }
    bc.boundary_names.push_back(spec.name);
    bc.boundary_nodes.push_back(selected);
    bc.boundary_prescribed.emplace_back();
    std::array<const std::optional<ExpressionSpec>*, D + 1> comps;
    for (int d = 0; d < D; ++d) comps[std::size_t(d)] = &spec.displacement[d];
    comps[D] = &spec.pressure;
    bool prescribes = false;
    for (const auto* c : comps) prescribes = prescribes || c->has_value();
    LOOM_CHECK(!prescribes || !selected.empty(), InputError,
               spec.region_where << ": error: boundary[" << k << "].region.box: method mpm prescribes values on grid nodes, and the region "
                                 << "holds none (the grid spans " << point_text<D>(layout.lo, "[", "]") << " to " << point_text<D>(layout.hi, "[", "]") << ")");
    for (int d = 0; d < D + 1; ++d) {
      if (!*comps[d]) continue;
      const Index expr = add_expression(bc, **comps[d]);
      const Expression& g = bc.expressions[std::size_t(expr)];
      for (Index i : selected) {
        // The particles start undisplaced: a displacement must vanish at t = 0 where the grid applies it.
        const Vec<D>& X = nodes.X[i];
        const double g0 = d < D ? (D == 3 ? g(0.0, X.x(), X.y(), X[D - 1]) : g(0.0, X.x(), X.y())) : 0.0;
        LOOM_CHECK(g0 == 0.0, InputError,
                   (*comps[d])->where << ": error: " << (*comps[d])->key << ": method mpm moves the grid nodes by the increments of the "
                                      << "prescribed displacement, which must vanish at t = 0 (the particles start undisplaced); it is "
                                      << g0 << " at grid node " << point_text<D>(X) << ": ramp it, e.g. \"t * ("
                                      << (*comps[d])->text << ")\"");
        const Index dof = i * pn + d;
        auto it = prescribed_at.find(dof);
        if (it != prescribed_at.end()) {
          const std::string& other = bc.expressions[std::size_t(bc.prescribed[it->second].expression)].text();
          LOOM_CHECK(other == g.text(), InputError,
                     (*comps[d])->where << ": error: " << (*comps[d])->key << ": grid node " << point_text<D>(nodes.X[i])
                                        << " is also prescribed by another boundary with \"" << other << "\"");
          continue;
        }
        prescribed_at[dof] = bc.prescribed.size();
        bc.prescribed.push_back({dof, i, expr});
        bc.boundary_prescribed.back().push_back(Index(bc.prescribed.size() - 1));
      }
    }
  }
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    std::array<Index, D> expr;
    expr.fill(kNoIndex);
    for (int d = 0; d < D; ++d) {
      const auto e = combine(scene.body_force[d], scene.bodies[b].body_force[d]);
      if (e) expr[std::size_t(d)] = add_expression(bc, *e), bc.has_loads = true;
    }
    bc.body_force.push_back(expr);
  }
}

template void build_grid_conditions<2>(const SceneSpec&, const Nodes<2>&, const GridLayoutT<2>&, BoundaryConditions<2>&);
template void build_grid_conditions<3>(const SceneSpec&, const Nodes<3>&, const GridLayoutT<3>&, BoundaryConditions<3>&);

namespace {

RectangleSpec rectangle_of(const MeshSpec& m) {
  RectangleSpec r;
  r.origin = m.origin * m.scale, r.size = m.size * m.scale, r.nx = m.nx, r.ny = m.ny, r.pattern = m.pattern;
  return r;
}

}  // namespace

// The columns the scene needs (both dimensions: the 2D-only ones stay unused in 3D).
template <int D>
void MpmModelT<D>::set_columns(const BodySpec& body) {
  coupled = scene.scene.method == Method::mpm_fem;
  dynamic = scene.time.integrator == Integrator::newmark;
  mixed = body.element == Formulation::p1p1_up;
  osgs = mixed && body.stabilisation == Stabilisation::osgs;
  particle_newmark = scene.mpm.scheme == MpmScheme::particle_newmark;
  grid_nodes.u_n.use(coupled);  // the grid starts every step undeformed (mpm_fem: at its reference): u is the step's displacement
  grid_nodes.lumped_mass.use(!particle_newmark);  // particle Newmark: the grid carries no mass, velocity or acceleration
  for (auto* c : {&grid_nodes.v_n, &grid_nodes.a_n, &grid_nodes.v, &grid_nodes.a}) c->use(dynamic && !particle_newmark);
  if (coupled) grid_nodes.v.use(), grid_nodes.a.use();  // the FEM nodes' Newmark state
  grid_nodes.p.use(mixed);
  grid_nodes.proj_u.use(osgs), grid_nodes.proj_p.use(osgs), grid_nodes.lumped_volume.use(osgs);
  for (auto* c : {&particles.X, &particles.u}) c->use();
  particles.mass.use(), particles.volume.use(), particles.F.use(), particles.body.use();
  particles.v.use(dynamic), particles.a.use(dynamic);
  particles.pressure.use(mixed);
  particles.proj_u.use(osgs), particles.proj_p.use(osgs);
  particle_loc.F.use();
  // Materials with history carry b^e at the particles (converged) and at their locations (the iterate's): a
  // hencky_perzyna that yields, drucker_prager. Without tau0 hencky_perzyna is elastic Hencky, a function of F
  // (b^e = F F^T), and pays nothing.
  const bool history = std::any_of(scene.bodies.begin(), scene.bodies.end(), [&](const BodySpec& b) {
    const MaterialSpec& m = scene.materials[std::size_t(b.material)];
    return b.element == Formulation::p1 && has_history(m);
  });
  particles.be.use(history), particle_loc.be.use(history);
  particle_loc.xi.use(scene.grid.quad9);
  particle_loc.N.use(!scene.grid.quad9);
  particle_loc.receding.use(particle_newmark && scene.mpm.receding_contact > 0.0);
  traction_points.X.use(), traction_points.u.use(), traction_points.volume.use(), traction_points.body.use();
  traction_loc.entity = "traction point";
  probe_points.X.use(), probe_points.u.use();
  probe_loc.entity = "probe point";
}

// UMFPACK for the mixed system, receding contact and non-associated plasticity (unsymmetric, indefinite), the scene's
// choice otherwise (petsc takes them all: GMRES, or a Schur-complement fieldsplit).
template <int D>
void MpmModelT<D>::choose_linear_solver() {
  const bool unsymmetric = particle_newmark && scene.mpm.receding_contact > 0.0;  // receding contact: K T
  const bool non_associated = has_unsymmetric_material(scene);
  linear_solver = (mixed || unsymmetric || non_associated) && scene.solver.linear != LinearSolverKind::petsc ? LinearSolverKind::umfpack
                                                                                                            : scene.solver.linear;
  const char* chosen = linear_solver_key(scene.solver.linear);
  LOOM_CHECK(!(non_associated && needs_spd(scene.solver.linear)), InputError,
             scene.solver.linear_where << ": error: solver.linear: " << chosen << " needs a symmetric tangent, and drucker_prager's "
                        << "non-associated flow (dilatancy_angle != friction_angle) makes it unsymmetric; use umfpack or auto");
  LOOM_CHECK(!(unsymmetric && needs_spd(scene.solver.linear)), InputError,
             scene.solver.linear_where << ": error: solver.linear: " << chosen << " needs a symmetric tangent, and receding contact (mpm.receding_contact > 0) "
                        << "makes it unsymmetric; use umfpack or auto");
  LOOM_CHECK(!(mixed && needs_spd(scene.solver.linear)), InputError,
             scene.solver.linear_where << ": error: solver.linear: " << chosen << " needs a symmetric positive definite tangent, and the mixed u-p system "
                        << "(p1p1_up) is indefinite and, stabilised, unsymmetric; use umfpack or auto");
}

template void MpmModelT<2>::set_columns(const BodySpec&);
template void MpmModelT<3>::set_columns(const BodySpec&);
template void MpmModelT<2>::choose_linear_solver();
template void MpmModelT<3>::choose_linear_solver();

// Soft-stiffness outside nodes, wall sides, and the particles that point probes follow (the nearest to `at`).
template <>
void MpmModelT<2>::build_particle_newmark_data() {
  outside_node.assign(std::size_t(grid_nodes.size()), 0);
  for (std::size_t k = 0; k < scene.boundaries.size(); ++k)
    if (scene.boundaries[k].outside)
      for (Index i : bc.boundary_nodes[k]) outside_node[std::size_t(i)] = 1;
  if (coupled)  // the FEM nodes lower the flags of the grid cells they touch (spec A13)
    for (std::size_t i = 0; i < outside_node.size(); ++i) outside_node[i] |= coupled_mesh.fem_node[i];
  wall_sides = find_wall_sides(grid, bc, grid_nodes.size(), coupled ? &coupled_mesh.interface_node : nullptr);
  probe_particle.clear();
  for (const auto& p : scene.probes) {
    if (p.kind != ProbeKind::point) continue;
    Index nearest = 0;
    for (Index q = 1; q < particles.X.size(); ++q)
      if ((particles.X[q] - p.at).squaredNorm() < (particles.X[nearest] - p.at).squaredNorm()) nearest = q;
    probe_particle.push_back(nearest);
  }
  probe_points.resize(Index(probe_particle.size()));
  for (std::size_t k = 0; k < probe_particle.size(); ++k) probe_points.X[Index(k)] = particles.X[probe_particle[k]];
}

// Method mpm_fem: the grid and the FEM bodies' rectangles, refined alike, as one mesh with shared nodes.
template <>
void MpmModelT<2>::build_coupled_model_grid() {
  const MeshSpec& gm = scene.grid.mesh;
  const RectangleSpec rect = rectangle_of(gm);
  std::vector<FemBlock> blocks;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const BodySpec& fb = scene.bodies[b];
    if (fb.element != Formulation::quad9) continue;
    const RectangleSpec r = rectangle_of(fb.mesh);
    blocks.push_back({GradedRectangle{r.origin, r.size, r.nx, r.ny, Vec2::Ones(), scene.grid.refinements}, Index(b), fb.name});
  }
  try {
    coupled_mesh = build_coupled_grid(GradedRectangle{rect.origin, rect.size, rect.nx, rect.ny, scene.grid.grading, scene.grid.refinements},
                                      blocks, Formulation::p1, grid_nodes, grid, layout);
  } catch (const InputError& e) {  // name the FEM body's mesh (the message names the body)
    const std::string what = e.what();
    for (const FemBlock& b : blocks)
      if (what.find("\"" + b.name + "\"") != std::string::npos) {
        std::ostringstream os;
        os << scene.bodies[std::size_t(b.body)].mesh.where << ": error: body[" << b.body << "].mesh: " << what;
        throw InputError(os.str());
      }
    throw;
  }
  layout.moves = true;
  activity.always_active_from = coupled_mesh.grid_cells;
}

template <>
MpmModelT<2>::MpmModelT(const SceneSpec& spec) : scene(spec) {
  check_memory(scene);
  const BodySpec& body = scene.bodies.at(std::size_t(mpm_body_index(scene)));
  // 1. Columns the scene needs.
  set_columns(body);

  // 2. Grid, particles, traction points.
  const MeshSpec& gm = scene.grid.mesh;
  const RectangleSpec rect = rectangle_of(gm);
  const bool structured = gm.generator == MeshGenerator::rectangle && gm.distortion == 0.0;
  if (coupled) build_coupled_model_grid();
  else try {
    if (scene.grid.quad9) build_quad9_grid(GradedRectangle{rect.origin, rect.size, rect.nx, rect.ny, scene.grid.grading, scene.grid.refinements},
                                           body.element, grid_nodes, grid, layout);
    else if (scene.grid.quad4) build_quad_grid(rect, body.element, grid_nodes, grid, layout);
    else build_background_grid(generate_body_mesh(gm), structured ? &rect : nullptr, body.element, grid_nodes, grid, layout);
  } catch (const InputError& e) {
    std::ostringstream os;
    os << gm.where << ": error: grid: " << e.what();
    throw InputError(os.str());
  }
  materials = body_materials(scene);
  build_material_points(scene, particles);
  if (dynamic) {
    for_each_initial_velocity(
        scene, particles.X.size(), [&](Index p) { return particles.body[p]; }, [&](Index p) { return Vec2(particles.X[p]); },
        [&](Index p, const Vec2& v) { particles.v[p] = v; });
    if (coupled) {  // the FEM bodies' nodes, at their reference position
      std::vector<Index> node_body(std::size_t(grid_nodes.size()), kNoIndex);
      for (Index c = coupled_mesh.grid_cells; c < grid.size(); ++c)
        for (int a = 0; a < grid.stride; ++a) node_body[std::size_t(grid.node(c, a))] = grid.body[c];
      for_each_initial_velocity(
          scene, grid_nodes.size(), [&](Index i) { return node_body[std::size_t(i)]; }, [&](Index i) { return Vec2(grid_nodes.X[i]); },
          [&](Index i, const Vec2& v) { grid_nodes.v[i] = v; });
    }
  }
  bc.per_node = mixed ? 3 : 2;
  build_traction_points(scene, traction_points, bc);
  std::vector<Vec2> tracers;
  for (const auto& p : scene.probes)
    if (p.kind == ProbeKind::point) tracers.push_back(p.at);
  probe_points.resize(Index(tracers.size()));
  for (Index k = 0; k < probe_points.X.size(); ++k) probe_points.X[k] = tracers[std::size_t(k)];
  build_grid_conditions(scene, grid_nodes, layout, bc);
  if (coupled) build_reset_field(grid, coupled_mesh.grid_cells, grid_nodes, coupled_mesh.fem_node, bc, reset);
  finish_conditions();

  // 3. Where the points are, and the active grid.
  StepContext ctx;
  ctx.scene = &scene;
  try {
    locate_points(ctx, layout, grid, grid_nodes, particles, particle_loc);
    locate_points(ctx, layout, grid, grid_nodes, traction_points, traction_loc);
  } catch (const RunError& e) {
    std::ostringstream os;
    if (body.particles.kind != ParticleGenerator::none)
      os << body.particles.where << ": error: body[0].particles: the generated " << (body.particles.kind == ParticleGenerator::disk ? "disk" : "beam")
         << " does not fit in the background grid" << (coupled ? " (method mpm_fem: an MPM body lies inside the grid, outside the FEM bodies)" : "")
         << ": " << e.what();
    else os << gm.where << ": error: grid: the body does not fit in the background grid at t = 0: " << e.what();
    throw InputError(os.str());
  }
  if (particle_newmark) {
    build_particle_newmark_data();
    activate_grid(ctx, grid, particle_loc, bc, activity, system);
    flag_soft_cells(ctx, grid, outside_node, activity);
    return;
  }
  locate_probe_points(ctx);
  activate_grid(ctx, grid, particle_loc, bc, activity, system);
}

// Incremental prescribed values, zero targets and loads; the linear solver for the system.
template <int D>
void MpmModelT<D>::finish_conditions() {
  bc.increments = true;
  bc.target = Eigen::VectorXd::Zero(grid_nodes.size() * bc.per_node);
  bc.external = Eigen::VectorXd::Zero(grid_nodes.size() * bc.per_node);
  choose_linear_solver();
}

// A point probe outside the grid is an error of its own key; then the tracers are located.
template <int D>
void MpmModelT<D>::locate_probe_points(const StepContext& ctx) {
  for (std::size_t k = 0, tracer = 0; k < scene.probes.size(); ++k) {
    if (scene.probes[k].kind != ProbeKind::point) continue;
    const Vec<D> at = probe_points.X[Index(tracer++)];
    Vec4 N;
    if (find_cell(layout, grid, grid_nodes, at, kNoIndex, N) == kNoIndex) {
      std::ostringstream os;
      os << scene.probes[k].where << ": error: probe[" << k << "].at: " << point_text<D>(at)
         << " is outside the background grid (a point probe follows the material point at `at`)";
      throw InputError(os.str());
    }
  }
  try {
    locate_points(ctx, layout, grid, grid_nodes, probe_points, probe_loc);
  } catch (const RunError& e) {
    std::ostringstream os;
    os << scene.grid.mesh.where << ": error: grid: a probe point is outside the background grid at t = 0: " << e.what();
    throw InputError(os.str());
  }
}

template void MpmModelT<2>::finish_conditions();
template void MpmModelT<3>::finish_conditions();
template void MpmModelT<2>::locate_probe_points(const StepContext&);
template void MpmModelT<3>::locate_probe_points(const StepContext&);

}  // namespace loom
