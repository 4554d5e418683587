#include <membrane/physics/terms/bending.h>

namespace Membrane
{
  void BendingEnergy::add_energy(const TermPoint &point, const double ds, EnergyTerms &energy) const
  {
    const double excess = point.H - material.spontaneous_curvature->value(point.phi);
    energy.bending += 0.5 * material.bending_rigidity->value(point.phi) * excess * excess * ds;
  }

  double BendingEnergy::potential(const TermPoint &point) const
  {
    // d/dphi of the density at fixed X: 1/2 kappa' (H - H0)^2 - kappa (H - H0) H0'.
    const double phi    = point.phi;
    const double excess = point.H - material.spontaneous_curvature->value(phi);
    return 0.5 * material.bending_rigidity->derivative(phi) * excess * excess -
           material.bending_rigidity->value(phi) * excess * material.spontaneous_curvature->derivative(phi);
  }

  void BendingEnergy::add_normal_stiffness(const TermPoint &point, NormalStiffness &stiffness) const
  {
    // The normal row's implicit part, -tau L_X [(kappa grad H~, grad psi) + 1/2 (kappa (H - H0)^2 H~, psi)]:
    // lap_s[kappa (H - H0)] and the H^2 (H - H0) / 2 part of the normal variation, with H~ new.
    const double excess = point.H - material.spontaneous_curvature->value(point.phi);
    stiffness.kappa += material.bending_rigidity->value(point.phi);
    stiffness.curvature_mass += 0.5 * excess * excess;
  }

  void BendingEnergy::add_shape_force(const TermPoint &point, ShapeForce &force) const
  {
    // The rest of E_n with the frozen fields, on the right-hand side with + tau L_X:
    // (grad psi) the phase-dependent part of grad_s[kappa (H - H0)], ((H - H0) kappa' - kappa H0') grad phi;
    // (psi) -kappa (H - H0) |grad_s nu|^2.
    const double phi    = point.phi;
    const double kappa  = material.bending_rigidity->value(phi);
    const double excess = point.H - material.spontaneous_curvature->value(phi);
    force.flux += (excess * material.bending_rigidity->derivative(phi) -
                   kappa * material.spontaneous_curvature->derivative(phi)) *
                  point.grad_phi;
    force.source += -kappa * excess * scalar_product(point.grad_nu, point.grad_nu);
  }
} // namespace Membrane
