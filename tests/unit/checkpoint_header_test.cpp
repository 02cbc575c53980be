// engine/methods/recipes/run_output: the part of a checkpoint that is not a store. It round-trips, a checkpoint
// written before it held the probes and the stop window still continues (they start empty), and a continued run
// whose time.stop_when watches another probe starts its window afresh. A store's column that an older checkpoint
// does not name (particles/be) restores as unused, and is refused where the scene uses it.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/io/checkpoint.hpp"
#include "engine/methods/recipes/run_output.hpp"
#include "engine/store/points.hpp"
#include "tests/support/test_support.hpp"

namespace loom {
namespace {

std::string scene_text(const std::string& stop_probe) {
  return "[scene]\nname = \"block\"\n"
         "[time]\nintegrator = \"newmark\"\ndt = 0.1\nsteps = 10\nstop_when = { probe = \"" + stop_probe + "\", below = 1e-3 }\n"
         "[[material]]\nname = \"m\"\nmodel = \"neo_hooke\"\nE = 100.0\nnu = 0.3\ndensity = 1.0\n"
         "[[body]]\nname = \"b\"\nmaterial = \"m\"\nelement = \"p1\"\n"
         "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [1.0, 1.0], divisions = [2, 2] }\n"
         "[[probe]]\nname = \"speed\"\nkind = \"speed\"\n"
         "[[probe]]\nname = \"top\"\nkind = \"extent\"\ncomponent = \"y\"\n"
         "[output]\nevery = 0\n";
}

CheckpointHeader header() {
  CheckpointHeader h;
  h.step = 4, h.t = 0.4, h.newton_iterations = 17, h.cutbacks = 1;
  h.method = "fem", h.scene_hash = "hash", h.linear_solver = "cholmod";
  h.probe_values = {0.25, 1.5};
  h.stop_history = {Vec2(0.3, 0.5), Vec2(0.4, 0.25)};
  h.stop_probe = "speed";
  return h;
}

CheckpointHeader read_back(const CheckpointWriter& w, const SceneSpec& scene, const testing::TempDir& dir) {
  w.write(dir.file("checkpoint.loom"));
  return read_checkpoint_header(CheckpointReader(dir.file("checkpoint.loom")), scene, nullptr);
}

TEST(CheckpointHeader, RoundTripsTheProbesAndTheStopWindow) {
  testing::TempDir dir("checkpoint_header");
  CheckpointWriter w;
  write_checkpoint_header(w, header());
  const CheckpointHeader h = read_back(w, testing::scene_from_text(scene_text("speed")), dir);
  EXPECT_EQ(h.step, 4);
  EXPECT_EQ(h.probe_values, header().probe_values);
  ASSERT_EQ(h.stop_history.size(), 2u);
  EXPECT_EQ(h.stop_history[1], Vec2(0.4, 0.25));
  EXPECT_EQ(h.stop_probe, "speed");
}

TEST(CheckpointHeader, AnotherStopProbeStartsTheWindowAfresh) {
  testing::TempDir dir("checkpoint_header_other_probe");
  CheckpointWriter w;
  write_checkpoint_header(w, header());
  const CheckpointHeader h = read_back(w, testing::scene_from_text(scene_text("top")), dir);
  EXPECT_EQ(h.probe_values, header().probe_values);
  EXPECT_TRUE(h.stop_history.empty());
}

// The header as loom wrote it before it kept the probes and the stop window.
TEST(CheckpointHeader, AnOlderCheckpointWithoutProbesContinues) {
  testing::TempDir dir("checkpoint_header_older");
  const CheckpointHeader full = header();
  CheckpointWriter w;
  w.text("run/method", full.method);
  w.text("run/scene_hash", full.scene_hash);
  w.value("run/step", full.step);
  w.value("run/t", full.t);
  w.value("run/newton_iterations", full.newton_iterations);
  w.value("run/cutbacks", full.cutbacks);
  w.text("run/linear_solver", full.linear_solver);
  w.value("run/last_frame_time", full.last_frame_time);
  w.value("run/frames", Index(0));
  const CheckpointHeader h = read_back(w, testing::scene_from_text(scene_text("speed")), dir);
  EXPECT_EQ(h.step, 4);
  EXPECT_EQ(h.newton_iterations, 17);
  EXPECT_TRUE(h.probe_values.empty());
  EXPECT_TRUE(h.stop_history.empty());
}

// Particles as loom wrote them before they could carry b^e: every column but "be".
TEST(CheckpointStore, AColumnAnOlderCheckpointLacksRestoresAsUnused) {
  testing::TempDir dir("checkpoint_store_older");
  Points<2> written;
  written.X.use(), written.u.use();
  written.resize(3);
  written.u[1] = Vec2(0.5, -0.25);
  CheckpointWriter w;
  written.for_each_column([&](const char* name, const auto& c) {
    if (std::string(name) != "be") w.column(std::string("particles/") + name, c);
  });
  w.write(dir.file("checkpoint.loom"));
  const CheckpointReader r(dir.file("checkpoint.loom"));
  Points<2> plain;
  plain.X.use(), plain.u.use();
  r.store("particles", plain);
  EXPECT_EQ(plain.u.size(), 3);
  EXPECT_EQ(plain.u[1], Vec2(0.5, -0.25));
  EXPECT_FALSE(plain.be.used());
  Points<2> with_history = plain;
  with_history.be.use();
  EXPECT_THROW(r.store("particles", with_history), InputError);
}

}  // namespace
}  // namespace loom
