// One output frame as plain arrays: the snapshot the output system takes of the stores, handed to a
// writer that may run concurrently with the next step (the stores are not touched by the writer).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "engine/core/types.hpp"
#include "engine/store/cells.hpp"

namespace loom {

struct FrameArray {
  std::string name;
  int components = 1;
  std::vector<double> values;  // n_entities * components
};

// One meaning of `pressure` for every method, written into each file's field data beside the arrays.
inline constexpr const char* kPressureDefinition =
    "pressure = -tr(sigma)/3: the mean compressive Cauchy stress, positive in compression (every method)";
inline constexpr const char* kMeanStressDefinition =
    "mean_stress = tr(sigma)/3 = -pressure: the unknown p of the mixed u-p MPM (sigma = dev(sigma) + p I), positive in tension";

struct Frame {
  int step = 0;
  double time = 0.0;
  std::vector<double> points;          // 3 coordinates per point
  std::vector<Index> connectivity;     // node indices of all cells, concatenated
  std::vector<Index> offsets;          // end of each cell in connectivity
  std::vector<std::uint8_t> cell_types;  // VTK cell type of each cell
  std::vector<FrameArray> point_arrays, cell_arrays;
  // Strings written as the dataset's field data (name, text): what the arrays mean.
  std::vector<std::pair<std::string, std::string>> notes;

  Index n_points() const { return Index(points.size() / 3); }
  Index n_cells() const { return Index(offsets.size()); }
};

// VTK cell type codes used by loom.
inline constexpr std::uint8_t kVtkTriangle = 5;
inline constexpr std::uint8_t kVtkQuad = 9;
inline constexpr std::uint8_t kVtkQuadraticTriangle = 22;
inline constexpr std::uint8_t kVtkBiquadraticQuad = 28;
inline constexpr std::uint8_t kVtkTetra = 10;
inline constexpr std::uint8_t kVtkQuadraticTetra = 24;  // corners, then edges 01 12 20 03 13 23 (loom's tet10 order)

// The VTK cell of a loom cell type (0 for the stencils of integration domains, which are never output).
inline std::uint8_t vtk_cell_type(CellType t) {
  switch (t) {
    case CellType::tri3: return kVtkTriangle;
    case CellType::tri6: return kVtkQuadraticTriangle;
    case CellType::quad4: return kVtkQuad;
    case CellType::quad9: return kVtkBiquadraticQuad;
    case CellType::tet4: return kVtkTetra;
    case CellType::tet10: return kVtkQuadraticTetra;
    case CellType::stencil3: case CellType::stencil4: case CellType::stencil5: return 0;
  }
  return 0;
}

}  // namespace loom
