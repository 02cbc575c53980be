// The reference areas A_0 of the triangles a remesh creates in a dynamic es_pfem run (lumped masses), chosen so that
// the body's mass stays what it was and each new triangle's density is that of the material it replaces.
//
// The new triangles that share edges form patches (an edge flip, an inflow strip, the region of a removed particle).
//  1. A removed triangle whose region a patch now covers (its centroid lies in one of the patch's triangles: a
//     re-triangulation of the same particles covers the same region) gives that patch its whole mass rho A_0.
//  2. What the particles lost otherwise (removed boundary triangles, removed particles: M_a less what their kept
//     and matched triangles account for) goes to the patches around them in proportion to their new area.
//  3. Within a patch the mass is spread over its triangles in proportion to their areas in the reference
//     configuration, A(X_a, X_b, X_c), when those tile what the patch's mass came from (every one positive and
//     their sum rho sum A(X) equal to the patch's mass to 1e-9: an elastic solid whose triangles have always had
//     their reference areas): then every new triangle gets its own A_0 = A(X) and its volume ratio A_n / A_0 is
//     the exact J. Otherwise (a flow: the particles' reference positions no longer bound the material they
//     carry) at a uniform density, A_0 proportional to A_n.
// Matching removed triangles to the region they covered is what keeps an elastic body's volume exact through
// flips: sharing each particle's lost mass by area among all the patches around it moved mass between
// neighbouring patches (volume ratios off by up to 18 % where a straightening beam flipped a row of squares, the
// energy that an undamped integrator then kept; docs/free_surface.md).
// Where the body's mass is not kept exactly (docs/free_surface.md §2.7): a removed triangle whose region no fresh
// triangle at its own corners covers (a cavity of six or more particles re-triangulated) goes through step 2, its
// mass conserved but its patch no longer tiling; a particle with no fresh triangle around it (a boundary triangle
// removed by the alpha shape between kept ones) gives its D_a to the kept triangles around it, their density
// raised, and only a particle left in no triangle at all loses it; a particle whose kept and matched triangles hold more
// than M_a is not charged the excess (D_a is clamped at 0). A patch that nothing gave mass to (in 3D a sliver the
// remesh added on the surface) takes the particles' volume, A_n / J_e, and that mass from the kept triangles around
// its corners, so that the body's mass stays what it was.
// In 3D (D = 3) the same with tetrahedra for triangles, volumes for areas, patches joined by shared faces and
// quarter shares at the corners.
#pragma once

#include <vector>

#include "engine/methods/pfem/domain_transfer.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"

namespace loom {

// Sets cells[b].measure of every triangle flagged in is_new[b] (not those flagged in gap_cells, which the caller
// handles). nodes.lumped_mass holds each particle's mass before the remesh; density is per body.
template <int D>
void share_mass_to_new_triangles(const DomainSnapshot<D>& old, const Nodes<D>& nodes, std::vector<Cells>& cells,
                                 const std::vector<std::vector<char>>& is_new, const std::vector<double>& density,
                                 const std::vector<std::vector<char>>* gap_cells);

}  // namespace loom
