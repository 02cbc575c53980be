#include "engine/scene/smoothed_options.hpp"

#include <cmath>

namespace loom {

namespace {

// Where the history b^e of hencky_perzyna and drucker_prager is carried from step to step outside the smoothing domains.
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
    if (m.model == MaterialModel::drucker_prager)
      t.error("material", "drucker_prager's plastic flow changes the volume (dilatancy, the return to the apex), and the smoothed "
                          "elements take a domain's J from its history as sqrt(det b^e), true of isochoric flow only; run it with "
                          "method mpm (element p1) or with p1, tri6 (tet10) or quad9 in methods fem and pfem");
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
  } else if (has_history(m) && !carries_history(s.scene.method, b.element)) {
    // The material points of method mpm and the quadrature points of fem's and pfem's displacement elements carry
    // b^e (systems/assemble/materials/history_point.hpp, engine/methods/pfem/point_history_transfer.hpp).
    const char* why = b.element == Formulation::p1p1_up     ? " (its pressure equation is that of neo_hooke_split)"
                      : b.element == Formulation::p1p1_uphi ? " (its dilatation phi is that of neo_hooke)"
                                                            : "";
    const bool frictional = m.model == MaterialModel::drucker_prager;
    t.error("material", "material \"" + m.name + "\" " + (frictional ? "is plastic (drucker_prager): plasticity" : "yields (tau0): viscoplasticity") +
                            " needs an integration point that carries its history b^e from step to step (" +
                            (frictional ? "" : "the elements es_up, es_u, fem_up, fem_u; ") +
                            "p1, tri6 (tet10) and quad9 in methods fem and pfem; method mpm's particles with element p1), not " + element + why);
  }
}

}  // namespace loom
