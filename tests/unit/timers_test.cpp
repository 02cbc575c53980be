// Timers (engine/timing/timers): calls, total and max accumulate per name; the end-of-run table and
// timings.json name every timer.
#include <gtest/gtest.h>

#include <oneapi/tbb/parallel_for.h>

#include <sstream>
#include <string>
#include <thread>

#include "engine/timing/timers.hpp"

namespace loom {

TEST(Timers, CallsTotalAndMaxAccumulate) {
  Timers t;
  t.add("assemble", 1.0);
  t.add("assemble", 3.0);
  t.add("assemble", 2.0);
  t.add("solve", 0.5);
  const auto s = t.snapshot();
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.at("assemble").calls, 3);
  EXPECT_DOUBLE_EQ(s.at("assemble").total, 6.0);
  EXPECT_DOUBLE_EQ(s.at("assemble").max, 3.0);
  EXPECT_EQ(s.at("solve").calls, 1);
  t.clear();
  EXPECT_TRUE(t.snapshot().empty());
}

TEST(Timers, ConcurrentAddsAreAllCounted) {
  Timers t;
  oneapi::tbb::parallel_for(0, 1000, [&](int) { t.add("parallel", 1e-3); });
  EXPECT_EQ(t.snapshot().at("parallel").calls, 1000);
  EXPECT_NEAR(t.snapshot().at("parallel").total, 1.0, 1e-9);
}

TEST(ScopedTimer, AddsOneCallWhenItEnds) {
  Timers t;
  {
    ScopedTimer s(t, "scope");
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  const auto s = t.snapshot();
  ASSERT_TRUE(s.count("scope"));
  EXPECT_EQ(s.at("scope").calls, 1);
  EXPECT_GE(s.at("scope").total, 1e-3);
}

TEST(ScopedTimer, StopEndsTheMeasurementOnce) {
  Timers t;
  double elapsed = 0;
  {
    ScopedTimer s(t, "early");
    elapsed = s.stop();
    EXPECT_EQ(s.stop(), 0.0);
  }
  EXPECT_EQ(t.snapshot().at("early").calls, 1);
  EXPECT_DOUBLE_EQ(t.snapshot().at("early").total, elapsed);
}

TEST(Timers, TableNamesEveryTimer) {
  Timers t;
  t.add("newton", 4.0);
  t.add("newton/assemble", 1.0);
  t.add("newton/solve", 2.5);
  t.add("output", 0.5);
  t.add("output/write_vtu", 0.25);
  t.add("writer/flush", 0.125);  // a sub-timer whose parent is not timed itself
  t.add("newton/solve/factorize", 2.0);  // two levels down
  std::ostringstream os;
  t.print_table(os, 8.0);
  const std::string s = os.str();
  for (const char* name : {"newton", "assemble", "solve", "output", "write_vtu", "flush", "factorize"})
    EXPECT_NE(s.find(name), std::string::npos) << name << " missing from\n" << s;
  // Top-level rows come by total time; children below their parent.
  EXPECT_LT(s.find("newton"), s.find("output"));
  EXPECT_LT(s.find("newton"), s.find("assemble"));
  EXPECT_LT(s.find("solve"), s.find("assemble"));  // 2.5 s before 1.0 s
  EXPECT_NE(s.find("50.0%"), std::string::npos) << s;  // newton: 4 of 8 s
}

TEST(Timers, JsonNamesEveryTimerWithItsStatistics) {
  Timers t;
  t.add("newton", 4.0);
  t.add("newton", 2.0);
  t.add("newton/solve", 2.5);
  std::ostringstream os;
  t.write_json(os, 8.0);
  const std::string s = os.str();
  EXPECT_NE(s.find("\"wall\": 8"), std::string::npos) << s;
  EXPECT_NE(s.find("\"newton\": {\"calls\": 2, \"total\": 6, \"mean\": 3, \"max\": 4, \"share\": 0.75}"), std::string::npos) << s;
  EXPECT_NE(s.find("\"newton/solve\": {\"calls\": 1"), std::string::npos) << s;
  EXPECT_EQ(s.front(), '{');
  EXPECT_EQ(s[s.find_last_not_of('\n')], '}');
}

}  // namespace loom

// The profile (loom run --profile): events nested step > system > iteration > sub-phase.
namespace loom {

namespace {

using Clock = Timers::Clock;

// Records a scope of [from, to] milliseconds after `origin` under the given mark.
void scope(Timers& t, Clock::time_point origin, const std::string& name, int run, int iteration, double from, double to) {
  auto at = [&](double ms) { return origin + std::chrono::microseconds(static_cast<long long>(ms * 1000)); };
  t.add_scope(name, {run, iteration}, at(from), at(to));
}

}  // namespace

TEST(Profile, IsOffUnlessEnabled) {
  Timers t;
  EXPECT_FALSE(t.profiling());
  t.begin_graph_run(1, 1.0, 1.0);
  t.set_iteration(3);
  { ScopedTimer s(t, "newton/assemble"); }
  t.end_graph_run();
  EXPECT_TRUE(t.profile_runs().empty());
  EXPECT_TRUE(t.profile_events().empty());
  EXPECT_EQ(t.mark().iteration, -1);
  std::ostringstream os;
  t.write_json(os, 1.0);
  EXPECT_EQ(os.str().find("\"profile\""), std::string::npos) << os.str();
  EXPECT_NE(os.str().find("\"most_expensive\": [{\"name\": \"newton/assemble\""), std::string::npos) << os.str();
}

TEST(Profile, ScopesCarryTheirGraphRunAndNewtonIteration) {
  Timers t;
  t.enable_profile();
  { ScopedTimer s(t, "before"); }
  t.begin_graph_run(4, 2.0, 0.5);
  t.set_iteration(2);
  { ScopedTimer s(t, "newton/solve"); }
  t.set_iteration(-1);
  { ScopedTimer s(t, "commit"); }
  t.end_graph_run();
  const auto runs = t.profile_runs();
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0].step, 4);
  EXPECT_EQ(runs[0].dt, 0.5);
  EXPECT_GE(runs[0].seconds, 0.0);
  const auto events = t.profile_events();
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].run, -1);
  EXPECT_EQ(events[1].run, 0);
  EXPECT_EQ(events[1].iteration, 2);
  EXPECT_EQ(events[2].iteration, -1);
  EXPECT_EQ(t.snapshot().at("newton/solve").calls, 1);  // the statistics still count every scope
}

