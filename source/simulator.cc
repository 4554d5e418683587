#include <membrane/io/atomic_file.h>
#include <membrane/io/field_output.h>
#include <membrane/physics/energy.h>
#include <membrane/simulator.h>
#include <membrane/surface/initial_shapes.h>

#include <deal.II/base/utilities.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace Membrane
{
  using namespace dealii;

  Simulator::Simulator(const Parameters &parameters, RunOptions options, MPI_Comm communicator)
    : parameters(parameters)
    , options(std::move(options))
    , communicator(communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    , timer(communicator, pcout, TimerOutput::never, TimerOutput::wall_times)
    , triangulation(communicator)
    , surface(triangulation, true)
    , cahn_hilliard(triangulation, true)
  {}

  Simulator::~Simulator() = default;

  void Simulator::setup()
  {
    TimerOutput::Scope scope(timer, "setup");
    make_periodic_unit_square(triangulation, parameters.cells_per_side);
    surface.setup();
    cahn_hilliard.setup();
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      std::filesystem::create_directories(parameters.output_directory);
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
    geometry           = compute_geometry(surface);
    initial_mass       = integrate(surface, phi);
    initial_area       = surface.area();
  }

  void Simulator::warn_if_unresolved() const
  {
    // The diffuse interface phi = tanh(1.06 s / xi) spans about 2.8 xi between
    // phi = -0.9 and 0.9; it needs h <= 1.25 xi to be seen by >= 2 cells.
    const double h  = surface.max_cell_diameter() / std::sqrt(2.0);
    const double xi = parameters.material.transition_length;
    if (h > 1.25 * xi)
      pcout << "Warning: cell size h = " << h << " exceeds 1.25 x the transition length xi = " << xi
            << " (h/xi = " << h / xi << "); the diffuse interface (width ~2.8 xi) is under-resolved. "
            << "Increase <Mesh/Cells per side> to at least " << std::ceil(1.0 / (1.25 * xi)) << ".\n";
  }

  bool Simulator::advance(const double tau)
  {
    Vector       phi_new = surface.scalar_space().make_owned();
    Vector       potential = surface.scalar_space().make_owned();
    unsigned int iterations = 0;
    Timer        solve_clock;
    {
      TimerOutput::Scope scope(timer, "Cahn-Hilliard step");
      iterations = cahn_hilliard.step(surface, geometry, parameters.material, parameters.cahn_hilliard,
                                      parameters.linear_solver, tau, phi, phi_new, potential);
    }
    const double solve_seconds = solve_clock.wall_time();
    if (!std::isfinite(phi_new.l2_norm()) || phi_new.linfty_norm() > 10)
      return false;
    phi                = phi_new;
    chemical_potential = potential;
    time += tau;
    ++step;
    record_statistics(tau, iterations, solve_seconds);
    return true;
  }

  void Simulator::record_statistics(const double tau, const unsigned int iterations, const double solve_seconds)
  {
    TimerOutput::Scope scope(timer, "statistics");
    const EnergyTerms energy = compute_energy(surface, geometry, phi, parameters.material);
    const double      area   = surface.area();
    const double      mass   = integrate(surface, phi);
    stats.set("step", step);
    stats.set("time", time);
    stats.set("tau", tau);
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
    stats.set("solver_iterations", iterations);
    stats.set("solve_seconds", solve_seconds);
    stats.set("wall_seconds", wall.wall_time());
    stats.end_row();
  }

  void Simulator::report_progress(const bool force)
  {
    const double now = wall.wall_time();
    if (options.quiet || (!force && now - last_progress < 1.0))
      return;
    last_progress = now;
    const double eta = time > 0 ? now * (parameters.end_time - time) / time : 0;
    pcout << "step " << std::setw(6) << step << "  t = " << std::scientific << std::setprecision(4) << time
          << "  tau = " << std::setprecision(2) << stats.last("tau") << "  F = " << std::setprecision(6)
          << stats.last("energy") << std::defaultfloat << std::setprecision(3) << "  elapsed " << now
          << " s  left ~" << eta << " s" << std::endl;
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

  void Simulator::write_summary(const std::string &stop_reason, const double wall_seconds) const
  {
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return;
    std::ostringstream out;
    out << std::setprecision(16) << "{\n  \"code_version\": \"" << code_version() << "\",\n"
        << "  \"stop_reason\": \"" << stop_reason << "\",\n  \"steps\": " << step << ",\n  \"time\": " << time
        << ",\n  \"wall_seconds\": " << wall_seconds;
    for (const char *c : {"energy", "bending_energy", "gaussian_energy", "gradient_energy", "well_energy", "area",
                          "area_drift", "mass", "mass_drift"})
      out << ",\n  \"" << c << "\": " << stats.last(c);
    out << "\n}\n";
    write_file_atomically(parameters.output_directory + "/summary.json", out.str());
  }

  std::string Simulator::run()
  {
    wall.restart();
    setup();
    set_initial_state();
    warn_if_unresolved();
    write_run_info();
    pcout << "Membrane patch: " << triangulation.n_global_active_cells() << " cells, "
          << surface.scalar_space().dof_handler().n_dofs() << " vertex DoFs, "
          << Utilities::MPI::n_mpi_processes(communicator) << " MPI rank(s); output in "
          << parameters.output_directory << "/\n";

    record_statistics(0, 0, 0);
    const auto write_fields = [&]() {
      if (!parameters.write_vtu)
        return;
      TimerOutput::Scope scope(timer, "output");
      output->write(surface, geometry, {{"phi", &phi}, {"Y", &chemical_potential}}, time, step);
    };
    write_fields();
    next_output_time = parameters.output_interval;

    std::string stop_reason = "end time";
    while (time < parameters.end_time * (1 - 1e-12))
      {
        if (step >= parameters.max_steps)
          {
            stop_reason = "maximum steps";
            break;
          }
        const double tau = std::min(parameters.time_step, parameters.end_time - time);
        if (!advance(tau))
          {
            stop_reason = "diverged at t = " + std::to_string(time) + ": phi became non-finite or |phi| > 10; "
                          "the last good state is kept (reduce <Time stepping/Time step>)";
            break;
          }
        const bool last = time >= parameters.end_time * (1 - 1e-12);
        if (time >= next_output_time * (1 - 1e-12) || last)
          {
            write_fields();
            while (next_output_time <= time * (1 + 1e-12))
              next_output_time += std::max(parameters.output_interval, 1e-300);
            if (Utilities::MPI::this_mpi_process(communicator) == 0)
              stats.write(parameters.output_directory + "/statistics.txt");
          }
        report_progress(last);
      }
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      stats.write(parameters.output_directory + "/statistics.txt");
    write_summary(stop_reason, wall.wall_time());
    pcout << "Stopped (" << stop_reason << ") after " << step << " steps at t = " << time << "; "
          << "energy " << stats.last("energy") << ", mass drift " << stats.last("mass_drift") << ", area drift "
          << stats.last("area_drift") << "\nResults: " << parameters.output_directory << "/surface.pvd, "
          << "statistics.txt, summary.json, parameters.prm\n";
    if (!options.quiet)
      timer.print_wall_time_statistics(communicator);
    return stop_reason;
  }
} // namespace Membrane
