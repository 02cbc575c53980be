// Seed 004 particle generators (see the header for the counting rules). The ceil() arguments are evaluated
// in double precision in the order the authors' code uses, because the published counts depend on it: for
// (N_theta0, R0) = (600, 1.4) the core ring at r = 0.28 has exactly 120 = 600 * 0.28 / 1.4 particles in exact
// arithmetic, but (600 * r) / R0 rounds to 120.00000000000003 and the ring gets 121 (57 083 in all; exact
// integer arithmetic would give 57 082).
#include "engine/mesh/particle_generators.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>

#include "engine/core/errors.hpp"

namespace loom {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// The authors' code stops at 100 layers: layers that do not bridge the gap by then are a bad input.
constexpr int kMaxLayers = 100;
// Ring sizes grow like f^k: refuse sets that would not fit in memory rather than fail allocating them.
constexpr double kMaxParticles = 2.0e7;

// N_b: the smallest n with sum_{k=1..n} factor^-k >= gap (the gap in units of the core spacing).
int count_layers(double gap, double factor) {
  double step = 1.0 / factor;
  double reach = step;
  int n = 1;
  while (reach < gap) {
    LOOM_CHECK(n < kMaxLayers, InputError,
               "particle layers: " << kMaxLayers << " layers of factor " << factor << " span only " << reach
                                   << " core spacings, less than the gap of " << gap << " core spacings");
    step /= factor;
    reach += step;
    ++n;
  }
  return n;
}

void check_total(double n_particles) {
  LOOM_CHECK(n_particles <= kMaxParticles, InputError,
             "particle generator: the parameters give at least " << n_particles
                                                                 << " particles, more than the limit of " << kMaxParticles);
}

void add_particle(GeneratedParticles& out, const Vec2& x, double mass, double density) {
  out.X.push_back(x);
  out.mass.push_back(mass);
  out.volume.push_back(mass / density);
}

void add_ring(GeneratedParticles& out, const Vec2& centre, double r, int n, double mass, double density) {
  const double dtheta = kTwoPi / n;
  for (int j = 0; j < n; ++j)
    add_particle(out, centre + r * Vec2(std::cos(j * dtheta), std::sin(j * dtheta)), mass, density);
}

// One beam boundary layer: extent L x H (from the wall, centred on the centre line), tile dL x dH.
struct BeamLayer {
  double L, H, dL, dH;
  int cols, rows;
};

}  // namespace

GeneratedParticles generate_disk_particles(const DiskParticleSpec& spec) {
  const double R = spec.radius, R0 = spec.core_radius, f = spec.factor, rho = spec.density;
  LOOM_CHECK(R0 > 0 && R0 < R, InputError,
             "disk particles: need 0 < core_radius < radius, got core_radius " << R0 << " and radius " << R);
  LOOM_CHECK(spec.n_theta >= 7, InputError,
             "disk particles: n_theta must be at least 7 (floor(n_theta / 2 pi) >= 1 core ring), got " << spec.n_theta);
  LOOM_CHECK(f > 1, InputError, "disk particles: the layer factor must be > 1, got " << f);
  LOOM_CHECK(rho > 0, InputError, "disk particles: density must be > 0, got " << rho);

  const int n_rings = static_cast<int>(spec.n_theta / kTwoPi);
  const double dR = R0 / n_rings;
  const int n_layers = count_layers((R - R0) / dR, f);
  check_total(0.5 * n_rings * spec.n_theta);  // a lower bound of the core count, before allocating it

  std::vector<int> core_sizes(static_cast<std::size_t>(n_rings));
  double n_core = 1;  // the centre particle
  for (int i = 0; i < n_rings; ++i) {
    const double r = R0 - i * dR;
    core_sizes[std::size_t(i)] = static_cast<int>(std::ceil(spec.n_theta * r / R0));
    n_core += core_sizes[std::size_t(i)];
  }
  std::vector<int> layer_sizes(static_cast<std::size_t>(n_layers));
  double n_total = n_core, n_ring = spec.n_theta;
  for (int k = 0; k < n_layers; ++k) {
    n_ring = std::ceil(f * n_ring);
    n_total += n_ring;
    check_total(n_total);
    layer_sizes[std::size_t(k)] = static_cast<int>(n_ring);
  }

  GeneratedParticles out;
  out.X.reserve(std::size_t(n_total));
  out.mass.reserve(std::size_t(n_total));
  out.volume.reserve(std::size_t(n_total));
  const double core_mass = rho * std::numbers::pi * R0 * R0 / n_core;
  add_particle(out, spec.centre, core_mass, rho);
  for (int i = 0; i < n_rings; ++i) add_ring(out, spec.centre, R0 - i * dR, core_sizes[std::size_t(i)], core_mass, rho);

  // Layer k: thickness dR_k = dR f^-k, particles on its outer radius r_k, each carrying r_k dtheta_k dR_k.
  double r = R0, dR_k = dR;
  for (const int n : layer_sizes) {
    dR_k /= f;
    r += dR_k;
    add_ring(out, spec.centre, r, n, rho * r * (kTwoPi / n) * dR_k, rho);
  }
  return out;
}

