// Closed vesicles in a run (MODEL.md section 8): the reference surface, the volume
// term of each shape step and the vesicle columns of the statistics. Part of Simulator.
#include <membrane/analysis/spherical_modes.h>
#include <membrane/analysis/vesicle_domain.h>
#include <membrane/simulator.h>
#include <membrane/surface/closed_surfaces.h>
#include <membrane/surface/gauss_map.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>

#include <cmath>
#include <string>
#include <vector>

namespace Membrane
{
  using namespace dealii;

  void Simulator::make_reference_surface()
  {
    if (!closed())
      {
        make_periodic_unit_square(triangulation, parameters.cells_per_side);
        base_level      = factor_cells_per_side(parameters.cells_per_side).second;
        input_cell_size = 1.0 / parameters.cells_per_side;
        return;
      }
    make_closed_surface(triangulation, parameters.reference);
    base_level      = 0; // the input mesh is the coarse mesh
    input_cell_size = std::sqrt(GridTools::volume(triangulation) / triangulation.n_global_active_cells());
  }

  double Simulator::reference_cell_size() const
  {
    if (!closed()) // as the patch always had it, bit for bit
      return 1.0 / (parameters.cells_per_side << finest_level());
    return input_cell_size / (1u << finest_level());
  }

  bool Simulator::volume_constrained() const
  {
    return closed() && parameters.volume.constraint != "free";
  }

  bool Simulator::volume_fixed() const
  {
    return closed() && parameters.volume.constraint == "fixed";
  }

  VolumeCoupling Simulator::volume_term(const double tau) const
  {
    VolumeCoupling term;
    const VolumeOptions &options = parameters.volume;
    if (!volume_constrained())
      return term;
    term.active = true;
    term.fixed  = volume_fixed();
    if (term.fixed)
      // Linearized constraint with drift correction: integral W.n ds = V_target(t_{m+1}) - V(X).
      term.volume_defect = target_volume(options, initial_volume, initial_area, time + tau) - enclosed_volume(surface);
    else
      term.pressure = options.pressure;
    return term;
  }

  double Simulator::pressure_work_of_step(const double volume_before, const double pressure_before) const
  {
    // integral p dV over the step by the trapezoidal rule in p (p^m of the previous step,
    // p^{m+1} of this one; a prescribed pressure is the same at both ends). With a fixed,
    // unmoving target dV is round-off; it matters when V_target is ramped.
    const VolumeCoupling term = volume_term(trial_end_time - time);
    if (!term.active)
      return 0;
    const double p_before = term.fixed ? (step > 0 ? pressure_before : volume_pressure) : term.pressure;
    return 0.5 * (p_before + volume_pressure) * (enclosed_volume(surface) - volume_before);
  }

  void Simulator::restore_volume()
  {
    // dV/dalpha = integral nu.n ds for X + alpha nu (nu: the vertex normals, Q1); two
    // Newton steps reach round-off, the shift being of the size of the grid move's
    // second-order volume change.
    const FieldSpace &vectors = surface.vector_space();
    const Vector      normal  = vectors.ghosted_copy(compute_vertex_normals(surface));
    const double      target  = target_volume(parameters.volume, initial_volume, initial_area, trial_end_time);
    const double      mass    = integrate(surface, phi);
    for (unsigned int it = 0; it < 2; ++it)
      {
        const double defect = target - enclosed_volume(surface);
        const QGauss<dim>       quadrature(2);
        FEValues<dim, spacedim> fe_values(surface.mapping(), vectors.fe(), quadrature,
                                          update_normal_vectors | update_JxW_values);
        FEValues<dim, spacedim> normal_values(surface.mapping(), vectors.fe(), quadrature, update_values);
        std::vector<Tensor<1, spacedim>> nu(quadrature.size());
        double                           slope = 0;
        for (const auto &cell : vectors.dof_handler().active_cell_iterators())
          if (cell->is_locally_owned())
            {
              fe_values.reinit(cell);
              normal_values.reinit(cell);
              normal_values[FEValuesExtractors::Vector(0)].get_function_values(normal, nu);
              for (const unsigned int q : fe_values.quadrature_point_indices())
                slope += nu[q] * fe_values.normal_vector(q) * fe_values.JxW(q);
            }
        slope = Utilities::MPI::sum(slope, communicator);
        Vector displacement = vectors.make_owned();
        displacement        = surface.displacement();
        Vector shift        = vectors.make_owned();
        shift               = normal;
        displacement.add(defect / slope, shift);
        surface.set_displacement(displacement);
      }
    Vector corrected = surface.scalar_space().make_owned();
    corrected        = phi;
    corrected.add((mass - integrate(surface, phi)) / surface.area());
    surface.scalar_space().constraints().distribute(corrected);
    phi = corrected;
  }

  BudShape Simulator::measure_vesicle_bud() const
  {
    // The patch's height has no meaning on a vesicle; the domain protrusion and the neck,
    // measured along the vesicle's domain axis, feed the outcome classification.
    const VesicleDomain domain = measure_vesicle_domain(surface, phi);
    BudShape            shape;
    shape.domain_area       = domain.domain_area;
    shape.domain_protrusion = domain.protrusion;
    shape.neck_radius       = domain.neck_radius;
    shape.bud_radius        = domain.bud_radius;
    shape.neck_ratio        = domain.neck_ratio;
    return shape;
  }

  void Simulator::record_vesicle_statistics()
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
    stats.set("integral_K", integrate(surface, geometry.gauss_curvature));

    stats.set("gauss_map_area", gauss_map_area(surface, geometry.normal));
    // The shape spectrum (analysis/spherical_modes.h): the mean of u_lm^2 over m, which
    // Milner and Safran predict as k_BT / (kappa (l - 1)(l + 2)(l (l + 1) + Sigma R^2 / kappa)).
    const std::vector<double> shape_power = spherical_mode_powers(surface, 4);
    for (unsigned int l = 2; l <= 4; ++l)
      stats.set("shape_mode_" + std::to_string(l), shape_power[l] / (2 * l + 1));
  }
} // namespace Membrane
