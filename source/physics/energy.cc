#include <membrane/physics/energy.h>
#include <membrane/physics/free_energy.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

namespace Membrane
{
  using namespace dealii;

  EnergyTerms compute_energy(const Surface &surface, const Geometry &geometry, const Vector &phi,
                             const Material &material)
  {
    const FieldSpace       &scalars = surface.scalar_space();
    const QGauss<dim>       quadrature(2);
    FEValues<dim, spacedim> fe_values(surface.mapping(), scalars.fe(), quadrature,
                                      update_values | update_gradients | update_JxW_values);
    const unsigned int      n_q = quadrature.size();
    std::vector<double>     phi_values(n_q), H(n_q), K(n_q);
    std::vector<Tensor<1, spacedim>> phi_gradients(n_q);
    FreeEnergy terms(material);
    terms.prepare(surface, geometry);
    TermPoint point;

    EnergyTerms local;
    for (const auto &cell : scalars.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(phi, phi_values);
          fe_values.get_function_gradients(phi, phi_gradients);
          fe_values.get_function_values(geometry.mean_curvature, H);
          fe_values.get_function_values(geometry.gauss_curvature, K);
          for (unsigned int q = 0; q < n_q; ++q)
            {
              point.phi      = phi_values[q];
              point.grad_phi = phi_gradients[q];
              point.H        = H[q];
              point.K        = K[q];
              terms.add_energy(point, fe_values.JxW(q), local);
            }
        }
    const MPI_Comm comm = scalars.communicator();
    EnergyTerms    sum;
    sum.bending  = Utilities::MPI::sum(local.bending, comm);
    sum.gaussian = Utilities::MPI::sum(local.gaussian, comm);
    sum.gradient = Utilities::MPI::sum(local.gradient, comm);
    sum.well     = Utilities::MPI::sum(local.well, comm);
    terms.add_global_energy(sum);
    return sum;
  }
} // namespace Membrane
