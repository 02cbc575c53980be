// CHOLMOD on the two halves of a bisection, factorised concurrently and joined through the separator's
// Schur complement (substructuring). Debian packages no shared-memory parallel sparse Cholesky (MUMPS-seq has no
// OpenMP, SuperLU_DIST and PETSc are MPI), and on 2D meshes CHOLMOD's supernodal fronts are too small for its
// BLAS threads to pay (perf/compare/README.md): the two halves of the top of a nested dissection are the
// parallelism a two-core machine can use.
//
// With the dofs ordered [half 0 | half 1 | separator s], A = [A00 0 A0s; 0 A11 A1s; As0 As1 Ass], and
//   S = Ass - sum_h Ash Ahh^-1 Ahs,   x_s = S^-1 (b_s - sum_h Ash Ahh^-1 b_h),   x_h = Ahh^-1 (b_h - Ahs x_s).
// Ahs is non-zero only in the rows of half h's interface T (its dofs coupled to the separator). Each half is
// ordered with T last (AMD on the interior, then T), so its factor ends with the dense block
// L_TT, and L_TT L_TT^T is the Schur complement of the interior onto T: Ash Ahh^-1 Ahs = W^T W with
// W = L_TT^-1 A_Ts, a triangular solve of size |T| instead of |T| solves with the whole factor.
// The split is the same for every thread count (the halves run as two tasks; the one METIS call, the bisection,
// runs alone: METIS shares the C library's rand() state), so results do not depend on the thread count, bit for
// bit; they differ from the unsplit CHOLMOD in round-off.
#include "engine/linalg/bisected_cholesky.hpp"

#include "engine/linalg/cholmod_lower.hpp"

#include <oneapi/tbb/parallel_invoke.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace loom {
namespace {

using Csc = CholmodCsc;

// One half: its dofs in the factor's order (interior by AMD, then the interface T in the matrix's order), the lower
// triangle of its block in that order, its factor, the coupling A_Ts.
struct Half {
  std::vector<int> dofs;
  int n_interface = 0;
  Csc H;
  cholmod_common c{};
  cholmod_factor* L = nullptr;
  cholmod_dense *B = nullptr, *Z = nullptr, *X = nullptr, *Y = nullptr, *E = nullptr;
  Eigen::MatrixXd Ats;  // |T| x |s|
  std::vector<std::array<int, 3>> ats_source;  // (source, row in T, column in s)
  Eigen::MatrixXd Ltt;                         // the factor's trailing |T| x |T| block (lower)
  Eigen::MatrixXd W;                           // L_TT^-1 A_Ts
  Half() { cholmod_start(&c), set_relaxed_supernodes(c); }
  Half(const Half&) = delete;
  Half& operator=(const Half&) = delete;
  ~Half() { release(); cholmod_finish(&c); }
  void release() {
    cholmod_free_factor(&L, &c);
    for (cholmod_dense** d : {&B, &Z, &X, &Y, &E}) cholmod_free_dense(d, &c);
  }
  int size() const { return int(dofs.size()); }
};

class BisectedCholesky final : public LinearSolver {
 public:
  const char* name() const override { return "cholmod_bisected"; }

