#include "engine/scene/material_options.hpp"

#include <initializer_list>
#include <sstream>
#include <string>

#include "engine/scene/loader_support.hpp"

namespace loom {
namespace {

void read_hencky_perzyna(MaterialSpec& m, const TableReader& t) {
  if (t.has("tau0")) m.tau0 = t.real("tau0");
  m.viscosity = t.real("viscosity");
  if (t.has("viscosity") && !t.has("tau0")) t.error("viscosity", "viscosity acts above the yield stress: give tau0 too (without it the material is elastic)");
  // tau0 = 0 and mu = 0 leave no deviatoric stress once it flows: the tangent is singular.
  if (t.has("tau0") && m.tau0 == 0.0 && !(m.viscosity > 0.0))
    t.error("tau0", "tau0 = 0 needs viscosity > 0 (a Maxwell fluid); with both zero the material carries no shear stress");
}

void read_drucker_prager(MaterialSpec& m, const TableReader& t, int dimension) {
  if (!t.has("friction_angle")) {  // the checks below would only repeat it
    t.error("model", "model = \"drucker_prager\" needs friction_angle (degrees)");
    return;
  }
  m.friction_angle = t.real("friction_angle");
  m.dilatancy_angle = t.real("dilatancy_angle");
  m.cohesion = t.real("cohesion");
  if (!(m.friction_angle < 90.0)) t.error("friction_angle", "friction_angle must be below 90 degrees");
  // Dilatancy above friction: more plastic volume change than the friction accounts for (the plastic work of
  // some paths would be negative).
  if (m.dilatancy_angle > m.friction_angle) {
    std::ostringstream why;
    why << "dilatancy_angle must not exceed friction_angle (" << m.friction_angle << " degrees)";
    t.error("dilatancy_angle", why.str());
  }
  if (m.friction_angle == 0.0 && m.cohesion == 0.0)
    t.error("friction_angle", "friction_angle = 0 and cohesion = 0 leave the material no shear strength: give one of them");
  m.cone = dimension == 3 ? ConeMatch::compression : ConeMatch::plane_strain;
  if (t.has("cone"))
    m.cone = pick<ConeMatch>(t.string("cone"), {{"plane_strain", ConeMatch::plane_strain}, {"compression", ConeMatch::compression},
                                                {"extension", ConeMatch::extension}});
}

}  // namespace

void read_plasticity(MaterialSpec& m, const TableReader& t, int dimension) {
  const auto only_for = [&](MaterialModel model, const char* name, std::initializer_list<const char*> keys) {
    for (const char* k : keys)
      if (t.has(k) && m.model != model) t.error(k, std::string(k) + " is used by model = \"" + name + "\" only");
  };
  only_for(MaterialModel::hencky_perzyna, "hencky_perzyna", {"tau0", "viscosity"});
  only_for(MaterialModel::drucker_prager, "drucker_prager", {"friction_angle", "dilatancy_angle", "cohesion", "cone"});
  if (m.model == MaterialModel::hencky_perzyna) read_hencky_perzyna(m, t);
  if (m.model == MaterialModel::drucker_prager) read_drucker_prager(m, t, dimension);
}

}  // namespace loom
