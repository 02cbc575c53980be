#include "engine/scene/mpm_options.hpp"

#include <sstream>
#include <string>
#include <vector>

#include "engine/mesh/tetrahedron_rules.hpp"
#include "engine/mesh/triangle_rules.hpp"
#include "engine/scene/loader_support.hpp"

namespace loom {

void read_newmark_parameters(const TableReader& time, TimeSpec& t) {
  t.beta = time.real("beta");
  t.gamma = time.real("gamma");
  for (const char* k : {"beta", "gamma"})
    if (time.has(k) && t.integrator != Integrator::newmark)
      time.error(k, std::string(k) + " is used by integrator = \"newmark\" only (bossak derives its own from alpha)");
  // Newmark is unconditionally stable for linear problems when 2 beta >= gamma >= 1/2 (the schema holds gamma >= 1/2).
  if (2.0 * t.beta < t.gamma) {
    std::ostringstream os;
    os << "Newmark with beta = " << t.beta << ", gamma = " << t.gamma << " is only conditionally stable: take 2 beta >= gamma (e.g. beta = "
       << 0.25 * (t.gamma + 0.5) * (t.gamma + 0.5) << "; mpm.scheme = \"particle_newmark\" needs 2 beta > gamma strictly, e.g. 0.3)";
    time.error(time.has("beta") ? "beta" : "gamma", os.str());
  }
}

void read_particle_generator(const TableReader& body, BodySpec& b) {
  const auto t = body.table("particles");
  if (!t.present()) return;
  ParticleGeneratorSpec& g = b.particles;
  g.where = t.where();
  if (body.table("mesh").present()) body.error("particles", "give either mesh (particles generated in its cells) or particles, not both");
  if (body.has("particles_per_cell")) body.error("particles_per_cell", "particles_per_cell samples a body mesh; body.particles generates its own");
  const bool disk = t.string("generator") == "disk";
  g.kind = disk ? ParticleGenerator::disk : ParticleGenerator::beam;
  const std::vector<std::string> disk_keys = {"centre", "radius", "core_radius", "n_theta"};
  const std::vector<std::string> beam_keys = {"root", "length", "height", "core_height", "n_height"};
  for (const std::string& k : disk ? beam_keys : disk_keys)
    if (t.has(k)) t.error(k, k + " belongs to generator = \"" + (disk ? "beam" : "disk") + "\"");
  for (const std::string& k : disk ? disk_keys : beam_keys)
    if (!t.has(k) && k != "centre" && k != "root") t.error("", "missing key " + k + " (generator = \"" + t.string("generator") + "\")");
  if (!t.has("factor")) t.error("", "missing key factor (the boundary layers' refinement, > 1)");
  g.factor = t.has("factor") ? t.real("factor") : 1.0;
  if (disk) {
    g.centre = t.vec2("centre");
    g.radius = t.has("radius") ? t.real("radius") : 0.0;
    g.core_radius = t.has("core_radius") ? t.real("core_radius") : 0.0;
    g.n_theta = t.has("n_theta") ? int(t.integer("n_theta")) : 0;
    if (t.has("radius") && t.has("core_radius") && !(g.core_radius < g.radius)) t.error("core_radius", "the core must be smaller than the disk: core_radius < radius");
  } else {
    g.root = t.vec2("root");
    g.length = t.has("length") ? t.real("length") : 0.0;
    g.height = t.has("height") ? t.real("height") : 0.0;
    g.core_height = t.has("core_height") ? t.real("core_height") : 0.0;
    g.n_height = t.has("n_height") ? int(t.integer("n_height")) : 0;
    if (t.has("height") && t.has("core_height") && !(g.core_height < g.height)) t.error("core_height", "the core must be thinner than the beam: core_height < height");
  }
}

void read_mpm_options(SceneSpec& s, const TableReader& root) {
  const auto t = root.table("mpm"), grid = root.table("grid"), time = root.table("time");
  const auto bodies = root.array("body"), boundaries = root.array("boundary");
  const bool mpm = is_mpm(s.scene.method);
  if (t.present() && !mpm) root.error("mpm", "[mpm] is used by method = \"mpm\" only");
  for (std::size_t b = 0; b < bodies.size() && b < s.bodies.size(); ++b)
    if (s.bodies[b].particles.kind != ParticleGenerator::none && !mpm) bodies[b].error("particles", "generated particles are used by method = \"mpm\" only");
  MpmSpec& m = s.mpm;
  const bool coupled = s.scene.method == Method::mpm_fem;  // Newmark at the particles, as the FEM nodes have it
  m.scheme = t.string("scheme") == "particle_newmark" || (coupled && !t.has("scheme")) ? MpmScheme::particle_newmark : MpmScheme::grid_newmark;
  if (coupled && m.scheme != MpmScheme::particle_newmark)
    t.error("scheme", "method mpm_fem runs scheme = \"particle_newmark\" (the coupling of [Aulisa 2019] §4 keeps v, a at the particles)");
  const auto soft = t.table("soft_stiffness");
  m.soft_c1 = soft.real("c1"), m.soft_c2 = soft.real("c2");
  m.receding_contact = t.real("receding_contact");
  if (!mpm) return;
  const bool particle = m.scheme == MpmScheme::particle_newmark;
  if (!particle) {
    if (soft.present()) t.error("soft_stiffness", "the soft stiffness belongs to scheme = \"particle_newmark\"");
    if (t.has("receding_contact")) t.error("receding_contact", "receding contact belongs to scheme = \"particle_newmark\"");
    if (s.grid.quad9) grid.error("cells", "quad9 grids run scheme = \"particle_newmark\" (set [mpm] scheme)");
    for (const char* k : {"beta", "gamma"})
      if (time.has(k)) time.error(k, std::string("method mpm's grid_newmark integrates with beta = 1/4, gamma = 1/2 ([Moreno et al.]); ") + k +
                                         " is settable with [mpm] scheme = \"particle_newmark\"");
    for (std::size_t b = 0; b < bodies.size() && b < s.bodies.size(); ++b)
      if (s.bodies[b].particles.kind != ParticleGenerator::none)
        bodies[b].error("particles", "generated particles carry their own masses, which scheme = \"particle_newmark\" uses; grid_newmark samples a body mesh");
    for (std::size_t b = 0; b < boundaries.size() && b < s.boundaries.size(); ++b)
      if (s.boundaries[b].outside) boundaries[b].error("outside", "outside marks nodes for the soft stiffness of scheme = \"particle_newmark\"");
    return;
  }
  if (s.time.integrator != Integrator::newmark)
    time.error("integrator", "scheme = \"particle_newmark\" integrates with integrator = \"newmark\" (the particles carry v and a)");
  // A particle's velocity that the grid cannot represent sees no grid increment, and Newmark's particle update of
  // (v, dt a) then has the matrix [[1 - gamma/beta, 1 - gamma/(2 beta)], [-1/beta, 1 - 1/(2 beta)]]: det = 1 - (gamma
  // - 1/2) / beta, trace = 2 - (gamma + 1/2) / beta. Both eigenvalues lie in the unit disk without a repeated -1 only
  // if 2 beta > gamma strictly: at 2 beta = gamma = 1/2 (the average acceleration rule) the eigenvalue -1 is double
  // and such velocities grow linearly. The paper takes beta = 0.3, the default here.
  if (!time.has("beta")) s.time.beta = 0.3;
  if (2.0 * s.time.beta == s.time.gamma) {  // 2 beta < gamma is refused with every scheme (read_newmark_parameters)
    std::ostringstream os;
    os << "scheme = \"particle_newmark\" needs 2 beta > gamma strictly (beta = " << s.time.beta << ", gamma = " << s.time.gamma
       << "): at 2 beta = gamma the particles' update has a double eigenvalue -1 for velocities the grid cannot hold, which then "
          "grow step by step ([Aulisa 2019] takes beta = 0.3, the default of this scheme)";
    time.error(time.has("beta") ? "beta" : "gamma", os.str());
  }
  for (std::size_t b = 0; b < bodies.size() && b < s.bodies.size(); ++b)
    if (s.bodies[b].element != Formulation::p1 && !(coupled && s.bodies[b].element == Formulation::quad9))
      bodies[b].error("element", "scheme = \"particle_newmark\" is a displacement formulation: element = \"p1\" (it names the grid's "
                                 "displacement interpolation, whatever the cells)");
  if (s.grid.present && !s.grid.quad4 && !s.grid.quad9)
    grid.error("cells", "scheme = \"particle_newmark\" runs on quad9 or quad4 cells (the paper's grids are quad9)");
  if (s.grid.ghost_penalty > 0.0) grid.error("ghost_penalty", "scheme = \"particle_newmark\" steadies edge cells with [mpm.soft_stiffness]; set ghost_penalty = 0");
  if (t.has("receding_contact") && m.receding_contact > 0.0 && !s.grid.quad9)
    t.error("receding_contact", "the receding-contact extrapolation needs the three node rows of quad9 cells (grid.cells = \"quad9\")");
  for (std::size_t b = 0; b < boundaries.size() && b < s.boundaries.size(); ++b)
    if (s.boundaries[b].has_traction)
      boundaries[b].error("traction", "scheme = \"particle_newmark\" takes body forces only (tractions on particle sets are not implemented)");
}

void read_mpm_body(const SceneSpec& s, const TableReader& t, BodySpec& b) {
  b.particles_per_cell = int(t.integer("particles_per_cell"));
  if (s.scene.dimension == 3) {
    if (!t.has("particles_per_cell")) b.particles_per_cell = 4;
    const int n = b.particles_per_cell;
    if (t.has("particles_per_cell") && !has_tetrahedron_rule(n)) {
      std::string sizes;
      for (int k : tetrahedron_rule_sizes()) sizes += (sizes.empty() ? "" : ", ") + std::to_string(k);
      t.error("particles_per_cell", "no tetrahedron rule with " + std::to_string(n) + " points (available: " + sizes + ")");
    }
  } else if (t.has("particles_per_cell") && !has_triangle_rule(b.particles_per_cell)) {
    std::string sizes;
    for (int n : triangle_rule_sizes()) sizes += (sizes.empty() ? "" : ", ") + std::to_string(n);
    t.error("particles_per_cell", "no triangle rule with " + std::to_string(b.particles_per_cell) + " points (available: " + sizes + ")");
  }
  b.stabilisation = pick<Stabilisation>(t.string("stabilisation"), {{"none", Stabilisation::none}, {"ppp", Stabilisation::ppp},
                                                                    {"asgs", Stabilisation::asgs}, {"osgs", Stabilisation::osgs}});
  b.tau_c1 = t.real("tau_c1");
  b.tau_c2 = t.real("tau_c2");
  for (const char* k : {"stabilisation", "tau_c1", "tau_c2"})
    if (t.has(k) && b.element != Formulation::p1p1_up) t.error(k, std::string(k) + " is only used by element = \"p1p1_up\"");
  if (b.element == Formulation::p1p1_up && b.material != kNoIndex &&
      s.materials[std::size_t(b.material)].model != MaterialModel::neo_hooke_split)
    t.error("element", "p1p1_up takes the pressure of a deviatoric/volumetric split: use it with model = \"neo_hooke_split\"");
}

}  // namespace loom