  void analyze(const SparseMatrix& A) override {
    const int n = int(A.rows());
    // 1. The bisection: METIS's node separator of A's graph (CHOLMOD's Partition module).
    std::vector<int> part(std::size_t(n), 0);
    {
      cholmod_common c{};
      cholmod_start(&c);
      c.print = 0;
      cholmod_sparse a{};
      a.nrow = a.ncol = std::size_t(n), a.nzmax = std::size_t(A.nonZeros());
      a.p = const_cast<int*>(A.outerIndexPtr()), a.i = const_cast<int*>(A.innerIndexPtr()), a.x = nullptr;
      a.stype = 1, a.itype = CHOLMOD_INT, a.xtype = CHOLMOD_PATTERN, a.dtype = CHOLMOD_DOUBLE, a.sorted = 1, a.packed = 1;
      if (n > 1) cholmod_bisect(&a, nullptr, 0, 1, part.data(), &c);
      const bool ok = c.status == CHOLMOD_OK;
      cholmod_finish(&c);
      if (!ok) std::fill(part.begin(), part.end(), 0);  // one "half": the whole matrix, no separator
    }
    // 2. Interfaces: dofs of a half coupled to the separator.
    std::vector<char> interface(std::size_t(n), 0);
    for (int j = 0; j < n; ++j)
      if (part[std::size_t(j)] == 2)
        for (SparseMatrix::InnerIterator it(A, j); it; ++it)
          if (part[std::size_t(it.row())] != 2) interface[std::size_t(it.row())] = 1;
    separator_.clear();
    local_.assign(std::size_t(n), -1);
    for (auto& h : halves_) h.release(), h.dofs.clear(), h.ats_source.clear(), h.n_interface = 0;
    for (int pass = 0; pass < 2; ++pass)  // interior dofs first, then the interface
      for (int g = 0; g < n; ++g) {
        const int ph = part[std::size_t(g)];
        if (ph == 2 || interface[std::size_t(g)] != pass) continue;
        Half& h = halves_[std::size_t(ph)];
        local_[std::size_t(g)] = int(h.dofs.size());
        h.dofs.push_back(g);
        if (pass == 1) ++h.n_interface;
      }
    for (int g = 0; g < n; ++g)
      if (part[std::size_t(g)] == 2) local_[std::size_t(g)] = int(separator_.size()), separator_.push_back(g);
    const int k = int(separator_.size());
    part_ = std::move(part);
    // 3. The separator's own block and its couplings to the halves, from the separator's columns.
    ass_source_.clear();
    for (int lj = 0; lj < k; ++lj)
      for (SparseMatrix::InnerIterator it(A, separator_[std::size_t(lj)]); it; ++it) {
        const int i = int(it.row()), pi = part_[std::size_t(i)], li = local_[std::size_t(i)];
        const int src = int(&it.value() - A.valuePtr());
        if (pi == 2) ass_source_.push_back({src, li, lj});
        else {
          Half& h = halves_[std::size_t(pi)];
          h.ats_source.push_back({src, li - (h.size() - h.n_interface), lj});
        }
      }
    // 4. Each half ordered and analysed, the two at once.
    tbb::parallel_invoke([&] { analyze_half(halves_[0], 0, A, part_, local_, k); },
                         [&] { analyze_half(halves_[1], 1, A, part_, local_, k); });
  }

  bool factorize(const SparseMatrix& A) override {
    const double* a = A.valuePtr();
    const int k = int(separator_.size());
    bool ok[2] = {true, true};
    auto run = [&](int s) {
      Half& h = halves_[std::size_t(s)];
      if (h.size() == 0) return;
      h.H.gather(A);
      cholmod_sparse view = h.H.view(h.size(), -1);
      cholmod_factorize(&view, h.L, &h.c);  // natural order, lower triangle: CHOLMOD factorises it as it is
      if (h.c.status < CHOLMOD_OK || h.L->minor < h.L->n) return void(ok[s] = false);  // not positive definite
      h.Ats.setZero();
      for (const auto& [src, r, col] : h.ats_source) h.Ats(r, col) = a[src];
      h.Ltt = trailing_block(h);
      h.W = h.Ats;
      if (h.n_interface > 0 && k > 0) h.Ltt.triangularView<Eigen::Lower>().solveInPlace(h.W);
    };
    tbb::parallel_invoke([&] { run(0); }, [&] { run(1); });
    if (!ok[0] || !ok[1]) return false;
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(k, k);
    for (const auto& [src, r, col] : ass_source_) S(r, col) = a[src];
    for (auto& h : halves_)
      if (h.size() > 0 && h.n_interface > 0) S.noalias() -= h.W.transpose() * h.W;
    schur_.compute(S);
    if (k > 0 && schur_.info() != Eigen::Success) return false;
    return true;
  }

