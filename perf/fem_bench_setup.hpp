// Shared set-up of the fem benchmarks: the stores of a Cook's membrane run (Neo-Hooke, P1, plane
// strain), built by FemModel as FemRun builds them, so that the benchmarks drive the real systems
// (assemble_system, solve_linear_step, update_iterate) on them.
//
// Mesh: Cook's membrane, an nx by ny grid split into 2 nx ny triangles ("alternating" diagonals, as in
// scenes/cooks_membrane_linear.toml); nx ny = n_cells / 2 with the most nearly square factorisation,
// so the cell count is exactly the benchmark argument. Material: E = 250, nu = 0.3 (the timing of the
// kernels and of the sparse factorizations does not depend on the values). Step 1 of a static run,
// left edge clamped, shear traction 6.25 on the right edge. The benchmarks make their own LinearSolve.
//
// The iterate is that of the step's second Newton iteration (two full Newton updates from u = u_n = 0):
// a genuine mid-Newton state (at 10^3 cells: residual norm 14 against 22 at the start of the step and
// 1e-11 at convergence, J in [0.91, 1.05]), at which the tangent is positive definite so that CHOLMOD
// applies, and every prescribed dof already sits on its target (residual-only assembly computes no cell
// tangent). An arbitrary smooth field would not do: the one tried first made the tangent indefinite.
#pragma once

#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/graph/step_context.hpp"
#include "engine/linalg/linear_solver.hpp"
#include "engine/linalg/linear_system.hpp"
#include "engine/methods/model/fem_model.hpp"
#include "engine/scene/scene_loader.hpp"
#include "engine/store/boundary_conditions.hpp"
#include "engine/store/cells.hpp"
#include "engine/store/nodes.hpp"
#include "engine/store/quad_points.hpp"
#include "engine/timing/timers.hpp"
#include "systems/assemble/assemble_system.hpp"
#include "systems/assemble/compute_geometry.hpp"
#include "systems/assemble/materials/material.hpp"
#include "systems/loads/apply_boundary_conditions.hpp"
#include "systems/solve/solve_linear_step.hpp"
#include "systems/update/update_iterate.hpp"

namespace loom::perf {

// nx >= ny with nx * ny = cells_half and ny as large as possible.
inline void grid_divisions(Index n_cells, int& nx, int& ny) {
  const Index half = n_cells / 2;
  ny = 1;
  for (Index d = 1; d * d <= half; ++d)
    if (half % d == 0) ny = int(d);
  nx = int(half / ny);
}

inline std::string cooks_membrane_scene(Index n_cells) {
  int nx = 0, ny = 0;
  grid_divisions(n_cells, nx, ny);
  std::ostringstream s;
  s << "[scene]\nname = \"perf-cooks-membrane\"\nmethod = \"fem\"\n"
    << "[time]\nintegrator = \"static\"\ndt = 1.0\nsteps = 1\n"
    << "[[material]]\nname = \"rubber\"\nmodel = \"neo_hooke\"\nE = 250.0\nnu = 0.3\n"
    << "[[body]]\nname = \"membrane\"\nmaterial = \"rubber\"\nelement = \"p1\"\n"
    << "mesh = { generator = \"cooks_membrane\", divisions = [" << nx << ", " << ny
    << "], pattern = \"alternating\" }\n"
    << "[[boundary]]\nname = \"clamped\"\nregion = { box = [[0.0, 0.0], [0.0, 44.0]] }\ndisplacement = { x = 0.0, y = "
       "0.0 }\n"
    << "[[boundary]]\nname = \"loaded\"\nregion = { box = [[48.0, 44.0], [48.0, 60.0]] }\ntraction = { y = 6.25 }\n"
    << "[output]\nevery = 0\n";
  return s.str();
}

// The stores of one run (FemModel, as FemRun builds them). Not movable: ctx points at scene.
struct FemBenchRun : FemModel {
  StepContext ctx;

  explicit FemBenchRun(Index n_cells) : loom::FemModel(load_scene_text(cooks_membrane_scene(n_cells), "perf/cooks_membrane")) {
    ctx.scene = &scene;
    // Step 1 of the static run: loads and targets at t = dt.
    ctx.step = 1, ctx.dt = scene.time.dt, ctx.t = ctx.dt, ctx.step_end = true;
    apply_boundary_conditions(ctx, nodes, cells, materials, bc);
    deform();
  }
  FemBenchRun(const FemBenchRun&) = delete;
  FemBenchRun& operator=(const FemBenchRun&) = delete;

  Index n_cells() const {
    Index n = 0;
    for (const auto& c : cells) n += c.size();
    return n;
  }

  // Two Newton iterations of step 1 from u = u_n = 0 (the iterate described in the header).
  void deform() {
    LinearSolve solver(LinearSolverKind::automatic);
    Timers timers;
    for (int it = 0; it < 2; ++it) {
      if (assemble_system(ctx, AssemblyMode::residual_and_tangent, materials, nodes, cells, bc, quad, system)
                  .inverted_cells != 0 ||
          solve_linear_step(nodes, bc, solver, system, timers) != LinearSolveStatus::ok)
        throw std::runtime_error("set-up Newton iteration failed");
      update_iterate(1.0, system, nodes);
    }
  }
};

}  // namespace loom::perf
