#pragma once
// Solvers for the (non-symmetric) coupled systems of a time step.
//  direct: MUMPS through PETSc, the robust default;
//  gmres:  restarted GMRES with PETSc's block-Jacobi/ILU, for large runs.

#include <membrane/types.h>

#include <string>

namespace Membrane
{
  struct LinearSolverOptions
  {
    std::string  type              = "direct";
    double       relative_tolerance = 1e-10;
    unsigned int max_iterations     = 2000;
  };

  /// Solve matrix * solution = rhs; returns the iteration count (1 for direct).
  /// Throws dealii::SolverControl::NoConvergence on failure.
  unsigned int solve_linear_system(const SparseMatrix &matrix, Vector &solution, const Vector &rhs,
                                   const LinearSolverOptions &options);
} // namespace Membrane
