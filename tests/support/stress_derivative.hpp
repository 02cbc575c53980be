// dP/dF of a material's first Piola stress P(F) by central differences (the 9 x 9 layout of tensor9.hpp), against
// which the kernels' consistent tangents are checked. Any type with bool stress(const Mat3& F, Mat3& P) will do: a
// hyperelastic material, or a history material's step at a point (history_point.hpp).
#pragma once

#include <gtest/gtest.h>

#include "systems/assemble/materials/tensor9.hpp"

namespace loom::testing {

template <class MaterialT>
Mat9 stress_derivative(const MaterialT& m, const Mat3& F, double h = 1e-6) {
  Mat9 A;
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) {
      Mat3 dF = Mat3::Zero(), Pp = Mat3::Zero(), Pm = Mat3::Zero();
      dF(k, l) = h;
      EXPECT_TRUE(m.stress(F + dF, Pp));
      EXPECT_TRUE(m.stress(F - dF, Pm));
      const Mat3 dP = (Pp - Pm) / (2 * h);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) A(ij(i, j), ij(k, l)) = dP(i, j);
    }
  return A;
}

}  // namespace loom::testing
