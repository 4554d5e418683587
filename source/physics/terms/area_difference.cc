#include <membrane/physics/terms/area_difference.h>

#include <cmath>

namespace Membrane
{
  using namespace dealii;

  void declare_area_difference_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Area difference");
    prm.declare_entry("Stiffness", "0", Patterns::Double(0, 1e12),
                      "k = alpha kappa (energy) of the area-difference elasticity of a closed vesicle, F_ADE = pi k / "
                      "(2 A) (M - M_0)^2 with M = integral H ds (MODEL.md section 11; alpha of order 1, Miao et al. "
                      "1994). 0: no such term. Needs a closed <Mesh/Reference surface>.");
    prm.declare_entry("Reduced difference", "1", Patterns::Double(-100, 100),
                      "m_0: the preferred area difference of the monolayers in units of a sphere's, M_0 = -8 pi R_0 "
                      "m_0 with R_0 = sqrt(A / (4 pi)) (H = -2/R on a sphere: a sphere has m = 1).");
    prm.leave_subsection();
  }

  AreaDifferenceOptions parse_area_difference_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Area difference");
    AreaDifferenceOptions options;
    options.stiffness          = prm.get_double("Stiffness");
    options.reduced_difference = prm.get_double("Reduced difference");
    prm.leave_subsection();
    return options;
  }

  std::pair<double, double> total_mean_curvature_and_area(const Surface &surface, const Geometry &geometry)
  {
    return {integrate(surface, geometry.mean_curvature), surface.area()};
  }

  void AreaDifferenceEnergy::prepare(const Surface &surface, const Geometry &geometry)
  {
    const auto [M, A]      = total_mean_curvature_and_area(surface, geometry);
    const double R0        = std::sqrt(A / (4 * M_PI));
    const double preferred = -8 * M_PI * R0 * options.reduced_difference;
    area                   = A;
    excess                 = M - preferred;
  }

  void AreaDifferenceEnergy::add_global_energy(EnergyTerms &energy) const
  {
    energy.area_difference += M_PI * options.stiffness / (2 * area) * excess * excess;
  }

  void AreaDifferenceEnergy::add_shape_force(const TermPoint &point, ShapeForce &force) const
  {
    // -E_n on the right-hand side: + 2 (pi k / A)(M - M_0) K (see the header).
    force.source += 2 * M_PI * options.stiffness / area * excess * point.K;
  }
} // namespace Membrane
