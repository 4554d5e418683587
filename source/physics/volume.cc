#include <membrane/physics/volume.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <cmath>

namespace Membrane
{
  using namespace dealii;

  double enclosed_volume(const Surface &surface)
  {
    // X.n sqrt(g) = X.(a_1 x a_2) is of degree 2 in each reference variable on a
    // bilinear cell, so 2x2 Gauss points integrate it exactly.
    const FieldSpace       &scalars = surface.scalar_space();
    const QGauss<dim>       quadrature(2);
    FEValues<dim, spacedim> fe_values(surface.mapping(), scalars.fe(), quadrature,
                                      update_quadrature_points | update_normal_vectors | update_JxW_values);
    double                  local = 0;
    for (const auto &cell : scalars.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            local += fe_values.quadrature_point(q) * fe_values.normal_vector(q) * fe_values.JxW(q);
        }
    return Utilities::MPI::sum(local, scalars.communicator()) / 3;
  }

  double reduced_volume(const double volume, const double area)
  {
    return 6 * std::sqrt(numbers::PI) * volume / std::pow(area, 1.5);
  }

  double volume_of_reduced_volume(const double reduced, const double area)
  {
    return reduced * std::pow(area, 1.5) / (6 * std::sqrt(numbers::PI));
  }

  double target_volume(const VolumeOptions &options, const double initial_volume, const double initial_area,
                       const double time)
  {
    if (options.reduced_volume_target <= 0)
      return initial_volume;
    const double final_volume = volume_of_reduced_volume(options.reduced_volume_target, initial_area);
    const double progress     = options.ramp_time > 0 ? std::min(time / options.ramp_time, 1.0) : 1.0;
    return initial_volume + progress * (final_volume - initial_volume);
  }
} // namespace Membrane
