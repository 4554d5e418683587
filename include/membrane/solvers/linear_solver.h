#pragma once
// Solvers for the (non-symmetric) coupled systems of a time step, kept alive
// across steps so that work that depends only on the mesh is done once:
//  direct: LU by MUMPS through PETSc, the robust default. The symbolic analysis
//          (fill-reducing ordering) is reused while the sparsity pattern is
//          unchanged, and a second right-hand side costs one substitution.
//          With reuse_iterations > 0 the factors of an earlier matrix are kept as
//          the preconditioner of GMRES for the next matrices (which change little
//          from one time step to the next); only when GMRES needs more than
//          reuse_iterations iterations is the current matrix factorized.
//          For large meshes MUMPS can compress the fronts (block low-rank, BLR) and
//          keep the factors on disk (out of core): less time and memory per
//          factorization, at a relative accuracy of about low_rank_tolerance;
//  gmres:  restarted GMRES with PETSc's block-Jacobi/ILU, for large runs.

#include <membrane/solvers/linear_solver_options.h>
#include <membrane/core/types.h>

#include <petscksp.h>

#include <string>

namespace Membrane
{
  class LinearSolver
  {
  public:
    /// `options_prefix`: PETSc options prefix of this system's KSP ("shape_", "cahn_hilliard_"),
    /// so that expert settings reach one system only, e.g. PETSC_OPTIONS="-shape_ksp_monitor".
    explicit LinearSolver(LinearSolverOptions options = {}, std::string options_prefix = "");
    ~LinearSolver();
    LinearSolver(const LinearSolver &)            = delete;
    LinearSolver &operator=(const LinearSolver &) = delete;

    /// Solve matrix * solution = rhs; returns the iteration count (1 for direct).
    /// A matrix with the pattern of the previous one is factorized numerically
    /// only (the ordering is reused). Throws dealii::ExcMessage on failure (zero
    /// pivot, no convergence).
    unsigned int solve(const SparseMatrix &matrix, Vector &solution, const Vector &rhs);

    /// Another right-hand side for the matrix of the last solve(), which must be
    /// unchanged since: no factorization, one forward/back substitution.
    unsigned int solve_again(Vector &solution, const Vector &rhs);

    /// Forget the operator and its factorization (call after a mesh change).
    void reset();

    /// Numeric factorizations done so far (for benchmarks and tests).
    unsigned int n_factorizations() const { return factorizations; }

  private:
    void         create(MPI_Comm communicator);
    void         factorize(Mat matrix);
    void         configure_factorization();
    bool         try_solve(Vector &solution, const Vector &rhs);
    unsigned int apply_factors(Vector &solution, const Vector &rhs);
    unsigned int iterations() const;

    LinearSolverOptions options;
    std::string         options_prefix;
    KSP                 ksp            = nullptr;
    Mat                 factorized     = nullptr; ///< copy of the matrix whose LU factors are in use
    Mat                 current        = nullptr; ///< the matrix of the last solve()
    bool                factors_current = false;  ///< `factorized` equals `current`
    bool                configured      = false;  ///< MUMPS' controls set on the factor matrix
    unsigned int        factorizations = 0;
    std::string         failure;
  };
} // namespace Membrane
