#include "engine/scene/scene_loader.hpp"

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "engine/core/errors.hpp"
#include "engine/scene/dimension_options.hpp"
#include "engine/scene/material_options.hpp"
#include "engine/scene/expression.hpp"
#include "engine/scene/mesh_options.hpp"
#include "engine/scene/method_checks.hpp"
#include "engine/scene/mpm_options.hpp"
#include "engine/scene/overrides.hpp"
#include "engine/scene/pfem_options.hpp"
#include "engine/scene/smoothed_options.hpp"
#include "engine/scene/probe_options.hpp"
#include "engine/scene/inlet_options.hpp"
#include "engine/scene/wall_options.hpp"
#include "engine/scene/loader_support.hpp"
#include "engine/scene/schema_validator.hpp"
#include "engine/scene/table_reader.hpp"

namespace loom {
namespace {

std::string hash_text(const std::string& text) {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a
  for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  std::ostringstream os;
  os << std::hex << h;
  return os.str();
}

void check_expression(const std::optional<ExpressionSpec>& e, Diagnostics& diag, int dimension) {
  if (!e) return;
  const std::string err = Expression::compile_error(e->text, dimension);
  if (!err.empty()) diag.error(e->where, e->key, "invalid expression \"" + e->text + "\": " + err);
}

VectorExpression read_vector(const TableReader& t, Diagnostics& diag, int dimension) {
  VectorExpression v;
  if (!t.present()) return v;
  v.x = t.expression("x");
  v.y = t.expression("y");
  v.z = t.expression("z");
  if (dimension < 3 && v.z) t.error("z", "a z component in a two-dimensional scene (scene.dimension = 2)");
  for (int d = 0; d < 3; ++d) check_expression(v[d], diag, dimension);
  return v;
}

class Loader {
 public:
  Loader(const toml::table& root, const std::string& file, Diagnostics& diag)
      : root_(&root, "", "", file, diag), diag_(diag) {}

  SceneSpec load() {
    SceneSpec s;
    read_scene(s);
    read_time(s);
    read_solver(s);
    for (const auto& m : root_.array("material")) read_material(s, m);
    for (const auto& b : root_.array("body")) read_body(s, b);
    for (const auto& b : root_.array("boundary")) read_boundary(s, b);
    for (const auto& w : root_.array("wall")) read_wall(s, w);
    for (const auto& i : root_.array("inlet")) read_inlet(s, i);
    s.body_force = read_vector(root_.table("body_force"), diag_, s.scene.dimension);
    for (const auto& p : root_.array("probe")) read_probe(s, p);
    read_stop_when(s);
    read_adaptive_dt(s);
    read_pfem_options(s, root_);
    const auto grid = root_.table("grid");
    s.grid.present = grid.present();
    if (grid.present()) read_grid(grid, s.grid), read_mesh_dimension(s.scene.dimension, grid, s.grid.mesh);
    if (grid.present() && s.scene.dimension == 2 && grid.has("file"))
      grid.error("file", "a background grid from a mesh file is three-dimensional (scene.dimension = 3); in 2D use a generator");
    read_output(s);
    check_mass(s);
    check_method_support(s, root_, diag_);
    check_dimension_support(s, root_);
    read_mpm_options(s, root_);
    return s;
  }

 private:
  void read_scene(SceneSpec& s) {
    const auto t = root_.table("scene");
    s.scene.name = t.string("name");
    if (t.has("name") && s.scene.name.empty()) t.error("name", "must not be empty");
    const std::string m = t.string("method");
    s.scene.method = pick<Method>(m, {{"fem", Method::fem}, {"pfem", Method::pfem}, {"es_pfem", Method::es_pfem},
                                      {"mpm", Method::mpm}, {"mpm_fem", Method::mpm_fem}});
    s.scene.dimension = int(t.integer("dimension"));
    s.scene.units = t.string("units");
    s.scene.description = t.string("description");
  }

