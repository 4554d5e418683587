#include <membrane/physics/free_energy.h>
#include <membrane/shape_preconditioner.h>
#include <membrane/shape_solver.h>
#include <membrane/shape_options.h>
#include <membrane/solvers/cell_assembly.h>
#include <membrane/solvers/vector_access.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

#include <cmath>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    constexpr unsigned int pressure_component = ShapeComponents::pressure, curvature_component = ShapeComponents::curvature,
                           first_tangent_component = ShapeComponents::first_tangent;
    /// The lumped vertex integrals, each a scalar-space vector: the mass, then the
    /// three components of integral psi nu, of the two test tangents and of the two
    /// B~ tangents.
    constexpr unsigned int n_lumped = 1 + 3 * 5;
  } // namespace

  void ShapePreconditioner::build(const FieldSpace &system_space, const SparseMatrix &matrix, const Surface &surface,
                                  const Geometry &geometry, const Material &material, const ShapeOptions &options,
                                  const double tau, const Vector &phi, const bool periodic)
  {
    system             = &system_space;
    scalars            = &surface.scalar_space();
    const double tauL  = tau * material.shape_mobility;
    const double delta = options.pressure_stabilization;
    // The implicit parts of the energy terms (physics/free_energy.h): the normal row's
    // stiffness on H~ and the tangential law's line stiffness.
    FreeEnergy terms(material);
    terms.prepare(surface, geometry);
    TermPoint        point;
    const double     line_stiffness = options.line_stiffness * tauL * terms.tangential_stiffness_weight();

    // One pattern per mesh (a new mesh makes a new preconditioner, ShapeSolver::setup).
    for (auto *m : {&mass, &tangential_operator, &stiffness, &bending, &pair_operator, &pressure_schur})
      if (patterns_ready)
        *m = 0;
      else
        scalars->reinit_matrix(*m);
    patterns_ready = true;
    std::array<Vector, n_lumped> lumped;
    for (auto &v : lumped)
      v = scalars->make_owned();

    const QGauss<dim>       quadrature(2);
    const unsigned int      n_q = quadrature.size();
    FEValues<dim, spacedim> fe_values(surface.mapping(), scalars->fe(), quadrature,
                                      update_values | update_gradients | update_JxW_values | update_jacobians);
    FEValues<dim, spacedim> vector_values(surface.mapping(), surface.vector_space().fe(), quadrature, update_values);
    const FEValuesExtractors::Vector all_components(0);
    std::vector<double>              phi_q(n_q), H_q(n_q);
    std::vector<Tensor<1, spacedim>> grad_phi_q(n_q);
    std::vector<Tensor<1, spacedim>> nu_q(n_q);
    const unsigned int               n = scalars->fe().n_dofs_per_cell();
    FullMatrix<double> local_T(n, n), local_M(n, n), local_K(n, n), local_Ke(n, n), local_pair(n, n), local_schur(n, n);
    std::array<dealii::Vector<double>, n_lumped> local_lumped;
    for (auto &v : local_lumped)
      v.reinit(n);
    std::vector<types::global_dof_index> dofs(n);
    CellAssembler add_T(scalars->constraints(), tangential_operator), add_M(scalars->constraints(), mass),
        add_K(scalars->constraints(), stiffness), add_Ke(scalars->constraints(), bending),
        add_pair(scalars->constraints(), pair_operator), add_schur(scalars->constraints(), pressure_schur);

    for (const auto &cell : scalars->dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          vector_values.reinit(surface.vector_space().cell(cell));
          fe_values.get_function_values(phi, phi_q);
          fe_values.get_function_gradients(phi, grad_phi_q);
          fe_values.get_function_values(geometry.mean_curvature, H_q);
          vector_values[all_components].get_function_values(geometry.normal, nu_q);
          const auto reference_length = reference_edge_lengths(cell);
          local_T = 0, local_M = 0, local_K = 0, local_Ke = 0, local_pair = 0, local_schur = 0;
          for (auto &v : local_lumped)
            v = 0;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const double ds     = fe_values.JxW(q);
              point.phi                       = phi_q[q];
              point.H                         = H_q[q];
              const NormalStiffness stiffness = terms.normal_stiffness(point);
              const double          root      = std::sqrt(tauL * stiffness.kappa);
              // The implicit line stiffness of the tangential law (shape_solver/assembly.cc)
              // acts along grad phi; its isotropic bound keeps the tangential block's
              // solve positive definite.
              const double                       line = line_stiffness * grad_phi_q[q].norm_square();
              const auto                         a    = parameter_tangents(fe_values.jacobian(q), reference_length);
              std::array<Tensor<1, spacedim>, 2> unit{{a[0] / a[0].norm(), a[1] / a[1].norm()}};
              for (unsigned int i = 0; i < n; ++i)
                {
                  const double               psi      = fe_values.shape_value(i, q) * ds;
                  const Tensor<1, spacedim> &grad_psi = fe_values.shape_grad(i, q);
                  for (unsigned int j = 0; j < n; ++j)
                    {
                      const double v  = fe_values.shape_value(j, q);
                      const double gg = (fe_values.shape_grad(j, q) * grad_psi) * ds;
                      local_M(i, j) += v * psi;
                      local_T(i, j) += v * psi + line * gg;
                      local_K(i, j) += gg;
                      // Normal row's H~ block, with its sign: -K_e.
                      local_Ke(i, j) += tauL * stiffness.kappa * (gg + stiffness.curvature_mass * v * psi);
                      local_pair(i, j) += v * psi + root * gg;
                      // -S: the tangential law's Darcy flux tau L_X grad gamma with the
                      // stabilization's share, and the normal motion's tau L_X H gamma
                      // fed back through -H W.nu in div_s W.
                      local_schur(i, j) += tauL * ((1 + delta) * gg + H_q[q] * H_q[q] * v * psi);
                    }
                  local_lumped[0](i) += psi;
                  for (unsigned int c = 0; c < spacedim; ++c)
                    {
                      local_lumped[1 + c](i) += psi * nu_q[q][c];
                      for (unsigned int k = 0; k < 2; ++k)
                        {
                          local_lumped[4 + 3 * k + c](i) += psi * a[k][c];
                          local_lumped[10 + 3 * k + c](i) += psi * unit[k][c];
                        }
                    }
                }
            }
          cell->get_dof_indices(dofs);
          add_M.add(local_M, dofs);
          add_T.add(local_T, dofs);
          add_K.add(local_K, dofs);
          add_Ke.add(local_Ke, dofs);
          add_pair.add(local_pair, dofs);
          add_schur.add(local_schur, dofs);
          for (unsigned int l = 0; l < n_lumped; ++l)
            scalars->constraints().distribute_local_to_global(local_lumped[l], dofs, lumped[l]);
        }
    for (auto *m : {&tangential_operator, &mass, &stiffness, &bending, &pair_operator, &pressure_schur})
      m->compress(VectorOperation::add);
    for (auto &v : lumped)
      v.compress(VectorOperation::add);

    dealii::PETScWrappers::PreconditionBoomerAMG::AdditionalData amg;
    amg.symmetric_operator = true;
    pair_amg.initialize(pair_operator, amg);
    mass_jacobi.initialize(mass);
    pressure_amg.initialize(pressure_schur, amg);
    with_line_stiffness = line_stiffness > 0;
    if (with_line_stiffness)
      tangential_amg.initialize(tangential_operator, amg);

    // The free vertices this process owns, with their lumped integrals.
    vertices.clear();
    constrained.clear();
    const Vector normal = geometry.normal; // ghosted
    {
      std::array<std::unique_ptr<LocalValues>, n_lumped> values;
      for (unsigned int l = 0; l < n_lumped; ++l)
        values[l] = std::make_unique<LocalValues>(lumped[l]);
      const LocalValues normal_values(normal);
      std::vector<bool> seen(system->owned().n_elements(), false);
      for (const auto &cell : system->dof_handler().active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int v : cell->vertex_indices())
            {
              const auto first = cell->vertex_dof_index(v, 0);
              if (!system->owned().is_element(first) || system->constraints().is_constrained(first) ||
                  seen[system->owned().index_within_set(first)])
                continue;
              seen[system->owned().index_within_set(first)] = true;
              VertexData data;
              for (unsigned int c = 0; c < 7; ++c)
                data.system[c] = cell->vertex_dof_index(v, c);
              data.scalar       = scalars->cell(cell)->vertex_dof_index(v, 0);
              const double mass = (*values[0])[data.scalar];
              // Averaged directions: the normal, the test tangents of the tangential law and the
              // directions of B~ (integral psi t ds / integral psi ds).
              Tensor<1, spacedim>                normal;
              std::array<Tensor<1, spacedim>, 2> test_tangent, tangent;
              for (unsigned int c = 0; c < spacedim; ++c)
                {
                  normal[c] = (*values[1 + c])[data.scalar] / mass;
                  for (unsigned int k = 0; k < 2; ++k)
                    {
                      test_tangent[k][c] = (*values[4 + 3 * k + c])[data.scalar] / mass;
                      tangent[k][c]      = (*values[10 + 3 * k + c])[data.scalar] / mass;
                    }
                }
              if (!periodic)
                {
                  // Closed surfaces test the tangential law and expand B~ in each
                  // vertex's own orthonormal frame (shape_solver/assembly.cc).
                  Tensor<1, spacedim> nu;
                  const auto          vector_cell = surface.vector_space().cell(cell);
                  for (unsigned int c = 0; c < spacedim; ++c)
                    nu[c] = normal_values[vector_cell->vertex_dof_index(v, c)];
                  const auto frame = tangent_frame(nu);
                  for (unsigned int k = 0; k < 2; ++k)
                    test_tangent[k] = tangent[k] = frame[k];
                }
              data.unit_normal = normal / normal.norm();
              Tensor<2, spacedim> rows, columns;
              for (unsigned int c = 0; c < spacedim; ++c)
                {
                  rows[0][c] = columns[c][0] = normal[c];
                  rows[1][c]                 = test_tangent[0][c];
                  rows[2][c]                 = test_tangent[1][c];
                  columns[c][1]              = tangent[0][c];
                  columns[c][2]              = tangent[1][c];
                }
              data.displacement = invert(rows);
              data.curvature    = invert(columns);
              vertices.push_back(data);
            }
    }
    for (const auto i : system->owned())
      if (system->constraints().is_constrained(i))
        constrained.emplace_back(i, 1.0 / matrix.diag_element(i));

    system_matrix = &matrix;
  }

  void ShapePreconditioner::mass_solve(Vector &x, const Vector &b) const
  {
    // The consistent mass matrix is well conditioned (Jacobi-CG needs about 10 iterations).
    cg_solve(mass, mass_jacobi, x, b);
  }

  void ShapePreconditioner::tangential_solve(Vector &x, const Vector &b) const
  {
    if (with_line_stiffness)
      cg_solve(tangential_operator, tangential_amg, x, b);
    else
      mass_solve(x, b);
  }

  template <typename Preconditioner>
  void ShapePreconditioner::cg_solve(const SparseMatrix &matrix, const Preconditioner &preconditioner, Vector &x,
                                     const Vector &b)
  {
    SolverControl    control(200, 1e-8 * b.l2_norm());
    SolverCG<Vector> cg(control);
    x = 0;
    if (b.l2_norm() > 0)
      cg.solve(matrix, x, b, preconditioner);
  }

  void ShapePreconditioner::update_residual(Vector &rho, const Vector &src, const Vector &z) const
  {
    system_matrix->vmult(rho, z);
    rho.sadd(-1.0, 1.0, src);
  }

  void ShapePreconditioner::vmult(Vector &dst, const Vector &src) const
  {
    Vector z   = system->make_owned();
    Vector rho = src;
    Vector s = scalars->make_owned(), t = scalars->make_owned();

    // 1. gamma from the area rows: -S gamma = -rho_gamma.
    {
      const LocalValues r(rho);
      OwnedValues       sv(s);
      for (const auto &v : vertices)
        sv[v.scalar] = -r[v.system[pressure_component]];
    }
    pressure_amg.vmult(t, s);
    {
      const LocalValues tv(t);
      OwnedValues       zv(z);
      for (const auto &v : vertices)
        zv[v.system[pressure_component]] = tv[v.scalar];
    }
    update_residual(rho, src, z);

    std::array<Vector, 3> a{{scalars->make_owned(), scalars->make_owned(), scalars->make_owned()}};
    std::array<Vector, 3> x{{scalars->make_owned(), scalars->make_owned(), scalars->make_owned()}};
    // 2. The tangential motion from the tangential law, (W.a_k, psi) ~ M (W.a_k):
    // W.a_k = M^-1 rho_k.
    {
      const LocalValues r(rho);
      OwnedValues       a1(a[1]), a2(a[2]);
      for (const auto &v : vertices)
        {
          a1[v.scalar] = r[v.system[first_tangent_component]];
          a2[v.scalar] = r[v.system[first_tangent_component + 1]];
        }
    }
    tangential_solve(x[1], a[1]);
    tangential_solve(x[2], a[2]);
    {
      const LocalValues x1(x[1]), x2(x[2]);
      OwnedValues       zv(z);
      for (const auto &v : vertices)
        {
          Tensor<1, spacedim> b;
          b[1]                        = x1[v.scalar];
          b[2]                        = x2[v.scalar];
          const Tensor<1, spacedim> w = v.displacement * b;
          for (unsigned int c = 0; c < spacedim; ++c)
            zv[v.system[c]] += w[c];
        }
    }
    update_residual(rho, src, z);

    // 3. The normal pair (w_n, H~): [M -K_e; K M] by the preconditioner [M -K_e;
    // K M + 2 K_s]
    //    (header): u = M^-1 f, v = (M + K_s)^-1 (g - K u), y = (M + K_s)^-1 M v,
    //    x = u + M^-1 K_e y.
    {
      const LocalValues r(rho);
      OwnedValues       fv(a[0]), gv(a[1]);
      for (const auto &v : vertices)
        {
          fv[v.scalar]     = r[v.system[curvature_component]];
          double projected = 0;
          for (unsigned int c = 0; c < spacedim; ++c)
            projected += v.unit_normal[c] * r[v.system[c]];
          gv[v.scalar] = projected;
        }
    }
    Vector &u = x[0], &w = x[1], &y = x[2], &t2 = a[2];
    mass_solve(u, a[0]);
    stiffness.vmult(t, u);
    a[1] -= t;
    pair_amg.vmult(w, a[1]);
    mass.vmult(t2, w);
    pair_amg.vmult(y, t2);
    bending.vmult(t, y);
    mass_solve(t2, t);
    u += t2;
    {
      const LocalValues uv(u), yv(y);
      OwnedValues       zv(z);
      for (const auto &v : vertices)
        {
          Tensor<1, spacedim> b;
          b[0]                          = uv[v.scalar];
          const Tensor<1, spacedim> inc = v.displacement * b;
          for (unsigned int c = 0; c < spacedim; ++c)
            zv[v.system[c]] += inc[c];
          zv[v.system[curvature_component]] += yv[v.scalar];
        }
    }
    update_residual(rho, src, z);

    // 4. B~ from the curvature rows, (H~ nu + B~_k t_k, psi e) ~ C M (H~, B~)
    // with the vertex's
    //    averaged directions C = [nu t_1 t_2]: B~ = M^-1 of the tangential part
    //    of C^-1 rho_c. The normal part would correct H~ without the normal law's
    //    balance that step 3 just struck (a change of H~ is a bending force K_e
    //    H~ in the normal row); added, it made the sweep diverge once tau L_X
    //    kappa / h^4 exceeded about 1.
    {
      const LocalValues r(rho);
      OwnedValues       c1(a[1]), c2(a[2]);
      for (const auto &v : vertices)
        {
          Tensor<1, spacedim> b;
          for (unsigned int c = 0; c < spacedim; ++c)
            b[c] = r[v.system[c]];
          const Tensor<1, spacedim> hb = v.curvature * b;
          c1[v.scalar]                 = hb[1];
          c2[v.scalar]                 = hb[2];
        }
    }
    mass_solve(x[1], a[1]);
    mass_solve(x[2], a[2]);
    {
      const LocalValues b1(x[1]), b2(x[2]);
      OwnedValues       zv(z);
      for (const auto &v : vertices)
        {
          zv[v.system[first_tangent_component]] += b1[v.scalar];
          zv[v.system[first_tangent_component + 1]] += b2[v.scalar];
        }
    }
    {
      const LocalValues r(src);
      OwnedValues       zv(z);
      for (const auto &[i, inverse_diagonal] : constrained)
        zv[i] = inverse_diagonal * r[i];
    }
    dst = z;
  }
} // namespace Membrane
