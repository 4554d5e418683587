#pragma once
// Tangential grid control and ALE remap of phi (MODEL.md section 4, step 4).
//
// The Lagrangian mesh follows the lipids and shears without bound. After each
// physical step every vertex moves toward the average of its edge neighbours,
// projected on its tangent plane (paper, Discretization 2):
//     d_i = w P_i ( mean_{j ~ i} X_j - X_i ),   P_i = I - nu_i nu_i^T,
// so the surface itself moves only by O(|d|^2 |H|). phi is then remapped so that
// its distribution in space is unchanged: the new vertex X_i + d_i takes the
// value of the old field there, phi_i + d_i . g_i with g the L2-projected
// (continuous) surface gradient of phi. A constant correction restores
// integral phi ds exactly; its size is reported as remap_mass_correction.

#include <membrane/surface/surface.h>

namespace Membrane
{
  /// Grid-control displacement d (owned vector of the vector space).
  Vector grid_control_displacement(const Surface &surface, const Vector &normal_ghosted, double weight);

  /// Continuous surface gradient of a scalar field (L2 projection; owned, vector space).
  Vector recover_gradient(const Surface &surface, const Vector &scalar_ghosted);

  /// Moves the surface by `shift` (owned, vector space) and remaps `phi`
  /// (ghosted, updated in place). Returns the mass correction per unit area.
  double move_tangentially_and_remap(Surface &surface, const Vector &shift, Vector &phi);

  /// Cell quality of the current surface: the smallest signed sine of a corner
  /// angle over all cells (1: rectangles; <= 0: a folded cell; -1: a cell whose
  /// normal opposes the vertex normals `normal_ghosted`, i.e. an inverted cell).
  double min_corner_sine(const Surface &surface, const Vector &normal_ghosted);
} // namespace Membrane
