#include <membrane/io/atomic_file.h>
#include <membrane/io/checkpoint.h>
#include <membrane/io/field_output.h>
#include <membrane/io/log_file.h>
#include <membrane/io/stop_signal.h>
#include <membrane/simulator.h>
#include <membrane/solvers/vector_access.h>
#include <membrane/surface/adaptivity.h>
#include <membrane/surface/closed_surfaces.h>
#include <membrane/surface/grid_control.h>
#include <membrane/surface/initial_shapes.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <iomanip>
#include <sstream>

namespace Membrane
{
  using namespace dealii;

  std::string Simulator::format(const double value)
  {
    std::ostringstream out;
    out << std::setprecision(4) << value;
    return out.str();
  }

  Simulator::Simulator(const Parameters &parameters, RunOptions options, MPI_Comm communicator)
    : parameters(parameters)
    , options(std::move(options))
    , communicator(communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    , timer(communicator, pcout, TimerOutput::never, TimerOutput::wall_times)
    , triangulation(communicator)
    , surface(triangulation, !parameters.reference.closed())
    , cahn_hilliard(triangulation, !parameters.reference.closed())
    , shape_solver(triangulation, !parameters.reference.closed(), parameters.shape_options.curvature_mass)
    , step_control({parameters.adaptive, parameters.min_time_step, parameters.max_time_step, parameters.growth_factor,
                    parameters.accuracy_tolerance},
                   parameters.time_step)
  {}

  Simulator::~Simulator() = default;

  void Simulator::setup()
  {
    TimerOutput::Scope scope(timer, "setup");
    make_reference_surface();
    if (!parameters.resume_from.empty())
      refine_like_checkpoint(parameters.resume_from, triangulation, parameters.cells_per_side,
                             base_level + parameters.adaptivity.max_level);
    surface.setup();
    cahn_hilliard.setup();
    if (parameters.evolve_shape)
      shape_solver.setup();
    tangential_corrector.reset();
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      {
        std::filesystem::create_directories(parameters.output_directory);
        log = std::make_unique<LogFile>(parameters.output_directory + "/log.txt");
      }
    MPI_Barrier(communicator);
    output = std::make_unique<FieldOutput>(parameters.output_directory);
  }

  void Simulator::set_initial_state()
  {
    TimerOutput::Scope scope(timer, "initial state");
    if (parameters.shape == "bump")
      {
        const double a1 = set_bump(surface, parameters.bump_radius, parameters.bump_area);
        pcout << "Bump amplitude a1 = " << a1 << " for area " << parameters.bump_area << '\n';
      }
    else if (parameters.shape == "cosine modes")
      set_cosine_modes(surface, parse_cosine_modes(parameters.cosine_modes, "Initial shape/Cosine modes"));
    else if (parameters.shape == "expression")
      set_displacement_expression(surface, parameters.displacement_expression, "Initial shape/Displacement expression");
    if (closed())
      set_analytic_displacement(surface, parameters.reference); // refined initial meshes: onto the sphere/ellipsoid

    phi                = surface.scalar_space().ghosted_copy(make_initial_phase(surface, parameters.initial_phase));
    chemical_potential = surface.scalar_space().make_ghosted();
    pressure           = surface.scalar_space().make_ghosted();
    geometry           = compute_geometry(surface);
    energy             = compute_energy(surface, geometry, phi, parameters.material);
    initial_mass       = integrate(surface, phi);
    initial_area       = surface.area();
    initial_volume     = closed() ? enclosed_volume(surface) : 0.0;
    reference_areas    = vertex_areas(surface);
    step_control.set_tau(parameters.time_step);
    cell_quality       = min_corner_sine(surface, geometry.normal);
  }

  void Simulator::resume()
  {
    TimerOutput::Scope scope(timer, "initial state");
    Vector      displacement = surface.vector_space().make_owned();
    Vector      phi_owned    = surface.scalar_space().make_owned();
    std::string statistics_text;
    reference_areas     = surface.scalar_space().make_owned();
    StepIncrements increments{surface.vector_space().make_owned(), surface.scalar_space().make_owned()};
    const auto  scalars = load_checkpoint(parameters.resume_from, surface, displacement, phi_owned, reference_areas,
                                          statistics_text, &increments);
    surface.set_displacement(displacement);
    if (reference_areas.linfty_norm() == 0) // a checkpoint of format 1
      reference_areas = vertex_areas(surface);
    phi                = surface.scalar_space().ghosted_copy(phi_owned);
    chemical_potential = surface.scalar_space().make_ghosted();
    pressure           = surface.scalar_space().make_ghosted();
    geometry           = compute_geometry(surface);
    energy             = compute_energy(surface, geometry, phi, parameters.material);
    time               = scalars.at("time");
    // A resumed run continues with its step size, within the bounds it is given now
    // (a fixed-step run takes its Time step).
    step_control.set_tau(parameters.adaptive ? std::clamp(scalars.at("tau"), parameters.min_time_step,
                                                          parameters.max_time_step)
                                             : parameters.time_step);
    step               = static_cast<unsigned int>(scalars.at("step"));
    rejected_steps     = static_cast<unsigned int>(scalars.at("rejected_steps"));
    grid_control_skipped = static_cast<unsigned int>(scalars.at("grid_control_skipped"));
    if (scalars.count("irreducible_error_steps")) // absent in older checkpoints
      irreducible_error_steps = static_cast<unsigned int>(scalars.at("irreducible_error_steps"));
    // The accuracy control continues as if uninterrupted: the last step's increments and the
    // last rejection for the local error (older checkpoints: the first step has no estimate).
    if (scalars.count("previous_tau") && scalars.at("previous_tau") > 0)
      {
        previous_tau        = scalars.at("previous_tau");
        previous_increment  = increments.shape;
        previous_phi_change = increments.phi;
      }
    if (scalars.count("error_rejection_tau"))
      step_control.note_error_rejection(scalars.at("error_rejection_tau"), scalars.at("error_rejection_estimate"));
    // The stall detector judges the last 20 attempts, also across a resume (older checkpoints:
    // it starts afresh).
    if (scalars.count("recent_attempts"))
      step_control.restore_attempt_history(
        {static_cast<unsigned int>(std::clamp(scalars.at("recent_attempts"), 0.0, 20.0)),
         static_cast<unsigned int>(std::clamp(scalars.at("recent_rejections"), 0.0, double((1U << 20) - 1)))});
    for (const char *kind : rejection_kinds) // absent in checkpoints written before the count by kind
      if (scalars.count(std::string("rejected_") + kind))
        rejections[kind] = static_cast<unsigned int>(scalars.at(std::string("rejected_") + kind));
    initial_area       = scalars.at("initial_area");
    initial_mass       = scalars.at("initial_mass");
    if (scalars.count("initial_volume"))
      initial_volume = scalars.at("initial_volume");
    next_output_time   = scalars.at("next_output_time");
    if (scalars.count("wall_seconds"))
      earlier_wall_seconds = scalars.at("wall_seconds"); // the run's wall time counts all its segments
    if (scalars.count("shape_factorizations")) // so does its count of factorizations
      shape_solver.resume_factorization_count(static_cast<unsigned int>(scalars.at("shape_factorizations")));
    if (scalars.count("pressure_work"))
      {
        pressure_work   = scalars.at("pressure_work");
        volume_pressure = scalars.at("volume_pressure");
      }
    if (scalars.count("adaptations"))
      {
        adaptations            = static_cast<unsigned int>(scalars.at("adaptations"));
        adaptation_energy_jump = scalars.at("adaptation_energy_jump");
      }
    stats              = Statistics::from_text(statistics_text);
    cell_quality       = min_corner_sine(surface, geometry.normal);
    output->resume(time, parameters.resume_from);
    pcout << "Resumed from " << parameters.resume_from << " at step " << step << ", t = " << time << '\n';
    // A continuation with changed parameters is legitimate (e.g. a line-tension
    // branch); it is said and recorded in run_info.json.
    for (const auto &change : changed_parameters(checkpoint_parameters(parameters.resume_from), options.parameter_text))
      if (change.rfind("Checkpoint/Resume from", 0) != 0)
        changed_on_resume.push_back(change);
    if (!changed_on_resume.empty())
      {
        pcout << "Resumed with changed parameters:";
        for (const auto &change : changed_on_resume)
          pcout << "\n  " << change;
        pcout << '\n';
      }
  }

  void Simulator::warn_if_unresolved() const
  {
    // The diffuse interface phi = tanh(3 s / (4 xi)) spans about 3.9 xi between
    // phi = -0.9 and 0.9; h <= 1.25 xi puts about 3 cells across it. h is
    // measured on the current surface, where the interface is (everywhere if none).
    // With local refinement, the size the interface cells reach as the interface sharpens
    // (the smooth bump start is refined only then).
    const AdaptivityOptions &adaptivity = parameters.adaptivity;
    const double             xi         = parameters.material.transition_length;
    const double             interface  = interface_cell_size(surface, phi, xi, adaptivity, base_level);
    // A phi that is uniform stays uniform in the deterministic flow: no interface will need the mesh.
    const auto [phi_min, phi_max] = global_range(phi);
    if (interface == 0 && !parameters.thermal.active() && phi_max == phi_min)
      return;
    const double h = interface > 0 ? interface : surface.max_cell_diameter() / std::sqrt(2.0);
    if (h <= 1.25 * xi)
      return;
    pcout << "Warning: cell size h = " << h
          << (interface > 0 ? (adaptivity.enabled() ? " at the interface once refined" : " at the interface") : "")
          << " exceeds 1.25 x the transition length xi = " << xi << " (h/xi = " << h / xi
          << "); the diffuse interface (width ~3.9 xi between phi = -0.9 and 0.9) is under-resolved. ";
    const double factor = h / (1.25 * xi);
    if (adaptivity.enabled() && xi / adaptivity.interface_cells_per_xi > 1.25 * xi)
      pcout << "Raise <Mesh/Interface cells per xi> to at least 0.8.\n";
    else if (parameters.adaptivity.enabled())
      pcout << "Raise <Mesh/Maximum refinement level> above " << parameters.adaptivity.max_level
            << " or <Mesh/Cells per side> to at least " << std::ceil(parameters.cells_per_side * factor) << ".\n";
    else
      pcout << "Increase <Mesh/Cells per side> to at least " << std::ceil(parameters.cells_per_side * factor)
            << ", or refine locally with <Mesh/Maximum refinement level>.\n";
  }

  RunResult Simulator::run()
  {
    initialize();
    while (advance())
      ;
    return finish();
  }

  void Simulator::write_fields()
  {
    if (!parameters.write_vtu || last_written == step)
      return;
    last_written = step;
    TimerOutput::Scope scope(timer, "output");
    // The local area error a_i / a_ref,i - 1 of every vertex (statistics.txt has its maximum).
    const Vector areas      = vertex_areas(surface);
    Vector       area_error = surface.scalar_space().make_owned();
    {
      const LocalValues area(areas), reference(reference_areas);
      OwnedValues       error(area_error);
      for (const auto i : area_error.locally_owned_elements())
        error[i] = reference[i] > 0 ? area[i] / reference[i] - 1 : 0.0;
    }
    area_error.compress(VectorOperation::insert);
    surface.scalar_space().constraints().distribute(area_error);
    const Vector area_error_ghosted = surface.scalar_space().ghosted_copy(area_error);
    output->write(surface, geometry,
                  {{"phi", &phi}, {"Y", &chemical_potential}, {"gamma", &pressure}, {"area_error", &area_error_ghosted}},
                  time, step);
  }

  std::string Simulator::curvature_resolution_note() const
  {
    // Energy rises that do not shrink with tau: on a mesh too coarse for the curvature
    // the discrete shape velocity is no longer a descent direction of the discrete
    // energy (docs/reliability.md). Say so when the mesh is that coarse.
    const double arc   = largest_curvature_per_cell(triangulation, surface, geometry);
    const double bound = 2 * parameters.adaptivity.curvature_resolution;
    if (arc <= bound)
      return "";
    return "; the mesh does not resolve the curvature (the most bent cell spans " + format(arc) +
           " rad of arc, more than 2 x <Mesh/Curvature resolution> = " + format(bound) +
           "), where the discrete shape step stops being a descent step of the discrete energy: refine with "
           "<Mesh/Maximum refinement level> or <Mesh/Cells per side>";
  }

  std::string Simulator::line_stiffness_note(const Rejection &last, const double tau) const
  {
    // The explicit phase force Y grad phi overshoots on interface-scale tangential modes once
    // tau L_X sigma / h^2 is O(1) (docs/model.md); the implicit line stiffness removes that limit.
    const Material &material = parameters.material;
    if (!parameters.evolve_shape || last.kind != "energy_rise" || parameters.shape_options.line_stiffness > 0 ||
        material.line_tension <= 0)
      return "";
    const double h     = reference_cell_size();
    const double limit = h * h / (material.shape_mobility * material.line_tension);
    if (tau > 10 * limit)
      return "";
    // The stiffness is sigma xi^2 |grad_s phi|^2: without an interface (phi uniform, or a
    // broad profile that has not sharpened) there is none, and the rise has another cause.
    if (largest_relative_steepness(surface, phi, material.transition_length) < 0.5)
      return "";
    return "; tau is within 10x of the explicit limit of the phase force, h^2 / (L_X sigma) = " + format(limit) +
           " for the finest cells: if the energy rises at the phase interface, <Shape/Line stiffness> = 1 lifts "
           "that limit (docs/model.md)";
  }

  bool Simulator::end_time_reached() const
  {
    return time >= parameters.end_time * (1 - 1e-12);
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
    write_run_info();
    pcout << (closed() ? "Vesicle (" + parameters.reference.type + "): " : std::string("Membrane patch: "))
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
      bud = closed() ? measure_vesicle_bud() : measure_bud(surface, phi);
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
                                             : "; reduce <Time stepping/Time step> or set Adaptive = true") +
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
    if (parameters.equilibrium_rate > 0 && change / trial < parameters.equilibrium_rate)
      {
        if (plateau_since < 0)
          plateau_since = time - trial;
        if (time - plateau_since >= parameters.equilibrium_time * (1 - 1e-12))
          return stop("equilibrium: relative energy rate " + format(change / trial) + " < " +
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
} // namespace Membrane
