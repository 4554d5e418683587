// Discrete geometry on analytic surfaces: observed convergence orders of the
// vertex normals, mean curvature H, Gaussian curvature K and area, and the
// discrete Gauss-Bonnet theorem on the periodic patch.
#include <membrane/surface/geometry.h>
#include <membrane/surface/initial_shapes.h>

#include <deal.II/base/numbers.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/manifold_lib.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace Membrane;
using dealii::numbers::PI;

namespace
{
  // Graph z = A cos(2 pi x) cos(2 pi y) with its exact normal, H and K.
  constexpr double amplitude = 0.1;
  struct Graph
  {
    double wx, wy, wxx, wyy, wxy;
    explicit Graph(const dealii::Point<spacedim> &p)
    {
      const double k = 2 * PI, cx = std::cos(k * p[0]), cy = std::cos(k * p[1]);
      const double sx = std::sin(k * p[0]), sy = std::sin(k * p[1]);
      wx  = -amplitude * k * sx * cy;
      wy  = -amplitude * k * cx * sy;
      wxx = -amplitude * k * k * cx * cy;
      wyy = -amplitude * k * k * cx * cy;
      wxy = amplitude * k * k * sx * sy;
    }
    double q() const { return 1 + wx * wx + wy * wy; }
    dealii::Tensor<1, spacedim> normal() const
    {
      return dealii::Tensor<1, spacedim>({-wx, -wy, 1.0}) / std::sqrt(q());
    }
    double mean() const
    {
      return ((1 + wy * wy) * wxx - 2 * wx * wy * wxy + (1 + wx * wx) * wyy) / std::pow(q(), 1.5);
    }
    double gauss() const { return (wxx * wyy - wxy * wxy) / (q() * q()); }
  };

  double exact_area()
  {
    // Periodic trapezoidal rule: spectrally accurate for this smooth integrand.
    const unsigned int n = 400;
    double             sum = 0;
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        sum += std::sqrt(Graph(dealii::Point<spacedim>((i + 0.5) / n, (j + 0.5) / n, 0)).q());
    return sum / (n * n);
  }

  struct Errors
  {
    double normal, mean, gauss, area, gauss_integral;
  };

  Errors geometry_errors(const unsigned int cells_per_side)
  {
    Triangulation tria(MPI_COMM_WORLD);
    make_periodic_unit_square(tria, cells_per_side);
    Surface surface(tria, true);
    surface.setup();
    set_cosine_modes(surface, {{amplitude / 2, 1, 1, 0}, {amplitude / 2, 1, -1, 0}});
    const Geometry geometry = compute_geometry(surface);

    // Nodal errors: the reference vertex (u1, u2) carries the analytic values.
    Errors errors{0, 0, 0, 0, 0};
    const auto &vectors = surface.vector_space();
    const auto &scalars = surface.scalar_space();
    for (const auto &cell : scalars.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const auto vcell = vectors.cell(cell);
          for (const unsigned int v : cell->vertex_indices())
            {
              const Graph g(cell->vertex(v));
              dealii::Tensor<1, spacedim> nu;
              for (unsigned int c = 0; c < spacedim; ++c)
                nu[c] = geometry.normal[vcell->vertex_dof_index(v, c)];
              errors.normal = std::max(errors.normal, (nu - g.normal()).norm());
              errors.mean = std::max(errors.mean, std::abs(geometry.mean_curvature[cell->vertex_dof_index(v, 0)] - g.mean()));
              errors.gauss = std::max(errors.gauss, std::abs(geometry.gauss_curvature[cell->vertex_dof_index(v, 0)] - g.gauss()));
            }
        }
    errors.normal = dealii::Utilities::MPI::max(errors.normal, MPI_COMM_WORLD);
    errors.mean   = dealii::Utilities::MPI::max(errors.mean, MPI_COMM_WORLD);
    errors.gauss  = dealii::Utilities::MPI::max(errors.gauss, MPI_COMM_WORLD);
    errors.area   = std::abs(surface.area() - exact_area());
    errors.gauss_integral = std::abs(integrate(surface, geometry.gauss_curvature));
    return errors;
  }

