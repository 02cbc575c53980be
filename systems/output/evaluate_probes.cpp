#include "systems/output/evaluate_probes.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>

#include "engine/mesh/quad9_shape.hpp"
#include "engine/mesh/simplex_geometry.hpp"
#include "engine/mesh/triangle_geometry.hpp"
#include "systems/output/mesh_energy.hpp"
#include "systems/output/tet_sections.hpp"

namespace loom {

double stress_component(const Mat3& sigma, StressComponent c) {
  switch (c) {
    case StressComponent::xx: return sigma(0, 0);
    case StressComponent::yy: return sigma(1, 1);
    case StressComponent::xy: return sigma(0, 1);
    case StressComponent::zz: return sigma(2, 2);
    case StressComponent::yz: return sigma(1, 2);
    case StressComponent::xz: return sigma(0, 2);
    case StressComponent::pressure: return -sigma.trace() / 3.0;
    case StressComponent::von_mises: return std::sqrt(1.5 * (sigma - sigma.trace() / 3.0 * Mat3::Identity()).squaredNorm());
  }
  return kNaN;
}

double cell_pressure(const BodyMaterial& material, const QuadPoints<2>& quad, Index cell) {
  double p = 0.0;
  for (int q = 0; q < quad.per_cell; ++q) {
    Mat3 sigma;
    if (!point_stress(material, quad, cell * quad.per_cell + q, sigma)) return kNaN;
    p -= sigma.trace() / 3.0;
  }
  return p / quad.per_cell;
}

namespace {

// The reference coordinates of `at` in quad9 cell c, if it lies in the cell (reference configuration).
std::optional<Vec2> quad9_sample(const Nodes<2>& nodes, const Cells& cb, Index c, const Vec2& at) {
  Quad9Coordinates X;
  for (int a = 0; a < 9; ++a) X.row(a) = nodes.X[cb.node(c, a)].transpose();
  Vec2 xi;
  if (!quad9_inverse_map(X, at, xi) || xi.cwiseAbs().maxCoeff() > 1.0 + 1e-9) return std::nullopt;
  return xi;
}

// quad9: the stress at reference coordinates l = (xi, eta) from its 3 x 3 Gauss values, by the biquadratic
// Lagrange interpolation through the Gauss points (exact for a biquadratic stress field): the 1D quadratic
// through -g, 0, g evaluated at xi is quadratic_lagrange(xi / g).
double gauss_lagrange_weight(const std::array<double, 4>& l, int q) {
  const double g = std::sqrt(0.6);
  const Eigen::Vector3d Lx = quadratic_lagrange(l[0] / g), Ly = quadratic_lagrange(l[1] / g);
  return Lx[q % 3] * Ly[q / 3];  // quad9_gauss: point q = 3 j + i at (g_i, g_j)
}

// Weight of quadrature point q in the stress at barycentric coordinates l of a simplex: the linear interpolation through
// the points of the rules whose point q has l_q = a and the others b (the triangle's 3 points: a = 2/3, b = 1/6; the
// tetrahedron's 4 points, point q nearest corner q: kTet4RuleA, kTet4RuleB), (l_q - b) / (a - b), exact for a linear
// stress field; one point: its value; quad9: the biquadratic interpolation through its Gauss points.
double point_weight(int per_cell, int dimension, const std::array<double, 4>& l, int q) {
  if (per_cell == 1) return 1.0;
  if (per_cell == 9) return gauss_lagrange_weight(l, q);
  if (dimension == 2) return 2.0 * l[std::size_t(q)] - 1.0 / 3.0;
  constexpr double a = 0.58541019662496845446, b = 0.13819660112501051518;  // kTet4RuleA, kTet4RuleB
  return (l[std::size_t(q)] - b) / (a - b);
}

// Where a stress probe's reference point lies in cell c of block b, if it does: its barycentric coordinates in the
// corner triangle (an inverted one holds nothing) or tetrahedron, or quad9's reference coordinates.
std::optional<StressSample> stress_sample(const Nodes<2>& nodes, const Cells& cb, Index b, Index c, const Vec2& at) {
  if (cb.type == CellType::quad9) {
    if (const auto xi = quad9_sample(nodes, cb, c, at)) return StressSample{b, c, {xi->x(), xi->y(), 0.0, 0.0}};
    return std::nullopt;
  }
  const Vec2 &a = nodes.X[cb.node(c, 0)], &e1 = nodes.X[cb.node(c, 1)], &e2 = nodes.X[cb.node(c, 2)];
  if (!(signed_area(a, e1, e2) > 0.0)) return std::nullopt;
  const auto l = barycentric(a, e1, e2, at);
  if (l && l->minCoeff() >= -1e-9) return StressSample{b, c, {(*l)[0], (*l)[1], (*l)[2], 0.0}};
  return std::nullopt;
}
std::optional<StressSample> stress_sample(const Nodes<3>& nodes, const Cells& cb, Index b, Index c, const Vec3& at) {
  const auto l = barycentric(nodes.X[cb.node(c, 0)], nodes.X[cb.node(c, 1)], nodes.X[cb.node(c, 2)], nodes.X[cb.node(c, 3)], at);
  if (l && l->minCoeff() >= -1e-9) return StressSample{b, c, {(*l)[0], (*l)[1], (*l)[2], (*l)[3]}};
  return std::nullopt;
}

std::array<Vec3, 4> corners_at(const Nodes<3>& nodes, const Cells& cb, Index c) {
  return {nodes.position_n(cb.node(c, 0)), nodes.position_n(cb.node(c, 1)), nodes.position_n(cb.node(c, 2)), nodes.position_n(cb.node(c, 3))};
}

// A section probe: the area of the cut of the body's cells by its plane, or the largest (smallest) coordinate of the
// cut's points along the probe's component (NaN where the plane misses the body).
double section_value(const ProbeSpec& p, const MovingPlane& plane, const Nodes<3>& nodes, const std::vector<Cells>& cells) {
  double area = 0.0, e = p.max ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
  for (const Cells& cb : cells)
    for (Index c = 0; c < cb.size(); ++c) {
      if (cb.body[c] != p.body) continue;
      const TetCut cut = cut_tet(corners_at(nodes, cb, c), plane.point, plane.normal);
      area += cut.area();
      for (int i = 0; i < cut.n; ++i) e = p.max ? std::max(e, cut.points[std::size_t(i)][p.component]) : std::min(e, cut.points[std::size_t(i)][p.component]);
    }
  if (p.component == 5) return area;
  return std::isfinite(e) ? e : kNaN;
}

// Area of a probe's body cells (weights: dV_n per point, or the seed-001 triangles' reference areas A_0 times rho)
// on the downstream side of an inlet's section when the plan has one. Summed point by point in cell order, so that
// an unclipped volume is the plain sum of the weights dV_n.
template <int D>
double body_measure(const ProbePlan& plan, std::size_t k, bool mass, double t, const std::vector<BodyMaterial>& materials, const Nodes<D>& nodes,
                    const std::vector<Cells>& cells, const std::vector<QuadPoints<D>>& quad) {
  const ProbeSpec& p = plan.probes[k];
  const double rho = materials[std::size_t(p.body)].density;
  double sum = 0.0;
  for (std::size_t b = 0; b < cells.size(); ++b) {
    const Cells& cb = cells[b];
    const bool reference_area = integrates_on_domains(cb.formulation) && cb.measure.used();
    for (Index c = 0; c < cb.size(); ++c) {
      if (cb.body[c] != p.body) continue;
      double f = 1.0;
      if constexpr (D == 2)
        if (p.inlet != kNoIndex)
          f = fraction_downstream(nodes.position_n(cb.node(c, 0)), nodes.position_n(cb.node(c, 1)), nodes.position_n(cb.node(c, 2)),
                                  plan.downstream[k][0], plan.downstream[k][1]);
      if constexpr (D == 3)
        if (p.inlet != kNoIndex) f = tet_fraction_downstream(corners_at(nodes, cb, c), plan.planes[k].point_at(t), plan.planes[k].normal);
      if (mass && reference_area) {
        sum += rho * cb.measure[c] * f;
        continue;
      }
      for (int q = 0; q < quad[b].per_cell; ++q) {
        const Index i = c * quad[b].per_cell + q;
        sum += (mass ? rho * quad[b].weight_n[i] / quad[b].F_n[i].determinant() : quad[b].weight_n[i]) * f;
      }
    }
  }
  return sum;
}

}  // namespace

double fraction_downstream(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& point, const Vec2& normal) {
  const double whole = signed_area(a, b, c);
  if (whole == 0.0) return 0.0;
  // Sutherland-Hodgman against one line: the polygon of the triangle's part with d >= 0.
  const Vec2 v[3] = {a, b, c};
  double d[3];
  for (int i = 0; i < 3; ++i) d[i] = (v[i] - point).dot(normal);
  if (d[0] >= 0.0 && d[1] >= 0.0 && d[2] >= 0.0) return 1.0;
  if (d[0] <= 0.0 && d[1] <= 0.0 && d[2] <= 0.0) return 0.0;
  Vec2 poly[4];
  int n = 0;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (d[i] >= 0.0) poly[n++] = v[i];
    if ((d[i] > 0.0 && d[j] < 0.0) || (d[i] < 0.0 && d[j] > 0.0)) poly[n++] = v[i] + (d[i] / (d[i] - d[j])) * (v[j] - v[i]);
  }
  double area = 0.0;
  for (int i = 0; i < n; ++i) area += 0.5 * (poly[i].x() * poly[(i + 1) % n].y() - poly[(i + 1) % n].x() * poly[i].y());
  return area / whole;
}

