// Stage: output. The statistics row of each accepted step (with the patch spectra or the
// vesicle columns), the progress line, field snapshots, checkpoints and the run records
// (run_info.json, summary.json). Part of Simulator.
#include <membrane/io/atomic_file.h>
#include <membrane/io/checkpoint.h>
#include <membrane/io/field_output.h>
#include <membrane/io/json.h>
#include <membrane/simulator.h>
#include <membrane/solvers/vector_access.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace Membrane
{
  using namespace dealii;

  void Simulator::record_statistics(const double tau_used)
  {
    TimerOutput::Scope scope(timer, "statistics");
    const double area = surface.area();
    const double mass = integrate(surface, phi);
    area_error        = max_relative_difference(vertex_areas(surface), reference_areas);
    bud = topology->measure_domain(surface, phi);
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
    // The mean surface pressure: the tension Sigma of the fluctuation spectra (with the mean
    // line-energy density G, (gradient_energy + well_energy) / area).
    stats.set("gamma_mean", integrate(surface, pressure) / area);
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
    stats.set("mesh_motion_energy", mesh_motion_energy);
    stats.set("dissipation", dissipation);
    stats.set("area_error", area_error);
    stats.set("shape_mass_correction", shape_mass_correction);
    stats.set("error_estimate", error_estimate);
    stats.set("step_error", step_error);
    stats.set("area_projections", area_projections);
    stats.set("tangential_area_moves", tangential_area_moves);
    stats.set("solver_iterations", solver_iterations);
    stats.set("cells", triangulation.n_global_active_cells());
    stats.set("dofs", surface.scalar_space().dof_handler().n_dofs());
    stats.set("refinement_level", finest_level());
    stats.set("adaptations", adaptations);
    stats.set("adaptation_energy_jump", adaptation_energy_jump);
    if (parameters.adaptivity.measure_carried_energy)
      {
        stats.set("adaptation_energy_carried", adaptation_energy_carried);
        stats.set("carried_measured", carried_measured);
      }
    stats.set("wall_seconds", earlier_wall_seconds + wall.wall_time());
    if (topology->encloses_volume())
      record_volume_statistics();
    topology->record_shape_statistics(surface, geometry, phi, energy, stats);
    if (parameters.structure_factor_shells > 0)
      {
        const StructureFactor S = topology->phase_structure_factor(surface, phi, parameters.structure_factor_shells);
        for (std::size_t n = 0; n < S.power.size(); ++n)
          stats.set("phase_shell_" + std::to_string(n + 1), S.power[n]);
        stats.set("phase_wavenumber", S.mean_wavenumber);
      }
    stats.end_row();
  }

  void Simulator::record_volume_statistics()
  {
    // The mean normal stress jump p + <H gamma>: on a sphere, where a uniform surface
    // tension and the pressure are interchangeable (the local area constraint fixes the
    // volume too), it is the Laplace pressure dF/dR / dV/dR of MODEL.md section 8.
    const FieldSpace       &scalars = surface.scalar_space();
    const QGauss<dim>       quadrature(2);
    FEValues<dim, spacedim> fe_values(surface.mapping(), scalars.fe(), quadrature, update_values | update_JxW_values);
    std::vector<double>     H(quadrature.size()), gamma(quadrature.size());
    double                  local = 0;
    for (const auto &cell : scalars.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(geometry.mean_curvature, H);
          fe_values.get_function_values(pressure, gamma);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            local += H[q] * gamma[q] * fe_values.JxW(q);
        }
    const double area        = surface.area();
    const double tension_jump = Utilities::MPI::sum(local, communicator) / area;
    const double volume      = enclosed_volume(surface);
    const double target      = parameters.volume.constraint == "fixed"
                                 ? target_volume(parameters.volume, initial_volume, initial_area, time)
                                 : initial_volume;
    stats.set("volume", volume);
    stats.set("volume_drift", (volume - target) / initial_volume);
    stats.set("reduced_volume", reduced_volume(volume, area));
    stats.set("pressure", volume_pressure);
    stats.set("pressure_work", pressure_work);
    stats.set("laplace_pressure", volume_pressure + tension_jump);
    stats.set("volume_compliance", parameters.volume.constraint == "free" ? 1.0 : shape_solver.volume_compliance());
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

  void Simulator::write_checkpoint() const
  {
    TimerOutput::Scope scope(timer, "checkpoint");
    const auto attempts = step_control.attempt_history(); // for the stall detector
    std::map<std::string, double> scalars = {{"time", time},
                     {"tau", step_control.tau()},
                     {"step", step},
                     {"rejected_steps", rejected_steps},
                     {"grid_control_skipped", grid_control_skipped},
                     {"irreducible_error_steps", irreducible_error_steps},
                     {"initial_area", initial_area},
                     {"initial_mass", initial_mass},
                     {"next_output_time", next_output_time},
                     {"adaptations", adaptations},
                     {"cells_per_side", parameters.cells_per_side},
                     {"wall_seconds", earlier_wall_seconds + wall.wall_time()},
                     {"adaptation_energy_jump", adaptation_energy_jump},
                     {"adaptation_energy_carried", adaptation_energy_carried},
                     {"carried_measured", carried_measured},
                     {"twin_pending", twin_pending ? 1.0 : 0.0},
                     {"twin_tau", twin_tau},
                     {"twin_energy", twin_energy},
                     {"initial_volume", initial_volume},
                     {"volume_pressure", volume_pressure},
                     {"pressure_work", pressure_work},
                     {"previous_tau", previous_tau},
                     {"error_rejection_tau", step_control.error_rejection().tau},
                     {"error_rejection_estimate", step_control.error_rejection().error},
                     {"shape_factorizations", shape_solver.n_factorizations()},
                     {"recent_attempts", attempts.count},
                     {"recent_rejections", attempts.rejected}};
    for (const auto &[kind, count] : rejections)
      scalars["rejected_" + kind] = count;
    // The last step's increments, which the accuracy control's next error estimate compares
    // with (none before the first step and after a mesh adaptation: previous_tau = 0).
    std::optional<StepIncrements> increments;
    if (previous_tau > 0)
      increments = StepIncrements{previous_increment, previous_phi_change};
    save_checkpoint(parameters.output_directory + "/checkpoint.txt", surface, phi, reference_areas, scalars,
                    stats.to_text(), options.parameter_text, increments ? &*increments : nullptr);
  }

  void Simulator::write_run_info() const
  {
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return;
    const std::string dir = parameters.output_directory + "/";
    write_file_atomically(dir + "parameters.prm", options.parameter_text);
    JsonObject info;
    info.add("code_version", code_version())
      .add("command", options.command_line)
      .add("mpi_ranks", Utilities::MPI::n_mpi_processes(communicator))
      .add("cells", triangulation.n_global_active_cells())
      .add("vertices_dofs", surface.scalar_space().dof_handler().n_dofs())
      .add("parameter_file", "parameters.prm");
    if (!parameters.resume_from.empty())
      {
        info.add("resumed_from", parameters.resume_from);
        std::string changes = "[";
        for (const auto &change : changed_on_resume)
          changes += (changes.size() > 1 ? ", " : "") + json_string(change);
        info.add_raw("changed_on_resume", changes + "]");
      }
    write_file_atomically(dir + "run_info.json", info.str());
  }

  void Simulator::write_summary(const RunResult &result, const double wall_seconds) const
  {
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return;
    // {"energy_rise": n, ...}: every kind, 0 included, on one line.
    std::string rejection_counts = "{";
    for (const char *kind : rejection_kinds)
      rejection_counts += (rejection_counts.size() > 1 ? ", " : "") + json_string(kind) + ": " +
                          std::to_string(rejections.count(kind) ? rejections.at(kind) : 0U);
    rejection_counts += "}";
    JsonObject summary;
    summary.add("code_version", code_version())
      .add("stop_reason", result.stop_reason)
      .add("failed", result.failed)
      .add("outcome", result.outcome)
      .add("steps", step)
      .add("rejected_steps", rejected_steps)
      .add_raw("rejections", rejection_counts)
      .add("time", time)
      .add("wall_seconds", wall_seconds)
      .add("grid_control_refused_fraction", step > 0 ? double(grid_control_skipped) / step : 0.0)
      .add("irreducible_error_steps", irreducible_error_steps)
      .add("shape_factorizations", shape_solver.n_factorizations())
      .add("shape_krylov_solves", shape_solver.n_krylov_solves())   // Linear solver/Type = block:
      .add("shape_krylov_iterations", shape_solver.n_krylov_iterations()); // FGMRES, this run segment
    for (const char *c : {"energy", "bending_energy", "gaussian_energy", "gradient_energy", "well_energy", "area",
                          "area_drift", "mass", "mass_drift", "bud_height", "neck_radius", "bud_radius", "neck_ratio",
                          "domain_area", "domain_protrusion", "bud_direction", "min_corner_sine", "area_error", "cells",
                          "adaptations", "adaptation_energy_jump"})
      summary.add(c, stats.last(c));
    if (parameters.adaptivity.measure_carried_energy)
      for (const char *c : {"adaptation_energy_carried", "carried_measured"})
        summary.add(c, stats.last(c));
    if (topology->encloses_volume())
      for (const char *c : {"volume", "volume_drift", "reduced_volume", "pressure", "pressure_work", "laplace_pressure"})
        summary.add(c, stats.last(c));
    for (const std::string &c : topology->summary_columns())
      summary.add(c, stats.last(c));
    write_file_atomically(parameters.output_directory + "/summary.json", summary.str());
  }
} // namespace Membrane