  // Sphere of radius R (outward normals): nu = x/R, H = -2/R, K = 1/R^2.
  Errors sphere_errors(const unsigned int refinements)
  {
    constexpr double radius = 0.7;
    Triangulation    tria(MPI_COMM_WORLD);
    dealii::GridGenerator::hyper_sphere(tria, dealii::Point<spacedim>(), radius);
    tria.set_all_manifold_ids(0);
    tria.set_manifold(0, dealii::SphericalManifold<dim, spacedim>());
    tria.refine_global(refinements);
    Surface surface(tria, false);
    surface.setup();
    const Geometry geometry = compute_geometry(surface);

    // Nodal root-mean-square errors: the max norm does not converge at the eight
    // valence-3 vertices of the cube-sphere mesh, where linear elements lose
    // consistency; everywhere else the errors are O(h^2).
    Errors      errors{0, 0, 0, 0, 0};
    double      n_vertices = 0;
    const auto &vectors = surface.vector_space();
    for (const auto &cell : surface.scalar_space().dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          {
            dealii::Tensor<1, spacedim> nu;
            for (unsigned int c = 0; c < spacedim; ++c)
              nu[c] = geometry.normal[vectors.cell(cell)->vertex_dof_index(v, c)];
            // Every vertex is visited once per adjacent cell; the RMS weights
            // it by its valence, which does not change the order.
            n_vertices += 1;
            errors.normal += (nu - cell->vertex(v) / radius).norm_square();
            errors.mean += std::pow(geometry.mean_curvature[cell->vertex_dof_index(v, 0)] + 2 / radius, 2);
            errors.gauss += std::pow(geometry.gauss_curvature[cell->vertex_dof_index(v, 0)] - 1 / (radius * radius), 2);
          }
    n_vertices    = dealii::Utilities::MPI::sum(n_vertices, MPI_COMM_WORLD);
    errors.normal = std::sqrt(dealii::Utilities::MPI::sum(errors.normal, MPI_COMM_WORLD) / n_vertices);
    errors.mean   = std::sqrt(dealii::Utilities::MPI::sum(errors.mean, MPI_COMM_WORLD) / n_vertices);
    errors.gauss  = std::sqrt(dealii::Utilities::MPI::sum(errors.gauss, MPI_COMM_WORLD) / n_vertices);
    errors.area   = std::abs(surface.area() - 4 * PI * radius * radius);
    errors.gauss_integral = std::abs(integrate(surface, geometry.gauss_curvature) - 4 * PI);
    return errors;
  }

  /// Print the error table and return the observed orders of the finest pair.
  Errors observed_orders(const std::vector<Errors> &errors, const char *label)
  {
    Errors orders{};
    for (unsigned int i = 1; i < errors.size(); ++i)
      {
        const auto order = [&](double Errors::*e) { return std::log2(errors[i - 1].*e / errors[i].*e); };
        orders = {order(&Errors::normal), order(&Errors::mean), order(&Errors::gauss),
                  order(&Errors::area), order(&Errors::gauss_integral)};
        std::printf("%s level %u: normal %.3e (%.2f)  H %.3e (%.2f)  K %.3e (%.2f)  area %.3e (%.2f)  "
                    "|intK - 2 pi chi| %.2e (%.2f)\n",
                    label, i, errors[i].normal, orders.normal, errors[i].mean, orders.mean, errors[i].gauss,
                    orders.gauss, errors[i].area, orders.area, errors[i].gauss_integral, orders.gauss_integral);
      }
    return orders;
  }
} // namespace

TEST(Geometry, SecondOrderOnPeriodicGraph)
{
  std::vector<Errors> errors;
  for (const unsigned int n : {16u, 32u, 64u})
    errors.push_back(geometry_errors(n));
  const Errors orders = observed_orders(errors, "graph");
  EXPECT_GT(orders.normal, 1.9);
  EXPECT_GT(orders.mean, 1.9);
  EXPECT_GT(orders.gauss, 1.9);
  EXPECT_GT(orders.area, 1.9);
  // Discrete Gauss-Bonnet on the periodic patch: integral K ds -> 0 at O(h^2).
  EXPECT_GT(orders.gauss_integral, 1.9);
  EXPECT_LT(errors.back().gauss_integral, 5e-3);
}

TEST(Geometry, SphereCurvaturesAndGaussBonnet)
{
  std::vector<Errors> errors;
  for (const unsigned int r : {3u, 4u, 5u})
    errors.push_back(sphere_errors(r));
  const Errors orders = observed_orders(errors, "sphere");
  // The cube-sphere mesh is not uniform, so the O(h^2) superconvergence of the
  // periodic grid is lost: normals converge at ~1.4, H and K at first order.
  EXPECT_GT(orders.normal, 1.3);
  EXPECT_GT(orders.area, 1.9);
  EXPECT_GT(orders.mean, 0.9);
  EXPECT_GT(orders.gauss, 0.85);
  EXPECT_LT(errors.back().gauss_integral, 0.05 * 4 * PI);
}
