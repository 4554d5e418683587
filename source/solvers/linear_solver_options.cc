// The entries of the section Linear solver, declared and read here.
#include <membrane/solvers/linear_solver_options.h>

#include <deal.II/base/parameter_handler.h>

namespace Membrane
{
  using namespace dealii;

  void declare_linear_solver_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    prm.declare_entry("Type", "direct", Patterns::Selection("direct|gmres|block"),
                      "direct: MUMPS (robust; default); gmres: GMRES with block-Jacobi ILU; block: the shape "
                      "system by FGMRES with a block preconditioner (algebraic multigrid on the pressure Schur "
                      "complement and on the normal-motion/curvature pair; iterations independent of the mesh, "
                      "cost per step proportional to the unknowns; consistent curvature mass only), the "
                      "Cahn-Hilliard system by LU (benchmarks/README.md).");
    prm.declare_entry("Relative tolerance", "1e-10", Patterns::Double(1e-16, 1), "For Type = gmres and block.");
    prm.declare_entry("Maximum iterations", "2000", Patterns::Integer(1), "For Type = gmres and block.");
    prm.declare_entry("Reuse iterations", "0", Patterns::Integer(0, 100),
                      "For Type = direct: the LU factors of an earlier step precondition GMRES for the current "
                      "matrix; the matrix is factorized anew only when GMRES would need more than this many "
                      "iterations (0: factorize every step). The result is the same to Reuse tolerance.");
    prm.declare_entry("Reuse tolerance", "1e-12", Patterns::Double(1e-16, 1e-6),
                      "Relative residual that the GMRES iterations with reused factors must reach.");
    prm.declare_entry("Low-rank tolerance", "0", Patterns::Double(0, 1e-4),
                      "For Type = direct: MUMPS compresses the blocks of its fronts to low rank up to this "
                      "relative accuracy (block low-rank factorization, ICNTL(35) = 2, CNTL(7)), and two steps "
                      "of iterative refinement follow every solve; 0: exact LU. At 1e-8 the solution is the "
                      "exact one to round-off and a factorization costs less from about 128 x 128 cells on "
                      "(benchmarks/README.md).");
    prm.declare_entry("Out of core", "false", Patterns::Bool(),
                      "For Type = direct: MUMPS keeps the LU factors on disk, in a directory of each process "
                      "under $MUMPS_OOC_TMPDIR (default /tmp), instead of in memory (ICNTL(22) = 1): for meshes "
                      "whose factors do not fit. Files a killed run leaves there are removed by the next "
                      "out-of-core run on the host.");
    prm.leave_subsection();
  }

  LinearSolverOptions parse_linear_solver_parameters(ParameterHandler &prm)
  {
    LinearSolverOptions options;
    prm.enter_subsection("Linear solver");
    options.type               = prm.get("Type");
    options.relative_tolerance = prm.get_double("Relative tolerance");
    options.reuse_iterations   = prm.get_integer("Reuse iterations");
    options.reuse_tolerance    = prm.get_double("Reuse tolerance");
    options.max_iterations     = prm.get_integer("Maximum iterations");
    options.low_rank_tolerance = prm.get_double("Low-rank tolerance");
    options.out_of_core        = prm.get_bool("Out of core");
    prm.leave_subsection();
    return options;
  }
} // namespace Membrane
