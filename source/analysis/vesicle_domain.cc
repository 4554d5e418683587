#include <membrane/analysis/surface_quads.h>
#include <membrane/analysis/vesicle_domain.h>
#include <membrane/solvers/vector_access.h>

#include <deal.II/base/geometry_info.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <cmath>
#include <limits>

namespace Membrane
{
  using namespace dealii;

  VesicleDomain measure_vesicle_domain(const Surface &surface, const Vector &phi)
  {
    const FieldSpace       &scalars = surface.scalar_space();
    const MPI_Comm          comm    = scalars.communicator();
    const QGauss<dim>       quadrature(2);
    FEValues<dim, spacedim> fe_values(surface.mapping(), scalars.fe(), quadrature,
                                      update_values | update_quadrature_points | update_JxW_values);
    std::vector<double>     phi_q(quadrature.size());
    Tensor<1, spacedim>     moment, domain_moment;
    double                  area = 0, domain_area = 0;
    for (const auto &cell : scalars.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(phi, phi_q);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              const double ds = fe_values.JxW(q);
              moment += ds * fe_values.quadrature_point(q);
              area += ds;
              if (phi_q[q] > 0)
                {
                  domain_moment += ds * fe_values.quadrature_point(q);
                  domain_area += ds;
                }
            }
        }
    VesicleDomain result;
    area               = Utilities::MPI::sum(area, comm);
    result.domain_area = Utilities::MPI::sum(domain_area, comm);
    if (result.domain_area <= 0 || result.domain_area >= area)
      return result;
    const Tensor<1, spacedim> centroid = Utilities::MPI::sum(moment, comm) / area;
    Tensor<1, spacedim>       axis     = Utilities::MPI::sum(domain_moment, comm) / result.domain_area - centroid;
    if (axis.norm() == 0)
      return result;
    axis /= axis.norm();

    // The domain's farthest vertex and the mean height of the phi = 0 crossings on cell edges.
    double            top = -std::numeric_limits<double>::max(), rim_sum = 0, rim_count = 0;
    const LocalValues phi_values(phi);
    for (const auto &cell : surface.vector_space().dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const auto X           = surface.mapping().get_vertices(cell);
          const auto scalar_cell = scalars.cell(cell);
          double     value[4];
          for (const unsigned int v : cell->vertex_indices())
            {
              value[v] = phi_values[scalar_cell->vertex_dof_index(v, 0)];
              if (value[v] > 0)
                top = std::max(top, (X[v] - Point<spacedim>(centroid)) * axis);
            }
          for (unsigned int l = 0; l < GeometryInfo<dim>::lines_per_cell; ++l)
            {
              const unsigned int a = GeometryInfo<dim>::line_to_cell_vertices(l, 0);
              const unsigned int b = GeometryInfo<dim>::line_to_cell_vertices(l, 1);
              if ((value[a] > 0) == (value[b] > 0))
                continue;
              const double          s = value[a] / (value[a] - value[b]);
              const Point<spacedim> x = X[a] + s * (X[b] - X[a]);
              rim_sum += (x - Point<spacedim>(centroid)) * axis;
              rim_count += 1;
            }
        }
    top       = Utilities::MPI::max(top, comm);
    rim_sum   = Utilities::MPI::sum(rim_sum, comm);
    rim_count = Utilities::MPI::sum(rim_count, comm);
    if (rim_count > 0)
      result.protrusion = (top - rim_sum / rim_count) / (2 * std::sqrt(result.domain_area / (4 * numbers::PI)));
    if (top > 0)
      {
        const Neck neck    = find_neck_along(gather_surface_quads(surface), Point<spacedim>(centroid), axis, 0.0, top);
        result.neck_radius = neck.radius;
        result.bud_radius  = neck.bud_radius;
        result.neck_ratio  = neck.ratio;
      }
    return result;
  }
} // namespace Membrane
