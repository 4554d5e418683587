#include <membrane/physics/terms/gaussian.h>
#include <membrane/surface/surface.h>

#include <cmath>

namespace Membrane
{
  void GaussianEnergy::prepare(const Surface &surface, const Geometry &)
  {
    euler_characteristic = surface.euler_characteristic();
    constant_part = 0.5 * (material.gaussian_rigidity->value(1.0) + material.gaussian_rigidity->value(-1.0));
  }

  void GaussianEnergy::add_energy(const TermPoint &point, const double ds, EnergyTerms &energy) const
  {
    // Only the phase-dependent part kappa_G(phi) - kappa_G_c is integrated against the projected
    // K^m; the constant part is exact by Gauss-Bonnet (add_global_energy). The projected K does not
    // integrate to 2 pi chi, and its error at a narrow neck grows with the level.
    energy.gaussian += (material.gaussian_rigidity->value(point.phi) - constant_part) * point.K * ds;
  }

  void GaussianEnergy::add_global_energy(EnergyTerms &energy) const
  {
    energy.gaussian += 2 * M_PI * euler_characteristic * constant_part; // Gauss-Bonnet
  }

  double GaussianEnergy::potential(const TermPoint &point) const
  {
    return material.gaussian_rigidity->derivative(point.phi) * point.K; // kappa_G' K
  }

  void GaussianEnergy::add_shape_force(const TermPoint &point, ShapeForce &force) const
  {
    // lap_c[kappa_G] of E_n in weak form, + tau L_X (kappa_G' c^ij d_j phi a_i, grad psi), with
    // c^ij d_j phi a_i = H_nu grad phi + sym(grad_s nu) grad phi and H_nu = -tr grad_s nu
    // (from the gradient of the Q1 vertex-normal field; docs/model.md).
    const auto  &G        = point.grad_nu;
    const auto  &grad_phi = point.grad_phi;
    const double H_nu     = -trace(G);
    force.flux += material.gaussian_rigidity->derivative(point.phi) *
                  (H_nu * grad_phi + 0.5 * (G * grad_phi + transpose(G) * grad_phi));
  }
} // namespace Membrane
