// Flips on loom's own arrays (not CGAL's Triangulation_3::flip, which would break its Delaunay object; spec
// §3 R3.4). The mesh is held as tets + face neighbours; a flip replaces a cavity (2 tets, or the n tets around
// an edge) by new tets with the same outer faces, so the neighbours outside it are relinked face by face.
#include "systems/remesh/tet_flips.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>

#include <Eigen/Geometry>  // cross

#include "engine/core/errors.hpp"
#include "engine/core/parallel.hpp"
#include "engine/mesh/tet_adjacency.hpp"
#include "engine/mesh/tet_mesh.hpp"  // kTetFaces
#include "systems/remesh/delaunay_check.hpp"  // strictly_inside_sphere

namespace loom {
namespace {

using Tet = std::array<Index, 4>;
using Face = std::array<Index, 3>;

constexpr int kMaxRing = 7;  // Shewchuk: larger rings rarely help and the DP grows as n^3
// A new tet must have 6V > kMinVolume l_max^3 (regular: 0.71), far above the round-off of 6V (~1e-16 l_max^3 times
// |x| / l_max): it is then positive in exact arithmetic, and positive new tets with the cavity's outer faces tile
// the cavity exactly. A bound on q would not do: a needle of width w has q ~ w / l but 6V ~ w^2 l.
constexpr double kMinVolume = 1e-12;
// "Strictly better" beyond the round-off of q, so that no flip and its reverse can both be accepted.
constexpr double kMargin = 1e-12;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kMaxRepairPasses = 50;
constexpr double kSliver = 0.1;  // q below which a tet is a sliver (the spec's measure; Remesh3dResult::slivers)  // Lawson's flips terminate; a cap against a cycle the margins could allow

// The bar the new tets of a transformation must clear, from the worst q of the tets it replaces: the sliver pass asks
// for strictly better; the Delaunay repair for positive tets none of which is worse than both `floor` (the sliver
// threshold) and the worst it replaces, so that it never undoes what the sliver pass did.
struct Bar {
  bool improve = true;
  double floor = 0.0;
  double operator()(double old_min) const { return improve ? old_min + kMargin : std::min(floor, old_min) - kMargin; }
};

// Sorts v ascending; returns true when the permutation was odd.
template <std::size_t N>
bool sort_odd(std::array<Index, N>& v) {
  bool odd = false;
  for (std::size_t i = 1; i < N; ++i)
    for (std::size_t j = i; j > 0 && v[j - 1] > v[j]; --j) std::swap(v[j - 1], v[j]), odd = !odd;
  return odd;
}

Face sorted_face(Index a, Index b, Index c) {
  Face f{a, b, c};
  sort_odd(f);
  return f;
}

// A transformation found around one bad tet: the tets it removes and those it creates.
struct Candidate {
  int kind = 0;               // 0 none, 1 flip 2-3, 2 edge removal
  std::array<Index, 3> key{};  // sorted face (2-3) or edge (a, b, -1): tie-break independent of storage order
  double old_min = kInf, new_min = -kInf;
  std::vector<Index> old_tets;
  std::vector<Tet> new_tets;
  bool better_than(const Candidate& o) const {
    if (o.kind == 0) return true;
    if (new_min != o.new_min) return new_min > o.new_min;
    return std::tie(kind, key) < std::tie(o.kind, o.key);
  }
};

// The closed ring of tets around edge (a, b), a < b: ring points p ordered so that every (a, b, p_i, p_i+1) is
// positive, starting at the smallest point index.
struct Ring {
  Index a = kNoIndex, b = kNoIndex;
  std::vector<Index> p, tets;
};

class FlipMesh {
 public:
  FlipMesh(const std::vector<Vec3>& x, const std::vector<Index>& flat, std::vector<std::array<Index, 4>>* neighbours) : x_(x) {
    const std::size_t n = flat.size() / 4;
    tets_.resize(n);
    for (std::size_t t = 0; t < n; ++t) tets_[t] = {flat[4 * t], flat[4 * t + 1], flat[4 * t + 2], flat[4 * t + 3]};
    q_.resize(n);
    for_each_index(Index(n), [&](Index t) { q_[std::size_t(t)] = quality(tets_[std::size_t(t)]); });
    alive_.assign(n, 1);
    if (neighbours && neighbours->size() == n) nbr_ = std::move(*neighbours);
    else link_faces(flat);
  }

