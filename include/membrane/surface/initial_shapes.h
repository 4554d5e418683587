#pragma once
// Initial shapes of the periodic patch, as displacements D(u) of the unit square
// (X = (u1, u2, 0) + D). Every shape is periodic by construction or checked.

#include <membrane/surface/surface.h>

#include <deal.II/base/function.h>

#include <string>
#include <vector>

namespace Membrane
{
  /// One periodic cosine mode: amplitude * cos(2 pi (k1 u1 + k2 u2) + phase) in z.
  struct CosineMode
  {
    double amplitude;
    int    k1, k2;
    double phase;
  };

  /// Parse "A k1 k2 [phase]; A k1 k2 [phase]; ..."; throws naming `entry`.
  std::vector<CosineMode> parse_cosine_modes(const std::string &text, const std::string &entry);

  /// Set D to the interpolant of a vector function of the reference point.
  void set_displacement(Surface &surface, const dealii::Function<spacedim> &displacement);

  /// The centred bump of MODEL.md section 5: z = a1 (1 + cos(pi rho / R0)) for
  /// rho = |u - (1/2,1/2)| < R0. Returns a1 solved so that the discrete area is
  /// `target_area` (bisection on the monotone area(a1)).
  double set_bump(Surface &surface, double radius, double target_area);

  /// Sum of cosine modes.
  void set_cosine_modes(Surface &surface, const std::vector<CosineMode> &modes);

  /// User expression "Dx; Dy; Dz" in u1 = x, u2 = y (and pi); must be periodic.
  void set_displacement_expression(Surface &surface, const std::string &expression,
                                   const std::string &entry);

  /// The bump profile b(rho) = 1 + cos(pi rho / R0) inside R0, 0 outside.
  double bump_profile(const dealii::Point<spacedim> &reference_point, double radius);
} // namespace Membrane
