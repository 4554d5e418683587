// Stage 3 of a step: area and volume restoration. The vertex areas the step aims at, the
// projections of the moved surface back onto the local area constraint and a fixed volume, the
// tangential area correction, the restoration of integral phi ds, and the reference areas that
// follow the vertices through grid control and adaptation. Part of Simulator.
#include <membrane/simulator.h>
#include <membrane/solvers/vector_access.h>
#include <membrane/surface/closed_surfaces.h>
#include <membrane/surface/mesh_motion.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace Membrane
{
  using namespace dealii;

  Vector Simulator::area_target(const double tau, const Vector &areas) const
  {
    // The step restores a fraction theta = min(1, tau / T_a) of the area defect a_ref - a^m
    // (a Baumgarte-type relaxation of the constraint drift at the rate 1/T_a). Restoring it
    // whole in every step would move the surface by an amount that does not shrink with tau,
    // and so change the energy by about integral gamma (a_ref - a^m) even in the shortest
    // step: a step cut short to land on the end time, or retried after a rejection, was then
    // rejected at any tau and the run stalled.
    // At a temperature no energy test applies, and the reason for T_a > tau there is the variation
    // of the defect (restored whole in every step, its cell-scale part grew on the two-phase patch
    // at kappa/10: docs/model.md, physical temperature). Its uniform part, the relative defect u of
    // the whole membrane (the area the noise adds), is then restored whole: the target is
    // (1 - theta) (1 + u) a^m + theta a_ref, whose sum is the total reference area for any theta.
    Vector target = areas;
    if (parameters.shape_options.correct_area)
      {
        const double relaxation = parameters.shape_options.area_relaxation_time;
        const double theta      = relaxation > 0 ? std::min(1.0, tau / relaxation) : 1.0;
        const double uniform =
          parameters.thermal.active() && theta < 1 ? reference_areas.l1_norm() / areas.l1_norm() - 1 : 0;
        target *= (1 - theta) * (1 + uniform);
        target.add(theta, reference_areas);
      }
    return target;
  }

  bool Simulator::restore_areas_and_volume(const double tau, const Vector &target, Vector &gamma)
  {
    const ShapeOptions &options = parameters.shape_options;
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
            const Vector         areas       = vertex_areas(surface);
            const VolumeCoupling volume      = volume_term(tau);
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
            if (!add_shape_increment(correction))
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
        if (fixed_volume && tangential.iterations > 0)
          {
            // The tangential moves change the enclosed volume of the bilinear surface at
            // second order: one more volume projection adds to them.
            const ShapeUpdate correction = shape_solver.correct_area(surface, surface.scalar_space().make_owned(),
                                                                     &timer, volume_term(tau));
            if (!add_shape_increment(correction))
              return false;
            gamma += correction.pressure;
            volume_pressure += correction.volume_pressure;
          }
      }
    pressure = gamma;
    return true;
  }

  bool Simulator::restore_material_areas(const double tau, const Vector &target, Vector &gamma,
                                         const Vector &displacement_before)
  {
    const ShapeOptions &options = parameters.shape_options;
    area_projections            = 0;
    tangential_area_moves       = 0;
    if (options.correct_area)
      {
        TimerOutput::Scope scope(timer, "area projection");
        const FieldSpace  &vectors = surface.vector_space();
        Vector             increment = vectors.make_owned();
        increment                    = surface.displacement();
        increment -= displacement_before;
        surface.set_displacement(displacement_before);
        // The corrections keep the enclosed volume to first order; restore_volume() does the rest.
        VolumeCoupling volume = volume_term(tau);
        volume.volume_defect  = 0;
        for (unsigned int k = 0; k < options.area_corrections; ++k)
          {
            const Vector areas = material_areas(displacement_before, increment);
            if (max_relative_difference(areas, target) <= options.area_tolerance)
              break;
            Vector defect = target;
            defect -= areas;
            const ShapeUpdate correction = shape_solver.correct_area(surface, defect, &timer, volume);
            if (!std::isfinite(correction.increment.l2_norm()))
              return false;
            increment += correction.increment;
            gamma += correction.pressure;
            ++area_projections;
          }
        Vector moved = vectors.make_owned();
        moved        = displacement_before;
        moved += increment;
        surface.set_displacement(moved);
        if (options.tangential_area_iterations > 0)
          {
            // What the stabilized area row leaves is met by a tangential flow of the lipids on
            // X~ (the Lagrangian correction applied to the material configuration): the mesh
            // keeps only the normal part of W, so this flow only carries phi (move_mesh).
            const Vector normal     = vectors.ghosted_copy(compute_vertex_normals(surface));
            const auto   tangential = tangential_corrector.correct(surface, normal, target,
                                                                   options.tangential_area_tolerance,
                                                                   options.tangential_area_iterations);
            tangential_area_moves = tangential.iterations;
          }
      }
    pressure = gamma;
    return true;
  }

  Vector Simulator::material_areas(const Vector &displacement_before, const Vector &increment)
  {
    // The vertex areas of X~ = X^m + W itself, not their linearization a^m + (div_s W, chi_i)
    // on Gamma^m: at a temperature the normal noise adds O(|grad W|^2) of area in every mode,
    // which the linear form does not see (the sphere at kappa/10 gained 4e-3 of total area in
    // its first 10 steps, all of its local area error). Leaves the surface at X^m.
    Vector moved = surface.vector_space().make_owned();
    moved        = displacement_before;
    moved += increment;
    surface.set_displacement(moved);
    Vector areas = vertex_areas(surface);
    surface.set_displacement(displacement_before);
    return areas;
  }

  void Simulator::restore_mass(const Vector &phi_new)
  {
    // phi~ rides on the vertices (Lagrangian), so integral phi ds = sum phi_i a_i
    // changes with the vertex areas. The pressure stabilization leaves a local area
    // error of O(tau) per step (the residual of the tangential law in the area row)
    // that correlates with grad phi and so adds up; a constant restores the mass.
    phi = phi_new;
    if (!parameters.shape_options.correct_mass)
      return;
    Vector       corrected = phi_new;
    const double mass      = integrate(surface, phi);
    shape_mass_correction  = (initial_mass - mass) / surface.area();
    corrected.add(shape_mass_correction);
    surface.scalar_space().constraints().distribute(corrected);
    phi = corrected;
  }

  Vector Simulator::area_ratio() const
  {
    // a_ref,i / a_i as a nodal field (1 up to the local area error), so that the
    // reference area can follow the vertices through a change of the mesh.
    const Vector areas = vertex_areas(surface);
    Vector       ratio = surface.scalar_space().make_owned();
    {
      const LocalValues area(areas), reference(reference_areas);
      OwnedValues       values(ratio);
      for (const auto i : ratio.locally_owned_elements())
        values[i] = area[i] > 0 ? reference[i] / area[i] : 1.0;
    }
    ratio.compress(VectorOperation::insert);
    surface.scalar_space().constraints().distribute(ratio);
    return surface.scalar_space().ghosted_copy(ratio);
  }

  void Simulator::carry_reference_areas(const Vector &ratio_owned)
  {
    Vector carried = vertex_areas(surface);
    {
      const LocalValues ratio(ratio_owned);
      OwnedValues       values(carried);
      for (const auto i : carried.locally_owned_elements())
        values[i] *= ratio[i];
    }
    carried.compress(VectorOperation::insert);
    const double total = carried.mean_value() * carried.size();
    if (total > 0)
      carried *= initial_area / total; // the total reference area is kept exactly
    reference_areas = carried;
  }

  double Simulator::area_work_of_step(const Vector &target, const Vector &areas_before) const
  {
    // The surface pressure gamma is the multiplier of the vertex-area rows (div_s W, chi_i) =
    // target_i - a_i: restoring the defect changes F by about -sum_i gamma_i (target_i - a_i).
    const LocalValues gamma(pressure), restored(target), area(areas_before);
    double            work = 0;
    for (const auto i : target.locally_owned_elements())
      work -= gamma[i] * (restored[i] - area[i]);
    return Utilities::MPI::sum(work, communicator);
  }

  bool Simulator::volume_constrained() const
  {
    return topology->encloses_volume() && parameters.volume.constraint != "free";
  }

  bool Simulator::volume_fixed() const
  {
    return topology->encloses_volume() && parameters.volume.constraint == "fixed";
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
} // namespace Membrane
