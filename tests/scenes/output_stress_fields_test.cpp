// Stress fields in the output files, read back through VTK's reader: the nodal stress of output.nodal_stress (fem,
// pfem, es_pfem meshes), and the FEM bodies' cells of method mpm_fem in the grid's file with their body and stress.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "engine/core/types.hpp"
#include "tests/scenes/scene_checks.hpp"
#include "tests/scenes/vtu_frame.hpp"
#include "tests/support/test_support.hpp"

namespace loom::testing {
namespace {

// A distorted box of linear tetrahedra under the homogeneous displacement u = G X (every shear component) on its
// whole boundary: every cell carries sigma = lambda tr(eps) I + 2 mu eps, so every node's volume-weighted mean is
// sigma again, to round-off.
constexpr double kE = 1000.0, kNu = 0.3;
const char* kHomogeneousBox = R"([scene]
name = "homogeneous-box"
method = "fem"
dimension = 3
[time]
dt = 1.0
steps = 1
[[material]]
name = "m"
model = "linear_elastic"
E = 1000.0
nu = 0.3
[[body]]
name = "cube"
material = "m"
element = "p1"
mesh = { generator = "box", size = [1.0, 1.0, 1.0], divisions = [3, 3, 3], distortion = 0.2 }
[[boundary]]
name = "face0"
region = { box = [[0.0, 0.0, 0.0], [0.0, 1.0, 1.0]] }
displacement = { x = "0.001 * y + 0.002 * z", y = "0.003 * x", z = "0.001 * x + 0.002 * y + 0.004 * z" }
[[boundary]]
name = "face1"
region = { box = [[1.0, 0.0, 0.0], [1.0, 1.0, 1.0]] }
displacement = { x = "0.001 * y + 0.002 * z", y = "0.003 * x", z = "0.001 * x + 0.002 * y + 0.004 * z" }
[[boundary]]
name = "face2"
region = { box = [[0.0, 0.0, 0.0], [1.0, 0.0, 1.0]] }
displacement = { x = "0.001 * y + 0.002 * z", y = "0.003 * x", z = "0.001 * x + 0.002 * y + 0.004 * z" }
[[boundary]]
name = "face3"
region = { box = [[0.0, 1.0, 0.0], [1.0, 1.0, 1.0]] }
displacement = { x = "0.001 * y + 0.002 * z", y = "0.003 * x", z = "0.001 * x + 0.002 * y + 0.004 * z" }
[[boundary]]
name = "face4"
region = { box = [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0]] }
displacement = { x = "0.001 * y + 0.002 * z", y = "0.003 * x", z = "0.001 * x + 0.002 * y + 0.004 * z" }
[[boundary]]
name = "face5"
region = { box = [[0.0, 0.0, 1.0], [1.0, 1.0, 1.0]] }
displacement = { x = "0.001 * y + 0.002 * z", y = "0.003 * x", z = "0.001 * x + 0.002 * y + 0.004 * z" }
[output]
every = 1
nodal_stress = true
)";

TEST(OutputStressFields, TheNodalStressOfAHomogeneousStateIsItsStressAtEveryNode) {
  TempDir out("nodal_stress");
  const std::string scene = out.file("box.toml");
  std::ofstream(scene) << kHomogeneousBox;
  const Command c = run_loom({"run", scene, "--out", out.path(), "--quiet"});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const VtuFrame f = read_vtu(out.file("homogeneous-box_000001.vtu"));
  Mat3 G;
  G << 0.0, 0.001, 0.002, 0.003, 0.0, 0.0, 0.001, 0.002, 0.004;
  const double lambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu)), mu = kE / (2 * (1 + kNu));
  const Mat3 eps = 0.5 * (G + G.transpose());
  const Mat3 sigma = lambda * eps.trace() * Mat3::Identity() + 2 * mu * eps;
  const double mises = std::sqrt(1.5 * (sigma - sigma.trace() / 3.0 * Mat3::Identity()).squaredNorm());
  vtkDataArray *nodal = f.point("nodal_stress"), *nodal_mises = f.point("nodal_von_mises");
  ASSERT_NE(nodal, nullptr);
  ASSERT_NE(nodal_mises, nullptr);
  ASSERT_EQ(nodal->GetNumberOfComponents(), 9);
  ASSERT_EQ(nodal->GetNumberOfTuples(), f.grid->GetNumberOfPoints());
  EXPECT_EQ(f.grid->GetNumberOfPoints(), 64);
  for (vtkIdType i = 0; i < f.grid->GetNumberOfPoints(); ++i) {
    double s[9];
    nodal->GetTuple(i, s);
    for (int j = 0; j < 9; ++j) EXPECT_NEAR(s[j], sigma(j / 3, j % 3), 1e-10 * sigma.norm()) << "node " << i << ", component " << j;
    EXPECT_NEAR(nodal_mises->GetTuple1(i), mises, 1e-10 * sigma.norm()) << "node " << i;
  }
}

