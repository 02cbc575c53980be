#include "engine/scene/method_checks.hpp"

namespace loom {

void check_method_support(const SceneSpec& s, const TableReader& root, Diagnostics& diag) {
  const bool mpm = s.scene.method == Method::mpm;
  const auto time = root.table("time"), grid = root.table("grid");
  const auto bodies = root.array("body"), boundaries = root.array("boundary"), probes = root.array("probe");
  const auto materials = root.array("material");
  if (!mpm) {
    if (grid.present()) root.error("grid", "[grid] is used by method = \"mpm\" only");
    if (s.time.initial_acceleration == InitialAcceleration::equilibrium && s.time.mass == MassKind::consistent)
      time.error("initial_acceleration", "equilibrium solves for a_0 with the lumped mass; use mass = \"lumped\"");
    for (std::size_t b = 0; b < bodies.size() && b < s.bodies.size(); ++b) {
      if (s.bodies[b].element == Formulation::p1p1_up) bodies[b].error("element", "p1p1_up is an MPM grid formulation: use method = \"mpm\"");
      if (bodies[b].has("particles_per_cell")) bodies[b].error("particles_per_cell", "particles_per_cell is used by method = \"mpm\" only");
    }
    for (std::size_t b = 0; b < boundaries.size() && b < s.boundaries.size(); ++b)
      if (s.boundaries[b].pressure) boundaries[b].error("pressure", "a prescribed pressure needs method = \"mpm\" with element = \"p1p1_up\"");
    for (std::size_t k = 0; k < probes.size() && k < s.probes.size(); ++k)
      if (s.probes[k].kind == ProbeKind::energy) probes[k].error("kind", "energy probes are implemented by method = \"mpm\"");
    return;
  }
  if (!grid.present()) root.table("scene").error("method", "method = \"mpm\" needs a background grid: add a [grid] table");
  if (s.time.integrator == Integrator::euler_backward || s.time.integrator == Integrator::bossak)
    time.error("integrator", "method mpm integrates with newmark (seed 003 §3.3) or static");
  if (s.solver.tangent == TangentUpdate::once_per_step) root.table("solver").error("tangent", "method mpm assembles its tangent at every iteration");
  if (time.has("mass") && s.time.mass == MassKind::consistent) time.error("mass", "method mpm uses the lumped grid mass (seed 003 §5)");
  if (s.bodies.size() > 1) bodies[1].error("", "method mpm supports one body for now");
  for (std::size_t b = 0; b < bodies.size() && b < s.bodies.size(); ++b) {
    const auto e = s.bodies[b].element;
    if (e != Formulation::p1 && e != Formulation::p1p1_up)
      bodies[b].error("element", "method mpm takes element = \"p1\" (displacement) or \"p1p1_up\" (mixed, seed 003)");
    const Index m = s.bodies[b].material;
    if (m != kNoIndex && e != Formulation::p1p1_up && s.materials[std::size_t(m)].nu == 0.5)
      materials[std::size_t(m)].error("nu", "nu = 0.5 (incompressible) needs element = \"p1p1_up\" on body \"" + s.bodies[b].name + "\"");
  }
  const bool mixed = !s.bodies.empty() && s.bodies[0].element == Formulation::p1p1_up;
  for (std::size_t b = 0; b < boundaries.size() && b < s.boundaries.size(); ++b)
    if (s.boundaries[b].pressure && !mixed) boundaries[b].error("pressure", "a prescribed pressure needs element = \"p1p1_up\"");
  for (std::size_t k = 0; k < probes.size() && k < s.probes.size(); ++k)
    if (s.probes[k].kind == ProbeKind::pressure_jump && !mixed)
      probes[k].error("kind", "method mpm measures pressure jumps on the grid pressure of element = \"p1p1_up\"");
    else if (s.probes[k].kind == ProbeKind::volume)
      probes[k].error("kind", "volume probes measure the cells of method fem or pfem; method mpm has no body mesh after the start");
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    const Index m = s.bodies[b].material;
    if (m != kNoIndex && !(s.materials[std::size_t(m)].density > 0) && !(s.time.integrator != Integrator::static_))
      diag.error(s.materials[std::size_t(m)].where, "material[" + std::to_string(m) + "].density",
                  "method mpm: particles carry mass = density x volume, and the grid projects with it: density must be > 0 (body \"" +
                      s.bodies[b].name + "\")");
  }
}

}  // namespace loom