  // q computed on the sorted corners (sign fixed by the parity), so that it depends on the tet alone.
  double quality(Tet t) const {
    const bool odd = sort_odd(t);
    const double q = tet_quality(x_[t[0]], x_[t[1]], x_[t[2]], x_[t[3]]);
    return odd ? -q : q;
  }

  std::vector<Index> bad_tets(double threshold) const {
    struct Bad {
      double q;
      Tet sorted;
      Index tet;
    };
    std::vector<Bad> bad;
    for (Index t = 0; t < Index(tets_.size()); ++t)
      if (alive_[t] && q_[t] < threshold) bad.push_back({q_[t], tets_[t], t}), sort_odd(bad.back().sorted);
    std::sort(bad.begin(), bad.end(),
              [](const Bad& r, const Bad& s) { return std::tie(r.q, r.sorted) < std::tie(s.q, s.sorted); });
    std::vector<Index> order(bad.size());
    for (std::size_t i = 0; i < bad.size(); ++i) order[i] = bad[i].tet;
    return order;
  }

  // q of a tet a flip would create, or -inf when it is not safely positive (kMinVolume).
  double new_quality(Tet t) const {
    const double q = quality(t);
    const bool odd = sort_odd(t);
    const Vec3 &a = x_[t[0]], &b = x_[t[1]], &c = x_[t[2]], &d = x_[t[3]];
    const double det = (odd ? -1.0 : 1.0) * (b - a).dot((c - a).cross(d - a));
    const double l2 = std::max({(b - a).squaredNorm(), (c - a).squaredNorm(), (d - a).squaredNorm(),
                                (c - b).squaredNorm(), (d - b).squaredNorm(), (d - c).squaredNorm()});
    return det > kMinVolume * l2 * std::sqrt(l2) ? q : -kInf;
  }

  bool alive(Index t) const { return alive_[t] != 0; }
  // The worse q of t and the tet across its face f.
  double worst_across(Index t, int f) const { return std::min(q_[t], q_[nbr_[t][f]]); }

  // The best improving transformation involving tet t (kind 0 when none improves its cavity).
  Candidate best_around(Index t) const {
    Candidate best;
    // Candidates come back only when they improve their cavity.
    for (int f = 0; f < 4; ++f) {
      Candidate c = flip23(t, f, Bar{});
      if (c.kind && c.better_than(best)) best = std::move(c);
    }
    static constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    for (const auto& e : kEdges) {
      Candidate c = edge_removal(t, e[0], e[1], Bar{}, kMaxRing);
      if (c.kind && c.better_than(best)) best = std::move(c);
    }
    return best;
  }

  // Whether the face of t opposite corner f is not locally Delaunay: the apex across it inside t's circumsphere, or
  // t's own apex inside the other's, by more than the margin of strictly_inside_sphere (either, so that a repaired
  // mesh passes R3.7 (faces_delaunay) where it passes this).
  bool fails_delaunay(Index t, int f) const {
    const Index o = nbr_[t][f];
    if (o == kNoIndex) return false;
    const Tet &T = tets_[t], &O = tets_[o];
    const Index apex_o = apex(O, T, f), apex_t = T[f];
    return strictly_inside_sphere(x_[T[0]], x_[T[1]], x_[T[2]], x_[T[3]], x_[apex_o]) ||
           strictly_inside_sphere(x_[O[0]], x_[O[1]], x_[O[2]], x_[O[3]], x_[apex_t]);
  }

  // The failing interior faces, each once (from its lower tet), in the order of their sorted corners.
  std::vector<std::pair<Index, int>> failing_faces() const {
    std::vector<std::pair<Face, std::pair<Index, int>>> found;
    for (Index t = 0; t < Index(tets_.size()); ++t) {
      if (!alive_[t]) continue;
      for (int f = 0; f < 4; ++f) {
        const Index o = nbr_[t][f];
        if (o == kNoIndex || o < t || !fails_delaunay(t, f)) continue;
        const Tet& T = tets_[t];
        found.push_back({sorted_face(T[kTetFaces[f][0]], T[kTetFaces[f][1]], T[kTetFaces[f][2]]), {t, f}});
      }
    }
    std::sort(found.begin(), found.end());
    std::vector<std::pair<Index, int>> out;
    for (const auto& r : found) out.push_back(r.second);
    return out;
  }