  void read_time(SceneSpec& s) {
    const auto t = root_.table("time");
    s.time.integrator = pick<Integrator>(t.string("integrator"), {{"static", Integrator::static_}, {"euler_backward", Integrator::euler_backward},
                                                                  {"newmark", Integrator::newmark}, {"bossak", Integrator::bossak}});
    s.time.alpha = t.real("alpha");
    if (t.has("alpha") && s.time.integrator != Integrator::bossak) t.error("alpha", "alpha is used by integrator = \"bossak\" only");
    s.time.initial_acceleration = pick<InitialAcceleration>(t.string("initial_acceleration"), {{"zero", InitialAcceleration::zero},
                                                                                               {"equilibrium", InitialAcceleration::equilibrium}});
    if (t.has("initial_acceleration") && s.time.integrator != Integrator::newmark && s.time.integrator != Integrator::bossak)
      t.error("initial_acceleration", "initial_acceleration is used by integrator = \"newmark\" or \"bossak\" only");
    s.time.predictor = pick<Predictor>(t.string("predictor"), {{"last_step", Predictor::last_step},
                                                               {"constant_acceleration", Predictor::constant_acceleration}});
    if (t.has("predictor") && s.time.integrator != Integrator::newmark && s.time.integrator != Integrator::bossak)
      t.error("predictor", "predictor is used by integrator = \"newmark\" or \"bossak\" only");
    s.time.dt = t.real("dt");
    s.time.steps = int(t.integer("steps"));
    s.time.mass = pick<MassKind>(t.string("mass"), {{"lumped", MassKind::lumped}, {"consistent", MassKind::consistent}});
    // Default: the equilibrium acceleration of Newmark and Bossak, whose solve needs the lumped mass (zero with the
    // consistent one; the other integrators have none).
    const bool second_order = s.time.integrator == Integrator::newmark || s.time.integrator == Integrator::bossak;
    if (!t.has("initial_acceleration") && (!second_order || s.time.mass == MassKind::consistent))
      s.time.initial_acceleration = InitialAcceleration::zero;
    read_newmark_parameters(t, s.time);
  }

  // After the probes: time.stop_when names one.
  void read_stop_when(SceneSpec& s) {
    const auto t = root_.table("time").table("stop_when");
    if (!t.present()) return;
    const std::string probe = t.string("probe");
    s.time.stop_probe = find_by_name(s.probes, probe);
    if (t.has("probe") && s.time.stop_probe == kNoIndex) t.error("probe", "no [[probe]] named \"" + probe + "\" (known: " + names_of(s.probes) + ")");
    if (t.has("below") == t.has("rate_below")) t.error("", "give either below (the probe's magnitude) or rate_below (its rate of change)");
    s.time.stop_rate = t.has("rate_below");
    s.time.stop_below = s.time.stop_rate ? t.real("rate_below") : t.real("below");
    s.time.stop_over = t.real("over");
    if (t.has("over") && !s.time.stop_rate) t.error("over", "over is the window of rate_below");
    s.time.stop_after = t.real("after");
  }

  // After the probes: time.adaptive_dt names one, and its formula must evaluate.
  void read_adaptive_dt(SceneSpec& s) {
    const auto time = root_.table("time");
    const auto t = time.table("adaptive_dt");
    if (!t.present()) {
      if (time.has("end")) time.error("end", "end closes a run with time.adaptive_dt; with a fixed dt the run ends at steps * dt");
      return;
    }
    const std::string probe = t.string("probe");
    s.time.adaptive_probe = find_by_name(s.probes, probe);
    if (t.has("probe") && s.time.adaptive_probe == kNoIndex) t.error("probe", "no [[probe]] named \"" + probe + "\" (known: " + names_of(s.probes) + ")");
    s.time.adaptive_expression = t.string("expression");
    if (s.time.adaptive_probe != kNoIndex && t.has("expression")) {
      std::string err;
      const double dt = evaluate_formula(s.time.adaptive_expression, {{probe, 0.0}, {"t", 0.0}}, &err);
      if (!err.empty()) t.error("expression", "invalid formula \"" + s.time.adaptive_expression + "\" (it may use " + probe + " and t): " + err);
      else if (!(dt > 0.0)) t.error("expression", "the step must be > 0; at " + probe + " = 0, t = 0 it is " + std::to_string(dt));
    }
    if (!time.has("end")) time.error("", "time.adaptive_dt needs time.end, the time the run ends at");
    s.time.end = time.real("end");
  }