GeneratedParticles generate_beam_particles(const BeamParticleSpec& spec) {
  const double L = spec.length, H = spec.height, H0 = spec.core_height, f = spec.factor, rho = spec.density;
  LOOM_CHECK(L > 0 && H > 0, InputError, "beam particles: length and height must be > 0, got " << L << " and " << H);
  LOOM_CHECK(H0 > 0 && H0 < H, InputError,
             "beam particles: need 0 < core_height < height, got core_height " << H0 << " and height " << H);
  const double L0 = L - 0.5 * (H - H0);  // the layers add (H - H0) / 2 at the free end too
  LOOM_CHECK(L0 > 0, InputError,
             "beam particles: length " << L << " leaves no core (length - (height - core_height) / 2 = " << L0 << ")");
  LOOM_CHECK(spec.n_height >= 2, InputError, "beam particles: n_height must be at least 2, got " << spec.n_height);
  LOOM_CHECK(f > 1, InputError, "beam particles: the layer factor must be > 1, got " << f);
  LOOM_CHECK(rho > 0, InputError, "beam particles: density must be > 0, got " << rho);

  const double dH = H0 / (spec.n_height - 1);
  const double n_cols_core = std::ceil(L0 / dH) + 1;
  check_total(n_cols_core * spec.n_height);
  const int n_cols = static_cast<int>(n_cols_core);
  const double dL = L0 / (n_cols - 1);
  const int n_layers = count_layers(0.5 * (H - H0) / dH, f) - 1;

  std::vector<BeamLayer> layers;
  BeamLayer layer{L0, H0, dL, dH, n_cols, spec.n_height};
  double n_total = double(n_cols) * spec.n_height;
  for (int k = 0; k < n_layers; ++k) {
    layer.dL /= f;
    layer.dH /= f;
    layer.L += layer.dL;
    layer.H += 2 * layer.dH;
    const double cols = std::ceil(layer.L / layer.dL) + 1, rows = std::ceil(layer.H / layer.dH) + 1;
    n_total += 2 * cols + rows - 2;
    check_total(n_total);
    layer.cols = static_cast<int>(cols);
    layer.rows = static_cast<int>(rows);
    layers.push_back(layer);
  }

  GeneratedParticles out;
  out.X.reserve(std::size_t(n_total));
  out.mass.reserve(std::size_t(n_total));
  out.volume.reserve(std::size_t(n_total));
  const double x0 = spec.root.x(), y0 = spec.root.y();
  const double core_mass = rho * L0 * H0 / (double(n_cols) * spec.n_height);
  for (int i = 0; i < n_cols; ++i)
    for (int j = 0; j < spec.n_height; ++j) add_particle(out, Vec2(x0 + i * dL, y0 - 0.5 * H0 + j * dH), core_mass, rho);

  // Ring k: top row (wall to free end), free-end column (downwards), bottom row (back to the wall),
  // evenly spaced over the layer's extent; each particle carries the tile dL_k x dH_k.
  for (const BeamLayer& b : layers) {
    const double sx = b.L / (b.cols - 1), sy = b.H / (b.rows - 1), top = y0 + 0.5 * b.H, bottom = y0 - 0.5 * b.H;
    const double mass = rho * b.dL * b.dH;
    for (int j = 0; j < b.cols; ++j) add_particle(out, Vec2(x0 + j * sx, top), mass, rho);
    for (int j = 1; j < b.rows; ++j) add_particle(out, Vec2(x0 + b.L, top - j * sy), mass, rho);
    for (int j = b.cols - 2; j >= 0; --j) add_particle(out, Vec2(x0 + j * sx, bottom), mass, rho);
  }
  return out;
}

}  // namespace loom
