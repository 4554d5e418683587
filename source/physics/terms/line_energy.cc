#include <membrane/physics/double_well.h>
#include <membrane/physics/terms/line_energy.h>

namespace Membrane
{
  void LineEnergy::add_energy(const TermPoint &point, const double ds, EnergyTerms &energy) const
  {
    energy.gradient += 0.5 * sigma * xi * xi * point.grad_phi.norm_square() * ds;
    energy.well += sigma * DoubleWell::value(point.phi) * ds;
  }

  void LineEnergy::add_shape_force(const TermPoint &point, ShapeForce &force) const
  {
    // Normal variation of G, on the right-hand side with + tau L_X (source, psi):
    // -sigma xi^2 b^ij d_i phi d_j phi with b^ij d_i phi d_j phi = -grad phi . grad_s nu . grad phi,
    // and + H G (the line energy acts as a tension).
    const auto &grad_phi = point.grad_phi;
    force.source += sigma * xi2 * (grad_phi * (point.grad_nu * grad_phi));
    force.source += point.H * (sigma * (0.5 * xi2 * grad_phi.norm_square() + DoubleWell::value(point.phi)));
  }
} // namespace Membrane
