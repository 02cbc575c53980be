#include "systems/update/commit_particle_newmark.hpp"

#include "engine/core/parallel.hpp"
#include "engine/mesh/grid_point_shape.hpp"
#include "systems/assemble/assemble_particle_newmark.hpp"
#include "systems/assemble/elements/particle_newmark_point.hpp"

namespace loom {
namespace {

template <int NEN>
void commit(const StepContext& ctx, const Cells& grid, const Nodes<2>& g, const PointLocations& loc, Points<2>& particles) {
  const SceneSpec& scene = *ctx.scene;
  const ParticleNewmark tn{scene.time.beta, scene.time.gamma, ctx.dt};
  const double c_c = scene.mpm.receding_contact;
  const bool receding = c_c > 0.0 && loc.receding.used();
  const bool history = particles.be.used() && loc.be.used();
  for_each_index(particles.X.size(), [&](Index p) {
    const Index c = loc.cell[p];
    const PointShape<NEN> s = point_shape<NEN>(grid, g, c, loc, p);
    NodalVectors<NEN> du;
    for (int a = 0; a < NEN; ++a) du.row(a) = g.u[grid.node(c, a)].transpose();
    const Vec2 u_p = du.transpose() * s.N;
    const Vec2 a_new = tn.acceleration(u_p, particles.v[p], particles.a[p]);
    particles.v[p] = tn.velocity(particles.v[p], particles.a[p], a_new);
    particles.a[p] = a_new;
    particles.u[p] += u_p;
    const NodalVectors<NEN> dN = receding ? particle_trial_gradients<NEN>(s.dN, loc.receding[p], c_c) : s.dN;
    particles.F[p] = deformation_gradient<NEN>(du, dN, particles.F[p]);
    if (history) particles.be[p] = loc.be[p];  // the return map of the converged iterate (the last assembly's)
  });
}

}  // namespace

void commit_particle_newmark(const StepContext& ctx, const Cells& grid, const Nodes<2>& grid_nodes, const PointLocations& loc,
                             Points<2>& particles) {
  if (grid.stride == 9) commit<9>(ctx, grid, grid_nodes, loc, particles);
  else commit<4>(ctx, grid, grid_nodes, loc, particles);
}

void follow_particles(const StepContext&, const std::vector<Index>& followed, const Points<2>& particles, Points<2>& points) {
  for (std::size_t k = 0; k < followed.size(); ++k) points.u[Index(k)] = particles.u[followed[k]];
}

}  // namespace loom