  void read_solver(SceneSpec& s) {
    const auto t = root_.table("solver");
    s.solver.max_iterations = int(t.integer("max_iterations"));
    s.solver.residual_relative = t.real("residual_relative");
    s.solver.residual_absolute = t.real("residual_absolute");
    s.solver.increment_relative = t.real("increment_relative");
    s.solver.line_search = t.boolean("line_search");
    s.solver.max_cutbacks = int(t.integer("max_cutbacks"));
    s.solver.linear = pick<LinearSolverKind>(t.string("linear"), {{"auto", LinearSolverKind::automatic},
                                                                  {"cholmod", LinearSolverKind::cholmod},
                                                                  {"umfpack", LinearSolverKind::umfpack},
                                                                  {"cg", LinearSolverKind::cg},
                                                                  {"cholmod_bisected", LinearSolverKind::cholmod_bisected},
                                                                  {"petsc", LinearSolverKind::petsc}});
    s.solver.linear_where = t.has("linear") ? t.where("linear") : t.where();
    s.solver.linear_tolerance = t.real("linear_tolerance");
    s.solver.tangent = pick<TangentUpdate>(t.string("tangent"), {{"every_iteration", TangentUpdate::every_iteration},
                                                                 {"once_per_step", TangentUpdate::once_per_step}});
    s.solver.reuse_factor = t.boolean("reuse_factor");
    s.solver.petsc_options = t.string("petsc_options");
    s.solver.petsc_options_where = t.has("petsc_options") ? t.where("petsc_options") : t.where();
    if (s.solver.linear == LinearSolverKind::petsc) {
      const std::string problem = petsc_solver_problem();
      if (!problem.empty()) t.error("linear", "solver.linear = \"petsc\": " + problem);
    } else if (!s.solver.petsc_options.empty()) {
      t.error("petsc_options", "solver.petsc_options applies only with solver.linear = \"petsc\"");
    }
    if (s.solver.reuse_factor && s.solver.linear == LinearSolverKind::cg)
      t.error("reuse_factor", "solver.linear = \"cg\" has no factorisation to reuse; use a direct back-end or reuse_factor = false");
    if (s.solver.reuse_factor && s.solver.tangent == TangentUpdate::once_per_step)
      t.error("reuse_factor", "tangent = \"once_per_step\" reuses the step's first factorisation already; choose one of the two");
  }

