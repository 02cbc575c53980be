// Builds the boundary conditions of a scene on its mesh: selects the nodes and boundary edges of each
// [[boundary]] region, numbers the prescribed dofs and compiles the expressions. Errors that need the
// mesh (a region that selects nothing, two boundaries prescribing one dof differently) are InputErrors
// naming the scene position.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engine/linalg/dof_map.hpp"
#include "engine/methods/model/build_mesh.hpp"
#include "engine/scene/scene_spec.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

// dofs_per_node: layout of the run's DofMap (displacement components first). tie_mid_nodes (PFEM): the
// mid-nodes of boundary edges with a condition are tied to their corners (seed 000 eq 24).
// frozen_tractions (PFEM): the traction edges to use instead of searching the current boundary. A dead
// load lives on the reference surface (eq 8), whatever the remesh does to the current boundary (alpha
// shapes may cover a loaded edge), so PFEM computes its edges once, on the initial mesh.
// regions: the bodies' mesh-file groups, for regions given by group (a mid-node is in a group when both
// corners of its edge are).
BoundaryConditions<2> build_boundary_conditions(const SceneSpec& scene, const Nodes<2>& nodes,
                                                const std::vector<Cells>& cells, const std::vector<Index>& node_body,
                                                const BodyRegions& regions, int dofs_per_node, bool tie_mid_nodes = false,
                                                const std::vector<TractionEdge<2>>* frozen_tractions = nullptr);

// Compiles expression `e` into bc.expressions (named by its scene position for error messages); returns
// its index.
template <int D>
Index add_expression(BoundaryConditions<D>& bc, const ExpressionSpec& e);
// Sum of the global and the per-body body force (both per unit mass): "(a) + (b)", or whichever is given.
std::optional<ExpressionSpec> combine(const std::optional<ExpressionSpec>& a, const std::optional<ExpressionSpec>& b);

// Dof kinds of the run: prescribed where a boundary prescribes a displacement component, tied for the
// ties of `bc`; with three
// dofs per node the third (phi) is free at nodes of mixed u-phi cells and absent elsewhere.
template <int D>
std::vector<DofKind> dof_kinds(const BoundaryConditions<D>& bc, const std::vector<Cells>& cells, Index n_nodes, int dofs_per_node);

// The physical group of the body's mesh file that boundary k's region names; InputError listing the groups if none.
const MeshRegion& boundary_group(const SceneSpec& scene, const BodyRegions& regions, std::size_t k);

// boundary[].region.normal: whether a boundary edge (3D: face) whose outward normal is `outward` faces direction `d`,
// that is lies within 45 degrees of it (n . d / (|n| |d|) >= cos 45 degrees, with a relative 1e-12 of slack so that
// a face at exactly 45 degrees counts whatever the rounding). Neither vector need be of unit length; a zero
// one faces nothing. The one test of the four traction builders (fem and mpm, 2D and 3D).
template <int D>
bool faces_direction(const Vec<D>& outward, const Vec<D>& d) {
  const double scale = outward.norm() * d.norm();
  return scale > 0.0 && outward.dot(d) >= (std::sqrt(0.5) - 1e-12) * scale;
}

// The direction of boundary[].region.normal in D components, or nothing when the region has none.
template <int D>
std::optional<Vec<D>> region_normal(const BoundarySpec& spec) {
  if (!spec.normal) return std::nullopt;
  if constexpr (D == 2) return Vec<D>(*spec.normal);
  else return Vec<D>(spec.normal->x(), spec.normal->y(), spec.normal_z);
}

// The InputError of boundary k's traction when no boundary edge (3D: face) carries it: `needs` says which a traction
// needs ("boundary edges with both end nodes in the region"), `in_region` how many of those the region holds before
// region.normal's filter. With none, the message names the region's box or group; else region.normal, which
// removed them all. Returns when `loaded` > 0.
void check_traction_support(const SceneSpec& scene, std::size_t k, std::size_t loaded, std::size_t in_region, const std::string& needs);

// The prescribed dofs found so far, and the boundary that prescribed each (for the message when two disagree).
struct PrescribedDofs {
  std::map<Index, std::size_t> at;  // dof -> entry of bc.prescribed
  std::vector<Index> by;            // per entry: the boundary
};
// Prescribes the displacement components of boundary k at its selected nodes (not at tied mid-nodes), and
// records them in bc.boundary_prescribed.back(); a dof prescribed twice must carry the same expression.
template <int D>
void prescribe_displacements(const SceneSpec& scene, std::size_t k, const std::vector<Index>& selected,
                             const std::map<Index, std::array<Index, 2>>& tied, const Nodes<D>& nodes, PrescribedDofs& seen,
                             BoundaryConditions<D>& bc);

}  // namespace loom
