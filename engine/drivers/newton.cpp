#include "engine/drivers/newton.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace loom {

namespace {

// Marks the Newton iteration in progress for the profile; -1 when the loop is left, however.
class IterationMark {
 public:
  explicit IterationMark(Timers& timers) : timers_(timers) { timers_.set_iteration(0); }
  ~IterationMark() { timers_.set_iteration(-1); }
  void set(int iteration) { timers_.set_iteration(iteration); }

 private:
  Timers& timers_;
};

// "1.2e-08": the short form of a relative level in a message.
std::string short_number(double x) {
  std::ostringstream os;
  os.precision(2);
  os << x;
  return os.str();
}

}  // namespace

bool residual_still_decreasing(const std::vector<double>& levels) {
  if (levels.size() < 6) return false;
  const auto half = levels.begin() + std::ptrdiff_t(levels.size() / 2);
  return std::adjacent_find(half, levels.end(), [](double a, double b) { return b >= a; }) == levels.end();
}

// A floor: the later half no better than a decade below the earlier one, and not a slow but steady decrease (a
// tangent kept for the step converges linearly after a fast start).
bool residual_stagnated(const std::vector<double>& levels) {
  if (levels.size() < 6) return false;
  const auto half = levels.begin() + std::ptrdiff_t(levels.size() / 2);
  const double earlier = *std::min_element(levels.begin(), half), later = *std::min_element(half, levels.end());
  return later >= 0.1 * earlier && !residual_still_decreasing(levels);
}

