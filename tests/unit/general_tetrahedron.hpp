// The tetrahedron of the 3D element tests: general (no face parallel to a coordinate plane), positively oriented.
#pragma once

#include "systems/assemble/elements/tet4.hpp"

namespace loom::testing {

inline Tet4Corners general_tetrahedron() {
  Tet4Corners x;
  x << 0.1, -0.2, 0.3, 1.4, 0.1, 0.2, 0.3, 1.2, -0.1, 0.2, 0.4, 1.5;
  return x;
}

}  // namespace loom::testing
