#pragma once
// Phase-dependent material moduli h(phi) for h in {kappa, kappa_G, H0}, with
// h(+1) = h_A and h(-1) = h_B (MODEL.md section 2). A law is a pointwise
// functor giving the value and the derivative h'(phi) needed by the chemical
// potential, so no quadrature loop is written per law.

#include <deal.II/base/parameter_handler.h>

#include <memory>
#include <string>

namespace Membrane
{
  class ModulusLaw
  {
  public:
    virtual ~ModulusLaw()                          = default;
    virtual double value(double phi) const         = 0;
    virtual double derivative(double phi) const    = 0;
  };

  /// Declares, inside the current subsection: Law, Phase A value, Phase B
  /// value, Expression, Derivative expression.
  void declare_modulus_parameters(dealii::ParameterHandler &prm, const std::string &symbol,
                                  const std::string &meaning, double default_value);

  /// Builds the law from the current subsection; `name` is the subsection's
  /// name used in error messages. Throws on inconsistent entries (e.g. a user
  /// derivative that does not match the expression).
  std::unique_ptr<ModulusLaw> parse_modulus_law(dealii::ParameterHandler &prm, const std::string &name);

  /// The laws, for programs and tests that build them directly.
  std::unique_ptr<ModulusLaw> make_linear_law(double phase_a, double phase_b);
  std::unique_ptr<ModulusLaw> make_tanh_law(double phase_a, double phase_b);
  std::unique_ptr<ModulusLaw> make_expression_law(const std::string &value, const std::string &derivative,
                                                  const std::string &name);
} // namespace Membrane
