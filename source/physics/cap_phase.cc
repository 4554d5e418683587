// Polar cap domains of the initial phase on a closed surface (initial_phase.h).
#include <membrane/physics/initial_phase.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>

#include <cmath>
#include <sstream>

namespace Membrane
{
  using namespace dealii;

  std::vector<Tensor<1, spacedim>> parse_cap_axes(const std::string &text, const std::string &entry)
  {
    std::vector<Tensor<1, spacedim>> axes;
    for (const std::string &item : Utilities::split_string_list(text, ';'))
      {
        if (item.empty())
          continue;
        std::istringstream  in(item);
        Tensor<1, spacedim> axis;
        in >> axis[0] >> axis[1] >> axis[2];
        AssertThrow(!in.fail() && axis.norm() > 0 && std::isfinite(axis.norm()),
                    ExcMessage("Entry <" + entry + ">: cannot read the axis <" + item +
                               ">; expected three numbers 'x y z', not all zero, per cap"));
        axes.push_back(axis / axis.norm());
      }
    AssertThrow(!axes.empty(), ExcMessage("Entry <" + entry + ">: needs at least one axis 'x y z'"));
    return axes;
  }

  Vector make_cap_phase(const Surface &surface, const InitialPhaseOptions &options)
  {
    const FieldSpace       &scalars = surface.scalar_space();
    const MPI_Comm          comm    = scalars.communicator();
    const QGauss<dim>       quadrature(2);
    FEValues<dim, spacedim> fe_values(surface.mapping(), scalars.fe(), quadrature,
                                      update_quadrature_points | update_JxW_values);
    // Quadrature points and weights of the current surface, and its centroid.
    std::vector<Point<spacedim>> points;
    std::vector<double>          weights;
    Tensor<1, spacedim>          moment;
    double                       area = 0;
    for (const auto &cell : scalars.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              points.push_back(fe_values.quadrature_point(q));
              weights.push_back(fe_values.JxW(q));
              moment += fe_values.JxW(q) * fe_values.quadrature_point(q);
              area += fe_values.JxW(q);
            }
        }
    area   = Utilities::MPI::sum(area, comm);
    const Point<spacedim> centroid(Utilities::MPI::sum(moment, comm) / area);
    const auto cosine = [&](const Point<spacedim> &x, const Tensor<1, spacedim> &axis) {
      const Tensor<1, spacedim> d = x - centroid;
      return d.norm() > 0 ? (d * axis) / d.norm() : 0.0;
    };
    const double radius = std::sqrt(area / (4 * numbers::PI));

    // One edge cos(theta_c) per cap: the area with cos(theta) > s falls monotonically
    // in s; bisection for the prescribed fraction.
    std::vector<double> edges;
    for (const auto &axis : options.cap_axes)
      {
        double low = -1, high = 1;
        for (unsigned int it = 0; it < 60; ++it)
          {
            const double mid  = 0.5 * (low + high);
            double       part = 0;
            for (std::size_t q = 0; q < points.size(); ++q)
              if (cosine(points[q], axis) > mid)
                part += weights[q];
            (Utilities::MPI::sum(part, comm) > options.cap_area_fraction * area ? low : high) = mid;
          }
        edges.push_back(0.5 * (low + high));
      }

    Vector phi = scalars.make_owned();
    for (const auto &cell : scalars.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          {
            const auto dof = cell->vertex_dof_index(v, 0);
            if (!scalars.owned().is_element(dof))
              continue;
            Point<spacedim> x = cell->vertex(v);
            for (unsigned int c = 0; c < spacedim; ++c)
              x[c] += surface.displacement()[surface.vector_space().cell(cell)->vertex_dof_index(v, c)];
            double value = -1;
            for (std::size_t k = 0; k < edges.size(); ++k)
              {
                const double c = cosine(x, options.cap_axes[k]);
                const double d = radius * (std::acos(std::clamp(edges[k], -1.0, 1.0)) -
                                           std::acos(std::clamp(c, -1.0, 1.0))); // > 0 inside
                value = std::max(value, options.cap_sharp ? (d > 0 ? 1.0 : -1.0)
                                                          : std::tanh(3 * d / (4 * options.transition_length)));
              }
            phi[dof] = value;

          }
    phi.compress(VectorOperation::insert);
    scalars.constraints().distribute(phi);
    return phi;
  }
} // namespace Membrane
