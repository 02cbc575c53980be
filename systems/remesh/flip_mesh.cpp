// FlipMesh's moves (flip_mesh.hpp): linking the faces, the 2-3 flip, the ring around an edge, edge removal by
// dynamic programming, and replacing a cavity.
#include "systems/remesh/flip_mesh.hpp"

#include "engine/core/errors.hpp"
#include "engine/mesh/tet_adjacency.hpp"

namespace loom::flips {

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

}  // namespace loom::flips
