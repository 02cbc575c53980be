#include "engine/methods/recipes/mpm_method.hpp"

#include <chrono>
#include <iomanip>
#include <sstream>

#include "engine/core/errors.hpp"
#include "engine/drivers/newton.hpp"
#include "engine/drivers/run_driver.hpp"
#include "engine/drivers/time_loop.hpp"
#include "engine/io/files.hpp"
#include "engine/io/vtk_writer.hpp"
#include "engine/methods/model/build_mesh.hpp"
#include "engine/methods/model/model_checks.hpp"
#include "engine/methods/recipes/adaptive_step.hpp"
#include "engine/methods/recipes/conditioning_note.hpp"
#include "engine/methods/recipes/cut_back_policy.hpp"
#include "engine/methods/recipes/fem_newton_problem.hpp"
#include "engine/methods/recipes/mpm_newton_problem.hpp"
#include "engine/methods/recipes/run_output.hpp"
#include "engine/scene/expression.hpp"
#include "engine/store/store_report.hpp"
#include "systems/loads/apply_grid_loads.hpp"
#include "systems/locate/activate_grid.hpp"
#include "systems/locate/contact_flags.hpp"
#include "systems/locate/locate_points.hpp"
#include "systems/map/interpolate_to_particles.hpp"
#include "systems/map/project_to_grid.hpp"
#include "systems/map/rest_held_grid_nodes.hpp"
#include "systems/output/snapshot_particles.hpp"
#include "systems/update/commit_particle_newmark.hpp"
#include "systems/update/coupled_fem.hpp"

