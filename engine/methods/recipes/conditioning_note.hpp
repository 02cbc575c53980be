// What a step's tangent said about itself. A tangent that is singular up to round-off (the factorization's
// pivot ratio below LinearSolve::kNearlySingular) is not refused -- the unstabilised mixed elements are
// singular in their spurious pressure modes and are run on purpose to show them -- but it is said: in the
// failure of a step that did not converge, and once per run on stderr for a step that did (its answer
// may then hold an arbitrary part).
#pragma once

#include <cstdio>
#include <ostream>
#include <string>

#include "engine/drivers/step_status.hpp"
#include "engine/graph/step_context.hpp"
#include "engine/linalg/linear_solver.hpp"

namespace loom {

// `hint`: the recipe's likely cause, added to the warning.
inline void note_conditioning(const LinearSolve& solver, const StepContext& ctx, StepStatus& status, std::ostream* log, bool& warned,
                              const std::string& hint = "") {
  const double rcond = solver.min_rcond();
  if (!(rcond < LinearSolve::kNearlySingular)) return;
  char ratio[32];
  std::snprintf(ratio, sizeof ratio, "%.2g", rcond);
  const std::string causes =
      "a part of the model is free to move (a rigid-body motion no condition holds, an hourglass mode of sparse cells) or the "
      "material lost stability";
  if (!status.converged) {
    if (status.failure.find("singular") == std::string::npos)
      status.failure += std::string("; the tangent matrix was singular up to round-off in this step (pivot ratio ") + ratio + "): " + causes;
    return;
  }
  if (warned || !log) return;
  warned = true;
  *log << "loom: warning: step " << ctx.step << " (t = " << ctx.t << "): the tangent matrix is singular up to round-off (pivot ratio "
       << ratio << " < " << LinearSolve::kNearlySingular << "): " << causes
       << ", or the element has spurious modes (the mixed elements without stabilisation); the answer may hold an arbitrary part"
       << (hint.empty() ? "" : "; " + hint) << ". Later steps are not checked again.\n";
}

}  // namespace loom