// Off by default: a mesh frame carries no nodal stress unless the scene asks for it.
TEST(OutputStressFields, NoNodalStressUnlessAskedFor) {
  TempDir out("no_nodal_stress");
  const std::string scene = out.file("box.toml");
  std::string text = kHomogeneousBox;
  text.erase(text.find("nodal_stress = true"));
  std::ofstream(scene) << text;
  const Command c = run_loom({"run", scene, "--out", out.path(), "--quiet"});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const VtuFrame f = read_vtu(out.file("homogeneous-box_000001.vtu"));
  EXPECT_EQ(f.point("nodal_stress"), nullptr);
  EXPECT_EQ(f.point("nodal_von_mises"), nullptr);
}

// Method mpm_fem (the disk rolling on the FEM plate, five steps): the plate's 160 quad9 cells (20 x 2, refined once)
// follow the active grid cells in the grid's file with cell data body = 1 (the plate is the scene's second body) and
// their Cauchy stress, symmetric, with von_mises from it; the grid's cells have body -1 and no stress (NaN). The
// disk presses on the plate: some of its cells are in vertical compression.
TEST(OutputStressFields, TheCoupledPlateWritesItsBodyAndStressInTheGridFile) {
  TempDir out("mpm_fem_plate");
  const Command c = run_loom({"run", std::string(LOOM_SOURCE_DIR) + "/scenes/rolling_disk_on_plate.toml", "--out", out.path(), "--quiet",
                              "--set", "time.steps=5", "--set", "output.every=5"});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const VtuFrame f = read_vtu(out.file("rolling_disk_on_plate_000005_grid.vtu"));
  vtkDataArray *body = f.cell("body"), *stress = f.cell("stress"), *mises = f.cell("von_mises");
  ASSERT_NE(body, nullptr);
  ASSERT_NE(stress, nullptr);
  ASSERT_NE(mises, nullptr);
  int plate_cells = 0;
  double lowest_syy = 0.0;
  for (vtkIdType k = 0; k < f.grid->GetNumberOfCells(); ++k) {
    double s[9];
    stress->GetTuple(k, s);
    if (body->GetTuple1(k) < 0.0) {
      EXPECT_EQ(body->GetTuple1(k), -1.0);
      EXPECT_TRUE(std::isnan(s[0]) && std::isnan(mises->GetTuple1(k))) << "grid cell " << k;
      continue;
    }
    ++plate_cells;
    EXPECT_EQ(body->GetTuple1(k), 1.0);
    const double scale = std::abs(s[0]) + std::abs(s[4]) + std::abs(s[1]) + 1.0;
    EXPECT_NEAR(s[1], s[3], 1e-9 * scale) << "cell " << k;
    const double p = (s[0] + s[4] + s[8]) / 3.0, d0 = s[0] - p, d4 = s[4] - p, d8 = s[8] - p;
    EXPECT_NEAR(mises->GetTuple1(k), std::sqrt(1.5 * (d0 * d0 + d4 * d4 + d8 * d8 + 2 * s[1] * s[1])), 1e-9 * scale) << "cell " << k;
    lowest_syy = std::min(lowest_syy, s[4]);
  }
  EXPECT_EQ(plate_cells, 160);
  EXPECT_LT(lowest_syy, 0.0);
}

}  // namespace
}  // namespace loom::testing
