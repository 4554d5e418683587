#include <membrane/solvers/cell_assembly.h>
#include <membrane/solvers/petsc_check.h>

#include <petscvec.h>

namespace Membrane
{
  using namespace dealii;

  CellAssembler::CellAssembler(const AffineConstraints<double> &constraints, SparseMatrix &matrix)
    : constraints(constraints)
    , matrix(matrix)
  {
    check_petsc(MatSetOption(matrix, MAT_IGNORE_ZERO_ENTRIES, PETSC_TRUE), "MatSetOption");
  }

  bool CellAssembler::unconstrained(const std::vector<types::global_dof_index> &dofs)
  {
    indices.resize(dofs.size());
    for (unsigned int i = 0; i < dofs.size(); ++i)
      {
        if (constraints.is_constrained(dofs[i]))
          return false;
        indices[i] = static_cast<PetscInt>(dofs[i]);
      }
    return true;
  }

  void CellAssembler::add(const FullMatrix<double> &local_matrix, const std::vector<types::global_dof_index> &dofs)
  {
    if (!unconstrained(dofs))
      return constraints.distribute_local_to_global(local_matrix, dofs, matrix);
    const auto n = static_cast<PetscInt>(dofs.size());
    // FullMatrix stores its entries row by row, as MatSetValues reads them by default.
    check_petsc(MatSetValues(matrix, n, indices.data(), n, indices.data(), &local_matrix(0, 0), ADD_VALUES),
                "MatSetValues");
  }

  void CellAssembler::add(const FullMatrix<double> &local_matrix, const dealii::Vector<double> &local_rhs,
                          const std::vector<types::global_dof_index> &dofs, Vector &rhs)
  {
    if (!unconstrained(dofs))
      return constraints.distribute_local_to_global(local_matrix, local_rhs, dofs, matrix, rhs);
    const auto n = static_cast<PetscInt>(dofs.size());
    check_petsc(MatSetValues(matrix, n, indices.data(), n, indices.data(), &local_matrix(0, 0), ADD_VALUES),
                "MatSetValues");
    check_petsc(VecSetValues(rhs, n, indices.data(), local_rhs.data(), ADD_VALUES), "VecSetValues");
  }
} // namespace Membrane