  void read_material(SceneSpec& s, const TableReader& t) {
    MaterialSpec m;
    m.name = read_name(t);
    m.where = t.where();
    if (find_by_name(s.materials, m.name) != kNoIndex) t.error("name", "a material named \"" + m.name + "\" already exists");
    m.model = pick<MaterialModel>(t.string("model"), {{"neo_hooke", MaterialModel::neo_hooke}, {"linear_elastic", MaterialModel::linear_elastic},
                                                                       {"neo_hooke_split", MaterialModel::neo_hooke_split},
                                                                       {"hencky_perzyna", MaterialModel::hencky_perzyna},
                                                                       {"drucker_prager", MaterialModel::drucker_prager}});
    read_plasticity(m, t, s.scene.dimension);
    m.density = t.real("density");
    const bool e_nu = t.has("E") || t.has("nu"), k_g = t.has("K") || t.has("G");
    if (e_nu && k_g) {
      t.error(t.has("K") ? "K" : "G", "give the elastic constants either as (E, nu) or as (K, G), not both");
    } else if (e_nu) {
      if (!t.has("E")) t.error("nu", "nu needs E");
      if (!t.has("nu")) t.error("E", "E needs nu");
      m.E = t.real("E"), m.nu = t.real("nu");
      // nu = 1/2: kappa and lambda are infinite (IEEE inf); only the mixed u-p formulation takes it.
      if (m.nu == 0.5 && m.model != MaterialModel::neo_hooke_split)
        t.error("nu", "nu = 0.5 (incompressible) needs model = \"neo_hooke_split\" and element = \"p1p1_up\" (method mpm); "
                      "other models must be in (-1, 0.5)");
      m.mu = m.E / (2 * (1 + m.nu));                            // seed 000 eq 49
      m.lambda = m.E * m.nu / ((1 + m.nu) * (1 - 2 * m.nu));
      m.G = m.mu, m.K = m.lambda + 2 * m.mu / 3;                 // eq 50
    } else if (k_g) {
      if (!t.has("K")) t.error("G", "G needs K");
      if (!t.has("G")) t.error("K", "K needs G");
      m.K = t.real("K"), m.G = t.real("G");
      m.mu = m.G, m.lambda = m.K - 2 * m.G / 3;                  // eq 50
      m.E = 9 * m.K * m.G / (3 * m.K + m.G);
      m.nu = (3 * m.K - 2 * m.G) / (2 * (3 * m.K + m.G));
    } else {
      t.error("", "missing elastic constants: give (E, nu) or (K, G)");
    }
    s.materials.push_back(m);
  }

  // quad9 is an element of method fem on generated quadrilaterals (PFEM remeshes triangles; the MPM grids
  // take their cell type from [grid]; gmsh quadrilaterals are not read yet).
  void check_quad9_body(SceneSpec& s, const TableReader& t, BodySpec& b) {
    if (s.scene.method == Method::mpm_fem) {  // an FEM body of the coupled method: a rectangle beside the grid
      if (b.mesh.generator != MeshGenerator::rectangle)
        t.table("mesh").error("generator", "an FEM body of method mpm_fem is a rectangle of quad9 cells beside the grid (generator = \"rectangle\")");
    } else if (s.scene.method != Method::fem)
      t.error("element", std::string("quad9 is an element of method = \"fem\" (method ") + method_name(s.scene.method) +
                             (is_mpm(s.scene.method) ? ": a quad9 background grid is grid.cells = \"quad9\")" : ")"));
    const auto mesh = t.table("mesh");
    if (b.mesh.generator == MeshGenerator::file)
      mesh.error("file", "element quad9 needs a generated mesh (generator = \"rectangle\" or \"cooks_membrane\"); mesh files are read as triangles");
    if (mesh.has("pattern")) mesh.error("pattern", "pattern cuts quadrilaterals into triangles: element quad9 keeps them, leave pattern out");
    b.mesh.quads = true;
  }

