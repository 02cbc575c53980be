// The history b^e (hencky_perzyna, drucker_prager) at pfem's quadrature points across a remesh. The new points are those of the new
// cells: a point of a cell that kept its corners copies its old point, as F_n does; the others take b^e mapped by the
// scene's scheme (CPM, BTM-ISO0/1/2 on the same background triangulation of the old points as F_n; every variant keeps
// an SPD tensor SPD), scaled so that det b^e = J^2 of their mapped F_n where the flow is isochoric (hencky_perzyna:
// b^e's volume is F's, as the smoothed domains' transfer does, domain_transfer.cpp). drucker_prager's flow changes
// the volume, so its mapped b^e is kept as mapped.
#pragma once

#include <algorithm>
#include <vector>

#include "engine/scene/scene_spec.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/history_columns.hpp"
#include "engine/store/quad_points.hpp"
#include "systems/map/map_state.hpp"
#include "systems/update/commit_domains.hpp"

namespace loom {

// The formulations whose blocks carry b^e before the remesh (their new blocks carry it after).
template <int D>
std::vector<Formulation> formulations_with_history(const std::vector<Cells>& cells, const std::vector<QuadPoints<D>>& quad) {
  std::vector<Formulation> f;
  for (std::size_t k = 0; k < cells.size(); ++k)
    if (quad[k].be_n.used()) f.push_back(cells[k].formulation);
  return f;
}

// Whether every material with history flows at constant volume (none is drucker_prager).
inline bool isochoric_plastic_flow(const SceneSpec& scene) {
  return std::none_of(scene.materials.begin(), scene.materials.end(), [](const MaterialSpec& m) { return m.model == MaterialModel::drucker_prager; });
}

// old_be: b^e_n of every old point (I where none), in the order of the old points given to map_state for F_n.
template <int D>
void transfer_point_history(const std::vector<Vec<D>>& old_x, const std::vector<Mat3>& old_be, const std::vector<Vec<D>>& new_x,
                            const std::vector<Index>& copy_from, const MapSettings& settings, bool isochoric, std::vector<QuadPoints<D>>& quad) {
  if (std::none_of(quad.begin(), quad.end(), [](const QuadPoints<D>& q) { return q.be_n.used(); })) return;
  std::vector<Mat3> new_be;
  MapStats stats;  // the same counts as F_n's
  map_state(old_x, old_be, new_x, copy_from, settings, new_be, stats);
  std::size_t next = 0;
  for (QuadPoints<D>& q : quad)
    for (Index p = 0; p < q.size(); ++p, ++next) {
      if (!q.be_n.used()) continue;
      const bool kept = copy_from[next] >= 0;
      q.be_n[p] = q.be[p] = kept || !isochoric ? new_be[next] : with_volume_ratio(new_be[next], q.F_n[p].determinant());
    }
}

}  // namespace loom
