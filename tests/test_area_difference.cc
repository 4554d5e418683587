// Area-difference elasticity (MODEL.md section 11, physics/terms/area_difference.h).
// The term's normal force uses dM[V_n n] = -2 integral K V_n ds for M = integral H ds. On
// ellipsoids, the derivative of the discrete M (the projected mean curvature of the scheme)
// along a smooth normal move, by central differences, approaches -2 integral K_h V_n ds
// under refinement; and the energy of a sphere is the closed form pi k / (2 A) (M - M_0)^2
// with M = -8 pi R.
#include <membrane/physics/energy.h>
#include <membrane/physics/free_energy.h>
#include <membrane/physics/terms/area_difference.h>
#include <membrane/surface/closed_surfaces.h>
#include <membrane/surface/geometry.h>
#include <membrane/surface/initial_shapes.h>

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace
{
  using namespace Membrane;

  ReferenceSurfaceOptions ellipsoid(const unsigned int n)
  {
    ReferenceSurfaceOptions options;
    options.type           = "ellipsoid";
    options.cells_per_side = n;
    options.semi_axes      = {{1.3, 1.0, 0.8}};
    return options;
  }

  /// The move's normal speed f and the ellipsoid's unit normal at a point of it.
  double speed(const dealii::Point<spacedim> &x)
  {
    return 1 + 0.5 * x[0] + 0.3 * x[1] * x[2];
  }

  class NormalMove : public dealii::Function<spacedim>
  {
  public:
    NormalMove(const std::array<double, 3> &axes, const double size)
      : dealii::Function<spacedim>(spacedim)
      , axes(axes)
      , size(size)
    {}
    double value(const dealii::Point<spacedim> &x, const unsigned int c) const override
    {
      dealii::Tensor<1, spacedim> n;
      for (unsigned int d = 0; d < spacedim; ++d)
        n[d] = x[d] / (axes[d] * axes[d]);
      return size * speed(x) * n[c] / n.norm();
    }

  private:
    const std::array<double, 3> axes;
    const double                size;
  };
} // namespace

TEST(AreaDifference, ForceIsTheDerivativeOfTheTotalMeanCurvature)
{
  std::vector<double> errors;
  for (const unsigned int n : {4u, 8u, 16u})
    {
      const ReferenceSurfaceOptions options = ellipsoid(n);
      Triangulation                 tria(MPI_COMM_WORLD);
      make_closed_surface(tria, options);
      Surface surface(tria, false);
      surface.setup();
      const Geometry geometry = compute_geometry(surface);
      // -2 integral K f ds on the reference ellipsoid.
      const dealii::QGauss<dim>                 quadrature(3);
      dealii::FEValues<dim, spacedim>           fe_values(surface.mapping(), surface.scalar_space().fe(), quadrature,
                                                          dealii::update_values | dealii::update_quadrature_points |
                                                            dealii::update_JxW_values);
      std::vector<double>                       K(quadrature.size());
      double                                    force = 0;
      for (const auto &cell : surface.scalar_space().dof_handler().active_cell_iterators())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(geometry.gauss_curvature, K);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            force += -2 * K[q] * speed(fe_values.quadrature_point(q)) * fe_values.JxW(q);
        }
      const double epsilon = 1e-4;
      std::array<double, 2> M{};
      for (const int side : {0, 1})
        {
          set_displacement(surface, NormalMove(options.semi_axes, side == 0 ? epsilon : -epsilon));
          M[side] = total_mean_curvature_and_area(surface, compute_geometry(surface)).first;
        }
      const double derivative = (M[0] - M[1]) / (2 * epsilon);
      errors.push_back(std::abs(derivative - force) / std::abs(force));
      std::cout << n << " cells per side: dM/deps = " << derivative << ", -2 integral K f ds = " << force
                << ", relative difference " << errors.back() << std::endl;
    }
  const double order = std::log2(errors[1] / errors[2]);
  std::cout << "observed order " << order << std::endl;
  EXPECT_GT(order, 1.0);
  EXPECT_LT(errors.back(), 0.02);
}

TEST(AreaDifference, SphereEnergyIsTheClosedForm)
{
  ReferenceSurfaceOptions options;
  options.type           = "sphere";
  options.cells_per_side = 16;
  options.radius         = 0.8;
  Triangulation tria(MPI_COMM_WORLD);
  make_closed_surface(tria, options);
  Surface surface(tria, false);
  surface.setup();
  const Geometry geometry = compute_geometry(surface);
  Material       material;
  material.bending_rigidity                 = make_linear_law(1, 1);
  material.gaussian_rigidity                = make_linear_law(0, 0);
  material.spontaneous_curvature            = make_linear_law(0, 0);
  material.area_difference.stiffness        = 3;
  material.area_difference.reduced_difference = 2;
  Vector phi = surface.scalar_space().make_ghosted();
  const EnergyTerms energy = compute_energy(surface, geometry, phi, material);
  // A = 4 pi R^2, M = -8 pi R, M_0 = -8 pi R m_0: F = pi k / (2 A) (8 pi R (m_0 - 1))^2 = 8 pi^2 k (m_0 - 1)^2.
  const double expected = 8 * M_PI * M_PI * 3;
  std::cout << "F_ADE = " << energy.area_difference << ", closed form " << expected << std::endl;
  EXPECT_NEAR(energy.area_difference / expected, 1, 0.02);
  EXPECT_NEAR(energy.total(), energy.bending + energy.area_difference, 1e-12);
}
