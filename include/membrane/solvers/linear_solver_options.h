#pragma once
// The options of the linear solvers (linear_solver.h: the types), without PETSc.

#include <string>

namespace dealii
{
  class ParameterHandler;
}

namespace Membrane
{
  struct LinearSolverOptions
  {
    std::string  type              = "direct";
    double       relative_tolerance = 1e-10;
    unsigned int max_iterations     = 2000;
    /// direct: GMRES iterations allowed with earlier LU factors before
    /// refactorizing (0: factorize every matrix).
    unsigned int reuse_iterations = 0;
    /// direct with reuse: relative residual reached by those iterations.
    double reuse_tolerance = 1e-12;
    /// direct: dropping tolerance of MUMPS' block low-rank factorization (ICNTL(35) = 2,
    /// CNTL(7)); 0: the exact (full-rank) LU.
    double low_rank_tolerance = 0;
    /// direct: MUMPS writes the LU factors to disk (ICNTL(22) = 1) in $MUMPS_OOC_TMPDIR
    /// (default /tmp) instead of holding them in memory.
    bool out_of_core = false;
  };

  /// The section Linear solver of the input: declared with defaults and documentation, and read.
  void                declare_linear_solver_parameters(dealii::ParameterHandler &prm);
  LinearSolverOptions parse_linear_solver_parameters(dealii::ParameterHandler &prm);
} // namespace Membrane
