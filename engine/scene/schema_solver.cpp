#include "engine/scene/schema_keys.hpp"

namespace loom {

// [solver]: Newton and the linear solver.
void add_solver_keys(std::vector<KeySpec>& s) {
  s.push_back(key("solver", K::table, "Newton-Raphson and linear solver settings."));
  s.push_back(key("solver.max_iterations", K::integer, "Newton iterations allowed per step before a cut-back.").by_default("25").at_least(1));
  s.push_back(key("solver.residual_relative", K::real, "Converged when |r| <= residual_relative * |r_0| (r_0: first residual of the step).").by_default("1e-8").at_least(0));
  s.push_back(key("solver.residual_absolute", K::real, "Converged when |r| <= residual_absolute (force units).").by_default("1e-10").at_least(0));
  s.push_back(key("solver.increment_relative", K::real, "Converged when |du| <= increment_relative * |u - u_n| (stagnation at round-off).").by_default("1e-12").at_least(0));
  s.push_back(key("solver.line_search", K::boolean, "Backtracking line search on the residual norm.").by_default("false"));
  s.push_back(key("solver.max_cutbacks", K::integer, "Times a step may be halved after Newton fails before the run gives up.").by_default("4").at_least(0).at_most(30));
  s.push_back(key("solver.linear", K::choice,
                  "Linear solver: cholmod (SPD), umfpack (general LU), auto (CHOLMOD, UMFPACK if not positive definite), cg (conjugate "
                  "gradients with the diagonal preconditioner, SPD: for systems too large to factorise, from about 3e5 dofs in 3D; "
                  "slow near incompressibility; docs/solvers_3d.md), cholmod_bisected (SPD: CHOLMOD on the two halves of a bisection at once, "
                  "joined by the separator's Schur complement: uses two cores on large 2D systems; perf/compare/README.md), petsc (PETSc's "
                  "Krylov solvers with algebraic multigrid: CG or GMRES with GAMG and the rigid-body modes, a Schur-complement "
                  "fieldsplit for mixed elements; for systems too large to factorise; docs/petsc.md).")
                  .one_of({"auto", "cholmod", "umfpack", "cg", "cholmod_bisected", "petsc"}).by_default("auto"));
  s.push_back(key("solver.petsc_options", K::string,
                  "solver.linear = \"petsc\": PETSc options that replace loom's defaults, e.g. \"-ksp_type gmres -pc_type ilu\" or "
                  "\"-pc_type lu -pc_factor_mat_solver_type mumps\" (the environment's PETSC_OPTIONS also apply, before these). "
                  "Options PETSc never used are reported at the end of the run.")
                  .by_default("\"\""));
  s.push_back(key("solver.linear_tolerance", K::real,
                  "cg and petsc: each linear solve stops at |K du + r| <= linear_tolerance |r|; reuse_factor: each GMRES solve stops at "
                  "|M^-1 (K du + r)| <= linear_tolerance |M^-1 r|, M the kept factorisation (the increment's relative error). Newton "
                  "then converges as with a direct solver while linear_tolerance is well below solver.residual_relative.")
                  .by_default("1e-10").above(0).below(1));
  s.push_back(key("solver.tangent", K::choice,
                  "every_iteration: full Newton; once_per_step: the tangent of the step's first iteration is factorised once and reused "
                  "(modified Newton, [Reinold 2021] §3.6; methods fem and pfem).")
                  .one_of({"every_iteration", "once_per_step"}).by_default("every_iteration"));
  s.push_back(key("solver.reuse_factor", K::boolean,
                  "Keep the factorisation of the tangent while the sparsity pattern is unchanged (across Newton iterations and "
                  "steps) and solve each new tangent by GMRES preconditioned with it, to solver.linear_tolerance; factorise afresh when "
                  "GMRES needs more than 8 iterations, or fails in 20. Newton stays exact (unlike once_per_step); the iterates differ "
                  "from a fresh factorisation's by linear_tolerance, so a restarted run is not the same bit for bit. For direct "
                  "back-ends: pays where factorising dominates a step (es_pfem at 10^3 to 10^4 dofs; perf/README.md). With petsc: "
                  "the preconditioner (the multigrid hierarchy) is kept instead, and set up afresh when a solve needs more than "
                  "twice the iterations of the first solve after its set-up.")
                  .by_default("false"));
}

}  // namespace loom
