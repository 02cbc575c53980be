// The boundary edges (3D: faces) a traction acts on, as the four builders select them (engine/methods/model/
// build_boundary_conditions.cpp, build_solid_3d.cpp, build_particles.cpp, mpm_model_3d.cpp), with and without
// boundary[].region.normal. The fixture is a beam [0, 1] x [0, 0.1] (3D: x [0, 0.1]) with a traction region that spans
// its last tenth, [0.9, 1] x [0, 0.1]: the box holds the end x = 1 and the last stretch of the top and bottom (3D: and
// of the two sides), 4 edges of total length 0.3 on 10 x 2 squares (3D: 24 faces of total area 0.05 on 10 x 2 x 2
// cubes). With normal = [1, 0] only the end carries the traction: 2 edges of total length h = 0.1 (3D: 8 faces of area
// h^2 = 0.01), each with outward normal +x. The outward normal of an edge a -> b is taken as (y_b - y_a, -(x_b - x_a))
// (counter-clockwise cells); the test checks it independently: the end's edges run upwards (y_b > y_a).
//  - a direction at exactly 45 degrees to two faces takes both (the end and the top), any length of the direction
//    gives the same faces;
//  - PFEM ties only the mid-nodes of the loaded edges (and of the clamp's), not those the normal left out;
//  - a direction no edge of the region faces is an InputError naming region.normal.
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "engine/core/errors.hpp"
#include "engine/methods/model/build_boundary_conditions.hpp"
#include "engine/methods/model/fem_model.hpp"
#include "engine/methods/model/mpm_model.hpp"
#include "tests/support/test_support.hpp"

