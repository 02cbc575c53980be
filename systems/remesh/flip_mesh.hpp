// The mesh the 3D remesh's flips work on (tet_flips.hpp: the sliver pass R3.4 and the Delaunay repair R3.8), on
// loom's own arrays, not CGAL's Triangulation_3::flip, which would break its Delaunay object (spec §3 R3.4). The
// mesh is held as tets + face neighbours; a flip replaces a cavity (2 tets, or the n tets around an edge) by new tets
// with the same outer faces, so the neighbours outside it are relinked face by face. Internal to loom_remesh.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>
#include <vector>

#include <Eigen/Geometry>  // cross

#include "engine/core/parallel.hpp"
#include "engine/core/types.hpp"
#include "engine/mesh/tet_mesh.hpp"  // kTetFaces
#include "systems/remesh/delaunay_check.hpp"  // strictly_inside_sphere
#include "systems/remesh/tet_flips.hpp"       // tet_quality

namespace loom::flips {

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

inline Face sorted_face(Index a, Index b, Index c) {
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
    return fails_either_way(T, O, apex(O, T, f), T[f]);
  }

  // The shared face of a and b fails the in-sphere test: b's apex inside a's circumsphere, or a's inside b's.
  bool fails_either_way(const Tet& a, const Tet& b, Index apex_b, Index apex_a) const {
    return strictly_inside_sphere(x_[a[0]], x_[a[1]], x_[a[2]], x_[a[3]], x_[apex_b]) ||
           strictly_inside_sphere(x_[b[0]], x_[b[1]], x_[b[2]], x_[b[3]], x_[apex_a]);
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
        if (fails_either_way(tets[i], tets[j], apex_j, apex_i)) return false;
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


}  // namespace loom::flips