  void read_body(SceneSpec& s, const TableReader& t) {
    BodySpec b;
    b.name = read_name(t);
    b.where = t.where();
    if (find_by_name(s.bodies, b.name) != kNoIndex) t.error("name", "a body named \"" + b.name + "\" already exists");
    const std::string mat = t.string("material");
    b.material = find_by_name(s.materials, mat);
    if (t.has("material") && b.material == kNoIndex)
      t.error("material", "no [[material]] named \"" + mat + "\" (known: " + names_of(s.materials) + ")");
    // tet10 is tri6's counterpart: the quadratic isoparametric displacement formulation, on tetrahedra.
    const std::string element = t.string("element");
    b.element = pick<Formulation>(element, {{"p1", Formulation::p1}, {"tri6", Formulation::tri6}, {"p1p1_uphi", Formulation::p1p1_uphi},
                                            {"p1p1_up", Formulation::p1p1_up}, {"es_up", Formulation::es_up},
                                            {"es_u", Formulation::es_u}, {"fem_up", Formulation::fem_up}, {"fem_u", Formulation::fem_u},
                                            {"quad9", Formulation::quad9}, {"tet10", Formulation::tri6}});
    check_element_dimension(s.scene.dimension, s.scene.method, element, t);
    read_mpm_body(s, t, b);
    read_smoothed_body(s, t, b);
    if (b.element == Formulation::p1p1_uphi && b.material != kNoIndex &&
        s.materials[std::size_t(b.material)].model == MaterialModel::linear_elastic) {
      // phi is tied to det F (eq 26): a finite-strain constraint that a small-strain law cannot honour
      // (its volumetric stress follows tr eps, not J), and Newton stalls as nu -> 0.5.
      t.error("element", "p1p1_uphi is a finite-strain formulation (phi = det F); use it with model = \"neo_hooke\"");
    }
    if (b.element != Formulation::p1p1_uphi && t.has("alpha_s")) {
      t.error("alpha_s", "alpha_s is only used by element = \"p1p1_uphi\"");
    } else if (b.element == Formulation::p1p1_uphi && b.material != kNoIndex) {
      // seed 000 eq 30: a stress-like factor; a formula is evaluated in the body's material constants.
      const auto& material = s.materials[std::size_t(b.material)];
      const auto spec = t.expression("alpha_s");
      const std::string text = spec ? spec->text : t.string("alpha_s");
      std::string err;
      b.alpha_s = evaluate_formula(text, {{"K", material.K}, {"G", material.G}, {"E", material.E}, {"nu", material.nu}}, &err);
      if (!err.empty()) t.error("alpha_s", "invalid formula \"" + text + "\" (it may use K, G, E, nu): " + err);
      else if (!(b.alpha_s >= 0.0)) t.error("alpha_s", "must be >= 0, got " + std::to_string(b.alpha_s));
    }
    read_particle_generator(t, b);
    if (b.particles.kind == ParticleGenerator::none) read_mesh(t.table("mesh"), b.mesh);
    read_mesh_dimension(s.scene.dimension, t.table("mesh"), b.mesh);
    if (b.element == Formulation::quad9) check_quad9_body(s, t, b);
    const std::string inertia = t.string("inertia");
    b.unit_inertia = inertia == "unit_density";
    if (t.has("inertia") && !(s.scene.method == Method::mpm_fem && b.element == Formulation::quad9))
      t.error("inertia", "inertia chooses the density of an FEM body's inertia in method mpm_fem (element = \"quad9\")");
    b.body_force = read_vector(t.table("body_force"), diag_, s.scene.dimension);
    b.initial_velocity = read_vector(t.table("initial_velocity"), diag_, s.scene.dimension);
    if (t.has("initial_velocity") && s.time.integrator == Integrator::static_)
      t.error("initial_velocity", "an initial velocity needs a dynamic time.integrator (euler_backward, newmark or bossak); the scene is static");
    warn_if_locking(s, t, b);
    s.bodies.push_back(b);
  }

  // Linear displacement triangles lock as nu -> 1/2: the divergence-free displacements they can represent
  // are too few, and the answer comes out far too stiff without any sign of trouble (16 % on a bonded block
  // at nu = 0.4999, 73 % on Cook's membrane). Allowed (it is the baseline the other elements are measured
  // against), but said.
  void warn_if_locking(SceneSpec& s, const TableReader& t, const BodySpec& b) {
    if (b.element != Formulation::p1 || b.material == kNoIndex) return;
    const MaterialSpec& m = s.materials[std::size_t(b.material)];
    if (!(m.nu > 0.49)) return;
    std::ostringstream os;
    os << (t.has("element") ? t.where("element") : t.where()) << ": warning: body[" << s.bodies.size() << "].element: p1 (linear "
       << "displacement triangles) locks for nearly incompressible materials, and material \"" << m.name << "\" has nu = " << m.nu
       << " > 0.49: displacements come out too small (73 % on Cook's membrane at nu = 0.4999). Use element = "
       << (is_mpm(s.scene.method) ? "\"p1p1_up\" (mixed u-p, with model = \"neo_hooke_split\")"
                                         : "\"p1p1_uphi\" (mixed u-phi, model neo_hooke) or \"tri6\" (quadratic)");
    s.warnings.push_back(os.str());
  }


