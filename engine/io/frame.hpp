// One output frame as plain arrays: the snapshot the output system takes of the stores, handed to a
// writer that may run concurrently with the next step (the stores are not touched by the writer).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/types.hpp"

namespace loom {

struct FrameArray {
  std::string name;
  int components = 1;
  std::vector<double> values;  // n_entities * components
};

struct Frame {
  int step = 0;
  double time = 0.0;
  std::vector<double> points;          // 3 coordinates per point
  std::vector<Index> connectivity;     // node indices of all cells, concatenated
  std::vector<Index> offsets;          // end of each cell in connectivity
  std::vector<std::uint8_t> cell_types;  // VTK cell type of each cell
  std::vector<FrameArray> point_arrays, cell_arrays;

  Index n_points() const { return Index(points.size() / 3); }
  Index n_cells() const { return Index(offsets.size()); }
};

// VTK cell type codes used by loom.
inline constexpr std::uint8_t kVtkTriangle = 5;
inline constexpr std::uint8_t kVtkQuad = 9;
inline constexpr std::uint8_t kVtkQuadraticTriangle = 22;

}  // namespace loom