TEST(Profile, JsonNestsStepSystemIterationAndSubPhase) {
  Timers t;
  t.enable_profile();
  const auto origin = Clock::now();  // enable_profile's origin is earlier: starts only shift
  t.begin_graph_run(1, 1.0, 1.0);
  scope(t, origin, "apply_boundary_conditions", 0, -1, 0, 1);
  scope(t, origin, "newton", 0, -1, 1, 10);
  scope(t, origin, "newton/assemble", 0, 0, 1, 2);
  scope(t, origin, "newton/solve", 0, 1, 2, 5);
  scope(t, origin, "newton/solve/factorize", 0, 1, 2, 4);
  scope(t, origin, "newton/update", 0, 1, 5, 5.5);
  scope(t, origin, "newton/assemble", 0, 1, 5.5, 6);
  scope(t, origin, "newton/assemble", 0, 1, 6, 7);  // a line-search trial: merged with the one before
  scope(t, origin, "output", 0, -1, 10, 10.5);
  scope(t, origin, "output/write_vtu", 0, 1, 10.2, 30);  // the writer, still busy during the next step
  std::ostringstream os;
  t.write_json(os, 0.05);
  const std::string s = os.str();
  // One line per node; the order in the text follows the nesting.
  std::size_t at = 0;
  for (const char* node : {"\"name\": \"step 1\", \"step\": 1", "\"name\": \"apply_boundary_conditions\", \"calls\": 1",
                           "\"name\": \"newton\", \"calls\": 1", "\"name\": \"iteration 0\", \"calls\": 0",
                           "\"name\": \"assemble\", \"calls\": 1", "\"name\": \"iteration 1\", \"calls\": 0",
                           "\"name\": \"solve\", \"calls\": 1", "\"name\": \"factorize\", \"calls\": 1",
                           "\"name\": \"update\", \"calls\": 1", "\"name\": \"assemble\", \"calls\": 2",
                           "\"name\": \"output\", \"calls\": 1", "\"name\": \"output/write_vtu\", \"calls\": 1"}) {
    const auto p = s.find(node, at);
    ASSERT_NE(p, std::string::npos) << node << " missing or out of order in\n" << s;
    at = p + 1;
  }
  // Iteration 1 lasts as long as its phases: solve 3 ms + update 0.5 ms + assemble 1.5 ms.
  const auto it1 = s.find("\"name\": \"iteration 1\"");
  const auto seconds = s.find("\"seconds\": ", it1);
  EXPECT_NEAR(std::stod(s.substr(seconds + 11)), 5e-3, 1e-5) << s;
  // The writer is not nested in output (it does not fit in its time) and is marked.
  const auto writer = s.find("\"name\": \"output/write_vtu\"");
  EXPECT_NE(s.find("\"concurrent\": true", writer), std::string::npos);
  EXPECT_EQ(s.find("\"name\": \"write_vtu\""), std::string::npos) << s;
}

TEST(Profile, MostExpensiveRanksBySelfTime) {
  const auto top = most_expensive({{"newton", 10.0}, {"newton/solve", 6.0}, {"newton/assemble", 3.0}, {"output", 0.5},
                                   {"output/write_vtu", 2.0}, {"probes", 0.1}},
                                  3);
  ASSERT_EQ(top.size(), 3u);
  EXPECT_EQ(top[0].first, "newton/solve");
  EXPECT_EQ(top[1].first, "newton/assemble");
  EXPECT_EQ(top[2].first, "output/write_vtu");  // output's self time is clamped at 0, newton's is 1
  EXPECT_DOUBLE_EQ(top[0].second, 6.0);
}

TEST(Timers, TableEndsWithTheThreeMostExpensive) {
  Timers t;
  t.add("newton", 4.0);
  t.add("newton/solve", 2.5);
  t.add("newton/assemble", 1.0);
  t.add("output", 0.75);
  std::ostringstream os;
  t.print_table(os, 8.0);
  EXPECT_NE(os.str().find("most expensive (self time): 1. newton/solve 2.500 s (31.2%), 2. newton/assemble 1.000 s (12.5%), "
                          "3. output 0.750 s (9.4%)"),
            std::string::npos)
      << os.str();
}

}  // namespace loom
