#include "engine/mesh/tet_particles.hpp"

#include "engine/core/errors.hpp"
#include "engine/mesh/tetrahedron_rules.hpp"

namespace loom {

TetParticles place_tet_particles(const TetMeshData& mesh, int per_cell, double density) {
  const auto& rule = tetrahedron_rule(per_cell);
  TetParticles out;
  const std::size_t n = std::size_t(mesh.n_tets()) * rule.size();
  out.X.reserve(n), out.volume.reserve(n), out.mass.reserve(n);
  for (Index t = 0; t < mesh.n_tets(); ++t) {
    const Vec3* x[4];
    for (int a = 0; a < 4; ++a) x[a] = &mesh.X[std::size_t(mesh.tets[4 * std::size_t(t) + std::size_t(a)])];
    const double volume = tet_volume(*x[0], *x[1], *x[2], *x[3]);
    LOOM_CHECK(volume > 0.0, InputError, "tetrahedron " << t << " of the body mesh has volume " << volume << " (inverted or degenerate)");
    for (const auto& q : rule) {
      out.X.push_back(q.l[0] * *x[0] + q.l[1] * *x[1] + q.l[2] * *x[2] + q.l[3] * *x[3]);
      out.volume.push_back(q.w * volume);
      out.mass.push_back(density * q.w * volume);
    }
  }
  return out;
}

}  // namespace loom
