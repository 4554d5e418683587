// Shape step, assembly: the seven (or five) rows of the shape system on Gamma^m, with the energy
// terms' normal stiffness and force, the tangential law, the stabilized area rows, the curvature
// rows and the thermal noise (the equations are in shape_solver.h). Part of ShapeSolver.
#include <membrane/physics/free_energy.h>
#include <membrane/physics/stress_force.h>
#include <membrane/physics/tangential_noise.h>
#include <membrane/shape_solver.h>
#include <membrane/solvers/cell_assembly.h>
#include <membrane/solvers/vector_access.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <array>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    constexpr unsigned int pressure_component = ShapeComponents::pressure, curvature_component = ShapeComponents::curvature,
                           first_tangent_component = ShapeComponents::first_tangent;
    /// Fixes the constant pressure where H = 0 (see the header); dimensionless.
    constexpr double pressure_regularization = 1e-12;

    /// Frozen data of Gamma^m at one quadrature point.
    struct PointData
    {
      Tensor<1, spacedim> nu, grad_phi, tangent[2], unit_tangent[2];
      /// tau L_X eta, the thermal displacement density (0 at k_BT = 0): its part along nu in the
      /// normal row, and in the tangential law and its residual either eta itself or, with the
      /// split of the ALE scheme, grad_s chi (physics/tangential_noise.h).
      double              normal_noise = 0;
      Tensor<1, spacedim> tangential_noise;
      Tensor<1, spacedim> stress_force; ///< f of the stress terms (read only with Line force = stress)
      double              H = 0, Y = 0;
      NormalStiffness     stiffness; ///< of the energy terms (physics/free_energy.h)
      ShapeForce          force;
    };
  } // namespace


  void ShapeSolver::assemble(const Surface &surface, const Geometry &geometry, const Material &material,
                             const ShapeOptions &options, const double tau, const Vector &phi,
                             const Vector &potential, const ThermalNoise &noise)
  {
    matrix = 0;
    rhs    = 0;
    const QGauss<dim>       quadrature(2);
    const unsigned int      n_q = quadrature.size(), n_dofs = space.fe().n_dofs_per_cell();
    FEValues<dim, spacedim> fe_values(surface.mapping(), space.fe(), quadrature,
                                      update_values | update_gradients | update_JxW_values | update_jacobians);
    FEValues<dim, spacedim> scalar_values(surface.mapping(), surface.scalar_space().fe(), quadrature,
                                          update_values | update_gradients);
    FEValues<dim, spacedim> vector_values(surface.mapping(), surface.vector_space().fe(), quadrature,
                                          update_values | update_gradients);
    const FEValuesExtractors::Vector all_components(0);

    std::vector<double>              phi_q(n_q), H_q(n_q), K_q(n_q), Y_q(n_q);
    std::vector<Tensor<1, spacedim>> grad_phi_q(n_q), nu_q(n_q);
    std::vector<Tensor<2, spacedim>> grad_nu_q(n_q);
    std::vector<Tensor<1, spacedim>> stress_force_q(n_q), grad_chi_q(n_q);
    std::vector<PointData>           data(n_q);
    // Unit normals and tangent frames at the cell's vertices (closed surfaces and the
    // lumped curvature mass, see below).
    const FieldSpace &vectors = surface.vector_space();
    dealii::Vector<double>           normal_dofs(vectors.fe().n_dofs_per_cell());
    std::vector<Tensor<1, spacedim>> vertex_normal(GeometryInfo<dim>::vertices_per_cell);
    std::vector<std::array<Tensor<1, spacedim>, 2>> vertex_frame(GeometryInfo<dim>::vertices_per_cell);
    const bool lumped  = curvature_mass != CurvatureMass::consistent;
    const bool reduced = curvature_mass == CurvatureMass::lumped;
    std::vector<unsigned int>        vertex_of(n_dofs);
    for (unsigned int i = 0; i < n_dofs; ++i)
      vertex_of[i] = space.fe().system_to_component_index(i).second;
    std::vector<unsigned int>        component(n_dofs);
    std::vector<double>              value(n_dofs);
    std::vector<Tensor<1, spacedim>> gradient(n_dofs);
    for (unsigned int i = 0; i < n_dofs; ++i)
      component[i] = space.fe().system_to_component_index(i).first;
    FullMatrix<double>               local_matrix(n_dofs, n_dofs);
    dealii::Vector<double>           local_rhs(n_dofs);
    std::vector<types::global_dof_index> dof_indices(n_dofs);

    FreeEnergy terms(material);
    terms.prepare(surface, geometry);
    TermPoint point;
    const double tauL  = tau * material.shape_mobility;
    const double delta = options.pressure_stabilization;
    // Weight of the linearized gradient energy in the tangential law (see below).
    const double line_stiffness = options.line_stiffness * tauL * terms.tangential_stiffness_weight();
    // Line force = stress: the stress terms' force f = -M_L^-1 dF/dX replaces their potential
    // form in the normal row and their part of Y grad phi in the tangential law.
    const bool   stress_form = options.line_force == LineForce::stress;
    const Vector stress      = stress_form ? stress_force(surface, phi, terms) : Vector();

    // The tangential law is tested, and the tangential part B~ of the curvature vector
    // expanded, along two tangent directions per vertex. On the periodic patch these are
    // the parameter directions a_k of the cell, the same in every cell. On a closed
    // mesh the cells' parameter axes turn from one cube face to the next: around a cube
    // corner (three cells) the a_k of the cells nearly cancel in the vertex's row, so
    // that row no longer holds the vertex's tangential motion. There each vertex gets
    // its own orthonormal frame of the plane normal to its vertex normal.
    const auto frame = [&](const unsigned int j, const unsigned int k, const PointData &d) -> Tensor<1, spacedim> {
      return periodic ? d.unit_tangent[k] : vertex_frame[vertex_of[j]][k];
    };
    const auto test_tangent = [&](const unsigned int i, const unsigned int k, const PointData &d) -> Tensor<1, spacedim> {
      return periodic ? d.tangent[k] : vertex_frame[vertex_of[i]][k];
    };
    CellAssembler assembler(space.constraints(), matrix);
    for (const auto &cell : space.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          scalar_values.reinit(surface.scalar_space().cell(cell));
          vector_values.reinit(surface.vector_space().cell(cell));
          scalar_values.get_function_values(phi, phi_q);
          scalar_values.get_function_gradients(phi, grad_phi_q);
          scalar_values.get_function_values(geometry.mean_curvature, H_q);
          scalar_values.get_function_values(geometry.gauss_curvature, K_q);
          scalar_values.get_function_values(potential, Y_q);
          vector_values[all_components].get_function_values(geometry.normal, nu_q);
          vector_values[all_components].get_function_gradients(geometry.normal, grad_nu_q);
          if (stress_form)
            vector_values[all_components].get_function_values(stress, stress_force_q);
          if (noise.active() && noise.tangential_potential)
            scalar_values.get_function_gradients(*noise.tangential_potential, grad_chi_q);
          if (!periodic || lumped)
            {
              vectors.cell(cell)->get_dof_values(geometry.normal, normal_dofs);
              for (unsigned int v = 0; v < GeometryInfo<dim>::vertices_per_cell; ++v)
                {
                  Tensor<1, spacedim> nu;
                  for (unsigned int i = 0; i < normal_dofs.size(); ++i)
                    if (vectors.fe().system_to_component_index(i).second == v)
                      nu[vectors.fe().system_to_component_index(i).first] = normal_dofs[i];
                  vertex_normal[v] = nu / nu.norm();
                  vertex_frame[v]  = tangent_frame(nu);
                }
            }
          // Reference edge lengths turn the unit-cell Jacobian into a_k = dX/du_k.
          const auto reference_length = reference_edge_lengths(cell);

          for (unsigned int q = 0; q < n_q; ++q)
            {
              PointData &d = data[q];
              d.nu         = nu_q[q];
              d.grad_phi   = grad_phi_q[q];
              d.H          = H_q[q];
              d.Y          = Y_q[q];
              const auto tangents = parameter_tangents(fe_values.jacobian(q), reference_length);
              for (unsigned int k = 0; k < 2; ++k)
                {
                  d.tangent[k]      = tangents[k];
                  d.unit_tangent[k] = tangents[k] / tangents[k].norm();
                }
              // The energy terms' normal-row coefficients (physics/terms/).
              point.phi      = phi_q[q];
              point.H        = H_q[q];
              point.K        = K_q[q];
              point.grad_phi = grad_phi_q[q];
              point.nu       = nu_q[q];
              point.grad_nu  = grad_nu_q[q];
              d.stiffness    = terms.normal_stiffness(point);
              d.force        = terms.shape_force(point, stress_form);
              if (stress_form)
                {
                  // The normal row takes f . nu; the tangential law Y grad phi of the other
                  // terms (their explicit potentials) plus f.
                  d.force.source += stress_force_q[q] * nu_q[q];
                  d.Y            = terms.potential(point);
                  d.stress_force = stress_force_q[q];
                }
              // Thermal force, times tau L_X: standard deviation sqrt(2 k_BT tau L_X / w_q) per component.
              if (noise.active())
                {
                  const Tensor<1, spacedim> eta = shape_noise(noise, tauL, cell_key(cell->id()), q, fe_values.JxW(q));
                  d.normal_noise                = eta * nu_q[q];
                  d.tangential_noise            = noise.tangential_potential ? grad_chi_q[q] : eta;
                }
            }

          local_matrix = 0;
          local_rhs    = 0;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const PointData &d  = data[q];
              const double     ds = fe_values.JxW(q);
              // Q1 system: every shape function is one component's hat function.
              for (unsigned int i = 0; i < n_dofs; ++i)
                {
                  value[i]    = fe_values.shape_value(i, q);
                  gradient[i] = fe_values.shape_grad(i, q);
                }
              for (unsigned int i = 0; i < n_dofs; ++i)
                {
                  const unsigned int         ci       = component[i];
                  const double               psi      = value[i] * ds;
                  const Tensor<1, spacedim>  grad_psi = gradient[i] * ds;
                  const Tensor<1, spacedim> &nu_i     = vertex_normal[vertex_of[i]];
                  // The row's equation: with five fields the W_1, W_2 rows hold the tangential law.
                  const bool tangential_row = reduced ? (ci == 1 || ci == 2) : ci >= first_tangent_component;
                  const unsigned int tangent_k =
                    !tangential_row ? 0 : reduced ? ci - 1 : ci - first_tangent_component; // k of a tangential row
                  for (unsigned int j = 0; j < n_dofs; ++j)
                    {
                      const unsigned int         cj = component[j];
                      const double               v  = value[j];
                      const Tensor<1, spacedim> &gv = gradient[j];
                      const bool                 same_vertex = vertex_of[j] == vertex_of[i];
                      double                     a  = 0;
                      if (reduced && ci == 0) // curvature row along nu_i, lumped mass
                        {
                          if (cj < spacedim)
                            a = nu_i[cj] * (gv * grad_psi); // sum_c nu_i,c (grad_s W_c, grad_s psi)
                          else if (cj == curvature_component && same_vertex)
                            a = psi; // a_i H~_i
                        }
                      else if (ci < spacedim && !tangential_row) // curvature row, psi_vec = psi e_ci
                        {
                          if (cj == ci)
                            a = gv * grad_psi; // (grad_s W, grad_s psi_vec)
                          else if (lumped) // a_i (H~_i nu_i + B~_k,i t_k,i) . e_ci
                            {
                              if (same_vertex && cj == curvature_component)
                                a = nu_i[ci] * psi;
                              else if (same_vertex && cj >= first_tangent_component)
                                a = vertex_frame[vertex_of[i]][cj - first_tangent_component][ci] * psi;
                            }
                          else if (cj == curvature_component)
                            a = v * d.nu[ci] * psi;
                          else if (cj >= first_tangent_component)
                            a = v * frame(j, cj - first_tangent_component, d)[ci] * psi;
                        }
                      else if (ci == pressure_component) // area row
                        {
                          if (cj < spacedim)
                            a = gv[cj] * psi + delta * v * grad_psi[cj]; // div_s W psi + delta W . grad psi
                          else if (cj == pressure_component)
                            a = -delta * tauL * (gv * grad_psi) - pressure_regularization * v * psi;
                        }
                      else if (ci == curvature_component) // normal row
                        {
                          if (cj < spacedim)
                            a = v * d.nu[cj] * psi;
                          else if (cj == curvature_component)
                            a = -tauL * d.stiffness.kappa * (gv * grad_psi + d.stiffness.curvature_mass * v * psi);
                          else if (cj == pressure_component)
                            a = -tauL * d.H * v * psi;
                        }
                      else // tangential row k
                        {
                          const Tensor<1, spacedim> &t = test_tangent(i, tangent_k, d);
                          if (cj < spacedim)
                            // W . t psi, and the force's change under the move: the frozen phi
                            // profile stretched by W changes grad phi by -(grad_s W)^T grad phi,
                            // so tau L_X times -d/dW of (sigma xi^2 / 2)|grad phi|^2 adds
                            // + tau L_X sigma xi^2 ((grad_s W)^T grad phi, (grad_s V)^T grad phi)
                            // with V = psi t, (grad_s V)^T grad phi = (t . grad phi) grad_s psi.
                            a = v * t[cj] * psi +
                                line_stiffness * d.grad_phi[cj] * (t * d.grad_phi) * (gv * grad_psi);
                          else if (cj == pressure_component)
                            a = -tauL * (gv * t) * psi;
                        }
                      local_matrix(i, j) += a;
                    }

                  double b = 0;
                  if (tangential_row) // + tau L_X (Y grad phi + eta, psi a_k)
                    b = tauL * d.Y * (d.grad_phi * test_tangent(i, tangent_k, d)) * psi +
                        (d.tangential_noise * test_tangent(i, tangent_k, d)) * psi;
                  else if (reduced && ci == 0)
                    b = -(nu_i * grad_psi); // -(nu_i . grad_s X^m, grad_s psi)
                  else if (ci < spacedim)
                    b = -grad_psi[ci]; // -(grad_s X^m, grad_s psi_vec)
                  else if (ci == pressure_component) // + a_target - a^m: add_area_defect()
                    b = delta * tauL * d.Y * (d.grad_phi * grad_psi) + delta * (d.tangential_noise * grad_psi);
                  else // normal row, + tau L_X (eta, psi nu)
                    b = tauL * (d.force.flux * grad_psi + d.force.source * psi) + d.normal_noise * psi;
                  // Line force = stress: + tau L_X (f, psi a_k) in the tangential law and its residual
                  // + delta tau L_X (f, grad psi) in the area row (f . nu is in the normal row's source).
                  if (stress_form && tangential_row)
                    b += tauL * (d.stress_force * test_tangent(i, tangent_k, d)) * psi;
                  else if (stress_form && ci == pressure_component)
                    b += delta * tauL * (d.stress_force * grad_psi);
                  local_rhs(i) += b;
                }
            }
          cell->get_dof_indices(dof_indices);
          assembler.add(local_matrix, local_rhs, dof_indices, rhs);
        }
    matrix.compress(VectorOperation::add);
    rhs.compress(VectorOperation::add);
  }
} // namespace Membrane
