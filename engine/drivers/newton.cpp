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

}  // namespace

NewtonReport solve_newton(NonlinearProblem& p, const NewtonSettings& s, Timers& timers) {
  NewtonReport report;
  IterationMark iteration_mark(timers);
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
      if (!p.assemble(true)) return fail("a cell inverted during the Newton iterations");
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
      if (admissible && !acceptable()) return fail("the line search found no decrease of the residual");
    }
    if (!admissible) return fail("a cell inverted during the Newton iterations");
    if (!std::isfinite(r_new)) return fail("the residual is not finite");
    r = r_new;
    note_blocks();
    report.residuals.push_back(r);
    if (s.log) *s.log << "  newton " << it << ": |r| = " << r << " (|r|/|r_0| = " << r / std::max(r0, 1e-300) << "), step " << step << "\n";
    if (converged_at(r, step * p.increment_norm())) {
      report.converged = true;
      return report;
    }
    if (r > 1e12 * std::max(r0, s.residual_absolute)) return fail("the residual diverges");
  }
  std::ostringstream os;
  os << "no convergence in " << s.max_iterations << " iterations (residual " << r << ", first " << r0 << ")";
  return fail(os.str());
}

}  // namespace loom
