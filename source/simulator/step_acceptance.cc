// Stage 5 of a step: acceptance. A trial step is rejected when it is not finite, a cell
// degenerates, a vertex moves too far, the energy rises (T = 0) or the estimated local error
// exceeds the tolerance; the step controller (time_step_control.h) then chooses tau. Part of
// Simulator.
#include <membrane/simulator.h>

#include <algorithm>
#include <cmath>

namespace Membrane
{
  using namespace dealii;

  Simulator::Rejection Simulator::judge_step(const double tau_trial, const double energy_before)
  {
    if (!std::isfinite(energy.total()) || !std::isfinite(physical_energy))
      return {"non_finite", "the energy became non-finite"};
    if (parameters.evolve_shape && cell_quality < parameters.min_cell_quality)
      return {"degenerate_cell", "a cell degenerated (corner sine " + format(cell_quality) + " < " +
                                   format(parameters.min_cell_quality) + ")"};
    // A CFL-like bound on the motion: a semi-implicit step is stable at any tau, so a
    // tau far too large for the dynamics shows as a move of many cells, not as a blow-up.
    const double moved_cells = max_increment / reference_cell_size();
    if (parameters.evolve_shape && parameters.max_increment_cells > 0 && moved_cells > parameters.max_increment_cells)
      return {"large_move", "a vertex would move " + format(moved_cells) + " cell sizes in one step (more than <Time "
                            "stepping/Maximum increment> = " + format(parameters.max_increment_cells) +
                            "; 0 there: no bound)"};
    // A moving volume target or a prescribed pressure does work p dV on the membrane:
    // F - integral p dV, not F, is what the constrained gradient flow decreases.
    // With Mesh motion = ale the physical step alone: the mesh motion's change is a discretization
    // error, recorded as mesh_motion_energy. So is the area the smoothing cuts off the curved
    // surface: the next step restores it against the surface pressure, work -(gamma, a_ref - a)
    // that the step control counts as it counts p dV (step_area_work; 0 with the Lagrangian mesh).
    const double rise = physical_energy - energy_before - step_pressure_work - step_area_work;
    dissipation       = -rise; // of the step the loop accepts, for its statistics and equilibrium stop
    // At a temperature the energy fluctuates: a rise is no sign of a failed step.
    if (!parameters.thermal.active() && rise > parameters.energy_tolerance * std::max(std::abs(energy_before), 1e-300))
      return {"energy_rise", "the energy would rise by " + format(rise)};
    step_error     = previous_tau > 0 ? local_error(tau_trial) : -1;
    error_estimate = step_control.controls_accuracy() && step_error >= 0 ? step_error / step_control.accuracy() : -1;
    // An estimate that does not fall with tau is accepted (TimeStepController::irreducible).
    local_error_irreducible = step_control.irreducible(tau_trial, error_estimate);
    if (error_estimate > 1 && !local_error_irreducible)
      {
        step_control.note_error_rejection(tau_trial, error_estimate);
        rejection_factor = TimeStepController::shrink_factor(error_estimate);
        return {"local_error", "the estimated local error is " + format(error_estimate) +
                                 " x <Time stepping/Accuracy tolerance>"};
      }
    return {};
  }

  std::string Simulator::fixed_step_remedy(const Rejection &why) const
  {
    std::string remedy = "; reduce <Time stepping/Time step>";
    if (why.kind == "degenerate_cell" && parameters.mesh_motion == MeshMotion::lagrangian)
      remedy += ", or set <Shape/Mesh motion> = ale (the mesh then does not follow the lipids)";
    if (!parameters.thermal.active())
      remedy += ", or set <Time stepping/Adaptive> = true";
    return remedy;
  }

  double Simulator::local_error(const double tau) const
  {
    // First-order steps: the local error is about half the change of the increment
    // against the previous velocity, tau^2/2 |dV/dt|. Shape in cells, phi absolute.
    const double ratio     = tau / previous_tau;
    const double cell_size = reference_cell_size();
    Vector       shape     = step_increment;
    shape.add(-ratio, previous_increment);
    Vector phase = step_phi_change;
    phase.add(-ratio, previous_phi_change);
    return 0.5 * std::max(shape.linfty_norm() / cell_size, phase.linfty_norm());
  }

  double Simulator::reference_cell_size() const
  {
    return topology->finest_cell_size(finest_level());
  }

} // namespace Membrane
