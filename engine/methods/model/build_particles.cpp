#include "engine/methods/model/build_particles.hpp"

#include <cmath>
#include <sstream>

#include "engine/core/errors.hpp"
#include "engine/mesh/boundary_edges.hpp"
#include "engine/mesh/particle_generators.hpp"
#include "engine/mesh/triangle_rules.hpp"
#include "engine/methods/model/build_boundary_conditions.hpp"
#include "engine/methods/model/build_mesh.hpp"

namespace loom {
namespace {

GeneratedParticles generate_particles(const ParticleGeneratorSpec& spec, double density, std::size_t body) {
  try {
    if (spec.kind == ParticleGenerator::disk) {
      DiskParticleSpec d;
      d.centre = spec.centre, d.radius = spec.radius, d.core_radius = spec.core_radius, d.n_theta = spec.n_theta, d.factor = spec.factor;
      d.density = density;
      return generate_disk_particles(d);
    }
    BeamParticleSpec m;
    m.root = spec.root, m.length = spec.length, m.height = spec.height, m.core_height = spec.core_height, m.n_height = spec.n_height;
    m.factor = spec.factor, m.density = density;
    return generate_beam_particles(m);
  } catch (const InputError& e) {
    std::ostringstream os;
    os << spec.where << ": error: body[" << body << "].particles: " << e.what();
    throw InputError(os.str());
  }
}

}  // namespace

void build_material_points(const SceneSpec& scene, Points<2>& particles) {
  std::vector<Vec2> X;
  std::vector<double> volume, mass;
  std::vector<Index> body;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const BodySpec& spec = scene.bodies[b];
    if (spec.element == Formulation::quad9) continue;  // an FEM body of method mpm_fem: no particles
    const double density = scene.materials[std::size_t(spec.material)].density;
    if (spec.particles.kind != ParticleGenerator::none) {
      const GeneratedParticles g = generate_particles(spec.particles, density, b);
      X.insert(X.end(), g.X.begin(), g.X.end());
      volume.insert(volume.end(), g.volume.begin(), g.volume.end());
      mass.insert(mass.end(), g.mass.begin(), g.mass.end());
      body.insert(body.end(), g.X.size(), Index(b));
      continue;
    }
    const MeshData mesh = generate_body_mesh(spec.mesh);
    const auto& rule = triangle_rule(spec.particles_per_cell);
    for (Index t = 0; t < mesh.n_triangles(); ++t) {
      const Vec2 &x0 = mesh.X[std::size_t(mesh.triangles[3 * std::size_t(t)])], &x1 = mesh.X[std::size_t(mesh.triangles[3 * std::size_t(t) + 1])],
                 &x2 = mesh.X[std::size_t(mesh.triangles[3 * std::size_t(t) + 2])];
      const double area = 0.5 * ((x1 - x0).x() * (x2 - x0).y() - (x2 - x0).x() * (x1 - x0).y());
      LOOM_CHECK(area > 0.0, InputError, spec.mesh.where << ": error: body[" << b << "].mesh: the generated mesh has degenerate cells");
      for (const auto& q : rule) {
        X.push_back(q.l[0] * x0 + q.l[1] * x1 + q.l[2] * x2);
        volume.push_back(q.w * area);
        mass.push_back(density * q.w * area);
        body.push_back(Index(b));
      }
    }
  }
  particles.resize(Index(X.size()));
  for (Index p = 0; p < Index(X.size()); ++p) {
    particles.X[p] = X[std::size_t(p)];
    particles.volume[p] = volume[std::size_t(p)];
    particles.mass[p] = mass[std::size_t(p)];
    particles.body[p] = body[std::size_t(p)];
  }
}

void build_traction_points(const SceneSpec& scene, Points<2>& points, BoundaryConditions<2>& bc) {
  std::vector<Vec2> X;
  std::vector<double> weight;
  std::vector<Index> body;
  // Two-point Gauss rule on an edge: exact for the linear shape functions times a linear traction.
  const double s[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  for (std::size_t k = 0; k < scene.boundaries.size(); ++k) {
    const BoundarySpec& spec = scene.boundaries[k];
    if (!spec.has_traction) continue;
    const MeshData mesh = generate_body_mesh(scene.bodies[std::size_t(spec.body)].mesh);
    Vec2 lo = mesh.X[0], hi = mesh.X[0];
    for (const auto& x : mesh.X) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
    const double tol = 1e-9 * std::max(1.0, (hi - lo).norm());
    auto inside = [&](const Vec2& x) {
      return x.x() >= spec.box_min.x() - tol && x.x() <= spec.box_max.x() + tol && x.y() >= spec.box_min.y() - tol && x.y() <= spec.box_max.y() + tol;
    };
    std::array<Index, 2> expr{kNoIndex, kNoIndex};
    const std::optional<ExpressionSpec>* comps[2] = {&spec.traction.x, &spec.traction.y};
    for (int d = 0; d < 2; ++d) {
      if (!*comps[d]) continue;
      std::ostringstream where;
      where << (*comps[d])->where << ": " << (*comps[d])->key;
      bc.expressions.emplace_back((*comps[d])->text, where.str());
      expr[std::size_t(d)] = Index(bc.expressions.size() - 1);
    }
    // region.normal: the body mesh's triangles are counter-clockwise, so the outward normal of a boundary edge
    // a -> b (as in its triangle) is (x_b - x_a) turned clockwise.
    const std::optional<Vec2> direction = region_normal<2>(spec);
    std::size_t n_edges = 0, n_in_region = 0;  // loaded; in the region, before region.normal's filter
    for (const auto& e : boundary_edges(mesh.triangles, 3)) {
      const Vec2 &xa = mesh.X[std::size_t(e.a)], &xb = mesh.X[std::size_t(e.b)];
      if (!inside(xa) || !inside(xb)) continue;
      ++n_in_region;
      if (direction && !faces_direction<2>(Vec2(xb.y() - xa.y(), xa.x() - xb.x()), *direction)) continue;
      ++n_edges;
      for (double si : s) {
        X.push_back((1 - si) * xa + si * xb);
        weight.push_back(0.5 * (xb - xa).norm());
        body.push_back(spec.body);
        bc.traction_point_expression.push_back(expr);
      }
    }
    check_traction_support(scene, k, n_edges, n_in_region, "boundary edges of the body mesh with both end nodes in the region");
    if (expr[0] != kNoIndex || expr[1] != kNoIndex) bc.has_loads = true;
  }
  points.resize(Index(X.size()));
  for (Index q = 0; q < Index(X.size()); ++q) {
    points.X[q] = X[std::size_t(q)];
    points.volume[q] = weight[std::size_t(q)];
    points.body[q] = body[std::size_t(q)];
  }
}

}  // namespace loom
