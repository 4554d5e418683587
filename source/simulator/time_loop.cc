// The time loop of a run and one trial step as the sequence of its stages (simulator.h).
// Part of Simulator.
#include <membrane/io/stop_signal.h>
#include <membrane/simulator.h>
#include <membrane/surface/grid_control.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>

namespace Membrane
{
  using namespace dealii;

  RunResult Simulator::run()
  {
    initialize();
    while (advance())
      ;
    return finish();
  }

  void Simulator::initialize()
  {
    wall.restart();
    setup();
    if (parameters.resume_from.empty())
      {
        set_initial_state();
        adapt_initial_mesh();
      }
    else
      resume();
    segment_start_time = time;
    warn_if_unresolved();
    // With a fixed grid-control weight per step the state at a given time depends on the
    // number of steps, which accuracy control exists to choose (docs/time-step-accuracy.md).
    if (parameters.accuracy_tolerance > 0 && parameters.evolve_shape && parameters.grid_control_weight > 0 &&
        parameters.grid_control_rate == 0)
      pcout << "Warning: with <Time stepping/Accuracy tolerance> > 0 and <Shape/Grid control rate> = 0 the mesh is "
               "smoothed once per step whatever tau, so the result depends on the number of steps and does not "
               "converge as the tolerance shrinks; set <Shape/Grid control rate> (e.g. 10).\n";
    // The stabilized step adds s (phi - phi^m) to the potential with no noise to match it, which cools
    // the slow modes of phi at a fixed tau (experiments/studies/capillary_waves: a phase boundary's
    // modes n = 2, 3 keep 56 % and 39 % of their variance at tau = 2e-5).
    if (parameters.thermal.active() && parameters.material.phase_mobility > 0 &&
        parameters.cahn_hilliard.scheme == "stabilized")
      pcout << "Warning: at <Material/Temperature> > 0 the stabilized Cahn-Hilliard scheme lowers the stationary "
               "variance of phi's slow modes at a fixed tau (its stabilization damps every step without noise to "
               "match); for thermal statistics of phi set <Cahn-Hilliard/Scheme> = linearized.\n";
    write_run_info();
    pcout << topology->name() << ": "
          << triangulation.n_global_active_cells() << " cells, "
          << surface.scalar_space().dof_handler().n_dofs() << " vertex DoFs, "
          << Utilities::MPI::n_mpi_processes(communicator) << " MPI rank(s); output in "
          << parameters.output_directory << "/\n";

    if (parameters.resume_from.empty())
      {
        record_statistics(0);
        write_fields();
        next_output_time = parameters.output_interval;
      }
    else
      bud = topology->measure_domain(surface, phi);
  }

