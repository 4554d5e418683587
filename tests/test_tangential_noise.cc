// The Helmholtz split of the shape step's tangential noise (physics/tangential_noise.h): the
// irrotational part grad_s chi enters the shape step, the solenoidal part n x grad_s psi only
// carries the lipids.
#include <membrane/physics/tangential_noise.h>
#include <membrane/surface/geometry.h>
#include <membrane/surface/initial_shapes.h>
#include <membrane/surface/mesh_motion.h>

#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/numerics/vector_tools.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace Membrane;
using dealii::Point;
using dealii::Tensor;

namespace
{
  /// Norms and inner products of the two parts on the current surface.
  struct SplitMeasures
  {
    double irrotational = 0; ///< ||grad_s chi||^2
    double solenoidal   = 0; ///< ||n x grad_s psi||^2
    double overlap      = 0; ///< (grad_s chi, n x grad_s psi)
    double divergence   = 0; ///< max_i |(n x grad_s psi, grad_s chi_i)|
    double divergence_scale = 0; ///< max_i of sum over the cells of |n x grad_s psi| |grad_s chi_i|
  };

  SplitMeasures measure(const Surface &surface, const TangentialNoise &split)
  {
    using namespace dealii;
    const FieldSpace       &scalars = surface.scalar_space();
    const QGauss<dim>       quadrature(2);
    FEValues<dim, spacedim> fe_values(surface.mapping(), scalars.fe(), quadrature,
                                      update_values | update_gradients | update_JxW_values | update_jacobians);
    FEValues<dim, spacedim> vector_values(surface.mapping(), surface.vector_space().fe(), quadrature, update_values);
    const Membrane::Vector  normal = surface.vector_space().ghosted_copy(compute_vertex_normals(surface));
    std::vector<Tensor<1, spacedim>> grad_chi(4), grad_psi(4), nu(4);
    Membrane::Vector divergence = scalars.make_owned(), scale = scalars.make_owned();
    dealii::Vector<double>               local(4), local_scale(4);
    std::vector<types::global_dof_index> dofs(4);
    SplitMeasures                        m;
    for (const auto &cell : scalars.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          vector_values.reinit(surface.vector_space().cell(cell));
          vector_values[FEValuesExtractors::Vector(0)].get_function_values(normal, nu);
          fe_values.get_function_gradients(split.potential, grad_chi);
          fe_values.get_function_gradients(split.stream, grad_psi);
          local       = 0;
          local_scale = 0;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              const Tensor<1, spacedim> rotated =
                cross_product_3d(oriented_cell_normal(fe_values.jacobian(q), nu[q]), grad_psi[q]);
              const double ds = fe_values.JxW(q);
              m.irrotational += grad_chi[q].norm_square() * ds;
              m.solenoidal += rotated.norm_square() * ds;
              m.overlap += grad_chi[q] * rotated * ds;
              for (unsigned int i = 0; i < 4; ++i)
                {
                  local(i) += rotated * fe_values.shape_grad(i, q) * ds;
                  local_scale(i) += rotated.norm() * fe_values.shape_grad(i, q).norm() * ds;
                }
            }
          cell->get_dof_indices(dofs);
          scalars.constraints().distribute_local_to_global(local, dofs, divergence);
          scalars.constraints().distribute_local_to_global(local_scale, dofs, scale);
        }
    divergence.compress(VectorOperation::add);
    scale.compress(VectorOperation::add);
    const MPI_Comm comm = scalars.communicator();
    m.irrotational      = Utilities::MPI::sum(m.irrotational, comm);
    m.solenoidal        = Utilities::MPI::sum(m.solenoidal, comm);
    m.overlap           = Utilities::MPI::sum(m.overlap, comm);
    m.divergence        = divergence.linfty_norm();
    m.divergence_scale  = scale.linfty_norm();
    return m;
  }

  void make_unit_sphere(Triangulation &tria, const unsigned int refinements)
  {
    dealii::GridGenerator::hyper_sphere(tria, Point<spacedim>(), 1.0);
    tria.set_all_manifold_ids(0);
    tria.set_manifold(0, dealii::SphericalManifold<dim, spacedim>());
    tria.refine_global(refinements);
  }
} // namespace