  // Lawson's flip for a failing face: 2-3 where the two tets' union is convex across it, else 3-2 around an edge of
  // the face held by three tets, or 4-4 around one held by four (a near-coplanar pair of faces, as the rectangles
  // of an extruded prism); the best of those that clear `bar` and whose new tets are locally Delaunay among
  // themselves (kind 0: none).
  Candidate lawson_flip(Index t, int f, const Bar& bar) const {
    Candidate best = flip23(t, f, bar);
    if (best.kind && !delaunay_inside(best.new_tets)) best = Candidate{};
    for (int i = 0; i < 3; ++i) {
      Candidate c = edge_removal(t, kTetFaces[f][i], kTetFaces[f][(i + 1) % 3], bar, 4);
      if (c.kind && delaunay_inside(c.new_tets) && c.better_than(best)) best = std::move(c);
    }
    return best;
  }

  // Whether the faces two of `tets` share pass the in-sphere test both ways.
  bool delaunay_inside(const std::vector<Tet>& tets) const {
    for (std::size_t i = 0; i < tets.size(); ++i)
      for (std::size_t j = i + 1; j < tets.size(); ++j) {
        int shared = 0;
        Index apex_i = kNoIndex, apex_j = kNoIndex;
        for (Index v : tets[i]) shared += std::find(tets[j].begin(), tets[j].end(), v) != tets[j].end();
        if (shared != 3) continue;
        for (Index v : tets[i])
          if (std::find(tets[j].begin(), tets[j].end(), v) == tets[j].end()) apex_i = v;
        for (Index v : tets[j])
          if (std::find(tets[i].begin(), tets[i].end(), v) == tets[i].end()) apex_j = v;
        const Tet &a = tets[i], &b = tets[j];
        if (strictly_inside_sphere(x_[a[0]], x_[a[1]], x_[a[2]], x_[a[3]], x_[apex_j]) ||
            strictly_inside_sphere(x_[b[0]], x_[b[1]], x_[b[2]], x_[b[3]], x_[apex_i]))
          return false;
      }
    return true;
  }

  void apply(const Candidate& c);

  void write(std::vector<Index>& flat, std::size_t n_input, std::vector<Index>* origin, std::vector<std::array<Index, 4>>* neighbours) const {
    flat.clear();
    if (origin) origin->clear();
    std::vector<Index> renumber(tets_.size(), kNoIndex);
    for (std::size_t t = 0; t < tets_.size(); ++t)
      if (alive_[t]) {
        renumber[t] = Index(flat.size() / 4);
        flat.insert(flat.end(), tets_[t].begin(), tets_[t].end());
        if (origin) origin->push_back(t < n_input ? Index(t) : kNoIndex);
      }
    if (!neighbours) return;
    neighbours->clear();
    for (std::size_t t = 0; t < tets_.size(); ++t)
      if (alive_[t]) {
        std::array<Index, 4> n = nbr_[t];
        for (Index& o : n) o = o < 0 ? kNoIndex : renumber[std::size_t(o)];
        neighbours->push_back(n);
      }
  }

  void count(double threshold, Index& below, double& worst) const {
    below = 0, worst = 1.0;
    for (std::size_t t = 0; t < tets_.size(); ++t)
      if (alive_[t]) below += q_[t] < threshold, worst = std::min(worst, q_[t]);
  }

 private:
  void link_faces(const std::vector<Index>& flat);
  Candidate flip23(Index t, int f, const Bar& bar) const;
  Candidate edge_removal(Index t, int la, int lb, const Bar& bar, int max_ring) const;
  bool ring_around(Index t, int la, int lb, Ring& ring) const;
  // The corner of O off the face of T opposite T's corner f.
  static Index apex(const Tet& O, const Tet& T, int f) {
    for (Index v : O)
      if (v != T[kTetFaces[f][0]] && v != T[kTetFaces[f][1]] && v != T[kTetFaces[f][2]]) return v;
    return kNoIndex;
  }
  double old_min(const std::vector<Index>& tets) const {
    double m = kInf;
    for (Index t : tets) m = std::min(m, q_[t]);
    return m;
  }

