// State transfer between meshes (seed 000 §3.2): the history F_n of every new quadrature point from the
// old quadrature points, by
//  CPM: copy from the closest old point;
//  BTM: interpolate with linear shape functions on the Delaunay triangulation of the old points (eqs
//       19-20), with ISO0/1/2 (deformation_interpolation.hpp); copy where a new point coincides with an
//       old one; fall back to CPM outside the old points' hull or where the background triangle's radius
//       ratio r_in / r_circ is below 0.005 (eq 21).
// New points listed in `copy_from` (>= 0) take the old point's value as it is: the recipe uses it for
// cells that kept their corners, so an unchanged mesh transfers nothing.
#pragma once

#include <vector>

#include "engine/core/types.hpp"
#include "systems/map/iso_mode.hpp"

namespace loom {

enum class MapScheme { cpm, btm };

struct MapSettings {
  MapScheme scheme = MapScheme::cpm;
  IsoMode iso = IsoMode::iso0;
  double min_radius_ratio = 0.005;  // eq 21
  double coincidence = 1e-12;       // relative to the old points' bounding box: a copy, not an interpolation
};

struct MapStats {
  Index kept = 0;          // copied from the same point of an unchanged cell
  Index copied = 0;        // CPM, or BTM at a coinciding old point
  Index interpolated = 0;  // BTM
  Index fallback = 0;      // BTM falling back to CPM (outside the hull or a poor background triangle)
};

// Fills new_F (one per new point). copy_from[k] >= 0: new point k keeps old point copy_from[k].
void map_state(const std::vector<Vec2>& old_positions, const std::vector<Mat3>& old_F,
               const std::vector<Vec2>& new_positions, const std::vector<Index>& copy_from, const MapSettings& settings,
               std::vector<Mat3>& new_F, MapStats& stats);

// r_in / r_circ of a triangle (1/2 for an equilateral one, 0 for a degenerate one).
double radius_ratio(const Vec2& a, const Vec2& b, const Vec2& c);

// The same on tetrahedra (map_state_3d.cpp): a Delaunay_triangulation_3 of the old points, four barycentric weights,
// and the fallback where the background tetrahedron's 3 r_in / r_circ (1 for a regular one) is below
// 2 min_radius_ratio: 1 % of the regular simplex in both dimensions.
void map_state(const std::vector<Vec3>& old_positions, const std::vector<Mat3>& old_F, const std::vector<Vec3>& new_positions,
               const std::vector<Index>& copy_from, const MapSettings& settings, std::vector<Mat3>& new_F, MapStats& stats);

// 3 r_in / r_circ of a tetrahedron (1 for a regular one, 0 for a degenerate one).
double radius_ratio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

}  // namespace loom
