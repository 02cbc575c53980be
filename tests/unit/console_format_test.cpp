// Durations and counts for people (engine/io/console_format.hpp): the end-of-run line once printed
// "1 steps" and "1e+01 s".
#include <gtest/gtest.h>

#include "engine/io/console_format.hpp"

namespace loom {
namespace {

TEST(ConsoleFormat, DurationsInTheUnitThatReadsBest) {
  EXPECT_EQ(format_seconds(0.0004), "0.40 ms");
  EXPECT_EQ(format_seconds(0.35), "350 ms");
  EXPECT_EQ(format_seconds(0.9996), "1.0 s");
  EXPECT_EQ(format_seconds(14.61), "14.6 s");
  EXPECT_EQ(format_seconds(59.94), "59.9 s");
  EXPECT_EQ(format_seconds(125.0), "2 min 05 s");
  EXPECT_EQ(format_seconds(7384.0), "2 h 03 min");
}

TEST(ConsoleFormat, CountsWithTheirNoun) {
  EXPECT_EQ(count_of(1, "step"), "1 step");
  EXPECT_EQ(count_of(0, "step"), "0 steps");
  EXPECT_EQ(count_of(3, "Newton iteration"), "3 Newton iterations");
  EXPECT_EQ(count_of(2, "cut-back"), "2 cut-backs");
}

}  // namespace
}  // namespace loom
