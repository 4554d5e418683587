#include <membrane/solvers/out_of_core_directory.h>
#include <membrane/solvers/linear_solver.h>
#include <membrane/solvers/petsc_check.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace Membrane
{
  using namespace dealii;

  LinearSolver::LinearSolver(LinearSolverOptions options, std::string options_prefix)
    : options(std::move(options))
    , options_prefix(std::move(options_prefix))
  {}

  LinearSolver::~LinearSolver()
  {
    reset();
  }

  void LinearSolver::reset()
  {
    if (ksp != nullptr)
      KSPDestroy(&ksp);
    if (factorized != nullptr)
      MatDestroy(&factorized);
    ksp        = nullptr;
    factorized = nullptr;
    configured = false;
  }

  void LinearSolver::create(const MPI_Comm communicator)
  {
    check_petsc(KSPCreate(communicator, &ksp), "KSPCreate");
    PC pc;
    check_petsc(KSPGetPC(ksp, &pc), "KSPGetPC");
    if (options.type == "direct")
      {
        check_petsc(PCSetType(pc, PCLU), "PCSetType");
        check_petsc(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
        if (options.reuse_iterations > 0)
          {
            // The LU factors of an earlier matrix precondition GMRES for the current
            // one; right preconditioning makes the test act on the true residual.
            check_petsc(KSPSetType(ksp, KSPGMRES), "KSPSetType");
            check_petsc(KSPSetPCSide(ksp, PC_RIGHT), "KSPSetPCSide");
            check_petsc(KSPSetTolerances(ksp, options.reuse_tolerance, 0.0, PETSC_DEFAULT,
                                   static_cast<PetscInt>(options.reuse_iterations)),
                  "KSPSetTolerances");
          }
        else
          check_petsc(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
      }
    else
      {
        check_petsc(KSPSetType(ksp, KSPGMRES), "KSPSetType");
        check_petsc(KSPGMRESSetRestart(ksp, 100), "KSPGMRESSetRestart");
        check_petsc(PCSetType(pc, PCBJACOBI), "PCSetType");
        check_petsc(KSPSetTolerances(ksp, options.relative_tolerance, 0.0, PETSC_DEFAULT,
                               static_cast<PetscInt>(options.max_iterations)),
              "KSPSetTolerances");
      }
    // Expert tuning through PETSc's options database (e.g. PETSC_OPTIONS="-mat_mumps_icntl_7 5"),
    // for one system with its prefix ("-shape_mat_mumps_icntl_7 5").
    if (!options_prefix.empty())
      check_petsc(KSPSetOptionsPrefix(ksp, options_prefix.c_str()), "KSPSetOptionsPrefix");
    check_petsc(KSPSetFromOptions(ksp), "KSPSetFromOptions");
  }

  void LinearSolver::configure_factorization()
  {
    // MUMPS reads these at its analysis, so they go on the factor matrix once the
    // operators are known and before the first factorization of this KSP.
    if (configured || options.type != "direct")
      return;
    configured = true;
    if (options.low_rank_tolerance <= 0 && !options.out_of_core)
      return;
    PC pc;
    check_petsc(KSPGetPC(ksp, &pc), "KSPGetPC");
    check_petsc(PCFactorSetUpMatSolverType(pc), "PCFactorSetUpMatSolverType");
    Mat factor;
    check_petsc(PCFactorGetMatrix(pc, &factor), "PCFactorGetMatrix");
    if (options.low_rank_tolerance > 0)
      {
        // Block low-rank fronts, the factors kept in low-rank form; blocks are
        // compressed up to a relative error of CNTL(7).
        check_petsc(MatMumpsSetIcntl(factor, 35, 2), "MatMumpsSetIcntl(35)");
        check_petsc(MatMumpsSetCntl(factor, 7, options.low_rank_tolerance), "MatMumpsSetCntl(7)");
        // Two steps of iterative refinement (a product with the exact matrix and a
        // substitution each) take the solution from about 100 x the tolerance back to
        // round-off at 1e-8 (test Shape.LowRankAndOutOfCoreFactorizationsKeepTheStep).
        check_petsc(MatMumpsSetIcntl(factor, 10, -2), "MatMumpsSetIcntl(10)");
      }
    if (options.out_of_core)
      {
        // MUMPS reads $MUMPS_OOC_TMPDIR at the factorization: this process's own directory,
        // so that files a killed run leaves behind can be told apart and removed later.
        out_of_core_directory();
        check_petsc(MatMumpsSetIcntl(factor, 22, 1), "MatMumpsSetIcntl(22)");
      }
  }

  void LinearSolver::factorize(const Mat matrix)
  {
    if (factorized == nullptr)
      check_petsc(MatDuplicate(matrix, MAT_COPY_VALUES, &factorized), "MatDuplicate");
    else
      check_petsc(MatCopy(matrix, factorized, SAME_NONZERO_PATTERN), "MatCopy");
    // A new state of the preconditioning matrix: PETSc refactorizes numerically
    // and keeps the symbolic analysis (the pattern is the same).
    check_petsc(KSPSetOperators(ksp, matrix, factorized), "KSPSetOperators");
    configure_factorization();
    check_petsc(KSPSetUp(ksp), "KSPSetUp (factorization)");
    PC pc;
    check_petsc(KSPGetPC(ksp, &pc), "KSPGetPC");
    PCFailedReason reason;
    check_petsc(PCGetFailedReason(pc, &reason), "PCGetFailedReason");
    AssertThrow(reason == PC_NOERROR, ExcMessage("the LU factorization failed (PETSc PC reason " +
                                                 std::to_string(static_cast<int>(reason)) + ")"));
    factors_current = true;
    ++factorizations;
  }

  unsigned int LinearSolver::apply_factors(Vector &solution, const Vector &rhs)
  {
    // The factors are those of the current matrix: one substitution is the direct
    // solution (iterating cannot improve on its round-off).
    PC pc;
    check_petsc(KSPGetPC(ksp, &pc), "KSPGetPC");
    check_petsc(PCApply(pc, rhs, solution), "PCApply");
    AssertThrow(std::isfinite(solution.l2_norm()), ExcMessage("the LU solve gave non-finite values"));
    return 1;
  }

  unsigned int LinearSolver::solve(const SparseMatrix &matrix, Vector &solution, const Vector &rhs)
  {
    current = matrix; // MatrixBase::operator Mat
    if (ksp == nullptr)
      create(matrix.get_mpi_communicator());
    if (options.type == "direct" && options.reuse_iterations > 0)
      {
        if (factorized != nullptr)
          {
            check_petsc(KSPSetOperators(ksp, current, factorized), "KSPSetOperators");
            factors_current = false;
            if (try_solve(solution, rhs))
              return iterations();
          }
        factorize(current); // none yet, or the old factors no longer precondition well enough
        return apply_factors(solution, rhs);
      }
    check_petsc(KSPSetOperators(ksp, current, current), "KSPSetOperators");
    configure_factorization();
    if (options.type == "direct")
      ++factorizations;
    AssertThrow(try_solve(solution, rhs), ExcMessage("the linear solver (" + options.type + ") failed: " + failure));
    return iterations();
  }

  unsigned int LinearSolver::solve_again(Vector &solution, const Vector &rhs)
  {
    AssertThrow(ksp != nullptr, ExcMessage("LinearSolver::solve_again() before solve()"));
    if (options.type == "direct" && options.reuse_iterations > 0)
      {
        if (factors_current)
          return apply_factors(solution, rhs);
        if (try_solve(solution, rhs))
          return iterations();
        factorize(current);
        return apply_factors(solution, rhs);
      }
    AssertThrow(try_solve(solution, rhs), ExcMessage("the linear solver (" + options.type + ") failed: " + failure));
    return iterations();
  }

  bool LinearSolver::try_solve(Vector &solution, const Vector &rhs)
  {
    check_petsc(KSPSolve(ksp, rhs, solution), "KSPSolve");
    KSPConvergedReason reason;
    check_petsc(KSPGetConvergedReason(ksp, &reason), "KSPGetConvergedReason");
    failure = "PETSc reason " + std::to_string(static_cast<int>(reason));
    return reason > 0;
  }

  unsigned int LinearSolver::iterations() const
  {
    PetscInt n = 1;
    if (options.type != "direct" || options.reuse_iterations > 0)
      check_petsc(KSPGetIterationNumber(ksp, &n), "KSPGetIterationNumber");
    return static_cast<unsigned int>(std::max<PetscInt>(n, 1));
  }
} // namespace Membrane
