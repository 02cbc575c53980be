#include "engine/scene/smoothed_options.hpp"

#include <cmath>

namespace loom {

void read_hencky_perzyna(MaterialSpec& m, const TableReader& t) {
  const bool hp = m.model == MaterialModel::hencky_perzyna;
  for (const char* k : {"tau0", "viscosity"})
    if (t.has(k) && !hp) t.error(k, std::string(k) + " is used by model = \"hencky_perzyna\" only");
  if (!hp) return;
  if (t.has("tau0")) m.tau0 = t.real("tau0");
  m.viscosity = t.real("viscosity");
  if (t.has("viscosity") && !t.has("tau0")) t.error("viscosity", "viscosity acts above the yield stress: give tau0 too (without it the material is elastic)");
  // tau0 = 0 and mu = 0 leave no deviatoric stress once it flows: the tangent is singular.
  if (t.has("tau0") && m.tau0 == 0.0 && !(m.viscosity > 0.0))
    t.error("tau0", "tau0 = 0 needs viscosity > 0 (a Maxwell fluid); with both zero the material carries no shear stress");
}

namespace {

// Where hencky_perzyna's history b^e is carried from step to step outside the smoothing domains.
bool carries_history(Method method, Formulation element) {
  if (is_mpm(method)) return element == Formulation::p1;
  return (method == Method::fem || method == Method::pfem) &&
         (element == Formulation::p1 || element == Formulation::tri6 || element == Formulation::quad9);
}

}  // namespace

void read_smoothed_body(const SceneSpec& s, const TableReader& t, BodySpec& b) {
  const char* element = formulation_name(b.element);
  if (has_pressure(b.element)) {
    if (!t.has("alpha_stab"))
      t.error("element", std::string(element) + " needs alpha_stab, the dimensionless PPP factor of its pressure (0: unstabilised; the "
                                                 "[Reinold 2021] uses 0.5 for Cook's membrane and 200 for the flows)");
    else b.alpha_stab = t.real("alpha_stab");
  } else if (t.has("alpha_stab")) {
    t.error("alpha_stab", "alpha_stab is used by element = \"es_up\" or \"fem_up\" only");
  }
  // The third nodal dof is phi or p, one or the other in a run.
  for (const BodySpec& other : s.bodies)
    if ((has_pressure(b.element) && has_dilatation(other.element)) || (has_dilatation(b.element) && has_pressure(other.element)))
      t.error("element", std::string(element) + " and body \"" + other.name + "\"'s " + formulation_name(other.element) +
                             " cannot share a run: the third nodal unknown is the pressure of one and the dilatation of the other");
  b.j_projection = t.boolean("j_projection");
  if (t.has("j_projection") && !integrates_on_domains(b.element))
    t.error("j_projection", "j_projection is used by the elements es_up, es_u, fem_up and fem_u only");
  if (b.material == kNoIndex) return;
  const MaterialSpec& m = s.materials[std::size_t(b.material)];
  if (integrates_on_domains(b.element)) {
    if (m.model == MaterialModel::linear_elastic && (s.scene.method == Method::es_pfem || b.j_projection))
      t.error(s.scene.method == Method::es_pfem ? "material" : "j_projection",
              "linear_elastic is geometrically linear on a fixed mesh; remeshing and the J projection act on the finite-strain "
              "history of hencky_perzyna");
    // The smoothed elements assemble their inertia with the lumped mass of their triangles only.
    if (s.time.integrator != Integrator::static_ && s.time.mass == MassKind::consistent)
      t.error("element", std::string(element) + " integrates the inertia with the lumped mass: set time.mass = \"lumped\"");
    if (s.scene.method != Method::fem && s.scene.method != Method::es_pfem)
      t.error("element", std::string(element) + " runs with method = \"fem\" (fixed mesh) or \"es_pfem\" (remeshed); method " +
                             method_name(s.scene.method) + " takes other elements");
  } else if (s.scene.method == Method::es_pfem) {
    t.error("element", "method es_pfem takes the elements es_up, es_u, fem_up or fem_u, not " + std::string(element));
  } else if (std::isfinite(m.tau0) && !carries_history(s.scene.method, b.element)) {
    // The material points of method mpm and the quadrature points of fem's and pfem's displacement elements carry
    // b^e (systems/assemble/materials/history_point.hpp, engine/methods/pfem/point_history_transfer.hpp).
    const char* why = b.element == Formulation::p1p1_up     ? " (its pressure equation is that of neo_hooke_split)"
                      : b.element == Formulation::p1p1_uphi ? " (its dilatation phi is that of neo_hooke)"
                                                            : "";
    t.error("material", "material \"" + m.name + "\" yields (tau0): viscoplasticity needs an integration point that carries its history "
                        "b^e from step to step (the elements es_up, es_u, fem_up, fem_u; p1, tri6 (tet10) and quad9 in methods fem and "
                        "pfem; method mpm's particles with element p1), not " + element + why);
  }
}

}  // namespace loom
