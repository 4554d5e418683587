#pragma once
// Adding cell matrices to the global PETSc matrix. deal.II's
// AffineConstraints::distribute_local_to_global resolves the constraints row by row and
// hands PETSc one row at a time; on the uniform parts of a mesh no DoF of a cell is
// constrained, and one MatSetValues call for the whole cell block does the same work
// with far less overhead (the insertion was about 8 % of a 7.3 step).

#include <membrane/core/types.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <petscmat.h>

#include <vector>

namespace Membrane
{
  /// Adds cell contributions to a matrix (and right-hand side) assembled from scratch.
  /// A cell without constrained DoFs goes to PETSc as one block; the values and the
  /// order in which they accumulate are those of distribute_local_to_global (zero
  /// entries are skipped as deal.II skips them: MAT_IGNORE_ZERO_ENTRIES, so that
  /// patterns without some couplings stay valid). Other cells go through
  /// distribute_local_to_global. Call compress(add) on the matrix and vector afterwards.
  class CellAssembler
  {
  public:
    CellAssembler(const dealii::AffineConstraints<double> &constraints, SparseMatrix &matrix);

    void add(const dealii::FullMatrix<double> &local_matrix, const std::vector<dealii::types::global_dof_index> &dofs);
    void add(const dealii::FullMatrix<double> &local_matrix, const dealii::Vector<double> &local_rhs,
             const std::vector<dealii::types::global_dof_index> &dofs, Vector &rhs);

  private:
    /// True if no DoF is constrained; then `indices` holds them as PetscInt.
    bool unconstrained(const std::vector<dealii::types::global_dof_index> &dofs);

    const dealii::AffineConstraints<double> &constraints;
    SparseMatrix                            &matrix;
    std::vector<PetscInt>                    indices;
  };
} // namespace Membrane
