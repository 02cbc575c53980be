// The validated, typed content of a scene file. Every value here has passed the schema and the semantic
// checks of the loader; builders (mesh, boundary regions) may still find errors that need the mesh
// (an empty region), so the specs keep the source position of the keys they came from.
#pragma once

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/core/types.hpp"
#include "engine/linalg/linear_solver.hpp"
#include "engine/mesh/generators.hpp"
#include "engine/store/cells.hpp"
#include "engine/scene/source.hpp"

namespace loom {

enum class Method { fem, pfem, es_pfem, mpm, mpm_fem };
inline const char* method_name(Method m) {
  constexpr const char* names[] = {"fem", "pfem", "es_pfem", "mpm", "mpm_fem"};
  return names[int(m)];
}
// The methods run by the mpm recipe: the background grid with material points, alone or coupled to FEM bodies.
inline bool is_mpm(Method m) { return m == Method::mpm || m == Method::mpm_fem; }
enum class Integrator { static_, euler_backward, newmark, bossak };
enum class InitialAcceleration { zero, equilibrium };
enum class Predictor { last_step, constant_acceleration };
enum class Stabilisation { none, ppp, asgs, osgs };
enum class EnergyPart { kinetic, elastic, total, potential, mechanical };
enum class MassKind { lumped, consistent };
enum class MaterialModel { neo_hooke, linear_elastic, neo_hooke_split, hencky_perzyna, drucker_prager };
// drucker_prager: which Mohr-Coulomb section its cone passes through.
enum class ConeMatch { plane_strain, compression, extension };
enum class TangentUpdate { every_iteration, once_per_step };
enum class MeshGenerator { rectangle, cooks_membrane, file, box };
enum class ProbeKind { reaction, point, newton, extent, pressure_jump, volume, remesh, energy, stress, wall_force, penetration, speed, mass,
                       angular_momentum, section };
enum class StressComponent { xx, yy, xy, zz, yz, xz, von_mises, pressure };
enum class RemeshQuantity { area_change, changed, rejected, isolated, merged, crossings, inserted, removed, flipped, slivers, capped, repaired };

// A scalar given as a number or an expression in t, x, y (compiled later by Expression).
struct ExpressionSpec {
  std::string text;  // muparser source; a number is stored as its decimal text
  SourceRef where;
  std::string key;   // display key path, for messages
};

struct SceneInfo {
  std::string name;
  Method method = Method::fem;
  int dimension = 2;
  std::string units, description;
};

struct TimeSpec {
  Integrator integrator = Integrator::static_;
  double dt = 1.0;
  int steps = 1;
  MassKind mass = MassKind::lumped;
  InitialAcceleration initial_acceleration = InitialAcceleration::zero;  // newmark, bossak
  Predictor predictor = Predictor::last_step;  // newmark, bossak (method fem): where Newton starts a step
  double alpha = -0.3;  // bossak: alpha_B in [-1/3, 0]
  double beta = 0.25, gamma = 0.5;  // newmark (fem; mpm with scheme particle_newmark)
  // time.stop_when: the run ends (completed) after the first step at t >= stop_after whose probe `stop_probe`
  // reads a magnitude below `stop_below` (a flow that has come to rest); time.steps is then an upper bound.
  Index stop_probe = kNoIndex;
  double stop_below = 0.0, stop_after = 0.0;
  bool stop_rate = false;  // stop_below bounds the probe's rate of change over the last stop_over of time
  double stop_over = 0.0;
  // time.adaptive_dt: each step's size from a formula in the latest value of a probe (named by the probe) and t,
  // evaluated at the step's start; the run ends at t = end (time.steps is then the most steps it may take).
  Index adaptive_probe = kNoIndex;
  std::string adaptive_expression;
  double end = 0.0;
};

struct SolverSpec {
  int max_iterations = 25;
  double residual_relative = 1e-8;
  double residual_absolute = 1e-10;
  double increment_relative = 1e-12;
  bool line_search = false;
  int max_cutbacks = 4;
  LinearSolverKind linear = LinearSolverKind::automatic;
  SourceRef linear_where;  // of solver.linear (or of [solver], or the file)
  double linear_tolerance = kDefaultCgTolerance;  // cg, and GMRES with reuse_factor: relative residual of each linear solve
  TangentUpdate tangent = TangentUpdate::every_iteration;
  bool reuse_factor = false;  // GMRES preconditioned by the last factorisation of the pattern (LinearSolve)
  std::string petsc_options;  // linear = petsc: PETSc options after loom's defaults
  SourceRef petsc_options_where;
};

// Elastic constants are kept in both forms; the loader derives the missing pair.
struct MaterialSpec {
  std::string name;
  MaterialModel model = MaterialModel::neo_hooke;
  double E = 0, nu = 0, K = 0, G = 0;
  double lambda = 0, mu = 0;  // Lamé constants (seed 000 eq 49-50)
  double density = 0;
  // hencky_perzyna (seed 001 §2): shear yield stress (infinite: Hencky elastic) and Bingham viscosity.
  double tau0 = std::numeric_limits<double>::infinity();
  double viscosity = 0;
  // drucker_prager: Mohr-Coulomb's friction and dilatancy angles (degrees) and cohesion, and the cone's match.
  double friction_angle = 0, dilatancy_angle = 0, cohesion = 0;
  ConeMatch cone = ConeMatch::plane_strain;
  SourceRef where;
};

// Hencky elasticity with a plastic return (hencky_perzyna, drucker_prager): the elements and particles see one model.
inline bool is_hencky(MaterialModel m) { return m == MaterialModel::hencky_perzyna || m == MaterialModel::drucker_prager; }
// Non-associated flow (drucker_prager with dilatancy_angle != friction_angle): the consistent tangent is unsymmetric,
// so a back-end that reads one triangle (CHOLMOD) would solve with another matrix and Newton would lose its rate.
inline bool has_unsymmetric_tangent(const MaterialSpec& m) {
  return m.model == MaterialModel::drucker_prager && m.dilatancy_angle != m.friction_angle;
}
// A material whose state is not a function of F: it carries the elastic history b^e from step to step.
inline bool has_history(const MaterialSpec& m) {
  return m.model == MaterialModel::drucker_prager || (m.model == MaterialModel::hencky_perzyna && std::isfinite(m.tau0));
}

struct MeshSpec {
  MeshGenerator generator = MeshGenerator::rectangle;
  Vec2 origin = Vec2::Zero();
  Vec2 size = Vec2::Ones();
  int nx = 1, ny = 1;
  GridPattern pattern = GridPattern::right;
  bool quads = false;  // generators: quadrilaterals (the body's element is quad9), pattern unused
  double scale = 1.0;
  double distortion = 0.0;
  long long seed = 1;
  std::string file;     // generator file: the mesh file, resolved (relative to the scene file's directory)
  std::string surface;  // generator file: the physical surface that is the body ("" = every triangle)
  std::string key;      // display key of the table, e.g. body[0].mesh
  SourceRef where;
  SourceRef file_where;
  // 3D: the z parts of the box generator, and the extrusion of a 2D generator's mesh (depth > 0).
  double origin_z = 0.0, size_z = 1.0;
  int nz = 1;
  double depth = 0.0;
  int layers = 1;
  bool bcc = false;  // generator box: the body-centred cubic lattice instead of Kuhn cubes (mesh.lattice)
};

struct VectorExpression {
  std::optional<ExpressionSpec> x, y, z;  // a component left out is absent (free / zero); z in 3D scenes only
  const std::optional<ExpressionSpec>& operator[](int d) const { return d == 0 ? x : d == 1 ? y : z; }
  bool any() const { return x || y || z; }
};

// Particles of seed 004's appendix, generated without a body mesh: a disk (uniform core + boundary layers)
// or a cantilever beam on a wall at x = root.x with centre line y = root.y.
enum class ParticleGenerator { none, disk, beam };
struct ParticleGeneratorSpec {
  ParticleGenerator kind = ParticleGenerator::none;
  Vec2 centre = Vec2::Zero();  // disk
  double radius = 0, core_radius = 0;
  int n_theta = 0;
  Vec2 root = Vec2::Zero();  // beam
  double length = 0, height = 0, core_height = 0;
  int n_height = 0;
  double factor = 1.0;  // boundary-layer refinement
  SourceRef where;
};

struct BodySpec {
  std::string name;
  Index material = 0;  // index into SceneSpec::materials
  Formulation element = Formulation::p1;
  double alpha_s = 0.0;  // PPP stabilisation of p1p1_uphi, stress units (resolved from the scene's formula)
  double alpha_stab = 0.0;  // PPP stabilisation of es_up and fem_up, dimensionless (seed 001 eq 48)
  bool j_projection = false;  // es_*, fem_*: b^e's volumetric part from the nodal J after every step (seed 001 eq 56)
  MeshSpec mesh;
  VectorExpression body_force;
  VectorExpression initial_velocity;  // at t = 0, in the reference position (engine/methods/model/initial_velocity.hpp)
  // Method mpm (seed 003):
  int particles_per_cell = 3;  // material points per body cell (triangle_rules)
  Stabilisation stabilisation = Stabilisation::asgs;  // p1p1_up
  double tau_c1 = 1.0, tau_c2 = 1.0;  // eq 21: tau1 = c1 h^2 / (2 mu), tau2 = 2 c2 mu
  ParticleGeneratorSpec particles;  // instead of particles_per_cell in a body mesh (seed 004 Appendix A)
  // Method mpm_fem, an FEM body (element quad9): its inertia with unit density instead of the material's, as
  // seed 004's eq 41 and its authors' code have it (the published plates are nearly massless, spec A3).
  bool unit_inertia = false;
  SourceRef where;
};

// The background grid of method mpm: a generated triangulation (MeshSpec's generators) or a rectangle of quad4 cells.
struct GridSpec {
  bool present = false;
  bool quad4 = false;  // cells = "quad4": bilinear cells of a rectangle
  bool quad9 = false;  // cells = "quad9": biquadratic cells of a graded rectangle (seed 004)
  Vec2 grading = Vec2::Ones();  // quad9: ratio of successive coarse cell sizes
  int refinements = 0;          // quad9: midpoint refinements J
  double ghost_penalty = 0.0;  // gamma_0 of the face ghost penalty (0: off)
  MeshSpec mesh;
};

struct BoundarySpec {
  std::string name;
  Index body = 0;
  Vec2 box_min = Vec2::Zero(), box_max = Vec2::Zero();
  double box_min_z = 0.0, box_max_z = 0.0;  // 3D
  std::string group;  // instead of the box: a physical group of the body's mesh file
  SourceRef region_where;
  // region.normal (with a traction only): the traction acts on the region's boundary edges (3D: faces) whose outward
  // normal lies within 45 degrees of this direction (stored as a unit vector, its z in normal_z in 3D scenes).
  std::optional<Vec2> normal;
  double normal_z = 0.0;
  SourceRef normal_where;
  VectorExpression displacement;
  VectorExpression traction;
  bool has_traction = false;
  std::optional<ExpressionSpec> pressure;  // mpm, p1p1_up: prescribed grid pressure
  bool outside = false;  // mpm particle_newmark: the region's grid nodes lower the soft-stiffness flags
};

// Rigid walls (seed 001 §1.8: ground and walls as planes with a normal penalty): a line through `point` whose
// `normal` points into the side the material may occupy, or a box whose four sides hold the material inside.
// A node of the named body (every body when kNoIndex) behind a plane, g = (x - point) . normal < 0, gets the
// penalty force -k_N A g normal (A: its share of the boundary length); with stick, also a tangential penalty
// that holds it at its first-contact point.
struct WallSpec {
  std::string name;
  std::vector<std::pair<Vec3, Vec3>> planes;  // (point, unit normal); z = 0 in 2D
  Index body = kNoIndex;
  double penalty = 0.0;  // k_N, force per unit length per unit penetration; 0: chosen from the material and mesh
  bool stick = false;
  double spacing = 0.0;  // remesh spacing at the wall (particle insertion and removal); 0: the body's
  double spacing_ramp = 0.0;  // distance over which that spacing grows to the body's; 0: one body spacing
  SourceRef where;
};

// Method mpm: the time scheme and seed 004's edge terms.
//  grid_newmark:     seed 003 (Moreno et al.): particles projected to the grid, lumped grid mass, Newmark on the grid;
//  particle_newmark: seed 004 (Aulisa & Capodaglio): particles are the quadrature points and carry the Newmark
//                    state, consistent particle mass, soft stiffness and receding contact.
enum class MpmScheme { grid_newmark, particle_newmark };
struct MpmSpec {
  MpmScheme scheme = MpmScheme::grid_newmark;
  double soft_c1 = 0.0, soft_c2 = 0.0;  // C_E for flags M_E < 5 and 5 <= M_E < 9
  double receding_contact = 0.0;       // C_c in [0, 1]
};

struct ProbeSpec {
  std::string name;
  ProbeKind kind = ProbeKind::newton;
  Index boundary = kNoIndex;  // reaction
  Index wall = kNoIndex;      // wall_force; penetration (kNoIndex: every wall)
  int component = 0;          // 0: x, 1: y (wall_force: 2, along the wall's normal)
  StressComponent stress = StressComponent::xx;  // stress
  Vec2 at = Vec2::Zero();     // point, stress
  double at_z = 0.0;          // its z in a 3D scene
  std::string group;          // point, stress: a physical point of the mesh file instead of `at` (resolved into `at`)
  Index body = kNoIndex;      // point (kNoIndex: any body), extent and pressure_jump
  bool max = true;            // extent: largest (true) or smallest coordinate
  double gap = 0.0;           // extent of particles (> 0): stop at the first gap wider than this (detached particles)
  RemeshQuantity quantity = RemeshQuantity::area_change;  // remesh
  Index inlet = kNoIndex;     // volume, mass: only the part of the body downstream of this inlet's section
  Vec3 normal = Vec3::Zero();  // section (3D): the unit normal of the plane through `at` that cuts the body
  EnergyPart energy = EnergyPart::total;  // energy
  bool has_reference = false;  // a reference value (a converged solution, a closed form) printed against the last value
  double reference = 0.0;
  SourceRef where;
};

// Inflow (seed 001 §4.4, §1.8 of its spec): material enters body `body` through the section from `from` to `to` at
// `velocity` (per unit time; it must point across the section) between t = start and start + duration. A row of
// particles behind the section, `spacing` apart (0: the body's initial mean edge length), is driven at the
// velocity; when it reaches the section it is released and a new row is added one spacing behind it.
struct InletSpec {
  std::string name;
  Index body = 0;
  Vec2 from = Vec2::Zero(), to = Vec2::Zero();
  Vec2 velocity = Vec2::Zero();
  double start = 0.0, duration = 0.0;
  double spacing = 0.0;
  // 3D (scene.dimension = 3): the section is the disc of `radius` about `centre` normal to the velocity (its z in
  // velocity_z); while the inlet runs the disc moves at section_velocity (perpendicular to the velocity: a nozzle).
  Vec3 centre = Vec3::Zero(), section_velocity = Vec3::Zero();
  double radius = 0.0, velocity_z = 0.0;
  SourceRef where;
};

// PFEM remeshing and state transfer (seed 000 §3).
struct PfemSpec {
  double alpha = 1.2;
  double lchar = 0.0;  // constant l_char when > 0
  bool local = true;   // l_char^loc (eqs 17-18)
  int every = 1;
  bool btm = false;    // map scheme: false = CPM
  int iso = 0;         // 0, 1, 2
  // Free surfaces (seed 001 §3.1): keep the triangles inside the previous boundary (the alpha test decides only
  // where surfaces meet or the body opens) instead of every triangle that passes the alpha test.
  bool constrained_surface = false;
  // Particle insertion and removal (factors of the body's spacing h0; 0: off), h0 (0: each body's initial mean
  // edge length).
  double insert_above = 0.0, remove_below = 0.0, spacing = 0.0;
  // 3D (systems/remesh/remesh_3d.hpp): keep a mesh that is still Delaunay (R3.7), or repair one that is nearly (R3.8);
  // the quality 3 r_in / R below which cells are improved by flips (R3.4; 0: none).
  bool keep_delaunay = true, repair = false;
  double flip_quality = 0.2;
  // es_pfem, dynamic: the mass that filled gaps (new material), as a fraction of the bodies' mass, above which a run fails.
  double max_new_material = 0.05;
};

struct OutputSpec {
  std::string directory;
  int every = 1;
  int checkpoint_every = 0;  // steps between checkpoints (0: none)
  bool nodal_stress = false; // point data nodal_stress and nodal_von_mises on mesh frames (fem, pfem, es_pfem)
  SourceRef where;           // of the directory key (or of [output])
};

struct SceneSpec {
  std::string file;          // path of the scene file
  std::string text_hash;     // hash of the file content and the --set overrides
  SceneInfo scene;
  TimeSpec time;
  SolverSpec solver;
  std::vector<MaterialSpec> materials;
  std::vector<BodySpec> bodies;
  GridSpec grid;
  MpmSpec mpm;
  std::vector<BoundarySpec> boundaries;
  std::vector<WallSpec> walls;
  std::vector<InletSpec> inlets;
  VectorExpression body_force;  // global, per unit mass
  std::vector<ProbeSpec> probes;
  PfemSpec pfem;
  OutputSpec output;
  // Things that are allowed but rarely meant (file:line:column: warning: key: why), printed on stderr by
  // the program; the run goes on.
  std::vector<std::string> warnings;
};

// Method mpm, mpm_fem: the body of material points (mpm_fem's other bodies are FEM bodies, element quad9).
inline Index mpm_body_index(const SceneSpec& s) {
  for (std::size_t b = 0; b < s.bodies.size(); ++b)
    if (s.bodies[b].element != Formulation::quad9) return Index(b);
  return 0;
}

inline bool has_unsymmetric_material(const SceneSpec& s) {
  for (const MaterialSpec& m : s.materials)
    if (has_unsymmetric_tangent(m)) return true;
  return false;
}

}  // namespace loom
