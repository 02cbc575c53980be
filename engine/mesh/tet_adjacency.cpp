#include "engine/mesh/tet_adjacency.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

#include "engine/mesh/tet_mesh.hpp"  // kTetFaces

namespace loom {
namespace {

template <std::size_t N>
void sort_small(std::array<Index, N>& v) {
  for (std::size_t i = 1; i < N; ++i)
    for (std::size_t j = i; j > 0 && v[j - 1] > v[j]; --j) std::swap(v[j - 1], v[j]);
}

std::size_t point_count(const std::vector<Index>& tets) {
  Index top = -1;
  for (Index v : tets) top = std::max(top, v);
  return std::size_t(top + 1);
}

// Counting sort of records into buckets by a key in [0, n): `first` gets the n + 1 bucket starts, `out` the records,
// in input order within each bucket.
template <typename Record, typename KeyOf>
void bucket_by(std::size_t n, const std::vector<Record>& records, KeyOf key_of, std::vector<Index>& first, std::vector<Record>& out) {
  first.assign(n + 1, 0);
  for (const Record& r : records) ++first[std::size_t(key_of(r)) + 1];
  for (std::size_t k = 0; k < n; ++k) first[k + 1] += first[k];
  std::vector<Index> fill(first.begin(), first.end() - 1);
  out.resize(records.size());
  for (const Record& r : records) out[std::size_t(fill[std::size_t(key_of(r))]++)] = r;
}

// Every cell as (sorted corners, index), bucketed by the smallest corner and sorted within the bucket.
void sorted_cells(const std::vector<Index>& tets, std::vector<Index>& first, std::vector<std::array<Index, 5>>& cells) {
  std::vector<std::array<Index, 5>> records(tets.size() / 4);
  for (std::size_t t = 0; t < records.size(); ++t) {
    std::array<Index, 4> s{tets[4 * t], tets[4 * t + 1], tets[4 * t + 2], tets[4 * t + 3]};
    sort_small(s);
    records[t] = {s[0], s[1], s[2], s[3], Index(t)};
  }
  bucket_by(point_count(tets), records, [](const std::array<Index, 5>& r) { return r[0]; }, first, cells);
  for (std::size_t a = 0; a + 1 < first.size(); ++a)
    std::sort(cells.begin() + first[a], cells.begin() + first[a + 1]);
}

}  // namespace

std::vector<std::array<Index, 4>> tet_face_neighbours(const std::vector<Index>& tets) {
  const std::size_t nt = tets.size() / 4, n = point_count(tets);
  // Per face: its two larger corners packed in one key, and 4 t + local face, bucketed by the smallest corner.
  struct Record {
    std::uint64_t key;
    Index face;
  };
  auto sorted_face = [&](std::size_t t, std::size_t f) {
    std::array<Index, 3> s{tets[4 * t + std::size_t(kTetFaces[f][0])], tets[4 * t + std::size_t(kTetFaces[f][1])],
                           tets[4 * t + std::size_t(kTetFaces[f][2])]};
    sort_small(s);
    return s;
  };
  std::vector<Index> first(n + 1, 0);
  for (std::size_t t = 0; t < nt; ++t)
    for (std::size_t f = 0; f < 4; ++f) ++first[std::size_t(sorted_face(t, f)[0]) + 1];
  for (std::size_t k = 0; k < n; ++k) first[k + 1] += first[k];
  std::vector<Index> fill(first.begin(), first.end() - 1);
  std::vector<Record> faces(4 * nt);
  for (std::size_t t = 0; t < nt; ++t)
    for (std::size_t f = 0; f < 4; ++f) {
      const auto s = sorted_face(t, f);
      faces[std::size_t(fill[std::size_t(s[0])]++)] = {(std::uint64_t(std::uint32_t(s[1])) << 32) | std::uint32_t(s[2]), Index(4 * t + f)};
    }
  // Within a bucket (a few dozen faces), by key then face: the records were filled in ascending face order, so a
  // stable sort on the key alone gives that order.
  std::vector<std::array<Index, 4>> nbr(nt, {kNoIndex, kNoIndex, kNoIndex, kNoIndex});
  for (std::size_t a = 0; a < n; ++a) {
    Record* begin = faces.data() + first[a];
    Record* end = faces.data() + first[a + 1];
    if (end - begin > 64) {
      std::stable_sort(begin, end, [](const Record& r, const Record& s) { return r.key < s.key; });
    } else {
      for (Record* i = begin + 1; i < end; ++i)
        for (Record* j = i; j > begin && (j - 1)->key > j->key; --j) std::swap(*(j - 1), *j);
    }
    for (Record* i = begin; i != end;) {
      Record* j = i + 1;
      while (j != end && j->key == i->key) ++j;
      if (j - i == 2) {
        const Index p = i->face, q = (i + 1)->face;
        nbr[std::size_t(p / 4)][std::size_t(p % 4)] = q / 4;
        nbr[std::size_t(q / 4)][std::size_t(q % 4)] = p / 4;
      } else if (j - i > 2) {
        for (Record* k = i; k != j; ++k) nbr[std::size_t(k->face / 4)][std::size_t(k->face % 4)] = kNonManifold;
      }
      i = j;
    }
  }
  return nbr;
}

std::vector<BoundaryFace> boundary_faces(const std::vector<Index>& tets) { return boundary_faces(tets, tet_face_neighbours(tets)); }

std::vector<BoundaryFace> boundary_faces(const std::vector<Index>& tets, const std::vector<std::array<Index, 4>>& neighbours) {
  std::vector<BoundaryFace> faces;
  for (std::size_t t = 0; t < neighbours.size(); ++t)
    for (int f = 0; f < 4; ++f) {
      const Index across = neighbours[t][std::size_t(f)];
      if (across == kNonManifold) throw std::runtime_error("tetrahedral mesh: a face is shared by more than two tetrahedra");
      if (across != kNoIndex) continue;
      const Index* v = tets.data() + 4 * t;
      const int* k = kTetFaces[f];
      faces.push_back({{v[k[0]], v[k[1]], v[k[2]]}, Index(t), f});
    }
  return faces;
}

std::vector<std::pair<Index, Index>> tet_edges(const std::vector<Index>& tets) {
  static constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  const std::size_t nt = tets.size() / 4, n = point_count(tets);
  // The larger corner of every edge, bucketed by the smaller one.
  std::vector<Index> first(n + 1, 0);
  for (std::size_t t = 0; t < nt; ++t)
    for (const auto& e : kEdges) ++first[std::size_t(std::min(tets[4 * t + std::size_t(e[0])], tets[4 * t + std::size_t(e[1])])) + 1];
  for (std::size_t k = 0; k < n; ++k) first[k + 1] += first[k];
  std::vector<Index> fill(first.begin(), first.end() - 1), other(6 * nt);
  for (std::size_t t = 0; t < nt; ++t)
    for (const auto& e : kEdges) {
      const Index a = tets[4 * t + std::size_t(e[0])], b = tets[4 * t + std::size_t(e[1])];
      other[std::size_t(fill[std::size_t(std::min(a, b))]++)] = std::max(a, b);
    }
  // Each edge is in several tets: drop the repeats with a stamp per point, then sort the few left.
  std::vector<std::pair<Index, Index>> edges;
  edges.reserve(other.size() / 4);
  std::vector<Index> seen_from(n, kNoIndex);
  for (std::size_t a = 0; a < n; ++a) {
    const std::size_t start = edges.size();
    for (Index i = first[a]; i < first[a + 1]; ++i) {
      const Index b = other[std::size_t(i)];
      if (seen_from[std::size_t(b)] == Index(a)) continue;
      seen_from[std::size_t(b)] = Index(a);
      edges.emplace_back(Index(a), b);
    }
    std::sort(edges.begin() + long(start), edges.end());
  }
  return edges;
}

TetCellSet::TetCellSet(const std::vector<Index>& tets) {
  std::vector<std::array<Index, 5>> cells;
  sorted_cells(tets, first_, cells);
  rest_.resize(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) rest_[i] = {cells[i][1], cells[i][2], cells[i][3], cells[i][4]};
}

Index TetCellSet::find(const Index* v) const {
  std::array<Index, 4> s{v[0], v[1], v[2], v[3]};
  sort_small(s);
  if (s[0] < 0 || std::size_t(s[0]) + 1 >= first_.size()) return kNoIndex;
  for (Index i = first_[std::size_t(s[0])]; i < first_[std::size_t(s[0]) + 1]; ++i) {
    const auto& r = rest_[std::size_t(i)];
    if (r[0] == s[1] && r[1] == s[2] && r[2] == s[3]) return r[3];
  }
  return kNoIndex;
}

std::vector<Index> tet_sorted_order(const std::vector<Index>& tets) {
  std::vector<Index> first;
  std::vector<std::array<Index, 5>> cells;
  sorted_cells(tets, first, cells);
  std::vector<Index> order(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) order[i] = cells[i][4];
  return order;
}

}  // namespace loom