  const std::vector<Vec3>& x_;
  std::vector<Tet> tets_;
  std::vector<std::array<Index, 4>> nbr_;  // tet across the face opposite each corner, kNoIndex on the surface
  std::vector<double> q_;
  std::vector<char> alive_;
};

// Faces matched by tet_adjacency (deterministic, no hashing). A face in more than two tets (a non-manifold input) is
// left unlinked, i.e. surface, so no flip crosses it.
void FlipMesh::link_faces(const std::vector<Index>& flat) {
  nbr_ = tet_face_neighbours(flat);
  for (auto& n : nbr_)
    for (Index& o : n)
      if (o == kNonManifold) o = kNoIndex;
}

// 2-3 flip across the face of t opposite corner f: the new edge joins the two apexes. Face (f0, f1, f2) is
// outward from t, so (d1, f0, f1, f2) is positive and the new tets are (d1, d2, f_k, f_k+1).
Candidate FlipMesh::flip23(Index t, int f, const Bar& bar) const {
  Candidate c;
  const Index o = nbr_[t][f];
  if (o == kNoIndex) return c;
  const Tet& T = tets_[t];
  const std::array<Index, 3> fv{T[kTetFaces[f][0]], T[kTetFaces[f][1]], T[kTetFaces[f][2]]};
  Index d2 = kNoIndex;
  for (Index v : tets_[o])
    if (v != fv[0] && v != fv[1] && v != fv[2]) d2 = v;
  c.old_tets = {t, o};
  c.old_min = old_min(c.old_tets);
  const double min_q = bar(c.old_min);
  double m = kInf;
  for (int k = 0; k < 3; ++k) {
    c.new_tets.push_back({T[f], d2, fv[k], fv[(k + 1) % 3]});
    m = std::min(m, new_quality(c.new_tets.back()));
    if (m <= min_q) return Candidate{};  // no improvement: skip the rest
  }
  c.kind = 1, c.new_min = m, c.key = sorted_face(fv[0], fv[1], fv[2]);
  return c;
}

// Walks across the faces holding edge (a, b) from tet t; false when the ring opens (surface, or a
// non-manifold edge) or holds more than kMaxRing tets.
bool FlipMesh::ring_around(Index t, int la, int lb, Ring& ring) const {
  const Tet& T = tets_[t];
  int lc = 0;
  while (lc == la || lc == lb) ++lc;
  const int ld = 6 - la - lb - lc;
  const Index a = T[la], b = T[lb];
  // (a, b, T[ld], T[lc]) is positive when the permutation (la, lb, ld, lc) of the stored order is even.
  std::array<Index, 4> perm{la, lb, ld, lc};
  const bool reversed = sort_odd(perm);
  std::vector<Index> p{T[ld], T[lc]}, tets{t};
  Index cur = t, ahead = T[lc];  // the ring point whose far face we cross next
  Index behind = T[ld];
  for (;;) {
    int far = 0;  // the corner of cur opposite the face (a, b, ahead)
    while (tets_[cur][far] == a || tets_[cur][far] == b || tets_[cur][far] == ahead) ++far;
    if (tets_[cur][far] != behind) return false;  // not a manifold ring (cannot happen in a valid mesh)
    const Index next = nbr_[cur][far];
    if (next == kNoIndex) return false;
    if (next == t) break;
    if (Index(tets.size()) == kMaxRing) return false;
    Index e = kNoIndex;
    for (Index v : tets_[next])
      if (v != a && v != b && v != ahead) e = v;
    tets.push_back(next), behind = ahead, ahead = e, cur = next;
    if (e != p.front()) p.push_back(e);
  }
  if (tets.size() < 3 || p.size() != tets.size()) return false;
  if (reversed) std::reverse(p.begin(), p.end());
  ring.a = a, ring.b = b;
  if (a > b) std::swap(ring.a, ring.b), std::reverse(p.begin(), p.end());  // swapping a, b flips the orientation
  const auto first = std::min_element(p.begin(), p.end());
  std::rotate(p.begin(), first, p.end());
  ring.p = std::move(p), ring.tets = std::move(tets);
  return true;
}

// Shewchuk's edge removal: the ring polygon p_0..p_n-1 is triangulated, each triangle (p_i, p_k, p_j), i < k < j,
// giving tets (a, p_i, p_k, p_j) and (b, p_i, p_j, p_k). Dynamic programming over sub-polygons p_i..p_j
// (Klincsek): best[i][j] = max over k of min(best[i][k], best[k][j], q of the two tets of triangle (i, k, j)),
// the largest worst quality any triangulation of that sub-polygon gives; best[0][n-1] is the optimum.
Candidate FlipMesh::edge_removal(Index t, int la, int lb, const Bar& bar, int max_ring) const {
  Candidate c;
  Ring r;
  if (!ring_around(t, la, lb, r) || int(r.tets.size()) > max_ring) return c;
  c.old_tets = r.tets;
  c.old_min = old_min(c.old_tets);
  const double min_q = bar(c.old_min);
  const int n = int(r.p.size());
  std::array<std::array<double, kMaxRing>, kMaxRing> best;
  std::array<std::array<int, kMaxRing>, kMaxRing> split;
  for (int i = 0; i + 1 < n; ++i) best[i][i + 1] = kInf;
  for (int len = 2; len < n; ++len)
    for (int i = 0; i + len < n; ++i) {
      const int j = i + len;
      best[i][j] = -kInf, split[i][j] = -1;  // -inf: nothing above min_q
      for (int k = i + 1; k < j; ++k) {
        // Bound: a split is dropped as soon as it cannot beat both min_q and the best split so far.
        const double need = std::max(best[i][j], min_q);
        double v = std::min(best[i][k], best[k][j]);
        if (v > need) v = std::min(v, new_quality({r.a, r.p[i], r.p[k], r.p[j]}));
        if (v > need) v = std::min(v, new_quality({r.b, r.p[i], r.p[j], r.p[k]}));
        if (v > need) best[i][j] = v, split[i][j] = k;
      }
    }
  if (split[0][n - 1] < 0) return c;
  std::vector<std::array<int, 2>> stack{{0, n - 1}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j - i < 2) continue;
    const int k = split[i][j];
    c.new_tets.push_back({r.a, r.p[i], r.p[k], r.p[j]});
    c.new_tets.push_back({r.b, r.p[i], r.p[j], r.p[k]});
    stack.push_back({i, k}), stack.push_back({k, j});
  }
  c.kind = 2, c.new_min = best[0][n - 1], c.key = {r.a, r.b, kNoIndex};
  return c;
}

// Replaces the cavity: new tets are appended, their faces linked among themselves or, for the cavity's outer
// faces, to the tet outside (whose back link is redirected) or to nothing (surface).
void FlipMesh::apply(const Candidate& c) {
  struct Outer {
    Face f;
    Index tet;
    int local;
  };
  std::vector<Outer> outer;
  const auto in_cavity = [&](Index s) {
    return std::find(c.old_tets.begin(), c.old_tets.end(), s) != c.old_tets.end();
  };
  for (Index t : c.old_tets)
    for (int i = 0; i < 4; ++i) {
      const Index o = nbr_[t][i];
      if (o != kNoIndex && in_cavity(o)) continue;
      const auto& v = kTetFaces[i];
      int back = -1;
      if (o != kNoIndex)
        for (int j = 0; j < 4; ++j)
          if (nbr_[o][j] == t) back = j;
      outer.push_back({sorted_face(tets_[t][v[0]], tets_[t][v[1]], tets_[t][v[2]]), o, back});
    }
  for (Index t : c.old_tets) alive_[t] = 0;
  const Index first = Index(tets_.size());
  std::vector<Face> faces;  // of the new tets, 4 per tet
  for (const Tet& T : c.new_tets) {
    tets_.push_back(T), q_.push_back(quality(T)), alive_.push_back(1);
    nbr_.push_back({kNoIndex, kNoIndex, kNoIndex, kNoIndex});
    for (const auto& v : kTetFaces) faces.push_back(sorted_face(T[v[0]], T[v[1]], T[v[2]]));
  }
  std::size_t n_outer = 0;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const Index t = first + Index(i / 4);
    const int local = int(i % 4);
    std::size_t j = 0;  // the same face in another new tet
    while (j < faces.size() && (j == i || faces[j] != faces[i])) ++j;
    if (j < faces.size()) {
      nbr_[t][local] = first + Index(j / 4);
      continue;
    }
    const auto o = std::find_if(outer.begin(), outer.end(), [&](const Outer& r) { return r.f == faces[i]; });
    LOOM_ASSERT(o != outer.end(), "a new tet's face is neither inside the cavity nor on its boundary");
    ++n_outer;
    nbr_[t][local] = o->tet;
    if (o->tet != kNoIndex) nbr_[o->tet][o->local] = t;
  }
  LOOM_ASSERT(n_outer == outer.size(), "the new tets do not close the cavity");
  (void)n_outer;
}

}  // namespace