  bool Simulator::advance()
  {
    if (loop_stopped)
      return false;
    const auto stop = [&](const std::string &reason, const bool failed) {
      run_result.stop_reason = reason;
      run_result.failed      = failed;
      loop_stopped           = true;
      return false;
    };
    if (end_time_reached())
      return stop("end time", false);
    if (step >= parameters.max_steps)
      return stop("maximum steps", false);
    // SIGTERM/SIGINT: every rank stops at the same step and the state is kept.
    if (Utilities::MPI::max(stop_requested() ? 1 : 0, communicator) > 0)
      {
        interrupted = true;
        return stop(std::string("interrupted by ") + stop_signal_name(stop_signal()) + " at t = " + format(time) +
                      "; a checkpoint of the last state is written",
                    true);
      }
    const double    trial         = std::min(step_control.tau(), parameters.end_time - time);
    const double    energy_before = energy.total();
    rejection_factor              = 0.5;
    const Rejection why           = try_step(trial);
    if (!why.empty())
      {
        ++rejected_steps;
        ++rejections[why.kind];
        if (!step_control.reject(trial, rejection_factor))
          return stop("step failed at t = " + format(time) + ": " + why.message +
                        (parameters.adaptive ? "; tau fell below <Time stepping/Minimum time step>" + curvature_resolution_note()
                                             : fixed_step_remedy(why)) +
                        line_stiffness_note(why, trial) +
                        ". The last good state is kept",
                      true);
        if (step_control.stalled())
          {
            // Steps keep failing at a tiny tau. With a complete bud this is the
            // approach to pinch-off (the neck is below what the mesh resolves).
            const bool budded = classify_outcome(bud, parameters.outcome, false) == "complete bud";
            return stop(std::string(budded ? "pinch-off approach" : "stalled") + " at t = " + format(time) +
                          ": half of the last 20 steps were rejected (last: " + why.message +
                          ") at tau = " + format(step_control.tau()) + curvature_resolution_note() +
                          line_stiffness_note(why, step_control.tau()) +
                          ". The last good state is kept",
                        !budded);
          }
        return true;
      }
    time += trial;
    ++step;
    grid_control_skipped += grid_move_skipped;
    irreducible_error_steps += local_error_irreducible;
    pressure_work += step_pressure_work;
    compare_with_old_mesh(trial);
    record_statistics(trial);
    const double change =
      std::abs(energy.total() - energy_before - step_pressure_work) / std::max(std::abs(energy_before), 1e-300);
    step_control.accept(trial, max_increment, reference_cell_size(), change, error_estimate, local_error_irreducible);
    previous_increment  = step_increment;
    previous_phi_change = step_phi_change;
    previous_tau        = trial;
    if (adaptation_due() && adapt_mesh())
      previous_tau = 0; // the increments live on the old mesh

    const bool output_due = time >= next_output_time * (1 - 1e-12);
    if (output_due || end_time_reached())
      {
        write_fields();
        if (parameters.output_interval <= 0)
          next_output_time = time; // every step
        else
          while (next_output_time <= time * (1 + 1e-12))
            next_output_time += parameters.output_interval;
        if (Utilities::MPI::this_mpi_process(communicator) == 0)
          stats.write(parameters.output_directory + "/statistics.txt");
      }
    if (parameters.checkpoint_interval > 0 && step % parameters.checkpoint_interval == 0)
      write_checkpoint();
    report_progress(end_time_reached());

    if (parameters.evolve_shape && bud.neck_ratio < parameters.outcome.complete_neck_ratio &&
        bud.neck_radius < parameters.pinch_off_radius)
      return stop("pinch-off approach: neck radius " + format(bud.neck_radius) + " < " +
                    format(parameters.pinch_off_radius),
                  false);
    // The rate must stay below the threshold for Equilibrium time (from the step whose start it
    // first held at): one slow step after a change of a parameter is not yet a plateau.
    // It is the physical step's rate, the one the step control judges (step_acceptance.cc): with
    // Mesh motion = ale the smoothing's change of the discrete energy (mesh_motion_energy) is a
    // discretization error, and on a fine mesh the fixed weight per step takes more steps to bring
    // the mesh to its fixed point than the shape takes to settle; with the Lagrangian mesh the
    // physical step is the whole step (physical_energy = F^{m+1}, no area work).
    const double physical_change = std::abs(dissipation) / std::max(std::abs(energy_before), 1e-300);
    if (parameters.equilibrium_rate > 0 && physical_change / trial < parameters.equilibrium_rate)
      {
        if (plateau_since < 0)
          plateau_since = time - trial;
        if (time - plateau_since >= parameters.equilibrium_time * (1 - 1e-12))
          return stop("equilibrium: relative energy rate " + format(physical_change / trial) + " < " +
                        format(parameters.equilibrium_rate) +
                        (parameters.equilibrium_time > 0 ? " for " + format(time - plateau_since) : std::string()),
                      false);
      }
    else
      plateau_since = -1;
    return true;
  }

  RunResult Simulator::finish()
  {
    if (finished_run)
      return run_result;
    finished_run = true;
    if (!loop_stopped) // finished by the caller before a stop rule applied
      run_result = {"finished by the caller at t = " + format(time), false, ""};
    loop_stopped = true;
    write_fields();
    if (parameters.checkpoint_interval > 0 || interrupted)
      write_checkpoint();
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      stats.write(parameters.output_directory + "/statistics.txt");
    RunResult &result = run_result;
    result.outcome = classify_outcome(bud, parameters.outcome, result.stop_reason.rfind("pinch-off", 0) == 0);
    write_summary(result, earlier_wall_seconds + wall.wall_time());
    pcout << "Stopped (" << result.stop_reason << ") after " << step << " steps (" << rejected_steps
          << " rejected) at t = " << time << "; outcome: " << result.outcome << "; energy " << stats.last("energy")
          << ", mass drift " << stats.last("mass_drift") << ", area drift " << stats.last("area_drift")
          << "\nResults: " << parameters.output_directory << "/surface.pvd, statistics.txt, summary.json, parameters.prm\n";
    if (irreducible_error_steps > 0)
      pcout << "Note: " << irreducible_error_steps << " steps were accepted with an error estimate above <Time "
            << "stepping/Accuracy tolerance> that did not fall with tau (a stiff part of the step: the finest modes of a "
            << "random initial mixture, or a bud the mesh barely resolves; see docs/model.md, time steps); tau was "
            << "held there.\n";
    if (!options.quiet)
      timer.print_wall_time_statistics(communicator);
    return result;
  }

