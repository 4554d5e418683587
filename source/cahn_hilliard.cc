#include <membrane/cahn_hilliard.h>
#include <membrane/solvers/cell_assembly.h>
#include <membrane/physics/double_well.h>
#include <membrane/physics/free_energy.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <optional>

namespace Membrane
{
  using namespace dealii;

  CahnHilliardSolver::CahnHilliardSolver(const Triangulation &triangulation, const bool periodic)
    : periodic(periodic)
    , space(triangulation, 2)
  {}

  void CahnHilliardSolver::setup()
  {
    space.setup(periodic);
    space.reinit_matrix(matrix);
    rhs = space.make_owned();
    solver.reset(); // the mesh (and so the pattern) changed
  }

  void CahnHilliardSolver::assemble(const Surface &surface, const Geometry &geometry, const Material &material,
                                    const CahnHilliardOptions &options, const double tau, const Vector &phi_old,
                                    const ThermalNoise &noise)
  {
    matrix = 0;
    rhs    = 0;
    const QGauss<dim>       quadrature(2);
    // The tangent frame of the noise needs the Jacobian and the normal; only then are they computed.
    const UpdateFlags flags = update_values | update_gradients | update_JxW_values |
                              (noise.active() ? update_jacobians | update_normal_vectors : update_default);
    FEValues<dim, spacedim> fe_values(surface.mapping(), space.fe(), quadrature, flags);
    FEValues<dim, spacedim> field_values(surface.mapping(), surface.scalar_space().fe(), quadrature, update_values);
    const FEValuesExtractors::Scalar phi_part(0), potential_part(1);

    const unsigned int n_q = quadrature.size(), n_dofs = space.fe().n_dofs_per_cell();
    std::vector<double> old(n_q), H(n_q), K(n_q);
    FullMatrix<double>  local_matrix(n_dofs, n_dofs);
    dealii::Vector<double> local_rhs(n_dofs);
    std::vector<types::global_dof_index> dof_indices(n_dofs);

    const double sigma = material.line_tension, xi2 = std::pow(material.transition_length, 2);
    const double mobility = material.phase_mobility;
    // The line energy's part of Y is this step's operator; the other terms' parts are explicit.
    const FreeEnergy terms(material);
    TermPoint        curvature_point;
    // Conserved noise (model B, MODEL.md section 10), in the mass row times tau:
    // + sqrt(2 k_BT L_phi tau) (zeta_h, grad_s psi), zeta_h constant per cell, two independent
    // normals along an orthonormal tangent frame scaled by 1/sqrt(|cell|). A constant psi has no
    // gradient, so integral phi ds is kept exactly.
    const double noise_scale = noise.active() ? std::sqrt(2 * noise.temperature * mobility * tau) : 0.0;
    // The implicit coefficient S of the scheme (see the header), per quadrature point.
    const bool   linearized = options.scheme == "linearized";
    const double constant_S = options.scheme == "stabilized" ? options.stabilization : 0.0;

    CellAssembler assembler(space.constraints(), matrix);
    for (const auto &cell : space.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          field_values.reinit(surface.scalar_space().cell(cell));
          field_values.get_function_values(phi_old, old);
          field_values.get_function_values(geometry.mean_curvature, H);
          field_values.get_function_values(geometry.gauss_curvature, K);
          local_matrix = 0;
          local_rhs    = 0;
          Tensor<1, spacedim> zeta;
          if (noise.active())
            {
              double area = 0;
              for (unsigned int q = 0; q < n_q; ++q)
                area += fe_values.JxW(q);
              // The frame at the cell's first quadrature point: t_1 along a_1, t_2 = n x t_1.
              Tensor<1, spacedim> t1;
              for (unsigned int d = 0; d < spacedim; ++d)
                t1[d] = fe_values.jacobian(0)[d][0];
              t1 /= t1.norm();
              const Tensor<1, spacedim> t2  = cross_product_3d(fe_values.normal_vector(0), t1);
              const std::uint64_t       key = cell_key(cell->id());
              zeta = (standard_normal(noise.seed, noise.step, key, 0) * t1 +
                      standard_normal(noise.seed, noise.step, key, 1) * t2) *
                     (noise_scale / std::sqrt(area));
            }
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const double S = linearized ? DoubleWell::second_derivative(old[q]) : constant_S;
              // Explicit part of Y: sigma (f'(phi^m) - S phi^m) + curvature coupling.
              curvature_point.phi = old[q];
              curvature_point.H   = H[q];
              curvature_point.K   = K[q];
              const double explicit_potential = sigma * (DoubleWell::derivative(old[q]) - S * old[q]) +
                                                terms.potential(curvature_point);
              const double ds = fe_values.JxW(q);
              for (unsigned int i = 0; i < n_dofs; ++i)
                {
                  const double              psi      = fe_values[phi_part].value(i, q);
                  const Tensor<1, spacedim> grad_psi = fe_values[phi_part].gradient(i, q);
                  const double              chi      = fe_values[potential_part].value(i, q);
                  const Tensor<1, spacedim> grad_chi = fe_values[potential_part].gradient(i, q);
                  for (unsigned int j = 0; j < n_dofs; ++j)
                    {
                      const double              phi_j      = fe_values[phi_part].value(j, q);
                      const Tensor<1, spacedim> grad_phi_j = fe_values[phi_part].gradient(j, q);
                      const double              Y_j        = fe_values[potential_part].value(j, q);
                      const Tensor<1, spacedim> grad_Y_j   = fe_values[potential_part].gradient(j, q);
                      // Mass row (times tau): (phi~, psi) + tau L_phi (grad Y, grad psi).
                      // Potential row: (Y, chi) - sigma xi^2 (grad phi~, grad chi) - sigma S (phi~, chi).
                      local_matrix(i, j) += (psi * phi_j + tau * mobility * grad_psi * grad_Y_j + chi * Y_j -
                                             sigma * xi2 * grad_chi * grad_phi_j - sigma * S * chi * phi_j) * ds;
                    }
                  local_rhs(i) += (psi * old[q] + chi * explicit_potential + zeta * grad_psi) * ds;
                }
            }
          cell->get_dof_indices(dof_indices);
          assembler.add(local_matrix, local_rhs, dof_indices, rhs);
        }
    matrix.compress(VectorOperation::add);
    rhs.compress(VectorOperation::add);
  }

  unsigned int CahnHilliardSolver::step(const Surface &surface, const Geometry &geometry, const Material &material,
                                        const CahnHilliardOptions &options, const LinearSolverOptions &solver_options,
                                        const double tau, const Vector &phi_old, Vector &phi_new,
                                        Vector &chemical_potential, TimerOutput *timer,
                                        const ThermalNoise &noise)
  {
    {
      std::optional<TimerOutput::Scope> scope;
      if (timer)
        scope.emplace(*timer, "Cahn-Hilliard assembly");
      assemble(surface, geometry, material, options, tau, phi_old, noise);
    }
    Vector       solution   = space.make_owned();
    unsigned int iterations = 0;
    {
      std::optional<TimerOutput::Scope> scope;
      if (timer)
        scope.emplace(*timer, "Cahn-Hilliard solve");
      if (!solver)
        {
          // Type = block preconditions the shape system only; the two-field
          // Cahn-Hilliard system keeps its LU.
          LinearSolverOptions own = solver_options;
          if (own.type == "block")
            own.type = "direct";
          solver = std::make_unique<LinearSolver>(own, "cahn_hilliard_");
        }
      iterations = solver->solve(matrix, solution, rhs);
    }
    space.constraints().distribute(solution);
    const Vector solution_ghosted = space.ghosted_copy(solution);
    copy_component(space, solution_ghosted, 0, surface.scalar_space(), phi_new);
    copy_component(space, solution_ghosted, 1, surface.scalar_space(), chemical_potential);
    return iterations;
  }
} // namespace Membrane
