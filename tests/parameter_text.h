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
} // namespace Membrane::Testing
