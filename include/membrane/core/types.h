#pragma once
// Dimensions and linear-algebra types shared by the whole library.
// The membrane is a 2-manifold in R^3; all fields are distributed PETSc vectors
// so that the same code runs on one core and on many (the step-40 pattern).

#include <deal.II/distributed/tria.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

namespace Membrane
{
  constexpr unsigned int dim      = 2;
  constexpr unsigned int spacedim = 3;

  using Triangulation = dealii::parallel::distributed::Triangulation<dim, spacedim>;
  using Vector        = dealii::PETScWrappers::MPI::Vector;
  using SparseMatrix  = dealii::PETScWrappers::MPI::SparseMatrix;

  /// The version of the sources this library was built from (`git describe`).
  const char *code_version();
} // namespace Membrane
