// One timed Newton iteration (assemble with tangent, factorize, back-substitute, scatter, update) repeated from
// the same iterate: the loop shared by bench_newton_step and bench_smoothed. The phases go into counters
// (per iteration, ms); the caller adds its own (sizes, threads).
#pragma once

#include <benchmark/benchmark.h>

#include "engine/linalg/linear_solver.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/nodes.hpp"
#include "engine/timing/timers.hpp"
#include "perf/solver_threads.hpp"
#include "systems/solve/solve_linear_step.hpp"
#include "systems/update/update_iterate.hpp"

namespace loom::perf {

// restore() puts the run back at its iterate; assemble() assembles residual and tangent and returns the
// number of inverted cells. Returns false (and marks the benchmark skipped) if an iteration was not one.
template <class Restore, class Assemble>
bool time_newton_iterations(benchmark::State& state, Restore&& restore, Assemble&& assemble, Nodes<2>& nodes,
                            const BoundaryConditions<2>& bc, LinearSolve& solver, LinearSystem& system) {
  // Warm-up: symbolic analysis and first factorization (kept by the solver afterwards).
  assemble();
  const auto w0 = Clock::now();
  const bool factorized = solver.factorize(system.pattern);
  const double first_factorize = seconds(w0, Clock::now());
  if (!factorized) {
    state.SkipWithError("the tangent could not be factorized");
    return false;
  }
  Timers timers;
  double t_assemble = 0, t_solve = 0, t_update = 0;
  Index inverted = 0;
  bool singular = false;
  for (auto _ : state) {
    restore();
    const auto t0 = Clock::now();
    inverted += assemble();
    const auto t1 = Clock::now();
    singular |= solve_linear_step(nodes, bc, solver, system, timers) != LinearSolveStatus::ok;
    const auto t2 = Clock::now();
    update_iterate(1.0, system, nodes);
    const auto t3 = Clock::now();
    benchmark::DoNotOptimize(nodes.u.data());
    t_assemble += seconds(t0, t1), t_solve += seconds(t1, t2), t_update += seconds(t2, t3);
    state.SetIterationTime(seconds(t0, t3));
  }
  if (inverted != 0 || singular) {
    state.SkipWithError("inverted cells or a singular tangent: the timings are not those of a Newton iteration");
    return false;
  }
  const auto stats = timers.snapshot();
  const double t_factorize = stats.at("newton/solve/factorize").total;
  const double t_back = stats.at("newton/solve/back_substitute").total;
  const double t_scatter = t_solve - t_factorize - t_back;
  const double total = t_assemble + t_solve + t_update;
  using benchmark::Counter;
  auto per_iteration_ms = [](double s) { return Counter(1e3 * s, Counter::kAvgIterations); };
  state.counters["assemble_ms"] = per_iteration_ms(t_assemble);
  state.counters["factorize_ms"] = per_iteration_ms(t_factorize);
  state.counters["back_substitute_ms"] = per_iteration_ms(t_back);
  state.counters["scatter_ms"] = per_iteration_ms(t_scatter);
  state.counters["update_ms"] = per_iteration_ms(t_update);
  state.counters["total_ms"] = per_iteration_ms(total);
  state.counters["outside_solver"] = (t_assemble + t_scatter + t_update) / total;
  state.counters["first_factorize_ms"] = 1e3 * first_factorize;
  state.counters["dofs"] = double(system.dofs.n_free);
  state.counters["nnz"] = double(system.pattern.matrix.nonZeros());
  return true;
}

}  // namespace loom::perf
