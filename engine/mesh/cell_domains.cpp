#include "engine/mesh/cell_domains.hpp"

#include "engine/mesh/colouring.hpp"

namespace loom {

template <int D>
Edges<D> build_cell_domains(const Cells& cells, Index n_nodes) {
  constexpr int N = D + 1;
  Edges<D> store;
  store.stencil = Cells(D == 2 ? CellType::stencil3 : CellType::stencil4, cells.formulation);
  store.whole_triangles = true;
  const Index n = cells.size();
  std::vector<Index>& nodes = store.stencil.nodes.values();
  nodes.reserve(std::size_t(n) * N);
  for (Index t = 0; t < n; ++t) nodes.insert(nodes.end(), cells.cell_nodes(t), cells.cell_nodes(t) + N);
  store.stencil.body.assign(n, 0);
  for (Index t = 0; t < n; ++t) store.stencil.body[t] = cells.body[t];
  store.resize(n);
  for (Index t = 0; t < n; ++t) {
    store.triangles[2 * t] = t;  // the second stays kNoIndex
    for (int a = 0; a < N; ++a) store.pressure_weight[N * t + a] = 1.0 / double(N);
  }
  colour_cells(store.stencil, n_nodes);
  return store;
}

template Edges<2> build_cell_domains<2>(const Cells&, Index);
template Edges<3> build_cell_domains<3>(const Cells&, Index);

}  // namespace loom
