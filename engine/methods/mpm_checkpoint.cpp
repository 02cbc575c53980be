// Checkpoints of the mpm recipe: every column of the particles, the traction and probe points and their
// grid locations (the walk of the next locate starts from the cell a point was in), the grid nodes, and the
// run's header (engine/methods/run_output.hpp). The grid's active set, dof numbering and pattern follow
// from the particles' cells and are rebuilt by the first step after a restore, as a step rebuilds them
// whenever the active set changes.
#include <string>

#include "engine/methods/mpm_method.hpp"
#include "engine/methods/run_output.hpp"

namespace loom {

void MpmRun::write_checkpoint(int step) {
  writer_.wait();  // the step's frames are in the collection
  ScopedTimer timer(timers_, "checkpoint");
  CheckpointWriter w;
  CheckpointHeader h;
  h.step = step;
  h.t = ctx_.t;
  h.newton_iterations = status_.total_iterations;
  h.cutbacks = status_.total_cutbacks;
  h.method = "mpm";
  h.scene_hash = scene_.text_hash;
  h.linear_solver = solver_.backend();
  h.last_frame_time = last_frame_time_;
  h.frames = pvd_.entries();
  write_checkpoint_header(w, h);
  w.store("particles", m_.particles);
  w.store("particle_locations", m_.particle_loc);
  w.store("traction_points", m_.traction_points);
  w.store("traction_point_locations", m_.traction_loc);
  w.store("probe_points", m_.probe_points);
  w.store("probe_point_locations", m_.probe_loc);
  w.store("grid_nodes", m_.grid_nodes);
  store_checkpoint(w, options_, step);
}

CheckpointHeader MpmRun::restore_checkpoint(const CheckpointReader& r) {
  const CheckpointHeader h = read_checkpoint_header(r, scene_, options_.log);
  r.store("particles", m_.particles);
  r.store("particle_locations", m_.particle_loc);
  r.store("traction_points", m_.traction_points);
  r.store("traction_point_locations", m_.traction_loc);
  r.store("probe_points", m_.probe_points);
  r.store("probe_point_locations", m_.probe_loc);
  r.store("grid_nodes", m_.grid_nodes);
  m_.activity.version = 0;  // the first step activates the grid of the restored particles
  status_.total_iterations = h.newton_iterations;
  status_.total_cutbacks = h.cutbacks;
  solver_.use_backend(h.linear_solver);
  last_frame_time_ = h.last_frame_time;
  ctx_.step = h.step;
  ctx_.t = h.t;
  ctx_.dt = scene_.time.dt;
  return h;
}

}  // namespace loom
