// Boundary conditions and loads of a mesh-based run, built once from the scene's [[boundary]] and body
// force tables: which dofs are prescribed and by which expression, the boundary edges that carry a
// traction, the body forces of each body. The apply_boundary_conditions system evaluates them at the
// time of each step into `target` (prescribed values) and `external` (nodal external forces).
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "engine/core/types.hpp"
#include "engine/linalg/dof_map.hpp"
#include "engine/scene/expression.hpp"

namespace loom {

// A boundary edge carrying a traction: corners a, b (counter-clockwise along the outline), the mid-node of
// a quadratic edge or kNoIndex, the expression of each component (kNoIndex: zero).
template <int D>
struct TractionEdge {
  Index a, b;
  Index mid;
  std::array<Index, D> expression;
};

// A boundary face of a tetrahedral mesh carrying a traction: corners counter-clockwise seen from outside
// (nodes[0..2]), the mid-nodes of its edges 01, 12, 20 on a quadratic face (nodes[3..5]; kNoIndex when linear),
// the expression of each component (kNoIndex: zero).
struct TractionFace {
  std::array<Index, 6> nodes;
  std::array<Index, 3> expression;
};

template <int D>
struct BoundaryConditions {
  std::vector<Expression> expressions;  // compiled; referenced by index below
  int per_node = D;                     // dofs per node of the run's DofMap (dof = node * per_node + component)

  struct Prescribed {
    Index dof;   // global dof (node * per_node + component)
    Index node;
    Index expression;       // the displacement at t; kNoIndex: the node moves at `velocity` from u_n (an inlet's row)
    double velocity = 0.0;  // of this component, when expression == kNoIndex
  };
  std::vector<Prescribed> prescribed;

  using TractionEdge = loom::TractionEdge<D>;
  std::vector<TractionEdge> traction_edges;
  std::vector<TractionFace> traction_faces;  // D = 3

  std::vector<std::array<Index, D>> body_force;  // per body, per component; kNoIndex: zero
  std::vector<Tie> ties;                           // dofs tied to the mean of two others (PFEM TRI6, eq 24)

  // Method mpm: the traction points (a Points store) sample the loaded boundary edges (3D: faces) of the body mesh;
  // each carries the traction expressions of its edge (weight: its share of the edge's reference length or area).
  std::vector<std::array<Index, D>> traction_point_expression;
  std::vector<Vec<D>> particle_body_force;  // per particle, at the step time: b per unit mass
  std::vector<Vec<D>> traction_point_force;  // per traction point, at the step time: its traction times its weight
  std::vector<Vec<D>> fem_body_force;  // method mpm_fem: per Gauss point of the FEM cells (9 per cell, in cell order), b per unit mass
  bool increments = false;  // mpm: `target` holds the step's increment of prescribed displacements

  std::vector<std::string> boundary_names;              // the scene's [[boundary]] names, in order
  std::vector<std::vector<Index>> boundary_nodes;       // nodes selected by each boundary's region
  std::vector<std::vector<Index>> boundary_prescribed;  // entries of `prescribed` owned by each boundary

  bool loads_depend_on_time = false;  // else `external` is computed once
  bool has_loads = false;             // any traction or body force

  // Evaluated at the current step time:
  Eigen::VectorXd target;    // n_dofs: prescribed values (meaningful on prescribed dofs only)
  Eigen::VectorXd external;  // n_dofs: nodal external forces (tractions, body forces)
  double external_time = kNaN;  // time `external` was evaluated at
};

}  // namespace loom
