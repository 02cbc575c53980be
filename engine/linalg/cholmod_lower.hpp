// A block of loom's sparse matrix, stored as CHOLMOD factorises it fastest: the lower triangle, permuted into
// the factor's order, in CHOLMOD's int CSC layout, each value gathered from its slot in the source matrix. Given
// a permuted matrix in natural order, cholmod_factorize takes it as it is; given the unpermuted matrix and the
// ordering, it would build tril(P A P^T) by a transpose at every factorisation (5 % of an MPM cantilever step at
// 10^4 particles, 3.8 % at 10^5). Used by the CHOLMOD back-ends (linear_solver.cpp, bisected_cholesky.cpp).
#pragma once

#include <cholmod.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "engine/linalg/sparse_pattern.hpp"

namespace loom {

// A CSC matrix in CHOLMOD's int layout, one triangle (stype 1 upper, -1 lower), whose values are gathered from A.
struct CholmodCsc {
  std::vector<int> p, i;
  std::vector<double> x;
  std::vector<int> source;  // x[k] = A.valuePtr()[source[k]]
  cholmod_sparse view(int n, int stype) {
    cholmod_sparse s{};
    s.nrow = s.ncol = std::size_t(n);
    s.nzmax = i.size();
    s.p = p.data(), s.i = i.data(), s.x = x.data();
    s.stype = stype, s.itype = CHOLMOD_INT, s.xtype = CHOLMOD_REAL, s.dtype = CHOLMOD_DOUBLE;
    s.sorted = 1, s.packed = 1;
    return s;
  }
  void gather(const SparseMatrix& A) {
    const double* a = A.valuePtr();
    for (std::size_t k = 0; k < x.size(); ++k) x[k] = a[source[k]];
  }
};

// Supernode amalgamation twice as relaxed as CHOLMOD's defaults (nrelax 4, 16, 48; zrelax 0.8, 0.1, 0.05): the
// supernodes of 2D meshes are small, and larger ones with a few explicit zeros run the dense kernels better.
// Numeric factorisation 13-21 % faster on the MPM cantilever (10^4-10^5 particles) and Cook's membrane at 10^5
// cells, unchanged on small meshes (perf/compare/README.md).
inline void set_relaxed_supernodes(cholmod_common& c) {
  c.print = 0;  // failures are reported by loom, not printed by CHOLMOD
  c.nrelax[0] = 8, c.nrelax[1] = 32, c.nrelax[2] = 96;
  c.zrelax[0] = 0.8, c.zrelax[1] = 0.2, c.zrelax[2] = 0.1;
  c.supernodal = CHOLMOD_SUPERNODAL;
}

// The lower triangle of a block of A, rows sorted: position(g) is the block's index of A's dof g, or -1 for a dof
// outside it. Each value comes from A's upper triangle, which is what CHOLMOD reads of a matrix of stype 1: where A
// is not symmetric (an unsymmetric tangent given to an SPD back-end) the block holds what CHOLMOD was given before.
template <class Position>
void build_permuted_lower(const SparseMatrix& A, int n_block, Position&& position, CholmodCsc& H) {
  std::vector<int> count(std::size_t(n_block) + 1, 0);
  auto for_each_upper = [&](auto&& f) {  // f(column, row) in the block, for each entry of A's upper triangle in it
    for (int c = 0; c < A.outerSize(); ++c) {
      const int pc = position(c);
      if (pc < 0) continue;
      for (SparseMatrix::InnerIterator it(A, c); it; ++it) {
        const int pr = it.row() <= c ? position(int(it.row())) : -1;
        if (pr >= 0) f(std::min(pr, pc), std::max(pr, pc), int(&it.value() - A.valuePtr()));
      }
    }
  };
  for_each_upper([&](int col, int, int) { ++count[std::size_t(col) + 1]; });
  for (int q = 0; q < n_block; ++q) count[std::size_t(q) + 1] += count[std::size_t(q)];
  H.p = count;
  std::vector<std::pair<int, int>> entries(std::size_t(count.back()));  // (row, slot in A), by column
  for_each_upper([&](int col, int row, int src) { entries[std::size_t(count[std::size_t(col)]++)] = {row, src}; });
  H.i.resize(entries.size()), H.source.resize(entries.size());
  for (int q = 0; q < n_block; ++q) {
    const auto first = entries.begin() + H.p[std::size_t(q)], last = entries.begin() + H.p[std::size_t(q) + 1];
    std::sort(first, last);
    for (auto e = first; e != last; ++e) H.i[std::size_t(e - entries.begin())] = e->first, H.source[std::size_t(e - entries.begin())] = e->second;
  }
  H.x.assign(H.i.size(), 0.0);
}

}  // namespace loom
