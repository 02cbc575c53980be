// The files of a run read back as a user's tools would read them (DESIGN §6): the .pvd collection and
// every .vtu through VTK's own reader, probes.csv, run.json and timings.json; no temporary file left.
#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkCell.h>
#include <vtkCellType.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <limits>

#include "engine/methods/model/build_mesh.hpp"
#include "engine/scene/scene_loader.hpp"
#include "tests/scenes/scene_checks.hpp"
#include "tests/scenes/vtu_frame.hpp"
#include "tests/support/test_support.hpp"

namespace loom::testing {
namespace {

const std::string kCook = std::string(LOOM_SOURCE_DIR) + "/scenes/cooks_membrane_linear.toml";
const std::string kPvd = "cooks-membrane-linear.pvd";

double relative_gap(double a, double b) { return std::abs(a - b) / std::max(1.0, std::max(std::abs(a), std::abs(b))); }

// Reference coordinates of the scene's mesh, generated again from the spec (not read from the output).
std::vector<Vec2> reference_nodes(const std::vector<std::string>& sets = {}) {
  const SceneSpec scene = load_scene(kCook, sets);
  return generate_body_mesh(scene.bodies.at(0).mesh).X;
}

Index nearest(const std::vector<Vec2>& X, const Vec2& at) {
  Index best = 0;
  for (Index i = 0; i < Index(X.size()); ++i)
    if ((X[std::size_t(i)] - at).squaredNorm() < (X[std::size_t(best)] - at).squaredNorm()) best = i;
  return best;
}

void expect_valid_frame(const VtuFrame& f, const std::vector<Vec2>& X, std::size_t n_cells) {
  ASSERT_EQ(f.grid->GetNumberOfPoints(), vtkIdType(X.size()));
  ASSERT_EQ(f.grid->GetNumberOfCells(), vtkIdType(n_cells));
  vtkDataArray* u = f.point("displacement");
  ASSERT_NE(u, nullptr);
  EXPECT_EQ(u->GetNumberOfComponents(), 3);
  ASSERT_EQ(u->GetNumberOfTuples(), vtkIdType(X.size()));
  const std::pair<const char*, int> cell_arrays[] = {{"stress", 9}, {"pressure", 1}, {"J", 1}, {"von_mises", 1}};
  for (const auto& [name, components] : cell_arrays) {
    vtkDataArray* a = f.cell(name);
    ASSERT_NE(a, nullptr) << name;
    EXPECT_EQ(a->GetNumberOfComponents(), components) << name;
    EXPECT_EQ(a->GetNumberOfTuples(), vtkIdType(n_cells)) << name;
  }
  // Points are the current configuration: x = X + u (plane: z = 0).
  for (vtkIdType i = 0; i < f.grid->GetNumberOfPoints(); ++i) {
    double x[3], d[3];
    f.grid->GetPoint(i, x);
    u->GetTuple(i, d);
    const Vec2& Xi = X[std::size_t(i)];
    EXPECT_NEAR(x[0], Xi.x() + d[0], 1e-12 * 60) << "point " << i;
    EXPECT_NEAR(x[1], Xi.y() + d[1], 1e-12 * 60) << "point " << i;
    EXPECT_EQ(x[2], 0.0);
    EXPECT_EQ(d[2], 0.0);
  }
  // Cauchy stress (row-major 3x3): symmetric, plane strain (no out-of-plane shear), and the derived
  // pressure and von Mises stress follow from it.
  vtkDataArray *s = f.cell("stress"), *p = f.cell("pressure"), *vm = f.cell("von_mises"), *J = f.cell("J");
  auto* note = vtkStringArray::SafeDownCast(f.grid->GetFieldData()->GetAbstractArray("pressure_definition"));
  ASSERT_NE(note, nullptr) << "the file says what pressure is";
  EXPECT_NE(note->GetValue(0).find("pressure = -tr(sigma)/3"), std::string::npos) << note->GetValue(0);
  for (vtkIdType c = 0; c < f.grid->GetNumberOfCells(); ++c) {
    double t[9];
    s->GetTuple(c, t);
    const double scale = 1.0 + std::abs(t[0]) + std::abs(t[4]) + std::abs(t[8]) + std::abs(t[1]);
    EXPECT_NEAR(t[1], t[3], 1e-12 * scale);
    EXPECT_EQ(t[2], 0.0);
    EXPECT_EQ(t[5], 0.0);
    EXPECT_EQ(t[6], 0.0);
    EXPECT_EQ(t[7], 0.0);
    const double pressure = -(t[0] + t[4] + t[8]) / 3.0;
    EXPECT_NEAR(p->GetTuple1(c), pressure, 1e-12 * scale) << "cell " << c;
    const double d0 = t[0] + pressure, d4 = t[4] + pressure, d8 = t[8] + pressure;
    const double mises = std::sqrt(1.5 * (d0 * d0 + d4 * d4 + d8 * d8 + 2 * t[1] * t[1]));
    EXPECT_NEAR(vm->GetTuple1(c), mises, 1e-12 * scale) << "cell " << c;
    EXPECT_GT(J->GetTuple1(c), 0.0);
    EXPECT_TRUE(std::isfinite(J->GetTuple1(c)));
  }
}

void expect_no_temporary_files(const std::string& dir) {
  for (const auto& f : files_under(dir)) EXPECT_EQ(f.find(".tmp"), std::string::npos) << "left behind: " << f;
}

TEST(OutputReadBack, CooksMembraneLinearFilesAreCompleteAndConsistent) {
  TempDir out("output_cook");
  const Command c = run_loom({"run", kCook, "--out", out.path(), "--quiet"});
  ASSERT_EQ(c.exit_code, 0) << c.err;

  // 1. The directory holds exactly the documented files.
  EXPECT_EQ(files_under(out.path()), (std::vector<std::string>{"cooks-membrane-linear.pvd", "cooks-membrane-linear_000000.vtu",
                                                               "cooks-membrane-linear_000001.vtu", "probes.csv", "run.json",
                                                               "timings.json"}));
  expect_no_temporary_files(out.path());

  // 2. probes.csv: header step,time,<probes in scene order>, then step 0 and one row per step.
  const std::string csv = read_text(out.file("probes.csv"));
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "step,time,uy_C,uy_M,reaction_y");
  const ProbeTable probes = read_probes(out.file("probes.csv"));
  ASSERT_EQ(probes.rows.size(), 2u);
  EXPECT_EQ(probes.column("step"), (std::vector<double>{0, 1}));
  EXPECT_EQ(probes.column("time"), (std::vector<double>{0, 1}));
  EXPECT_EQ(probes.rows[0], (std::vector<double>{0, 0, 0, 0, 0}));
  // Equilibrium: the clamp holds the total shear load 6.25 * 16 = 100 (sign: the force on the body).
  EXPECT_NEAR(probes.column("reaction_y")[1], -100.0, 1e-6);

