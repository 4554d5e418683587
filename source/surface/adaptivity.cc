#include <membrane/surface/adaptivity.h>

namespace Membrane
{
  using namespace dealii;

  void declare_adaptivity_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Maximum refinement level", "0", Patterns::Integer(0, 6),
                      "Local refinement: levels of refinement allowed above the input mesh (Cells per side) where "
                      "the interface or the curvature need them; cells are coarsened back to the input mesh "
                      "where neither does. 0: a uniform mesh that never changes.");
    prm.declare_entry("Adaptivity interval", "10", Patterns::Integer(1, 100000),
                      "Accepted steps between mesh adaptations (with Maximum refinement level > 0).");
    prm.declare_entry("Interface cells per xi", "1.5", Patterns::Double(0.25, 16),
                      "Cells holding the diffuse interface (a vertex with |phi| < Interface phi) are refined until "
                      "their size on the surface is at most xi / this (the interface's 10-90 % width is 2.9 xi).");
    prm.declare_entry("Interface phi", "0.9", Patterns::Double(0.1, 0.999),
                      "A vertex with |phi| below this belongs to the diffuse interface.");
    prm.declare_entry("Curvature resolution", "0.3", Patterns::Double(0.01, 10),
                      "Cells are refined until h |kappa_max| <= this (h: cell size on the surface, kappa_max: the "
                      "largest principal curvature at its vertices), so that bud caps and necks are resolved.");
  }

  AdaptivityOptions parse_adaptivity_parameters(ParameterHandler &prm)
  {
    AdaptivityOptions options;
    options.max_level              = prm.get_integer("Maximum refinement level");
    options.interval               = prm.get_integer("Adaptivity interval");
    options.interface_cells_per_xi = prm.get_double("Interface cells per xi");
    options.interface_phi          = prm.get_double("Interface phi");
    options.curvature_resolution   = prm.get_double("Curvature resolution");
    return options;
  }
} // namespace Membrane