NewtonReport solve_newton(NonlinearProblem& p, const NewtonSettings& s, Timers& timers) {
  NewtonReport report;
  IterationMark iteration_mark(timers);
  // A cell that inverts after a first update of many body sizes: the loads are out of scale with the body.
  auto units_hint = [&]() -> std::string {
    if (!(report.first_increment_over_size > 10.0)) return "";
    return "; the first Newton update moved nodes by " + short_number(report.first_increment_over_size) +
           " times the body's size: the loads are far beyond what the body can carry -- check that E, density, body forces and "
           "tractions are in one system of units (a mesh in mm with a density in kg/m^3 and g in m/s^2 makes the weight 1e6 "
           "times too large for MPa)";
  };
  auto fail = [&](const std::string& why) {
    report.failure = why;
    return report;
  };
  bool first = true;
  bool have_tangent = false;  // the last assembly's tangent is at the current iterate
  int iteration = 0;
  auto assemble = [&]() {
    ScopedTimer t(timers, "newton/assemble");
    const bool lazy = s.expected_iterations > 0 && iteration >= s.expected_iterations && !s.tangent_once_per_step;
    const bool tangent = first || (!s.tangent_once_per_step && !lazy);
    first = false;
    have_tangent = tangent || s.tangent_once_per_step;
    return p.assemble(tangent);
  };

  // A trial point of the line search.
  auto assemble_trial = [&]() {
    if (!(s.line_search && s.trials_without_tangent) || s.tangent_once_per_step) return assemble();
    ScopedTimer t(timers, "newton/assemble");
    have_tangent = false;
    return p.assemble(false);
  };

  if (!assemble()) return fail("a cell is inverted at the start of the step");
  const double r0 = p.residual_norm();
  if (!std::isfinite(r0)) return fail("the initial residual is not finite");
  report.residuals.push_back(r0);
  if (s.log) *s.log << "  newton 0: |r_0| = " << r0 << ", force scale " << p.force_scale() << "\n";
  double r = r0;
  // Blocks (when more than one): the largest norm of each in the step so far.
  std::vector<double> block_reference(std::size_t(p.blocks()), 0.0);
  auto note_blocks = [&] {
    for (int b = 0; b < p.blocks(); ++b) block_reference[std::size_t(b)] = std::max(block_reference[std::size_t(b)], p.block_norm(b));
  };
  const double momentum_0 = p.block_norm(0);
  auto blocks_converged = [&](bool first_assembly) {
    for (int b = 0; b < p.blocks(); ++b) {
      const double n = p.block_norm(b);
      // Momentum: against its first norm and the forces in balance, as the one-block test; pressure: against
      // the largest norm of the step (it starts at exactly 0 from rest).
      double reference = first_assembly ? 0.0 : block_reference[std::size_t(b)];
      if (b == 0) reference = std::max(first_assembly ? 0.0 : momentum_0, p.force_scale());
      if (!(n <= s.residual_absolute || n <= s.residual_relative * reference)) return false;
    }
    return true;
  };
  note_blocks();
  // The residual's level against the reference its test uses (the largest over the blocks): converged at
  // residual_relative; one per accepted assembly, for the stagnation test.
  std::vector<double> levels;
  // A residual (block) already below residual_absolute has converged: level 0.
  auto note_level = [&](double res) {
    double level = res <= s.residual_absolute ? 0.0 : res / std::max({r0, p.force_scale(), 1e-300});
    if (p.blocks() > 1) {
      level = 0.0;
      for (int b = 0; b < p.blocks(); ++b) {
        const double n = p.block_norm(b);
        const double reference = b == 0 ? std::max(momentum_0, p.force_scale()) : block_reference[std::size_t(b)];
        if (n > s.residual_absolute) level = std::max(level, n / std::max(reference, 1e-300));
      }
    }
    levels.push_back(level);
  };
  // Converged at residual norm `res` after an increment of norm `increment`.
  auto converged_at = [&](double res, double increment) {
    if (p.prescribed_pending()) return false;
    if (increment <= s.increment_relative * p.step_change_norm()) return true;
    if (p.blocks() > 1) return blocks_converged(false);
    const double reference = std::max(r0, p.force_scale());
    return res <= s.residual_absolute || res <= s.residual_relative * reference;
  };
  const bool at_rest = p.blocks() > 1 ? blocks_converged(true) : r <= s.residual_absolute || r <= s.residual_relative * p.force_scale();
  if (at_rest && !p.prescribed_pending()) {
    report.converged = true;
    return report;
  }

  for (int it = 1; it <= s.max_iterations; ++it) {
    iteration_mark.set(it);
    if (!have_tangent) {  // lazy tangent: the residual alone did not converge
      ScopedTimer t(timers, "newton/assemble");
      if (!p.assemble(true)) return fail("a cell inverted during the Newton iterations" + units_hint());
      have_tangent = true;
    }
    iteration = it;
    bool solved;
    {
      ScopedTimer t(timers, "newton/solve");
      solved = p.solve();
    }
    if (!solved) return fail(p.solve_failure());
    report.iterations = it;
    if (it == 1) report.first_increment_over_size = p.increment_over_size();
    double step = 1.0;
    {
      ScopedTimer t(timers, "newton/update");
      p.update(step);
    }
    bool admissible = assemble_trial();
    double r_new = admissible ? p.residual_norm() : INFINITY;
    // Armijo on the residual norm; a trial that already converges is accepted (near convergence the
    // residual sits at round-off and need not decrease).
    auto acceptable = [&] { return admissible && (r_new <= (1.0 - 1e-4 * step) * r || converged_at(r_new, step * p.increment_norm())); };
    if (s.line_search && !acceptable()) {
      for (int k = 0; k < 10 && !acceptable(); ++k) {
        {
          ScopedTimer t(timers, "newton/update");
          p.update(-0.5 * step);  // back to half the previous trial step
        }
        step *= 0.5;
        admissible = assemble_trial();
        r_new = admissible ? p.residual_norm() : INFINITY;
      }
      if (admissible && !acceptable()) return fail("the line search found no decrease of the residual" + units_hint());
    }
    if (!admissible) return fail("a cell inverted during the Newton iterations" + units_hint());
    if (!std::isfinite(r_new)) return fail("the residual is not finite" + units_hint());
    r = r_new;
    note_blocks();
    note_level(r);
    report.residuals.push_back(r);
    if (s.log) *s.log << "  newton " << it << ": |r| = " << r << " (|r|/|r_0| = " << r / std::max(r0, 1e-300) << "), step " << step << "\n";
    if (converged_at(r, step * p.increment_norm())) {
      report.converged = true;
      return report;
    }
    if (r > 1e12 * std::max(r0, s.residual_absolute)) return fail("the residual diverges" + units_hint());
  }
  std::ostringstream os;
  os << "no convergence in " << s.max_iterations << " iterations (residual " << r << ", first " << r0 << ")";
  // The best of the later half: the floor the iterations reached. Only a floor of round-off size is named (far
  // above it, the iterations cycle: a message about the tolerance would mislead).
  const double floor = levels.empty() ? 0.0 : *std::min_element(levels.begin() + std::ptrdiff_t(levels.size() / 2), levels.end());
  // A floor at or below the tolerance did not stop the iterations (a prescribed value still being applied): no
  // advice about the tolerance then.
  if (residual_still_decreasing(levels)) {
    const auto half = levels.begin() + std::ptrdiff_t(levels.size() / 2);
    const double factor = std::pow(levels.back() / *half, 1.0 / double(levels.end() - half - 1));
    os << ": the residual was still decreasing, by a factor of " << short_number(factor)
       << " per iteration: raise solver.max_iterations (or, with solver.tangent = \"once_per_step\", use every_iteration)";
  } else if (residual_stagnated(levels) && floor <= 1e-4 && floor > s.residual_relative) {
    report.stagnated = true;
    report.stagnation = floor;
    os << ": the residual stagnated at " << short_number(floor) << " relative to the forces in balance, above solver.residual_relative = "
       << short_number(s.residual_relative) << ": loosen it (solver.residual_relative = " << short_number(std::pow(10.0, std::ceil(std::log10(2.0 * floor))))
       << ") if that accuracy suffices, or make the tangent better conditioned (a material nearer incompressibility, or bodies of very "
          "different stiffness, raise the round-off floor of the residual)";
  }
  return fail(os.str());
}

}  // namespace loom
