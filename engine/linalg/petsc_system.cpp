#include "engine/linalg/petsc_system.hpp"

namespace loom {

std::string petsc_error_text(PetscErrorCode code) {
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  return (text ? std::string(text) : std::string("PETSc error")) + " (" + std::to_string(int(code)) + ")";
}

int PetscSystem::ranks() {
  int size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return size;
}

// One process keeps PETSC_COMM_SELF, the communicator of every result before runs had ranks.
MPI_Comm PetscSystem::communicator() { return ranks() > 1 ? PETSC_COMM_WORLD : PETSC_COMM_SELF; }

void PetscSystem::build(const SparseMatrix& A, const SolveStructure& structure) {
  destroy();
  layout_ = whole_node_layout(A, structure);
  const PetscInt n_rows = layout_.rows;
  const int size = ranks();
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const std::vector<int> first = rows_of_ranks(layout_, size);
  first_row_ = first[std::size_t(rank)], end_row_ = first[std::size_t(rank) + 1];
  distributed_ = size > 1;
  const MPI_Comm comm = communicator();
  LOOM_PETSC_CALL(MatCreate(comm, &matrix_));
  if (size == 1) {
    LOOM_PETSC_CALL(MatSetSizes(matrix_, n_rows, n_rows, n_rows, n_rows));
    LOOM_PETSC_CALL(MatSetType(matrix_, MATSEQAIJ));
    LOOM_PETSC_CALL(MatSetBlockSize(matrix_, layout_.block_size));
    LOOM_PETSC_CALL(MatSeqAIJSetPreallocationCSR(matrix_, layout_.offsets.data(), layout_.columns.data(), nullptr));
  } else {
    const PetscInt mine = end_row_ - first_row_;
    LOOM_PETSC_CALL(MatSetSizes(matrix_, mine, mine, n_rows, n_rows));
    LOOM_PETSC_CALL(MatSetType(matrix_, MATMPIAIJ));
    LOOM_PETSC_CALL(MatSetBlockSize(matrix_, layout_.block_size));
    std::vector<PetscInt> offsets(std::size_t(mine) + 1);
    const int base = layout_.offsets[std::size_t(first_row_)];
    for (PetscInt r = 0; r <= mine; ++r) offsets[std::size_t(r)] = layout_.offsets[std::size_t(first_row_ + r)] - base;
    LOOM_PETSC_CALL(MatMPIAIJSetPreallocationCSR(matrix_, offsets.data(), layout_.columns.data() + base, nullptr));
    LOOM_PETSC_CALL(MatSetOption(matrix_, MAT_NO_OFF_PROC_ENTRIES, PETSC_TRUE));
    values_.assign(layout_.columns.size(), 0.0);
  }
  LOOM_PETSC_CALL(MatSetOption(matrix_, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  LOOM_PETSC_CALL(MatCreateVecs(matrix_, &solution_, &rhs_));
  if (size > 1) LOOM_PETSC_CALL(VecScatterCreateToAll(solution_, &gather_, &whole_solution_));
}

void PetscSystem::destroy() {
  if (matrix_) MatDestroy(&matrix_);
  if (rhs_) VecDestroy(&rhs_);
  if (solution_) VecDestroy(&solution_);
  if (gather_) VecScatterDestroy(&gather_);
  if (whole_solution_) VecDestroy(&whole_solution_);
  values_.clear();
  distributed_ = false;
}

void PetscSystem::set_values(const SparseMatrix& A, double decoupled) {
  if (!distributed()) {
    PetscScalar* values = nullptr;
    LOOM_PETSC_CALL(MatSeqAIJGetArray(matrix_, &values));
    copy_values(A, layout_, decoupled, values);
    LOOM_PETSC_CALL(MatSeqAIJRestoreArray(matrix_, &values));
    return;
  }
  copy_values(A, layout_, decoupled, values_.data());
  for (PetscInt r = first_row_; r < end_row_; ++r) {
    const int first = layout_.offsets[std::size_t(r)], count = layout_.offsets[std::size_t(r) + 1] - first;
    LOOM_PETSC_CALL(MatSetValues(matrix_, 1, &r, count, layout_.columns.data() + first, values_.data() + first, INSERT_VALUES));
  }
  LOOM_PETSC_CALL(MatAssemblyBegin(matrix_, MAT_FINAL_ASSEMBLY));
  LOOM_PETSC_CALL(MatAssemblyEnd(matrix_, MAT_FINAL_ASSEMBLY));
}

// (Getting and restoring the values raises the matrix's state; an assembly raises it across ranks.)
void PetscSystem::touch() {
  if (distributed()) return;
  PetscScalar* values = nullptr;
  LOOM_PETSC_CALL(MatSeqAIJGetArray(matrix_, &values));
  LOOM_PETSC_CALL(MatSeqAIJRestoreArray(matrix_, &values));
}

void PetscSystem::set_rhs(const Eigen::VectorXd& b) {
  PetscScalar* values = nullptr;
  LOOM_PETSC_CALL(VecSet(rhs_, 0.0));
  LOOM_PETSC_CALL(VecGetArray(rhs_, &values));
  for (Index e = 0; e < b.size(); ++e) {
    const int row = layout_.row_of_equation[std::size_t(e)];
    if (row >= first_row_ && row < end_row_) values[row - first_row_] = b[e];
  }
  LOOM_PETSC_CALL(VecRestoreArray(rhs_, &values));
}

void PetscSystem::get_solution(Eigen::VectorXd& x, Index n) {
  ::Vec whole = solution_;
  if (distributed()) {
    LOOM_PETSC_CALL(VecScatterBegin(gather_, solution_, whole_solution_, INSERT_VALUES, SCATTER_FORWARD));
    LOOM_PETSC_CALL(VecScatterEnd(gather_, solution_, whole_solution_, INSERT_VALUES, SCATTER_FORWARD));
    whole = whole_solution_;
  }
  const PetscScalar* out = nullptr;
  LOOM_PETSC_CALL(VecGetArrayRead(whole, &out));
  x.resize(n);
  for (Index e = 0; e < n; ++e) x[e] = out[layout_.row_of_equation[std::size_t(e)]];
  LOOM_PETSC_CALL(VecRestoreArrayRead(whole, &out));
}

::Vec PetscSystem::node_coordinates(const SolveStructure& structure) const {
  const int dim = structure.dim, bs = layout_.block_size;
  const PetscInt first_block = first_row_ / bs, end_block = end_row_ / bs;
  ::Vec coords;
  if (distributed()) LOOM_PETSC_CALL(VecCreateMPI(PETSC_COMM_WORLD, (end_block - first_block) * dim, PETSC_DETERMINE, &coords));
  else LOOM_PETSC_CALL(VecCreateSeq(PETSC_COMM_SELF, PetscInt(layout_.node_of_row_block.size()) * dim, &coords));
  LOOM_PETSC_CALL(VecSetBlockSize(coords, dim));
  PetscScalar* c = nullptr;
  LOOM_PETSC_CALL(VecGetArray(coords, &c));
  for (PetscInt b = first_block; b < end_block; ++b)
    for (int d = 0; d < dim; ++d)
      c[std::size_t(b - first_block) * std::size_t(dim) + std::size_t(d)] =
          structure.coordinates[std::size_t(layout_.node_of_row_block[std::size_t(b)]) * std::size_t(dim) + std::size_t(d)];
  LOOM_PETSC_CALL(VecRestoreArray(coords, &c));
  return coords;
}

void PetscSystem::field_sets(int dim, IS* u, IS* p) const {
  const int per_node = layout_.block_size;
  std::vector<PetscInt> u_rows, p_rows;
  for (PetscInt r = first_row_; r < end_row_; ++r) (r % per_node < dim ? u_rows : p_rows).push_back(r);
  const MPI_Comm comm = communicator();
  LOOM_PETSC_CALL(ISCreateGeneral(comm, PetscInt(u_rows.size()), u_rows.data(), PETSC_COPY_VALUES, u));
  LOOM_PETSC_CALL(ISSetBlockSize(*u, dim));
  LOOM_PETSC_CALL(ISCreateGeneral(comm, PetscInt(p_rows.size()), p_rows.data(), PETSC_COPY_VALUES, p));
}

}  // namespace loom