  void read_boundary(SceneSpec& s, const TableReader& t) {
    BoundarySpec b;
    b.name = read_name(t);
    if (find_by_name(s.boundaries, b.name) != kNoIndex) t.error("name", "a boundary named \"" + b.name + "\" already exists");
    if (t.has("body")) {
      const std::string body = t.string("body");
      b.body = find_by_name(s.bodies, body);
      if (b.body == kNoIndex) t.error("body", "no [[body]] named \"" + body + "\" (known: " + names_of(s.bodies) + ")");
    } else if (s.bodies.size() > 1 && !is_mpm(s.scene.method)) {  // mpm, mpm_fem: the grid (and FEM) nodes in the box, of any body
      t.error("", "missing key body (the scene has several bodies)");
    }
    const auto region = t.table("region");
    b.group = region.string("group");
    b.region_where = region.where(region.has("group") ? "group" : "box");
    if (region.present() && region.has("box") == region.has("group")) region.error("", "give either box or group");
    if (region.has("group") && is_mpm(s.scene.method))
      region.error("group", "method mpm selects grid nodes and loaded edges by box; physical groups select mesh nodes of fem and pfem bodies");
    if (region.has("group") && b.body != kNoIndex && std::size_t(b.body) < s.bodies.size() &&
        s.bodies[std::size_t(b.body)].mesh.generator != MeshGenerator::file)
      region.error("group", "body \"" + s.bodies[std::size_t(b.body)].name + "\" has a generated mesh, without groups: select by box");
    const auto box = region.box("box");
    b.box_min = box[0], b.box_max = box[1];
    if (region.has("box") && (box[0].x() > box[1].x() || box[0].y() > box[1].y()))
      region.error("box", "the first corner must be the lower-left one ([[xmin, ymin], [xmax, ymax]])");
    if (s.scene.dimension == 3) {
      b.box_min_z = region.box_component("box", 0, 2), b.box_max_z = region.box_component("box", 1, 2);
      if (region.has("box") && b.box_min_z > b.box_max_z) region.error("box", "the first corner must be the lowest one ([[xmin, ymin, zmin], [xmax, ymax, zmax]])");
    }
    b.displacement = read_vector(t.table("displacement"), diag_, s.scene.dimension);
    b.pressure = t.expression("pressure");
    check_expression(b.pressure, diag_, s.scene.dimension);
    const auto traction = t.table("traction");
    b.has_traction = traction.present();
    b.traction = read_vector(traction, diag_, s.scene.dimension);
    b.outside = t.boolean("outside");
    if (t.table("displacement").present() && !b.displacement.any())
      t.error("displacement", s.scene.dimension == 3 ? "give at least one component (x, y or z)" : "give at least one component (x or y)");
    if (region.has("normal")) read_region_normal(s.scene.dimension, t, region, b);
    s.boundaries.push_back(b);
  }

  // boundary[].region.normal: a direction that picks, out of the region's boundary edges (3D: faces), those its
  // traction acts on. Conditions on nodes (displacement, pressure, outside) would still act on every node of the
  // region, whatever the direction says: such a boundary is refused rather than half-filtered.
  void read_region_normal(int dimension, const TableReader& t, const TableReader& region, BoundarySpec& b) {
    Vec3 n(region.component("normal", 0), region.component("normal", 1), dimension == 3 ? region.component("normal", 2) : 0.0);
    const double largest = n.cwiseAbs().maxCoeff();
    const std::string selects = "region.normal selects the boundary edges (3D: faces) a traction acts on";
    const bool displacement = t.table("displacement").present();
    if (!(largest > 0.0)) {
      region.error("normal", "the direction must not be zero: " + selects + ", those whose outward normal lies within 45 degrees of it");
    } else if (!b.has_traction) {
      region.error("normal", selects + ", and this boundary has no traction" +
                                 (displacement ? "; its displacement acts on the region's nodes whatever their normal: leave normal out"
                                               : "; a displacement acts on the region's nodes: leave normal out"));
    } else if (displacement || b.pressure || b.outside) {
      const std::string what = displacement ? "displacement" : b.pressure ? "pressure" : "outside = true";
      region.error("normal", selects + ", but this boundary's " + what + " acts on every node of the region whatever the normal: "
                                       "give the traction a [[boundary]] of its own");
    } else {
      n = (n / largest).normalized();  // scaled first: a finite vector of huge numbers has an infinite norm
      b.normal = Vec2(n.x(), n.y());
      b.normal_z = n.z();
      b.normal_where = region.where("normal");
    }
  }

