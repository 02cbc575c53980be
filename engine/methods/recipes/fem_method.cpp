#include "engine/methods/recipes/fem_method.hpp"

#include <chrono>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "engine/core/errors.hpp"
#include "engine/drivers/newton.hpp"
#include "engine/drivers/run_driver.hpp"
#include "engine/drivers/time_loop.hpp"
#include "engine/io/files.hpp"
#include "engine/io/vtk_writer.hpp"
#include "engine/methods/model/model_checks.hpp"
#include "engine/methods/pfem/inlet_flow.hpp"
#include "engine/methods/pfem/inlet_flow_3d.hpp"
#include "engine/methods/recipes/adaptive_step.hpp"
#include "engine/methods/recipes/conditioning_note.hpp"
#include "engine/methods/recipes/cut_back_policy.hpp"
#include "engine/methods/recipes/fem_newton_problem.hpp"
#include "engine/methods/recipes/run_output.hpp"
#include "engine/store/store_report.hpp"
#include "systems/loads/apply_boundary_conditions.hpp"
#include "systems/output/snapshot_frame.hpp"
#include "systems/update/commit_domains.hpp"
#include "systems/update/commit_step.hpp"

namespace loom {

template <int D>
FemRunT<D>::FemRunT(const SceneSpec& scene, const RunOptions& options)
    : m_(scene), scene_(m_.scene), options_(options), solver_(m_.linear_solver, m_.scene.solver.linear_tolerance, m_.scene.solver.reuse_factor, m_.scene.solver.petsc_options) {
  ctx_.scene = &scene_;
  solver_.set_options_where((std::ostringstream() << m_.scene.solver.petsc_options_where).str());
  resolve_probe_groups();
  check_model();
  if (options_.profile) timers_.enable_profile();
  pfem_ = scene_.scene.method == Method::pfem || scene_.scene.method == Method::es_pfem;
  if (pfem_) {
    pfem_settings_ = pfem_settings_of(scene_);
    topology_ = initial_topology(m_);
    check_inlets();
  }
  probe_plan_ = plan_probes<D>(scene_, m_.nodes, m_.cells, m_.node_body);
  if constexpr (D == 3) {
    std::vector<std::size_t> found;
    for (const auto& samples : probe_plan_.samples) found.push_back(samples.size());
    check_stress_probes_found(m_.scene, found);
  }
  build_graph();
}

template <int D>
FemRunT<D>::~FemRunT() = default;

// A probe given by a physical point of the mesh file reads at that point's node.
template <int D>
void FemRunT<D>::resolve_probe_groups() {
  for (std::size_t k = 0; k < m_.scene.probes.size(); ++k) {
    ProbeSpec& p = m_.scene.probes[k];
    if (p.group.empty()) continue;
    const MeshRegion* region = nullptr;
    std::string known;
    for (std::size_t b = 0; b < m_.regions.size(); ++b) {
      if (p.body != kNoIndex && Index(b) != p.body) continue;
      for (const auto& r : m_.regions[b]) {
        if (r.name == p.group && !region) region = &r;
        known += (known.empty() ? "" : ", ") + ("\"" + r.name + "\"");
      }
    }
    std::ostringstream os;
    os << p.where << ": error: probe[" << k << "].group: ";
    LOOM_CHECK(region, InputError, os.str() << "no physical group \"" << p.group << "\" in the mesh files (groups: " << (known.empty() ? "none" : known) << ")");
    LOOM_CHECK(region->corners.size() == 1, InputError,
               os.str() << "\"" << p.group << "\" holds " << region->corners.size() << " nodes; a probe reads at one point (a physical point)");
    const Vec<D> X = m_.nodes.X[region->corners.front()];
    p.at = X.template head<2>();
    if constexpr (D == 3) p.at_z = X[2];
  }
}

// Scene errors that need the mesh and that only a run cares about (tests build models without conditions):
// a static body free to move, a point probe off every body.
template <int D>
void FemRunT<D>::check_model() const {
  if constexpr (D == 3) return;  // 3D: a free body shows as a singular tangent, named by Newton
  else {
  std::vector<const Cells*> blocks;
  for (const auto& c : m_.cells) blocks.push_back(&c);
  // Walls hold what rests on them through their penalty: a static body on a wall is not free (one that does
  // not touch any wall is, and Newton then names the singular tangent).
  if (m_.walls.empty()) check_rigid_motions_held(scene_, m_.nodes, blocks, m_.bc, m_.node_body);
  std::vector<Vec2> X(std::size_t(m_.nodes.size()));
  for (Index i = 0; i < m_.nodes.size(); ++i) X[std::size_t(i)] = m_.nodes.X[i];
  std::vector<Index> corners, corner_body;
  for (const auto& cb : m_.cells)
    for (Index c = 0; c < cb.size(); ++c) {  // quadrilaterals as two corner triangles
      for (int a = 0; a < 3; ++a) corners.push_back(cb.node(c, a));
      corner_body.push_back(cb.body[c]);
      if (corners_of_stride(cb.stride) == 4) {
        for (int a : {0, 2, 3}) corners.push_back(cb.node(c, a));
        corner_body.push_back(cb.body[c]);
      }
    }
  check_point_probes_inside(scene_, X, corners, corner_body);
  }
}

// An inlet's section must be an edge (3D: triangles) of its body's initial mesh: the particles on it are the first row
// (layer) released.
template <int D>
void FemRunT<D>::check_inlets() const {
  if constexpr (D == 2) {
  for (std::size_t k = 0; k < scene_.inlets.size(); ++k) {
    const InletSpec& in = scene_.inlets[k];
    const InletFrame frame = inlet_frame(in, topology_);
    const std::size_t on = particles_on_section(frame, topology_, m_.nodes, in.body).size();
    std::ostringstream os;
    os << in.where << ": error: inlet[" << k << "].from: " << on << " particle(s) of body \"" << scene_.bodies[std::size_t(in.body)].name
       << "\" lie on the section from (" << in.from.x() << ", " << in.from.y() << ") to (" << in.to.x() << ", " << in.to.y()
       << "); the body's mesh must begin at the section (an edge of it on the section, the material on the side the velocity points to)";
    LOOM_CHECK(on >= 2, InputError, os.str());
    // The body lies downstream: its centroid is on the side the velocity points to.
    Vec2 centre = Vec2::Zero();
    for (Index i : topology_.points_of_body[std::size_t(in.body)]) centre += m_.nodes.X[i];
    centre /= double(topology_.points_of_body[std::size_t(in.body)].size());
    std::ostringstream side;
    side << in.where << ": error: inlet[" << k << "].velocity: points away from body \"" << scene_.bodies[std::size_t(in.body)].name
         << "\" (the material would flow in on the side where the body is not)";
    LOOM_CHECK(frame.distance(centre) > 0.0, InputError, side.str());
  }
  } else {
    check_inlet_discs(scene_, topology_, m_.nodes);
  }
}

template <int D>
void FemRunT<D>::build_graph() {
  graph_ = std::make_unique<StepGraph>(method_name(scene_.scene.method), ctx_, timers_);
  StepGraph& g = *graph_;
  g.name_store(&m_.nodes, "nodes");
  g.name_store(&m_.cells, "cells");
  g.name_store(&m_.quad, "quad_points");
  g.name_store(&m_.materials, "materials");
  g.name_store(&m_.bc, "boundary_conditions");
  g.name_store(&m_.system, "linear_system");
  g.name_store(&status_, "step_status");
  g.name_store(&probe_writer_, "probes.csv");
  g.name_store(&writer_, "vtk_writer");

  if (pfem_) {
    g.name_store(&topology_, "pfem_topology");
    const auto remesh = g.add_node("remesh", {{&m_.materials}, {&topology_, &m_.nodes, &m_.cells, &m_.quad, &m_.edges, &m_.bc, &m_.system}},
                                   [this] { remesh_node(); },
                                   "triangulate + alpha shape, transfer the history, rebuild dofs/sparsity where the connectivity changed");
    g.run_if(remesh, nullptr, [this] {
      const bool due = ctx_.step % pfem_settings_.every == 0;
      if (!due) last_remesh_ = RemeshReport{};  // the remesh probes report this step's remesh: none
      return due;
    });
  }
  g.add_system("apply_boundary_conditions", &apply_boundary_conditions<D>, m_.nodes, m_.cells, m_.materials, m_.bc);
  if (!m_.walls.empty()) {
    g.name_store(&m_.walls, "walls");
    g.name_store(&m_.node_body, "node_body");
    g.add_system("measure_contact_areas", &measure_contact_areas<D>, m_.walls, m_.cells, m_.nodes);
  }
  g.add_node("newton", {{&m_.bc, &m_.cells, &m_.materials}, {&m_.nodes, &m_.quad, &m_.edges, &m_.system, &status_}}, [this] { newton_node(); },
             "reset_iterate, then assemble -> solve -> update until converged");
  if (!m_.walls.empty()) {
    const auto commit_walls = g.add_system("commit_wall_contact", &commit_wall_contact<D>, m_.walls, m_.node_body, m_.nodes);
    g.run_if(commit_walls, &status_, [this] { return status_.converged; });
  }
  const auto commit = g.add_system("commit", &commit_step<D>, m_.cells, m_.nodes, m_.quad);
  g.run_if(commit, &status_, [this] { return status_.converged; });
  if (!m_.edges.empty()) {
    g.name_store(&m_.edges, "edges");
    const auto commit_edges = g.add_system("commit_domains", &commit_domains<D>, m_.cells, m_.nodes, m_.quad, m_.edges);
    g.run_if(commit_edges, &status_, [this] { return status_.converged; });
  }
  const auto probes = g.add_node("probes", {{&m_.nodes, &m_.cells, &m_.quad, &m_.edges, &m_.materials, &m_.system, &m_.bc}, {&probe_writer_}},
                                 [this] { probes_node(); });
  g.run_if(probes, &status_, [this] { return status_.converged && ctx_.step_end; });
  const auto output = g.add_node("output", {{&m_.nodes, &m_.cells, &m_.quad, &m_.materials}, {&writer_}}, [this] { output_node(); },
                                 "snapshot here; the VTK file is written while the next step runs");
  g.run_if(output, &status_, [this] { return status_.converged && ctx_.step_end && frame_due(); });
  g.build();
}

template <int D>
void FemRunT<D>::remesh_node() {
  last_remesh_ = remesh_model(pfem_settings_, ctx_.t - ctx_.dt, topology_, m_, timers_);
  if (last_remesh_.new_material_mass > 0.0) {
    new_material_mass_ += last_remesh_.new_material_mass;
    check_new_material();
  }
  if (last_remesh_.changed) {
    probe_plan_ = plan_probes(scene_, m_.nodes, m_.cells, m_.node_body);
    last_change_ = last_remesh_, last_change_step_ = ctx_.step;  // a cut-back's retry remeshes the changed mesh again
  }
}

// A dynamic es_pfem run carries its mass on the particles; only gaps that a remesh filled add to it. Past
// remesh.max_new_material of the bodies' mass the answer is doubtful: the run fails rather than exit 0 with it.
template <int D>
void FemRunT<D>::check_new_material() const {
  double mass = 0.0;
  for (Index i = 0; i < m_.nodes.size(); ++i) mass += m_.nodes.lumped_mass[i];
  const double limit = scene_.pfem.max_new_material;
  LOOM_CHECK(!(new_material_mass_ > limit * mass), RunError,
             "remesh: the gaps filled where surfaces met (or voids closed) have added " << new_material_mass_ << " kg since the start, "
                 << 100.0 * new_material_mass_ / mass << " % of the bodies' mass (" << mass << " kg), above remesh.max_new_material = " << limit
                 << ": mass that no particle carried, a doubtful answer (a layer a few cells thick folding onto itself). Refine the mesh "
                    "where the flow thins, insert particles (remesh.insert_above), or raise remesh.max_new_material to accept it");
}

template <int D>
void FemRunT<D>::newton_node() {
  if (scene_.time.predictor == Predictor::constant_acceleration && m_.nodes.v.used())
    predict_iterate(ctx_.dt, m_.nodes);
  else
    reset_iterate(m_.nodes);
  FemNewtonProblemT<D> problem(ctx_, m_.materials, m_.cells, m_.bc, m_.nodes, m_.quad, m_.system, solver_, timers_, &m_.edges);
  problem.set_walls(&m_.walls, &m_.node_body);
  NewtonSettings settings = newton_settings_of(scene_.solver);
  settings.trials_without_tangent = true;  // assemble_system's residual alone is the full one's; the state it keeps (F, b^e at the
                                           // points) is that of the last assembly, always at the accepted iterate
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
  note_conditioning(solver_, ctx_, status_, options_.log, warned_singular_);
  // A cell the alpha shape has just added (or removed) changes a nearly incompressible body at once: say so,
  // it is the usual reason why a PFEM step fails where the previous ones converged.
  if (!report.converged && pfem_ && last_change_step_ == ctx_.step) {
    std::ostringstream os;
    os << "; the remesh before this step changed the connectivity (body area " << last_change_.area_before << " -> "
       << last_change_.area_after << ", " << last_change_.rejected << " triangles rejected by the alpha test)";
    status_.failure += os.str();
  }
}

template <int D>
void FemRunT<D>::probes_node() {
  std::vector<WallResult> walls;
  if (!m_.walls.empty()) walls = wall_results(m_.walls, m_.node_body, m_.nodes, m_.system.dofs);
  evaluate_probes(ctx_, probe_plan_, m_.materials, m_.nodes, m_.cells, m_.quad, m_.system, m_.bc, status_.step_iterations,
                  last_remesh_.stats(), walls, probe_values_, &m_.edges);
  if (probe_writer_.is_open()) probe_writer_.write(ctx_.step, ctx_.t, probe_values_);
}

template <int D>
bool FemRunT<D>::frame_due() const {
  if (!options_.write_files || scene_.output.every == 0) return false;
  return ctx_.step % scene_.output.every == 0 || ctx_.step == scene_.time.steps;
}

template <int D>
void FemRunT<D>::output_node() {
  last_frame_time_ = ctx_.t;
  auto frame = std::make_shared<Frame>();
  snapshot_frame(ctx_, m_.materials, m_.nodes, m_.cells, m_.quad, *frame);
  std::ostringstream name;
  name << file_stem(scene_.scene.name) << "_" << std::setw(6) << std::setfill('0') << frame->step << ".vtu";
  const std::string dir = options_.output_directory, file = name.str();
  writer_.submit([this, frame, dir, file] {
    ScopedTimer t(timers_, "output/write_vtu");
    write_vtu(dir + "/" + file, *frame);
    pvd_.add(frame->time, file);
  });
}

namespace {
// The scene's name of a block's element: tri6's formulation on tetrahedra is the scene's tet10.
const char* element_name(const Cells& cells) {
  return cells.type == CellType::tet10 ? "tet10" : formulation_name(cells.formulation);
}
}  // namespace

template <int D>
void FemRunT<D>::describe(std::ostream& os) const {
  os << "scene '" << scene_.scene.name << "' (" << scene_.file << "), method " << method_name(scene_.scene.method) << ", " << scene_.bodies.size() << (scene_.bodies.size() == 1 ? " body\n" : " bodies\n");
  os << "stores:\n";
  {
    StoreReport r(os, "nodes", m_.nodes.size());
    m_.nodes.for_each_column(r);
  }
  {
    StoreReport r(os, "points", m_.points.size());
    m_.points.for_each_column(r);
  }
  for (std::size_t b = 0; b < m_.cells.size(); ++b) {
    {
      StoreReport r(os, std::string("cells[") + element_name(m_.cells[b]) + ", " + cell_type_name(m_.cells[b].type) + "]",
                    m_.cells[b].size());
      m_.cells[b].for_each_column(r);
    }
    os << "    colours: " << m_.cells[b].n_colours() << "\n";
    StoreReport r(os, std::string("quad_points[") + element_name(m_.cells[b]) + "]", m_.quad[b].size());
    m_.quad[b].for_each_column(r);
  }
  for (std::size_t e = 0; e < m_.edges.size(); ++e) {
    const Edges<D>& d = m_.edges[e];
    {
      StoreReport r(os, std::string("edges[") + formulation_name(d.stencil.formulation) + ", " + cell_type_name(d.stencil.type) +
                            (d.whole_triangles ? (D == 2 ? ", triangles" : ", tetrahedra") : "") + "]",
                    d.size());
      d.for_each_column(r);
    }
    os << "    colours: " << d.stencil.n_colours() << "\n";
  }
  os << "  linear_system: " << m_.system.dofs.n_dofs() << " dofs, " << m_.system.dofs.n_free << " free, "
     << m_.system.pattern.matrix.nonZeros() << " non-zeros; solver "
     << linear_solver_name(m_.linear_solver)
     << "\n";
  os << "  boundary_conditions: " << m_.bc.prescribed.size() << " prescribed dofs, "
     << (D == 3 ? m_.bc.traction_faces.size() : m_.bc.traction_edges.size()) << (D == 3 ? " traction faces" : " traction edges") << ", loads " << (m_.bc.has_loads ? (m_.bc.loads_depend_on_time ? "time-dependent" : "constant") : "none") << "\n";
  graph_->print(os);
}

// a_0 = M^-1 (f_ext - f_int) with the lumped mass: a constant load is then integrated exactly by Newmark and Bossak
// (free fall: u = g t^2 / 2). From an assembly without inertia (the step-0 residual the probes read holds the
// integrator's inertia of the initial velocity), which is put back afterwards.
template <int D>
void FemRunT<D>::set_equilibrium_acceleration() {
  const Eigen::VectorXd step0_full = m_.system.residual_full, step0 = m_.system.residual;
  assemble_system(ctx_, AssemblyMode::static_residual, m_.materials, m_.nodes, m_.cells, m_.bc, m_.quad, m_.system, &m_.edges);
  if (!m_.walls.empty()) add_wall_contact(m_.walls, m_.node_body, m_.nodes, false, m_.system);
  const DofMap& dofs = m_.system.dofs;
  // The residual of a tied mid-node (PFEM TRI6, TET10) went to its masters (T^T r), so its mass goes with it: each
  // master's mass is the row sum of T^T M T, m_a + sum over its ties of m_mid / 2 (a uniform g then gives a_0 = g).
  std::vector<double> mass(std::size_t(dofs.n_dofs()), 0.0);
  for (Index i = 0; i < m_.nodes.size(); ++i)
    for (int d = 0; d < D; ++d) mass[std::size_t(dofs.dof(i, d))] = m_.nodes.lumped_mass[i];
  for (const Tie& tie : dofs.ties)
    for (Index master : tie.master) mass[std::size_t(master)] += 0.5 * m_.nodes.lumped_mass[tie.dof / dofs.per_node];
  for (Index i = 0; i < m_.nodes.size(); ++i)
    for (int d = 0; d < D; ++d) {
      const Index dof = dofs.dof(i, d);
      const double m = mass[std::size_t(dof)];
      m_.nodes.a_n[i][d] = dofs.kind[std::size_t(dof)] == DofKind::free && m > 0.0 ? -m_.system.residual_full[dof] / m : 0.0;
    }
  // A tied mid-node follows its masters, so that the integrator stays linear in the tie.
  for (const Tie& tie : dofs.ties) {
    const int d = tie.dof % dofs.per_node;
    if (d < D)
      m_.nodes.a_n[tie.dof / dofs.per_node][d] =
          0.5 * (m_.nodes.a_n[tie.master[0] / dofs.per_node][d] + m_.nodes.a_n[tie.master[1] / dofs.per_node][d]);
  }
  m_.system.residual_full = step0_full, m_.system.residual = step0;
}

template <int D>
void FemRunT<D>::write_initial_state() {
  // Step 0: loads at t = 0, one assembly for the reactions, probes and the first frame.
  ctx_.step = 0, ctx_.t = 0.0, ctx_.dt = scene_.time.dt, ctx_.step_end = true;
  apply_boundary_conditions(ctx_, m_.nodes, m_.cells, m_.materials, m_.bc);
  assemble_system(ctx_, AssemblyMode::residual, m_.materials, m_.nodes, m_.cells, m_.bc, m_.quad, m_.system, &m_.edges);
  if (!m_.walls.empty()) {
    measure_contact_areas(ctx_, m_.walls, m_.cells, m_.nodes);
    add_wall_contact(m_.walls, m_.node_body, m_.nodes, false, m_.system);
  }
  if (scene_.time.initial_acceleration == InitialAcceleration::equilibrium && m_.nodes.a_n.used() && m_.nodes.lumped_mass.used())
    set_equilibrium_acceleration();
  status_ = StepStatus{};
  status_.converged = true;
  probes_node();
  if (options_.write_files && scene_.output.every > 0) output_node();
}

template <int D>
RunSummary FemRunT<D>::run() {
  const auto start = std::chrono::steady_clock::now();
  RunSummary summary;
  summary.steps_requested = scene_.time.steps;
  summary.dofs = m_.system.dofs.n_free;
  for (const auto& c : m_.cells) summary.cells += c.size();
  const RunSchedule schedule = start_run(
      scene_, options_, [this](const CheckpointReader& r) { return restore_checkpoint(r); }, summary, pvd_, probe_writer_);

  RunHooks hooks;
  hooks.write_initial_state = [&] { write_initial_state(); };
  hooks.write_last_converged_state = [&](int failed_step, double last_converged_time) {
    if (!options_.write_files || scene_.output.every <= 0 || last_converged_time == last_frame_time_) return;
    // Keep the last converged state for inspection (commit left it in u_n and F_n); it may lie inside
    // the failed step after converged sub-steps, so it takes that step's number.
    ctx_.step = failed_step;
    ctx_.t = last_converged_time;
    output_node();
  };
  hooks.wait_for_writer = [&] { writer_.wait(); };
  hooks.settled = [&](const StepContext& c) { return stop_.met(scene_.time, c.t, probe_values_); };
  use_adaptive_step(scene_, probe_values_, hooks);
  if (options_.write_files) hooks.write_checkpoint = [&](int step) { write_checkpoint(step); };
  const TimeLoopResult result = drive_run(schedule, ctx_, *graph_, status_, hooks);
  summarise_run(result, status_, schedule, summary);
  summarise_linear_solver(solver_, summary);
  wall_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary.wall_seconds = wall_;
  return summary;
}

template class FemRunT<2>;
template class FemRunT<3>;

}  // namespace loom
