#include "engine/scene/schema.hpp"

#include <sstream>
#include <unordered_map>

#include "engine/scene/schema_keys.hpp"

namespace loom {
namespace {

std::vector<KeySpec> build_schema() {
  const std::string expr = " A number or a muparser expression in t (time), x, y (and z in 3D: reference coordinates).";
  std::vector<KeySpec> s;
  // [scene]
  s.push_back(key("scene", K::table, "What the scene is and which method runs it. Papers are cited by short keys ([Schewe 2024], "
                  "[Moreno et al.], ...), listed under References in README.md.").require());
  s.push_back(key("scene.name", K::string, "Name of the scene; names the .pvd file and the default output directory.").require());
  s.push_back(key("scene.method", K::choice,
                  "Method (recipe) that runs the scene: fem (updated-Lagrangian finite elements on a fixed mesh), pfem (remeshing "
                  "every step, [Schewe 2024] §3), es_pfem (the edge-based smoothed elements remeshed every step, [Reinold 2021]) or mpm (implicit mixed material point method, [Moreno et al.]; with "
                  "mpm.scheme = \"particle_newmark\", [Aulisa 2019]'s implicit MPM); mpm_fem: that MPM on a quad9 grid coupled "
                  "monolithically to FEM bodies whose quad9 cells share the grid's nodes ([Aulisa 2019] §4).")
                  .one_of({"fem", "pfem", "es_pfem", "mpm", "mpm_fem"}).by_default("fem"));
  s.push_back(key("scene.dimension", K::integer,
                      "Spatial dimension: 2 (plane strain) or 3 (methods fem, pfem, es_pfem and mpm on tetrahedra: p1 = linear "
                      "tetrahedron, tet10, p1p1_uphi = mixed linear tetrahedron, the face-smoothed es_up, es_u, fem_up, fem_u; mpm: p1, "
                      "p1p1_up; every vector and box corner then takes 3 numbers, expressions may use z).")
                      .by_default("2").at_least(2).at_most(3));
  s.push_back(key("scene.units", K::string, "Units of the numbers in the scene, for the reader only; loom is unit-agnostic.").by_default("\"\""));
  s.push_back(key("scene.description", K::string, "Free text.").by_default("\"\""));
  // [time]
  s.push_back(key("time", K::table, "Time stepping.").require());
  s.push_back(key("time.integrator", K::choice,
                  "static: no inertia; euler_backward: implicit Euler ([Schewe 2024] eq 12; methods fem, pfem and es_pfem); newmark: Newmark "
                  "with time.beta, time.gamma (method mpm: on the grid with lumped mass and beta = 1/4, gamma = 1/2, [Moreno et al.] §3.3, "
                  "or at the particles, mpm.scheme); bossak: alpha-Bossak "
                  "(Wood, Bossak & Zienkiewicz 1980; [Reinold 2021] §3.6) with beta = (1 - alpha)^2 / 4, gamma = 1/2 - alpha (methods fem, "
                  "pfem and es_pfem).")
                  .one_of({"static", "euler_backward", "newmark", "bossak"}).by_default("static"));
  s.push_back(key("time.alpha", K::real,
                  "bossak: alpha_B in [-1/3, 0]; 0 is Newmark's average acceleration (no numerical damping), more negative damps the "
                  "highest frequencies more.").by_default("-0.3").at_least(-1.0 / 3.0).at_most(0));
  s.push_back(key("time.beta", K::real,
                  "newmark (method fem; method mpm with mpm.scheme = \"particle_newmark\"): beta of Newmark's method; unconditionally "
                  "stable for 2 beta >= gamma >= 1/2. 1/4 with gamma = 1/2 is the average acceleration rule; [Aulisa 2019] uses 0.3, the default "
                  "of mpm.scheme = \"particle_newmark\", which needs 2 beta > gamma strictly.")
                  .by_default("0.25").above(0).at_most(0.5));
  s.push_back(key("time.gamma", K::real, "newmark: gamma of Newmark's method (see time.beta); gamma > 1/2 damps.").by_default("0.5").at_least(0.5).at_most(1));
  s.push_back(key("time.dt", K::real, "Time step (pseudo-time for static runs; boundary expressions see t = step * dt).").require().above(0));
  s.push_back(key("time.steps", K::integer, "Number of steps.").require().at_least(1));
  s.push_back(key("time.mass", K::choice, "Mass matrix of dynamic integrators: row-sum lumped or consistent (mpm: lumped only).")
                  .one_of({"lumped", "consistent"}).by_default("lumped"));
  s.push_back(key("time.initial_acceleration", K::choice,
                  "newmark, bossak: the acceleration at t = 0. equilibrium: a_0 = M^-1 (f_ext - f_int) with the lumped mass, the state the "
                  "equations of motion give at t = 0, so that a load applied from t = 0 on (gravity, a step load) is integrated "
                  "exactly (a body falls at g); every method (mpm_fem, mpm's particle_newmark: the body force at the particles and at "
                  "the FEM bodies' free nodes, their f_int being 0). zero: a_0 = 0 ([Moreno et al.] Algorithm 1), which lags a load "
                  "applied at t = 0 by half a step (free fall: by g dt t / 2). Default equilibrium; zero with time.mass = "
                  "\"consistent\".")
                  .one_of({"zero", "equilibrium"}).by_default("equilibrium"));
  s.push_back(key("time.predictor", K::choice,
                  "newmark, bossak (methods fem, pfem, es_pfem): where Newton starts each step: last_step (u = u_n), or constant_acceleration "
                  "(u = u_n + dt v_n + dt^2 a_n / 2, whose residual is only f_int's change along a smooth path: fast rotations, "
                  "where u_n leaves the whole inertial force to the first Newton update).")
                  .one_of({"last_step", "constant_acceleration"}).by_default("last_step"));
  s.push_back(key("time.stop_when", K::table,
                  "End the run early, as completed, after the first step at t >= after whose probe reads a magnitude below `below` "
                  "(a flow that has come to rest: a speed probe), or has changed by less than rate_below * over in the last `over` of "
                  "time (a front that has stopped: an extent probe); time.steps is then the most steps the run may take."));
  s.push_back(key("time.stop_when.probe", K::string, "Name of the [[probe]] to watch.").require());
  s.push_back(key("time.stop_when.below", K::real, "The run stops when |probe| < below.").above(0));
  s.push_back(key("time.stop_when.rate_below", K::real,
                  "Instead of below: the run stops when the probe's mean rate of change over the last `over` of time is below this.").above(0));
  s.push_back(key("time.stop_when.over", K::real, "Window of rate_below (time).").by_default("1").above(0));
  s.push_back(key("time.stop_when.after", K::real, "Not before this time (a flow starting from rest).").by_default("0").at_least(0));
  s.push_back(key("time.adaptive_dt", K::table,
                  "Adaptive time step: each step's size is `expression`, a formula in the latest value of `probe` (written by its "
                  "name) and t, evaluated at the step's start (the value of the step before; [Aulisa 2019]'s bouncing disk takes "
                  "dt from the lowest particle's height). time.dt is then only the first step's bound for the checks, time.end "
                  "closes the run, and time.steps is the most steps it may take."));
  s.push_back(key("time.adaptive_dt.probe", K::string, "Name of the [[probe]] the step size follows.").require());
  s.push_back(key("time.adaptive_dt.expression", K::string,
                  "The step size, a muparser formula in the probe's name and t (e.g. \"bottom > -0.16 ? 0.005 : 0.001\").").require());
  s.push_back(key("time.end", K::real, "With time.adaptive_dt: the time at which the run ends.").above(0));
  add_solver_keys(s);  // [solver]: engine/scene/schema_solver.cpp
  // [[material]]
  s.push_back(key("material", K::table_array, "Materials; give either (E, nu) or (K, G).").require());
  s.push_back(key("material[].name", K::string, "Name bodies refer to.").require());
  s.push_back(key("material[].model", K::choice,
                  "Plane strain, F33 = 1. neo_hooke: psi = lambda/2 ln^2 J + mu/2 (F:F - 3) - mu ln J ([Schewe 2024] eqs 48-51); "
                  "linear_elastic: small-strain Hooke, sigma = lambda tr(eps) I + 2 mu eps; neo_hooke_split: psi = mu/2 (J^(-2/3) F:F - 3) "
                  "+ K/2 (J - 1)^2 ([Moreno et al.] §2.2), the material of the mixed u-p formulation; hencky_perzyna: Hencky elasticity "
                  "(quadratic in the logarithmic elastic strains) with Perzyna viscoplasticity of von Mises type, a Bingham material "
                  "([Reinold 2021] §2), for the elements es_up, es_u, fem_up and fem_u, the quadrature points of p1, tri6 (tet10) and "
                  "quad9 in methods fem and pfem and method mpm's particles (element p1), which carry its history b^e; "
                  "drucker_prager: the same Hencky elasticity with rate-independent Drucker-Prager plasticity and non-associated "
                  "flow (friction_angle, dilatancy_angle, cohesion; [de Souza Neto 2008] §8.3), for the elements and particles "
                  "that carry b^e except the smoothed ones (its flow changes the volume).")
                  .one_of({"neo_hooke", "linear_elastic", "neo_hooke_split", "hencky_perzyna", "drucker_prager"}).require());
  s.push_back(key("material[].E", K::real, "Young's modulus (with nu).").above(0));
  s.push_back(key("material[].nu", K::real,
                  "Poisson's ratio (with E), -1 < nu < 0.5; nu = 0.5 (incompressible, 1/kappa = 0) with model neo_hooke_split and "
                  "element p1p1_up.").above(-1).at_most(0.5));
  s.push_back(key("material[].K", K::real, "Bulk modulus (with G).").above(0));
  s.push_back(key("material[].G", K::real, "Shear modulus (with K).").above(0));
  s.push_back(key("material[].tau0", K::real,
                  "hencky_perzyna: yield stress in simple shear, tau_eq = sqrt(dev tau : dev tau / 2) <= tau0 (absent: elastic, no yield).").at_least(0));
  s.push_back(key("material[].viscosity", K::real,
                  "hencky_perzyna: Bingham plastic viscosity mu (steady simple shear: tau = tau0 + mu gammadot); 0: rate-independent "
                  "von Mises.").by_default("0").at_least(0));
  s.push_back(key("material[].friction_angle", K::real,
                  "drucker_prager: Mohr-Coulomb's friction angle phi in degrees, 0 <= phi < 90; the cone's slope eta and cohesion "
                  "factor xi follow from it (see cone). Yield: sqrt(J2) + eta p - xi c <= 0, p the mean stress (positive in tension).")
                  .at_least(0));
  s.push_back(key("material[].dilatancy_angle", K::real,
                  "drucker_prager: dilatancy angle psi in degrees, 0 <= psi <= friction_angle (psi = phi: associated flow; 0: "
                  "plastic flow at constant volume on the cone).").by_default("0").at_least(0));
  s.push_back(key("material[].cohesion", K::real, "drucker_prager: cohesion c (0: a cohesionless material, which carries no tension).")
                  .by_default("0").at_least(0));
  s.push_back(key("material[].cone", K::choice,
                  "drucker_prager: the Mohr-Coulomb section the cone matches: plane_strain (Mohr-Coulomb's friction and "
                  "dilatancy in the plane, for any dilatancy_angle, where the flow has no out-of-plane part), "
                  "compression (outer cone, triaxial compression) or extension (inner cone). Default: plane_strain in 2D, "
                  "compression in 3D.").one_of({"plane_strain", "compression", "extension"}));
  s.push_back(key("material[].density", K::real, "Reference mass density rho_0 (needed by dynamic integrators and body forces).").by_default("0").at_least(0));
  // [[body]]
  s.push_back(key("body", K::table_array, "Bodies: a mesh, a material and an element.").require());
  s.push_back(key("body[].name", K::string, "Name boundaries and probes refer to.").require());
  s.push_back(key("body[].material", K::string, "Name of a [[material]].").require());
  s.push_back(key("body[].element", K::choice,
                  "Element formulation: p1 (linear displacement triangle), tri6 (quadratic displacement triangle, [Schewe 2024] §4.1), "
                  "p1p1_uphi (mixed linear displacement / nodal volume dilatation with polynomial pressure projection, [Schewe 2024] "
                  "§4.2), p1p1_up (method mpm: mixed linear displacement / linear pressure on the grid, [Moreno et al.] eqs 16-26). Method mpm "
                  "takes p1 or p1p1_up; they are the formulation on the background grid. es_up, es_u: edge-based smoothed linear "
                  "triangles ([Reinold 2021] §3), mixed displacement / nodal pressure with PPP (alpha_stab) or displacement only; fem_up, "
                  "fem_u: the same integrated per triangle; all four with model hencky_perzyna, linear_elastic (geometrically linear), "
                  "neo_hooke or neo_hooke_split. "
                  "quad9 (method fem): biquadratic displacement quadrilateral, 3 x 3 Gauss points ([Aulisa 2019] §2.2), on the "
                  "quadrilaterals of a generated mesh (rectangle, cooks_membrane; no pattern); method mpm_fem: an FEM body, a rectangle "
                  "of quad9 cells (total Lagrangian, Newmark with consistent mass) outside the grid and sharing the grid's nodes along "
                  "a common side; it is refined grid.refinements times like the grid. 3D: p1 is the linear tetrahedron "
                  "(one point), tet10 the quadratic one (four points, VTK_QUADRATIC_TETRA order), p1p1_uphi the mixed linear "
                  "tetrahedron (N-check = 1/4, four points); es_up, es_u face-based smoothed linear tetrahedra (the domain of each "
                  "face; methods fem and es_pfem), fem_up, fem_u the same per tetrahedron.")
                  .one_of({"p1", "tri6", "p1p1_uphi", "p1p1_up", "es_up", "es_u", "fem_up", "fem_u", "quad9", "tet10"}).by_default("p1"));
  s.push_back(key("body[].alpha_stab", K::real,
                  "es_up, fem_up (required): dimensionless PPP factor of the pressure, (alpha_stab / G) int (q - q_mean)(p - p_mean) "
                  "([Reinold 2021] eq 48); 0: the unstabilised u-p element (ES-FEM-UP); the paper uses 0.5 (Cook's membrane) and 200 "
                  "(flows).").at_least(0));
  s.push_back(key("body[].j_projection", K::boolean,
                  "es_up, es_u, fem_up, fem_u: after every step, replace the volumetric part of each domain's b^e by the mean of its "
                  "nodes' J, which the particles carry from step to step ([Reinold 2021] eq 56; on a fixed mesh the ES-FEM-UP-J-proj of "
                  "§4.2). Off: es_pfem projects only the edges a remesh creates.").by_default("false"));
  s.push_back(key("body[].alpha_s", K::expression,
                  "PPP stabilisation factor alpha_s of p1p1_uphi ([Schewe 2024] eq 30), in stress units: a number, or a formula in the "
                  "material's K, G, E and nu (eq 47 suggests K; eq 52 and the benchmarks use K/10). Larger: smoother pressure, softer "
                  "response.").by_default("\"K/10\""));
  s.push_back(key("body[].particles_per_cell", K::integer,
                  "Method mpm: material points generated in each cell of the body mesh at the points of a symmetric triangle rule "
                  "(1, 3, 6, 12, 16 or 33; Dunavant), volume = rule weight x cell area, mass = density x volume. 3D: a symmetric "
                  "tetrahedron rule of 1, 4, 14 or 24 points (degrees 1, 2, 5, 6), default 4.")
                  .by_default("3").at_least(1).at_most(33));
  s.push_back(key("body[].stabilisation", K::choice,
                  "p1p1_up: none (Galerkin, unstable for nu -> 0.5), ppp (polynomial pressure projection, [Bochev 2006], factor "
                  "1/mu), asgs or osgs (variational subgrid scales, [Moreno et al.] §4 eqs 19-26).")
                  .one_of({"none", "ppp", "asgs", "osgs"}).by_default("asgs"));
  s.push_back(key("body[].tau_c1", K::real, "p1p1_up, asgs/osgs: c1 of tau1 = c1 h^2 / (2 mu), h = sqrt(grid cell area) ([Moreno et al.] eq 21).").by_default("1.0").above(0));
  s.push_back(key("body[].tau_c2", K::real, "p1p1_up, asgs/osgs: c2 of tau2 = 2 c2 mu ([Moreno et al.] eq 21).").by_default("1.0").above(0));
  s.push_back(key("body[].mesh", K::table,
                  "The body's mesh: a generator and its parameters, or a mesh file (method mpm: the mesh the particles are generated in).")
                  .require_unless("particles"));
  s.push_back(key("body[].inertia", K::choice,
                  "Method mpm_fem, an FEM body: the density of its inertia term. physical: rho_0 u'' with the material's density; "
                  "unit_density: u'' with density one, as [Aulisa 2019] eq 41 and its authors' code have it (their plates are nearly "
                  "massless). Its weight uses the material's density either way.")
                  .one_of({"physical", "unit_density"}).by_default("physical"));
  s.push_back(key("body[].particles", K::table,
                  "Method mpm, instead of a mesh: the particle sets of [Aulisa 2019] Appendix A, a uniform core with boundary layers "
                  "refined towards the surface, each particle with its own mass."));
  s.push_back(key("body[].particles.generator", K::choice,
                  "disk (centre, radius, core_radius, n_theta, factor) or beam (root, length, height, core_height, n_height, factor).")
                  .one_of({"disk", "beam"}).require());
  s.push_back(key("body[].particles.centre", K::vec2, "disk: centre.").by_default("[0.0, 0.0]"));
  s.push_back(key("body[].particles.radius", K::real, "disk: outer radius R (the last layer ends within a fraction of a layer of it).").above(0));
  s.push_back(key("body[].particles.core_radius", K::real, "disk: radius R_0 < R of the uniform core.").above(0));
  s.push_back(key("body[].particles.n_theta", K::integer, "disk: particles on the core's outer ring, N_theta0 (rings: floor(N_theta0 / 2 pi)).").at_least(7));
  s.push_back(key("body[].particles.root", K::vec2, "beam: the clamped end's centre (x on the wall, y the centre line).").by_default("[0.0, 0.0]"));
  s.push_back(key("body[].particles.length", K::real, "beam: length L.").above(0));
  s.push_back(key("body[].particles.height", K::real, "beam: height H.").above(0));
  s.push_back(key("body[].particles.core_height", K::real, "beam: height H_0 < H of the uniform core.").above(0));
  s.push_back(key("body[].particles.n_height", K::integer, "beam: particles across the core, N_H.").at_least(2));
  s.push_back(key("body[].particles.factor", K::real, "Each boundary layer is thinner than the one inside it by this factor (> 1).").above(1));
  s.push_back(key("body[].mesh.generator", K::choice,
                  "rectangle, or cooks_membrane (corners (0,0), (48,44), (48,60), (0,44)); give a generator or a file. 3D: box (origin, "
                  "size, divisions: a lattice of hexahedra each cut into six Kuhn tetrahedra), or rectangle and cooks_membrane "
                  "extruded along z over depth in divisions[2] layers (each prism cut into three tetrahedra, diagonals consistent between neighbours).")
                  .one_of({"rectangle", "cooks_membrane", "box"}).require_unless("file"));
  s.push_back(key("body[].mesh.lattice", K::choice,
                  "3D box: kuhn (six Kuhn tetrahedra per cube of the lattice), or bcc (the body-centred cubic lattice: the cube corners "
                  "and centres, whose Delaunay cells are congruent and unique inside the box, 3 r_in / R = 0.949; the lattice for method "
                  "pfem, whose remesh would otherwise choose anew between the cospherical Kuhn cells).").one_of({"kuhn", "bcc"}).by_default("kuhn"));
  s.push_back(key("body[].mesh.depth", K::real,
                  "3D: extrude the 2D generator's mesh from z = 0 to z = depth in divisions[2] layers (required with rectangle and "
                  "cooks_membrane in 3D).").above(0));
  s.push_back(key("body[].mesh.file", K::string,
                  "A mesh written by gmsh (.msh, format 4.1 or 2.2, ASCII or binary) of 3- or 6-node triangles in the plane z = 0 (3D: 4- or "
                  "10-node tetrahedra), relative to "
                  "the scene file (to the working directory when given with --set). 6-node triangles keep their mid-nodes (curved "
                  "edges). Its physical groups become regions that [[boundary]] (region.group) and probes (group) select."));
  s.push_back(key("body[].mesh.group", K::string, "With file: the physical surface (3D: volume) that is this body (default: every cell of the file)."));
  s.push_back(key("body[].mesh.origin", K::vec2, "Lower-left corner (rectangle).").by_default("[0.0, 0.0]"));
  s.push_back(key("body[].mesh.size", K::vec2, "Width and height (rectangle; required there)."));
  s.push_back(key("body[].mesh.divisions", K::ivec2, "Element edges along x and y (cooks_membrane: along the clamped-to-loaded direction and across).").require_unless("file"));
  s.push_back(key("body[].mesh.pattern", K::choice, "Triangulation of the grid: right, alternating, or shifted ([Schewe 2024] Fig 7b).")
                  .one_of({"right", "alternating", "shifted"}).by_default("right"));
  s.push_back(key("body[].mesh.scale", K::real, "Factor applied to all coordinates after generation (or reading: a mesh in m used in mm takes 1000).").by_default("1.0").above(0));
  s.push_back(key("body[].mesh.distortion", K::real, "Random move of interior nodes, as a fraction of the node's smallest altitude (no cell can invert up to 0.25).").by_default("0.0").at_least(0).at_most(0.25));
  s.push_back(key("body[].mesh.seed", K::integer, "Seed of the distortion.").by_default("1").at_least(0));
  s.push_back(key("body[].body_force", K::table, "Body force per unit mass on this body (added to the global [body_force])."));
  s.push_back(key("body[].body_force.x", K::expression, "x component." + expr).by_default("0"));
  s.push_back(key("body[].body_force.y", K::expression, "y component." + expr).by_default("0"));
  s.push_back(key("body[].body_force.z", K::expression, "z component (3D)." + expr).by_default("0"));
  s.push_back(key("body[].initial_velocity", K::table,
                  "The body's velocity at t = 0, a field in the reference position (dynamic integrators only: the nodes of "
                  "fem, pfem and es_pfem bodies, the particles of an mpm body, the nodes of an mpm_fem FEM body)."));
  s.push_back(key("body[].initial_velocity.x", K::expression, "x component, in x and y (t = 0), e.g. \"-0.5 * y\" for a rotation.").by_default("0"));
  s.push_back(key("body[].initial_velocity.y", K::expression, "y component, in x and y (t = 0).").by_default("0"));
  s.push_back(key("body[].initial_velocity.z", K::expression, "z component (3D), in x, y and z (t = 0).").by_default("0"));
  // [grid]
  s.push_back(key("grid", K::table,
                  "Method mpm: the background grid ([Moreno et al.] §3), fixed triangles or squares that need not conform to the body and "
                  "must contain the particles at all times; only cells holding particles are active."));
  s.push_back(key("grid.cells", K::choice,
                  "Cell type: tri3 (linear triangles, the P1 grids of [Moreno et al.]), quad4 (bilinear squares of a rectangle; generator = "
                  "\"rectangle\" without pattern or distortion) or quad9 (biquadratic cells of a rectangle, graded and refined, [Aulisa 2019]; "
                  "mpm.scheme = \"particle_newmark\").")
                  .one_of({"tri3", "quad4", "quad9"}).by_default("tri3"));
  s.push_back(key("grid.grading", K::vec2,
                  "quad9: ratio of the size of each coarse cell to the one before it along x and y (left to right, bottom to top).")
                  .by_default("[1.0, 1.0]"));
  s.push_back(key("grid.refinements", K::integer,
                  "quad9: midpoint refinements J of the coarse cells (each cell into four; [Aulisa 2019] §6).").by_default("0").at_least(0).at_most(8));
  s.push_back(key("grid.ghost_penalty", K::real,
                  "gamma_0 of the face ghost penalty on the sides of cut cells (jumps of the normal gradient of u, weight "
                  "gamma_0 mu h, and of p, gamma_0 h^3 / (2 mu)); it steadies nodes of nearly empty cells, which quad4 grids "
                  "need at the body's boundary (docs/mpm/README.md §6). 0: off. Default: 0.1 for quad4 cells, 0 for tri3.")
                  .at_least(0));
  s.push_back(key("grid.generator", K::choice,
                  "rectangle (located by arithmetic unless shifted or distorted) or cooks_membrane (located by walking). 3D: box (origin, "
                  "size, divisions: cubes each cut into six Kuhn tetrahedra, located by arithmetic unless distorted).")
                  .one_of({"rectangle", "cooks_membrane", "box"}).require_unless("file"));
  s.push_back(key("grid.file", K::string,
                  "3D: a gmsh mesh of 4- or 10-node tetrahedra (their corners make the tet4 grid), relative to the scene file; "
                  "located by walking from each point's last cell, with a bucket index to start."));
  s.push_back(key("grid.origin", K::vec2, "Lower-left corner (rectangle).").by_default("[0.0, 0.0]"));
  s.push_back(key("grid.size", K::vec2, "Width and height (rectangle; required there)."));
  s.push_back(key("grid.divisions", K::ivec2, "Cell edges along x and y (3D box: and z).").require_unless("file"));
  s.push_back(key("grid.pattern", K::choice, "Triangulation of the squares (tri3): right, alternating, or shifted.")
                  .one_of({"right", "alternating", "shifted"}).by_default("right"));
  s.push_back(key("grid.scale", K::real, "Factor applied to all coordinates after generation.").by_default("1.0").above(0));
  s.push_back(key("grid.distortion", K::real, "Random move of interior grid nodes (fraction of the smallest altitude).").by_default("0.0").at_least(0).at_most(0.25));
  s.push_back(key("grid.seed", K::integer, "Seed of the distortion.").by_default("1").at_least(0));
  // [mpm]
  s.push_back(key("mpm", K::table, "Method mpm: the time scheme and the edge terms of [Aulisa 2019]."));
  s.push_back(key("mpm.scheme", K::choice,
                  "grid_newmark: [Moreno et al.] §3.3, the particles' mass, velocity and acceleration projected to the grid, lumped grid mass, "
                  "Newmark with beta = 1/4, gamma = 1/2 on the grid, the particles taking the grid's velocity increment (FLIP); particle_newmark: [Aulisa 2019] §3, nothing projected, the particles "
                  "are the quadrature points and carry the Newmark state (consistent particle mass; time.beta, time.gamma), with soft "
                  "stiffness and receding contact; displacement element p1 only.")
                  .one_of({"grid_newmark", "particle_newmark"}).by_default("grid_newmark"));
  s.push_back(key("mpm.soft_stiffness", K::table,
                  "particle_newmark: [Aulisa 2019] eq 26, mu C_E int (grad u + grad u^T) : grad v on active cells whose flag M_E (nodes not "
                  "shared with an empty cell or a boundary marked outside) is below the cell's node count: C_E = c1 for M_E < 5, c2 otherwise."));
  s.push_back(key("mpm.soft_stiffness.c1", K::real, "C_E of cells with M_E < 5 (the paper: 1e-2 ... 1e-5, smaller for stiffer bodies).").by_default("0").at_least(0));
  s.push_back(key("mpm.soft_stiffness.c2", K::real, "C_E of cells with 5 <= M_E < 9 (the paper: 1e-6 ... 1e-10).").by_default("0").at_least(0));
  s.push_back(key("mpm.receding_contact", K::real,
                  "particle_newmark, quad9: C_c of [Aulisa 2019] §5: particles of a cell on a fixed wall (all three side nodes held in x and y) "
                  "that moved away from it in the last step build F from wall displacements extrapolated from the cell's interior rows, "
                  "so that the sticky grid contact lets go; 0: off, 1: full extrapolation.")
                  .by_default("0").at_least(0).at_most(1));
  // [[boundary]]
  s.push_back(key("boundary", K::table_array, "Named regions with optional conditions on them."));
  s.push_back(key("boundary[].name", K::string, "Name probes refer to.").require());
  s.push_back(key("boundary[].body", K::string, "Body the region selects from (may be left out when there is one body, and in methods mpm and mpm_fem, whose regions select grid and FEM nodes of any body)."));
  s.push_back(key("boundary[].region", K::table,
                  "Region: nodes inside the box (or of the group), and boundary edges with both end nodes inside. Method mpm: a "
                  "displacement or pressure acts on the grid nodes in the box, a traction on the body mesh's boundary edges (3D: faces) in "
                  "the box (carried by traction points that move with the body).").require());
  s.push_back(key("boundary[].region.box", K::box, "[[xmin, ymin], [xmax, ymax]] in reference coordinates (3D: [[xmin, ymin, zmin], [xmax, ymax, zmax]]; bounds included, to 1e-9 of the body size). 3D: the region's boundary faces are those with every corner inside."));
  s.push_back(key("boundary[].region.group", K::string,
                  "Instead of box: a physical group of the body's mesh file (a curve, a point or a surface); its nodes, and the mid-node "
                  "of every edge whose two corners are in it."));
  s.push_back(key("boundary[].region.normal", K::vec2,
                  "A direction (any length, not zero; 3 numbers in 3D): the region's boundary edges (3D: faces) whose outward normal lies "
                  "within 45 degrees of this direction; for tractions (e.g. [1, 0] loads only the end x = L of a beam with a box across "
                  "its whole end, not the top and bottom edges in the box). A boundary with normal takes a traction and no displacement, "
                  "pressure or outside, which act on every node of the region: give those a [[boundary]] of their own."));
  s.push_back(key("boundary[].displacement", K::table,
                  "Prescribed displacement; a component left out stays free (a roller). Method mpm: each step moves the region's "
                  "grid nodes by g(t_n+1) - g(t_n), so g must vanish at t = 0 (the particles start undisplaced)."));
  s.push_back(key("boundary[].displacement.x", K::expression, "Prescribed u_x." + expr));
  s.push_back(key("boundary[].displacement.y", K::expression, "Prescribed u_y." + expr));
  s.push_back(key("boundary[].displacement.z", K::expression, "Prescribed u_z (3D)." + expr));
  s.push_back(key("boundary[].traction", K::table, "Dead-load traction per unit reference length on the region's boundary edges ([Schewe 2024] eq 8; "
                  "with region.normal, on those facing it)."));
  s.push_back(key("boundary[].traction.x", K::expression, "x component." + expr).by_default("0"));
  s.push_back(key("boundary[].traction.y", K::expression, "y component." + expr).by_default("0"));
  s.push_back(key("boundary[].traction.z", K::expression, "z component (3D; per unit reference area on the region's boundary faces)." + expr).by_default("0"));
  s.push_back(key("boundary[].outside", K::boolean,
                  "Method mpm, mpm.soft_stiffness: the region's grid nodes count as outside the body in the flags M_E (the authors' code "
                  "marks every outer boundary of the disk grids this way, not the beam's clamped wall).").by_default("false"));
  s.push_back(key("boundary[].pressure", K::expression, "Method mpm, p1p1_up: prescribed grid pressure p (sigma = sigma_dev + p I) at the region's grid nodes, "
                  "e.g. to fix the pressure level of an enclosed incompressible body." + expr));
  add_free_surface_keys(s);  // [[wall]], [[inlet]], [remesh], [map]: engine/scene/schema_free_surface.cpp
  // [body_force]
  s.push_back(key("body_force", K::table, "Body force per unit mass on every body (gravity: y = -9.81); needs density > 0."));
  s.push_back(key("body_force.x", K::expression, "x component." + expr).by_default("0"));
  s.push_back(key("body_force.y", K::expression, "y component." + expr).by_default("0"));
  s.push_back(key("body_force.z", K::expression, "z component (3D)." + expr).by_default("0"));
  // [[probe]]
  s.push_back(key("probe", K::table_array, "Quantities written to probes.csv every step."));
  s.push_back(key("probe[].name", K::string, "Column name in probes.csv.").require());
  s.push_back(key("probe[].kind", K::choice,
                  "reaction: sum over the boundary's prescribed dofs of the force the constraint exerts on the body "
                  "(f_int + M a - f_ext); point: displacement of the node nearest to `at`; newton: Newton iterations of the step; "
                  "extent: largest (bound = max) or smallest coordinate of a body's nodes along `component`; "
                  "pressure_jump: mean |p_1 - p_2| of the cell pressures across the interior edges of a body (pressure oscillation); "
                  "volume: area of a body in the current configuration; remesh (pfem): a `quantity` of the step's remesh; "
                  "energy (mpm, mpm_fem): kinetic sum m v^2 / 2, elastic sum V_0 psi(F) of the particles (and of the FEM bodies' "
                  "Gauss points, with their consistent mass), total = kinetic + elastic, potential -sum m b . u of the body force "
                  "and -sum f . u of the boundary tractions at the step's time (u from the start), mechanical = kinetic + elastic + potential; fem and pfem (elements p1, tri6, "
                  "quad9, materials neo_hooke and linear_elastic, lumped mass): the same of the nodes' lumped masses and the "
                  "quadrature points, potential -f_ext . u of the nodal external loads; the smoothed elements (es_up, es_u, fem_up, "
                  "fem_u; methods fem and es_pfem): the energy stored in their domains' b^e (es_up and fem_up: its deviatoric part, and "
                  "1/2 p^T K_pp p of the pressure unknown). "
                  "stress (fem, pfem, es_pfem; 2D and 3D): a `component` of the Cauchy stress at `at` (xx, yy, xy, zz, von_mises, "
                  "or pressure = -tr/3; in 3D also yz and xz), extrapolated linearly from the quadrature points of the cell that "
                  "holds the point (three of a tri6, four of a tet10) and averaged over the cells that share it (a node, an edge, a "
                  "face). "
                  "Method mpm: point probes follow a tracer point that starts at `at` and moves with the grid (the material "
                  "point at `at`), extent probes the particles, pressure_jump is the mean |p_a - p_b| over the active grid's sides. "
                  "wall_force: a `component` (x, y, or normal: along the wall's normal, a single plane) of the force the `wall` exerts "
                  "on the bodies; penetration: the largest distance of a node behind the `wall` (or behind any wall), >= 0. "
                  "speed (fem, pfem, es_pfem): the largest speed |v| of a body's nodes (a flow at rest). mass (fem, pfem, es_pfem): the "
                  "body's mass, density times its reference area (the area it would have unstressed: volume is smaller by what the "
                  "pressure compresses it). volume and mass with `inlet`: only what lies downstream of the inlet's section (the poured "
                  "material). angular_momentum (dynamic fem, pfem, es_pfem with "
                  "the lumped mass; mpm): sum m (r x v), r from `at` (default the origin), of the nodes or particles. section (3D fem, pfem, "
                  "es_pfem): the cut of a body by the plane through `at` with `normal`: its area (component = \"area\", the default), or "
                  "the largest (bound = \"min\": smallest) x, y or z of the cut (the width and height of a printed layer).")
                  .one_of({"reaction", "point", "newton", "extent", "pressure_jump", "volume", "remesh", "energy", "angular_momentum", "stress", "wall_force",
                           "penetration", "speed", "mass", "section"}).require());
  s.push_back(key("probe[].inlet", K::string, "Of a volume or mass probe: count only the part of the body downstream of this [[inlet]]'s section."));
  s.push_back(key("probe[].wall", K::string, "Wall of a wall_force probe, or of a penetration probe (default: every wall)."));
  s.push_back(key("probe[].boundary", K::string, "Boundary of a reaction probe."));
  s.push_back(key("probe[].component", K::choice, "Component of a reaction, point or extent probe (x, y; 3D: z; an extent probe in 3D also r, the distance from the z axis, sqrt(x^2 + y^2): the spread of a slump), of a 3D angular_momentum probe (x, y, z), of a wall_force probe (x, y, normal), of a section probe (area, x, y, z), or of a stress probe (xx, yy, xy, zz, von_mises, pressure; 3D also yz, xz).")
                  .one_of({"x", "y", "z", "r", "normal", "area", "xx", "yy", "xy", "zz", "yz", "xz", "von_mises", "pressure"}));
  s.push_back(key("probe[].at", K::vec2, "Reference coordinates of a point or stress probe; of an angular_momentum probe, the point the moments are taken about (default the origin); a point of a section probe's plane."));
  s.push_back(key("probe[].normal", K::vec2, "Of a section probe (3D): the normal of the cutting plane (need not be a unit vector)."));
  s.push_back(key("probe[].group", K::string, "Instead of at: a physical point of the body's mesh file, where the point or stress probe reads."));
  s.push_back(key("probe[].body", K::string, "Body of a point probe (default: nearest node of any body), of an extent or pressure_jump probe (default: the only body)."));
  s.push_back(key("probe[].gap", K::real,
                  "An extent probe of method mpm's particles: the extent of the particles reached from the other end without a gap "
                  "wider than this along the component, so that particles detached from the body's edge (a granular front's "
                  "strays) do not count (absent: every particle). The walk starts at the other end's particle: give it a body "
                  "held there (a wall), since a stray at that end stops it at once.").above(0));
  s.push_back(key("probe[].bound", K::choice, "Which extent (of an extent probe, or a section probe's x, y or z): max or min.").one_of({"max", "min"}).by_default("max"));
  s.push_back(key("probe[].reference", K::real,
                  "A reference value of the probe (a converged solution, a closed form, a measurement): at the end of a run loom "
                  "prints the probe's last value against it with their relative difference. Informational: it does not change the "
                  "run or its exit code."));
  s.push_back(key("probe[].quantity", K::choice,
                  "Of a remesh probe: area_change (area after - area before, summed over bodies), changed (1 if the connectivity changed), "
                  "rejected (triangles removed by the alpha test), isolated (particles in no triangle), merged (remesh.surface = "
                  "constrained: triangles added where two surfaces met), crossings (boundary edges left out of the constraints because "
                  "they crossed another), inserted and removed (particles added and taken away by remesh.insert_above, "
                  "remesh.remove_below and [[inlet]]s). 3D (cells are tetrahedra, areas volumes): flipped (flips that removed slivers), "
                  "slivers (tetrahedra still below 0.1 in 3 r_in / R after them), capped (flat cells on the previous surface left out), repaired (flips of remesh.repair).")
                  .one_of({"area_change", "changed", "rejected", "isolated", "merged", "crossings", "inserted", "removed", "flipped", "slivers",
                           "capped", "repaired"}));
  s.push_back(key("probe[].energy", K::choice, "Which energy of an energy probe.").one_of({"kinetic", "elastic", "total", "potential", "mechanical"}).by_default("total"));
  // [output]
  s.push_back(key("output", K::table, "Where and how often results are written."));
  s.push_back(key("output.directory", K::string, "Output directory (relative to the working directory); `loom run --out` replaces it.")
                  .by_default("\"out/<scene.name>\""));
  s.push_back(key("output.every", K::integer, "Steps between VTK frames (0: no frames); the initial and the last state are always written.").by_default("1").at_least(0));
  s.push_back(key("output.checkpoint_every", K::integer,
                  "Steps between checkpoints (0: none): checkpoint_NNNNNN.loom in the output directory, one binary file with the "
                  "whole state of the run; only the newest is kept, and one is also written when the run is interrupted "
                  "(SIGINT, SIGTERM). `loom run SCENE --restart DIR` continues from it as if the run had not stopped.")
                  .by_default("0").at_least(0));
  s.push_back(key("output.nodal_stress", K::boolean,
                  "Also write the stress at the nodes (methods fem, pfem, es_pfem): point data nodal_stress (9 components, "
                  "row-major) and nodal_von_mises, each node's value the mean of the cell data stress of the cells that share "
                  "it, weighted by their current volume (area in 2D): smooth contours in ParaView, where the cell data show "
                  "one value per cell.")
                  .by_default("false"));
  return s;
}

}  // namespace

const char* value_kind_name(ValueKind k) {
  switch (k) {
    case K::table: return "table";
    case K::table_array: return "array of tables";
    case K::string: return "string";
    case K::choice: return "string";
    case K::real: return "number";
    case K::integer: return "integer";
    case K::boolean: return "boolean";
    case K::expression: return "number or expression string";
    case K::vec2: return "array of 2 numbers (3 in 3D)";
    case K::ivec2: return "array of 2 integers (3 in 3D)";
    case K::box: return "array of 2 arrays of 2 numbers (3 in 3D)";
  }
  return "?";
}

std::string KeySpec::range_text() const {
  std::ostringstream os;
  if (lower && upper) {
    os << "in " << (lower_open ? "(" : "[") << *lower << ", " << *upper << (upper_open ? ")" : "]");
  } else if (lower) {
    os << (lower_open ? "> " : ">= ") << *lower;
  } else if (upper) {
    os << (upper_open ? "< " : "<= ") << *upper;
  }
  return os.str();
}

const std::vector<KeySpec>& scene_schema() {
  static const std::vector<KeySpec> schema = build_schema();
  return schema;
}

const KeySpec* find_key_spec(const std::string& schema_path) {
  static const auto index = [] {
    std::unordered_map<std::string, const KeySpec*> m;
    for (const auto& k : scene_schema()) m.emplace(k.path, &k);
    return m;
  }();
  auto it = index.find(schema_path);
  return it == index.end() ? nullptr : it->second;
}

void print_schema(std::ostream& os, bool markdown) {
  auto type_text = [](const KeySpec& k) {
    std::string t = value_kind_name(k.kind);
    if (!k.choices.empty()) {
      t = "one of ";
      for (std::size_t i = 0; i < k.choices.size(); ++i) t += (i ? ", " : "") + k.choices[i];
    }
    if (!k.range_text().empty()) t += ", " + k.range_text();
    return t;
  };
  if (markdown) {
    // A '|' inside a cell (|r| in a doc) would end the cell: escape it.
    auto cell = [](const std::string& text) {
      std::string r;
      for (char c : text) r += c == '|' ? std::string("\\|") : std::string(1, c);
      return r;
    };
    os << "| key | type | default | meaning |\n| --- | --- | --- | --- |\n";
    for (const auto& k : scene_schema())
      os << "| `" << k.path << "` | " << cell(type_text(k)) << " | " << (k.required ? (k.unless.empty() ? std::string("required") : "required unless " + k.unless) : k.default_value.empty() ? "-" : "`" + k.default_value + "`")
         << " | " << cell(k.doc) << " |\n";
    return;
  }
  for (const auto& k : scene_schema()) {
    os << k.path << "\n    type: " << type_text(k) << "\n    default: "
       << (k.required ? (k.unless.empty() ? std::string("(required)") : "(required unless " + k.unless + ")") : k.default_value.empty() ? "(none)" : k.default_value) << "\n    " << k.doc << "\n";
  }
}

}  // namespace loom
