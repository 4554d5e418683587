#include <membrane/io/atomic_file.h>
#include <membrane/io/checkpoint.h>
#include <membrane/io/field_output.h>
#include <membrane/io/log_file.h>
#include <membrane/simulator.h>
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

  namespace
  {
    std::string format(const double value)
    {
      std::ostringstream out;
      out << std::setprecision(4) << value;
      return out.str();
    }
  } // namespace

  Simulator::Simulator(const Parameters &parameters, RunOptions options, MPI_Comm communicator)
    : parameters(parameters)
    , options(std::move(options))
    , communicator(communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    , timer(communicator, pcout, TimerOutput::never, TimerOutput::wall_times)
    , triangulation(communicator)
    , surface(triangulation, true)
    , cahn_hilliard(triangulation, true)
    , shape_solver(triangulation, true)
    , step_control({parameters.adaptive, parameters.min_time_step, parameters.max_time_step, parameters.growth_factor,
                    parameters.accuracy_tolerance},
                   parameters.time_step)
  {}

  Simulator::~Simulator() = default;

  void Simulator::setup()
  {
    TimerOutput::Scope scope(timer, "setup");
    make_periodic_unit_square(triangulation, parameters.cells_per_side);
    base_level = factor_cells_per_side(parameters.cells_per_side).second;
    if (!parameters.resume_from.empty())
      refine_like_checkpoint(parameters.resume_from, triangulation, parameters.cells_per_side,
                             base_level + parameters.adaptivity.max_level);
    surface.setup();
    cahn_hilliard.setup();
    if (parameters.evolve_shape)
      shape_solver.setup();
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

    phi                = surface.scalar_space().ghosted_copy(make_initial_phase(surface, parameters.initial_phase));
    chemical_potential = surface.scalar_space().make_ghosted();
    pressure           = surface.scalar_space().make_ghosted();
    geometry           = compute_geometry(surface);
    energy             = compute_energy(surface, geometry, phi, parameters.material);
    initial_mass       = integrate(surface, phi);
    initial_area       = surface.area();
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
    const auto  scalars = load_checkpoint(parameters.resume_from, surface, displacement, phi_owned, reference_areas,
                                          statistics_text);
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
    initial_area       = scalars.at("initial_area");
    initial_mass       = scalars.at("initial_mass");
    next_output_time   = scalars.at("next_output_time");
    if (scalars.count("wall_seconds"))
      earlier_wall_seconds = scalars.at("wall_seconds"); // the run's wall time counts all its segments
    if (scalars.count("adaptations"))
      {
        adaptations            = static_cast<unsigned int>(scalars.at("adaptations"));
        adaptation_energy_jump = scalars.at("adaptation_energy_jump");
      }
    stats              = Statistics::from_text(statistics_text);
    cell_quality       = min_corner_sine(surface, geometry.normal);
    output->resume(time);
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
    // The diffuse interface phi = tanh(1.06 s / xi) spans about 2.8 xi between
    // phi = -0.9 and 0.9; it needs h <= 1.25 xi to be seen by >= 2 cells. h is
    // measured on the current surface, where the interface is (everywhere if none).
    const double xi        = parameters.material.transition_length;
    const double interface = interface_cell_size(surface, phi, parameters.adaptivity.interface_phi);
    const double h         = interface > 0 ? interface : surface.max_cell_diameter() / std::sqrt(2.0);
    if (h <= 1.25 * xi)
      return;
    pcout << "Warning: cell size h = " << h << (interface > 0 ? " at the interface" : "")
          << " exceeds 1.25 x the transition length xi = " << xi << " (h/xi = " << h / xi
          << "); the diffuse interface (width ~2.8 xi) is under-resolved. ";
    const double factor = h / (1.25 * xi);
    if (parameters.adaptivity.enabled() && finest_level() < parameters.adaptivity.max_level)
      pcout << "Raise <Mesh/Interface cells per xi> to at least "
            << std::ceil(10 * parameters.adaptivity.interface_cells_per_xi * factor) / 10 << ".\n";
    else if (parameters.adaptivity.enabled())
      pcout << "Raise <Mesh/Maximum refinement level> above " << parameters.adaptivity.max_level
            << " or <Mesh/Cells per side> to at least " << std::ceil(parameters.cells_per_side * factor) << ".\n";
    else
      pcout << "Increase <Mesh/Cells per side> to at least " << std::ceil(parameters.cells_per_side * factor)
            << ", or refine locally with <Mesh/Maximum refinement level>.\n";
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

  Vector Simulator::area_defect() const
  {
    Vector defect = surface.scalar_space().make_owned();
    if (parameters.shape_options.correct_area)
      {
        defect = reference_areas;
        defect -= vertex_areas(surface);
      }
    return defect;
  }

  bool Simulator::move_shape(const double tau_trial, const Vector &phi_new)
  {
    const ShapeOptions &options = parameters.shape_options;
    ShapeUpdate update = shape_solver.step(surface, geometry, parameters.material, options, parameters.linear_solver,
                                           tau_trial, area_defect(), phi, chemical_potential, &timer);
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
    // The linearized constraint leaves an O(|grad W|^2) area error in every step.
    // Projecting it out within the step (same operator, one back-substitution)
    // keeps it from being corrected by the next step, whatever its tau.
    area_projections = 0;
    if (options.correct_area)
      {
        TimerOutput::Scope scope(timer, "area projection");
        for (unsigned int k = 0; k < options.area_corrections; ++k)
          {
            const Vector defect = area_defect();
            Vector       areas  = reference_areas;
            areas -= defect;
            if (max_relative_difference(areas, reference_areas) <= options.area_tolerance)
              break;
            const ShapeUpdate correction = shape_solver.correct_area(surface, defect, &timer);
            if (!apply(correction))
              return false;
            gamma += correction.pressure;
            step_increment += correction.increment;
            ++area_projections;
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

  void Simulator::control_grid(const double energy_before)
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
      const Vector normal = surface.vector_space().ghosted_copy(compute_vertex_normals(surface));
      const Vector shift  = grid_control_displacement(surface, normal, parameters.grid_control_weight);
      const Vector areas_before = vertex_areas(surface);
      remap_correction = move_tangentially_and_remap(surface, shift, phi);
      // The reference area moves with the vertices, each keeping its relative error;
      // the total reference area is kept exactly.
      Vector carried = vertex_areas(surface);
      for (const auto i : carried.locally_owned_elements())
        if (areas_before[i] > 0)
          carried[i] = carried[i] * (reference_areas[i] / areas_before[i]);
      carried.compress(VectorOperation::insert);
      const double total = carried.mean_value() * carried.size();
      if (total > 0)
        carried *= initial_area / total;
      reference_areas = carried;
    }
    update_geometry();
    if (std::isfinite(energy.total()) &&
        energy.total() <= energy_before + parameters.energy_tolerance * std::abs(energy_before))
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
    const auto      restore  = [&](const Rejection &why) {
      restore_state(before);
      return why;
    };
    grid_move_skipped = false;

    Vector phi_new   = surface.scalar_space().make_owned();
    Vector potential = surface.scalar_space().make_owned();
    try
      {
        solver_iterations = cahn_hilliard.step(surface, geometry, material, parameters.cahn_hilliard,
                                               parameters.linear_solver, tau_trial, phi, phi_new, potential, &timer);
        if (!std::isfinite(phi_new.l2_norm()) || phi_new.linfty_norm() > 10)
          return restore("phi became non-finite or |phi| > 10");
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
        if (parameters.evolve_shape)
          {
            if (!move_shape(tau_trial, phi_new))
              return restore("the shape solve gave non-finite values");
          }
        else
          phi = phi_new;
        control_grid(before.energy.total());
        cell_quality = min_corner_sine(surface, geometry.normal);
      }
    catch (const std::exception &)
      {
        return restore("a linear solve failed");
      }

    if (!std::isfinite(energy.total()))
      return restore("the energy became non-finite");
    if (parameters.evolve_shape && cell_quality < parameters.min_cell_quality)
      return restore("a cell degenerated (corner sine " + format(cell_quality) + " < " +
                     format(parameters.min_cell_quality) + ")");
    const double rise = energy.total() - before.energy.total();
    if (rise > parameters.energy_tolerance * std::max(std::abs(before.energy.total()), 1e-300))
      return restore("the energy would rise by " + format(rise));
    error_estimate = step_control.controls_accuracy() && previous_tau > 0 ? estimate_error(tau_trial) : -1;
    if (error_estimate > 1)
      {
        rejection_factor = TimeStepController::shrink_factor(error_estimate);
        return restore("the estimated local error is " + format(error_estimate) +
                       " x <Time stepping/Accuracy tolerance>");
      }
    return {};
  }

  double Simulator::estimate_error(const double tau) const
  {
    // First-order steps: the local error is about half the change of the increment
    // against the previous velocity, tau^2/2 |dV/dt|. Shape in cells, phi absolute.
    const double ratio     = tau / previous_tau;
    const double cell_size = 1.0 / (parameters.cells_per_side << finest_level());
    Vector       shape     = step_increment;
    shape.add(-ratio, previous_increment);
    Vector phase = step_phi_change;
    phase.add(-ratio, previous_phi_change);
    return 0.5 * std::max(shape.linfty_norm() / cell_size, phase.linfty_norm()) / step_control.accuracy();
  }

  void Simulator::record_statistics(const double tau_used)
  {
    TimerOutput::Scope scope(timer, "statistics");
    const double area = surface.area();
    const double mass = integrate(surface, phi);
    area_error        = max_relative_difference(vertex_areas(surface), reference_areas);
    bud               = measure_bud(surface, phi);
    stats.set("step", step);
    stats.set("time", time);
    stats.set("tau", tau_used);
    stats.set("energy", energy.total());
    stats.set("bending_energy", energy.bending);
    stats.set("gaussian_energy", energy.gaussian);
    stats.set("gradient_energy", energy.gradient);
    stats.set("well_energy", energy.well);
    stats.set("area", area);
    stats.set("area_drift", (area - initial_area) / initial_area);
    stats.set("mass", mass);
    stats.set("mass_drift", (mass - initial_mass) / std::max(std::abs(initial_mass), initial_area));
    const auto [phi_min, phi_max] = global_range(phi);
    stats.set("phi_min", phi_min);
    stats.set("phi_max", phi_max);
    const auto [gamma_min, gamma_max] = global_range(pressure);
    stats.set("gamma_min", gamma_min);
    stats.set("gamma_max", gamma_max);
    stats.set("bud_height", bud.height);
    stats.set("neck_radius", bud.neck_radius);
    stats.set("bud_radius", bud.bud_radius);
    stats.set("neck_ratio", bud.neck_ratio);
    stats.set("domain_area", bud.domain_area);
    stats.set("domain_protrusion", bud.domain_protrusion);
    stats.set("bud_direction", bud.direction);
    stats.set("max_increment", max_increment);
    stats.set("remap_mass_correction", remap_correction);
    stats.set("min_corner_sine", cell_quality);
    stats.set("rejected_steps", rejected_steps);
    stats.set("grid_control_skipped", grid_control_skipped);
    stats.set("area_error", area_error);
    stats.set("shape_mass_correction", shape_mass_correction);
    stats.set("error_estimate", error_estimate);
    stats.set("area_projections", area_projections);
    stats.set("solver_iterations", solver_iterations);
    stats.set("cells", triangulation.n_global_active_cells());
    stats.set("dofs", surface.scalar_space().dof_handler().n_dofs());
    stats.set("refinement_level", finest_level());
    stats.set("adaptations", adaptations);
    stats.set("adaptation_energy_jump", adaptation_energy_jump);
    stats.set("wall_seconds", earlier_wall_seconds + wall.wall_time());
    stats.end_row();
  }

  void Simulator::report_progress(const bool force)
  {
    const double now = wall.wall_time();
    if (options.quiet || (!force && now - last_progress < 1.0))
      return;
    last_progress = now;
    // Remaining wall time from the rate of this segment of the run.
    const double done = parameters.end_time > 0 ? time / parameters.end_time : 1.0;
    const double rate = (time - segment_start_time) / std::max(now, 1e-9);
    std::ostringstream line; // its own formatting state, not the terminal's
    line << "step " << std::setw(6) << step << "  t = " << std::scientific << std::setprecision(4) << time
         << std::defaultfloat << " (" << std::fixed << std::setprecision(1) << 100 * done << " %)"
         << std::scientific << "  tau = " << std::setprecision(2) << stats.last("tau") << "  F = "
         << std::setprecision(6) << stats.last("energy") << std::defaultfloat << std::setprecision(3)
         << "  bud height " << bud.height << "  neck " << bud.neck_radius << "  rejected " << rejected_steps
         << "  elapsed " << now << " s";
    if (rate > 0 && done < 1)
      line << ", ETA " << (parameters.end_time - time) / rate << " s";
    pcout << line.str() << std::endl;
  }

  void Simulator::write_checkpoint() const
  {
    TimerOutput::Scope scope(timer, "checkpoint");
    save_checkpoint(parameters.output_directory + "/checkpoint.txt", surface, phi, reference_areas,
                    {{"time", time},
                     {"tau", step_control.tau()},
                     {"step", step},
                     {"rejected_steps", rejected_steps},
                     {"grid_control_skipped", grid_control_skipped},
                     {"initial_area", initial_area},
                     {"initial_mass", initial_mass},
                     {"next_output_time", next_output_time},
                     {"adaptations", adaptations},
                     {"cells_per_side", parameters.cells_per_side},
                     {"wall_seconds", earlier_wall_seconds + wall.wall_time()},
                     {"adaptation_energy_jump", adaptation_energy_jump}},
                    stats.to_text(), options.parameter_text);
  }

  void Simulator::write_run_info() const
  {
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return;
    const std::string dir = parameters.output_directory + "/";
    write_file_atomically(dir + "parameters.prm", options.parameter_text);
    std::ostringstream info;
    info << "{\n  \"code_version\": \"" << code_version() << "\",\n"
         << "  \"command\": \"" << options.command_line << "\",\n"
         << "  \"mpi_ranks\": " << Utilities::MPI::n_mpi_processes(communicator) << ",\n"
         << "  \"cells\": " << triangulation.n_global_active_cells() << ",\n"
         << "  \"vertices_dofs\": " << surface.scalar_space().dof_handler().n_dofs() << ",\n"
         << "  \"parameter_file\": \"parameters.prm\"\n}\n";
    write_file_atomically(dir + "run_info.json", info.str());
  }

  void Simulator::write_summary(const RunResult &result, const double wall_seconds) const
  {
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return;
    std::ostringstream out;
    out << std::setprecision(16) << "{\n  \"code_version\": \"" << code_version() << "\",\n"
        << "  \"stop_reason\": \"" << result.stop_reason << "\",\n  \"failed\": " << (result.failed ? "true" : "false")
        << ",\n  \"outcome\": \"" << result.outcome << "\",\n  \"steps\": " << step
        << ",\n  \"rejected_steps\": " << rejected_steps << ",\n  \"time\": " << time
        << ",\n  \"wall_seconds\": " << wall_seconds << ",\n  \"grid_control_refused_fraction\": "
        << (step > 0 ? double(grid_control_skipped) / step : 0.0);
    for (const char *c : {"energy", "bending_energy", "gaussian_energy", "gradient_energy", "well_energy", "area",
                          "area_drift", "mass", "mass_drift", "bud_height", "neck_radius", "bud_radius", "neck_ratio",
                          "domain_area", "domain_protrusion", "bud_direction", "min_corner_sine", "area_error", "cells",
                          "adaptations", "adaptation_energy_jump"})
      out << ",\n  \"" << c << "\": " << stats.last(c);
    out << "\n}\n";
    write_file_atomically(parameters.output_directory + "/summary.json", out.str());
  }

  RunResult Simulator::run()
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
    write_run_info();
    pcout << "Membrane patch: " << triangulation.n_global_active_cells() << " cells, "
          << surface.scalar_space().dof_handler().n_dofs() << " vertex DoFs, "
          << Utilities::MPI::n_mpi_processes(communicator) << " MPI rank(s); output in "
          << parameters.output_directory << "/\n";

    unsigned int last_written = std::numeric_limits<unsigned int>::max();
    const auto   write_fields = [&]() {
      if (!parameters.write_vtu || last_written == step)
        return;
      last_written = step;
      TimerOutput::Scope scope(timer, "output");
      output->write(surface, geometry, {{"phi", &phi}, {"Y", &chemical_potential}, {"gamma", &pressure}}, time, step);
    };
    const bool root = Utilities::MPI::this_mpi_process(communicator) == 0;
    if (parameters.resume_from.empty())
      {
        record_statistics(0);
        write_fields();
        next_output_time = parameters.output_interval;
      }
    else
      bud = measure_bud(surface, phi);

    RunResult  result{"end time", false, ""};
    const auto finished = [&]() { return time >= parameters.end_time * (1 - 1e-12); };
    while (!finished())
      {
        if (step >= parameters.max_steps)
          {
            result.stop_reason = "maximum steps";
            break;
          }
        const double    trial         = std::min(step_control.tau(), parameters.end_time - time);
        const double    energy_before = energy.total();
        rejection_factor              = 0.5;
        const Rejection why           = try_step(trial);
        if (!why.empty())
          {
            ++rejected_steps;
            if (!step_control.reject(trial, rejection_factor))
              {
                result.stop_reason = "step failed at t = " + format(time) + ": " + why +
                                     (parameters.adaptive ? "; tau fell below <Time stepping/Minimum time step>"
                                                          : "; reduce <Time stepping/Time step> or set Adaptive = true") +
                                     ". The last good state is kept";
                result.failed = true;
                break;
              }
            if (step_control.stalled())
              {
                // Steps keep failing at a tiny tau. With a complete bud this is the
                // approach to pinch-off (the neck is below what the mesh resolves).
                const bool budded = classify_outcome(bud, parameters.outcome, false) == "complete bud";
                result.stop_reason = std::string(budded ? "pinch-off approach" : "stalled") + " at t = " +
                                     format(time) + ": half of the last 20 steps were rejected (last: " + why +
                                     ") at tau = " + format(step_control.tau()) + ". The last good state is kept";
                result.failed = !budded;
                break;
              }
            continue;
          }
        time += trial;
        ++step;
        grid_control_skipped += grid_move_skipped;
        record_statistics(trial);
        const double change = std::abs(energy.total() - energy_before) / std::max(std::abs(energy_before), 1e-300);
        step_control.accept(trial, max_increment, 1.0 / (parameters.cells_per_side << finest_level()), change,
                            error_estimate);
        previous_increment  = step_increment;
        previous_phi_change = step_phi_change;
        previous_tau        = trial;
        if (parameters.adaptivity.enabled() && step % parameters.adaptivity.interval == 0 && adapt_mesh())
          previous_tau = 0; // the increments live on the old mesh

        const bool output_due = time >= next_output_time * (1 - 1e-12);
        if (output_due || finished())
          {
            write_fields();
            if (parameters.output_interval <= 0)
              next_output_time = time; // every step
            else
              while (next_output_time <= time * (1 + 1e-12))
                next_output_time += parameters.output_interval;
            if (root)
              stats.write(parameters.output_directory + "/statistics.txt");
          }
        if (parameters.checkpoint_interval > 0 && step % parameters.checkpoint_interval == 0)
          write_checkpoint();
        report_progress(finished());

        if (parameters.evolve_shape && bud.neck_ratio < parameters.outcome.complete_neck_ratio &&
            bud.neck_radius < parameters.pinch_off_radius)
          {
            result.stop_reason = "pinch-off approach: neck radius " + format(bud.neck_radius) + " < " +
                                 format(parameters.pinch_off_radius);
            break;
          }
        if (parameters.equilibrium_rate > 0 &&
            change / trial < parameters.equilibrium_rate)
          {
            result.stop_reason = "equilibrium: relative energy rate " + format(change / trial) + " < " +
                                 format(parameters.equilibrium_rate);
            break;
          }
      }
    write_fields();
    if (parameters.checkpoint_interval > 0)
      write_checkpoint();
    if (root)
      stats.write(parameters.output_directory + "/statistics.txt");
    result.outcome = classify_outcome(bud, parameters.outcome, result.stop_reason.rfind("pinch-off", 0) == 0);
    write_summary(result, earlier_wall_seconds + wall.wall_time());
    pcout << "Stopped (" << result.stop_reason << ") after " << step << " steps (" << rejected_steps
          << " rejected) at t = " << time << "; outcome: " << result.outcome << "; energy " << stats.last("energy")
          << ", mass drift " << stats.last("mass_drift") << ", area drift " << stats.last("area_drift")
          << "\nResults: " << parameters.output_directory << "/surface.pvd, statistics.txt, summary.json, parameters.prm\n";
    if (!options.quiet)
      timer.print_wall_time_statistics(communicator);
    return result;
  }
} // namespace Membrane
