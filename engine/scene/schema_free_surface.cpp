#include "engine/scene/schema_keys.hpp"

namespace loom {

void add_free_surface_keys(std::vector<KeySpec>& s) {
  // [[wall]]
  s.push_back(key("wall", K::table_array,
                  "Rigid walls (methods fem, pfem, es_pfem; [Reinold 2021] §4.4: ground and walls as planes with a penalty): every node of "
                  "the body that gets behind a wall, g = (x - point) . normal < 0, is pushed back by the force -k_N A g normal, A its "
                  "share of the body's boundary that faces the wall (half of each boundary edge, 1/6 and 2/3 on quadratic edges, "
                  "projected on the wall, of the edges whose outward normal points into it: the tip of a sharp nose keeps its base edge's share), "
                  "with the tangent in the Newton matrix. The nodes are those of the current mesh: PFEM particles that reach the wall feel it. "
                  "At most 8 planes in all (a box is four)."));
  s.push_back(key("wall[].name", K::string, "Name wall_force and penetration probes refer to.").require());
  s.push_back(key("wall[].point", K::vec2, "A point of the wall's line (3D: plane)."));
  s.push_back(key("wall[].normal", K::vec2, "Normal of the wall, pointing to the side the material occupies (need not be a unit vector)."));
  s.push_back(key("wall[].box", K::box, "Instead of point and normal: [[xmin, ymin], [xmax, ymax]], four walls that keep the material inside (3D: six)."));
  s.push_back(key("wall[].body", K::string, "The body the wall acts on (default: every body)."));
  s.push_back(key("wall[].contact", K::choice, "Contact law: penalty.").one_of({"penalty"}).by_default("penalty"));
  s.push_back(key("wall[].penalty", K::real,
                  "k_N, force per unit boundary length per unit penetration (stress / length). 0 (default): 100 E / h with E the "
                  "largest Young's modulus of the bodies it acts on and h their mean boundary edge length at the start, so that the "
                  "penetration stays below 1 % of h while the contact pressure stays below E.")
                  .by_default("0").at_least(0));
  s.push_back(key("wall[].slip", K::choice,
                  "free: frictionless (a symmetry plane); stick: a node in contact is also held at its first-contact point (where its "
                  "path in the step it first touched crossed the wall, so that the holding force grows from zero as it goes in) by a "
                  "tangential penalty k_N; it is let go when it leaves the wall.")
                  .one_of({"free", "stick"}).by_default("free"));
  s.push_back(key("wall[].spacing", K::real,
                  "Remesh spacing at the wall (methods pfem and es_pfem, with remesh.insert_above): particles are inserted and "
                  "removed against this spacing at the wall, growing linearly to the body's spacing over spacing_ramp, each "
                  "edge judged by the spacing at its midpoint (so an edge standing on the wall is split only when it is longer than "
                  "about 1.7 / (1 - 0.85 (h0 - s) / ramp) times s); the alpha test takes a triangle as the body opening only if its "
                  "circumradius also exceeds alpha times the graded spacing at its circumcentre (the body's beyond the ramp). "
                  "0 (default): the body's spacing everywhere. Why: a stick "
                  "wall holds the particles on it, so the thrust of the paste below the next row of particles reaches the wall "
                  "without the paste yielding; a yield-stress deposit on a stick ground then holds a slope steeper by about that "
                  "row's height over the depth (docs/free_surface.md).")
                  .by_default("0").at_least(0));
  s.push_back(key("wall[].spacing_ramp", K::real,
                  "Distance from the wall over which its spacing grows linearly to the body's h0 (with spacing). 0 (default): h0. "
                  "Over one body spacing the growth per row is so steep that the rows next to the wall stay coarse (up to 1.7 / "
                  "(1 - 0.85 (h0 - s) / ramp) times s, 4.7 s for s = h0 / 4): a longer ramp makes the first rows follow s "
                  "(below about 3 s once (h0 - s) / ramp <= 1 / 2), at the cost of more particles.")
                  .by_default("0").at_least(0));
  // [[inlet]]
  s.push_back(key("inlet", K::table_array,
                  "Inflow (methods pfem, es_pfem; [Reinold 2021] §4.4): material enters a body through a section, the segment from `from` "
                  "to `to`, at `velocity`. A row of particles one `spacing` behind the section is driven at the velocity (prescribed "
                  "displacement); when it reaches the section it is released and a new row, with v = velocity, u = 0, J = 1 and an "
                  "unstressed history, is joined to it one spacing behind. The body's mesh must start at the section: its particles on "
                  "the section are the first row released, and the first new row is placed so that the last one reaches the section "
                  "when the inflow ends; it is then released. The poured area is |velocity . n| times the section's length times "
                  "the duration. In 3D the section is a disc (centre, radius) normal to the velocity: the body's particles on it and "
                  "its surface triangles there are the first layer, and each new layer is a copy of it one spacing upstream, joined "
                  "to the layer in front by three tetrahedra per triangle; the disc may move at section_velocity (a printing "
                  "nozzle), the driven layer with it. The poured volume is |velocity . n| times the area of the body's section "
                  "in the disc times the duration."));
  s.push_back(key("inlet[].name", K::string, "Name of the inlet (volume and mass probes may count only what lies downstream of it).").require());
  s.push_back(key("inlet[].body", K::string, "The body that flows in (default: the only body)."));
  s.push_back(key("inlet[].from", K::vec2, "2D: one end of the inlet section.").require_unless("centre"));
  s.push_back(key("inlet[].to", K::vec2, "2D: the other end of the inlet section.").require_unless("centre"));
  s.push_back(key("inlet[].centre", K::vec2, "3D: the centre of the inlet's disc, at t = start.").require_unless("from"));
  s.push_back(key("inlet[].radius", K::real, "3D: the radius of the inlet's disc (the body's particles on the disc's plane within it are the first layer).").above(0));
  s.push_back(key("inlet[].section_velocity", K::vec2,
                  "3D: velocity of the disc while the inlet runs (perpendicular to velocity: a nozzle moving along a print path); the "
                  "driven layer moves at velocity + section_velocity.").by_default("[0, 0, 0]"));
  s.push_back(key("inlet[].velocity", K::vec2,
                  "Velocity of the inflowing material relative to the section; must cross the section (not parallel to it; 3D: the "
                  "disc's normal).").require());
  s.push_back(key("inlet[].start", K::real, "Time the inflow starts.").by_default("0").at_least(0));
  s.push_back(key("inlet[].duration", K::real, "How long the inflow lasts.").require().above(0));
  s.push_back(key("inlet[].spacing", K::real,
                  "Distance between the rows of new particles and between the particles of a row (0: the body's spacing, remesh.spacing or "
                  "its initial mean edge length).").by_default("0").at_least(0));
  // [remesh], [map]: pfem only
  s.push_back(key("remesh", K::table, "Remeshing (methods pfem and es_pfem): constrained Delaunay of the particles and alpha-shape test ([Schewe 2024] §3.1); es_pfem rebuilds its edges and transfers their history ([Reinold 2021] §3.5)."));
  s.push_back(key("remesh.alpha", K::real, "alpha of the alpha-shape test ([Schewe 2024] eq 16): a triangle with circumradius > alpha * l_char is removed.").by_default("1.2").above(0));
  s.push_back(key("remesh.lchar", K::expression,
                  "Characteristic length l_char of [Schewe 2024] eq 16: a number, or \"local\" for l_char^loc of eqs 17-18 (mean neighbour distance "
                  "on the previous mesh, averaged over the triangle's corners).").by_default("\"local\""));
  s.push_back(key("remesh.every", K::integer, "Remesh before every this many steps.").by_default("1").at_least(1));
  s.push_back(key("map", K::table, "PFEM state transfer between meshes (method = pfem; [Schewe 2024] §3.2)."));
  s.push_back(key("map.scheme", K::choice, "cpm: copy from the closest old quadrature point; btm: interpolate in the background triangulation of the old points ([Schewe 2024] eqs 19-21).")
                  .one_of({"cpm", "btm"}).by_default("cpm"));
  s.push_back(key("map.iso", K::integer, "BTM interpolation of F: 0 plain, 1 F_vol and F_iso separately, 2 log U and log R of the polar decomposition ([Schewe 2024] eqs 22-23).")
                  .by_default("0").at_least(0).at_most(2));
  s.push_back(key("remesh.surface", K::choice,
                  "alpha_shape ([Schewe 2024] §3.1): every triangle of the constrained Delaunay triangulation that passes the alpha test "
                  "is part of the body, so concave stretches of surface may be filled. constrained ([Reinold 2021] §3.1): the triangles "
                  "inside the previous boundary are the body, and the alpha test decides only where two surfaces meet (a triangle "
                  "outside that passes it and joins points three or more boundary edges apart, or of different surface loops, is "
                  "added) and where the body opens (a triangle inside that fails it and has no edge on the surface is removed). In both, "
                  "edges of the previous boundary that cross another are left out of the constraints (the remesh probe's crossings).")
                  .one_of({"alpha_shape", "constrained"}).by_default("alpha_shape"));
  s.push_back(key("remesh.insert_above", K::real,
                  "Particle insertion against separation: before each remesh, a particle is added at the midpoint of every edge of "
                  "the previous mesh longer than insert_above times the spacing, with every nodal value (displacement, velocity, "
                  "pressure, J, ...) interpolated linearly; 0: off. [Reinold 2021] gives no value; 1.7 is a common choice. In 3D "
                  "(linear tetrahedra) at most one edge per tetrahedron and remesh, the longest first, the spacing the mean edge "
                  "of the initial mesh; edges at prescribed particles are not split.")
                  .by_default("0").at_least(0));
  s.push_back(key("remesh.remove_below", K::real,
                  "Particle removal against clogging: of two particles joined by an edge shorter than remove_below times the spacing, "
                  "one is removed (an interior one rather than one on the surface; never one with a prescribed displacement or load); "
                  "0: off. 0.3 is a common choice.")
                  .by_default("0").at_least(0).below(1));
  s.push_back(key("remesh.keep_delaunay", K::boolean,
                  "3D: keep the previous mesh as it is when it is still Delaunay at the particles' positions, no cell of it would tear "
                  "and no two surfaces are closer than alpha l_char: a body at rest costs no triangulation and does not churn between "
                  "equivalent meshes of cospherical points.").by_default("true"));
  s.push_back(key("remesh.repair", K::boolean,
                  "3D, with keep_delaunay: a previous mesh that is no longer Delaunay only at some faces (no tear, no surfaces "
                  "meeting) is repaired in place by flips toward the Delaunay mesh that make no sliver (Lawson's 2-3, 3-2 and 4-4), "
                  "instead of triangulating the body again: cells elsewhere keep their corners and their state, a step costs less "
                  "than a triangulation, and near-cospherical cells are not recut. A face no flip mends beside a sliver, or a "
                  "repaired cell that would tear, falls back to the whole remesh. Method pfem only (es_pfem's flows were measured "
                  "worse on repaired meshes).").by_default("false"));
  s.push_back(key("remesh.flip_quality", K::real,
                  "3D: tetrahedra whose 3 r_in / R (1 regular, 0 flat) is below this are improved by flips with the particles fixed "
                  "(2-3, 3-2, edge removal; the surface untouched); 0: none.").by_default("0.2").at_least(0).below(1));
  s.push_back(key("remesh.max_new_material", K::real,
                  "Method es_pfem, dynamic runs: where two surfaces meet (or a void closes) the remesh fills the gap with new material, "
                  "mass that no particle carried. Once the mass so added since the start exceeds this fraction of the bodies' mass the "
                  "run stops as failed (exit 1, the output so far kept): a flow that gains that much is a doubtful answer (a layer a "
                  "few cells thick folding on itself; refine it or insert particles). Raise it to accept the gain.")
                  .by_default("0.05").at_least(0));
  s.push_back(key("remesh.spacing", K::real,
                  "Spacing h0 that insert_above and remove_below multiply (0: each body's mean edge length at the start).")
                  .by_default("0").at_least(0));
}

}  // namespace loom
