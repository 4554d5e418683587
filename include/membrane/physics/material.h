#pragma once
// The membrane's material: phase-dependent moduli and the scalar constants of
// MODEL.md sections 2-3, with the pointwise energy density and its phi-derivative
// (the curvature part of the chemical potential Y).

#include <membrane/physics/moduli.h>

#include <memory>

namespace Membrane
{
  struct Material
  {
    std::unique_ptr<ModulusLaw> bending_rigidity;      ///< kappa(phi)
    std::unique_ptr<ModulusLaw> gaussian_rigidity;     ///< kappa_G(phi)
    std::unique_ptr<ModulusLaw> spontaneous_curvature; ///< H0(phi)
    double line_tension      = 0; ///< sigma
    double transition_length = 0; ///< xi
    double shape_mobility    = 0; ///< L_X
    double phase_mobility    = 0; ///< L_phi

    /// Helfrich bending density 1/2 kappa (H - H0)^2.
    double bending_density(double phi, double H) const;
    /// Gaussian density kappa_G K.
    double gaussian_density(double phi, double K) const;
    /// d/dphi of the two curvature densities:
    /// 1/2 kappa' (H - H0)^2 - kappa (H - H0) H0' + kappa_G' K.
    double curvature_potential(double phi, double H, double K) const;
  };
} // namespace Membrane
