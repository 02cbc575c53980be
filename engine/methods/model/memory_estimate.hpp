// Whether a scene's stores and its linear solver fit in memory, decided before anything is allocated: a
// divisions value a digit too long must be a clear error naming the key (exit 2), not std::bad_alloc.
//
// The estimate is per cell (per particle and grid cell for mpm), measured as the peak resident size of
// `loom run` on Cook's membrane at 200 x 200 and 400 x 400 divisions (2 n^2 triangles; docs/memory.md):
// p1 1.5 KB, tri6 8.5 KB, p1p1_uphi 5.5 KB per cell at 8e4 cells, growing like the fill of the sparse
// factorization, about 8 % per doubling of the cell count. The measured figures are the lower end, so that
// only scenes that cannot fit are refused.
#pragma once

#include <cstdint>
#include <string>

#include "engine/scene/scene_spec.hpp"

namespace loom {

struct MemoryEstimate {
  double cells = 0.0;  // cells of the body meshes (and grid cells for mpm)
  double bytes = 0.0;
};
MemoryEstimate estimate_memory(const SceneSpec& scene);

// The smaller of the memory the system has available (MemAvailable) and what the process's address-space
// limit (ulimit -v) leaves; `why` names the one that binds.
double available_memory(std::string* why = nullptr);

// Throws InputError naming the mesh key if the estimate exceeds the available memory.
void check_memory(const SceneSpec& scene);

}  // namespace loom
