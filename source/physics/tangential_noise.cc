// The shape step's thermal force at a quadrature point and the Helmholtz split of its tangential
// part (physics/tangential_noise.h).
#include <membrane/physics/tangential_noise.h>
#include <membrane/solvers/cell_assembly.h>
#include <membrane/solvers/linear_solver.h>
#include <membrane/surface/geometry.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <cmath>

namespace Membrane
{
  using namespace dealii;

  Tensor<1, spacedim> shape_noise(const ThermalNoise &noise, const double tau_mobility, const std::uint64_t key,
                                  const unsigned int q, const double JxW)
  {
    const double        scale = std::sqrt(2 * noise.temperature * tau_mobility / JxW);
    Tensor<1, spacedim> eta;
    for (unsigned int c = 0; c < spacedim; ++c)
      eta[c] = scale * standard_normal(noise.seed, noise.step, key, first_shape_noise_component + spacedim * q + c);
    return eta;
  }

  TangentialNoise split_tangential_noise(const Surface &surface, const Vector &normal, const ThermalNoise &noise,
                                         const double tau_mobility)
  {
    const FieldSpace       &scalars = surface.scalar_space();
    const FieldSpace       &vectors = surface.vector_space();
    const QGauss<dim>       quadrature(2); // the shape assembly's points: the same variates
    FEValues<dim, spacedim> fe_values(surface.mapping(), scalars.fe(), quadrature,
                                      update_values | update_gradients | update_JxW_values | update_jacobians);
    FEValues<dim, spacedim> vector_values(surface.mapping(), vectors.fe(), quadrature, update_values);
    const FEValuesExtractors::Vector all_components(0);
    std::vector<Tensor<1, spacedim>> nu_q(quadrature.size());
    const unsigned int               n_dofs = scalars.fe().n_dofs_per_cell();
    FullMatrix<double>               local_matrix(n_dofs, n_dofs);
    dealii::Vector<double>           local_chi(n_dofs), local_psi(n_dofs);
    std::vector<types::global_dof_index> dof_indices(n_dofs);

    SparseMatrix matrix;
    scalars.reinit_matrix(matrix);
    Vector rhs_chi = scalars.make_owned(), rhs_psi = scalars.make_owned();
    // The constants of chi and psi are free on a closed or periodic surface: a mass term
    // far below the smallest nonzero eigenvalue of the Laplacian (about 4 pi^2 / area) fixes them.
    const double  regularization = 1e-6 / surface.area();
    CellAssembler assembler(scalars.constraints(), matrix);
    for (const auto &cell : scalars.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          vector_values.reinit(vectors.cell(cell));
          vector_values[all_components].get_function_values(normal, nu_q);
          const std::uint64_t key = cell_key(cell->id());
          local_matrix            = 0;
          local_chi               = 0;
          local_psi               = 0;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              const double              ds  = fe_values.JxW(q);
              const Tensor<1, spacedim> n   = oriented_cell_normal(fe_values.jacobian(q), nu_q[q]);
              Tensor<1, spacedim>       eta = shape_noise(noise, tau_mobility, key, q, ds);
              eta -= (eta * n) * n; // eta_t
              for (unsigned int i = 0; i < n_dofs; ++i)
                {
                  const Tensor<1, spacedim> &grad_i = fe_values.shape_grad(i, q);
                  local_chi(i) += (eta * grad_i) * ds;                        // (eta_t, grad_s q)
                  local_psi(i) += (eta * cross_product_3d(n, grad_i)) * ds;   // (eta_t, n x grad_s q)
                  for (unsigned int j = 0; j < n_dofs; ++j)
                    local_matrix(i, j) += (grad_i * fe_values.shape_grad(j, q) +
                                           regularization * fe_values.shape_value(i, q) * fe_values.shape_value(j, q)) *
                                          ds;
                }
            }
          cell->get_dof_indices(dof_indices);
          assembler.add(local_matrix, local_chi, dof_indices, rhs_chi);
          scalars.constraints().distribute_local_to_global(local_psi, dof_indices, rhs_psi);
        }
    matrix.compress(VectorOperation::add);
    rhs_chi.compress(VectorOperation::add);
    rhs_psi.compress(VectorOperation::add);

    LinearSolverOptions options;
    options.relative_tolerance = 1e-12;
    LinearSolver solver(options, "tangential_noise_");
    Vector       chi = scalars.make_owned(), psi = scalars.make_owned();
    solver.solve(matrix, chi, rhs_chi);
    solver.solve_again(psi, rhs_psi);
    scalars.constraints().distribute(chi);
    scalars.constraints().distribute(psi);

    TangentialNoise split{scalars.ghosted_copy(chi), scalars.ghosted_copy(psi), 0};
    std::vector<Tensor<1, spacedim>> grad_psi(quadrature.size());
    for (const auto &cell : scalars.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_gradients(split.stream, grad_psi);
          for (const auto &g : grad_psi)
            split.max_stream_displacement = std::max(split.max_stream_displacement, g.norm());
        }
    split.max_stream_displacement = Utilities::MPI::max(split.max_stream_displacement, scalars.communicator());
    return split;
  }
} // namespace Membrane