  // 3. The .pvd lists the frames with their times; each file exists and reads back.
  const auto entries = parse_pvd(read_text(out.file(kPvd)));
  ASSERT_EQ(entries.size(), 2u);
  const std::vector<Vec2> X = reference_nodes();
  const Index corner = nearest(X, Vec2(48.0, 60.0));
  for (std::size_t k = 0; k < entries.size(); ++k) {
    SCOPED_TRACE(entries[k].file);
    EXPECT_EQ(entries[k].time, probes.column("time")[k]);
    ASSERT_TRUE(std::filesystem::exists(out.file(entries[k].file)));
    const VtuFrame f = read_vtu(out.file(entries[k].file));
    expect_valid_frame(f, X, 512);
    // The point probe reads the same node and value as the frame of that step.
    double d[3];
    f.point("displacement")->GetTuple(corner, d);
    EXPECT_LE(relative_gap(d[1], probes.column("uy_C")[k]), 1e-12) << d[1] << " vs " << probes.column("uy_C")[k];
  }

  // 4. run.json: the documented keys with their types and values.
  const Json run = parse_json(read_text(out.file("run.json")));
  for (const char* key : {"loom_version", "scene_file", "scene_name", "scene_hash", "method", "linear_solver", "failure"})
    EXPECT_EQ(run.at(key).kind, Json::Kind::string) << key;
  for (const char* key : {"threads", "ranks", "dofs", "cells", "steps_requested", "steps_done", "last_converged_step",
                          "last_converged_time", "newton_iterations", "cutbacks", "wall_seconds"})
    EXPECT_EQ(run.at(key).kind, Json::Kind::number) << key;
  EXPECT_EQ(run.at("converged").kind, Json::Kind::boolean);
  EXPECT_TRUE(run.at("converged").boolean);
  EXPECT_EQ(run.at("scene_file").string, kCook);
  EXPECT_EQ(run.at("scene_name").string, "cooks-membrane-linear");
  EXPECT_EQ(run.at("method").string, "fem");
  EXPECT_FALSE(run.at("scene_hash").string.empty());
  EXPECT_GE(run.at("threads").number, 1.0);
  EXPECT_EQ(run.at("cells").number, 512.0);
  EXPECT_EQ(run.at("dofs").number, 544.0);  // 289 nodes * 2 - 17 clamped nodes * 2
  EXPECT_EQ(run.at("steps_requested").number, 1.0);
  EXPECT_EQ(run.at("steps_done").number, 1.0);
  EXPECT_EQ(run.at("last_converged_step").number, 1.0);
  EXPECT_EQ(run.at("last_converged_time").number, 1.0);
  EXPECT_GE(run.at("newton_iterations").number, 1.0);
  EXPECT_EQ(run.at("cutbacks").number, 0.0);
  EXPECT_GE(run.at("wall_seconds").number, 0.0);
  EXPECT_EQ(run.at("failure").string, "");

