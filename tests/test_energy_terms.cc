// The energy terms (physics/free_energy.h): each term's normal force is the derivative of its
// energy, to discretization error, on ellipsoids under refinement (bending, Gaussian, line energy
// and area-difference elasticity); the tangential force Y grad phi of the line energy is its
// derivative along an area-preserving tangential move of the patch.
//
// Area-difference elasticity (MODEL.md section 11, physics/terms/area_difference.h).
// The term's normal force uses dM[V_n n] = -2 integral K V_n ds for M = integral H ds. On
// ellipsoids, the derivative of the discrete M (the projected mean curvature of the scheme)
// along a smooth normal move, by central differences, approaches -2 integral K_h V_n ds
// under refinement; and the energy of a sphere is the closed form pi k / (2 A) (M - M_0)^2
// with M = -8 pi R.
#include <membrane/physics/double_well.h>
#include <membrane/physics/energy.h>
#include <membrane/physics/free_energy.h>
#include <membrane/physics/stress_force.h>
#include <membrane/physics/terms/area_difference.h>
#include <membrane/physics/terms/bending.h>
#include <membrane/physics/terms/gaussian.h>
#include <membrane/physics/terms/line_energy.h>
#include <membrane/surface/closed_surfaces.h>
#include <membrane/surface/field_space.h>
#include <membrane/surface/geometry.h>
#include <membrane/surface/initial_shapes.h>
#include <membrane/surface/projection.h>
#include <membrane/surface/surface.h>

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <set>
#include <vector>

namespace
{
  using namespace Membrane;

  /// The move's normal speed f and the ellipsoid's unit normal at a point of it.
  double speed(const dealii::Point<spacedim> &x)
  {
    return 1 + 0.5 * x[0] + 0.3 * x[1] * x[2];
  }

  /// A move of the vertices, `size` times a vector field of the point (set_displacement
  /// evaluates it at the reference vertices).
  class Move : public dealii::Function<spacedim>
  {
  public:
    using Field = std::function<dealii::Tensor<1, spacedim>(const dealii::Point<spacedim> &)>;
    Move(const double size, Field field)
      : dealii::Function<spacedim>(spacedim)
      , size(size)
      , field(std::move(field))
    {}
    double value(const dealii::Point<spacedim> &x, const unsigned int c) const override { return size * field(x)[c]; }

  private:
    const double size;
    const Field  field;
  };

  /// The normal move f n of the ellipsoid with these semi-axes (n its unit normal at x).
  Move::Field normal_move(const std::array<double, 3> &axes)
  {
    return [axes](const dealii::Point<spacedim> &x) {
      dealii::Tensor<1, spacedim> n;
      for (unsigned int d = 0; d < spacedim; ++d)
        n[d] = x[d] / (axes[d] * axes[d]);
      return speed(x) * n / n.norm();
    };
  }

  /// The reference ellipsoid with n cells per cube edge, and central differences along the
  /// normal move f n of a quantity of the surface.
  struct Ellipsoid
  {
    static constexpr std::array<double, 3> semi_axes{{1.3, 1.0, 0.8}};
    Triangulation                          tria{MPI_COMM_WORLD};
    Surface                                surface{tria, false};

    explicit Ellipsoid(const unsigned int n)
    {
      ReferenceSurfaceOptions options;
      options.type           = "ellipsoid";
      options.cells_per_side = n;
      options.semi_axes      = semi_axes;
      make_closed_surface(tria, options);
      surface.setup();
    }

    /// (q(+eps) - q(-eps)) / (2 eps) with eps = 1e-4; leaves the surface moved by -eps.
    template <typename Quantity>
    double derivative_along_move(const Quantity &quantity)
    {
      const double          epsilon = 1e-4;
      std::array<double, 2> values{};
      for (const int side : {0, 1})
        {
          set_displacement(surface, Move(side == 0 ? epsilon : -epsilon, normal_move(semi_axes)));
          values[side] = quantity(static_cast<const Surface &>(surface));
        }
      return (values[0] - values[1]) / (2 * epsilon);
    }
  };
} // namespace

