// Cell colouring (engine/mesh/colouring): cells of one colour share no node; by_colour lists every cell
// once, grouped by colour in increasing cell order (what makes colour-by-colour assembly deterministic).
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <set>

#include "engine/mesh/colouring.hpp"
#include "engine/mesh/generators.hpp"

namespace loom {
namespace {

Cells cells_of(const MeshData& m) {
  Cells cells;
  cells.nodes.values() = m.triangles;
  cells.body.assign(m.n_triangles(), 0);
  return cells;
}

void expect_valid_colouring(const Cells& cells, Index n_nodes) {
  const Index n = cells.size();
  ASSERT_EQ(cells.colour.size(), n);
  ASSERT_EQ(Index(cells.colour_offsets.size()), cells.n_colours() + 1);
  EXPECT_EQ(cells.colour_offsets.front(), 0);
  EXPECT_EQ(cells.colour_offsets.back(), n);
  // by_colour is a permutation of the cells.
  std::vector<Index> sorted = cells.by_colour;
  std::sort(sorted.begin(), sorted.end());
  std::vector<Index> all(static_cast<std::size_t>(n));
  std::iota(all.begin(), all.end(), 0);
  EXPECT_EQ(sorted, all);
  for (Index k = 0; k < cells.n_colours(); ++k) {
    std::vector<char> taken(std::size_t(n_nodes), 0);
    const Index begin = cells.colour_offsets[std::size_t(k)], end = cells.colour_offsets[std::size_t(k) + 1];
    EXPECT_LT(begin, end) << "empty colour " << k;
    for (Index i = begin; i < end; ++i) {
      const Index c = cells.by_colour[std::size_t(i)];
      EXPECT_EQ(cells.colour[c], k);
      if (i > begin) {
        EXPECT_LT(cells.by_colour[std::size_t(i) - 1], c);
      }
      for (int a = 0; a < cells.stride; ++a) {
        const Index node = cells.node(c, a);
        EXPECT_FALSE(taken[std::size_t(node)]) << "colour " << k << " shares node " << node;
        taken[std::size_t(node)] = 1;
      }
    }
  }
}

}  // namespace

TEST(ColourCells, TwoCellsSharingAnEdgeGetTwoColours) {
  Cells cells;
  cells.nodes.values() = {0, 1, 2, 0, 2, 3};
  cells.body.assign(2, 0);
  colour_cells(cells, 4);
  EXPECT_EQ(cells.n_colours(), 2);
  EXPECT_NE(cells.colour[0], cells.colour[1]);
  expect_valid_colouring(cells, 4);
}

TEST(ColourCells, CellsWithoutCommonNodesShareAColour) {
  Cells cells;
  cells.nodes.values() = {0, 1, 2, 3, 4, 5};
  cells.body.assign(2, 0);
  colour_cells(cells, 6);
  EXPECT_EQ(cells.n_colours(), 1);
  expect_valid_colouring(cells, 6);
}

TEST(ColourCells, GridsOfEveryPatternAreColouredRaceFree) {
  for (GridPattern p : {GridPattern::right, GridPattern::alternating, GridPattern::shifted}) {
    RectangleSpec spec;
    spec.nx = 7, spec.ny = 5;
    spec.pattern = p;
    const MeshData m = generate_rectangle(spec);
    Cells cells = cells_of(m);
    colour_cells(cells, Index(m.X.size()));
    expect_valid_colouring(cells, Index(m.X.size()));
    // At least as many colours as cells around the busiest node.
    std::vector<int> valence(m.X.size(), 0);
    for (Index n : m.triangles) ++valence[std::size_t(n)];
    EXPECT_GE(cells.n_colours(), *std::max_element(valence.begin(), valence.end()));
  }
}

TEST(ColourCells, RecolouringGivesTheSameResult) {
  RectangleSpec spec;
  spec.nx = 6, spec.ny = 6;
  spec.pattern = GridPattern::alternating;
  Cells a = cells_of(generate_rectangle(spec));
  Cells b = cells_of(generate_rectangle(spec));
  colour_cells(a, 49);
  colour_cells(b, 49);
  colour_cells(b, 49);
  EXPECT_EQ(a.colour.values(), b.colour.values());
  EXPECT_EQ(a.by_colour, b.by_colour);
}

}  // namespace loom
