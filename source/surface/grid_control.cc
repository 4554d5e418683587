#include <membrane/surface/projection.h>
#include <membrane/solvers/vector_access.h>
#include <membrane/surface/geometry.h>
#include <membrane/surface/grid_control.h>

#include <deal.II/base/geometry_info.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

namespace Membrane
{
  using namespace dealii;

  Vector grid_control_displacement(const Surface &surface, const Vector &normal, const double weight)
  {
    const FieldSpace &space = surface.vector_space();
    const auto       &fe    = space.fe();
    // Sum over the edges at each vertex of (X_j - X_i), and the number of edges.
    // Interior edges are seen from both their cells, which doubles sum and count alike.
    Vector                 sums = space.make_owned(), counts = space.make_owned();
    dealii::Vector<double> local_sum(fe.n_dofs_per_cell()), local_count(fe.n_dofs_per_cell());
    std::vector<types::global_dof_index> dof_indices(fe.n_dofs_per_cell());
    for (const auto &cell : space.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const auto X = surface.mapping().get_vertices(cell);
          local_sum    = 0;
          local_count  = 0;
          for (unsigned int l = 0; l < GeometryInfo<dim>::lines_per_cell; ++l)
            {
              const unsigned int a = GeometryInfo<dim>::line_to_cell_vertices(l, 0);
              const unsigned int b = GeometryInfo<dim>::line_to_cell_vertices(l, 1);
              for (unsigned int c = 0; c < spacedim; ++c)
                {
                  local_sum(fe.component_to_system_index(c, a)) += X[b][c] - X[a][c];
                  local_sum(fe.component_to_system_index(c, b)) += X[a][c] - X[b][c];
                  local_count(fe.component_to_system_index(c, a)) += 1;
                  local_count(fe.component_to_system_index(c, b)) += 1;
                }
            }
          cell->get_dof_indices(dof_indices);
          space.constraints().distribute_local_to_global(local_sum, dof_indices, sums);
          space.constraints().distribute_local_to_global(local_count, dof_indices, counts);
        }
    sums.compress(VectorOperation::add);
    counts.compress(VectorOperation::add);

    Vector shift = space.make_owned();
    {
      const LocalValues sum(sums), count(counts), normals(normal);
      OwnedValues       out(shift);
      for_each_free_vertex(space, [&](const auto &, unsigned int, const auto &dofs) {
        Tensor<1, spacedim> d, nu;
        for (unsigned int c = 0; c < spacedim; ++c)
          {
            d[c]  = weight * sum[dofs[c]] / count[dofs[c]];
            nu[c] = normals[dofs[c]];
          }
        d -= (d * nu) * nu; // tangential only
        for (unsigned int c = 0; c < spacedim; ++c)
          out[dofs[c]] = d[c];
      });
    }
    shift.compress(VectorOperation::insert);
    space.constraints().distribute(shift);
    return shift;
  }

  Vector recover_gradient(const Surface &surface, const Vector &scalar)
  {
    const FieldSpace       &vectors = surface.vector_space();
    const QGauss<dim>       quadrature(2);
    FEValues<dim, spacedim> fe_values(surface.mapping(), vectors.fe(), quadrature, update_values | update_JxW_values);
    FEValues<dim, spacedim> scalar_values(surface.mapping(), surface.scalar_space().fe(), quadrature, update_gradients);
    std::vector<Tensor<1, spacedim>> gradients(quadrature.size());
    Vector                 rhs = vectors.make_owned();
    dealii::Vector<double> local(vectors.fe().n_dofs_per_cell());
    std::vector<types::global_dof_index> dof_indices(vectors.fe().n_dofs_per_cell());
    for (const auto &cell : vectors.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          scalar_values.reinit(surface.scalar_space().cell(cell));
          scalar_values.get_function_gradients(scalar, gradients);
          local = 0;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            for (unsigned int i = 0; i < local.size(); ++i)
              local(i) += gradients[q][vectors.fe().system_to_component_index(i).first] * fe_values.shape_value(i, q) *
                          fe_values.JxW(q);
          cell->get_dof_indices(dof_indices);
          vectors.constraints().distribute_local_to_global(local, dof_indices, rhs);
        }
    rhs.compress(VectorOperation::add);
    return project(surface, vectors, rhs);
  }

  double move_tangentially_and_remap(Surface &surface, const Vector &shift, Vector &phi)
  {
    const FieldSpace &vectors = surface.vector_space();
    const FieldSpace &scalars = surface.scalar_space();
    const double      mass_before = integrate(surface, phi);
    const Vector      gradient    = vectors.ghosted_copy(recover_gradient(surface, phi));
    const Vector      d           = vectors.ghosted_copy(shift);

    // phi_i <- phi(X_i + d_i) ~ phi_i + d_i . g_i
    Vector remapped  = nodal_dot_product(surface, d, gradient);
    Vector phi_owned = scalars.make_owned();
    phi_owned        = phi;
    remapped += phi_owned;

    Vector displacement = vectors.make_owned();
    displacement        = surface.displacement();
    displacement += shift;
    surface.set_displacement(displacement);

    phi                    = remapped;
    const double area      = surface.area();
    const double correction = (mass_before - integrate(surface, phi)) / area;
    remapped.add(correction);
    scalars.constraints().distribute(remapped);
    phi = remapped;
    return correction;
  }

  double min_corner_sine(const Surface &surface, const Vector &normal)
  {
    // Corners of the reference quad in counter-clockwise order 0 -> 1 -> 3 -> 2.
    static constexpr unsigned int ring[4] = {0, 1, 3, 2};
    double                        local   = 1;
    const LocalValues             normals(normal);
    for (const auto &cell : surface.vector_space().dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const auto                X = surface.mapping().get_vertices(cell);
          const Tensor<1, spacedim> n = cross_product_3d(X[3] - X[0], X[2] - X[1]);
          const Tensor<1, spacedim> unit = n / std::max(n.norm(), 1e-300);
          // A cell that flipped as a whole keeps convex corners; it shows as a cell
          // normal opposite to the vertex normals, which its neighbours dominate.
          double alignment = 0;
          for (const unsigned int v : cell->vertex_indices())
            for (unsigned int c = 0; c < spacedim; ++c)
              alignment += unit[c] * normals[cell->vertex_dof_index(v, c)];
          if (alignment <= 0)
            local = std::min(local, -1.0);
          for (unsigned int k = 0; k < 4; ++k)
            {
              const Tensor<1, spacedim> e1 = X[ring[(k + 1) % 4]] - X[ring[k]];
              const Tensor<1, spacedim> e2 = X[ring[(k + 3) % 4]] - X[ring[k]];
              local = std::min(local, (cross_product_3d(e1, e2) * unit) / (e1.norm() * e2.norm()));
            }
        }
    return Utilities::MPI::min(local, surface.vector_space().communicator());
  }
} // namespace Membrane