// For white tangential noise of covariance 2 k_BT tau L_X (a, b) the projections on the Q1
// gradients and on the rotated Q1 gradients have expected squared norms 2 k_BT tau L_X (N - 1)
// each (N vertices; the constants have no gradient). The solenoidal part is weakly
// divergence-free to round-off, (n x grad_s psi, grad_s q) = 0, and orthogonal to grad_s chi, on
// the cube-sphere (whose cells do not share an orientation) and on a curved periodic patch.
TEST(TangentialNoise, SplitIsOrthogonalDivergenceFreeAndHasTheWhiteNoisesSize)
{
  ThermalNoise noise;
  noise.temperature       = 0.05;
  const double tau_mobility = 1e-4;
  for (const bool periodic : {false, true})
    {
      Triangulation tria(MPI_COMM_WORLD);
      if (periodic)
        make_periodic_unit_square(tria, 24);
      else
        make_unit_sphere(tria, 3);
      Surface surface(tria, periodic);
      surface.setup();
      if (periodic)
        set_cosine_modes(surface, {{0.08, 1, 1, 0}, {0.03, 2, 1, 0.4}});
      const Vector normal   = surface.vector_space().ghosted_copy(compute_vertex_normals(surface));
      const double n_modes  = surface.scalar_space().dof_handler().n_dofs() -
                             surface.scalar_space().constraints().n_constraints() - 1.0;
      double       irrotational = 0, solenoidal = 0;
      const unsigned int samples = 8;
      for (unsigned int s = 0; s < samples; ++s)
        {
          noise.step                  = s;
          const TangentialNoise split = split_tangential_noise(surface, normal, noise, tau_mobility);
          const SplitMeasures   m     = measure(surface, split);
          EXPECT_LT(m.divergence, 1e-12 * m.divergence_scale) << periodic;
          EXPECT_LT(std::abs(m.overlap), 1e-10 * std::sqrt(m.irrotational * m.solenoidal)) << periodic;
          irrotational += m.irrotational;
          solenoidal += m.solenoidal;
        }
      const double expected = samples * 2 * noise.temperature * tau_mobility * n_modes;
      std::cout << (periodic ? "patch" : "sphere") << ": " << n_modes << " modes, irrotational "
                << irrotational / expected << ", solenoidal " << solenoidal / expected << " of the expected size"
                << std::endl;
      // Chi-squared with samples (N - 1) degrees of freedom: relative deviation about 2-3 %.
      EXPECT_NEAR(irrotational / expected, 1, 0.1) << periodic;
      EXPECT_NEAR(solenoidal / expected, 1, 0.1) << periodic;
    }
}

// The lipids' solenoidal motion alone (no mesh motion, no relative displacement) carries a
// uniform phi unchanged and conserves integral phi ds of a profile to round-off, however large.
TEST(TangentialNoise, SolenoidalTransportKeepsAUniformFieldAndConservesMass)
{
  Triangulation tria(MPI_COMM_WORLD);
  make_unit_sphere(tria, 3);
  Surface surface(tria, false);
  surface.setup();
  ThermalNoise noise;
  noise.temperature = 0.05;
  const Vector          normal = surface.vector_space().ghosted_copy(compute_vertex_normals(surface));
  const TangentialNoise split  = split_tangential_noise(surface, normal, noise, 1e-4);
  const FieldSpace     &scalars = surface.scalar_space();
  Vector uniform = scalars.make_owned(), profile = scalars.make_owned();
  uniform = 0.3;
  dealii::VectorTools::interpolate(surface.mapping(), scalars.dof_handler(),
                                   dealii::ScalarFunctionFromFunctionObject<spacedim>(
                                     [](const Point<spacedim> &x) { return std::tanh(x[2] / 0.3); }),
                                   profile);
  Vector       ghosted_uniform = scalars.ghosted_copy(uniform), ghosted_profile = scalars.ghosted_copy(profile);
  const double mass  = integrate(surface, ghosted_profile);
  const Vector still = surface.vector_space().make_owned();
  // About half a cell of solenoidal displacement (the transport's substep).
  const double scale = 0.5 * (M_PI / 16) / split.max_stream_displacement;
  move_and_transport(surface, still, still, {&ghosted_uniform, &ghosted_profile}, &split.stream, scale);
  Vector change = scalars.make_owned();
  change        = ghosted_uniform;
  change.add(-0.3);
  Vector moved = scalars.make_owned(), before = scalars.make_owned();
  moved  = ghosted_profile;
  before = profile;
  moved -= before;
  std::cout << "uniform field change " << change.linfty_norm() << ", profile change " << moved.linfty_norm()
            << ", mass change " << integrate(surface, ghosted_profile) - mass << std::endl;
  EXPECT_LT(change.linfty_norm(), 1e-13);
  EXPECT_GT(moved.linfty_norm(), 1e-2); // the profile did move
  EXPECT_LT(std::abs(integrate(surface, ghosted_profile) - mass), 1e-13);
}
