// Checkpoints of the mpm recipe: every column of the particles, the traction and probe points and their
// grid locations (the walk of the next locate starts from the cell a point was in), the grid nodes, and the
// run's header (engine/methods/recipes/run_output.hpp), and the active set the grid's Newton system was built
// around (systems/locate/grid_system.hpp). The active set follows from the particles' cells; the first step
// after a restore builds the system around the stored set and fits the active set into it, as the run it
// continues did.
#include <string>
#include <utility>

#include "engine/core/errors.hpp"
#include "engine/methods/recipes/mpm_method.hpp"
#include "engine/methods/recipes/run_output.hpp"

namespace loom {
namespace {

// The stores a checkpoint holds, by name: the same list for writing and reading.
template <class Model, class Visit>
void visit_stores(Model& m, Visit&& f) {
  f("particles", m.particles), f("particle_locations", m.particle_loc), f("traction_points", m.traction_points),
      f("traction_point_locations", m.traction_loc), f("probe_points", m.probe_points), f("probe_point_locations", m.probe_loc),
      f("grid_nodes", m.grid_nodes);
}

}  // namespace

template <int D>
void MpmRunT<D>::write_checkpoint(int step) {
  LOOM_ASSERT(step == ctx_.step, "a checkpoint is of the step that just completed");
  writer_.wait();  // the step's frames are in the collection
  ScopedTimer timer(timers_, "checkpoint");
  CheckpointWriter w;
  write_checkpoint_header(w, checkpoint_header(method_name(scene_.scene.method), ctx_, status_, scene_, solver_, last_frame_time_, pvd_,
                                                 probe_values_, stop_));
  visit_stores(std::as_const(m_), [&](const char* name, const auto& store) { w.store(name, store); });
  w.vector("grid_system_base", m_.activity.system_base);
  store_checkpoint(w, options_, step);
}

template <int D>
CheckpointHeader MpmRunT<D>::restore_checkpoint(const CheckpointReader& r) {
  const CheckpointHeader h = read_checkpoint_header(r, scene_, options_.log);
  std::vector<std::size_t> sizes;  // what the scene built: the same particles, points and grid
  visit_stores(std::as_const(m_), [&](const char*, const auto& store) { sizes.push_back(std::size_t(store.size())); });
  std::size_t k = 0;
  visit_stores(m_, [&](const char* name, auto& store) {
    r.store(name, store);
    r.expect_size(std::string(name) + " entries", std::size_t(store.size()), sizes[k++]);
  });
  m_.activity.version = 0;  // the first step activates the grid of the restored particles
  // ... in the Newton system the run had (grid_system.hpp): the same matrices, factorised in the same order.
  m_.activity.system_cells.clear();
  m_.activity.system_base.clear();
  if (r.has("grid_system_base")) r.vector("grid_system_base", m_.activity.system_base);
  // The probes of the restored step (which an adaptive step size reads before the next step writes them) come with
  // the checkpoint: evaluated here they would need the grid of that step, which the next step activates (its loads
  // failed for traction points beside cells that were not yet active).
  resume_from(h, scene_, ctx_, status_, solver_, last_frame_time_, probe_values_, stop_);
  return h;
}


template void MpmRunT<2>::write_checkpoint(int);
template void MpmRunT<3>::write_checkpoint(int);
template CheckpointHeader MpmRunT<2>::restore_checkpoint(const CheckpointReader&);
template CheckpointHeader MpmRunT<3>::restore_checkpoint(const CheckpointReader&);

}  // namespace loom