namespace loom {
namespace {

constexpr double kL = 1.0, kH = 0.1;
constexpr double kStretch = 0.1;  // the region's length along the beam, [0.9, 1]

// The region line of the loaded boundary: the box across the beam's end, with `normal` when given.
std::string end_region(const std::string& box, const std::string& normal) {
  return "region = { box = " + box + (normal.empty() ? std::string() : ", normal = " + normal) + " }\n";
}

std::string beam_2d(const std::string& normal, const std::string& method = "fem", const std::string& element = "p1") {
  return "[scene]\nname = \"beam-end\"\nmethod = \"" + method + "\"\n"
         "[time]\nintegrator = \"static\"\ndt = 1.0\nsteps = 1\n"
         "[[material]]\nname = \"m\"\nmodel = \"linear_elastic\"\nE = 100.0\nnu = 0.3\n"
         "[[body]]\nname = \"beam\"\nmaterial = \"m\"\nelement = \"" + element + "\"\n"
         "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [1.0, 0.1], divisions = [10, 2] }\n"
         "[[boundary]]\nname = \"clamp\"\nregion = { box = [[0.0, 0.0], [0.0, 0.1]] }\ndisplacement = { x = 0.0, y = 0.0 }\n"
         "[[boundary]]\nname = \"end\"\n" + end_region("[[0.9, 0.0], [1.0, 0.1]]", normal) + "traction = { x = 1.0 }\n"
         "[output]\nevery = 0\n";
}

std::string beam_3d(const std::string& normal) {
  return "[scene]\nname = \"beam-end-3d\"\nmethod = \"fem\"\ndimension = 3\n"
         "[time]\nintegrator = \"static\"\ndt = 1.0\nsteps = 1\n"
         "[[material]]\nname = \"m\"\nmodel = \"linear_elastic\"\nE = 100.0\nnu = 0.3\n"
         "[[body]]\nname = \"beam\"\nmaterial = \"m\"\nelement = \"p1\"\n"
         "mesh = { generator = \"box\", origin = [0.0, 0.0, 0.0], size = [1.0, 0.1, 0.1], divisions = [10, 2, 2] }\n"
         "[[boundary]]\nname = \"clamp\"\nregion = { box = [[0.0, 0.0, 0.0], [0.0, 0.1, 0.1]] }\n"
         "displacement = { x = 0.0, y = 0.0, z = 0.0 }\n"
         "[[boundary]]\nname = \"end\"\n" + end_region("[[0.9, 0.0, 0.0], [1.0, 0.1, 0.1]]", normal) + "traction = { x = 1.0 }\n"
         "[output]\nevery = 0\n";
}

// Method mpm: a body mesh like the fem beam's, in a grid that holds it.
std::string beam_mpm(const std::string& normal, int dimension) {
  const bool solid = dimension == 3;
  return "[scene]\nname = \"beam-end-mpm\"\nmethod = \"mpm\"\ndimension = " + std::to_string(dimension) + "\n"
         "[time]\nintegrator = \"newmark\"\ndt = 0.01\nsteps = 1\n"
         "[[material]]\nname = \"m\"\nmodel = \"neo_hooke\"\nE = 100.0\nnu = 0.3\ndensity = 1.0\n"
         "[[body]]\nname = \"beam\"\nmaterial = \"m\"\nelement = \"p1\"\nparticles_per_cell = " + (solid ? "1" : "3") + "\n" +
         (solid ? "mesh = { generator = \"box\", origin = [0.0, 0.0, 0.0], size = [1.0, 0.1, 0.1], divisions = [10, 2, 2] }\n"
                  "[grid]\ngenerator = \"box\"\norigin = [-0.5, -0.5, -0.5]\nsize = [2.0, 1.0, 1.0]\ndivisions = [4, 2, 2]\n"
                : "mesh = { generator = \"rectangle\", origin = [0.0, 0.0], size = [1.0, 0.1], divisions = [10, 2] }\n"
                  "[grid]\ngenerator = \"rectangle\"\norigin = [-0.5, -0.5]\nsize = [2.0, 1.0]\ndivisions = [8, 4]\n") +
         "[[boundary]]\nname = \"end\"\n" +
         end_region(solid ? "[[0.9, 0.0, 0.0], [1.0, 0.1, 0.1]]" : "[[0.9, 0.0], [1.0, 0.1]]", normal) + "traction = { x = 1.0 }\n"
         "[output]\nevery = 0\n";
}

struct Loaded {
  std::size_t count = 0;
  double size = 0.0;                  // total length (3D: area)
  Vec3 lo = Vec3::Constant(1e300);    // bounding box of the loaded edges' (faces') corners
  Vec3 hi = Vec3::Constant(-1e300);
  double worst_normal = 0.0;          // largest |n / |n| - e_x| over the loaded edges (faces)
};

Loaded traction_edges(const FemModel& m) {
  Loaded r;
  for (const auto& e : m.bc.traction_edges) {
    const Vec2 a = m.nodes.X[e.a], b = m.nodes.X[e.b], t = b - a;
    ++r.count;
    r.size += t.norm();
    for (const Vec2& x : {a, b}) r.lo = r.lo.cwiseMin(to_vec3<2>(x)), r.hi = r.hi.cwiseMax(to_vec3<2>(x));
    r.worst_normal = std::max(r.worst_normal, (Vec2(t.y(), -t.x()).normalized() - Vec2(1.0, 0.0)).norm());
  }
  return r;
}

Loaded traction_faces(const FemModelT<3>& m) {
  Loaded r;
  for (const auto& f : m.bc.traction_faces) {
    const Vec3 x0 = m.nodes.X[f.nodes[0]], x1 = m.nodes.X[f.nodes[1]], x2 = m.nodes.X[f.nodes[2]];
    const Vec3 n = (x1 - x0).cross(x2 - x0);
    ++r.count;
    r.size += 0.5 * n.norm();
    for (const Vec3& x : {x0, x1, x2}) r.lo = r.lo.cwiseMin(x), r.hi = r.hi.cwiseMax(x);
    r.worst_normal = std::max(r.worst_normal, (n.normalized() - Vec3(1.0, 0.0, 0.0)).norm());
  }
  return r;
}

// Traction points: their number and total weight (= the loaded length or area), and where they lie.
template <int D>
Loaded traction_points(const MpmModelT<D>& m) {
  Loaded r;
  for (Index q = 0; q < m.traction_points.X.size(); ++q) {
    ++r.count;
    r.size += m.traction_points.volume[q];
    const Vec3 x = to_vec3<D>(m.traction_points.X[q]);
    r.lo = r.lo.cwiseMin(x), r.hi = r.hi.cwiseMax(x);
  }
  return r;
}

TEST(TractionRegion, WithoutNormalTheBoxLoadsTheEndAndTheTopAndBottomEdges) {
  const FemModel m(testing::scene_from_text(beam_2d("")));
  const Loaded r = traction_edges(m);
  EXPECT_EQ(r.count, 4u);
  EXPECT_NEAR(r.size, kH + 2 * kStretch, 1e-12);
  EXPECT_NEAR(r.lo.x(), kL - kStretch, 1e-12);
}

TEST(TractionRegion, NormalKeepsOnlyTheEndEdges) {
  for (const std::string normal : {"[1.0, 0.0]", "[25.0, 0.0]"}) {
    SCOPED_TRACE(normal);
    const FemModel m(testing::scene_from_text(beam_2d(normal)));
    const Loaded r = traction_edges(m);
    EXPECT_EQ(r.count, 2u);
    EXPECT_NEAR(r.size, kH, 1e-12);  // the external force is the traction times h
    EXPECT_NEAR(r.lo.x(), kL, 1e-12);
    EXPECT_NEAR(r.hi.x(), kL, 1e-12);
    EXPECT_LE(r.worst_normal, 1e-12);
    // The orientation the builder relies on, seen directly: along x = L the edges of counter-clockwise cells run upwards.
    for (const auto& e : m.bc.traction_edges) EXPECT_GT(m.nodes.X[e.b].y(), m.nodes.X[e.a].y());
  }
}

TEST(TractionRegion, NormalUpKeepsTheTopEdgeAndFortyFiveDegreesTakesBoth) {
  const Loaded top = traction_edges(FemModel(testing::scene_from_text(beam_2d("[0.0, 1.0]"))));
  EXPECT_EQ(top.count, 1u);
  EXPECT_NEAR(top.lo.y(), kH, 1e-12);
  EXPECT_NEAR(top.hi.y(), kH, 1e-12);
  const Loaded corner = traction_edges(FemModel(testing::scene_from_text(beam_2d("[1.0, 1.0]"))));
  EXPECT_EQ(corner.count, 3u);  // the end's two and the top's one; the bottom faces down, 135 degrees away
  EXPECT_NEAR(corner.size, kH + kStretch, 1e-12);
  EXPECT_NEAR(corner.lo.x(), kL - kStretch, 1e-12);  // the top's edge
}

TEST(TractionRegion, FacesDirectionIsTheFortyFiveDegreeRule) {
  EXPECT_TRUE(faces_direction<2>(Vec2(1.0, 0.0), Vec2(3.0, 0.0)));
  EXPECT_TRUE(faces_direction<2>(Vec2(1.0, 0.0), Vec2(1.0, 1.0)));    // 45 degrees: in
  EXPECT_TRUE(faces_direction<2>(Vec2(1.0, 0.9), Vec2(1.0, 0.0)));    // 42 degrees
  EXPECT_FALSE(faces_direction<2>(Vec2(1.0, 1.1), Vec2(1.0, 0.0)));   // 47.7 degrees
  EXPECT_FALSE(faces_direction<2>(Vec2(0.0, 1.0), Vec2(1.0, 0.0)));
  EXPECT_FALSE(faces_direction<2>(Vec2(-1.0, 0.0), Vec2(1.0, 0.0)));
  EXPECT_FALSE(faces_direction<2>(Vec2(0.0, 0.0), Vec2(1.0, 0.0)));   // a degenerate edge faces nothing
  EXPECT_TRUE(faces_direction<3>(Vec3(0.0, 0.0, 2.0), Vec3(0.0, 1.0, 1.0)));
  EXPECT_FALSE(faces_direction<3>(Vec3(0.0, 0.0, 2.0), Vec3(0.0, 1.0, 0.9)));
}

TEST(TractionRegion, PfemTiesTheMidNodesOfTheLoadedEdgesOnly) {
  // tri6: the clamp's 2 edges and the loaded edges tie their mid-nodes (both components each).
  const FemModel all(testing::scene_from_text(beam_2d("", "pfem", "tri6")));
  const FemModel end(testing::scene_from_text(beam_2d("[1.0, 0.0]", "pfem", "tri6")));
  EXPECT_EQ(all.bc.ties.size(), 2u * (2 + 4));
  EXPECT_EQ(end.bc.ties.size(), 2u * (2 + 2));
  EXPECT_EQ(traction_edges(end).count, 2u);
  for (const auto& e : end.bc.traction_edges) EXPECT_EQ(e.mid, kNoIndex);  // tied: loaded through its corners
}

TEST(TractionRegion, NormalThatNoEdgeFacesNamesRegionNormal) {
  try {
    const FemModel m(testing::scene_from_text(beam_2d("[-1.0, 0.0]")));
    (void)m;
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("boundary[1].region.normal: a traction needs boundary edges"), std::string::npos) << what;
    EXPECT_NE(what.find("its filter removed all 4 of the region's boundary edges"), std::string::npos) << what;
  }
}

TEST(TractionRegion, ThreeDimensionalNormalKeepsOnlyTheEndFaces) {
  const Loaded all = traction_faces(FemModelT<3>(testing::scene_from_text(beam_3d(""))));
  EXPECT_EQ(all.count, 24u);  // end 2 x 2 squares, each side 2 squares; two triangles a square
  EXPECT_NEAR(all.size, kH * kH + 4 * kStretch * kH, 1e-12);
  const Loaded end = traction_faces(FemModelT<3>(testing::scene_from_text(beam_3d("[1.0, 0.0, 0.0]"))));
  EXPECT_EQ(end.count, 8u);
  EXPECT_NEAR(end.size, kH * kH, 1e-12);
  EXPECT_NEAR(end.lo.x(), kL, 1e-12);
  EXPECT_LE(end.worst_normal, 1e-12);  // boundary_faces' orientation: outward
  // 45 degrees between the end and the top z = h: both, not the bottom nor the sides y = 0, y = h.
  const Loaded corner = traction_faces(FemModelT<3>(testing::scene_from_text(beam_3d("[2.0, 0.0, 2.0]"))));
  EXPECT_EQ(corner.count, 8u + 4u);
  EXPECT_NEAR(corner.size, kH * kH + kStretch * kH, 1e-12);
}

TEST(TractionRegion, MpmTractionPointsFollowTheNormal) {
  // Two Gauss points an edge, weights summing to the edge's length.
  const Loaded all = traction_points(MpmModelT<2>(testing::scene_from_text(beam_mpm("", 2))));
  EXPECT_EQ(all.count, 2u * 4);
  EXPECT_NEAR(all.size, kH + 2 * kStretch, 1e-12);
  const Loaded end = traction_points(MpmModelT<2>(testing::scene_from_text(beam_mpm("[1.0, 0.0]", 2))));
  EXPECT_EQ(end.count, 2u * 2);
  EXPECT_NEAR(end.size, kH, 1e-12);
  EXPECT_NEAR(end.lo.x(), kL, 1e-12);
  EXPECT_NEAR(end.hi.x(), kL, 1e-12);
}

TEST(TractionRegion, Mpm3dTractionPointsFollowTheNormal) {
  // Three points a face, weights summing to the face's area.
  const Loaded all = traction_points(MpmModelT<3>(testing::scene_from_text(beam_mpm("", 3))));
  EXPECT_EQ(all.count, 3u * 24);
  EXPECT_NEAR(all.size, kH * kH + 4 * kStretch * kH, 1e-12);
  const Loaded end = traction_points(MpmModelT<3>(testing::scene_from_text(beam_mpm("[1.0, 0.0, 0.0]", 3))));
  EXPECT_EQ(end.count, 3u * 8);
  EXPECT_NEAR(end.size, kH * kH, 1e-12);
  EXPECT_NEAR(end.lo.x(), kL, 1e-12);
  EXPECT_NEAR(end.hi.x(), kL, 1e-12);
}

}  // namespace
}  // namespace loom
