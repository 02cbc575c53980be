// Builds the points of an MPM scene from its bodies' meshes (seed 003 §6, Kratos-style initialisation):
//  - material points at the points of a symmetric triangle rule in every body cell (particles_per_cell),
//    volume = rule weight x cell area, mass = density x volume, F = I;
//  - traction points: two Gauss points on every boundary edge of the body mesh inside a traction region,
//    weight = half the edge's reference length, with that boundary's traction expressions.
#pragma once

#include <vector>

#include "engine/scene/scene_spec.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/points.hpp"

namespace loom {

// Fills the used columns of `particles` (X, volume, mass, body, F; others zero).
void build_material_points(const SceneSpec& scene, Points<2>& particles);

// Fills traction_points (X, volume = weight, body) and bc.traction_point_expression; adds the expressions
// to bc. Throws InputError for a traction region without boundary edges.
void build_traction_points(const SceneSpec& scene, Points<2>& traction_points, BoundaryConditions<2>& bc);

}  // namespace loom
