// The Cahn-Hilliard entries of the input (section Cahn-Hilliard), declared and read here.
#include <membrane/cahn_hilliard_options.h>

#include <deal.II/base/parameter_handler.h>

#include <limits>

namespace Membrane
{
  using namespace dealii;

  void declare_cahn_hilliard_parameters(ParameterHandler &prm)
  {
    const double max_double = std::numeric_limits<double>::max();
    prm.enter_subsection("Cahn-Hilliard");
    prm.declare_entry("Scheme", "stabilized", Patterns::Selection("stabilized|linearized|explicit"),
                      "Treatment of f'(phi) in the linear step: stabilized: f'(phi^m) + s (phi - phi^m), energy "
                      "stable for s >= 9/8 (default); linearized: f'(phi^m) + f''(phi^m)(phi - phi^m); explicit: "
                      "f'(phi^m) as in the paper (tau limited by the double well).");
    prm.declare_entry("Stabilization", "1.5", Patterns::Double(0, max_double),
                      "s of the stabilized scheme (dimensionless, multiplies sigma). s >= max|f''|/2 = 9/8 on "
                      "[-1, 1] guarantees energy decay; 1.5 covers |phi| <= 1.1.");
    prm.leave_subsection();
  }

  CahnHilliardOptions parse_cahn_hilliard_parameters(ParameterHandler &prm)
  {
    CahnHilliardOptions options;
    prm.enter_subsection("Cahn-Hilliard");
    options.scheme        = prm.get("Scheme");
    options.stabilization = prm.get_double("Stabilization");
    prm.leave_subsection();
    return options;
  }
} // namespace Membrane
