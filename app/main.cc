// membrane-flow: phase separation and shape dynamics of an inhomogeneous lipid
// membrane (Mercker et al., SIAM J. Appl. Math. 73, 2013). See README.md.
#include <membrane/app.h>
#include <membrane/solvers/blas_threads.h>

#include <deal.II/base/mpi.h>

int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Membrane::use_single_threaded_blas();
  return Membrane::run_application(argc, argv);
}
