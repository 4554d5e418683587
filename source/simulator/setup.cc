// Stage: set-up of a run. The reference surface (periodic patch or closed vesicle), the
// finite element spaces and solvers, the initial state, or the state of a checkpoint to
// resume from. Part of Simulator.
#include <membrane/io/checkpoint.h>
#include <membrane/io/field_output.h>
#include <membrane/io/log_file.h>
#include <membrane/simulator.h>
#include <membrane/surface/grid_control.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace Membrane
{
  using namespace dealii;

  Simulator::Simulator(const Parameters &parameters, RunOptions options, MPI_Comm communicator)
    : parameters(parameters)
    , options(std::move(options))
    , communicator(communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    , timer(communicator, pcout, TimerOutput::never, TimerOutput::wall_times)
    , topology(MembraneTopology::create(parameters.reference, parameters.cells_per_side))
    , triangulation(communicator)
    , surface(triangulation, topology->periodic())
    , cahn_hilliard(triangulation, topology->periodic())
    , shape_solver(triangulation, topology->periodic(), parameters.shape_options.curvature_mass)
    , step_control({parameters.adaptive, parameters.min_time_step, parameters.max_time_step, parameters.growth_factor,
                    parameters.accuracy_tolerance},
                   parameters.time_step)
  {}

  Simulator::~Simulator() = default;

  void Simulator::setup()
  {
    TimerOutput::Scope scope(timer, "setup");
    topology->make_mesh(triangulation);
    base_level = topology->base_level();
    if (!parameters.resume_from.empty())
      refine_like_checkpoint(parameters.resume_from, triangulation, parameters.cells_per_side,
                             base_level + parameters.adaptivity.max_level);
    setup_spaces_and_solvers();
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      {
        std::filesystem::create_directories(parameters.output_directory);
        log = std::make_unique<LogFile>(parameters.output_directory + "/log.txt");
      }
    MPI_Barrier(communicator);
    output = std::make_unique<FieldOutput>(parameters.output_directory);
  }

  void Simulator::setup_spaces_and_solvers()
  {
    surface.setup();
    cahn_hilliard.setup();
    if (parameters.evolve_shape)
      shape_solver.setup();
    tangential_corrector.reset();
  }

  void Simulator::set_initial_state()
  {
    TimerOutput::Scope scope(timer, "initial state");
    const std::string placed = topology->place_initial_surface(
      surface, {parameters.shape, parameters.bump_radius, parameters.bump_area, parameters.cosine_modes,
                parameters.displacement_expression});
    if (!placed.empty())
      pcout << placed << '\n';

    phi                = surface.scalar_space().ghosted_copy(make_initial_phase(surface, parameters.initial_phase));
    chemical_potential = surface.scalar_space().make_ghosted();
    pressure           = surface.scalar_space().make_ghosted();
    geometry           = compute_geometry(surface);
    energy             = compute_energy(surface, geometry, phi, parameters.material);
    initial_mass       = integrate(surface, phi);
    initial_area       = surface.area();
    initial_volume     = topology->enclosed_volume(surface);
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
    if (scalars.count("adaptation_energy_carried"))
      {
        adaptation_energy_carried = scalars.at("adaptation_energy_carried");
        carried_measured          = static_cast<unsigned int>(scalars.at("carried_measured"));
        twin_pending              = scalars.at("twin_pending") > 0;
        twin_tau                  = scalars.at("twin_tau");
        twin_energy               = scalars.at("twin_energy");
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
        // A pending twin step (Measure carried energy) ran under the checkpoint's parameters: with
        // another line tension its energy is not comparable with the next step's.
        twin_pending = false;
        pcout << "Resumed with changed parameters:";
        for (const auto &change : changed_on_resume)
          pcout << "\n  " << change;
        pcout << '\n';
      }
  }
} // namespace Membrane