double tet_quality(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u = b - a, v = c - a, w = d - a;
  const Vec3 vw = v.cross(w), wu = w.cross(u), uv = u.cross(v);
  const double det = u.dot(vw);  // 6 V
  // Circumcentre - a = n / (2 det), so R = |n| / (2 |det|); r_in = 3V / S = |det| / (2 S).
  const Vec3 n = u.squaredNorm() * vw + v.squaredNorm() * wu + w.squaredNorm() * uv;
  const double two_s = vw.norm() + wu.norm() + uv.norm() + (v - u).cross(w - u).norm();  // 2 S
  const double den = two_s * n.norm();
  if (!(den > 0.0)) return 0.0;
  return 6.0 * det * std::abs(det) / den;  // 3 r_in / R = 6 det^2 / (2S |n|), with the sign of det
}

namespace {

// R3.4's passes on a mesh: each over the tets below the threshold, worst first.
void remove_slivers(FlipMesh& mesh, const FlipSettings& settings, FlipStats& stats) {
  mesh.count(settings.threshold, stats.below_before, stats.worst_before);
  for (int pass = 0; pass < settings.max_passes; ++pass) {
    const std::vector<Index> bad = mesh.bad_tets(settings.threshold);
    if (bad.empty()) break;
    ++stats.passes;
    Index done = 0;
    for (Index t : bad) {
      if (!mesh.alive(t)) continue;  // replaced by an earlier flip of this pass
      const Candidate c = mesh.best_around(t);
      if (c.kind == 0) continue;
      mesh.apply(c);
      ++done;
      if (c.kind == 1) ++stats.flips23;
      else if (c.old_tets.size() == 3) ++stats.flips32;
      else ++stats.edge_removals;
    }
    if (done == 0) break;
  }
  mesh.count(settings.threshold, stats.below_after, stats.worst_after);
}

}  // namespace

