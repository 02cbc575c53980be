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
