// Smoothing domains of the edge-based smoothed FEM: topology (engine/mesh/smoothing_edges) and geometry in
// B_n (systems/assemble/smoothing_geometry). Counts against Euler's relation, stencil order and
// orientation, a hand-checked two-triangle square, volumes that tile the body, the consistency of the
// smoothed gradients (they reproduce linear fields exactly), race-free colours, the wider coupling of
// edge stencils, and mesh errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <set>
#include <utility>
#include <vector>

#include "engine/core/errors.hpp"
#include "engine/mesh/boundary_edges.hpp"
#include "engine/mesh/cell_domains.hpp"
#include "engine/mesh/generators.hpp"
#include "engine/mesh/smoothing_edges.hpp"
#include "engine/mesh/triangle_geometry.hpp"
#include "systems/assemble/smoothing_geometry.hpp"

namespace loom {
namespace {

using Grad = Eigen::Matrix<double, Eigen::Dynamic, 2>;

struct Mesh {
  MeshData data;
  Nodes<2> nodes;
  Cells cells{CellType::tri3, Formulation::es_up};
  Index n_nodes() const { return nodes.size(); }
};

// A structured rectangle with distorted interior nodes. B_n is X + u_n with u_n affine (so it stays a valid
// mesh); the iterate u is garbage, to show that only u_n is read.
Mesh make_mesh(int nx, int ny, GridPattern pattern, double distortion = 0.2) {
  RectangleSpec spec;
  spec.origin = Vec2(1.0, -2.0);
  spec.size = Vec2(3.0, 2.0);
  spec.nx = nx, spec.ny = ny;
  spec.pattern = pattern;
  Mesh m;
  m.data = generate_rectangle(spec);
  distort_interior_nodes(m.data, distortion, 42);
  m.nodes.X.values() = m.data.X;
  m.nodes.resize(Index(m.data.X.size()));
  Eigen::Matrix2d B;
  B << 0.15, 0.2, -0.1, -0.05;  // u_n = B X + c: F = I + B, det F > 0
  for (Index i = 0; i < m.nodes.size(); ++i) {
    m.nodes.u_n[i] = B * m.nodes.X[i] + Vec2(0.3, -0.7);
    m.nodes.u[i] = Vec2(1e3 * std::sin(double(i)), 1e3);
  }
  m.cells.nodes.values() = m.data.triangles;
  m.cells.body.assign(m.data.n_triangles(), 0);
  return m;
}

double area_n(const Mesh& m, Index t) {
  const Index* c = m.cells.cell_nodes(t);
  return signed_area(m.nodes.position_n(c[0]), m.nodes.position_n(c[1]), m.nodes.position_n(c[2]));
}

const std::vector<GridPattern> kPatterns = {GridPattern::right, GridPattern::alternating, GridPattern::shifted};

void expect_valid_colouring(const Cells& cells, Index n_nodes) {
  const Index n = cells.size();
  ASSERT_EQ(cells.colour.size(), n);
  std::vector<Index> sorted = cells.by_colour;
  std::vector<Index> all(static_cast<std::size_t>(n));
  std::sort(sorted.begin(), sorted.end());
  std::iota(all.begin(), all.end(), 0);
  EXPECT_EQ(sorted, all) << "by_colour is a permutation";
  for (Index k = 0; k < cells.n_colours(); ++k) {
    std::vector<char> taken(std::size_t(n_nodes), 0);
    for (Index i = cells.colour_offsets[std::size_t(k)]; i < cells.colour_offsets[std::size_t(k) + 1]; ++i) {
      const Index c = cells.by_colour[std::size_t(i)];
      EXPECT_EQ(cells.colour[c], k);
      for (int a = 0; a < cells.stride; ++a) {
        EXPECT_FALSE(taken[std::size_t(cells.node(c, a))]) << "colour " << k << " shares node " << cells.node(c, a);
        taken[std::size_t(cells.node(c, a))] = 1;
      }
    }
  }
}

// Every domain: sum_I b~_I = 0 (constants), sum_I x_I (x) b~_I = I (the coordinates), and so the gradient
// of any linear field u = A x + c exactly.
void expect_consistent_gradients(const Mesh& m, const Edges<2>& e) {
  const int S = e.stride();
  Eigen::Matrix2d A;
  A << 0.7, -1.3, 2.1, 0.4;
  const Vec2 c(-0.5, 3.0);
  for (Index k = 0; k < e.size(); ++k) {
    const Eigen::Map<const Grad> b(e.gradient(k), S, 2);
    const double scale = b.cwiseAbs().maxCoeff();
    Vec2 sum = Vec2::Zero();
    Eigen::Matrix2d xb = Eigen::Matrix2d::Zero(), ub = Eigen::Matrix2d::Zero();
    for (int I = 0; I < S; ++I) {
      const Vec2 x = m.nodes.position_n(e.stencil.node(k, I));
      sum += b.row(I).transpose();
      xb += x * b.row(I);
      ub += (A * x + c) * b.row(I);
    }
    EXPECT_LE(sum.norm(), 1e-12 * scale) << "domain " << k;
    EXPECT_LE((xb - Eigen::Matrix2d::Identity()).norm(), 1e-12) << "domain " << k;
    EXPECT_LE((ub - A).norm(), 1e-12 * A.norm()) << "domain " << k;
  }
}

// Distinct (i, j) entries, diagonal included, that a block of stencils couples: the stiffness pattern.
std::set<std::pair<Index, Index>> coupled_pairs(const std::vector<const Cells*>& blocks) {
  std::set<std::pair<Index, Index>> pairs;
  for (const Cells* b : blocks)
    for (Index k = 0; k < b->size(); ++k)
      for (int I = 0; I < b->stride; ++I)
        for (int J = 0; J < b->stride; ++J) pairs.insert({b->node(k, I), b->node(k, J)});
  return pairs;
}

}  // namespace

TEST(SmoothingEdges, HandCheckedTwoTriangleSquare) {
  // Unit square cut along 0-2: triangles (0,1,2) and (0,2,3). The diagonal is met first as side 2-0 of
  // triangle 0, so its stencil is (2, 0, 1, 3).
  Mesh m;
  m.nodes.X.values() = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  m.nodes.resize(4);
  m.cells.nodes.values() = {0, 1, 2, 0, 2, 3};
  m.cells.body.assign(2, 7);
  EdgeDomains d = build_edge_domains(m.cells, 4);
  ASSERT_EQ(d.interior.size(), 1);
  ASSERT_EQ(d.boundary.size(), 4);
  EXPECT_EQ(d.interior.stencil.type, CellType::stencil4);
  EXPECT_EQ(d.boundary.stencil.type, CellType::stencil3);
  EXPECT_EQ(d.interior.stencil.formulation, Formulation::es_up);
  EXPECT_EQ(d.interior.stencil.nodes.values(), (std::vector<Index>{2, 0, 1, 3}));
  EXPECT_EQ(d.interior.stencil.body[0], 7);
  EXPECT_EQ(d.interior.triangles.values(), (std::vector<Index>{0, 1}));
  EXPECT_EQ(d.interior.pressure_weight.values(), (std::vector<double>{0.5, 0.5, 0, 0}));
  // Boundary edges in order of appearance: (0,1) and (1,2) of triangle 0, (2,3) and (3,0) of triangle 1.
  EXPECT_EQ(d.boundary.stencil.nodes.values(), (std::vector<Index>{0, 1, 2, 1, 2, 0, 2, 3, 0, 3, 0, 2}));
  EXPECT_EQ(d.boundary.triangles.values(), (std::vector<Index>{0, kNoIndex, 0, kNoIndex, 1, kNoIndex, 1, kNoIndex}));

  EXPECT_EQ(compute_smoothing_geometry(m.nodes, m.cells, d.interior), 0);
  EXPECT_EQ(compute_smoothing_geometry(m.nodes, m.cells, d.boundary), 0);
  // V = 2 * (1/2) / 3. grad N of (0,1,2): (-1,0), (1,-1), (0,1); of (0,2,3): (0,-1), (1,0), (-1,1); equal
  // areas, so b~ is their mean over the stencil (2, 0, 1, 3).
  EXPECT_DOUBLE_EQ(d.interior.volume_n[0], 1.0 / 3.0);
  Grad expected(4, 2);
  expected << 0.5, 0.5, -0.5, -0.5, 0.5, -0.5, -0.5, 0.5;
  EXPECT_LE((Eigen::Map<const Grad>(d.interior.gradient(0), 4, 2) - expected).norm(), 1e-15);
  EXPECT_LE((d.interior.midpoint[0] - Vec2(0.5, 0.5)).norm(), 1e-15);
  // Boundary edge (0,1): one third of triangle 0, b~ = its gradients.
  EXPECT_DOUBLE_EQ(d.boundary.volume_n[0], 1.0 / 6.0);
  expected.resize(3, 2);
  expected << -1, 0, 1, -1, 0, 1;
  EXPECT_LE((Eigen::Map<const Grad>(d.boundary.gradient(0), 3, 2) - expected).norm(), 1e-15);
  EXPECT_LE((d.boundary.midpoint[0] - Vec2(0.5, 0.0)).norm(), 1e-15);

  Edges<2> t = build_cell_domains<2>(m.cells, 4);
  EXPECT_EQ(compute_smoothing_geometry(m.nodes, m.cells, t), 0);
  EXPECT_EQ(t.stencil.nodes.values(), m.cells.nodes.values());
  EXPECT_EQ(t.triangles.values(), (std::vector<Index>{0, kNoIndex, 1, kNoIndex}));
  EXPECT_DOUBLE_EQ(t.volume_n[0], 0.5);
  EXPECT_LE((Eigen::Map<const Grad>(t.gradient(0), 3, 2) - expected).norm(), 1e-15);
  EXPECT_LE((t.midpoint[1] - Vec2(1.0 / 3, 2.0 / 3)).norm(), 1e-15);
  EXPECT_DOUBLE_EQ(t.pressure_weight[4], 1.0 / 3.0);
}

TEST(SmoothingEdges, CountsOrderAndOrientationFollowTheMesh) {
  for (GridPattern p : kPatterns) {
    const Mesh m = make_mesh(7, 5, p);
    const Index T = m.cells.size(), B = Index(boundary_edges(m.data.triangles, 3).size());
    const EdgeDomains d = build_edge_domains(m.cells, m.n_nodes());
    EXPECT_EQ(d.interior.size(), (3 * T - B) / 2);
    EXPECT_EQ(d.boundary.size(), B);
    EXPECT_EQ(d.interior.size() + d.boundary.size(), (3 * T + B) / 2) << "E = (3T + B) / 2";
    for (const Edges<2>* e : {&d.interior, &d.boundary}) {
      std::pair<Index, int> previous{-1, 0};
      for (Index k = 0; k < e->size(); ++k) {
        const Index t0 = e->triangles[2 * k], t1 = e->triangles[2 * k + 1];
        const Index a = e->stencil.node(k, 0), b = e->stencil.node(k, 1);
        // (a, b, opposite) is triangle t0 itself, counter-clockwise; (b, a, opposite') is t1.
        EXPECT_GT(area_n(m, t0), 0.0);
        EXPECT_NEAR(signed_area(m.nodes.position_n(a), m.nodes.position_n(b), m.nodes.position_n(e->stencil.node(k, 2))), area_n(m, t0), 1e-14);
        if (e->stride() == 4) {
          EXPECT_LT(t0, t1);
          EXPECT_NEAR(signed_area(m.nodes.position_n(b), m.nodes.position_n(a), m.nodes.position_n(e->stencil.node(k, 3))), area_n(m, t1), 1e-14);
        } else {
          EXPECT_EQ(t1, kNoIndex);
        }
        // First-appearance order: (first triangle, side) increases.
        const Index* c = m.cells.cell_nodes(t0);
        const int side = int(std::find(c, c + 3, a) - c);
        ASSERT_LT(side, 3);
        EXPECT_EQ(c[(side + 1) % 3], b);
        EXPECT_LT(previous, std::make_pair(t0, side));
        previous = {t0, side};
      }
    }
    // Deterministic: a rebuild gives the same stores.
    const EdgeDomains again = build_edge_domains(m.cells, m.n_nodes());
    EXPECT_EQ(again.interior.stencil.nodes.values(), d.interior.stencil.nodes.values());
    EXPECT_EQ(again.boundary.stencil.by_colour, d.boundary.stencil.by_colour);
  }
}

TEST(SmoothingEdges, VolumesTileTheBody) {
  for (GridPattern p : kPatterns) {
    Mesh m = make_mesh(16, 12, p);  // > kParallelGrain domains: the parallel path
    EdgeDomains d = build_edge_domains(m.cells, m.n_nodes());
    Edges<2> t = build_cell_domains<2>(m.cells, m.n_nodes());
    EXPECT_EQ(compute_smoothing_geometry(m.nodes, m.cells, d.interior), 0);
    EXPECT_EQ(compute_smoothing_geometry(m.nodes, m.cells, d.boundary), 0);
    EXPECT_EQ(compute_smoothing_geometry(m.nodes, m.cells, t), 0);
    double body = 0.0;
    for (Index e = 0; e < m.cells.size(); ++e) body += area_n(m, e);
    const double edges = std::accumulate(d.interior.volume_n.begin(), d.interior.volume_n.end(), 0.0) +
                         std::accumulate(d.boundary.volume_n.begin(), d.boundary.volume_n.end(), 0.0);
    const double triangles = std::accumulate(t.volume_n.begin(), t.volume_n.end(), 0.0);
    EXPECT_NEAR(edges, body, 1e-12 * body);
    EXPECT_NEAR(triangles, body, 1e-12 * body);
    for (Index k = 0; k < d.interior.size(); ++k)
      EXPECT_NEAR(d.interior.volume_n[k], (area_n(m, d.interior.triangles[2 * k]) + area_n(m, d.interior.triangles[2 * k + 1])) / 3, 1e-14);
    for (Index k = 0; k < d.boundary.size(); ++k) {
      const Vec2 mid = 0.5 * (m.nodes.position_n(d.boundary.stencil.node(k, 0)) + m.nodes.position_n(d.boundary.stencil.node(k, 1)));
      EXPECT_LE((d.boundary.midpoint[k] - mid).norm(), 1e-14);
    }
  }
}

TEST(SmoothingEdges, SmoothedGradientsReproduceLinearFields) {
  for (GridPattern p : kPatterns) {
    Mesh m = make_mesh(16, 12, p);
    EdgeDomains d = build_edge_domains(m.cells, m.n_nodes());
    Edges<2> t = build_cell_domains<2>(m.cells, m.n_nodes());
    compute_smoothing_geometry(m.nodes, m.cells, d.interior);
    compute_smoothing_geometry(m.nodes, m.cells, d.boundary);
    compute_smoothing_geometry(m.nodes, m.cells, t);
    expect_consistent_gradients(m, d.interior);
    expect_consistent_gradients(m, d.boundary);
    expect_consistent_gradients(m, t);
  }
}

TEST(SmoothingEdges, ColoursAreRaceFree) {
  for (GridPattern p : kPatterns) {
    const Mesh m = make_mesh(9, 6, p);
    const EdgeDomains d = build_edge_domains(m.cells, m.n_nodes());
    const Edges<2> t = build_cell_domains<2>(m.cells, m.n_nodes());
    expect_valid_colouring(d.interior.stencil, m.n_nodes());
    expect_valid_colouring(d.boundary.stencil, m.n_nodes());
    expect_valid_colouring(t.stencil, m.n_nodes());
  }
}

TEST(SmoothingEdges, EdgeStencilsCoupleMoreNodesThanTriangles) {
  // 8x8 "right" mesh, valence-6 interior nodes: each interior edge adds the pair of its opposite vertices,
  // (81 + 2 * (208 + 176)) / (81 + 2 * 208) = 849 / 497 = 1.71 entries of the stiffness pattern.
  for (GridPattern p : {GridPattern::right, GridPattern::alternating}) {
    const Mesh m = make_mesh(8, 8, p, 0.0);
    const EdgeDomains d = build_edge_domains(m.cells, m.n_nodes());
    const std::size_t es = coupled_pairs({&d.interior.stencil, &d.boundary.stencil}).size();
    const std::size_t fem = coupled_pairs({&m.cells}).size();
    const double ratio = double(es) / double(fem);
    const double off_diagonal = double(es - std::size_t(m.n_nodes())) / double(fem - std::size_t(m.n_nodes()));
    std::printf("pattern %d: ES couples %zu node pairs, FEM %zu: ratio %.3f (%.3f without the diagonal)\n", int(p), es, fem,
                ratio, off_diagonal);
    EXPECT_GE(ratio, 1.5);
    EXPECT_LE(ratio, 2.2);
    if (p == GridPattern::right) {
      EXPECT_EQ(es, 849u);
      EXPECT_EQ(fem, 497u);
    }
  }
}

TEST(SmoothingEdges, InvertedTrianglesAreCounted) {
  // Node 1 of the square moved across the diagonal: triangle 0 inverts, triangle 1 does not.
  Mesh m;
  m.nodes.X.values() = {Vec2(0, 0), Vec2(-0.5, 1), Vec2(1, 1), Vec2(0, 1)};
  m.nodes.resize(4);
  m.cells.nodes.values() = {0, 1, 2, 0, 2, 3};
  m.cells.body.assign(2, 0);
  EdgeDomains d = build_edge_domains(m.cells, 4);
  Edges<2> t = build_cell_domains<2>(m.cells, 4);
  EXPECT_EQ(compute_smoothing_geometry(m.nodes, m.cells, d.interior), 1);
  EXPECT_EQ(compute_smoothing_geometry(m.nodes, m.cells, d.boundary), 2);
  EXPECT_EQ(compute_smoothing_geometry(m.nodes, m.cells, t), 1);
}

TEST(SmoothingEdges, AnEdgeOfThreeTrianglesIsAMeshError) {
  Cells cells;
  cells.nodes.values() = {0, 1, 2, 1, 0, 3, 0, 1, 4};
  cells.body.assign(3, 0);
  try {
    build_edge_domains(cells, 5);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("nodes 0 and 1"), std::string::npos) << what;
  }
  cells.nodes.values() = {0, 1, 1};
  cells.body.assign(1, 0);
  EXPECT_THROW(build_edge_domains(cells, 2), InputError);
}

}  // namespace loom
