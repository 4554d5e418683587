#pragma once
// Test helper: Parameters from .prm text, everything else at its default.
#include <membrane/parameters.h>

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace Membrane::Testing
{
  inline Parameters make_parameters(const std::string &text)
  {
    dealii::ParameterHandler prm;
    Parameters::declare(prm);
    prm.parse_input_from_string(text);
    Parameters parameters;
    parameters.parse(prm);
    return parameters;
  }

  /// One fixed step of length tau at k_BT = temperature from a membrane at rest (phi = -1,
  /// line tension 1, grid control off, no VTU), for the one-step covariance tests of the
  /// thermal noise; `surface` holds the Mesh (and Volume) subsections.
  inline Parameters noisy_step_parameters(const std::string &surface, const double temperature,
                                          const unsigned int seed, const double mobility, const double tau,
                                          const double transition_length, const std::string &directory)
  {
    return make_parameters(surface + R"(
subsection Initial phase
  set Type = uniform
  set Uniform value = -1
end
subsection Material
  set Temperature = )" + std::to_string(temperature) + R"(
  set Noise seed = )" + std::to_string(seed) + R"(
  set Shape mobility = )" + std::to_string(mobility) + R"(
  set Line tension = 1
  set Transition length = )" + std::to_string(transition_length) + R"(
end
subsection Shape
  set Grid control weight = 0
end
subsection Time stepping
  set Adaptive = false
  set Time step = )" + std::to_string(tau) + R"(
  set Maximum steps = 1
end
subsection Output
  set Directory = )" + directory + R"(
  set Write VTU = false
end
)");
  }
} // namespace Membrane::Testing