template <int D>
ProbePlan plan_probes(const SceneSpec& scene, const Nodes<D>& nodes, const std::vector<Cells>& cells,
                      const std::vector<Index>& node_body) {
  ProbePlan plan;
  plan.probes = scene.probes;
  for (const auto& p : scene.probes) {
    Index best = kNoIndex;
    std::vector<Index> body_nodes;
    std::vector<std::array<Index, 3>> pairs;
    if (p.kind == ProbeKind::point) {
      double best_d = std::numeric_limits<double>::max();
      for (Index i = 0; i < nodes.size(); ++i) {
        if (p.body != kNoIndex && node_body[std::size_t(i)] != p.body) continue;
        const double d = (nodes.X[i] - probe_point<D>(p)).squaredNorm();
        if (d < best_d) best_d = d, best = i;
      }
    } else if (p.kind == ProbeKind::extent || p.kind == ProbeKind::speed) {
      for (Index i = 0; i < nodes.size(); ++i)
        if (node_body[std::size_t(i)] == p.body) body_nodes.push_back(i);
    } else if (D == 2 && p.kind == ProbeKind::pressure_jump) {
      // Interior edges: corner pairs shared by two cells of the body (in the same block).
      for (std::size_t b = 0; b < cells.size(); ++b) {
        std::map<std::uint64_t, Index> first;
        const Cells& cb = cells[b];
        for (Index c = 0; c < cb.size(); ++c) {
          if (cb.body[c] != p.body) continue;
          const int corners = corners_of_stride(cb.stride);
          for (int s = 0; s < corners; ++s) {
            const Index x = cb.node(c, s), y = cb.node(c, (s + 1) % corners);
            const std::uint64_t key = (std::uint64_t(std::min(x, y)) << 32) | std::uint64_t(std::max(x, y));
            auto [it, inserted] = first.emplace(key, c);
            if (!inserted) pairs.push_back({Index(b), it->second, c});
          }
        }
      }
    }
    std::vector<StressSample> samples;
    if (p.kind == ProbeKind::stress)
      for (std::size_t b = 0; b < cells.size(); ++b)
        for (Index c = 0; c < cells[b].size(); ++c)
          if (p.body == kNoIndex || cells[b].body[c] == p.body)
            if (const auto s = stress_sample(nodes, cells[b], Index(b), c, probe_point<D>(p))) samples.push_back(*s);
    plan.samples.push_back(std::move(samples));
    std::array<Vec2, 2> downstream{Vec2::Zero(), Vec2::Zero()};
    if (D == 2 && p.inlet != kNoIndex) {  // the section's normal along the inflow (engine/methods/pfem/inlet_flow.hpp)
      const InletSpec& in = scene.inlets[std::size_t(p.inlet)];
      const Vec2 t = (in.to - in.from).normalized();
      Vec2 n(-t.y(), t.x());
      if (n.dot(in.velocity) < 0.0) n = -n;
      downstream = {in.from, n};
    }
    plan.downstream.push_back(downstream);
    MovingPlane plane;
    if (p.kind == ProbeKind::section) plane.point = Vec3(p.at.x(), p.at.y(), p.at_z), plane.normal = p.normal;
    if (D == 3 && p.inlet != kNoIndex) {  // the disc's plane (engine/methods/pfem/inlet_flow_3d.hpp)
      const InletSpec& in = scene.inlets[std::size_t(p.inlet)];
      plane.point = in.centre, plane.velocity = in.section_velocity, plane.start = in.start, plane.duration = in.duration;
      plane.normal = Vec3(in.velocity.x(), in.velocity.y(), in.velocity_z).normalized();
    }
    plan.planes.push_back(plane);
    plan.node.push_back(best);
    plan.nodes.push_back(std::move(body_nodes));
    plan.cell_pairs.push_back(std::move(pairs));
  }
  return plan;
}

