#pragma once
// The membrane's material: phase-dependent moduli and the scalar constants of
// MODEL.md sections 2-3. The energy terms built from them are in physics/terms/
// (physics/free_energy.h).

#include <membrane/physics/moduli.h>

#include <memory>

namespace dealii
{
  class ParameterHandler;
}

namespace Membrane
{
  /// Area-difference elasticity of a closed bilayer (physics/terms/area_difference.h).
  struct AreaDifferenceOptions
  {
    double stiffness          = 0; ///< k = alpha kappa (energy); 0: no term
    double reduced_difference = 1; ///< m_0
    bool   active() const { return stiffness > 0; }
  };

  struct Material
  {
    std::unique_ptr<ModulusLaw> bending_rigidity;      ///< kappa(phi)
    std::unique_ptr<ModulusLaw> gaussian_rigidity;     ///< kappa_G(phi)
    std::unique_ptr<ModulusLaw> spontaneous_curvature; ///< H0(phi)
    double line_tension      = 0; ///< sigma
    double transition_length = 0; ///< xi
    double shape_mobility    = 0; ///< L_X
    double phase_mobility    = 0; ///< L_phi
    AreaDifferenceOptions area_difference;
  };

  /// The section Material of the input, with its subsections (moduli, Temperature and seed of
  /// the thermal noise, Area difference): declared with defaults and documentation. The parse
  /// reads all but the thermal noise (parse_thermal_parameters).
  void     declare_material_parameters(dealii::ParameterHandler &prm);
  Material parse_material_parameters(dealii::ParameterHandler &prm);
} // namespace Membrane
