#pragma once
// Input entries of closed vesicles (docs/vesicles.md): the reference surface (in
// Mesh), the volume constraint (Volume) and the polar-cap initial phase (in Initial
// phase). Called from Parameters::declare/parse; the checks name the entries.

#include <deal.II/base/parameter_handler.h>

namespace Membrane
{
  struct Parameters;

  void declare_vesicle_parameters(dealii::ParameterHandler &prm);
  /// Reads the entries into `parameters` (whose other entries are already read) and
  /// refuses combinations that make no sense on a closed surface or on the patch.
  void parse_vesicle_parameters(dealii::ParameterHandler &prm, Parameters &parameters);
} // namespace Membrane
