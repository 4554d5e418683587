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

  void LineEnergy::add_stress(const TermPoint &point, dealii::Tensor<2, spacedim> &T) const
  {
    // At fixed nodal phi a variation V changes ds by div_s V ds and |grad_s phi|^2 by
    // -2 grad phi . (grad_s V) grad phi, the well f(phi) not at all:
    //   dF_l[V] = integral ( G div_s V - sigma xi^2 grad phi . (grad_s V) grad phi ) ds,
    // T = G I - sigma xi^2 grad phi (x) grad phi (I acts as the tangential projector, since
    // grad_s V has tangential columns).
    const auto  &grad_phi = point.grad_phi;
    const double G        = sigma * (0.5 * xi2 * grad_phi.norm_square() + DoubleWell::value(point.phi));
    for (unsigned int c = 0; c < spacedim; ++c)
      {
        T[c][c] += G;
        for (unsigned int e = 0; e < spacedim; ++e)
          T[c][e] -= sigma * xi2 * grad_phi[c] * grad_phi[e];
      }
  }
} // namespace Membrane
