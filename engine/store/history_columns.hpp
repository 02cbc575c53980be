// Which blocks of quadrature points carry the history b^e of a material with history (a yielding hencky_perzyna,
// drucker_prager): the blocks of the given formulations. Used when a model is built (fem, pfem) and after each
// remesh (pfem), whose new blocks carry it as the old ones did.
#pragma once

#include <algorithm>
#include <vector>

#include "engine/store/cells.hpp"
#include "engine/store/quad_points.hpp"

namespace loom {

// After the quadrature points are allocated: b^e_n and the iterate's b^e in the blocks of those formulations
// (b^e = I, the reference state, until set).
template <int D>
void use_history_columns(const std::vector<Formulation>& with_history, const std::vector<Cells>& cells, std::vector<QuadPoints<D>>& quad) {
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const bool history = std::find(with_history.begin(), with_history.end(), cells[k].formulation) != with_history.end();
    quad[k].be_n.use(history), quad[k].be.use(history);
    quad[k].resize(quad[k].size());
  }
}

}  // namespace loom
