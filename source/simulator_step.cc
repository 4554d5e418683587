// One trial step of a run (the steps 1-5 of simulator.h) and the state it restores
// when the step is rejected. Part of Simulator.
#include <membrane/simulator.h>
#include <membrane/surface/grid_control.h>

#include <cmath>

namespace Membrane
{
  using namespace dealii;

  Simulator::State Simulator::save_state() const
  {
    State state{surface.vector_space().make_owned(), phi, pressure, reference_areas, geometry, energy};
    state.displacement = surface.displacement();
    return state;
  }

  void Simulator::restore_state(const State &state)
  {
    surface.set_displacement(state.displacement);
    phi      = state.phi;
    pressure = state.pressure;
    reference_areas = state.reference_areas;
    geometry = state.geometry;
    energy   = state.energy;
  }

  Vector Simulator::area_target(const double tau, const Vector &areas) const
  {
    // The step restores a fraction theta = min(1, tau / T_a) of the area defect a_ref - a^m
    // (a Baumgarte-type relaxation of the constraint drift at the rate 1/T_a). Restoring it
    // whole in every step would move the surface by an amount that does not shrink with tau,
    // and so change the energy by about integral gamma (a_ref - a^m) even in the shortest
    // step: a step cut short to land on the end time, or retried after a rejection, was then
    // rejected at any tau and the run stalled.
    Vector target = areas;
    if (parameters.shape_options.correct_area)
      {
        const double relaxation = parameters.shape_options.area_relaxation_time;
        const double theta      = relaxation > 0 ? std::min(1.0, tau / relaxation) : 1.0;
        target *= 1 - theta;
        target.add(theta, reference_areas);
      }
    return target;
  }

  bool Simulator::move_shape(const double tau_trial, const Vector &phi_new)
  {
    const ShapeOptions &options = parameters.shape_options;
    const Vector        areas_before = vertex_areas(surface);
    const Vector        target       = area_target(tau_trial, areas_before);
    Vector              defect_of_step = target;
    defect_of_step -= areas_before;
    ShapeUpdate update = shape_solver.step(surface, geometry, parameters.material, options, parameters.linear_solver,
                                           tau_trial, defect_of_step, phi, chemical_potential, &timer,
                                           volume_term(tau_trial), noise_of_step());
    Vector moved = surface.vector_space().make_owned();
    moved        = surface.displacement();
    const auto apply = [&](const ShapeUpdate &part) {
      if (!std::isfinite(part.increment.l2_norm()) || !std::isfinite(part.pressure.l2_norm()))
        return false;
      moved += part.increment;
      surface.set_displacement(moved);
      return true;
    };
    if (!apply(update))
      return false;
    max_increment  = update.increment.linfty_norm();
    step_increment = update.increment;
    Vector gamma  = update.pressure;
    volume_pressure = update.volume_pressure;
    // The linearized constraint leaves an O(|grad W|^2) area error in every step.
    // Projecting it out within the step (same operator, one back-substitution)
    // keeps it from being corrected by the next step, whatever its tau.
    area_projections      = 0;
    tangential_area_moves = 0;
    const bool fixed_volume = volume_fixed() && !shape_solver.volume_held_by_areas();
    if (options.correct_area || fixed_volume)
      {
        TimerOutput::Scope scope(timer, "area projection");
        // With a fixed volume each projection also restores V; a last one with the volume
        // defect alone removes the O(|W'|^2) volume error of the area corrections, which
        // stay large where the stabilized area row cannot be met exactly.
        // (The volume projection is made without the area ones too, Correct area = false.)
        const unsigned int projections =
          (options.correct_area ? options.area_corrections : 0) + (fixed_volume ? 1 : 0);
        for (unsigned int k = 0; k < projections; ++k)
          {
            const bool           volume_only = fixed_volume && k + 1 == projections;
            const Vector         areas  = vertex_areas(surface);
            const VolumeCoupling volume = volume_term(tau_trial);
            if ((volume_only || max_relative_difference(areas, target) <= options.area_tolerance) &&
                (!fixed_volume || std::abs(volume.volume_defect) <= options.area_tolerance * initial_volume))
              break;
            Vector defect = surface.scalar_space().make_owned();
            if (!volume_only)
              {
                defect = target;
                defect -= areas;
              }
            const ShapeUpdate correction = shape_solver.correct_area(surface, defect, &timer, volume);
            if (!apply(correction))
              return false;
            gamma += correction.pressure;
            volume_pressure += correction.volume_pressure;
            step_increment += correction.increment;
            ++area_projections;
          }
      }
    if (options.correct_area && options.tangential_area_iterations > 0)
      {
        TimerOutput::Scope scope(timer, "area projection");
        // Tangent planes of X^m + W, not of X^m: the step may have turned them.
        const Vector normal     = surface.vector_space().ghosted_copy(compute_vertex_normals(surface));
        const auto   tangential = tangential_corrector.correct(surface, normal, target,
                                                                 options.tangential_area_tolerance,
                                                                 options.tangential_area_iterations);
        tangential_area_moves = tangential.iterations;
        // The moves changed the surface itself: the volume projection below adds to them
        // (starting again from the displacement before the moves would undo them).
        moved = surface.displacement();
        if (fixed_volume && tangential.iterations > 0)
          {
            // The tangential moves change the enclosed volume of the bilinear surface at
            // second order: one more volume projection restores it.
            const ShapeUpdate correction = shape_solver.correct_area(surface, surface.scalar_space().make_owned(),
                                                                     &timer, volume_term(tau_trial));
            if (!apply(correction))
              return false;
            gamma += correction.pressure;
            volume_pressure += correction.volume_pressure;
          }
      }
    pressure = gamma;
    // phi~ rides on the vertices (Lagrangian), so integral phi ds = sum phi_i a_i
    // changes with the vertex areas. The pressure stabilization leaves a local area
    // error of O(tau) per step (the residual of the tangential law in the area row)
    // that correlates with grad phi and so adds up; a constant restores the mass.
    phi = phi_new;
    if (options.correct_mass)
      {
        Vector       corrected = phi_new;
        const double mass      = integrate(surface, phi);
        shape_mass_correction  = (initial_mass - mass) / surface.area();
        corrected.add(shape_mass_correction);
        surface.scalar_space().constraints().distribute(corrected);
        phi = corrected;
      }
    return true;
  }

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