  // Per half one forward and one backward sweep, as an unsplit solve: in the factor's order (T last),
  // z = L^-1 b_h; the interface part of y_h = A_hh^-1 b_h is y_T = L_TT^-T z_T; with x_s known, the forward
  // sweep of b_h - A_hs x_s only changes z_T by -L_TT^-1 A_Ts x_s; then x_h = L^-T z.
  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    const int k = int(separator_.size());
    x.resize(b.size());
    bool ok[2] = {true, true};
    Eigen::VectorXd part_rs[2] = {Eigen::VectorXd::Zero(k), Eigen::VectorXd::Zero(k)};
    auto forward = [&](int s) {
      Half& h = halves_[std::size_t(s)];
      if (h.size() == 0) return;
      double* hb = static_cast<double*>(h.B->x);
      for (int l = 0; l < h.size(); ++l) hb[l] = b[h.dofs[std::size_t(l)]];
      if (!cholmod_solve2(CHOLMOD_L, h.L, h.B, nullptr, &h.Z, nullptr, &h.Y, &h.E, &h.c))
        return void(ok[s] = false);
      if (k == 0 || h.n_interface == 0) return;
      const auto zt = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(h.Z->x) + (h.size() - h.n_interface), h.n_interface);
      const Eigen::VectorXd yt = h.Ltt.transpose().triangularView<Eigen::Upper>().solve(zt);
      part_rs[s].noalias() = h.Ats.transpose() * yt;
    };
    tbb::parallel_invoke([&] { forward(0); }, [&] { forward(1); });
    if (!ok[0] || !ok[1]) return false;
    Eigen::VectorXd xs;
    if (k > 0) {
      Eigen::VectorXd rs(k);
      for (int q = 0; q < k; ++q) rs[q] = b[separator_[std::size_t(q)]];
      xs = schur_.solve(rs - part_rs[0] - part_rs[1]);
      for (int q = 0; q < k; ++q) x[separator_[std::size_t(q)]] = xs[q];
    }
    auto backward = [&](int s) {
      Half& h = halves_[std::size_t(s)];
      if (h.size() == 0) return;
      if (k > 0 && h.n_interface > 0)
        Eigen::Map<Eigen::VectorXd>(static_cast<double*>(h.Z->x) + (h.size() - h.n_interface), h.n_interface).noalias() -= h.W * xs;
      if (!cholmod_solve2(CHOLMOD_Lt, h.L, h.Z, nullptr, &h.X, nullptr, &h.Y, &h.E, &h.c))
        return void(ok[s] = false);
      const double* xh = static_cast<const double*>(h.X->x);
      for (int l = 0; l < h.size(); ++l) x[h.dofs[std::size_t(l)]] = xh[l];
    };
    tbb::parallel_invoke([&] { backward(0); }, [&] { backward(1); });
    return ok[0] && ok[1];
  }

  double rcond() override {
    double r = 1.0;
    for (auto& h : halves_)
      if (h.size() > 0) r = std::min(r, cholmod_rcond(h.L, &h.c));
    if (!separator_.empty()) {
      const Eigen::VectorXd d = Eigen::MatrixXd(schur_.matrixL()).diagonal();
      r = std::min(r, std::pow(d.minCoeff() / d.maxCoeff(), 2));
    }
    return r;
  }

  FactorSize factor_size() override {
    const double k = double(separator_.size());
    FactorSize f{k * (k + 1) / 2, k * k * k / 3};
    for (auto& h : halves_)
      if (h.size() > 0) f.entries += h.c.lnz, f.flops += h.c.fl + double(h.n_interface) * h.n_interface * k + 2.0 * h.n_interface * k * k;
    return f;
  }

  // For tests: the sizes of the halves and of the separator.
  std::array<int, 3> split() const { return {halves_[0].size(), halves_[1].size(), int(separator_.size())}; }

 private:
  // AMD on the half's interior, then T as is. Not nested dissection, though it fills less (the cantilever at 10^5
  // particles: halves of 2.5 + 2.4e8 flops against AMD's 2.8 + 3.7e8, the whole 4.6e8): Debian's METIS draws
  // from the C library's single rand() state, so two orderings at once interleave their draws as the scheduler
  // chooses and the round-off changes from run to run, and one after the other they took 200 ms of an analysis
  // against AMD's 48 ms; with 23 analyses in its 120 steps the cantilever ran 15 % faster on two threads with AMD.
  // Between the two (tried 2026-11-29, 10^5 particles, 2 threads, 3 alternated runs of 120 steps): one or two more
  // METIS bisections of each half (alone), then CAMD with the separators as constraint sets, cut the larger half
  // to 2.9-3.4e8 flops and (two levels) the numeric factorisation by up to 9 %, but each level adds 20-25 ms of
  // serial METIS to every analysis, and the run was no faster (16.7-17.1 s against 17.0-17.6 s with AMD).
  // Breadth-first level structures instead of METIS (George's automatic nested dissection: deterministic, so it
  // could run in the two tasks) filled twice as much (7e8 flops a half): the ghost-penalty couplings thicken the
  // levels and near-square parts are cut along L-shaped levels.
  // The half's block is then stored permuted, as the lower triangle in the factor's order, and analysed in its
  // natural order: CHOLMOD factorises such a matrix as it is, where for a permuted one it would build
  // tril(P A P^T) by a transpose at every factorisation (3.8 % of a cantilever step at 10^5 particles).
  static void analyze_half(Half& h, int side, const SparseMatrix& A, const std::vector<int>& part, const std::vector<int>& local, int k) {
    const int nh = h.size(), ni = nh - h.n_interface;
    h.H.x.clear(), h.H.i.clear(), h.H.source.clear(), h.H.p.assign(1, 0);
    h.Ats = Eigen::MatrixXd::Zero(h.n_interface, k);
    if (nh == 0) return;
    // Rows of the half's block in column g: (local index, position of the value in A).
    auto for_each_in_block = [&](int g, auto&& f) {
      for (SparseMatrix::InnerIterator it(A, g); it; ++it)
        if (part[std::size_t(it.row())] == side) f(local[std::size_t(it.row())], int(&it.value() - A.valuePtr()));
    };
    std::vector<int> perm(static_cast<std::size_t>(nh));
    for (int l = 0; l < nh; ++l) perm[std::size_t(l)] = l;
    if (ni > 1) {
      Csc interior;  // upper triangle of the interior block, pattern only
      interior.p.assign(1, 0);
      std::vector<int> rows;
      for (int lj = 0; lj < ni; ++lj) {
        rows.clear();
        for_each_in_block(h.dofs[std::size_t(lj)], [&](int li, int) {
          if (li <= lj) rows.push_back(li);
        });
        std::sort(rows.begin(), rows.end());
        interior.i.insert(interior.i.end(), rows.begin(), rows.end());
        interior.p.push_back(int(interior.i.size()));
      }
      cholmod_sparse view = interior.view(ni, 1);
      view.xtype = CHOLMOD_PATTERN, view.x = nullptr;
      // Only the postordered AMD permutation is read: the simplicial analysis skips the supernodal pattern, which
      // the half's own analysis below builds.
      h.c.nmethods = 1, h.c.method[0].ordering = CHOLMOD_AMD, h.c.postorder = 1, h.c.supernodal = CHOLMOD_SIMPLICIAL;
      cholmod_factor* Li = cholmod_analyze(&view, &h.c);
      h.c.supernodal = CHOLMOD_SUPERNODAL;
      if (!Li) throw std::runtime_error("cholmod_bisected: the ordering of a half failed");
      const int* p = static_cast<const int*>(Li->Perm);
      std::copy(p, p + ni, perm.begin());
      cholmod_free_factor(&Li, &h.c);
    }
    std::vector<int> dofs(static_cast<std::size_t>(nh)), position(static_cast<std::size_t>(nh));
    for (int q = 0; q < nh; ++q) dofs[std::size_t(q)] = h.dofs[std::size_t(perm[std::size_t(q)])], position[std::size_t(perm[std::size_t(q)])] = q;
    build_permuted_lower(A, nh, [&](int g) { return part[std::size_t(g)] == side ? position[std::size_t(local[std::size_t(g)])] : -1; }, h.H);
    h.dofs = std::move(dofs);
    h.c.nmethods = 1, h.c.method[0].ordering = CHOLMOD_NATURAL, h.c.postorder = 0;
    cholmod_sparse view = h.H.view(nh, -1);
    h.L = cholmod_analyze(&view, &h.c);
    if (!h.L) throw std::runtime_error("cholmod_bisected: the symbolic analysis of a half failed");
    h.B = cholmod_allocate_dense(std::size_t(nh), 1, std::size_t(nh), CHOLMOD_REAL, &h.c);
  }

  // L_TT: the last |T| columns of the supernodal factor, lower triangle, dense.
  static Eigen::MatrixXd trailing_block(const Half& h) {
    const int nh = h.size(), t = h.n_interface, off = nh - t;
    Eigen::MatrixXd Ltt = Eigen::MatrixXd::Zero(t, t);
    const cholmod_factor* L = h.L;
    const int *super = static_cast<const int*>(L->super), *pi = static_cast<const int*>(L->pi), *px = static_cast<const int*>(L->px);
    const int* Ls = static_cast<const int*>(L->s);
    const double* Lx = static_cast<const double*>(L->x);
    for (std::size_t s = 0; s < L->nsuper; ++s) {
      const int k1 = super[s], k2 = super[s + 1];
      if (k2 <= off) continue;
      const int nsrow = pi[s + 1] - pi[s];
      for (int j = std::max(k1, off); j < k2; ++j)
        for (int r = j - k1; r < nsrow; ++r) Ltt(Ls[pi[s] + r] - off, j - off) = Lx[std::size_t(px[s]) + std::size_t(j - k1) * nsrow + r];
    }
    return Ltt;
  }

  std::array<Half, 2> halves_;
  std::vector<int> part_, local_, separator_;
  std::vector<std::array<int, 3>> ass_source_;
  Eigen::LLT<Eigen::MatrixXd> schur_;
};

}  // namespace

std::unique_ptr<LinearSolver> make_bisected_cholmod_solver() { return std::make_unique<BisectedCholesky>(); }

std::array<int, 3> bisected_cholmod_split(LinearSolver& solver) {
  auto* s = dynamic_cast<BisectedCholesky*>(&solver);
  return s ? s->split() : std::array<int, 3>{0, 0, 0};
}

}  // namespace loom
