// Stage 4 of a step: grid control. Tangential smoothing of the Lagrangian surface X~ with the
// ALE remap of phi (MODEL.md section 6), kept when the step as a whole descends (always at
// k_BT > 0); then the geometry and energy F^{m+1}. Part of Simulator.
#include <membrane/simulator.h>
#include <membrane/surface/grid_control.h>

#include <cmath>

namespace Membrane
{
  using namespace dealii;

  void Simulator::control_grid(const double energy_before, const double tau)
  {
    const Material &material = parameters.material;
    const auto      update_geometry = [&]() {
      TimerOutput::Scope scope(timer, "geometry");
      geometry = compute_geometry(surface);
      energy   = compute_energy(surface, geometry, phi, material);
    };
    if (!(parameters.evolve_shape && parameters.grid_control_weight > 0))
      return update_geometry();

    // Grid control re-parametrizes the Lagrangian surface X~. The moved state is
    // kept when the step as a whole does not raise the energy; only otherwise is the
    // geometry of X~ itself needed (near equilibrium the move's O(h^2) energy change
    // would stall the energy-based step control at any tau).
    const State lagrangian = save_state();
    {
      TimerOutput::Scope scope(timer, "grid control");
      // With a grid-control rate, a long step is smoothed in several sweeps (each within
      // the stable weight), so the mesh moves at the same rate per unit time whatever tau.
      const unsigned int sweeps = parameters.grid_control_sweeps_of_step(tau);
      const double       weight = parameters.grid_control_weight_of_step(tau);
      // The tangential moves change the volume of the bilinear surface; a fixed volume is
      // restored after each sweep (unless the vertex areas hold it).
      const bool restore_moved_volume = volume_fixed() && !shape_solver.volume_held_by_areas();
      remap_correction = 0;
      for (unsigned int sweep = 0; sweep < sweeps; ++sweep)
        {
          const Vector normal = surface.vector_space().ghosted_copy(compute_vertex_normals(surface));
          const Vector shift  = grid_control_displacement(surface, normal, weight);
          const Vector ratio  = area_ratio();
          remap_correction += move_tangentially_and_remap(surface, shift, phi);
          // The reference area moves with the vertices, each keeping its relative error;
          // the total reference area is kept exactly.
          carry_reference_areas(ratio);
          if (restore_moved_volume)
            restore_volume();
        }
    }
    update_geometry();
    // At a temperature the energy of the step fluctuates by about k_BT per mode, far more than
    // the O(h^2) change of the re-parametrization: the move is always kept.
    if (std::isfinite(energy.total()) &&
        (parameters.thermal.active() ||
         energy.total() <= energy_before + parameters.energy_tolerance * std::abs(energy_before)))
      return;
    restore_state(lagrangian);
    remap_correction  = 0;
    grid_move_skipped = true;
    update_geometry();
  }
} // namespace Membrane
