#pragma once
// The options of the Cahn-Hilliard step (cahn_hilliard.h: the schemes), without the solver.

#include <string>

namespace dealii
{
  class ParameterHandler;
}

namespace Membrane
{
  struct CahnHilliardOptions
  {
    std::string scheme        = "stabilized";
    double      stabilization = 1.5; ///< s (the term is sigma s (phi~ - phi^m))
  };

  /// The section Cahn-Hilliard of the input: declared with defaults and documentation, and read.
  void                declare_cahn_hilliard_parameters(dealii::ParameterHandler &prm);
  CahnHilliardOptions parse_cahn_hilliard_parameters(dealii::ParameterHandler &prm);
} // namespace Membrane
