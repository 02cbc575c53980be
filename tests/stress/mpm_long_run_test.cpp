// Long MPM runs watched for NaN and energy growth: the dynamic Cook's membrane (seed 003 §6.2.1, load
// applied at t = 0 and held). Newmark with beta = 1/4, gamma = 1/2 conserves energy on a fixed mesh; the
// particle-grid transfers can only dissipate, so the peak of kinetic + elastic energy in the last third of
// the converged steps must not exceed the peak of the first third (5 % allowance for where the peaks fall
// between steps). The peak u_y(A) of the first and last thirds is reported too: it drifts upward while the
// energy decays (docs/BENCHMARKS.md, stress suite). One case runs on a quad4 grid (ghost penalty 0.1).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "tests/stress/stress_support.hpp"

namespace loom::stress {
namespace {

struct Case {
  std::string stabilisation;
  int particles_per_cell, steps;
  bool must_converge;  // false: a known limitation (the row says why); the energy check still applies
  std::string cells = "tri3";  // the grid's cells (quad4: with its default ghost penalty)
};

TEST(Stress, MpmLongDynamicRunsNeitherBlowUpNorGainEnergy) {
  const std::string group = "long runs (MPM, Newmark, dynamic Cook's membrane)";
  const std::vector<Case> cases = {{"asgs", 12, 300, true}, {"ppp", 12, 300, true}, {"osgs", 12, 300, true}, {"asgs", 3, 400, false},
                                   {"asgs", 12, 300, true, "quad4"}};
  for (const Case& c : cases) {
    const std::string name = "mpm " + c.stabilisation + (c.cells == "quad4" ? " on a quad4 grid" : "") + ", " +
                             std::to_string(c.particles_per_cell) + " per cell, " +
                             std::to_string(c.steps) + " steps (t = " + format(0.025 * c.steps, 3) + " s)";
    SCOPED_TRACE(name);
    testing::TempDir out("stress_mpm_long_" + c.stabilisation + "_" + c.cells);
    const Outcome o = run_checked(scene_path("cooks_membrane_mpm_dynamic.toml"), out.path(),
                                  {"--set", "body[0].stabilisation=\"" + c.stabilisation + "\"", "--set",
                                   "body[0].particles_per_cell=" + std::to_string(c.particles_per_cell), "--set",
                                   "time.steps=" + std::to_string(c.steps), "--set", "output.every=0", "--set",
                                   "grid.cells=\"" + c.cells + "\""});
    std::string detail = std::to_string(o.newton_iterations) + " Newton, " + format(o.wall_seconds, 3) + " s";
    bool energy_holds = false;
    if (o.clean && o.probes.rows.size() > 30) {
      const auto kinetic = o.probes.column("kinetic_energy"), elastic = o.probes.column("elastic_energy"), uy = o.probes.column("uy_A");
      const std::size_t n = kinetic.size(), third = n / 3;
      double e_first = 0.0, e_last = 0.0, u_first = 0.0, u_last = 0.0;
      for (std::size_t k = 0; k < n; ++k) {
        const double e = kinetic[k] + elastic[k];
        if (k < third) e_first = std::max(e_first, e), u_first = std::max(u_first, uy[k]);
        if (k >= n - third) e_last = std::max(e_last, e), u_last = std::max(u_last, uy[k]);
      }
      energy_holds = e_last <= 1.05 * e_first;
      detail = "peak kinetic + elastic energy, first / last third of the steps: " + format(e_first, 4) + " / " + format(e_last, 4) +
               "; peak u_y(A): " + format(u_first, 4) + " / " + format(u_last, 4) + "; " + detail;
    }
    EXPECT_TRUE(energy_holds) << name << ": " << detail;
    if (c.must_converge) {
      EXPECT_TRUE(o.converged) << name << ": " << o.failure;
    }
    std::string check = energy_holds ? "holds (energy)" : "FAILS: energy grew";
    if (energy_holds && !o.converged)
      check = c.must_converge ? "FAILS: did not converge"
                              : "holds (energy); FAILS (known): with 3 particles per cell the tip drifts upward period after period "
                                "while the energy decays, until it leaves the background grid";
    record(group, name, o, detail, check);
  }
}

}  // namespace
}  // namespace loom::stress
