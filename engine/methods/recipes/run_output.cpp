#include "engine/methods/recipes/run_output.hpp"

#include <optional>
#include <ostream>

#include "engine/core/errors.hpp"
#include "engine/io/files.hpp"
#include "engine/io/run_files.hpp"

namespace loom {

namespace {
std::string stop_probe_name(const SceneSpec& scene) {
  const Index p = scene.time.stop_probe;
  return p == kNoIndex ? std::string() : scene.probes[std::size_t(p)].name;
}
}  // namespace

CheckpointHeader checkpoint_header(const std::string& method, const StepContext& ctx, const StepStatus& status, const SceneSpec& scene,
                                   const LinearSolve& solver, double last_frame_time, const PvdWriter& pvd,
                                   const std::vector<double>& probe_values, const StopCondition& stop) {
  CheckpointHeader h;
  h.step = ctx.step;
  h.t = ctx.t;
  h.newton_iterations = status.total_iterations;
  h.cutbacks = status.total_cutbacks;
  h.method = method;
  h.scene_hash = scene.text_hash;
  h.linear_solver = solver.backend();
  h.last_frame_time = last_frame_time;
  h.frames = pvd.entries();
  h.probe_values = probe_values;
  h.stop_history = stop.history();
  h.stop_probe = stop_probe_name(scene);
  return h;
}

void resume_from(const CheckpointHeader& h, const SceneSpec& scene, StepContext& ctx, StepStatus& status, LinearSolve& solver,
                 double& last_frame_time, std::vector<double>& probe_values, StopCondition& stop) {
  probe_values = h.probe_values;
  stop.restore(h.stop_history);
  status.total_iterations = h.newton_iterations;
  status.total_cutbacks = h.cutbacks;
  solver.use_backend(h.linear_solver);
  last_frame_time = h.last_frame_time;
  ctx.step = h.step;
  ctx.t = h.t;
  ctx.dt = scene.time.dt;
}

RunSchedule start_run(const SceneSpec& scene, const RunOptions& options,
                      const std::function<CheckpointHeader(const CheckpointReader&)>& restore, RunSummary& summary, PvdWriter& pvd,
                      ProbeWriter& probes) {
  RunSchedule schedule{scene.time.dt, scene.time.steps, scene.solver.max_cutbacks, options.progress, options.quiet ? nullptr : options.log};
  schedule.checkpoint_every = options.write_files ? scene.output.checkpoint_every : 0;
  schedule.stop_after = options.stop_after;
  std::optional<CheckpointHeader> restart;
  if (!options.restart_file.empty()) {
    restart = restore(CheckpointReader(options.restart_file));
    schedule.first_step = restart->step + 1;
    schedule.restarted = summary.restarted = true;
    summary.restarted_from = restart->step;
    LOOM_CHECK(options.stop_after == 0 || options.stop_after > restart->step, InputError,
               "--stop-after " << options.stop_after << ": error: the run continues from the checkpoint of step " << restart->step
                               << "; stop after a later step");
  }
  if (options.write_files) open_run_output(scene, options, restart ? &*restart : nullptr, pvd, probes);
  return schedule;
}

void write_checkpoint_header(CheckpointWriter& w, const CheckpointHeader& h) {
  w.text("run/method", h.method);
  w.text("run/scene_hash", h.scene_hash);
  w.value("run/step", h.step);
  w.value("run/t", h.t);
  w.value("run/newton_iterations", h.newton_iterations);
  w.value("run/cutbacks", h.cutbacks);
  w.text("run/linear_solver", h.linear_solver);
  w.value("run/last_frame_time", h.last_frame_time);
  w.value("run/frames", Index(h.frames.size()));
  for (std::size_t k = 0; k < h.frames.size(); ++k) {
    const std::string key = "run/frame/" + std::to_string(k);
    w.value(key + "/time", h.frames[k].time);
    w.value(key + "/part", h.frames[k].part);
    w.text(key + "/file", h.frames[k].file);
  }
  w.vector("run/probe_values", h.probe_values);
  w.vector("run/stop_history", h.stop_history);
  w.text("run/stop_probe", h.stop_probe);
}

CheckpointHeader read_checkpoint_header(const CheckpointReader& r, const SceneSpec& scene, std::ostream* log) {
  CheckpointHeader h;
  h.method = r.text("run/method");
  const std::string method = method_name(scene.scene.method);
  LOOM_CHECK(h.method == method, InputError,
             r.path() << ": error: the checkpoint is of a method " << h.method << " run; the scene runs method " << method);
  h.scene_hash = r.text("run/scene_hash");
  if (h.scene_hash != scene.text_hash && log)
    *log << r.path() << ": warning: the scene file or its --set overrides differ from those of the run that wrote the checkpoint; "
         << "continuing with the scene as it is now\n";
  h.step = r.value<int>("run/step");
  h.t = r.value<double>("run/t");
  LOOM_CHECK(h.step >= 0 && h.step < scene.time.steps, InputError,
             r.path() << ": error: the checkpoint is of step " << h.step << ", and the scene has " << scene.time.steps
                      << " steps: nothing is left to run (raise time.steps to continue)");
  h.newton_iterations = r.value<long long>("run/newton_iterations");
  h.cutbacks = r.value<int>("run/cutbacks");
  h.linear_solver = r.text("run/linear_solver");
  h.last_frame_time = r.value<double>("run/last_frame_time");
  const Index n = r.value<Index>("run/frames");
  for (Index k = 0; k < n; ++k) {
    const std::string key = "run/frame/" + std::to_string(k);
    h.frames.push_back({r.value<double>(key + "/time"), r.text(key + "/file"), r.value<int>(key + "/part")});
  }
  // Checkpoints of loom before 2026-12 hold neither the probes' values nor time.stop_when's window: their runs
  // continue with time.dt for a first adaptive step and a stop condition that starts looking afresh.
  if (r.has("run/probe_values")) r.vector("run/probe_values", h.probe_values);
  if (r.has("run/stop_history")) r.vector("run/stop_history", h.stop_history);
  if (r.has("run/stop_probe")) h.stop_probe = r.text("run/stop_probe");
  // ProbeWriter::reopen refuses another set of probes; time.stop_when may watch another one of them now.
  if (h.probe_values.size() != scene.probes.size()) h.probe_values.clear();
  if (h.stop_probe != stop_probe_name(scene)) h.stop_history.clear();
  return h;
}

void open_run_output(const SceneSpec& scene, const RunOptions& options, const CheckpointHeader* restart, PvdWriter& pvd,
                     ProbeWriter& probes) {
  const std::string& dir = options.output_directory;
  prepare_output_directory(dir, options.output_origin.empty() ? "output.directory" : options.output_origin);
  const std::string stem = file_stem(scene.scene.name);
  std::vector<std::string> names;
  for (const auto& p : scene.probes) names.push_back(p.name);
  // A restart checks the probes of the run it continues before it removes anything of that run.
  if (restart) probes.reopen(dir + "/probes.csv", names, restart->step);
  std::vector<std::string> listed;  // the checkpoint's collection
  if (restart)
    for (const auto& f : restart->frames) listed.push_back(f.file);
  remove_frames(dir, stem, restart ? restart->step : -1, listed);
  if (!restart) remove_checkpoints(dir, -1);
  pvd = PvdWriter(dir, stem);
  if (restart) pvd.restore(restart->frames);
  if (!restart) probes.open(dir + "/probes.csv", names);
}

void store_checkpoint(const CheckpointWriter& w, const RunOptions& options, int step) {
  w.write(checkpoint_path(options.output_directory, step));
  remove_checkpoints(options.output_directory, step);
}

}  // namespace loom
