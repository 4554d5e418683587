#include <membrane/surface/projection.h>
#include <membrane/solvers/vector_access.h>
#include <membrane/surface/geometry.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/fe_values_extractors.h>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    const QGauss<dim> &quadrature()
    {
      static const QGauss<dim> gauss(2);
      return gauss;
    }

    /// Assemble a right-hand side vector of `space` from a per-cell kernel.
    template <typename Kernel>
    Vector assemble_rhs(const Surface &surface, const FieldSpace &space, const UpdateFlags flags,
                        const Kernel &kernel)
    {
      Vector                  rhs = space.make_owned();
      FEValues<dim, spacedim> fe_values(surface.mapping(), space.fe(), quadrature(),
                                        flags | update_JxW_values);
      const unsigned int      n_dofs = space.fe().n_dofs_per_cell();
      dealii::Vector<double>  local(n_dofs);
      std::vector<types::global_dof_index> dof_indices(n_dofs);
      for (const auto &cell : space.dof_handler().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            local = 0;
            kernel(cell, fe_values, local);
            cell->get_dof_indices(dof_indices);
            space.constraints().distribute_local_to_global(local, dof_indices, rhs);
          }
      rhs.compress(VectorOperation::add);
      return rhs;
    }
  } // namespace

  Vector compute_vertex_normals(const Surface &surface)
  {
    const FieldSpace &space = surface.vector_space();
    const FiniteElement<dim, spacedim> &fe = space.fe();
    // Weighted sums integral n phi_i ds: the area-weighted average of the cell
    // normals around vertex i (paper eq. 6.5) with the hat function as weight.
    const Vector sums = space.ghosted_copy(assemble_rhs(
      surface, space, update_values | update_normal_vectors,
      [&](const auto &, const FEValues<dim, spacedim> &fe_values, dealii::Vector<double> &local) {
        for (const unsigned int q : fe_values.quadrature_point_indices())
          for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
            local(i) += fe_values.normal_vector(q)[fe.system_to_component_index(i).first] *
                        fe_values.shape_value(i, q) * fe_values.JxW(q);
      }));

    Vector normal = space.make_owned();
    {
      const LocalValues sum(sums);
      OwnedValues       out(normal);
      for_each_free_vertex(space, [&](const auto &, unsigned int, const auto &dofs) {
        Tensor<1, spacedim> n;
        for (unsigned int c = 0; c < spacedim; ++c)
          n[c] = sum[dofs[c]];
        n /= n.norm();
        for (unsigned int c = 0; c < spacedim; ++c)
          out[dofs[c]] = n[c];
      });
    }
    normal.compress(VectorOperation::insert);
    space.constraints().distribute(normal);
    return normal;
  }

  Vector compute_mean_curvature(const Surface &surface, const Vector &normal_ghosted)
  {
    const FieldSpace &vectors = surface.vector_space();
    const FiniteElement<dim, spacedim> &fe = vectors.fe();

    // Weak form of lap_s X = Hvec:  (Hvec, psi) = -(grad_s X, grad_s psi).
    // grad_s X_c = P e_c (P the tangential projector) on the discrete surface,
    // so (grad_s X, grad_s psi_i) = (grad_s phi_i)_c for psi_i = phi_i e_c.
    const Vector rhs = assemble_rhs(
      surface, vectors, update_gradients,
      [&](const auto &, const FEValues<dim, spacedim> &fe_values, dealii::Vector<double> &local) {
        for (const unsigned int q : fe_values.quadrature_point_indices())
          for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
            local(i) -= fe_values.shape_grad(i, q)[fe.system_to_component_index(i).first] *
                        fe_values.JxW(q);
      });
    const Vector curvature_vector = vectors.ghosted_copy(project(surface, vectors, rhs));

    return nodal_dot_product(surface, curvature_vector, normal_ghosted);
  }

  Vector nodal_dot_product(const Surface &surface, const Vector &a, const Vector &b)
  {
    const FieldSpace &vectors = surface.vector_space();
    const FieldSpace &scalars = surface.scalar_space();
    Vector            product = scalars.make_owned();
    {
      const LocalValues a_values(a), b_values(b);
      OwnedValues       out(product);
      for (const auto &cell : vectors.dof_handler().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const auto scalar_cell = scalars.cell(cell);
            for (const unsigned int v : cell->vertex_indices())
              {
                const auto dof = scalar_cell->vertex_dof_index(v, 0);
                if (!scalars.owned().is_element(dof))
                  continue;
                double sum = 0;
                for (unsigned int c = 0; c < spacedim; ++c)
                  sum += a_values[cell->vertex_dof_index(v, c)] * b_values[cell->vertex_dof_index(v, c)];
                out[dof] = sum;
              }
          }
    }
    product.compress(VectorOperation::insert);
    scalars.constraints().distribute(product);
    return product;
  }

  Vector compute_gauss_curvature(const Surface &surface, const Vector &normal_ghosted)
  {
    const FieldSpace &vectors = surface.vector_space();
    const FieldSpace &scalars = surface.scalar_space();
    FEValues<dim, spacedim> normal_values(surface.mapping(), vectors.fe(), quadrature(), update_gradients);
    std::vector<Tensor<2, spacedim>> normal_gradients(quadrature().size());
    const FEValuesExtractors::Vector all_components(0);

    const Vector rhs = assemble_rhs(
      surface, scalars, update_values,
      [&](const auto &cell, const FEValues<dim, spacedim> &fe_values, dealii::Vector<double> &local) {
        normal_values.reinit(vectors.cell(cell));
        normal_values[all_components].get_function_gradients(normal_ghosted, normal_gradients);
        for (const unsigned int q : fe_values.quadrature_point_indices())
          {
            // K = ((tr grad_s nu)^2 - |grad_s nu|^2) / 2
            const Tensor<2, spacedim> &G = normal_gradients[q];
            const double gauss = 0.5 * (trace(G) * trace(G) - scalar_product(G, G));
            for (unsigned int i = 0; i < fe_values.dofs_per_cell; ++i)
              local(i) += gauss * fe_values.shape_value(i, q) * fe_values.JxW(q);
          }
      });
    return project(surface, scalars, rhs);
  }

  Geometry compute_geometry(const Surface &surface)
  {
    Geometry geometry;
    geometry.normal          = surface.vector_space().ghosted_copy(compute_vertex_normals(surface));
    geometry.mean_curvature  = surface.scalar_space().ghosted_copy(compute_mean_curvature(surface, geometry.normal));
    geometry.gauss_curvature = surface.scalar_space().ghosted_copy(compute_gauss_curvature(surface, geometry.normal));
    return geometry;
  }

  Vector vertex_areas(const Surface &surface)
  {
    return assemble_rhs(surface, surface.scalar_space(), update_values,
                        [](const auto &, const FEValues<dim, spacedim> &fe_values, dealii::Vector<double> &local) {
                          for (const unsigned int q : fe_values.quadrature_point_indices())
                            for (unsigned int i = 0; i < fe_values.dofs_per_cell; ++i)
                              local(i) += fe_values.shape_value(i, q) * fe_values.JxW(q);
                        });
  }

  double max_relative_difference(const Vector &a, const Vector &b)
  {
    double            local = 0;
    const LocalValues a_values(a), b_values(b);
    for (const auto i : b.locally_owned_elements())
      if (b_values[i] > 0)
        local = std::max(local, std::abs(a_values[i] - b_values[i]) / b_values[i]);
    return Utilities::MPI::max(local, b.get_mpi_communicator());
  }

  double integrate(const Surface &surface, const Vector &scalar_ghosted)
  {
    const FieldSpace       &scalars = surface.scalar_space();
    FEValues<dim, spacedim> fe_values(surface.mapping(), scalars.fe(), quadrature(), update_values | update_JxW_values);
    std::vector<double>     values(quadrature().size());
    double                  local = 0;
    for (const auto &cell : scalars.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(scalar_ghosted, values);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            local += values[q] * fe_values.JxW(q);
        }
    return Utilities::MPI::sum(local, scalars.communicator());
  }

  std::array<Tensor<1, spacedim>, 2> tangent_frame(const Tensor<1, spacedim> &nu_in)
  {
    const Tensor<1, spacedim> nu = nu_in / nu_in.norm();
    Tensor<1, spacedim>       e;
    e[std::abs(nu[2]) < 0.9 ? 2 : 0] = 1;
    Tensor<1, spacedim> t            = e - (e * nu) * nu;
    t /= t.norm();
    return {{t, cross_product_3d(nu, t)}};
  }
} // namespace Membrane