  void read_output(SceneSpec& s) {
    const auto t = root_.table("output");
    s.output.directory = t.has("directory") ? t.string("directory") : "out/" + s.scene.name;
    s.output.every = int(t.integer("every"));
    s.output.checkpoint_every = int(t.integer("checkpoint_every"));
    s.output.nodal_stress = t.boolean("nodal_stress");
    if (s.output.nodal_stress && is_mpm(s.scene.method))
      t.error("nodal_stress", std::string("method ") + (s.scene.method == Method::mpm ? "mpm" : "mpm_fem") +
                                  " writes each particle's stress (point data stress of the particles' file); nodal_stress averages "
                                  "the cells of fem, pfem and es_pfem meshes");
    s.output.where = t.has("directory") ? t.where("directory") : t.where();
  }

  // Inertia and body forces act through the density: a zero density would silently drop them.
  void check_mass(const SceneSpec& s) {
    const bool global_force = s.body_force.any();
    for (std::size_t b = 0; b < s.bodies.size(); ++b) {
      const auto& body = s.bodies[b];
      if (body.material == kNoIndex) continue;
      const auto& mat = s.materials[std::size_t(body.material)];
      if (mat.density > 0) continue;
      if (s.time.integrator != Integrator::static_)
        diag_.error(mat.where, "material[" + std::to_string(body.material) + "].density",
                    "density must be > 0 for the dynamic integrator (used by body \"" + body.name + "\")");
      else if (global_force || body.body_force.any())
        diag_.error(mat.where, "material[" + std::to_string(body.material) + "].density",
                    "density must be > 0: a body force acts on body \"" + body.name + "\"");
    }
  }

  TableReader root_;
  Diagnostics& diag_;
};

}  // namespace

SceneSpec load_scene_text(const std::string& text, const std::string& file, const std::vector<std::string>& overrides) {
  toml::table root;
  try {
    root = toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    std::ostringstream os;
    os << file << ":" << e.source().begin.line << ":" << e.source().begin.column << ": error: syntax: " << e.description();
    throw InputError(os.str());
  }
  std::string all = text;
  for (const auto& o : overrides) {
    apply_override(root, o);
    all += "\n--set " + o;
  }
  Diagnostics diag;
  validate_against_schema(root, file, diag);
  SceneSpec spec;
  if (diag.ok()) spec = Loader(root, file, diag).load();
  if (!diag.ok()) {
    // Report in file order.
    auto errors = diag.errors();
    std::stable_sort(errors.begin(), errors.end(), [](const Diagnostic& a, const Diagnostic& b) {
      return a.where.line != b.where.line ? a.where.line < b.where.line : a.where.column < b.where.column;
    });
    Diagnostics sorted;
    for (const auto& e : errors) sorted.error(e.where, e.key, e.message);
    sorted.throw_if_errors();
  }
  spec.file = file;
  spec.text_hash = hash_text(all);
  return spec;
}

SceneSpec load_scene(const std::string& file, const std::vector<std::string>& overrides) {
  std::error_code ec;
  LOOM_CHECK(!std::filesystem::is_directory(file, ec), InputError, file << ": error: cannot read the scene file: it is a directory");
  std::ifstream in(file, std::ios::binary);
  LOOM_CHECK(in, InputError, file << ": error: cannot read the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return load_scene_text(text.str(), file, overrides);
}

}  // namespace loom