  // 5. timings.json: wall time and one entry per graph node (and its sub-timers).
  const Json timings = parse_json(read_text(out.file("timings.json")));
  const double wall = timings.at("wall").number;
  EXPECT_GT(wall, 0.0);
  EXPECT_NEAR(wall, run.at("wall_seconds").number, 1e-6 * wall);
  const Json& timers = timings.at("timers");
  ASSERT_EQ(timers.kind, Json::Kind::object);
  for (const char* node : {"apply_boundary_conditions", "newton", "commit", "probes", "output"})
    EXPECT_TRUE(timers.has(node)) << node;
  for (const auto& [name, t] : timers.object) {
    SCOPED_TRACE(name);
    const double calls = t.at("calls").number, total = t.at("total").number, mean = t.at("mean").number;
    EXPECT_GE(calls, 1.0);
    EXPECT_EQ(calls, std::floor(calls));
    EXPECT_GE(total, 0.0);
    EXPECT_NEAR(mean * calls, total, 1e-6 * total + 1e-12);
    EXPECT_LE(t.at("max").number, total * (1 + 1e-6) + 1e-12);
    EXPECT_NEAR(t.at("share").number, total / wall, 1e-6);
    EXPECT_LE(total, wall * (1 + 1e-6));
  }
}

TEST(OutputReadBack, FramesFollowOutputEveryAndTheLastStepIsAlwaysWritten) {
  TempDir out("output_every");
  const std::vector<std::string> sets{"--set", "time.steps=5", "--set", "output.every=2", "--set",
                                      "boundary[loaded].traction.y=6.25 * t / 5"};
  std::vector<std::string> args{"run", kCook, "--out", out.path(), "--quiet"};
  args.insert(args.end(), sets.begin(), sets.end());
  const Command c = run_loom(args);
  ASSERT_EQ(c.exit_code, 0) << c.err;
  expect_no_temporary_files(out.path());

  const ProbeTable probes = read_probes(out.file("probes.csv"));
  ASSERT_EQ(probes.rows.size(), 6u);
  EXPECT_EQ(probes.column("step"), (std::vector<double>{0, 1, 2, 3, 4, 5}));
  // Linear elasticity under a load ramp: the displacement grows in proportion.
  const auto uy = probes.column("uy_C");
  for (int k = 1; k <= 5; ++k) EXPECT_NEAR(uy[std::size_t(k)], uy[5] * k / 5.0, 1e-9 * std::abs(uy[5]));

  const auto entries = parse_pvd(read_text(out.file(kPvd)));
  ASSERT_EQ(entries.size(), 4u);
  const double times[] = {0, 2, 4, 5};
  const std::vector<Vec2> X = reference_nodes();
  const Index corner = nearest(X, Vec2(48.0, 60.0));
  for (std::size_t k = 0; k < entries.size(); ++k) {
    EXPECT_EQ(entries[k].time, times[k]);
    char name[64];
    std::snprintf(name, sizeof name, "cooks-membrane-linear_%06d.vtu", int(times[k]));
    EXPECT_EQ(entries[k].file, name);
    const VtuFrame f = read_vtu(out.file(entries[k].file));
    expect_valid_frame(f, X, 512);
    EXPECT_LE(relative_gap(f.point("displacement")->GetComponent(corner, 1), uy[std::size_t(times[k])]), 1e-12);
  }
  EXPECT_EQ(files_under(out.path()).size(), 4u + 4u);  // frames + pvd, probes.csv, run.json, timings.json

  // every = 0: no frames at all, the probes still every step.
  TempDir none("output_every0");
  ASSERT_EQ(run_loom({"run", kCook, "--out", none.path(), "--quiet", "--set", "output.every=0"}).exit_code, 0);
  EXPECT_EQ(files_under(none.path()), (std::vector<std::string>{"probes.csv", "run.json", "timings.json"}));
}

// --profile: timings.json gains "profile" with one entry per step, each holding the systems that ran;
// the newton system holds one "iteration k" per Newton iteration (0: the first assembly), each holding
// the sub-phases. Every child lies within its parent's time (concurrent entries aside); the phases of a
// system run one after the other, so below the step level they also add up to at most their parent (the
// systems of a step may overlap: probes and output run in parallel). Without --profile there is no
// "profile" key; "most_expensive" is always there.
double seconds_of(const Json& node) { return node.at("seconds").number; }

void expect_children_within(const Json& node, const std::string& path, bool sequential) {
  if (!node.has("children")) return;
  // Nested scopes read one monotonic clock, the child's two reads between its parent's, so a child lies
  // within its parent however the threads are scheduled; an iteration, which no scope times, spans its
  // phases (the sum of its phases was shorter by the untimed work between them: by microseconds, and by a
  // whole time slice when the thread was descheduled there on a loaded machine). slack: the profile's own
  // 1e-7 s and the file's 9 significant digits; structure errors are off by whole phase times.
  const double begin = node.at("start").number, end = begin + seconds_of(node), slack = 1e-6;
  double sum = 0.0;
  for (const Json& c : node.at("children").array) {
    const std::string name = c.at("name").string;
    EXPECT_GE(seconds_of(c), 0.0) << path << "/" << name;
    if (c.has("concurrent")) continue;
    sum += seconds_of(c);
    EXPECT_GE(c.at("start").number, begin - slack) << path << "/" << name;
    EXPECT_LE(c.at("start").number + seconds_of(c), end + slack) << path << "/" << name;
    expect_children_within(c, path + "/" + name, true);
  }
  if (sequential) {
    EXPECT_LE(sum, seconds_of(node) + slack) << path;
  }
}

TEST(OutputReadBack, ProfileNestsStepSystemIterationAndSubPhase) {
  TempDir out("output_profile");
  const std::string base = out.file("base_with_newton.toml");  // tests/scenes/base.toml (2 steps) + a newton probe
  write_text(base, read_text(std::string(LOOM_SOURCE_DIR) + "/tests/scenes/base.toml") +
                       "\n[[probe]]\nname = \"newton\"\nkind = \"newton\"\n");
  const Command c = run_loom({"run", base, "--out", out.path(), "--profile"});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_NE(c.out.find("most expensive (self time): 1. "), std::string::npos) << c.out;
  const Json timings = parse_json(read_text(out.file("timings.json")));
  for (const char* key : {"wall", "timers", "most_expensive", "profile"}) EXPECT_TRUE(timings.has(key)) << key;
  EXPECT_EQ(timings.at("most_expensive").array.size(), 3u);
  const ProbeTable probes = read_probes(out.file("probes.csv"));
  const auto newton = probes.column("newton");

  const auto& steps = timings.at("profile").at("steps").array;
  // The initial state may come first as step 0 (the first frame's writer); then steps 1 and 2.
  std::vector<const Json*> scene_steps;
  for (const Json& s : steps)
    if (s.at("step").number > 0) scene_steps.push_back(&s);
  ASSERT_EQ(scene_steps.size(), 2u);
  for (std::size_t k = 0; k < scene_steps.size(); ++k) {
    const Json& step = *scene_steps[k];
    SCOPED_TRACE(step.at("name").string);
    EXPECT_EQ(step.at("name").string, "step " + std::to_string(k + 1));
    EXPECT_EQ(step.at("t").number, double(k + 1));
    EXPECT_EQ(step.at("dt").number, 1.0);
    expect_children_within(step, step.at("name").string, false);
    std::vector<std::string> systems;
    const Json* newton_node = nullptr;
    for (const Json& s : step.at("children").array) {
      systems.push_back(s.at("name").string);
      if (s.at("name").string == "newton") newton_node = &s;
    }
    for (const char* name : {"apply_boundary_conditions", "newton", "commit", "probes", "output"})
      EXPECT_NE(std::find(systems.begin(), systems.end(), name), systems.end()) << name;
    ASSERT_NE(newton_node, nullptr);
    const auto& iterations = newton_node->at("children").array;
    ASSERT_EQ(iterations.size(), std::size_t(newton[k + 1]) + 1);  // iteration 0 (first assembly) and one per solve
    for (std::size_t i = 0; i < iterations.size(); ++i) {
      EXPECT_EQ(iterations[i].at("name").string, "iteration " + std::to_string(i));
      std::vector<std::string> phases;
      for (const Json& ph : iterations[i].at("children").array) phases.push_back(ph.at("name").string);
      const std::vector<std::string> expected =
          i == 0 ? std::vector<std::string>{"assemble"} : std::vector<std::string>{"solve", "update", "assemble"};
      EXPECT_EQ(phases, expected);
    }
    const Json& solve = iterations[1].at("children").array[0];
    ASSERT_TRUE(solve.has("children"));
    EXPECT_EQ(solve.at("children").array[0].at("name").string, "factorize");
    EXPECT_EQ(solve.at("children").array[1].at("name").string, "back_substitute");
  }

  TempDir plain("output_no_profile");
  ASSERT_EQ(run_loom({"run", base, "--out", plain.path(), "--quiet"}).exit_code, 0);
  const Json t2 = parse_json(read_text(plain.file("timings.json")));
  EXPECT_FALSE(t2.has("profile"));
  EXPECT_TRUE(t2.has("most_expensive"));
}

// --profile for method mpm (and mpm_fem, the same recipe): the steps hold the particle-Newmark systems and the
// Newton iterations.
TEST(OutputReadBack, ProfileOfAnMpmRunHoldsItsSystemsAndIterations) {
  TempDir out("output_profile_mpm");
  const Command c = run_loom({"run", std::string(LOOM_SOURCE_DIR) + "/scenes/rolling_disk_mpm.toml", "--out", out.path(), "--quiet",
                              "--profile", "--set", "time.steps=2", "--set", "output.every=0", "--set", "body[0].particles.n_theta=100"});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const Json timings = parse_json(read_text(out.file("timings.json")));
  ASSERT_TRUE(timings.has("profile"));
  int scene_steps = 0;
  for (const Json& step : timings.at("profile").at("steps").array) {
    if (step.at("step").number < 1) continue;
    ++scene_steps;
    std::vector<std::string> systems;
    const Json* newton = nullptr;
    for (const Json& s : step.at("children").array) {
      systems.push_back(s.at("name").string);
      if (s.at("name").string == "newton") newton = &s;
    }
    for (const char* name : {"locate_particles", "activate_grid", "newton", "commit_particle_newmark", "probes"})
      EXPECT_NE(std::find(systems.begin(), systems.end(), name), systems.end()) << name;
    ASSERT_NE(newton, nullptr);
    EXPECT_GE(newton->at("children").array.size(), 2u);  // iteration 0 and at least one solve
    expect_children_within(step, step.at("name").string, false);
  }
  EXPECT_EQ(scene_steps, 2);
}

}  // namespace
}  // namespace loom::testing

