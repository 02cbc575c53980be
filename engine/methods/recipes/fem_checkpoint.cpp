// Checkpoints of the fem and pfem recipes: every column of the node, cell and quadrature-point stores,
// the PFEM topology the next remesh starts from, and the run's header (engine/methods/recipes/run_output.hpp).
// What follows from them -- boundary conditions on the current mesh, dof numbering, sparsity, scatters,
// the probes' nodes -- is rebuilt on restore exactly as a remesh rebuilds it, so that the restarted run
// computes what the uninterrupted one would have, bit for bit.
#include <algorithm>
#include <string>

#include "engine/core/errors.hpp"
#include "engine/io/run_files.hpp"
#include "engine/mesh/colouring.hpp"
#include "engine/methods/pfem/pfem_checkpoint.hpp"
#include "engine/methods/recipes/fem_method.hpp"
#include "engine/methods/recipes/run_output.hpp"

namespace loom {

template <int D>
void FemRunT<D>::write_checkpoint(int step) {
  LOOM_ASSERT(step == ctx_.step, "a checkpoint is of the step that just completed");
  writer_.wait();  // the step's frame is in the collection
  ScopedTimer timer(timers_, "checkpoint");
  CheckpointWriter w;
  write_checkpoint_header(w, checkpoint_header(method_name(scene_.scene.method), ctx_, status_, scene_, solver_, last_frame_time_, pvd_,
                                                 probe_values_, stop_));
  w.store("nodes", m_.nodes);
  w.vector("node_body", m_.node_body);
  w.value("blocks", Index(m_.cells.size()));
  for (std::size_t k = 0; k < m_.cells.size(); ++k) {
    const std::string key = "block/" + std::to_string(k);
    w.value(key + "/formulation", int(m_.cells[k].formulation));
    w.store(key + "/cells", m_.cells[k]);
    w.vector(key + "/by_colour", m_.cells[k].by_colour);
    w.vector(key + "/colour_offsets", m_.cells[k].colour_offsets);
    w.store(key + "/quad_points", m_.quad[k]);
  }
  // The integration domains of seed 001's elements: their history b^e_n and geometry in B_n.
  w.value("domain_blocks", Index(m_.edges.size()));
  for (std::size_t k = 0; k < m_.edges.size(); ++k) w.store("domains/" + std::to_string(k), m_.edges[k]);
  if (pfem_) write_topology(w, topology_, m_);
  if (new_material_mass_ > 0.0) w.value("remesh/new_material_mass", new_material_mass_);  // absent: none (older checkpoints)
  store_checkpoint(w, options_, step);
}

template <int D>
CheckpointHeader FemRunT<D>::restore_checkpoint(const CheckpointReader& r) {
  const CheckpointHeader h = read_checkpoint_header(r, scene_, options_.log);
  // What the scene built, to check the checkpoint against: fem keeps its mesh, pfem its particles.
  const Index n_nodes = m_.nodes.size();
  const std::vector<Index> particle_body(m_.node_body.begin(), m_.node_body.begin() + (pfem_ ? topology_.n_points : n_nodes));
  std::vector<std::vector<Index>> connectivity;  // fem: the mesh the system was built on
  for (const auto& c : m_.cells) connectivity.push_back(c.nodes.values());
  r.store("nodes", m_.nodes);
  r.vector("node_body", m_.node_body);
  r.expect_size("node bodies", m_.node_body.size(), std::size_t(m_.nodes.size()));
  if (pfem_ && !particles_change()) {
    r.expect(m_.node_body.size() >= particle_body.size() && std::equal(particle_body.begin(), particle_body.end(), m_.node_body.begin()),
             "has other particles than the scene (" + std::to_string(particle_body.size()) + " in its bodies)");
  } else if (!pfem_) {
    r.expect_size("nodes", std::size_t(m_.nodes.size()), std::size_t(n_nodes));
  }
  const Index blocks = r.value<Index>("blocks");
  LOOM_CHECK(blocks == Index(m_.cells.size()), InputError,
             r.path() << ": error: the checkpoint has " << blocks << " cell blocks, the scene " << m_.cells.size()
                      << ": the scene differs from the one it was written for");
  for (std::size_t k = 0; k < m_.cells.size(); ++k) {
    const std::string key = "block/" + std::to_string(k);
    LOOM_CHECK(r.value<int>(key + "/formulation") == int(m_.cells[k].formulation), InputError,
               r.path() << ": error: cell block " << k << " has another element formulation than in this scene");
    r.store(key + "/cells", m_.cells[k]);
    r.vector(key + "/by_colour", m_.cells[k].by_colour);
    r.vector(key + "/colour_offsets", m_.cells[k].colour_offsets);
    r.store(key + "/quad_points", m_.quad[k]);
    r.expect_size("quadrature points in block " + std::to_string(k), std::size_t(m_.quad[k].size()),
                  std::size_t(m_.cells[k].size()) * std::size_t(m_.quad[k].per_cell));
    if (!pfem_) r.expect(m_.cells[k].nodes.values() == connectivity[k], "has another mesh (cell block " + std::to_string(k) + ")");
    for (Index v : m_.cells[k].nodes) r.expect(v >= 0 && v < m_.nodes.size(), "has cells on nodes it does not hold");
  }
  LOOM_CHECK(r.value<Index>("domain_blocks") == Index(m_.edges.size()), InputError,
             r.path() << ": error: the checkpoint has " << r.value<Index>("domain_blocks") << " blocks of integration domains, the scene "
                      << m_.edges.size() << ": the scene differs from the one it was written for");
  for (std::size_t k = 0; k < m_.edges.size(); ++k) {
    const std::vector<Index> stencil = m_.edges[k].stencil.nodes.values();
    r.store("domains/" + std::to_string(k), m_.edges[k]);
    if (!pfem_) r.expect(m_.edges[k].stencil.nodes.values() == stencil, "has other integration domains (block " + std::to_string(k) + ")");
    for (Index v : m_.edges[k].stencil.nodes) r.expect(v >= 0 && v < m_.nodes.size(), "has integration domains on nodes it does not hold");
    colour_cells(m_.edges[k].stencil, m_.nodes.size());  // the colour groups are not columns: rebuilt as the builder did
  }
  if (pfem_) {
    restore_topology(r, topology_, m_, particles_change());
    new_material_mass_ = r.has("remesh/new_material_mass") ? r.value<double>("remesh/new_material_mass") : 0.0;
    rebuild_system(m_, topology_, /*connectivity_changed=*/true);
    probe_plan_ = plan_probes(scene_, m_.nodes, m_.cells, m_.node_body);
  }
  resume_from(h, scene_, ctx_, status_, solver_, last_frame_time_, probe_values_, stop_);
  return h;
}

template void FemRunT<2>::write_checkpoint(int);
template void FemRunT<3>::write_checkpoint(int);
template CheckpointHeader FemRunT<2>::restore_checkpoint(const CheckpointReader&);
template CheckpointHeader FemRunT<3>::restore_checkpoint(const CheckpointReader&);

}  // namespace loom
