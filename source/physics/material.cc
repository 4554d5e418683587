#include <membrane/physics/material.h>

namespace Membrane
{
  double Material::bending_density(const double phi, const double H) const
  {
    const double excess = H - spontaneous_curvature->value(phi);
    return 0.5 * bending_rigidity->value(phi) * excess * excess;
  }

  double Material::gaussian_density(const double phi, const double K) const
  {
    return gaussian_rigidity->value(phi) * K;
  }

  double Material::curvature_potential(const double phi, const double H, const double K) const
  {
    const double excess = H - spontaneous_curvature->value(phi);
    return 0.5 * bending_rigidity->derivative(phi) * excess * excess -
           bending_rigidity->value(phi) * excess * spontaneous_curvature->derivative(phi) +
           gaussian_rigidity->derivative(phi) * K;
  }
} // namespace Membrane
