#include <membrane/physics/moduli.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/function_parser.h>

#include <cmath>
#include <sstream>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    /// h(phi) = mean + half_jump * shape(phi), shape(+-1) = +-1.
    class SymmetricLaw : public ModulusLaw
    {
    public:
      SymmetricLaw(const double phase_a, const double phase_b, const bool use_tanh)
        : mean(0.5 * (phase_a + phase_b))
        , half_jump(0.5 * (phase_a - phase_b))
        , use_tanh(use_tanh)
      {}
      double value(const double phi) const override
      {
        return mean + half_jump * (use_tanh ? std::tanh(phi) / std::tanh(1.0) : phi);
      }
      double derivative(const double phi) const override
      {
        if (!use_tanh)
          return half_jump;
        const double c = std::cosh(phi);
        return half_jump / (std::tanh(1.0) * c * c);
      }

    private:
      const double mean, half_jump;
      const bool   use_tanh;
    };

    class ExpressionLaw : public ModulusLaw
    {
    public:
      ExpressionLaw(const std::string &value_text, const std::string &derivative_text, const std::string &name)
      {
        for (auto [parser, text, entry] : {std::tuple{&value_parser, value_text, "Expression"},
                                           std::tuple{&derivative_parser, derivative_text, "Derivative expression"}})
          try
            {
              parser->initialize("phi", text, {});
            }
          catch (...)
            {
              AssertThrow(false, ExcMessage("Entry <" + name + "/" + entry + ">: cannot parse <" + text +
                                            "> as a function of phi"));
            }
        // The derivative must be that of the expression: compare with central
        // differences on [-1.2, 1.2] (the range phi visits).
        for (double phi = -1.2; phi <= 1.2001; phi += 0.1)
          {
            const double step = 1e-5;
            const double fd   = (value(phi + step) - value(phi - step)) / (2 * step);
            const double err  = std::abs(fd - derivative(phi));
            std::ostringstream message;
            message << "Entry <" << name << "/Derivative expression>: at phi = " << phi << " it gives "
                    << derivative(phi) << " but the expression's slope is " << fd;
            AssertThrow(err <= 1e-5 * (1 + std::abs(fd)), ExcMessage(message.str()));
          }
      }
      double value(const double phi) const override { return value_parser.value(Point<1>(phi)); }
      double derivative(const double phi) const override { return derivative_parser.value(Point<1>(phi)); }

    private:
      FunctionParser<1> value_parser, derivative_parser;
    };
  } // namespace

  std::unique_ptr<ModulusLaw> make_linear_law(const double a, const double b)
  {
    return std::make_unique<SymmetricLaw>(a, b, false);
  }
  std::unique_ptr<ModulusLaw> make_tanh_law(const double a, const double b)
  {
    return std::make_unique<SymmetricLaw>(a, b, true);
  }
  std::unique_ptr<ModulusLaw> make_expression_law(const std::string &value, const std::string &derivative,
                                                  const std::string &name)
  {
    return std::make_unique<ExpressionLaw>(value, derivative, name);
  }

  void declare_modulus_parameters(ParameterHandler &prm, const std::string &symbol, const std::string &meaning,
                                  const double default_value)
  {
    const std::string d = std::to_string(default_value);
    prm.declare_entry("Law", "linear", Patterns::Selection("constant|linear|tanh|expression"),
                      "How " + symbol + " depends on the order parameter phi. linear: (A+B)/2 + (A-B)/2 phi; "
                      "tanh: (A+B)/2 + (A-B)/2 tanh(phi)/tanh(1) (paper section 7.2); constant: A everywhere "
                      "(requires Phase A value = Phase B value); expression: the Expression entry.");
    prm.declare_entry("Phase A value", d, Patterns::Double(), meaning + " of pure phase A (phi = +1), " + symbol + "_A.");
    prm.declare_entry("Phase B value", d, Patterns::Double(), meaning + " of pure phase B (phi = -1), " + symbol + "_B.");
    prm.declare_entry("Expression", d, Patterns::Anything(),
                      "With Law = expression: " + symbol + " as a function of phi (muparser syntax).");
    prm.declare_entry("Derivative expression", "0", Patterns::Anything(),
                      "With Law = expression: d" + symbol + "/dphi as a function of phi; checked against the "
                      "Expression's slope at start-up.");
  }

  std::unique_ptr<ModulusLaw> parse_modulus_law(ParameterHandler &prm, const std::string &name)
  {
    const std::string law = prm.get("Law");
    const double      a   = prm.get_double("Phase A value");
    const double      b   = prm.get_double("Phase B value");
    if (law == "constant")
      {
        AssertThrow(a == b, ExcMessage("Entry <" + name + "/Law> = constant needs Phase A value = Phase B value (got " +
                                       std::to_string(a) + " and " + std::to_string(b) + "); use linear or tanh for a jump"));
        return make_linear_law(a, a);
      }
    if (law == "linear")
      return make_linear_law(a, b);
    if (law == "tanh")
      return make_tanh_law(a, b);
    return make_expression_law(prm.get("Expression"), prm.get("Derivative expression"), name);
  }
} // namespace Membrane
