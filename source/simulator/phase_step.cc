// Stage 1 of a step: the Cahn-Hilliard step on Gamma^m, phi^m -> (phi~, Y) (cahn_hilliard.h),
// with its conserved noise at k_BT > 0. Part of Simulator.
#include <membrane/simulator.h>

#include <cmath>

namespace Membrane
{
  using namespace dealii;

  bool Simulator::phase_step(const double tau, Vector &phi_new)
  {
    Vector potential = surface.scalar_space().make_owned();
    solver_iterations = cahn_hilliard.step(surface, geometry, parameters.material, parameters.cahn_hilliard,
                                           parameters.linear_solver, tau, phi, phi_new, potential, &timer,
                                           noise_of_step());
    if (!std::isfinite(phi_new.l2_norm()) || phi_new.linfty_norm() > 10)
      return false;
    chemical_potential = potential;
    // The change of phi in this step, for the local error estimate (step_acceptance.cc).
    step_phi_change = phi_new;
    Vector old      = surface.scalar_space().make_owned();
    old             = phi;
    step_phi_change -= old;
    return true;
  }

  ThermalNoise Simulator::noise_of_step() const
  {
    ThermalNoise noise = parameters.thermal;
    noise.step         = step;
    if (split_noise)
      noise.tangential_potential = &tangential_noise.potential;
    return noise;
  }
} // namespace Membrane
