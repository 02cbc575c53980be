// Assembly of the P1 Neo-Hooke Newton system (systems/assemble/assemble_system) on Cook's membrane,
// 1024 to 131072 cells, residual only and residual + tangent, with 1 and 2 oneTBB threads.
// Arguments: /<cells>/<threads>. items_per_second is cells per second.
//
// assemble_system has no serial switch; its serial reference is the 1-thread run (the same code on one
// oneTBB worker), and the 2-thread speed-up is the ratio of the two.
//
// Diagnostics (one thread), to tell where the time of a cell goes:
//  BM_CellLoop/<rung>/<cells>/1: the cell loop of assemble_system re-written here for the static P1
//    Neo-Hooke case (gather_p1_cell + p1_internal + the scatter into the CSR values), checked against
//    assemble_system at set-up (same matrix and internal forces to round-off). Rungs, each adding one
//    thing: residual_{natural,colour}; tangent_kernel_natural (no scatter), tangent_natural (mesh
//    order), tangent_colour (by_colour order, as assemble_system), tangent_colour_helper (each colour
//    through for_each_in, oneTBB on 1 thread), tangent_colour_helper_kind (plus the per-cell prescribed
//    dof look-up of the Dirichlet gap). BM_Assemble/tangent/<cells>/1 is the whole system.
//  BM_NeoHooke/<call>/<points>: the material alone on the F of the run's quadrature points: stress,
//    stress_tangent (the full 9x9 A) and, for comparison, an in-plane variant here that computes only
//    the 16 entries A_ijkl, i,j,k,l < 2, that the plane-strain kernel reads.
//
//   build-perf/perf/bench_assemble --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <oneapi/tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>
#include <vector>

#include "engine/core/parallel.hpp"
#include "perf/fem_bench_setup.hpp"
#include "systems/assemble/assemble_system.hpp"
#include "systems/assemble/elements/p1_cell.hpp"

