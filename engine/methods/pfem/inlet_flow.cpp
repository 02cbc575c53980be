#include "engine/methods/pfem/inlet_flow.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "engine/core/errors.hpp"
#include "engine/mesh/triangle_geometry.hpp"

namespace loom {
namespace {

// Triangles of the strip between two rows ordered along the section (the shorter diagonal first), each counter-
// clockwise. `xp`, `xq`: positions of the rows' particles.
void zip_rows(const std::vector<Index>& p, const std::vector<Vec2>& xp, const std::vector<Index>& q, const std::vector<Vec2>& xq,
              std::vector<Index>& triangles) {
  std::size_t i = 0, j = 0;
  auto emit = [&](Index a, const Vec2& xa, Index b, const Vec2& xb, Index c, const Vec2& xc) {
    if (signed_area(xa, xb, xc) > 0.0) triangles.insert(triangles.end(), {a, b, c});
    else triangles.insert(triangles.end(), {a, c, b});
  };
  while (i + 1 < p.size() || j + 1 < q.size()) {
    const bool advance_p = j + 1 == q.size() || (i + 1 < p.size() && (xp[i + 1] - xq[j]).norm() < (xp[i] - xq[j + 1]).norm());
    if (advance_p) {
      emit(p[i], xp[i], q[j], xq[j], p[i + 1], xp[i + 1]);
      ++i;
    } else {
      emit(p[i], xp[i], q[j], xq[j], q[j + 1], xq[j + 1]);
      ++j;
    }
  }
}

}  // namespace

InletFrame inlet_frame(const InletSpec& in, const PfemTopology& topo) {
  InletFrame f;
  f.from = in.from;
  f.length = (in.to - in.from).norm();
  f.tangent = (in.to - in.from) / f.length;
  f.normal = Vec2(-f.tangent.y(), f.tangent.x());
  if (f.normal.dot(in.velocity) < 0.0) f.normal = -f.normal;
  f.spacing = in.spacing > 0.0 ? in.spacing : topo.spacing[std::size_t(in.body)];
  return f;
}

std::vector<Index> particles_on_section(const InletFrame& f, const PfemTopology& topo, const Nodes<2>& nodes, Index body) {
  const double tol = 1e-6 * f.spacing;
  std::vector<std::pair<double, Index>> on;
  for (Index i : topo.points_of_body[std::size_t(body)]) {
    const Vec2 x = nodes.position_n(i);
    const double s = (x - f.from).dot(f.tangent);
    if (std::abs(f.distance(x)) <= tol && s >= -tol && s <= f.length + tol) on.emplace_back(s, i);
  }
  std::sort(on.begin(), on.end());
  std::vector<Index> out;
  for (const auto& [s, i] : on) out.push_back(i);
  return out;
}

void plan_inflow(const std::vector<InletSpec>& inlets, double t_n, const Nodes<2>& nodes, PfemTopology& topo, ParticleSetChange& change) {
  const Index n_old = topo.n_points;
  for (std::size_t k = 0; k < inlets.size(); ++k) {
    const InletSpec& in = inlets[k];
    InletState& state = topo.inlets[k];
    if (state.closed || t_n < in.start) continue;
    const InletFrame f = inlet_frame(in, topo);
    std::vector<Index>& triangles = change.triangles[std::size_t(in.body)];
    // The end: the driven row has just reached the section (the first row's offset makes the rows arrive there
    // at the end time) and is released; nothing is taken away.
    if (state.started && t_n >= in.start + in.duration * (1.0 - 1e-12)) {
      change.inlet_rows[k] = {}, change.inlet_row_set[k] = 1;
      change.mark_triangles_changed();  // the boundary conditions change
      state.closed = true;
      continue;
    }
    // The row in front: at the start the body's particles on the section, later the driven row once it has
    // reached the section.
    std::vector<Index> front;
    double d_front = 0.0;
    if (!state.started) {
      front = particles_on_section(f, topo, nodes, in.body);
      LOOM_CHECK(front.size() >= 2, RunError,
                 "inlet \"" << in.name << "\": " << front.size() << " particle(s) of its body lie on the section when it starts; the body's mesh must begin at the section");
    } else {
      for (Index i : state.row) d_front += f.distance(nodes.position_n(i));
      d_front /= double(state.row.size());
      if (d_front < 0.0) continue;  // still behind the section: driven on
      front = state.row;
    }
    // A new row h behind the front row, at n + 1 points evenly along the section. The first one is h_1 behind,
    // h_1 in [h/2, 3h/2) such that the poured depth |v . n| T is h_1 plus a whole number of rows: the last row then
    // reaches the section at the end time, when the inlet closes.
    double behind = f.spacing;
    if (!state.started) {
      const double depth = std::abs(in.velocity.dot(f.normal)) * in.duration;
      const double rows = std::max(1.0, std::round(depth / f.spacing));
      behind = depth - (rows - 1.0) * f.spacing;
    }
    const int n = std::max(1, int(std::lround(f.length / f.spacing)));
    std::vector<Index> row;
    std::vector<Vec2> x_front, x_row;
    for (Index i : front) x_front.push_back(nodes.position_n(i));
    for (int j = 0; j <= n; ++j) {
      const Vec2 x = f.from + (f.length * j / n) * f.tangent + (d_front - behind) * f.normal;
      row.push_back(n_old + Index(change.add.size()));
      change.add.push_back({in.body, kNoIndex, kNoIndex, x, in.velocity});
      x_row.push_back(x);
    }
    const std::size_t first = triangles.size();
    zip_rows(front, x_front, row, x_row, triangles);
    change.fresh_triangles.insert(change.fresh_triangles.end(), triangles.begin() + std::ptrdiff_t(first), triangles.end());
    change.mark_triangles_changed();
    change.inlet_rows[k] = row, change.inlet_row_set[k] = 1;
    state.started = true;
  }
}

void add_inlet_rows(const std::vector<InletSpec>& inlets, const PfemTopology& topo, BoundaryConditions<2>& bc) {
  std::map<Index, std::size_t> entry;  // dof -> index in bc.prescribed
  for (std::size_t e = 0; e < bc.prescribed.size(); ++e) entry[bc.prescribed[e].dof] = e;
  for (std::size_t k = 0; k < inlets.size(); ++k)
    for (Index i : topo.inlets[k].row)
      for (int d = 0; d < 2; ++d) {
        const typename BoundaryConditions<2>::Prescribed p{i * bc.per_node + d, i, kNoIndex, inlets[k].velocity[d]};
        const auto it = entry.find(p.dof);
        if (it != entry.end()) bc.prescribed[it->second] = p;
        else bc.prescribed.push_back(p);
      }
}

}  // namespace loom
