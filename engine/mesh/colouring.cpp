#include "engine/mesh/colouring.hpp"

#include <algorithm>
#include <vector>

namespace loom {

void colour_cells(Cells& cells, Index n_nodes) {
  const Index n = cells.size();
  const int stride = cells.stride;
  // node -> cells adjacency (CSR)
  std::vector<Index> offset(std::size_t(n_nodes) + 1, 0);
  for (Index k = 0; k < cells.nodes.size(); ++k) ++offset[std::size_t(cells.nodes[k]) + 1];
  for (std::size_t i = 0; i < std::size_t(n_nodes); ++i) offset[i + 1] += offset[i];
  std::vector<Index> adjacent(std::size_t(offset.back()));
  {
    std::vector<Index> fill(offset.begin(), offset.end() - 1);
    for (Index c = 0; c < n; ++c)
      for (int a = 0; a < stride; ++a) adjacent[std::size_t(fill[std::size_t(cells.node(c, a))]++)] = c;
  }
  cells.colour.assign(n, kNoIndex);
  std::vector<Index> last_seen;  // last_seen[k] == c: colour k is taken by a neighbour of cell c
  Index n_colours = 0;
  for (Index c = 0; c < n; ++c) {
    for (int a = 0; a < stride; ++a) {
      const Index v = cells.node(c, a);
      for (Index k = offset[std::size_t(v)]; k < offset[std::size_t(v) + 1]; ++k) {
        const Index col = cells.colour[adjacent[std::size_t(k)]];
        if (col != kNoIndex) last_seen[std::size_t(col)] = c;
      }
    }
    Index col = 0;
    while (col < n_colours && last_seen[std::size_t(col)] == c) ++col;
    if (col == n_colours) {
      ++n_colours;
      last_seen.push_back(kNoIndex);
    }
    cells.colour[c] = col;
  }
  cells.colour_offsets.assign(std::size_t(n_colours) + 1, 0);
  for (Index c = 0; c < n; ++c) ++cells.colour_offsets[std::size_t(cells.colour[c]) + 1];
  for (std::size_t k = 0; k < std::size_t(n_colours); ++k) cells.colour_offsets[k + 1] += cells.colour_offsets[k];
  cells.by_colour.resize(std::size_t(n));
  std::vector<Index> fill(cells.colour_offsets.begin(), cells.colour_offsets.end() - 1);
  for (Index c = 0; c < n; ++c) cells.by_colour[std::size_t(fill[std::size_t(cells.colour[c])]++)] = c;
}

}  // namespace loom
