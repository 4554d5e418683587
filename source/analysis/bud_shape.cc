#include <membrane/analysis/bud_shape.h>
#include <membrane/analysis/cross_sections.h>
#include <membrane/analysis/surface_quads.h>

#include <deal.II/base/geometry_info.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    double wrap(const double dx)
    {
      return dx - std::round(dx);
    }

    double area_of_phase_a(const Surface &surface, const Vector &phi)
    {
      const FieldSpace       &scalars = surface.scalar_space();
      const QGauss<dim>       quadrature(3);
      FEValues<dim, spacedim> fe_values(surface.mapping(), scalars.fe(), quadrature, update_values | update_JxW_values);
      std::vector<double>     values(quadrature.size());
      double                  local = 0;
      for (const auto &cell : scalars.dof_handler().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            fe_values.get_function_values(phi, values);
            for (const unsigned int q : fe_values.quadrature_point_indices())
              if (values[q] > 0)
                local += fe_values.JxW(q);
          }
      return Utilities::MPI::sum(local, scalars.communicator());
    }
  } // namespace

  BudShape measure_bud(const Surface &surface, const Vector &phi, const unsigned int levels)
  {
    // Every rank gathers the cells (current vertex positions, and phi there) of all
    // ranks: the cross-sections need whole cells, the averages below their edges.
    std::vector<double>            quad_phi;
    const std::vector<SurfaceQuad> quads = gather_surface_quads(surface, &phi, &quad_phi);
    // The edges, as pairs of end points.
    std::vector<Point<spacedim>> edges;
    std::vector<double>          edge_phi;
    for (std::size_t c = 0; c < quads.size(); ++c)
      for (unsigned int l = 0; l < GeometryInfo<dim>::lines_per_cell; ++l)
        for (const unsigned int end : {0, 1})
          {
            const unsigned int v = GeometryInfo<dim>::line_to_cell_vertices(l, end);
            edges.push_back(quads[c][v]);
            edge_phi.push_back(quad_phi[4 * c + v]);
          }

    BudShape shape;
    shape.domain_area = area_of_phase_a(surface, phi);
    if (edges.empty())
      return shape;

    // Samples are edge end points; on a locally refined mesh they crowd where the cells
    // are small. Weighting each by its edge's squared length (the area it stands for)
    // makes the averages below independent of the mesh: an end point weighs |b - a|^2,
    // a rim crossing (a point of a curve) |b - a|.
    std::vector<double> weight(edges.size());
    for (std::size_t e = 0; e + 1 < edges.size(); e += 2)
      weight[e] = weight[e + 1] = (edges[e + 1] - edges[e]).norm_square();
    std::vector<std::size_t> order(edges.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](const auto a, const auto b) { return edges[a][2] < edges[b][2]; });
    const double total_weight = std::accumulate(weight.begin(), weight.end(), 0.0);
    double       median = edges[order[order.size() / 2]][2];
    double below = 0;
    for (const auto k : order)
      if ((below += weight[k]) >= 0.5 * total_weight)
        {
          median = edges[k][2];
          break;
        }
    const Point<spacedim> &low = edges[order.front()], &high = edges[order.back()];
    shape.direction            = high[2] - median >= median - low[2] ? 1 : -1;
    const Point<spacedim> apex = shape.direction > 0 ? high : low;
    const auto radius = [&](const Point<spacedim> &p) {
      return std::hypot(wrap(p[0] - apex[0]), wrap(p[1] - apex[1]));
    };

    double far_sum = 0, far_weight = 0;
    for (std::size_t k = 0; k < edges.size(); ++k)
      if (radius(edges[k]) > 0.5)
        {
          far_sum += weight[k] * edges[k][2];
          far_weight += weight[k];
        }
    const double far = far_weight > 0 ? far_sum / far_weight : median;

    // The phase-A domain: its extreme point along s and the mean height of its rim.
    double top = -std::numeric_limits<double>::max(), rim_sum = 0, rim_weight = 0;
    for (std::size_t e = 0; e + 1 < edges.size(); e += 2)
      {
        for (const std::size_t k : {e, e + 1})
          if (edge_phi[k] > 0)
            top = std::max(top, shape.direction * edges[k][2]);
        if ((edge_phi[e] > 0) != (edge_phi[e + 1] > 0))
          {
            const double s      = edge_phi[e] / (edge_phi[e] - edge_phi[e + 1]);
            const double length = std::sqrt(weight[e]);
            rim_sum += length * (edges[e][2] + s * (edges[e + 1][2] - edges[e][2]));
            rim_weight += length;
          }
      }
    if (rim_weight > 0 && shape.domain_area > 0)
      shape.domain_protrusion = (top - shape.direction * rim_sum / rim_weight) /
                                (2 * std::sqrt(shape.domain_area / (4 * M_PI)));
    shape.height     = shape.direction * (apex[2] - far);
    if (shape.height <= 0)
      return shape;

    const Neck neck   = find_neck(quads, Point<2>(apex[0], apex[1]), far, apex[2], 1.0, levels);
    shape.neck_ratio  = neck.ratio;
    shape.neck_radius = neck.radius;
    shape.bud_radius  = neck.bud_radius;
    return shape;
  }

  std::string classify_outcome(const BudShape &shape, const OutcomeCriteria &criteria, const bool pinch_off)
  {
    if (pinch_off || shape.neck_ratio < criteria.complete_neck_ratio)
      return "complete bud";
    if (shape.domain_protrusion < criteria.flat_protrusion)
      return "flat";
    return "incomplete bud";
  }
} // namespace Membrane