template <int D>
void evaluate_probes(const StepContext& ctx, const ProbePlan& plan, const std::vector<BodyMaterial>& materials,
                     const Nodes<D>& nodes, const std::vector<Cells>& cells, const std::vector<QuadPoints<D>>& quad,
                     const LinearSystem& system, const BoundaryConditions<D>& bc, int newton_iterations,
                     const RemeshStats& remesh, const std::vector<WallResult>& walls, std::vector<double>& values,
                     const std::vector<Edges<D>>* domains) {
  values.assign(plan.probes.size(), 0.0);
  for (std::size_t k = 0; k < plan.probes.size(); ++k) {
    const ProbeSpec& p = plan.probes[k];
    switch (p.kind) {
      case ProbeKind::reaction: {
        double sum = 0.0;
        for (Index e : bc.boundary_prescribed[std::size_t(p.boundary)]) {
          const Index dof = bc.prescribed[std::size_t(e)].dof;
          if (dof % system.dofs.per_node == p.component) sum += system.residual_full[dof];
        }
        values[k] = sum;
        break;
      }
      case ProbeKind::point:
        values[k] = nodes.u_n[plan.node[k]][p.component];
        break;
      case ProbeKind::newton:
        values[k] = newton_iterations;
        break;
      case ProbeKind::extent: {
        double e = p.max ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
        for (Index i : plan.nodes[k]) {
          const auto at = nodes.position_n(i);
          const double x = p.component == 4 ? std::hypot(at[0], at[1]) : at[p.component];  // 4: r, the distance from the z axis
          e = p.max ? std::max(e, x) : std::min(e, x);
        }
        values[k] = e;
        break;
      }
      case ProbeKind::volume:
      case ProbeKind::mass:
        values[k] = body_measure(plan, k, p.kind == ProbeKind::mass, ctx.t, materials, nodes, cells, quad);
        break;
      case ProbeKind::section:
        if constexpr (D == 3) values[k] = section_value(p, plan.planes[k], nodes, cells);
        break;
      case ProbeKind::speed: {
        double fastest = 0.0;
        for (Index i : plan.nodes[k]) fastest = std::max(fastest, nodes.v_n[i].norm());
        values[k] = fastest;
        break;
      }
      case ProbeKind::remesh:
        switch (p.quantity) {
          case RemeshQuantity::area_change: values[k] = remesh.area_change; break;
          case RemeshQuantity::changed: values[k] = remesh.changed ? 1.0 : 0.0; break;
          case RemeshQuantity::rejected: values[k] = remesh.rejected; break;
          case RemeshQuantity::isolated: values[k] = remesh.isolated; break;
          case RemeshQuantity::merged: values[k] = remesh.merged; break;
          case RemeshQuantity::crossings: values[k] = remesh.crossings; break;
          case RemeshQuantity::inserted: values[k] = remesh.inserted; break;
          case RemeshQuantity::removed: values[k] = remesh.removed; break;
          case RemeshQuantity::flipped: values[k] = remesh.flipped; break;
          case RemeshQuantity::slivers: values[k] = remesh.slivers; break;
          case RemeshQuantity::capped: values[k] = remesh.capped; break;
          case RemeshQuantity::repaired: values[k] = remesh.repaired; break;
        }
        break;
      case ProbeKind::wall_force: {
        const WallResult& w = walls.at(std::size_t(p.wall));
        values[k] = p.component < 3 ? w.force[p.component] : w.force.dot(w.normal);
        break;
      }
      case ProbeKind::penetration: {
        double worst = 0.0;
        for (std::size_t w = 0; w < walls.size(); ++w)
          if (p.wall == kNoIndex || Index(w) == p.wall) worst = std::max(worst, walls[w].penetration);
        values[k] = worst;
        break;
      }
      case ProbeKind::angular_momentum: {  // about `at`, of the lumped nodal masses at the converged step
        double L = 0.0;  // 2D: the out-of-plane moment; 3D: the moment's component
        for (Index i = 0; i < nodes.size(); ++i) {
          const Vec<D> r = nodes.position_n(i) - probe_point<D>(p);
          if constexpr (D == 2) L += nodes.lumped_mass[i] * (r.x() * nodes.v_n[i].y() - r.y() * nodes.v_n[i].x());
          else L += nodes.lumped_mass[i] * r.cross(nodes.v_n[i])[p.component];
        }
        values[k] = L;
        break;
      }
      case ProbeKind::energy: {  // displacement formulations and hyperelastic materials (the loader checks)
        const MeshEnergy e = mesh_energy(materials, nodes, cells, quad, bc, domains);
        values[k] = p.energy == EnergyPart::kinetic     ? e.kinetic
                    : p.energy == EnergyPart::elastic   ? e.elastic
                    : p.energy == EnergyPart::potential ? e.potential
                    : p.energy == EnergyPart::total     ? e.kinetic + e.elastic
                                                        : e.kinetic + e.elastic + e.potential;
        break;
      }
      case ProbeKind::stress: {
        Mat3 mean = Mat3::Zero();
        for (const StressSample& s : plan.samples[k]) {
          const QuadPoints<D>& q = quad[std::size_t(s.block)];
          const BodyMaterial& m = materials[std::size_t(cells[std::size_t(s.block)].body[s.cell])];
          for (int i = 0; i < q.per_cell; ++i) {
            Mat3 sigma;
            if (!point_stress(m, q, s.cell * q.per_cell + i, sigma)) sigma.setConstant(kNaN);
            mean += point_weight(q.per_cell, D, s.l, i) * sigma / double(plan.samples[k].size());
          }
        }
        values[k] = plan.samples[k].empty() ? kNaN : stress_component(mean, p.stress);
        break;
      }
      case ProbeKind::pressure_jump: {
        if constexpr (D == 2) {
          double sum = 0.0;
          for (const auto& [block, c1, c2] : plan.cell_pairs[k]) {
            const Cells& cb = cells[std::size_t(block)];
            const BodyMaterial& m = materials[std::size_t(cb.body[c1])];
            sum += std::abs(cell_pressure(m, quad[std::size_t(block)], c1) - cell_pressure(m, quad[std::size_t(block)], c2));
          }
          values[k] = plan.cell_pairs[k].empty() ? 0.0 : sum / double(plan.cell_pairs[k].size());
        }
        break;
      }
    }
  }
}

template ProbePlan plan_probes<2>(const SceneSpec&, const Nodes<2>&, const std::vector<Cells>&, const std::vector<Index>&);
template ProbePlan plan_probes<3>(const SceneSpec&, const Nodes<3>&, const std::vector<Cells>&, const std::vector<Index>&);
template void evaluate_probes<2>(const StepContext&, const ProbePlan&, const std::vector<BodyMaterial>&, const Nodes<2>&,
                                 const std::vector<Cells>&, const std::vector<QuadPoints<2>>&, const LinearSystem&,
                                 const BoundaryConditions<2>&, int, const RemeshStats&, const std::vector<WallResult>&, std::vector<double>&,
                                 const std::vector<Edges<2>>*);
template void evaluate_probes<3>(const StepContext&, const ProbePlan&, const std::vector<BodyMaterial>&, const Nodes<3>&,
                                 const std::vector<Cells>&, const std::vector<QuadPoints<3>>&, const LinearSystem&,
                                 const BoundaryConditions<3>&, int, const RemeshStats&, const std::vector<WallResult>&, std::vector<double>&,
                                 const std::vector<Edges<3>>*);

}  // namespace loom
