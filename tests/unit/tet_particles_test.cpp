// Material points of a tetrahedral body (engine/mesh/tet_particles): on a distorted Kuhn box, every rule puts
// its points inside their cells and reproduces the box's volume and mass; rules of degree >= 1 its centre of
// mass and of degree >= 2 its second moments (inertia), to round-off, while the one-point rule misses the latter.
#include <gtest/gtest.h>

#include <string>

#include "engine/core/errors.hpp"
#include "engine/mesh/tet_generators.hpp"
#include "engine/mesh/tet_particles.hpp"

namespace loom {
namespace {

TetMeshData distorted_box(const Vec3& origin, const Vec3& size) {
  BoxSpec spec;
  spec.origin = origin, spec.size = size, spec.nx = 4, spec.ny = 3, spec.nz = 5;
  TetMeshData mesh = generate_box(spec);
  EXPECT_GT(distort_interior_nodes(mesh, 0.3, 7), 0.0);
  return mesh;
}

TEST(TetParticles, EveryRuleReproducesTheMomentsOfItsDegree) {
  const Vec3 o(-0.3, 1.0, 2.0), s(1.2, 0.7, 2.5), c = o + 0.5 * s;
  const double V = s.prod(), density = 1100.0;
  // Second moments of the box: int x_i^2 = V (c_i^2 + s_i^2 / 12), int x_i x_j = V c_i c_j (i != j).
  Mat3 second = V * c * c.transpose();
  for (int i = 0; i < 3; ++i) second(i, i) += V * s[i] * s[i] / 12.0;
  const TetMeshData mesh = distorted_box(o, s);
  for (const int n : {1, 4, 14, 24}) {
    const TetParticles p = place_tet_particles(mesh, n, density);
    ASSERT_EQ(p.X.size(), std::size_t(mesh.n_tets()) * std::size_t(n));
    double volume = 0.0, mass = 0.0;
    Vec3 first = Vec3::Zero();
    Mat3 moment = Mat3::Zero();
    for (std::size_t k = 0; k < p.X.size(); ++k) {
      EXPECT_GT(p.volume[k], 0.0);
      EXPECT_DOUBLE_EQ(p.mass[k], density * p.volume[k]);
      volume += p.volume[k], mass += p.mass[k];
      first += p.volume[k] * p.X[k];
      moment += p.volume[k] * p.X[k] * p.X[k].transpose();
      // Inside its cell: every barycentric coordinate positive (points k of cell k / n).
      const std::size_t t = k / std::size_t(n);
      const Vec3* x[4];
      for (int a = 0; a < 4; ++a) x[a] = &mesh.X[std::size_t(mesh.tets[4 * t + std::size_t(a)])];
      for (int a = 0; a < 4; ++a) {
        const Vec3* y[4] = {x[0], x[1], x[2], x[3]};
        y[a] = &p.X[k];
        EXPECT_GT(tet_volume(*y[0], *y[1], *y[2], *y[3]), 0.0) << n << " points, particle " << k;
      }
    }
    EXPECT_NEAR(volume, V, 1e-13 * V) << n;  // sums of up to 8640 terms
    EXPECT_NEAR(mass, density * V, 1e-13 * density * V) << n;
    EXPECT_LE((first - V * c).norm(), 1e-13 * V * c.norm()) << n;
    const double inertia_error = (moment - second).norm() / second.norm();
    if (n == 1)
      EXPECT_GT(inertia_error, 1e-4);  // the centroid rule is of degree 1 only
    else
      EXPECT_LE(inertia_error, 1e-13) << n;
  }
}

TEST(TetParticles, CountsWithoutARuleAndInvertedCellsAreRefused) {
  TetMeshData mesh = distorted_box(Vec3::Zero(), Vec3::Ones());
  EXPECT_THROW(place_tet_particles(mesh, 12, 1.0), InputError);
  std::swap(mesh.tets[4 * 5 + 1], mesh.tets[4 * 5 + 2]);  // tetrahedron 5 turned inside out
  try {
    place_tet_particles(mesh, 4, 1.0);
    FAIL() << "an inverted tetrahedron was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tetrahedron 5 "), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace loom