TEST(AreaDifference, ForceIsTheDerivativeOfTheTotalMeanCurvature)
{
  std::vector<double> errors;
  for (const unsigned int n : {4u, 8u, 16u})
    {
      Ellipsoid      ellipsoid(n);
      Surface       &surface  = ellipsoid.surface;
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
      const double derivative = ellipsoid.derivative_along_move([](const Surface &moved) {
        return total_mean_curvature_and_area(moved, compute_geometry(moved)).first;
      });
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

// Every term's force is the derivative of its energy, to discretization error: along a smooth
// normal move f n of an ellipsoid carrying a smooth phi (which rides on the vertices), the
// central difference of the term's discrete energy approaches its first variation as the shape
// step assembles it at W = 0, H~ = H^m,
//   dE/d eps = -[kappa ((grad H, grad f) + m (H, f)) + (flux, grad f) + (source, f)]
// (the normal row's implicit stiffness and explicit force of physics/free_energy.h).
TEST(EnergyTerms, NormalForcesAreTheDerivativesOfTheirEnergies)
{
  // One material per term, with phase-dependent moduli so that the flux parts count too.
  const auto material_of = [](const std::string &term) {
    Material m;
    m.bending_rigidity      = make_linear_law(term == "bending" ? 2.0 : 1.0, term == "bending" ? 1.0 : 1.0);
    m.spontaneous_curvature = make_linear_law(term == "bending" ? 1.0 : 0.0, term == "bending" ? -1.0 : 0.0);
    m.gaussian_rigidity     = make_linear_law(term == "gaussian" ? 0.5 : 0.0, term == "gaussian" ? -0.5 : 0.0);
    m.line_tension          = term == "line" ? 1.0 : 0.0;
    m.transition_length     = 0.3;
    return m;
  };
  const auto energy_of = [](const std::string &term, const EnergyTerms &e) {
    return term == "bending" ? e.bending : term == "gaussian" ? e.gaussian : e.gradient + e.well;
  };
  for (const std::string term : {"bending", "gaussian", "line"})
    {
      std::vector<double> errors;
      for (const unsigned int n : {4u, 8u, 16u})
        {
          Ellipsoid ellipsoid(n);
          Surface  &surface = ellipsoid.surface;
          const Material material = material_of(term);
          // phi and f as nodal fields of the reference ellipsoid (phi rides on the vertices).
          const auto &scalars = surface.scalar_space();
          Vector      phi_owned = scalars.make_owned(), f_owned = scalars.make_owned();
          for_each_free_vertex(scalars, [&](const auto &cell, const unsigned int v, const auto &dofs) {
            phi_owned[dofs[0]] = 0.8 * std::tanh(cell->vertex(v)[0] / 0.4);
            f_owned[dofs[0]]   = speed(cell->vertex(v));
          });
          phi_owned.compress(dealii::VectorOperation::insert);
          f_owned.compress(dealii::VectorOperation::insert);
          const Vector phi = scalars.ghosted_copy(phi_owned), f = scalars.ghosted_copy(f_owned);

          const Geometry        geometry = compute_geometry(surface);
          // The term alone (FreeEnergy would add the others' forces).
          std::unique_ptr<FreeEnergyTerm> single;
          if (term == "bending")
            single = std::make_unique<BendingEnergy>(material);
          else if (term == "gaussian")
            single = std::make_unique<GaussianEnergy>(material);
          else
            single = std::make_unique<LineEnergy>(material);
          single->prepare(surface, geometry);
          const dealii::QGauss<dim>       quadrature(3);
          dealii::FEValues<dim, spacedim> values(surface.mapping(), scalars.fe(), quadrature,
                                                 dealii::update_values | dealii::update_gradients |
                                                   dealii::update_JxW_values);
          dealii::FEValues<dim, spacedim> vectors(surface.mapping(), surface.vector_space().fe(), quadrature,
                                                  dealii::update_values | dealii::update_gradients);
          const unsigned int                              n_q = quadrature.size();
          std::vector<double>                             phi_q(n_q), H_q(n_q), K_q(n_q), f_q(n_q);
          std::vector<dealii::Tensor<1, spacedim>>        grad_phi_q(n_q), grad_H_q(n_q), grad_f_q(n_q), nu_q(n_q);
          std::vector<dealii::Tensor<2, spacedim>>        grad_nu_q(n_q);
          const dealii::FEValuesExtractors::Vector        all(0);
          double                                          variation = 0;
          for (const auto &cell : scalars.dof_handler().active_cell_iterators())
            {
              values.reinit(cell);
              vectors.reinit(surface.vector_space().cell(cell));
              values.get_function_values(phi, phi_q);
              values.get_function_gradients(phi, grad_phi_q);
              values.get_function_values(geometry.mean_curvature, H_q);
              values.get_function_gradients(geometry.mean_curvature, grad_H_q);
              values.get_function_values(geometry.gauss_curvature, K_q);
              values.get_function_values(f, f_q);
              values.get_function_gradients(f, grad_f_q);
              vectors[all].get_function_values(geometry.normal, nu_q);
              vectors[all].get_function_gradients(geometry.normal, grad_nu_q);
              for (unsigned int q = 0; q < n_q; ++q)
                {
                  TermPoint point;
                  point.phi      = phi_q[q];
                  point.grad_phi = grad_phi_q[q];
                  point.H        = H_q[q];
                  point.K        = K_q[q];
                  point.nu       = nu_q[q];
                  point.grad_nu  = grad_nu_q[q];
                  NormalStiffness stiffness;
                  ShapeForce      force;
                  single->add_normal_stiffness(point, stiffness);
                  single->add_shape_force(point, force);
                  variation -= (stiffness.kappa *
                                  (grad_H_q[q] * grad_f_q[q] + stiffness.curvature_mass * H_q[q] * f_q[q]) +
                                force.flux * grad_f_q[q] + force.source * f_q[q]) *
                               values.JxW(q);
                }
            }
          const double derivative = ellipsoid.derivative_along_move([&](const Surface &moved) {
            return energy_of(term, compute_energy(moved, compute_geometry(moved), phi, material));
          });
          errors.push_back(std::abs(derivative - variation) / std::abs(derivative));
          std::cout << term << ", " << n << " cells per side: dE/deps = " << derivative << ", variation "
                    << variation << ", relative difference " << errors.back() << std::endl;
        }
      const double order = std::log2(errors[1] / errors[2]);
      std::cout << term << ": observed order " << order << std::endl;
      EXPECT_GT(order, 1.5) << term; // 2.06 (bending), 1.95 (Gaussian), 2.00 (line)
      EXPECT_LT(errors.back(), 0.05) << term;
    }
}

namespace
{
  /// The divergence-free, periodic tangential shear (sin 2 pi y, 0, 0).
  dealii::Tensor<1, spacedim> shear(const dealii::Point<spacedim> &x)
  {
    return dealii::Tensor<1, spacedim>({std::sin(2 * M_PI * x[1]), 0.0, 0.0});
  }
} // namespace

// The tangential force of the line energy (the force Y grad phi of the tangential law, Y the
// chemical potential): on the flat periodic patch, with phi riding on the vertices, the central
// difference of the discrete line energy along the area-preserving shear V = (sin 2 pi y, 0, 0)
// approaches -integral Y_h grad phi . V ds, with Y_h the L2 projection of
// sigma (-xi^2 lap phi + f'(phi)). (On a divergence-free move the energy density's own term
// e div V vanishes; the area constraint's gamma takes up the rest.) phi mixes the modes (1, 0)
// and (1, 1), whose product has the shear's wave vector (0, 1): with fewer modes the first
// variation vanishes by symmetry.
TEST(EnergyTerms, TangentialForceIsTheDerivativeOfTheLineEnergy)
{
  Material material;
  material.bending_rigidity      = make_linear_law(1.0, 1.0);
  material.spontaneous_curvature = make_linear_law(0.0, 0.0);
  material.gaussian_rigidity     = make_linear_law(0.0, 0.0);
  material.line_tension          = 1.0;
  material.transition_length     = 0.1;
  const double        xi = material.transition_length;
  std::vector<double> errors;
  for (const unsigned int n : {16u, 32u, 64u})
    {
      Triangulation tria(MPI_COMM_WORLD);
      make_periodic_unit_square(tria, n);
      Surface surface(tria, true);
      surface.setup();
      const auto &scalars   = surface.scalar_space();
      Vector      phi_owned = scalars.make_owned();
      for_each_free_vertex(scalars, [&](const auto &cell, const unsigned int v, const auto &dofs) {
        const auto x       = cell->vertex(v);
        phi_owned[dofs[0]] = 0.5 * std::sin(2 * M_PI * x[0]) + 0.4 * std::sin(2 * M_PI * (x[0] + x[1])) + 0.1;
      });
      phi_owned.compress(dealii::VectorOperation::insert);
      scalars.constraints().distribute(phi_owned);
      const Vector phi = scalars.ghosted_copy(phi_owned);

      // Y_h: M Y = sigma ((xi^2 grad phi, grad psi) + (f'(phi), psi)).
      const dealii::QGauss<dim>       quadrature(3);
      dealii::FEValues<dim, spacedim> values(surface.mapping(), scalars.fe(), quadrature,
                                             dealii::update_values | dealii::update_gradients |
                                               dealii::update_JxW_values | dealii::update_quadrature_points);
      const unsigned int                           n_q = quadrature.size(), n_dofs = scalars.fe().n_dofs_per_cell();
      std::vector<double>                          phi_q(n_q), Y_q(n_q);
      std::vector<dealii::Tensor<1, spacedim>>     grad_phi_q(n_q);
      std::vector<dealii::types::global_dof_index> indices(n_dofs);
      Vector                                       rhs = scalars.make_owned();
      for (const auto &cell : scalars.dof_handler().active_cell_iterators())
        {
          values.reinit(cell);
          values.get_function_values(phi, phi_q);
          values.get_function_gradients(phi, grad_phi_q);
          dealii::Vector<double> local(n_dofs);
          for (unsigned int q = 0; q < n_q; ++q)
            for (unsigned int i = 0; i < n_dofs; ++i)
              local[i] += material.line_tension *
                          (xi * xi * grad_phi_q[q] * values.shape_grad(i, q) +
                           DoubleWell::derivative(phi_q[q]) * values.shape_value(i, q)) *
                          values.JxW(q);
          cell->get_dof_indices(indices);
          scalars.constraints().distribute_local_to_global(local, indices, rhs);
        }
      rhs.compress(dealii::VectorOperation::add);
      const Vector Y = scalars.ghosted_copy(project(surface, scalars, rhs));

      double variation = 0;
      for (const auto &cell : scalars.dof_handler().active_cell_iterators())
        {
          values.reinit(cell);
          values.get_function_values(Y, Y_q);
          values.get_function_gradients(phi, grad_phi_q);
          for (unsigned int q = 0; q < n_q; ++q)
            {
              dealii::Tensor<1, spacedim> V;
              for (unsigned int c = 0; c < spacedim; ++c)
                V[c] = shear(values.quadrature_point(q))[c];
              variation -= Y_q[q] * (grad_phi_q[q] * V) * values.JxW(q);
            }
        }
      const double epsilon = 1e-4;
      std::array<double, 2> energies{};
      for (const int side : {0, 1})
        {
          set_displacement(surface, Move(side == 0 ? epsilon : -epsilon, shear));
          const EnergyTerms e = compute_energy(surface, compute_geometry(surface), phi, material);
          energies[side]      = e.gradient + e.well;
        }
      const double derivative = (energies[0] - energies[1]) / (2 * epsilon);
      errors.push_back(std::abs(derivative - variation) / std::abs(derivative));
      std::cout << n << " x " << n << ": dE/deps = " << derivative << ", -(Y grad phi, V) = " << variation
                << ", relative difference " << errors.back() << std::endl;
    }
  const double order = std::log2(errors[1] / errors[2]);
  std::cout << "observed order " << order << std::endl;
  EXPECT_GT(order, 1.5); // 2.00: relative differences 1.3e-2, 3.2e-3, 8.0e-4 at 16, 32, 64 cells per side
  EXPECT_LT(errors.back(), 0.01);
}

namespace
{
  /// A smooth move with normal and tangential parts on the ellipsoid.
  dealii::Tensor<1, spacedim> general_move(const dealii::Point<spacedim> &x)
  {
    return dealii::Tensor<1, spacedim>(
      {0.3 * x[1] * x[2] + 0.2, -0.4 * x[0] + 0.1 * x[2] * x[2], 0.25 * x[0] * x[1]});
  }
} // namespace

// Shape/Line force = stress takes the line energy's force as the derivative of the discrete line
// energy itself (physics/stress_force.h), not a discretization of its continuum variation: on an
// ellipsoid carrying a steep phi (riding on the vertices), along a move with normal and tangential
// parts, the central difference of the discrete line energy equals -sum_j a_j f_j . V_j to the
// difference's own O(eps^2) error at every resolution, where the potential form of the reference
// scheme agrees only to O(h^2) (the tests above).
TEST(EnergyTerms, StressForceIsTheExactDerivativeOfTheDiscreteLineEnergy)
{
  Material material;
  material.bending_rigidity      = make_linear_law(1.0, 1.0);
  material.spontaneous_curvature = make_linear_law(0.0, 0.0);
  material.gaussian_rigidity     = make_linear_law(0.0, 0.0);
  material.line_tension          = 2.0;
  material.transition_length     = 0.1;
  for (const unsigned int n : {4u, 8u})
    {
      Ellipsoid   ellipsoid(n);
      Surface    &surface   = ellipsoid.surface;
      const auto &scalars   = surface.scalar_space();
      const auto &vectors   = surface.vector_space();
      Vector      phi_owned = scalars.make_owned();
      for_each_free_vertex(scalars, [&](const auto &cell, const unsigned int v, const auto &dofs) {
        phi_owned[dofs[0]] = 0.9 * std::tanh((cell->vertex(v)[0] - 0.2 * cell->vertex(v)[1]) / 0.15);
      });
      phi_owned.compress(dealii::VectorOperation::insert);
      const Vector phi = scalars.ghosted_copy(phi_owned);

      FreeEnergy terms(material);
      terms.prepare(surface, compute_geometry(surface));
      const Vector f     = stress_force(surface, phi, terms);
      const Vector areas = scalars.ghosted_copy(vertex_areas(surface));
      // -sum_j a_j f_j . V(x_j): V at the reference vertices, where set_displacement evaluates it.
      // (for_each_free_vertex visits a vertex once from each of its cells: count it once)
      double                                  variation = 0;
      std::set<dealii::types::global_dof_index> counted;
      for_each_free_vertex(vectors, [&](const auto &cell, const unsigned int v, const auto &dofs) {
        if (!counted.insert(dofs[0]).second)
          return;
        const double a = areas[scalars.cell(cell)->vertex_dof_index(v, 0)];
        for (unsigned int c = 0; c < spacedim; ++c)
          variation -= a * f[dofs[c]] * general_move(cell->vertex(v))[c];
      });

      const double          epsilon = 1e-5;
      std::array<double, 2> energies{};
      for (const int side : {0, 1})
        {
          set_displacement(surface, Move(side == 0 ? epsilon : -epsilon, general_move));
          const EnergyTerms e = compute_energy(surface, compute_geometry(surface), phi, material);
          energies[side]      = e.gradient + e.well;
        }
      const double derivative = (energies[0] - energies[1]) / (2 * epsilon);
      const double difference = std::abs(derivative - variation) / std::abs(derivative);
      std::cout << n << " cells per side: dE/deps = " << derivative << ", -(f, V)_M = " << variation
                << ", relative difference " << difference << std::endl;
      EXPECT_LT(difference, 1e-7);
    }
}

// The Gaussian energy of the constant part of kappa_G is Gauss-Bonnet's 2 pi chi kappa_G_c, exactly:
// the projected K^m of the scheme integrates to 4 pi only to discretization error, and on a narrow
// neck that error grows with the refinement level. On an ellipsoid (chi = 2) carrying a smooth phi,
// a uniform kappa_G gives 4 pi kappa_G, and shifting both phase values by d shifts the energy by
// 4 pi d, both to round-off.
TEST(GaussianEnergy, ConstantModulusGivesTheGaussBonnetEnergy)
{
  Ellipsoid     ellipsoid(8);
  Surface      &surface = ellipsoid.surface;
  EXPECT_EQ(surface.euler_characteristic(), 2);
  const auto   &scalars   = surface.scalar_space();
  Vector        phi_owned = scalars.make_owned();
  for_each_free_vertex(scalars, [&](const auto &cell, const unsigned int v, const auto &dofs) {
    phi_owned[dofs[0]] = 0.8 * std::tanh(cell->vertex(v)[0] / 0.4);
  });
  phi_owned.compress(dealii::VectorOperation::insert);
  const Vector   phi      = scalars.ghosted_copy(phi_owned);
  const Geometry geometry = compute_geometry(surface);
  const auto gaussian_energy = [&](const double phase_a, const double phase_b) {
    Material m;
    m.bending_rigidity      = make_linear_law(1, 1);
    m.spontaneous_curvature = make_linear_law(0, 0);
    m.gaussian_rigidity     = make_linear_law(phase_a, phase_b);
    return compute_energy(surface, geometry, phi, m).gaussian;
  };
  const double projected_total_curvature = integrate(surface, geometry.gauss_curvature);
  std::cout << "integral K^m ds = " << projected_total_curvature << " (4 pi = " << 4 * M_PI << ")" << std::endl;
  EXPECT_GT(std::abs(projected_total_curvature - 4 * M_PI), 1e-6); // so that the checks below can fail
  EXPECT_NEAR(gaussian_energy(-0.7, -0.7), 4 * M_PI * -0.7, 1e-12);
  EXPECT_NEAR(gaussian_energy(1.2, 0.2) - gaussian_energy(0.5, -0.5), 4 * M_PI * 0.7, 1e-12);
  EXPECT_NE(gaussian_energy(0.5, -0.5), 0.0); // the phase-dependent part remains

  Triangulation patch_mesh(MPI_COMM_WORLD);
  make_periodic_unit_square(patch_mesh, 4);
  Surface patch(patch_mesh, true);
  EXPECT_EQ(patch.euler_characteristic(), 0); // a torus
}
