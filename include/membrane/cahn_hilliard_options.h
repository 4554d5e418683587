#pragma once
// The options of the Cahn-Hilliard step (cahn_hilliard.h: the schemes), without the solver.

#include <string>

namespace Membrane
{
  struct CahnHilliardOptions
  {
    std::string scheme        = "stabilized";
    double      stabilization = 1.5; ///< s (the term is sigma s (phi~ - phi^m))
  };
} // namespace Membrane
