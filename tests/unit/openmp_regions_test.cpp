// engine/linalg/openmp_regions_of_one.cpp: with OpenMP limited to one thread (as ctest and the loom command run),
// CHOLMOD's parallel regions are bound to the program's GOMP_parallel and run on the calling thread (CHOLMOD is told
// to factorise supernodally, a region per supernode), and the factorisation is right; with any other limit, or with
// LOOM_OPENMP=libgomp (ctest runs the program so a second time), every region goes to libgomp.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "engine/linalg/linear_solver.hpp"
#include "engine/linalg/openmp_regions_of_one.hpp"

namespace loom {

TEST(OpenmpRegionsOfOne, CholmodsRegionsRunOnTheCallingThreadWhenOpenmpHasOneThread) {
  // The 5-point Laplacian on a 40 x 40 grid plus the identity: symmetric positive definite, supernodal.
  const int m = 40, n = m * m;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      const int k = i * m + j;
      t.emplace_back(k, k, 5.0);
      if (i + 1 < m) t.emplace_back(k, k + m, -1.0), t.emplace_back(k + m, k, -1.0);
      if (j + 1 < m) t.emplace_back(k, k + 1, -1.0), t.emplace_back(k + 1, k, -1.0);
    }
  SparsePattern p;
  p.matrix.resize(n, n);
  p.matrix.setFromTriplets(t.begin(), t.end());
  p.matrix.makeCompressed();
  p.version = 1;
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  Eigen::VectorXd x;
  const long before = openmp_regions_run_here();
  LinearSolve s(LinearSolverKind::cholmod);
  ASSERT_TRUE(s.factorize(p) && s.solve(b, x));
  EXPECT_LT((p.matrix * x - b).norm() / b.norm(), 1e-14);
  std::printf("[openmp regions] %ld run on the calling thread by one supernodal factorisation\n", openmp_regions_run_here() - before);
  const char* limit = std::getenv("OMP_THREAD_LIMIT");
  const char* choice = std::getenv("LOOM_OPENMP");
  if (limit && std::strcmp(limit, "1") == 0 && !(choice && std::strcmp(choice, "libgomp") == 0))
    EXPECT_GT(openmp_regions_run_here(), before) << "CHOLMOD's regions went to libgomp";
  else
    EXPECT_EQ(openmp_regions_run_here(), 0) << "a region ran here with OMP_THREAD_LIMIT=" << (limit ? limit : "(unset)");
}

}  // namespace loom
