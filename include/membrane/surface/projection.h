#pragma once
// L2 projections on the current surface: solve M u = b with the consistent mass
// matrix of a FieldSpace (conjugate gradients, Jacobi preconditioner; the Q1
// mass matrix has a mesh-independent condition number).

#include <membrane/surface/surface.h>

namespace Membrane
{
  /// Mass matrix of `space` on the current surface of `surface`, assembled into
  /// `mass`, which must already have the sparsity of `space` (reinit_matrix).
  void assemble_mass_matrix(const Surface &surface, const FieldSpace &space, SparseMatrix &mass);

  /// The L2 projection: solve M u = rhs (rhs assembled with constraints) with the
  /// surface's mass matrix of `space`; returns u owned, constraints applied.
  Vector project(const Surface &surface, const FieldSpace &space, const Vector &rhs);
} // namespace Membrane