namespace loom::testing {
namespace {

// Seed 001's u-p elements write the nodal pressure unknown (mean_stress, positive in tension) and es_pfem the
// particles' J; the cells' pressure (-tr sigma / 3, from the edges' stress) is its opposite on average.
TEST(OutputReadBack, SmoothedElementsWriteTheNodalPressureAndJ) {
  TempDir out("readback_es_pfem");
  const Command c = run_loom({"run", std::string(LOOM_SOURCE_DIR) + "/tests/scenes/es_pfem_bingham_column.toml", "--quiet", "--out", out.path()});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const VtuFrame f = read_vtu(out.file("es-pfem-bingham-column_000030.vtu"));
  vtkDataArray* p = f.point("mean_stress");
  vtkDataArray* J = f.point("J_node");
  ASSERT_NE(p, nullptr);
  ASSERT_NE(J, nullptr);
  ASSERT_EQ(p->GetNumberOfTuples(), f.grid->GetNumberOfPoints());
  double p_mean = 0.0, J_min = 1e300, J_max = 0.0;
  for (vtkIdType i = 0; i < p->GetNumberOfTuples(); ++i) {
    p_mean += p->GetTuple1(i) / double(p->GetNumberOfTuples());
    J_min = std::min(J_min, J->GetTuple1(i)), J_max = std::max(J_max, J->GetTuple1(i));
  }
  vtkDataArray* cell_pressure = f.cell("pressure");
  ASSERT_NE(cell_pressure, nullptr);
  double q_mean = 0.0;
  for (vtkIdType k = 0; k < cell_pressure->GetNumberOfTuples(); ++k) q_mean += cell_pressure->GetTuple1(k) / double(cell_pressure->GetNumberOfTuples());
  EXPECT_LT(p_mean, 0.0);  // a column under its weight is in compression
  EXPECT_NEAR(q_mean, -p_mean, 0.2 * std::abs(p_mean));
  EXPECT_GT(J_min, 0.0);
  EXPECT_LT(J_min, 1.0);  // compressed somewhere (rho g H / K = 5 % at the base)
}

// quad9 bodies are written as VTK_BIQUADRATIC_QUAD with the nine nodes in VTK's order (corners, mid-sides, centre):
// ParaView draws the curved cells from them. On Cook's membrane, n x n cells have (2n + 1)^2 nodes, and the written
// displacement at C is the probe's.
TEST(OutputReadBack, Quad9CellsAreBiquadraticQuadsWithTheirNineNodes) {
  TempDir out("readback_quad9");
  std::ifstream in(kCook);
  std::stringstream text;
  text << in.rdbuf();
  const std::string scene = std::regex_replace(text.str(), std::regex(R"(, pattern = "[a-z]+")"), "");
  ASSERT_NE(scene, text.str());
  std::ofstream(out.file("quad9.toml")) << scene;
  const Command c = run_loom({"run", out.file("quad9.toml"), "--quiet", "--out", out.path(), "--set", "body[0].element=quad9", "--set",
                              "body[0].mesh.divisions=[4,4]"});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const VtuFrame f = read_vtu(out.file("cooks-membrane-linear_000001.vtu"));
  ASSERT_EQ(f.grid->GetNumberOfCells(), 16);
  EXPECT_EQ(f.grid->GetNumberOfPoints(), 81);
  for (vtkIdType k = 0; k < f.grid->GetNumberOfCells(); ++k) {
    ASSERT_EQ(f.grid->GetCellType(k), VTK_BIQUADRATIC_QUAD);
    // The centre node lies inside the quadrilateral of the four corners (a mis-ordered cell would put a
    // mid-side or a corner there).
    vtkCell* cell = f.grid->GetCell(k);
    double centre[3], mean[3] = {0, 0, 0};
    f.grid->GetPoint(cell->GetPointId(8), centre);
    for (int a = 0; a < 4; ++a) {
      double x[3];
      f.grid->GetPoint(cell->GetPointId(a), x);
      for (int d = 0; d < 2; ++d) mean[d] += x[d] / 4;
    }
    EXPECT_LT(std::hypot(centre[0] - mean[0], centre[1] - mean[1]), 0.5) << "cell " << k;
  }
  const auto probes = read_probes(out.file("probes.csv"));
  vtkDataArray* u = f.point("displacement");
  ASSERT_NE(u, nullptr);
  double uy_max = 0.0;
  for (vtkIdType i = 0; i < u->GetNumberOfTuples(); ++i) uy_max = std::max(uy_max, u->GetComponent(i, 1));
  EXPECT_NEAR(uy_max, probes.column("uy_C").back(), 1e-9 * uy_max);  // C is the largest deflection
}

}  // namespace
}  // namespace loom::testing
