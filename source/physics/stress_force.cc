#include <membrane/physics/stress_force.h>
#include <membrane/solvers/vector_access.h>
#include <membrane/surface/geometry.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

namespace Membrane
{
  using namespace dealii;

  Vector stress_force(const Surface &surface, const Vector &phi_ghosted, const FreeEnergy &terms)
  {
    const FieldSpace &vectors = surface.vector_space();
    const FieldSpace &scalars = surface.scalar_space();
    // The energy's quadrature (physics/energy.cc): the derivative is that of the same sum.
    const QGauss<dim>       quadrature(2);
    FEValues<dim, spacedim> fe_values(surface.mapping(), vectors.fe(), quadrature, update_gradients | update_JxW_values);
    FEValues<dim, spacedim> scalar_values(surface.mapping(), scalars.fe(), quadrature, update_values | update_gradients);
    const unsigned int      n_q = quadrature.size(), n_dofs = vectors.fe().n_dofs_per_cell();
    std::vector<double>     phi_q(n_q);
    std::vector<Tensor<1, spacedim>>     grad_phi_q(n_q);
    dealii::Vector<double>               local(n_dofs);
    std::vector<types::global_dof_index> dof_indices(n_dofs);
    TermPoint                            point;

    // -dF/dX_j,c = -integral T : grad_s (psi_j e_c) ds = -integral T[c] . grad_s psi_j ds.
    Vector gradient = vectors.make_owned();
    for (const auto &cell : vectors.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          scalar_values.reinit(scalars.cell(cell));
          scalar_values.get_function_values(phi_ghosted, phi_q);
          scalar_values.get_function_gradients(phi_ghosted, grad_phi_q);
          local = 0;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              point.phi      = phi_q[q];
              point.grad_phi = grad_phi_q[q];
              const Tensor<2, spacedim> T = terms.stress(point);
              for (unsigned int i = 0; i < n_dofs; ++i)
                {
                  const unsigned int c = vectors.fe().system_to_component_index(i).first;
                  local(i) -= T[c] * fe_values.shape_grad(i, q) * fe_values.JxW(q);
                }
            }
          cell->get_dof_indices(dof_indices);
          vectors.constraints().distribute_local_to_global(local, dof_indices, gradient);
        }
    gradient.compress(VectorOperation::add);

    const Vector area  = scalars.ghosted_copy(vertex_areas(surface));
    const Vector sums  = vectors.ghosted_copy(gradient);
    Vector       force = vectors.make_owned();
    {
      const LocalValues sum(sums), areas(area);
      OwnedValues       out(force);
      for_each_free_vertex(vectors, [&](const auto &cell, const unsigned int v, const auto &dofs) {
        const double a = areas[scalars.cell(cell)->vertex_dof_index(v, 0)];
        for (unsigned int c = 0; c < spacedim; ++c)
          out[dofs[c]] = sum[dofs[c]] / a;
      });
    }
    force.compress(VectorOperation::insert);
    vectors.constraints().distribute(force);
    return vectors.ghosted_copy(force);
  }
} // namespace Membrane
