// The time loop's sub-steps (engine/drivers/time_loop.cpp): a step cut back to 1/64 of its size is completed by
// 64 sub-steps whose summed times fall short of the step's end by round-off; that remainder must join the last
// sub-step, not run as a step of its own (a step of 1e-13 s makes Bossak's inertia term 1e26 times the mass and
// fails through every cut-back: a thin-collapse run failed so at t = 80.896 s, dt = 8e-3 s).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/drivers/time_loop.hpp"

namespace loom {
namespace {

// A step graph whose Newton "converges" only on sub-steps no longer than `limit` (to a millionth) and not
// shorter than a millionth of it; it records every sub-step's size.
struct Fixture {
  StepContext ctx;
  Timers timers;
  StepGraph graph{"test", ctx, timers};
  StepStatus status;
  std::vector<double> sizes;
  double limit = 0.0;
  int store = 0;
  Fixture() {
    graph.add_node("newton", {{}, {&store}}, [this] {
      sizes.push_back(ctx.dt);
      status.converged = ctx.dt <= limit * (1.0 + 1e-6) && ctx.dt >= 1e-6 * limit;
      status.failure = status.converged ? "" : "a sub-step of " + std::to_string(ctx.dt) + " s";
    });
    graph.build();
  }
};

TEST(TimeLoop, RoundOffLeftBySubStepsJoinsTheLastOne) {
  const double dt = 8e-3;
  int slivers = 0;
  for (int k = 0; k < 200; ++k) {
    Fixture f;
    f.limit = dt / 64.0;
    f.ctx.t = 80.888 + 0.0137 * k;  // off the step grid: the loop counts its steps from here, as on a restart
    const double t_end = f.ctx.t + dt;
    const TimeLoopResult r = run_time_loop(dt, 1, 6, f.ctx, f.graph, f.status, {}, {1, 0});
    ASSERT_TRUE(r.completed) << "start " << 80.888 + 0.0137 * k << ": " << r.failure;
    EXPECT_EQ(r.last_step_time, t_end);
    EXPECT_EQ(f.status.total_cutbacks, 6);
    for (double h : f.sizes) slivers += h < 1e-6 * f.limit;
  }
  EXPECT_EQ(slivers, 0);
}

TEST(TimeLoop, CutBackSubStepsCompleteTheStepAtItsEnd) {
  Fixture f;
  f.limit = 0.4;
  const TimeLoopResult r = run_time_loop(1.0, 1, 2, f.ctx, f.graph, f.status, {}, {1, 0});
  ASSERT_TRUE(r.completed) << r.failure;
  EXPECT_EQ(r.last_step_time, 1.0);
  // 1.0 fails, 0.5 fails, then 0.25 four times: the halving stays at the size that converged.
  EXPECT_EQ(f.sizes, (std::vector<double>{1.0, 0.5, 0.25, 0.25, 0.25, 0.25}));
}

// Adaptive steps summed from t = 0 miss time.end by round-off: 25 steps of 0.3 s sum to 7.499999999999997, of 0.7
// s to 17.499999999999993 (short), of 4e-3 s to 0.10000000000000006 (past it). The run must end at time.end in its
// 25th step, not add a sliver step of 1e-15 s (which the fixture, like Bossak's 1 / dt^2, fails).
TEST(TimeLoop, AdaptiveStepsEndAtTimeEndWithoutASliver) {
  int short_of_end = 0;  // cases whose summed steps fall short (so that the test tests the join)
  for (const double step : {0.3, 0.7, 4e-3}) {
    SCOPED_TRACE(step);
    Fixture f;
    f.limit = step;
    const int n = 25;
    double summed = 0.0;
    for (int k = 0; k < n; ++k) summed += step;
    const double end = n * step;
    short_of_end += summed < end;
    TimeLoopCallbacks callbacks;
    callbacks.step_size = [step](const StepContext&) { return step; };
    callbacks.end_time = end;
    const TimeLoopResult r = run_time_loop(step, 2 * n, 0, f.ctx, f.graph, f.status, callbacks, {1, 0});
    ASSERT_TRUE(r.completed) << r.failure;
    EXPECT_EQ(r.last_converged_step, n);
    EXPECT_EQ(r.last_step_time, end);
    EXPECT_EQ(f.sizes.size(), std::size_t(n));
  }
  EXPECT_EQ(short_of_end, 2);
}

// A step whose status says that a shorter step solves the same problem (a static step under constant loads) is not
// cut back: the loop stops at once, says why, and counts no cut-back.
struct SameProblem {
  StepContext ctx;
  Timers timers;
  StepGraph graph{"test", ctx, timers};
  StepStatus status;
  std::vector<double> sizes;
  int store = 0;
  SameProblem() {
    graph.add_node("newton", {{}, {&store}}, [this] {
      sizes.push_back(ctx.dt);
      status.converged = false;
      status.failure = "no convergence";
      status.shorter_step_helps = false;
    });
    graph.build();
  }
};

TEST(TimeLoop, NoCutBackWhereAShorterStepSolvesTheSameProblem) {
  SameProblem f;
  const TimeLoopResult r = run_time_loop(1.0, 3, 5, f.ctx, f.graph, f.status, {}, {1, 0});
  EXPECT_FALSE(r.completed);
  EXPECT_TRUE(r.no_cut_back);
  EXPECT_EQ(r.failed_step, 1);
  EXPECT_EQ(f.sizes, std::vector<double>{1.0});
  EXPECT_EQ(f.status.total_cutbacks, 0);
  EXPECT_NE(r.failure.find("no convergence; no cut-back was tried: a shorter step solves the same problem here"), std::string::npos) << r.failure;
}

}  // namespace
}  // namespace loom
