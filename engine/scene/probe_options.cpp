#include "engine/scene/probe_options.hpp"

#include "engine/scene/loader_support.hpp"

namespace loom {
namespace {

// The probe's `body`: the named one, else the scene's only body, else `if_several` (kNoIndex: the key is missing).
Index probe_body(const SceneSpec& s, const TableReader& t, Index if_several = kNoIndex) {
  if (t.has("body")) {
    const std::string body = t.string("body");
    const Index b = find_by_name(s.bodies, body);
    if (b == kNoIndex) t.error("body", "no [[body]] named \"" + body + "\" (known: " + names_of(s.bodies) + ")");
    return b;
  }
  if (s.bodies.size() == 1) return 0;
  if (if_several == kNoIndex) t.error("", "missing key body (the scene has several bodies)");
  return if_several;
}

}  // namespace

void read_probe(SceneSpec& s, const TableReader& t) {
  ProbeSpec p;
  p.name = read_name(t);
  p.where = t.where();
  if (find_by_name(s.probes, p.name) != kNoIndex || p.name == "step" || p.name == "time")
    t.error("name", "the probe name \"" + p.name + "\" is already a column of probes.csv");
  if (p.name.find_first_of(",\"\n") != std::string::npos) t.error("name", "a probe name may not hold commas, quotes or newlines");
  const std::string kind = t.string("kind");
  p.kind = pick<ProbeKind>(kind, {{"reaction", ProbeKind::reaction}, {"point", ProbeKind::point}, {"newton", ProbeKind::newton},
                                  {"extent", ProbeKind::extent}, {"pressure_jump", ProbeKind::pressure_jump},
                                  {"volume", ProbeKind::volume}, {"remesh", ProbeKind::remesh}, {"energy", ProbeKind::energy},
                                  {"stress", ProbeKind::stress}, {"wall_force", ProbeKind::wall_force}, {"penetration", ProbeKind::penetration},
                                  {"speed", ProbeKind::speed}, {"mass", ProbeKind::mass}, {"angular_momentum", ProbeKind::angular_momentum},
                                  {"section", ProbeKind::section}});
  p.energy = pick<EnergyPart>(t.string("energy"), {{"kinetic", EnergyPart::kinetic}, {"elastic", EnergyPart::elastic}, {"total", EnergyPart::total},
                                                             {"potential", EnergyPart::potential}, {"mechanical", EnergyPart::mechanical}});
  p.max = t.string("bound") == "max";
  const std::string quantity = t.string("quantity");
  p.quantity = pick<RemeshQuantity>(quantity.empty() ? "area_change" : quantity, {{"area_change", RemeshQuantity::area_change},
               {"changed", RemeshQuantity::changed}, {"rejected", RemeshQuantity::rejected}, {"isolated", RemeshQuantity::isolated},
               {"merged", RemeshQuantity::merged}, {"crossings", RemeshQuantity::crossings}, {"inserted", RemeshQuantity::inserted},
               {"removed", RemeshQuantity::removed}, {"flipped", RemeshQuantity::flipped}, {"slivers", RemeshQuantity::slivers}, {"repaired", RemeshQuantity::repaired},
               {"capped", RemeshQuantity::capped}});
  const std::string component = t.string("component");
  p.component = component == "y" ? 1 : component == "z" ? 2 : 0;
  if (component == "z" && s.scene.dimension < 3) t.error("component", "component z in a two-dimensional scene (scene.dimension = 2)");
  p.stress = pick<StressComponent>(component, {{"xx", StressComponent::xx}, {"yy", StressComponent::yy}, {"xy", StressComponent::xy},
                                               {"zz", StressComponent::zz}, {"yz", StressComponent::yz}, {"xz", StressComponent::xz},
                                               {"von_mises", StressComponent::von_mises}, {"pressure", StressComponent::pressure}});
  if ((component == "yz" || component == "xz") && s.scene.dimension < 3)
    t.error("component", "component " + component + " in a two-dimensional scene (scene.dimension = 2): plane strain has no shear out of plane");
  const bool vector_component = component == "x" || component == "y" || component == "z";
  if (p.kind == ProbeKind::wall_force && component == "normal") {
    p.component = 3;  // after x, y, z
  } else if (component == "area") {
    if (p.kind != ProbeKind::section) t.error("component", "component area is read by section probes");
    p.component = 5;  // after x, y, z, normal and r
  } else if (p.kind == ProbeKind::section && t.has("component") && !vector_component) {
    t.error("component", "a section probe reads area, or the largest (bound = \"min\": smallest) x, y or z of the cut");
  } else if (component == "r") {
    if (p.kind != ProbeKind::extent || s.scene.dimension != 3)
      t.error("component", "component r (the distance from the z axis) is read by extent probes in 3D (scene.dimension = 3)");
    p.component = 4;  // after x, y, z and normal
  } else if (t.has("component") && (p.kind == ProbeKind::stress) == vector_component) {
    t.error("component", p.kind == ProbeKind::stress       ? (s.scene.dimension == 3 ? "a stress probe reads xx, yy, zz, xy, yz, xz, von_mises or pressure"
                                                                      : "a stress probe reads xx, yy, xy, zz, von_mises or pressure")
                         : p.kind == ProbeKind::wall_force ? std::string("a wall_force probe reads component x, y") +
                                                                 (s.scene.dimension == 3 ? ", z" : "") + " or normal"
                                                           : "kind = \"" + kind + "\" reads component x or y");
  }
  auto needs = [&](const char* key) {
    if (t.present() && t.has("kind") && !t.has(key)) t.error("", std::string("missing key ") + key + " (needed by kind = \"" + kind + "\")");
  };
  auto unused = [&](const char* key) {
    if (t.has(key)) t.error(key, std::string(key) + " is not used by kind = \"" + kind + "\"");
  };
  switch (p.kind) {
    case ProbeKind::reaction: {
      needs("boundary"), needs("component"), unused("at"), unused("body"), unused("group");
      const std::string bname = t.string("boundary");
      p.boundary = find_by_name(s.boundaries, bname);
      if (t.has("boundary") && p.boundary == kNoIndex) {
        t.error("boundary", "no [[boundary]] named \"" + bname + "\" (known: " + names_of(s.boundaries) + ")");
      } else if (p.boundary != kNoIndex && t.has("component")) {
        const auto& d = s.boundaries[std::size_t(p.boundary)].displacement;
        if (!d[p.component])
          t.error("component", "boundary \"" + bname + "\" prescribes no displacement in " + t.string("component") + ": there is no reaction to measure");
      }
      break;
    }
    case ProbeKind::stress:
      if (is_mpm(s.scene.method)) t.error("kind", "kind = \"stress\" reads the cells of fem and pfem meshes; method mpm has none");
      [[fallthrough]];
    case ProbeKind::point: {
      needs("component"), unused("boundary");
      if (t.present() && t.has("kind") && !t.has("at") && !t.has("group"))
        t.error("", "missing key at (or group: a physical point of the mesh file), needed by kind = \"" + kind + "\"");
      if (t.has("at") && t.has("group")) t.error("group", "give either at or group, not both");
      p.at = t.vec2("at");
      p.at_z = t.component("at", 2);
      p.group = t.string("group");
      if (t.has("group") && is_mpm(s.scene.method)) t.error("group", "method mpm starts its tracer points at coordinates: give at");
      if (t.has("body")) {
        const std::string body = t.string("body");
        p.body = find_by_name(s.bodies, body);
        if (p.body == kNoIndex) t.error("body", "no [[body]] named \"" + body + "\" (known: " + names_of(s.bodies) + ")");
      }
      break;
    }
    case ProbeKind::wall_force:
    case ProbeKind::penetration: {
      if (p.kind == ProbeKind::wall_force) needs("wall"), needs("component");
      else unused("component");
      unused("boundary"), unused("at"), unused("body"), unused("group");
      if (t.has("wall")) {
        const std::string wall = t.string("wall");
        p.wall = find_by_name(s.walls, wall);
        if (p.wall == kNoIndex) t.error("wall", "no [[wall]] named \"" + wall + "\" (known: " + names_of(s.walls) + ")");
        else if (p.component == 3 && s.walls[std::size_t(p.wall)].planes.size() != 1)
          t.error("component", "wall \"" + wall + "\" is a box of " + std::to_string(s.walls[std::size_t(p.wall)].planes.size()) +
                                   " planes: read component x, y" + (s.scene.dimension == 3 ? ", z" : "") + ", not normal");
      } else if (s.walls.empty()) {
        t.error("kind", "kind = \"" + kind + "\" measures [[wall]]s and the scene has none");
      }
      break;
    }
    case ProbeKind::newton:
    case ProbeKind::energy:
      unused("boundary"), unused("component"), unused("at"), unused("body"), unused("group");
      break;
    case ProbeKind::angular_momentum:
      unused("boundary"), unused("body"), unused("group");
      if (s.scene.dimension < 3) unused("component");  // 2D: the one out-of-plane moment
      if (s.time.integrator == Integrator::static_) t.error("kind", "kind = \"angular_momentum\" reads velocities: it needs a dynamic time.integrator");
      if (s.scene.method == Method::mpm_fem) t.error("kind", "kind = \"angular_momentum\" is implemented for methods fem, pfem, es_pfem and mpm");
      if (!is_mpm(s.scene.method) && s.time.mass == MassKind::consistent)
        t.error("kind", "kind = \"angular_momentum\" sums the lumped nodal masses: use time.mass = \"lumped\"");
      p.at = t.has("at") ? t.vec2("at") : Vec2::Zero();  // the point the moments are taken about
      p.at_z = t.component("at", 2);
      break;
    case ProbeKind::remesh:
      needs("quantity"), unused("boundary"), unused("component"), unused("at"), unused("body"), unused("group");
      if (s.scene.method != Method::pfem && s.scene.method != Method::es_pfem) t.error("kind", "kind = \"remesh\" needs method = \"pfem\" or \"es_pfem\"");
      break;
    case ProbeKind::section: {
      unused("boundary"), unused("group");
      if (s.scene.dimension != 3) t.error("kind", "kind = \"section\" cuts a body with a plane: three-dimensional (scene.dimension = 3)");
      if (is_mpm(s.scene.method)) t.error("kind", "kind = \"section\" cuts the cells of fem, pfem and es_pfem meshes");
      needs("at"), needs("normal");
      p.at = t.vec2("at"), p.at_z = t.component("at", 2);
      p.normal = Vec3(t.component("normal", 0), t.component("normal", 1), t.component("normal", 2));
      if (t.has("normal") && !(p.normal.norm() > 0.0)) t.error("normal", "the section's normal has zero length");
      else p.normal.normalize();
      if (!t.has("component")) p.component = 5;
      p.body = probe_body(s, t);
      break;
    }
    case ProbeKind::speed:
    case ProbeKind::mass:
      if (is_mpm(s.scene.method)) t.error("kind", "kind = \"" + kind + "\" reads the nodes and cells of fem, pfem and es_pfem meshes");
      if (p.kind == ProbeKind::speed && s.time.integrator == Integrator::static_)
        t.error("kind", "kind = \"speed\" reads nodal velocities: it needs a dynamic time.integrator");
      [[fallthrough]];
    case ProbeKind::extent:
    case ProbeKind::volume:
    case ProbeKind::pressure_jump: {
      if (p.kind == ProbeKind::extent) needs("component");
      else unused("component");
      if (t.has("gap") && p.kind == ProbeKind::extent) {
        if (!is_mpm(s.scene.method)) t.error("gap", "gap is read by extent probes of method mpm's particles (a mesh's extent has no strays)");
        p.gap = t.real("gap");
      }
      unused("boundary"), unused("at"), unused("group");
      // Method mpm_fem: extent probes read the particles.
      p.body = probe_body(s, t, s.scene.method == Method::mpm_fem && p.kind == ProbeKind::extent ? mpm_body_index(s) : kNoIndex);
      if (s.scene.method == Method::mpm_fem && p.kind == ProbeKind::extent && p.body != mpm_body_index(s))
        t.error("body", "method mpm_fem: an extent probe reads the particles of the MPM body \"" + s.bodies[std::size_t(mpm_body_index(s))].name + "\"");
      break;
    }
  }
  if (t.has("reference")) p.has_reference = true, p.reference = t.real("reference");
  if (p.kind != ProbeKind::extent && (p.kind != ProbeKind::section || p.component == 5)) unused("bound");
  if (p.kind != ProbeKind::section) unused("normal");
  if (p.kind != ProbeKind::extent) unused("gap");
  if (p.kind != ProbeKind::remesh) unused("quantity");
  if (p.kind != ProbeKind::energy) unused("energy");
  if (p.kind != ProbeKind::wall_force && p.kind != ProbeKind::penetration) unused("wall");
  if (p.kind != ProbeKind::volume && p.kind != ProbeKind::mass) unused("inlet");
  if (t.has("inlet")) {
    const std::string inlet = t.string("inlet");
    p.inlet = find_by_name(s.inlets, inlet);
    if (p.inlet == kNoIndex) t.error("inlet", "no [[inlet]] named \"" + inlet + "\" (known: " + names_of(s.inlets) + ")");
    else if (p.body != kNoIndex && s.inlets[std::size_t(p.inlet)].body != p.body) t.error("inlet", "inlet \"" + inlet + "\" feeds another body");
  }
  s.probes.push_back(p);
}

}  // namespace loom
