// What the recipes share about a run's files: opening the output (a fresh run, or a restarted one that
// keeps what its checkpoint had written) and the part of a checkpoint that is not a store -- the step and
// time, the run's totals, the linear solver in use, the frames of the collection, the step's probe values and
// time.stop_when's window.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "engine/drivers/run_driver.hpp"
#include "engine/drivers/step_status.hpp"
#include "engine/graph/step_context.hpp"
#include "engine/io/checkpoint.hpp"
#include "engine/io/probe_writer.hpp"
#include "engine/io/pvd_writer.hpp"
#include "engine/linalg/linear_solver.hpp"
#include "engine/methods/method.hpp"
#include "engine/scene/scene_spec.hpp"

namespace loom {

struct CheckpointHeader {
  int step = 0;
  double t = 0.0;
  long long newton_iterations = 0;
  int cutbacks = 0;
  std::string method, scene_hash, linear_solver;
  double last_frame_time = -1.0;
  std::vector<PvdWriter::Entry> frames;
  // The probes of the step (what time.adaptive_dt reads for the next step's size) and time.stop_when's window: a
  // restarted run goes on with them as the run it continues would have.
  std::vector<double> probe_values;
  StopCondition::History stop_history;
  std::string stop_probe;  // the probe time.stop_when watched (a continued run watching another one starts afresh)
};

// The header of a checkpoint of the step that just completed.
CheckpointHeader checkpoint_header(const std::string& method, const StepContext& ctx, const StepStatus& status, const SceneSpec& scene,
                                   const LinearSolve& solver, double last_frame_time, const PvdWriter& pvd,
                                   const std::vector<double>& probe_values, const StopCondition& stop);
// Where a restarted run resumes: time, totals, the linear back-end, the probes and the stop condition of the checkpoint.
void resume_from(const CheckpointHeader& h, const SceneSpec& scene, StepContext& ctx, StepStatus& status, LinearSolve& solver,
                 double& last_frame_time, std::vector<double>& probe_values, StopCondition& stop);

void write_checkpoint_header(CheckpointWriter& w, const CheckpointHeader& h);
// Throws InputError if the checkpoint was written by another method; warns on `log` if by another scene text.
CheckpointHeader read_checkpoint_header(const CheckpointReader& r, const SceneSpec& scene, std::ostream* log);

// Opens the run's output directory: a fresh run removes the frames and checkpoints of an earlier run of
// the scene and starts probes.csv; a restarted run (`restart` not null) keeps the rows and frames up to
// its checkpoint's step, removes later ones and restores the collection.
void open_run_output(const SceneSpec& scene, const RunOptions& options, const CheckpointHeader* restart, PvdWriter& pvd,
                     ProbeWriter& probes);

// The schedule of a run (time step, steps, cut-backs, checkpoints, --stop-after) and its output: a restarted
// run (options.restart_file) has its stores restored by `restore` first and begins after the checkpoint.
RunSchedule start_run(const SceneSpec& scene, const RunOptions& options,
                      const std::function<CheckpointHeader(const CheckpointReader&)>& restore, RunSummary& summary, PvdWriter& pvd,
                      ProbeWriter& probes);

// Writes the checkpoint of `step` into the output directory and removes the older ones.
void store_checkpoint(const CheckpointWriter& w, const RunOptions& options, int step);

}  // namespace loom
