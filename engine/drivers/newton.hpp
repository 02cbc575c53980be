// Newton-Raphson on a nonlinear problem given by its operations (seed 000 §2: the residual (4) and its
// linearisation (13)). Converged when no prescribed dof lags its target and either the residual norm is
// below residual_absolute, or below residual_relative times the reference max(|r_0|, force scale) (r_0:
// first residual of the step; force scale: the problem's measure of the forces in balance, so that a step
// that starts in equilibrium at round-off does not chase round-off), or the increment stagnates at
// round-off (|du| <= increment_relative |u - u_n|). An optional
// backtracking line search halves the step while the residual does not decrease (Armijo, c = 1e-4) or
// the iterate is inadmissible (an inverted cell). A problem with several residual blocks (mixed u-p) is
// converged when each block is (NonlinearProblem::blocks). Failure is reported, never thrown: the caller
// cuts the step back. A failure says what to change where it can: a residual that stagnated above the tolerance
// names its level and the tolerance; a cell inverted after a first update of many body sizes names the loads' units.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "engine/timing/timers.hpp"

namespace loom {

struct NewtonSettings {
  int max_iterations = 25;
  double residual_relative = 1e-8;
  double residual_absolute = 1e-10;
  double increment_relative = 1e-12;
  bool line_search = false;
  // Modified Newton (seed 001 §3.6): the tangent of the first iteration is assembled and factorised once per
  // step; later iterations assemble the residual only and reuse the factorisation.
  bool tangent_once_per_step = false;
  // Lazy tangent: from iteration `expected_iterations` on (the previous step's count; 0: never), the
  // assembly after an update computes the residual only, and the tangent is assembled at the same iterate
  // only if that residual has not converged. The converged step then skips a tangent it would not use
  // (a linear problem: one of its two assemblies per step). Only for problems whose residual-only
  // assembly gives the residual of the full one bit for bit, and that keep no state between assemblies.
  int expected_iterations = 0;
  // With the line search, assemble its trial points for the residual alone; the tangent is assembled at the
  // accepted point only if that has not converged (as the lazy tangent). The trials are then a fifth of a full
  // assembly each for es_up (perf/bench_smoothed, BM_SmoothedResidual), and the iterates are the same bit for bit.
  // Same conditions as the lazy tangent.
  bool trials_without_tangent = false;
  std::ostream* log = nullptr;  // one line per iteration (residual, step length) when set
};

class NonlinearProblem {
 public:
  virtual ~NonlinearProblem() = default;
  // Residual (and tangent) at the current iterate; false if the iterate is inadmissible (J <= 0). solve()
  // uses the tangent of the last assemble(true), factorised once.
  virtual bool assemble(bool with_tangent) = 0;
  virtual double residual_norm() const = 0;
  // Solves tangent * du = -residual; false if the tangent is singular.
  virtual bool solve() = 0;
  // Why solve() returned false, for the failure message.
  virtual std::string solve_failure() const { return "the tangent matrix is singular"; }
  // iterate += step * du
  virtual void update(double step) = 0;
  virtual double increment_norm() const = 0;   // |du| on the free dofs
  virtual double step_change_norm() const = 0;  // |u - u_n|
  virtual bool prescribed_pending() const = 0;  // some prescribed dof has not reached its target
  // Norm of the forces in balance at the last assembly (external loads, reactions); 0 if unknown.
  virtual double force_scale() const { return 0.0; }
  // Residual blocks tested separately (seed 001 §3.6: the momentum and the pressure residuals, in force and
  // volume units): block 0 is the momentum one, measured like the single residual (against max(|r_0|, force
  // scale)); the others against the largest norm they had in the step (they start at 0 from rest). Each must
  // fall below residual_relative times its reference (or below residual_absolute).
  virtual int blocks() const { return 1; }
  virtual double block_norm(int /*block*/) const { return residual_norm(); }
  // The largest displacement increment of the last solve relative to the size of the body (0: not known): a first
  // update that moves nodes by many body sizes means loads the body cannot carry (most often a unit mistake).
  virtual double increment_over_size() const { return 0.0; }
};

struct NewtonReport {
  bool converged = false;
  int iterations = 0;               // linear solves
  std::vector<double> residuals;    // residual norm after each assembly that was accepted
  std::string failure;              // why it did not converge
  // Failed in max_iterations with a residual that stopped falling (residual_stagnated) at a level of round-off
  // size above the tolerance: `stagnation`, relative to the reference residual_relative is compared with (<= 1e-4).
  bool stagnated = false;
  double stagnation = 0.0;
  double first_increment_over_size = 0.0;  // NonlinearProblem::increment_over_size after the first solve
};

// Whether residual levels (each relative to its reference, one per accepted assembly after the first) stopped
// falling: at least 6 of them, the best of the later half not a decade below the best of the earlier half, and
// the later half not still falling at every iteration (residual_still_decreasing: slow linear convergence).
bool residual_stagnated(const std::vector<double>& levels);
bool residual_still_decreasing(const std::vector<double>& levels);

NewtonReport solve_newton(NonlinearProblem& problem, const NewtonSettings& settings, Timers& timers);

}  // namespace loom
