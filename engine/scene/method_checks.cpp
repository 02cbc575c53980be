#include "engine/scene/method_checks.hpp"

#include "engine/store/cells.hpp"

namespace loom {

void check_method_support(const SceneSpec& s, const TableReader& root, Diagnostics& diag) {
  const bool mpm = is_mpm(s.scene.method);
  const auto time = root.table("time"), grid = root.table("grid");
  const auto bodies = root.array("body"), boundaries = root.array("boundary"), probes = root.array("probe");
  const auto materials = root.array("material");
  if (mpm && time.has("predictor"))
    time.error("predictor", "the MPM step starts from the grid reset to zero; predictor is used by methods fem, pfem and es_pfem");
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
    // Energy probes (systems/output/mesh_energy.hpp): displacement formulations with hyperelastic materials, the
    // smoothed elements with theirs (the domains' b^e), the lumped mass for the kinetic energy.
    for (std::size_t k = 0; k < probes.size() && k < s.probes.size(); ++k) {
      if (s.probes[k].kind != ProbeKind::energy) continue;
      for (const BodySpec& b : s.bodies) {
        const MaterialModel model = s.materials[std::size_t(b.material)].model;
        if (integrates_on_domains(b.element)) {  // the domains' energy is that of b^e: Hencky or Hooke
          if (model != MaterialModel::hencky_perzyna && model != MaterialModel::linear_elastic)
            probes[k].error("kind", "energy probes of the smoothed elements (es_up, es_u, fem_up, fem_u) take the materials hencky_perzyna "
                                    "and linear_elastic (body \"" + b.name + "\")");
          continue;
        }
        if (b.element != Formulation::p1 && b.element != Formulation::tri6 && b.element != Formulation::quad9 &&
            b.element != Formulation::p1p1_uphi)
          probes[k].error("kind", "energy probes of method " + std::string(method_name(s.scene.method)) +
                                      " take the elements p1, tri6, quad9 (tet10), p1p1_uphi, es_up, es_u, fem_up and fem_u (body \"" + b.name +
                                      "\" is none of them)");
        else if (b.element == Formulation::p1p1_uphi && s.scene.method != Method::fem)
          probes[k].error("kind", "energy probes of p1p1_uphi bodies need method fem (the reference simplex of a remeshed cell is not its own)");
        else if (model != MaterialModel::neo_hooke && model != MaterialModel::linear_elastic && !is_hencky(model))
          probes[k].error("kind", "energy probes of method " + std::string(method_name(s.scene.method)) +
                                      " take the materials neo_hooke, linear_elastic, hencky_perzyna and drucker_prager (body \"" + b.name + "\")");
      }
      if (s.time.integrator != Integrator::static_ && s.time.mass == MassKind::consistent)
        probes[k].error("kind", "the kinetic energy of method " + std::string(method_name(s.scene.method)) + " is of the lumped mass: use time.mass = \"lumped\"");
    }
    return;
  }
  if (!grid.present()) root.table("scene").error("method", std::string("method = \"") + method_name(s.scene.method) + "\" needs a background grid: add a [grid] table");
  if (s.time.integrator == Integrator::euler_backward || s.time.integrator == Integrator::bossak)
    time.error("integrator", "method mpm integrates with newmark ([Moreno et al.] §3.3) or static");
  if (s.solver.tangent == TangentUpdate::once_per_step) root.table("solver").error("tangent", "method mpm assembles its tangent at every iteration");
  if (time.has("mass") && s.time.mass == MassKind::consistent) time.error("mass", "method mpm uses the lumped grid mass ([Moreno et al.] §5)");
  const bool coupled = s.scene.method == Method::mpm_fem;
  if (coupled) {
    // One MPM body (particles) and one or more FEM bodies (quad9 rectangles sharing the grid's nodes).
    std::size_t n_mpm = 0, n_fem = 0;
    for (std::size_t b = 0; b < bodies.size() && b < s.bodies.size(); ++b) {
      const bool fem = s.bodies[b].element == Formulation::quad9;
      if (!fem && ++n_mpm > 1) bodies[b].error("", "method mpm_fem couples one MPM body (this is the second without element = \"quad9\") to FEM bodies");
      n_fem += fem;
    }
    if (n_mpm == 0) root.error("body", "method mpm_fem needs an MPM body: a body with particles (or a mesh to sample), not element = \"quad9\"");
    if (n_fem == 0) root.error("body", "method mpm_fem needs an FEM body: a body with element = \"quad9\" and a rectangle mesh beside the grid");
    if (grid.present() && !s.grid.quad9) grid.error("cells", "method mpm_fem couples FEM quad9 cells to a quad9 grid: cells = \"quad9\"");
  } else if (s.bodies.size() > 1 && root.table("mpm").string("scheme") != "particle_newmark") {
    // Several bodies share the grid (in contact through it, no slip) with Newmark at the particles; the grid
    // Newmark of [Moreno et al.] is checked with one.
    bodies[1].error("", "method mpm with several bodies needs [mpm] scheme = \"particle_newmark\" (method mpm_fem couples one to FEM bodies)");
  }
  for (std::size_t b = 0; b < bodies.size() && b < s.bodies.size(); ++b) {
    const auto e = s.bodies[b].element;
    if (coupled && e == Formulation::quad9) continue;
    if (e != Formulation::p1 && e != Formulation::p1p1_up)
      bodies[b].error("element", "method mpm takes element = \"p1\" (displacement) or \"p1p1_up\" (mixed, [Moreno et al.])");
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
