#include <membrane/solvers/linear_solver.h>

#include <deal.II/lac/petsc_precondition.h>
#include <deal.II/lac/petsc_solver.h>
#include <deal.II/lac/solver_control.h>

namespace Membrane
{
  using namespace dealii;

  unsigned int solve_linear_system(const SparseMatrix &matrix, Vector &solution, const Vector &rhs,
                                   const LinearSolverOptions &options)
  {
    const MPI_Comm comm = matrix.get_mpi_communicator();
    if (options.type == "direct")
      {
        SolverControl                      control(1, 0);
        PETScWrappers::SparseDirectMUMPS   mumps(control, comm);
        mumps.solve(matrix, solution, rhs);
        return 1;
      }
    SolverControl                      control(options.max_iterations, options.relative_tolerance * rhs.l2_norm());
    PETScWrappers::SolverGMRES         gmres(control, comm, PETScWrappers::SolverGMRES::AdditionalData(100));
    PETScWrappers::PreconditionBlockJacobi preconditioner(matrix);
    gmres.solve(matrix, solution, rhs, preconditioner);
    return control.last_step();
  }
} // namespace Membrane
