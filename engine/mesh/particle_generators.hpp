// Initial material points of seed 004: E. Aulisa and G. Capodaglio, "Monolithic coupling of implicit
// material point method with finite element method" (§6.1, Appendix A). A body is a uniform core plus
// boundary layers refined towards its surface by a factor f > 1, each layer 1/f as thick as the previous one.
// The algorithms are the ones of the authors' code (MyFEMuS applications/MPM_FEM ex1..ex4), which reproduce
// the paper's particle counts; the Appendix pseudocode does not (spec seed004 §1.13).
//
// Counting rules (N_b(a) = smallest n with sum_{k=1..n} f^-k >= a, a = layer gap / core spacing):
//  disk: N_r = floor(N_theta0 / 2 pi) core rings of spacing dR = R0 / N_r, ring i (radius R0 - i dR) with
//        ceil(N_theta0 r_i / R0) particles, plus the centre; then N_b((R - R0) / dR) rings, ring k with
//        ceil(f N_theta,k-1) particles (N_theta,0 = N_theta0) at radius R0 + sum_{j<=k} dR f^-j.
//  beam: N_H x N_L core grid, dH = H0 / (N_H - 1), L0 = L - (H - H0) / 2, N_L = ceil(L0 / dH) + 1; then
//        N_b((H - H0) / 2 / dH) - 1 rings (one fewer than the disk rule), ring k with 2 cols + rows - 2
//        particles, cols = ceil(L_k / dL_k) + 1, rows = ceil(H_k / dH_k) + 1.
// Units: lengths in the scene's length unit, density per unit area (plane strain, unit thickness).
#pragma once

#include <vector>

#include "engine/core/types.hpp"

namespace loom {

struct GeneratedParticles {
  std::vector<Vec2> X;         // reference positions
  std::vector<double> mass;    // m_p
  std::vector<double> volume;  // V_p = m_p / density
};

// Disk of seed 004 §6.1 / Appendix A: uniform core of radius core_radius (centre particle + rings), then
// boundary layers refined towards the surface by `factor` until the outer radius reaches `radius`.
struct DiskParticleSpec {
  Vec2 centre = Vec2::Zero();
  double radius = 0, core_radius = 0;
  int n_theta = 0;
  double factor = 1;
  double density = 0;
};

// Cantilever beam: root on the clamped wall at x = root.x(), centre line y = root.y(), length, height, core height,
// N_H points across the core, layer factor; no particles on the clamped side's layers (a ⊐-shaped ring per layer).
struct BeamParticleSpec {
  Vec2 root = Vec2::Zero();
  double length = 0, height = 0, core_height = 0;
  int n_height = 0;
  double factor = 1;
  double density = 0;
};

// Core masses are equal (rho * core area / core count); a layer particle carries rho * its tile
// (disk: r_k * dtheta_k * dR_k, beam: dL_k * dH_k). Throws InputError on invalid parameters.
GeneratedParticles generate_disk_particles(const DiskParticleSpec& spec);
GeneratedParticles generate_beam_particles(const BeamParticleSpec& spec);

}  // namespace loom