  bool Simulator::end_time_reached() const
  {
    return time >= parameters.end_time * (1 - 1e-12);
  }

  Simulator::Rejection Simulator::try_step(const double tau_trial)
  {
    // One trial step m -> m+1 from the state it restores when rejected.
    const State  before          = save_state();
    const double pressure_before = volume_pressure;
    const double energy_before   = before.energy.total();
    grid_move_skipped            = false;
    trial_end_time               = time + tau_trial;
    step_increment               = surface.vector_space().make_owned();
    max_increment                = 0;
    remap_correction             = 0;
    step_pressure_work           = 0;
    step_area_work               = 0;
    mesh_motion_energy           = 0;
    Rejection why;
    try
      {
        // 1. Cahn-Hilliard on Gamma^m: phi^m -> (phi~, Y)                    (phase_step.cc)
        Vector phi_new = surface.scalar_space().make_owned();
        if (!phase_step(tau_trial, phi_new))
          why = {"non_finite", "phi became non-finite or |phi| > 10"};
        else if (parameters.evolve_shape)
          {
            // 2. shape: X~ = X^m + W, with gamma and the volume pressure     (shape_step.cc)
            // 3. area and volume restoration, integral phi ds restored       (constraint_restoration.cc)
            const double volume_before = volume_constrained() ? enclosed_volume(surface) : 0;
            const Vector areas_before  = vertex_areas(surface);
            const Vector target        = area_target(tau_trial, areas_before);
            Vector       gamma;
            const bool   ale = parameters.mesh_motion == MeshMotion::ale;
            // The ALE scheme's tangential noise: its irrotational part in the shape step, its
            // solenoidal part in the lipids' transport (physics/tangential_noise.h).
            split_noise = ale && parameters.thermal.active();
            if (split_noise)
              tangential_noise = split_tangential_noise(surface, geometry.normal, noise_of_step(),
                                                        tau_trial * parameters.material.shape_mobility);
            // The ALE scheme restores nothing on the material configuration X~, which it never
            // builds as a mesh: the constraints hold on the moved mesh (grid_control_step.cc).
            if (!shape_step(tau_trial, areas_before, target, gamma) ||
                !(ale ? restore_material_areas(tau_trial, target, gamma, before.displacement) :
                        restore_areas_and_volume(tau_trial, target, gamma)))
              why = {"non_finite", "the shape solve gave non-finite values"};
            else if (ale)
              {
                pressure = gamma;
                phi      = phi_new; // integral phi ds of Gamma^m, carried exactly by the transport
                step_area_work = area_work_of_step(target, areas_before);
                move_mesh(tau_trial, before);
                step_pressure_work = pressure_work_of_step(volume_before, pressure_before);
              }
            else
              {
                restore_mass(phi_new);
                step_pressure_work = pressure_work_of_step(volume_before, pressure_before);
              }
          }
        else
          phi = phi_new;
        // 4. grid control with the ALE remap of phi, or the ALE mesh motion; geometry and F^{m+1}
        //                                                                     (grid_control_step.cc)
        if (why.empty())
          {
            if (!(parameters.evolve_shape && parameters.mesh_motion == MeshMotion::ale))
              {
                control_grid(energy_before + step_pressure_work, tau_trial);
                physical_energy = energy.total();
              }
            cell_quality = min_corner_sine(surface, geometry.normal);
          }
      }
    catch (const std::exception &)
      {
        why = {"solver_failure", "a linear solve failed"};
      }
    // 5. acceptance                                                          (step_acceptance.cc)
    if (why.empty())
      why = judge_step(tau_trial, energy_before);
    if (!why.empty())
      {
        restore_state(before);
        volume_pressure = pressure_before;
      }
    return why;
  }


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
} // namespace Membrane
