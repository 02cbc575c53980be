#include "systems/remesh/delaunay_check.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "engine/mesh/tet_adjacency.hpp"
#include "engine/mesh/tet_mesh.hpp"
#include "systems/remesh/point_in_tets.hpp"
#include "systems/remesh/remesh_3d.hpp"
#include "systems/remesh/surface_graph.hpp"

namespace loom {
namespace {


// Whether e lies inside the circumsphere of (a, b, c, d) by more than kDelaunayMargin of its squared radius (a flat
// cell counts as failing). Not CGAL's exact predicate, and with a margin: five cospherical points (a BCC surface
// pyramid, a right prism of an extruded mesh) leave a choice that any deformation decides one way or the other; an
// exact test would recut them as soon as the body strains, and back when it relaxes (churn, and a transfer of the
// history with every recut). A face whose vertex across lies inside by less than 0.1 % of R^2 -- a strain of about
// 1e-3 across a cospherical cell -- is kept; a flow that strains further is remeshed as before.
constexpr double kDelaunayMargin = 1e-3;

}  // namespace

bool strictly_inside_sphere(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& e) {
  const Vec3 u = b - a, v = c - a, w = d - a;
  const double det = u.dot(v.cross(w));
  if (det == 0.0) return true;
  const Vec3 centre = a + (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) + w.squaredNorm() * u.cross(v)) / (2.0 * det);
  const double r2 = (centre - a).squaredNorm();
  return (e - centre).squaredNorm() < r2 * (1.0 - kDelaunayMargin);
}

namespace {

double circumradius(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u = b - a, v = c - a, w = d - a;
  const double det = u.dot(v.cross(w));
  if (det == 0.0) return INFINITY;
  return ((u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) + w.squaredNorm() * u.cross(v)) / (2.0 * det)).norm();
}

}  // namespace

bool faces_delaunay(const std::vector<Vec3>& x, const std::vector<Index>& tets, const std::vector<std::array<Index, 4>>& nbr) {
  for (std::size_t t = 0; t < nbr.size(); ++t)
    for (std::size_t k = 0; k < 4; ++k) {
      const Index o = nbr[t][k];
      if (o < 0 || std::size_t(o) < t) continue;  // each interior face once, tested against the cell with the lower index
      const Index* c = &tets[4 * t];
      const Index* across = &tets[4 * std::size_t(o)];
      Index apex = across[0];  // the corner of o off the shared face
      for (int m = 0; m < 4; ++m)
        if (across[m] != c[kTetFaces[k][0]] && across[m] != c[kTetFaces[k][1]] && across[m] != c[kTetFaces[k][2]]) apex = across[m];
      if (strictly_inside_sphere(x[std::size_t(c[0])], x[std::size_t(c[1])], x[std::size_t(c[2])], x[std::size_t(c[3])], x[std::size_t(apex)]))
        return false;
    }
  return true;
}

bool no_tear(const std::vector<Vec3>& x, const std::vector<Index>& tets, const std::vector<std::array<Index, 4>>& nbr, double alpha,
             const std::vector<double>& average_distance, double l_char) {
  for (std::size_t t = 0; t < nbr.size(); ++t) {
    if (std::any_of(nbr[t].begin(), nbr[t].end(), [](Index o) { return o < 0; })) continue;  // a face on the surface
    const Index* v = &tets[4 * t];
    double l = l_char;
    if (!average_distance.empty())
      l = (average_distance[std::size_t(v[0])] + average_distance[std::size_t(v[1])] + average_distance[std::size_t(v[2])] +
           average_distance[std::size_t(v[3])]) / 4.0;
    if (alpha * l < circumradius(x[std::size_t(v[0])], x[std::size_t(v[1])], x[std::size_t(v[2])], x[std::size_t(v[3])])) return false;
  }
  return true;
}

bool no_merge_possible(const std::vector<Vec3>& x, const std::vector<Index>& tets, const std::vector<std::array<Index, 4>>& nbr, double alpha,
                       const std::vector<double>& average_distance, double l_char) {
  std::vector<std::array<Index, 3>> faces;
  for (const BoundaryFace& f : boundary_faces(tets, nbr)) faces.push_back(f.nodes);
  const SurfaceGraph surface(Index(x.size()), faces, x);
  std::vector<Index> points;
  double reach = 0.0;
  auto l_of = [&](Index v) { return average_distance.empty() ? l_char : average_distance[std::size_t(v)]; };
  for (Index v = 0; v < Index(x.size()); ++v)
    if (surface.on_surface(v)) points.push_back(v), reach = std::max(reach, alpha * l_of(v));
  if (points.empty() || !(reach > 0.0)) return true;
  // Buckets of side `reach`: a pair within reach lies in neighbouring buckets.
  Vec3 lo = x[std::size_t(points[0])];
  for (Index v : points) lo = lo.cwiseMin(x[std::size_t(v)]);
  auto key = [&](const Vec3& p) {
    return std::array<long, 3>{long(std::floor((p.x() - lo.x()) / reach)), long(std::floor((p.y() - lo.y()) / reach)),
                               long(std::floor((p.z() - lo.z()) / reach))};
  };
  std::vector<std::pair<std::array<long, 3>, Index>> buckets;
  for (Index v : points) buckets.emplace_back(key(x[std::size_t(v)]), v);
  std::sort(buckets.begin(), buckets.end());
  std::optional<PointInTets> inside;
  for (Index a : points) {
    const auto k = key(x[std::size_t(a)]);
    for (long dz = -1; dz <= 1; ++dz)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dx = -1; dx <= 1; ++dx) {
          const std::array<long, 3> nk{k[0] + dx, k[1] + dy, k[2] + dz};
          auto it = std::lower_bound(buckets.begin(), buckets.end(), std::make_pair(nk, Index(-1)));
          for (; it != buckets.end() && it->first == nk; ++it) {
            const Index b = it->second;
            if (b <= a) continue;
            const double gap = (x[std::size_t(a)] - x[std::size_t(b)]).norm();
            if (gap > alpha * 0.5 * (l_of(a) + l_of(b))) continue;
            const bool apart = surface.component(a) != surface.component(b) ||
                               surface.distance_along(a, b, kMergeDetour3d * gap) >= kMergeDetour3d * gap;
            if (!apart) continue;
            if (!inside) inside.emplace(x, tets, &nbr);
            if (!inside->contains_near(0.5 * (x[std::size_t(a)] + x[std::size_t(b)]), a)) return false;
          }
        }
  }
  return true;
}

}  // namespace loom
