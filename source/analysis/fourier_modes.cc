#include <membrane/analysis/fourier_modes.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>

#include <cmath>

namespace Membrane
{
  using namespace dealii;

  std::vector<std::complex<double>> fourier_amplitudes(const FieldSpace &space, const Vector &field,
                                                       const unsigned int                      component,
                                                       const std::vector<std::array<int, 2>> &modes)
  {
    // The reference mesh (MappingQ1 of the triangulation's vertices) gives u and du. Three
    // Gauss points per direction integrate the bilinear field times a mode of the lowest
    // shells to far below the statistical errors these amplitudes are used with.
    const MappingQ<dim, spacedim> reference_mapping(1);
    const QGauss<dim>             quadrature(3);
    FEValues<dim, spacedim>       fe_values(reference_mapping, space.fe(), quadrature,
                                            update_values | update_quadrature_points | update_JxW_values);
    std::vector<dealii::Vector<double>> values(quadrature.size(), dealii::Vector<double>(space.n_components()));
    std::vector<double>           parts(2 * modes.size(), 0.0);
    for (const auto &cell : space.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(field, values);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              const Point<spacedim> &u = fe_values.quadrature_point(q);
              const double           f = values[q][component] * fe_values.JxW(q);
              for (std::size_t m = 0; m < modes.size(); ++m)
                {
                  const double phase = 2 * M_PI * (modes[m][0] * u[0] + modes[m][1] * u[1]);
                  parts[2 * m] += f * std::cos(phase);
                  parts[2 * m + 1] -= f * std::sin(phase);
                }
            }
        }
    Utilities::MPI::sum(parts, space.communicator(), parts);
    std::vector<std::complex<double>> amplitudes(modes.size());
    for (std::size_t m = 0; m < modes.size(); ++m)
      amplitudes[m] = {parts[2 * m], parts[2 * m + 1]};
    return amplitudes;
  }

  LowestModes lowest_mode_powers(const FieldSpace &space, const Vector &field, const unsigned int component)
  {
    const auto a = fourier_amplitudes(space, field, component, {{{1, 0}}, {{0, 1}}, {{1, 1}}, {{1, -1}}});
    return {(std::norm(a[0]) + std::norm(a[1])) / 2, (std::norm(a[2]) + std::norm(a[3])) / 2};
  }
} // namespace Membrane