namespace loom {
template <int D>
MpmRunT<D>::MpmRunT(const SceneSpec& scene, const RunOptions& options)
    : m_(scene), scene_(m_.scene), options_(options), solver_(m_.linear_solver, m_.scene.solver.linear_tolerance, m_.scene.solver.reuse_factor, m_.scene.solver.petsc_options) {
  ctx_.scene = &scene_;
  solver_.set_options_where((std::ostringstream() << m_.scene.solver.petsc_options_where).str());
  if (options_.profile) timers_.enable_profile();
  // A static model must hold the active grid's rigid motions; a point probe must start in the body. (3D: as the 3D
  // fem, a free body shows as a singular tangent, and a probe must start in the grid.)
  if constexpr (D == 2) {
    check_rigid_motions_held(scene_, m_.grid_nodes, {&m_.grid}, m_.bc, {}, &m_.activity.active_cells);
    if (scene_.bodies.size() == 1 && scene_.bodies[0].particles.kind == ParticleGenerator::none) {  // generated particle sets have no mesh: probes follow the nearest particle
      const MeshData body_mesh = generate_body_mesh(scene_.bodies[0].mesh);
      check_point_probes_inside(scene_, body_mesh.X, body_mesh.triangles, std::vector<Index>(std::size_t(body_mesh.n_triangles()), 0));
    }
  }
  probe_plan_ = plan_particle_probes(scene_);
  if (m_.particle_newmark) build_particle_newmark_graph();
  else build_graph();
}

template <int D>
MpmRunT<D>::~MpmRunT() = default;

template <int D>
void MpmRunT<D>::name_stores(StepGraph& g) {
  g.name_store(&m_.layout, "grid_layout");
  g.name_store(&m_.grid, "grid_cells");
  g.name_store(&m_.grid_nodes, "grid_nodes");
  g.name_store(&m_.activity, "grid_activity");
  g.name_store(&m_.particles, "particles");
  g.name_store(&m_.particle_loc, "particle_locations");
  g.name_store(&m_.traction_points, "traction_points");
  g.name_store(&m_.traction_loc, "traction_point_locations");
  g.name_store(&m_.probe_points, "probe_points");
  g.name_store(&m_.probe_loc, "probe_point_locations");
  g.name_store(&m_.materials, "materials");
  g.name_store(&m_.bc, "grid_conditions");
  g.name_store(&m_.system, "linear_system");
  g.name_store(&m_.outside_node, "outside_nodes");
  g.name_store(&m_.wall_sides, "wall_sides");
  g.name_store(&m_.probe_particle, "probe_particles");
  g.name_store(&m_.reset, "reset_field");
  g.name_store(&m_.coupled_mesh.fem_node, "fem_nodes");
  g.name_store(&status_, "step_status");
  g.name_store(&probe_writer_, "probes.csv");
  g.name_store(&writer_, "vtk_writer");
}

// Probes and frames, on a converged state at the end of a step.
template <int D>
void MpmRunT<D>::add_output_nodes(StepGraph& g) {
  const auto probes = g.add_node("probes",
                                 {{&m_.particles, &m_.probe_points, &m_.grid, &m_.activity, &m_.grid_nodes, &m_.materials, &m_.system, &m_.bc},
                                  {&probe_writer_}},
                                 [this] { probes_node(); });
  g.run_if(probes, &status_, [this] { return status_.converged && ctx_.step_end; });
  const auto output = g.add_node("output", {{&m_.particles, &m_.materials, &m_.grid, &m_.activity, &m_.grid_nodes, &m_.particle_loc}, {&writer_}},
                                 [this] { output_node(); }, "snapshot here; the VTK files are written while the next step runs");
  g.run_if(output, &status_, [this] { return status_.converged && ctx_.step_end && frame_due(); });
}

template <int D>
void MpmRunT<D>::build_graph() {
  graph_ = std::make_unique<StepGraph>("mpm", ctx_, timers_);
  StepGraph& g = *graph_;
  name_stores(g);

  // 1. Initialisation phase (Algorithm 1 lines 5-15).
  g.add_system("locate_particles", &locate_points<D>, m_.layout, m_.grid, m_.grid_nodes, m_.particles, m_.particle_loc);
  if (D == 2 || m_.traction_points.X.size() > 0)
    g.add_system("locate_traction_points", &locate_points<D>, m_.layout, m_.grid, m_.grid_nodes, m_.traction_points, m_.traction_loc);
  g.add_system("locate_probe_points", &locate_points<D>, m_.layout, m_.grid, m_.grid_nodes, m_.probe_points, m_.probe_loc);
  g.add_system("activate_grid", &activate_grid<D>, m_.grid, m_.particle_loc, m_.bc, m_.activity, m_.system);
  g.add_system("project_to_grid", &project_to_grid<D>, m_.grid, m_.particles, m_.particle_loc, m_.grid_nodes);
  g.add_system("apply_grid_loads", &apply_grid_loads<D>, m_.grid, m_.grid_nodes, m_.activity, m_.particles, m_.particle_loc, m_.traction_points,
               m_.traction_loc, m_.bc);
  if (m_.dynamic) g.add_system("rest_held_grid_nodes", &rest_held_grid_nodes<D>, m_.bc, m_.grid_nodes);
  // 2. Updated-Lagrangian solve on the grid (lines 17-42).
  g.add_node("newton",
             {{&m_.grid, &m_.activity, &m_.particles, &m_.materials, &m_.bc}, {&m_.grid_nodes, &m_.particle_loc, &m_.system, &status_}},
             [this] { newton_node(); }, m_.osgs ? "assemble -> solve -> update until converged; OSGS projections before each assembly"
                                                  : "assemble -> solve -> update until converged");
  // 3. Convective phase (lines 44-49), on a converged state only.
  const auto interpolate = g.add_system("interpolate_to_particles", &interpolate_to_particles<D>, m_.grid, m_.grid_nodes, m_.particle_loc, m_.particles);
  g.run_if(interpolate, &status_, [this] { return status_.converged; });
  if (D == 2 || m_.traction_points.X.size() > 0) {
    const auto move = g.add_system("move_traction_points", &move_with_grid<D>, m_.grid, m_.grid_nodes, m_.activity, m_.traction_loc, m_.traction_points);
    g.run_if(move, &status_, [this] { return status_.converged; });
  }
  const auto tracers = g.add_system("move_probe_points", &move_with_grid<D>, m_.grid, m_.grid_nodes, m_.activity, m_.probe_loc, m_.probe_points);
  g.run_if(tracers, &status_, [this] { return status_.converged; });
  add_output_nodes(g);
  g.build();
}

// Seed 004 (Aulisa & Capodaglio §3): nothing is projected to the grid; the particles carry the Newmark state.
template <int D>
void MpmRunT<D>::build_particle_newmark_graph() {
  if constexpr (D == 3) {
    throw InputError(scene_.file + ": error: mpm.scheme: particle_newmark is two-dimensional");
  } else {
  graph_ = std::make_unique<StepGraph>("mpm (particle Newmark)", ctx_, timers_);
  StepGraph& g = *graph_;
  name_stores(g);
  if (m_.coupled) g.add_system("reset_grid", &reset_grid, m_.reset, m_.coupled_mesh.fem_node, m_.grid_nodes);
  g.add_system("locate_particles", &locate_points<2>, m_.layout, m_.grid, m_.grid_nodes, m_.particles, m_.particle_loc);
  g.add_system("activate_grid", &activate_grid<2>, m_.grid, m_.particle_loc, m_.bc, m_.activity, m_.system);
  g.add_system("flag_soft_cells", &flag_soft_cells, m_.grid, m_.outside_node, m_.activity);
  if (m_.particle_loc.receding.used())
    g.add_system("mark_receding_particles", &mark_receding_particles, m_.grid, m_.grid_nodes, m_.wall_sides, m_.particles, m_.particle_loc);
  g.add_system("apply_grid_loads", &apply_grid_loads<2>, m_.grid, m_.grid_nodes, m_.activity, m_.particles, m_.particle_loc, m_.traction_points,
               m_.traction_loc, m_.bc);
  g.add_node("newton",
             {{&m_.grid, &m_.activity, &m_.particles, &m_.materials, &m_.bc}, {&m_.grid_nodes, &m_.particle_loc, &m_.system, &status_}},
             [this] { newton_node(); }, "assemble -> solve -> update until converged (particles as quadrature points, consistent particle mass)");
  const auto commit = g.add_system("commit_particle_newmark", &commit_particle_newmark, m_.grid, m_.grid_nodes, m_.particle_loc, m_.particles);
  g.run_if(commit, &status_, [this] { return status_.converged; });
  if (m_.coupled) {
    const auto fem = g.add_system("commit_fem_nodes", &commit_fem_nodes, m_.coupled_mesh.fem_node, m_.grid_nodes);
    g.run_if(fem, &status_, [this] { return status_.converged; });
  }
  const auto follow = g.add_system("follow_particles", &follow_particles, m_.probe_particle, m_.particles, m_.probe_points);
  g.run_if(follow, &status_, [this] { return status_.converged; });
  add_output_nodes(g);
  g.build();
  }
}

template <int D>
void MpmRunT<D>::newton_node() {
  if (m_.particle_newmark)  // the grid starts every step undeformed: u is the step's displacement
    for (Index i = 0; i < m_.grid_nodes.size(); ++i) m_.grid_nodes.u[i].setZero();
  update_grid_kinematics(ctx_, m_.grid_nodes);  // grid Newmark: the predictor from the reset grid (lines 13-15)
  MpmNewtonProblemT<D> problem(ctx_, m_, solver_, timers_);
  NewtonSettings settings = newton_settings_of(scene_.solver);
  settings.expected_iterations = status_.iterations;  // the last step's: its last assembly needs no tangent
  if (options_.verbose && options_.log) {
    *options_.log << "step " << ctx_.step << " (t = " << ctx_.t << ", dt = " << ctx_.dt << ")\n";
    settings.log = options_.log;
  }
  solver_.reset_condition();
  const NewtonReport report = solve_newton(problem, settings, timers_);
  status_.converged = report.converged;
  status_.iterations = report.iterations;
  status_.step_iterations += report.iterations;
  status_.total_iterations += report.iterations;
  status_.failure = report.failure;
  status_.shorter_step_helps = report.converged || shorter_step_changes_problem(scene_, m_.bc.expressions);
  // The likely cause of a failure or of a singular tangent on quadrilateral cells: too few particles in some. A
  // quad4 (quad9) cell integrated at fewer than 4 (9) points has zero-energy modes; on quad9 grids the soft
  // stiffness of edge cells is what removes them (seed 004 eq 26).
  std::string hint;
  const bool suspect = !report.converged || solver_.min_rcond() < LinearSolve::kNearlySingular;
  const int nen = m_.grid.stride;
  if (suspect && D == 2 && (nen == 4 || nen == 9)) {  // a tet4 cell's gradients are constant: one point integrates it
    Index sparse = 0;
    for (Index c : m_.activity.active_cells) sparse += m_.particle_loc.count_in(c) < nen;
    if (sparse > 0) {
      std::ostringstream os;
      os << sparse << " of the " << m_.activity.active_cells.size() << " active " << cell_type_name(m_.grid.type) << " cells hold fewer than "
         << nen << " particles (a cell integrated at fewer points has zero-energy modes: "
         << (nen == 4 ? "raise body[0].particles_per_cell, refine the body mesh or coarsen the grid)"
                      : "raise the particle density, coarsen the grid, or give mpm.soft_stiffness larger c1, c2)");
      hint = os.str();
    }
  }
  note_conditioning(solver_, ctx_, status_, options_.log, warned_singular_, hint);
  if (!report.converged && !hint.empty()) status_.failure += "; " + hint;
}

template <int D>
void MpmRunT<D>::probes_node() {
  evaluate_particle_probes(ctx_, probe_plan_, m_.materials, m_.particles, m_.probe_points, m_.traction_points, GridView<D>{m_.grid, m_.activity, m_.grid_nodes},
                           m_.system, m_.bc, status_.step_iterations, probe_values_);
  if (probe_writer_.is_open()) probe_writer_.write(ctx_.step, ctx_.t, probe_values_);
}

template <int D>
bool MpmRunT<D>::frame_due() const {
  if (!options_.write_files || scene_.output.every == 0) return false;
  return ctx_.step % scene_.output.every == 0 || ctx_.step == scene_.time.steps;
}

template <int D>
void MpmRunT<D>::output_node() {
  last_frame_time_ = ctx_.t;
  auto particles = std::make_shared<Frame>();
  auto grid = std::make_shared<Frame>();
  snapshot_particles(ctx_, m_.materials, m_.particles, *particles);
  snapshot_grid(ctx_, m_.materials, m_.grid, m_.activity, m_.grid_nodes, m_.particle_loc, *grid);
  std::ostringstream stem;
  stem << file_stem(scene_.scene.name) << "_" << std::setw(6) << std::setfill('0') << particles->step;
  const std::string dir = options_.output_directory, particle_file = stem.str() + "_particles.vtp", grid_file = stem.str() + "_grid.vtu";
  writer_.submit([this, particles, grid, dir, particle_file, grid_file] {
    ScopedTimer t(timers_, "output/write_vtk");
    write_vtp(dir + "/" + particle_file, *particles);
    write_vtu(dir + "/" + grid_file, *grid);
    pvd_.add(particles->time, particle_file, 0);
    pvd_.add(grid->time, grid_file, 1);
  });
}

template <int D>
void MpmRunT<D>::describe(std::ostream& os) const {
  const BodySpec& body = scene_.bodies[std::size_t(mpm_body_index(scene_))];
  os << "scene '" << scene_.scene.name << "' (" << scene_.file << "), method " << method_name(scene_.scene.method) << ", element "
     << formulation_name(body.element);
  if (m_.coupled)
    os << ", " << m_.grid.size() - m_.coupled_mesh.grid_cells << " FEM quad9 cells sharing the grid's nodes (reset field: " << m_.reset.held_dof.size()
       << " held dofs)";
  if (m_.mixed) {
    const char* names[] = {"none", "ppp", "asgs", "osgs"};
    os << ", stabilisation " << names[int(body.stabilisation)];
  }
  if (m_.particle_newmark) {
    os << ", scheme particle_newmark (beta " << scene_.time.beta << ", gamma " << scene_.time.gamma << "; soft stiffness c1 " << scene_.mpm.soft_c1
       << ", c2 " << scene_.mpm.soft_c2 << "; receding contact " << scene_.mpm.receding_contact << ")";
  }
  if (body.particles.kind != ParticleGenerator::none) os << ", " << m_.particles.X.size() << " generated particles, grid ";
  else os << ", " << body.particles_per_cell << " particles per body cell, grid ";
  os << (!m_.layout.x_lines.empty() ? "graded rectangle (binary-search locate)"
          : m_.layout.structured    ? "structured (arithmetic locate)"
                                    : "unstructured (walk)")
     << "\n";
  os << "stores:\n";
  {
    StoreReport r(os, "grid_nodes", m_.grid_nodes.size());
    m_.grid_nodes.for_each_column(r);
  }
  {
    StoreReport r(os, std::string("grid_cells[") + cell_type_name(m_.grid.type) + "]", m_.grid.size());
    m_.grid.for_each_column(r);
  }
  os << "    colours: " << m_.grid.n_colours() << "; active at t = 0: " << m_.activity.n_active_cells() << " cells\n";
  {
    StoreReport r(os, "particles", m_.particles.X.size());
    m_.particles.for_each_column(r);
  }
  {
    StoreReport r(os, "particle_locations", m_.particle_loc.size());
    m_.particle_loc.for_each_column(r);
  }
  {
    StoreReport r(os, "traction_points", m_.traction_points.X.size());
    m_.traction_points.for_each_column(r);
  }
  os << "  linear_system: " << m_.system.dofs.n_dofs() << " dofs (" << m_.system.dofs.per_node << " per grid node), " << m_.system.dofs.n_free
     << " free at t = 0 (" << m_.activity.dormant_dofs.size() << " of them dormant: the layer of cells around the active ones, which keeps the "
     << "pattern while the body moves), " << m_.system.pattern.matrix.nonZeros() << " non-zeros; solver "
     << linear_solver_name(m_.linear_solver)
     << "\n";
  os << "  grid_conditions: " << m_.bc.prescribed.size() << " prescribed dofs, " << m_.traction_points.X.size() << " traction points, loads "
     << (m_.bc.has_loads ? "yes" : "none") << "\n";
  graph_->print(os);
}

// a_0 = M^-1 (f_ext - f_int) on the active grid at t = 0 (lumped mass), interpolated to the particles:
// a load applied from t = 0 on is then integrated exactly by Newmark (free fall: 1/2 g t^2).
template <int D>
void MpmRunT<D>::initial_acceleration() {
  MpmNewtonProblemT<D> problem(ctx_, m_, solver_, timers_, false);
  problem.assemble(false);
  const int pn = m_.system.dofs.per_node;
  Nodes<D>& g = m_.grid_nodes;
  for (Index i = 0; i < g.size(); ++i) {
    g.u[i].setZero();
    if (!(g.lumped_mass[i] > 0.0)) continue;
    for (int d = 0; d < D; ++d)
      g.a[i][d] = m_.system.dofs.kind[std::size_t(i * pn + d)] == DofKind::free ? -m_.system.residual_full[i * pn + d] / g.lumped_mass[i] : 0.0;
  }
  for (Index p = 0; p < m_.particles.X.size(); ++p) {
    const Index* corner = m_.grid.cell_nodes(m_.particle_loc.cell[p]);
    const Vec4& N = m_.particle_loc.N[p];
    m_.particles.a[p].setZero();
    for (int a = 0; a < m_.grid.stride; ++a) m_.particles.a[p] += N[a] * g.a[corner[a]];
  }
}

// mpm_fem: the FEM bodies start undeformed (f_int = 0), so a_0 = M^-1 f_ext with the lumped mass is rho b(X) / rho_i
// (b with the material's inertia) at every free dof of their nodes and 0 at the held ones (a clamped plate's free nodes start falling at g, as
// its lumped equations say; the consistent mass the step uses differs only next to the held nodes).
template <int D>
void MpmRunT<D>::fem_nodes_equilibrium_acceleration() {
  if constexpr (D == 2) {
    Nodes<2>& g = m_.grid_nodes;
    std::vector<Index> body(std::size_t(g.size()), kNoIndex);
    for (Index c = m_.activity.always_active_from; c != kNoIndex && c < m_.grid.size(); ++c)
      for (int a = 0; a < m_.grid.stride; ++a) body[std::size_t(m_.grid.node(c, a))] = m_.grid.body[c];
    for (Index i = 0; i < g.size(); ++i) {
      if (!m_.coupled_mesh.fem_node[std::size_t(i)] || body[std::size_t(i)] == kNoIndex) continue;
      const Index b = body[std::size_t(i)];
      const auto& e = m_.bc.body_force[std::size_t(b)];
      // The cell's force is rho b and its inertia rho_i (1 with inertia = "unit_density"): a_0 = rho b / rho_i.
      const BodySpec& spec = scene_.bodies[std::size_t(b)];
      const double density = scene_.materials[std::size_t(spec.material)].density;
      const double force_per_inertia = spec.unit_inertia ? density : 1.0;
      const Vec2 X = g.X[i] - g.u_n[i];
      for (int d = 0; d < 2; ++d)
        g.a[i][d] =
            e[std::size_t(d)] == kNoIndex ? 0.0 : force_per_inertia * m_.bc.expressions[std::size_t(e[std::size_t(d)])](0.0, X.x(), X.y());
    }
    for (const auto& p : m_.bc.prescribed)
      if (p.dof % m_.bc.per_node < 2 && m_.coupled_mesh.fem_node[std::size_t(p.node)]) g.a[p.node][p.dof % m_.bc.per_node] = 0.0;
  }
}

template <int D>
void MpmRunT<D>::write_initial_state() {
  ctx_.step = 0, ctx_.t = 0.0, ctx_.dt = scene_.time.dt, ctx_.step_end = true;
  if (!m_.particle_newmark) project_to_grid(ctx_, m_.grid, m_.particles, m_.particle_loc, m_.grid_nodes);
  apply_grid_loads(ctx_, m_.grid, m_.grid_nodes, m_.activity, m_.particles, m_.particle_loc, m_.traction_points, m_.traction_loc, m_.bc);
  if (m_.dynamic && scene_.time.initial_acceleration == InitialAcceleration::equilibrium) {
    if (m_.particle_newmark) {
      // The particles start with F = I, stress free: f_int = 0, and a body that touches no wall has the
      // equilibrium acceleration of its body force, particle by particle (free fall: exactly g).
      for (Index p = 0; p < m_.particles.X.size(); ++p)
        m_.particles.a[p] = m_.bc.particle_body_force.empty() ? Vec<D>::Zero() : m_.bc.particle_body_force[std::size_t(p)];
      if constexpr (D == 2)
        if (m_.coupled) fem_nodes_equilibrium_acceleration();
    } else {
      initial_acceleration();
    }
  }
  status_ = StepStatus{};
  status_.converged = true;
  probes_node();
  if (options_.write_files && scene_.output.every > 0) output_node();
}

template <int D>
RunSummary MpmRunT<D>::run() {
  const auto start = std::chrono::steady_clock::now();
  RunSummary summary;
  summary.steps_requested = scene_.time.steps;
  summary.cells = m_.grid.size();
  const RunSchedule schedule = start_run(
      scene_, options_, [this](const CheckpointReader& r) { return restore_checkpoint(r); }, summary, pvd_, probe_writer_);

  RunHooks hooks;
  hooks.write_initial_state = [&] { write_initial_state(); };
  hooks.write_last_converged_state = [&](int failed_step, double last_converged_time) {
    if (!options_.write_files || scene_.output.every <= 0 || last_converged_time == last_frame_time_) return;
    // The particles hold the last converged state (a failed step never reaches the convective phase).
    ctx_.step = failed_step;
    ctx_.t = last_converged_time;
    output_node();
  };
  hooks.wait_for_writer = [&] { writer_.wait(); };
  hooks.settled = [&](const StepContext& c) { return stop_.met(scene_.time, c.t, probe_values_); };
  use_adaptive_step(scene_, probe_values_, hooks);
  if (options_.write_files) hooks.write_checkpoint = [&](int step) { write_checkpoint(step); };
  const TimeLoopResult result = drive_run(schedule, ctx_, *graph_, status_, hooks);
  summary.dofs = m_.system.dofs.n_free;
  summarise_run(result, status_, schedule, summary);
  summarise_linear_solver(solver_, summary);
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}


template class MpmRunT<2>;
template class MpmRunT<3>;

}  // namespace loom
