// `mpirun -n N loom run scene.toml`: the rank and size of this process, read from the launcher's environment so that
// the loom program needs no MPI of its own (MPI starts in the PETSc plugin, the only part that communicates).
//
// What a distributed run is today (docs/petsc.md, "More than one process"): every rank reads the scene and runs the
// same steps on the same replicated stores; the linear solve of every Newton iteration is PETSc's across the ranks,
// each rank giving it its own rows, and its solution comes back to every rank. Rank 0 alone prints and writes the
// output, the probes and the checkpoints, which are those of a one-process run.
#pragma once

#include "engine/scene/scene_spec.hpp"

namespace loom {

struct MpiLaunch {
  int rank = 0, size = 1;
  bool lead() const { return rank == 0; }
};

// Open MPI's OMPI_COMM_WORLD_RANK / _SIZE, or MPICH's and Intel MPI's PMI_RANK / PMI_SIZE; one process without them.
MpiLaunch mpi_launch();

// Before a run on more than one rank: the scene must solve with solver.linear = "petsc", and the plugin's MPI must
// see the launcher's ranks (else loom and mpirun are of different MPIs); InputError naming the key otherwise. Then
// the ranks agree on when a signal stops the run.
void join_ranks(const MpiLaunch& launch, const SceneSpec& scene);

}  // namespace loom
