// The linear system the PETSc back-end hands to PETSc (plugin only: it includes PETSc's headers): the matrix laid out
// by whole nodes (whole_node_layout.hpp), its right-hand side and solution, the nodes' coordinates and the fields of a
// mixed system, on one process or on every rank of `mpirun -n N loom run`.
//
// Every rank holds loom's whole matrix and right-hand side (the stores are replicated: each rank runs the same steps on
// the same state) and gives PETSc only the rows it owns, contiguous whole row blocks balanced by entries
// (rows_of_ranks), so PETSc never sends a value between ranks while assembling (MAT_NO_OFF_PROC_ENTRIES: its stash
// adds off-process values in the order messages arrive, which would make runs differ bit by bit). The solution is
// gathered back to every rank in rank order, so every rank continues with the same numbers.
// On one process the matrix is a SeqAIJ whose values are written in place, exactly as before there were ranks.
#pragma once

#include <petscksp.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "engine/linalg/whole_node_layout.hpp"

namespace loom {

struct PetscFailure {
  std::string what;
};
// PETSc's words for an error code (the return error handler keeps no message of its own).
std::string petsc_error_text(PetscErrorCode code);

#define LOOM_PETSC_CALL(call)                                                                                         \
  do {                                                                                                                \
    if (PetscErrorCode code_ = (call); code_ != 0) throw PetscFailure{std::string(#call) + ": " + petsc_error_text(code_)}; \
  } while (0)

class PetscSystem {
 public:
  PetscSystem() = default;
  PetscSystem(const PetscSystem&) = delete;
  PetscSystem& operator=(const PetscSystem&) = delete;
  ~PetscSystem() = default;  // the owner calls destroy(), and not after PetscFinalize

  // The communicator of the solve: PETSC_COMM_SELF on one process, PETSC_COMM_WORLD across ranks.
  static MPI_Comm communicator();
  static int ranks();

  // Lays A's pattern out and creates the matrix (preallocated exactly) and the vectors.
  void build(const SparseMatrix& A, const SolveStructure& structure);
  void destroy();
  const WholeNodeLayout& layout() const { return layout_; }
  Mat matrix() const { return matrix_; }
  ::Vec rhs() const { return rhs_; }
  ::Vec solution() const { return solution_; }

  // A's values (the same on every rank), with `decoupled` on the decoupled rows' diagonals.
  void set_values(const SparseMatrix& A, double decoupled);
  // Marks the matrix changed, so that a set-up cannot take it for the one it was set up on.
  void touch();
  void set_rhs(const Eigen::VectorXd& b);
  // x (n of loom's equations) from the solution, on every rank.
  void get_solution(Eigen::VectorXd& x, Index n);
  // The owned row blocks' node coordinates (dim per node), block size dim; the caller destroys it.
  ::Vec node_coordinates(const SolveStructure& structure) const;
  // The owned rows of the first dim dofs of each node (u) and of the others (p), for a fieldsplit.
  void field_sets(int dim, IS* u, IS* p) const;

 private:
  bool distributed() const { return distributed_; }
  bool distributed_ = false;         // an MPIAIJ across ranks
  WholeNodeLayout layout_;
  int first_row_ = 0, end_row_ = 0;  // the rows this rank owns
  std::vector<double> values_;       // across ranks: the whole CSR values, of which this rank sets its rows
  Mat matrix_ = nullptr;
  ::Vec rhs_ = nullptr, solution_ = nullptr;
  VecScatter gather_ = nullptr;  // across ranks: the solution to every rank
  ::Vec whole_solution_ = nullptr;
};

}  // namespace loom