namespace {

using loom::AssemblyMode;
using loom::Index;
using loom::perf::FemBenchRun;

// One run per size, shared by the benchmarks of that size (building the pattern of 131072 cells takes
// longer than measuring it).
FemBenchRun& run_of(Index n_cells) {
  static std::map<Index, std::unique_ptr<FemBenchRun>> runs;
  auto& r = runs[n_cells];
  if (!r) r = std::make_unique<FemBenchRun>(n_cells);
  return *r;
}

void BM_Assemble(benchmark::State& state, AssemblyMode mode) {
  const Index n_cells = Index(state.range(0));
  const int threads = int(state.range(1));
  oneapi::tbb::global_control limit(oneapi::tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  FemBenchRun& run = run_of(n_cells);
  if (run.n_cells() != n_cells) {
    state.SkipWithError("the mesh does not have the requested number of cells");
    return;
  }
  Index inverted = 0;
  for (auto _ : state) {
    inverted += loom::assemble_system(run.ctx, mode, run.materials, run.nodes, run.cells, run.bc, run.quad, run.system)
                    .inverted_cells;
    benchmark::DoNotOptimize(run.system.residual.data());
    benchmark::ClobberMemory();
  }
  if (inverted != 0) state.SkipWithError("inverted cells: the kernel skipped work");
  state.SetItemsProcessed(state.iterations() * n_cells);
  state.counters["cells"] = double(n_cells);
  state.counters["colours"] = double(run.cells[0].n_colours());
}

// Cells 2^10 .. 2^17 (the ctest smoke run filters /1024/), threads 1 and 2.
void sizes(benchmark::internal::Benchmark* b) {
  b->RangeMultiplier(2)->Ranges({{1 << 10, 1 << 17}, {1, 2}})->UseRealTime()->Unit(benchmark::kMicrosecond);
}

BENCHMARK_CAPTURE(BM_Assemble, residual, AssemblyMode::residual)->Apply(sizes);
BENCHMARK_CAPTURE(BM_Assemble, tangent, AssemblyMode::residual_and_tangent)->Apply(sizes);

// ---- Diagnostics -------------------------------------------------------------------------------------

// What the re-written loop does: residual or tangent, scatter or not, cell order, and which of
// assemble_system's per-cell extras it adds.
struct Loop {
  bool tangent = true;
  bool scatter = true;          // false: the kernel's result is dropped (gather + kernel only)
  bool colour_order = true;     // cells in by_colour order (as assemble_system), else 0..n-1
  bool helper = false;          // each colour through engine/core/parallel.hpp's for_each_in (oneTBB, 1 thread)
  bool dof_kind_check = false;  // the per-cell look-up of prescribed dofs for the Dirichlet gap
};

// The P1 cell loop of assemble_system for the static case (no inertia, no prescribed dof lagging).
void cell_loop(FemBenchRun& run, const Loop& loop) {
  const loom::Cells& cells = run.cells[0];
  loom::QuadPoints<2>& quad = run.quad[0];
  const loom::CellScatter& sc = run.system.scatter[0];
  const auto& material = std::get<loom::NeoHooke>(run.materials[0].model);
  auto& A = run.system.pattern.matrix;
  double* values = A.valuePtr();
  if (loop.tangent && loop.scatter) std::fill(values, values + A.nonZeros(), 0.0);
  run.system.residual_full.setZero();
  loom::P1Vector sink = loom::P1Vector::Zero();
  auto body = [&](Index c) {
    if (loop.dof_kind_check) {  // as assemble_system: the gap of the cell's prescribed dofs
      bool lagging = false;
      for (int a = 0; a < 6; ++a) {
        const Index dof = sc.cell_dof(c, a);
        if (run.system.dofs.kind[std::size_t(dof)] != loom::DofKind::prescribed) continue;
        lagging = lagging || run.bc.target[dof] != run.nodes.u[dof / 2][dof % 2];
      }
      if (lagging) throw std::logic_error("the diagnostic loop assumes no lagging prescribed dof");
    }
    const loom::P1Cell cell = loom::gather_p1_cell(run.nodes, cells, quad, c);
    loom::P1Vector r = loom::P1Vector::Zero();
    loom::P1Matrix K = loom::P1Matrix::Zero();
    loom::p1_internal(material, cell, quad.F[c], r, loop.tangent ? &K : nullptr);
    if (!loop.scatter) {
      sink += r + K.col(0);
      return;
    }
    for (int a = 0; a < 6; ++a) run.system.residual_full[sc.cell_dof(c, a)] += r[a];
    if (loop.tangent)
      for (int a = 0; a < 6; ++a)
        for (int b = 0; b < 6; ++b) {
          const Index s = sc.matrix_slot(c, a, b);
          if (s != loom::kNoIndex) values[s] += K(a, b);
        }
  };
  if (!loop.colour_order) {
    for (Index c = 0; c < cells.size(); ++c) body(c);
  } else {
    for (Index k = 0; k < cells.n_colours(); ++k) {
      const Index begin = cells.colour_offsets[std::size_t(k)], end = cells.colour_offsets[std::size_t(k) + 1];
      if (loop.helper)
        loom::for_each_in(cells.by_colour.data() + begin, end - begin, body);
      else
        for (Index i = begin; i < end; ++i) body(cells.by_colour[std::size_t(i)]);
    }
  }
  benchmark::DoNotOptimize(sink.data());
}

// |a - b|_inf / |b|_inf
double relative_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).lpNorm<Eigen::Infinity>() / b.lpNorm<Eigen::Infinity>();
}

// The re-written loop must reproduce assemble_system (which also subtracts the external forces).
bool matches_assemble_system(FemBenchRun& run) {
  loom::assemble_system(run.ctx, AssemblyMode::residual_and_tangent, run.materials, run.nodes, run.cells, run.bc,
                        run.quad, run.system);
  const auto& A = run.system.pattern.matrix;
  const Eigen::VectorXd K_ref = Eigen::Map<const Eigen::VectorXd>(A.valuePtr(), A.nonZeros());
  const Eigen::VectorXd f_ref = run.system.residual_full + run.bc.external;
  cell_loop(run, Loop{.colour_order = false});
  const Eigen::VectorXd K = Eigen::Map<const Eigen::VectorXd>(A.valuePtr(), A.nonZeros());
  return relative_difference(K, K_ref) < 1e-12 && relative_difference(run.system.residual_full, f_ref) < 1e-12;
}

void BM_CellLoop(benchmark::State& state, Loop loop) {
  const Index n_cells = Index(state.range(0));
  oneapi::tbb::global_control limit(oneapi::tbb::global_control::max_allowed_parallelism, 1);
  FemBenchRun& run = run_of(n_cells);
  if (!matches_assemble_system(run)) {
    state.SkipWithError("the re-written cell loop does not reproduce assemble_system");
    return;
  }
  for (auto _ : state) {
    cell_loop(run, loop);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n_cells);
}

