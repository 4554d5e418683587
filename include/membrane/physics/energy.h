#pragma once
// The discrete free energy F^m (MODEL.md section 4): each term integrated over
// the current surface with the fields of the same step.

#include <membrane/physics/material.h>
#include <membrane/surface/geometry.h>

namespace Membrane
{
  struct EnergyTerms
  {
    double bending  = 0; ///< integral 1/2 kappa (H - H0)^2
    double gaussian = 0; ///< integral kappa_G K
    double gradient = 0; ///< integral sigma xi^2/2 |grad_s phi|^2
    double well     = 0; ///< integral sigma f(phi)
    double area_difference = 0; ///< pi k / (2 A) (M - M_0)^2 (closed vesicles, physics/terms/area_difference.h)
    double total() const { return bending + gaussian + gradient + well + area_difference; }
  };

  EnergyTerms compute_energy(const Surface &surface, const Geometry &geometry, const Vector &phi_ghosted,
                             const Material &material);
} // namespace Membrane
