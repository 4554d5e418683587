#pragma once
// Thermal noise (MODEL.md section 10): the fluctuating gradient flow at temperature k_BT.
//
// Each mobility that dissipates energy gets a noise whose covariance matches it
// (fluctuation-dissipation), and nothing else changes. Every normal variate is drawn from a
// counter-based generator keyed by (seed, step, global id of the vertex or cell, component):
// the trajectory does not depend on the partition, on the order of assembly or on a resume.

#include <membrane/core/types.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/grid/cell_id.h>

#include <cstdint>

namespace Membrane
{
  struct ThermalNoise
  {
    double        temperature = 0; ///< k_BT in the energy unit (0: deterministic)
    std::uint64_t seed        = 1;
    std::uint64_t step        = 0; ///< the index of the step being taken
    /// The ALE scheme's shape step: its tangential noise is grad_s chi of this field (ghosted,
    /// scalar space; physics/tangential_noise.h). Null: the white noise itself.
    const Vector *tangential_potential = nullptr;

    bool active() const { return temperature > 0; }
  };

  /// Entries Temperature and Noise seed of the subsection Material (the caller enters it).
  void declare_thermal_parameters(dealii::ParameterHandler &prm);
  /// Reads them (the caller enters Material).
  ThermalNoise parse_thermal_parameters(dealii::ParameterHandler &prm);

  /// A standard normal variate, a pure function of its key (splitmix64 hashing, Box-Muller).
  double standard_normal(std::uint64_t seed, std::uint64_t step, std::uint64_t id, unsigned int component);

  /// A global id of a cell that does not depend on the partition (a hash of its CellId: the
  /// coarse cell and the path of children to it).
  std::uint64_t cell_key(const dealii::CellId &id);
} // namespace Membrane
