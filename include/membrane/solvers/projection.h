#pragma once
// L2 projections on the current surface: solve M u = b with the consistent mass
// matrix of a FieldSpace (conjugate gradients, Jacobi preconditioner; the Q1
// mass matrix has a mesh-independent condition number).

#include <membrane/surface/surface.h>

namespace Membrane
{
  /// Mass matrix of `space` on the current surface of `surface`.
  void assemble_mass_matrix(const Surface &surface, const FieldSpace &space, SparseMatrix &mass);

  /// Solve mass * u = rhs (rhs assembled with constraints); returns u owned,
  /// constraints applied.
  Vector solve_mass_system(const FieldSpace &space, const SparseMatrix &mass, const Vector &rhs);
} // namespace Membrane