// Same sizes as BM_Assemble, one thread (the trailing /1 keeps the smoke filter /1024/ matching).
void serial_sizes(benchmark::internal::Benchmark* b) {
  b->RangeMultiplier(2)->Ranges({{1 << 10, 1 << 17}, {1, 1}})->UseRealTime()->Unit(benchmark::kMicrosecond);
}

// The ladder from the bare kernel to assemble_system's loop; BM_Assemble/tangent/<n>/1 is the last rung.
BENCHMARK_CAPTURE(BM_CellLoop, residual_natural, Loop{.tangent = false, .colour_order = false})->Apply(serial_sizes);
BENCHMARK_CAPTURE(BM_CellLoop, residual_colour, Loop{.tangent = false})->Apply(serial_sizes);
BENCHMARK_CAPTURE(BM_CellLoop, tangent_kernel_natural, Loop{.scatter = false, .colour_order = false})
    ->Apply(serial_sizes);
BENCHMARK_CAPTURE(BM_CellLoop, tangent_natural, Loop{.colour_order = false})->Apply(serial_sizes);
BENCHMARK_CAPTURE(BM_CellLoop, tangent_colour, Loop{})->Apply(serial_sizes);
BENCHMARK_CAPTURE(BM_CellLoop, tangent_colour_helper, Loop{.helper = true})->Apply(serial_sizes);
BENCHMARK_CAPTURE(BM_CellLoop, tangent_colour_helper_kind, Loop{.helper = true, .dof_kind_check = true})
    ->Apply(serial_sizes);

// The 16 in-plane entries of the Neo-Hooke A_ijkl (same formula as NeoHooke::stress_tangent).
bool stress_tangent_in_plane(const loom::NeoHooke& m, const loom::Mat3& F, loom::Mat3& P, double (&A)[2][2][2][2]) {
  const double J = F.determinant();
  if (!(J > 0.0)) return false;
  const loom::Mat3 Finv = F.inverse();
  const double c = m.lambda * std::log(J) - m.mu;
  P = m.mu * F + c * Finv.transpose();
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k)
        for (int l = 0; l < 2; ++l)
          A[i][j][k][l] =
              m.lambda * Finv(j, i) * Finv(l, k) - c * Finv(j, k) * Finv(l, i) + (i == k && j == l ? m.mu : 0.0);
  return true;
}

enum class MaterialCall { stress, stress_tangent, stress_tangent_in_plane };

void BM_NeoHooke(benchmark::State& state, MaterialCall call) {
  const Index n = Index(state.range(0));
  FemBenchRun& run = run_of(1 << 10);
  const auto& material = std::get<loom::NeoHooke>(run.materials[0].model);
  std::vector<loom::Mat3> F(static_cast<std::size_t>(n));
  for (Index q = 0; q < n; ++q) F[std::size_t(q)] = run.quad[0].F[q % run.quad[0].size()];
  loom::Mat3 P = loom::Mat3::Zero();
  loom::Mat9 A9 = loom::Mat9::Zero();
  double A4[2][2][2][2] = {};
  for (auto _ : state) {
    for (const auto& Fq : F) {
      switch (call) {  // DoNotOptimize keeps every entry computed, as the kernel would read it
        case MaterialCall::stress:
          material.stress(Fq, P);
          break;
        case MaterialCall::stress_tangent:
          material.stress_tangent(Fq, P, A9), benchmark::DoNotOptimize(A9);
          break;
        case MaterialCall::stress_tangent_in_plane:
          stress_tangent_in_plane(material, Fq, P, A4), benchmark::DoNotOptimize(A4);
          break;
      }
      benchmark::DoNotOptimize(P);
    }
  }
  state.SetItemsProcessed(state.iterations() * n);
}

BENCHMARK_CAPTURE(BM_NeoHooke, stress, MaterialCall::stress)->Arg(1 << 10)->UseRealTime();
BENCHMARK_CAPTURE(BM_NeoHooke, stress_tangent, MaterialCall::stress_tangent)->Arg(1 << 10)->UseRealTime();
BENCHMARK_CAPTURE(BM_NeoHooke, stress_tangent_in_plane, MaterialCall::stress_tangent_in_plane)
    ->Arg(1 << 10)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
