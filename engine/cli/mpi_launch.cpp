#include "engine/cli/mpi_launch.hpp"

#include <cstdlib>
#include <string>

#include "engine/core/errors.hpp"
#include "engine/core/interrupt.hpp"
#include "engine/linalg/linear_solver.hpp"

namespace loom {
namespace {

int environment_int(const char* name, int otherwise) {
  const char* value = std::getenv(name);
  if (!value || !*value) return otherwise;
  char* end = nullptr;
  const long n = std::strtol(value, &end, 10);
  return *end == '\0' && n >= 0 ? int(n) : otherwise;
}

}  // namespace

MpiLaunch mpi_launch() {
  MpiLaunch launch;
  for (const auto& [rank, size] : {std::pair{"OMPI_COMM_WORLD_RANK", "OMPI_COMM_WORLD_SIZE"}, std::pair{"PMI_RANK", "PMI_SIZE"}}) {
    const int n = environment_int(size, 0);
    if (n < 1) continue;
    launch.size = n;
    launch.rank = environment_int(rank, 0);
    break;
  }
  return launch;
}

void join_ranks(const MpiLaunch& launch, const SceneSpec& scene) {
  if (launch.size <= 1) return;
  LOOM_CHECK(scene.solver.linear == LinearSolverKind::petsc, InputError,
             scene.solver.linear_where << ": error: solver.linear: a run on " << launch.size
                                       << " MPI ranks solves with solver.linear = \"petsc\" (each rank gives PETSc its own rows); this scene's is "
                                       << linear_solver_key(scene.solver.linear) << " (set it in the scene or add --set solver.linear='\"petsc\"')");
  const int ranks = petsc_ranks();
  LOOM_CHECK(ranks == launch.size, InputError,
             "error: mpirun started " << launch.size << " ranks, but the MPI of loom's PETSc plugin sees "
                                      << (ranks == 0 ? std::string("none (MPI or PETSc did not start)") : std::to_string(ranks))
                                      << ": run loom with the mpirun of the MPI it was built with (Open MPI's, /usr/bin/mpirun on Debian)");
  set_interrupt_agreement(petsc_max_over_ranks());
}

}  // namespace loom