  Simulator::Rejection Simulator::try_step(const double tau_trial)
  {
    const Material &material = parameters.material;
    const State     before   = save_state();
    const double    pressure_before = volume_pressure;
    const auto      restore  = [&](const char *kind, const std::string &message) {
      restore_state(before);
      volume_pressure = pressure_before;
      return Rejection{kind, message};
    };
    grid_move_skipped = false;
    trial_end_time    = time + tau_trial;

    Vector phi_new   = surface.scalar_space().make_owned();
    Vector potential = surface.scalar_space().make_owned();
    try
      {
        solver_iterations = cahn_hilliard.step(surface, geometry, material, parameters.cahn_hilliard,
                                               parameters.linear_solver, tau_trial, phi, phi_new, potential, &timer,
                                               noise_of_step());
        if (!std::isfinite(phi_new.l2_norm()) || phi_new.linfty_norm() > 10)
          return restore("non_finite", "phi became non-finite or |phi| > 10");
        chemical_potential = potential;
        step_phi_change    = phi_new;
        {
          Vector old = surface.scalar_space().make_owned();
          old        = phi;
          step_phi_change -= old;
        }
        step_increment = surface.vector_space().make_owned();

        max_increment    = 0;
        remap_correction = 0;
        step_pressure_work = 0;
        if (parameters.evolve_shape)
          {
            const double volume_before = volume_constrained() ? enclosed_volume(surface) : 0;
            if (!move_shape(tau_trial, phi_new))
              return restore("non_finite", "the shape solve gave non-finite values");
            step_pressure_work = pressure_work_of_step(volume_before, pressure_before);
          }
        else
          phi = phi_new;
        control_grid(before.energy.total() + step_pressure_work, tau_trial);
        cell_quality = min_corner_sine(surface, geometry.normal);
      }
    catch (const std::exception &)
      {
        return restore("solver_failure", "a linear solve failed");
      }

    if (!std::isfinite(energy.total()))
      return restore("non_finite", "the energy became non-finite");
    if (parameters.evolve_shape && cell_quality < parameters.min_cell_quality)
      return restore("degenerate_cell", "a cell degenerated (corner sine " + format(cell_quality) + " < " +
                     format(parameters.min_cell_quality) + ")");
    // A CFL-like bound on the motion: a semi-implicit step is stable at any tau, so a
    // tau far too large for the dynamics shows as a move of many cells, not as a blow-up.
    const double moved_cells = max_increment / reference_cell_size();
    if (parameters.evolve_shape && parameters.max_increment_cells > 0 && moved_cells > parameters.max_increment_cells)
      return restore("large_move", "a vertex would move " + format(moved_cells) + " cell sizes in one step (more than <Time "
                     "stepping/Maximum increment> = " + format(parameters.max_increment_cells) +
                     "; 0 there: no bound)");
    // A moving volume target or a prescribed pressure does work p dV on the membrane:
    // F - integral p dV, not F, is what the constrained gradient flow decreases.
    const double rise = energy.total() - before.energy.total() - step_pressure_work;
    // At a temperature the energy fluctuates: a rise is no sign of a failed step.
    if (!parameters.thermal.active() && rise > parameters.energy_tolerance * std::max(std::abs(before.energy.total()), 1e-300))
      return restore("energy_rise", "the energy would rise by " + format(rise));
    step_error     = previous_tau > 0 ? local_error(tau_trial) : -1;
    error_estimate = step_control.controls_accuracy() && step_error >= 0 ? step_error / step_control.accuracy() : -1;
    // An estimate that does not fall with tau is accepted (TimeStepController::irreducible).
    local_error_irreducible = step_control.irreducible(tau_trial, error_estimate);
    if (error_estimate > 1 && !local_error_irreducible)
      {
        step_control.note_error_rejection(tau_trial, error_estimate);
        rejection_factor = TimeStepController::shrink_factor(error_estimate);
        return restore("local_error", "the estimated local error is " + format(error_estimate) +
                       " x <Time stepping/Accuracy tolerance>");
      }
    return {};
  }

  ThermalNoise Simulator::noise_of_step() const
  {
    ThermalNoise noise = parameters.thermal;
    noise.step         = step;
    return noise;
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
} // namespace Membrane
