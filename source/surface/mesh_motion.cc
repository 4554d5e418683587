#include <membrane/solvers/vector_access.h>
#include <membrane/surface/geometry.h>
#include <membrane/surface/grid_control.h>
#include <membrane/surface/mesh_motion.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

namespace Membrane
{
  using namespace dealii;

  MeshMotion parse_mesh_motion(const std::string &name)
  {
    if (name == "lagrangian")
      return MeshMotion::lagrangian;
    AssertThrow(name == "ale", ExcMessage("<Shape/Mesh motion> is lagrangian or ale, not '" + name + "'"));
    return MeshMotion::ale;
  }

  Vector normal_part(const Surface &surface, const Vector &increment, const Vector &normal)
  {
    const FieldSpace &space = surface.vector_space();
    Vector            part  = space.make_owned();
    {
      const LocalValues w(increment), nu(normal);
      OwnedValues       out(part);
      for_each_free_vertex(space, [&](const auto &, unsigned int, const auto &dofs) {
        double normal_component = 0;
        for (unsigned int c = 0; c < spacedim; ++c)
          normal_component += w[dofs[c]] * nu[dofs[c]];
        for (unsigned int c = 0; c < spacedim; ++c)
          out[dofs[c]] = normal_component * nu[dofs[c]];
      });
    }
    part.compress(VectorOperation::insert);
    space.constraints().distribute(part);
    return part;
  }

  Vector ale_mesh_increment(Surface &surface, const Vector &increment, const Vector &normal, const unsigned int sweeps,
                            const double weight)
  {
    const FieldSpace &vectors = surface.vector_space();
    Vector            start   = vectors.make_owned();
    start                     = surface.displacement();
    Vector mesh_increment     = normal_part(surface, increment, normal);
    for (unsigned int sweep = 0; weight > 0 && sweep < sweeps; ++sweep)
      {
        // The smoothing is measured where the normal motion (and the sweeps before) put the vertices.
        Vector at = start;
        at += mesh_increment;
        surface.set_displacement(at);
        mesh_increment += grid_control_displacement(surface, vectors.ghosted_copy(compute_vertex_normals(surface)), weight);
      }
    surface.set_displacement(start);
    return mesh_increment;
  }

  Vector transport_flux(const Surface &surface, const Vector &relative, const Vector &phi, const Vector *stream,
                        const double stream_scale)
  {
    const FieldSpace       &scalars = surface.scalar_space();
    const FieldSpace       &vectors = surface.vector_space();
    const QGauss<dim>       quadrature(2);
    FEValues<dim, spacedim> fe_values(surface.mapping(), scalars.fe(), quadrature,
                                      update_values | update_gradients | update_JxW_values | update_jacobians);
    FEValues<dim, spacedim> vector_values(surface.mapping(), vectors.fe(), quadrature, update_values);
    const FEValuesExtractors::Vector     all_components(0);
    std::vector<Tensor<1, spacedim>>     d(quadrature.size()), nu(quadrature.size()), grad_stream(quadrature.size());
    const Vector normal = stream ? vectors.ghosted_copy(compute_vertex_normals(surface)) : Vector();
    std::vector<double>                  phi_q(quadrature.size());
    std::vector<Tensor<1, spacedim>>     grad_phi(quadrature.size());
    dealii::Vector<double>               local(scalars.fe().n_dofs_per_cell());
    std::vector<types::global_dof_index> dof_indices(scalars.fe().n_dofs_per_cell());
    Vector                               flux = scalars.make_owned();
    for (const auto &cell : scalars.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          vector_values.reinit(vectors.cell(cell));
          vector_values[all_components].get_function_values(relative, d);
          if (stream)
            {
              // The lipids also move by the solenoidal noise n x grad_s psi: d gains its negative.
              vector_values[all_components].get_function_values(normal, nu);
              fe_values.get_function_gradients(*stream, grad_stream);
              for (const unsigned int q : fe_values.quadrature_point_indices())
                d[q] -= stream_scale * cross_product_3d(oriented_cell_normal(fe_values.jacobian(q), nu[q]), grad_stream[q]);
            }
          fe_values.get_function_values(phi, phi_q);
          fe_values.get_function_gradients(phi, grad_phi);
          local = 0;
          // (phi d, grad_s chi_i): the flux of phi through the moving mesh, -(v - w) = d / tau;
          // + 1/2 (d . grad_s phi, d . grad_s chi_i): the second-order term of phi(X + d)
          // (Lax-Wendroff), without which the centred explicit transport amplifies the finest
          // modes by 1 + O(|d|^2 / h^2) per step. For a random d it is the diffusion <d d>/2 of
          // the lipids' random walk.
          for (const unsigned int q : fe_values.quadrature_point_indices())
            for (unsigned int i = 0; i < local.size(); ++i)
              local(i) += (phi_q[q] * (d[q] * fe_values.shape_grad(i, q)) +
                           0.5 * (d[q] * grad_phi[q]) * (d[q] * fe_values.shape_grad(i, q))) *
                          fe_values.JxW(q);
          cell->get_dof_indices(dof_indices);
          scalars.constraints().distribute_local_to_global(local, dof_indices, flux);
        }
    flux.compress(VectorOperation::add);
    return flux;
  }

  void move_and_transport(Surface &surface, const Vector &mesh_increment, const Vector &relative,
                          const std::vector<Vector *> &fields, const Vector *stream, const double stream_scale)
  {
    const FieldSpace   &scalars = surface.scalar_space();
    const FieldSpace   &vectors = surface.vector_space();
    const Vector        d       = vectors.ghosted_copy(relative);
    std::vector<Vector> fluxes;
    for (const Vector *f : fields)
      fluxes.push_back(transport_flux(surface, d, *f, stream, stream_scale));
    const Vector areas_from = vertex_areas(surface);

    Vector displacement = vectors.make_owned();
    displacement        = surface.displacement();
    displacement += mesh_increment;
    surface.set_displacement(displacement);
    const Vector areas_to = vertex_areas(surface);

    for (unsigned int k = 0; k < fields.size(); ++k)
      {
        Vector carried = scalars.make_owned();
        {
          const LocalValues old_values(*fields[k]), from(areas_from), to(areas_to), flux(fluxes[k]);
          OwnedValues       out(carried);
          for (const auto i : carried.locally_owned_elements())
            if (!scalars.constraints().is_constrained(i))
              out[i] = (from[i] * old_values[i] - flux[i]) / to[i];
        }
        carried.compress(VectorOperation::insert);
        scalars.constraints().distribute(carried);
        *fields[k] = carried;
      }
  }
} // namespace Membrane