FlipStats improve_by_flips(const std::vector<Vec3>& points, std::vector<Index>& tets, const FlipSettings& settings,
                           std::vector<Index>* origin, std::vector<std::array<Index, 4>>* neighbours) {
  const std::size_t n_input = tets.size() / 4;
  FlipMesh mesh(points, tets, neighbours);
  FlipStats stats;
  remove_slivers(mesh, settings, stats);
  mesh.write(tets, n_input, origin, neighbours);
  return stats;
}

DelaunayRepairStats repair_delaunay(const std::vector<Vec3>& points, std::vector<Index>& tets, const FlipSettings& slivers,
                                    std::vector<std::array<Index, 4>>* neighbours) {
  const std::size_t n_input = tets.size() / 4;
  FlipMesh mesh(points, tets, neighbours);
  const double floor = slivers.threshold;
  const Bar bar{false, floor};
  DelaunayRepairStats stats;
  for (int pass = 0; pass < kMaxRepairPasses; ++pass) {
    const std::vector<std::pair<Index, int>> failing = mesh.failing_faces();
    if (failing.empty()) break;
    ++stats.passes;
    Index done = 0;
    for (const auto& [t, f] : failing) {
      if (!mesh.alive(t) || !mesh.fails_delaunay(t, f)) continue;  // an earlier flip of this pass replaced or fixed it
      const Candidate c = mesh.lawson_flip(t, f, bar);
      if (c.kind == 0) continue;
      mesh.apply(c);
      ++done;
    }
    stats.flips += done;
    if (done == 0) break;
  }
  if (stats.flips > 0 && slivers.threshold > 0.0) remove_slivers(mesh, slivers, stats.slivers);
  // What is left: a face whose flip only the quality bar refuses is kept (the sliver pass would undo the flip), and
  // one that no flip mends between two tets that are not slivers; one that no flip mends beside a sliver is stuck.
  const Bar positive{false, -kInf};
  for (const auto& [t, f] : mesh.failing_faces()) {
    ++stats.failing_after;
    stats.stuck += mesh.worst_across(t, f) < std::min(floor, kSliver) && mesh.lawson_flip(t, f, positive).kind == 0;
  }
  mesh.write(tets, n_input, nullptr, neighbours);
  return stats;
}

}  // namespace loom
