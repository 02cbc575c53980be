#include "engine/mesh/tet_background_grid.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include "engine/core/errors.hpp"
#include "engine/mesh/cell_buckets.hpp"
#include "engine/mesh/colouring.hpp"

namespace loom {
namespace {

// cells.neighbour across each face: the faces keyed by their sorted corners and sorted, so that the two
// cells sharing a face are adjacent in the list (no hashing of node triples, deterministic).
void find_face_neighbours(Cells& cells) {
  struct Face {
    std::array<Index, 3> key;
    Index cell;
    int local;  // the corner the face is opposite to
  };
  std::vector<Face> faces;
  faces.reserve(4 * std::size_t(cells.size()));
  for (Index c = 0; c < cells.size(); ++c)
    for (int a = 0; a < 4; ++a) {
      std::array<Index, 3> key;
      for (int k = 0; k < 3; ++k) key[std::size_t(k)] = cells.node(c, kTetFaces[a][k]);
      std::sort(key.begin(), key.end());
      faces.push_back({key, c, a});
    }
  std::sort(faces.begin(), faces.end(), [](const Face& f, const Face& g) {
    return f.key != g.key ? f.key < g.key : std::pair(f.cell, f.local) < std::pair(g.cell, g.local);
  });
  cells.neighbour.use();
  cells.neighbour.resize_strided(cells.size(), 4, kNoIndex);
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    LOOM_CHECK(j - i <= 2, InputError,
               "grid face (" << faces[i].key[0] << ", " << faces[i].key[1] << ", " << faces[i].key[2] << ") is shared by "
                             << j - i << " cells (at most two: the grid is not a manifold)");
    if (j - i == 2) {
      cells.neighbour[4 * faces[i].cell + faces[i].local] = faces[i + 1].cell;
      cells.neighbour[4 * faces[i + 1].cell + faces[i + 1].local] = faces[i].cell;
    }
    i = j;
  }
}

}  // namespace

void build_tet_grid(const TetMeshData& mesh, const BoxSpec* box, Formulation formulation, Nodes<3>& nodes, Cells& cells,
                    GridLayoutT<3>& layout) {
  LOOM_CHECK(!mesh.X.empty() && mesh.n_tets() > 0, InputError, "a tetrahedral grid needs nodes and cells");
  // 1. Nodes and cells.
  nodes.resize(Index(mesh.X.size()));
  for (Index i = 0; i < nodes.size(); ++i) nodes.X[i] = mesh.X[std::size_t(i)];
  cells = Cells(CellType::tet4, formulation);
  cells.nodes.values() = mesh.tets;
  cells.body.assign(mesh.n_tets(), 0);
  colour_cells(cells, nodes.size());
  find_face_neighbours(cells);

  // 2. Geometry: volumes and the constant shape gradients. With the edges e_k = x_k - x_0 and the cross
  // products n1 = e2 x e3, n2 = e3 x e1, n3 = e1 x e2 (tet_shape_at), N_k = (x - x_0) . n_k / (e1 . n1), so
  // grad N_k = n_k / (6 V) and grad N_0 = -(grad N_1 + grad N_2 + grad N_3).
  cells.measure.use();
  cells.measure.resize(cells.size(), 0.0);
  cells.gradient_3d.use();
  cells.gradient_3d.resize(cells.size(), Mat43::Zero());
  for (Index c = 0; c < cells.size(); ++c) {
    const Vec3& x0 = nodes.X[cells.node(c, 0)];
    const Vec3 e1 = nodes.X[cells.node(c, 1)] - x0, e2 = nodes.X[cells.node(c, 2)] - x0, e3 = nodes.X[cells.node(c, 3)] - x0;
    const double volume = tet_volume(x0, nodes.X[cells.node(c, 1)], nodes.X[cells.node(c, 2)], nodes.X[cells.node(c, 3)]);
    LOOM_CHECK(volume > 0.0, InputError, "grid cell " << c << " is degenerate or inverted (volume " << volume << ")");
    cells.measure[c] = volume;
    const double inv_det = 1.0 / e1.dot(e2.cross(e3));
    Mat43& g = cells.gradient_3d[c];
    g.row(1) = e2.cross(e3).transpose() * inv_det;
    g.row(2) = e3.cross(e1).transpose() * inv_det;
    g.row(3) = e1.cross(e2).transpose() * inv_det;
    g.row(0) = -(g.row(1) + g.row(2) + g.row(3));
  }

  // 3. Layout.
  layout = GridLayoutT<3>{};
  layout.lo = layout.hi = nodes.X[0];
  for (Index i = 0; i < nodes.size(); ++i) layout.lo = layout.lo.cwiseMin(nodes.X[i]), layout.hi = layout.hi.cwiseMax(nodes.X[i]);
  layout.tolerance = 1e-9 * layout.width();
  if (box) {
    layout.structured = true;
    layout.origin = box->origin;
    layout.nx = box->nx, layout.ny = box->ny, layout.nz = box->nz;
    layout.spacing = box->size.cwiseQuotient(Vec3(box->nx, box->ny, box->nz));
#ifndef NDEBUG
    // generate_box numbers the six tetrahedra of cube k = (kz ny + j) nx + i as 6k .. 6k + 5.
    LOOM_ASSERT(cells.size() == 6 * Index(box->nx) * box->ny * box->nz, "the grid is not generate_box(*box)");
    for (Index c = 0; c < cells.size(); ++c) {
      Vec3 centre = Vec3::Zero();
      for (int a = 0; a < 4; ++a) centre += 0.25 * nodes.X[cells.node(c, a)];
      const Index k = c / 6;
      const Vec3 cube(k % box->nx + 0.5, k / box->nx % box->ny + 0.5, k / (Index(box->nx) * box->ny) + 0.5);
      LOOM_ASSERT(((centre - layout.origin).cwiseQuotient(layout.spacing) - cube).cwiseAbs().maxCoeff() < 0.5,
                  "cell " << c << " is not in cube " << k);
    }
#endif
  } else {
    build_buckets(nodes, cells, layout);
  }
}

}  // namespace loom
