// The section Material of the input (the moduli, line tension, mobilities, and the
// subsections of the thermal noise and the area-difference elasticity), declared and read here.
#include <membrane/physics/material.h>
#include <membrane/physics/terms/area_difference.h>
#include <membrane/physics/thermal_noise.h>

#include <deal.II/base/parameter_handler.h>

#include <limits>
#include <string>
#include <utility>

namespace Membrane
{
  using namespace dealii;

  void declare_material_parameters(ParameterHandler &prm)
  {
    const double max_double = std::numeric_limits<double>::max();
    prm.enter_subsection("Material");
    {
      prm.enter_subsection("Bending rigidity");
      declare_modulus_parameters(prm, "kappa", "Bending rigidity (energy; > 0)", 1.0);
      prm.leave_subsection();
      prm.enter_subsection("Gaussian rigidity");
      declare_modulus_parameters(prm, "kappa_G", "Gaussian (saddle-splay) rigidity (energy)", 0.0);
      prm.leave_subsection();
      prm.enter_subsection("Spontaneous curvature");
      declare_modulus_parameters(prm, "H0", "Spontaneous curvature (1/length, sum of principal curvatures; "
                                         "negative bulges along +n)", 0.0);
      prm.leave_subsection();
      prm.declare_entry("Line tension", "450", Patterns::Double(0, max_double),
                        "sigma (energy/length^2): scale of the Cahn-Hilliard energy sigma (xi^2/2 |grad phi|^2 + "
                        "f(phi)); the sharp-interface line tension (energy/length) is sigma * xi. Physical "
                        "units: docs/units.md.");
      prm.declare_entry("Transition length", "0.03", Patterns::Double(1e-12, max_double),
                        "xi: width scale of the diffuse domain boundary (length; the patch side is 1). The "
                        "mesh should resolve it: cell size h <= 1.25 xi.");
      prm.declare_entry("Shape mobility", "5e-4", Patterns::Double(0, max_double),
                        "L_X: mobility of the overdamped shape flow dX/dt = -L_X (E_n n + E_t).");
      prm.declare_entry("Phase mobility", "0.05", Patterns::Double(0, max_double),
                        "L_phi: mobility of lateral sorting dphi/dt = L_phi lap_s Y.");
      declare_thermal_parameters(prm);
      declare_area_difference_parameters(prm);
    }
    prm.leave_subsection();
  }

  Material parse_material_parameters(ParameterHandler &prm)
  {
    Material material;
    prm.enter_subsection("Material");
    for (auto [name, law] : {std::pair{"Bending rigidity", &material.bending_rigidity},
                             std::pair{"Gaussian rigidity", &material.gaussian_rigidity},
                             std::pair{"Spontaneous curvature", &material.spontaneous_curvature}})
      {
        prm.enter_subsection(name);
        *law = parse_modulus_law(prm, std::string("Material/") + name);
        prm.leave_subsection();
      }
    material.line_tension      = prm.get_double("Line tension");
    material.transition_length = prm.get_double("Transition length");
    material.shape_mobility    = prm.get_double("Shape mobility");
    material.phase_mobility    = prm.get_double("Phase mobility");
    material.area_difference   = parse_area_difference_parameters(prm);
    prm.leave_subsection();
    return material;
  }
} // namespace Membrane
