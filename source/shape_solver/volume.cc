// The global volume term of the shape step on a closed surface (MODEL.md section 8):
// the pressure column, the linearized volume row and the elimination of p with the
// factorization of the step. Part of ShapeSolver (see shape_solver.h).
#include <membrane/shape_solver.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    /// The normal law is the row tested with the H~ component (assembly.cc).
    constexpr unsigned int normal_row = ShapeComponents::curvature;
    // ShapeSolver::volume_compliance_floor: the volume compliance -b.A^-1 c / (tau L_X A) is about 1 for a free surface and tends
    // to 0 where the local area constraint already fixes the volume: near a sphere, the
    // isoperimetric extreme, any area-preserving motion keeps V to first order, and p and a
    // uniform tension gamma are interchangeable. Below the floor (5e-3) the volume row is
    // dropped (p = 0): the row would be degenerate, and p z would be an O(1) motion for any
    // tau. The measured compliance is 5e-5 to 7e-4 on cube-spheres and 0.03 on an
    // ellipsoid of reduced volume 0.95 (4 cells per side).
  } // namespace

  void ShapeSolver::assemble_volume_coupling(const Surface &surface, const Geometry &geometry,
                                             const double tau_mobility)
  {
    volume.compliance_scale = tau_mobility * surface.area();
    pressure_column = space.make_owned();
    volume_row      = space.make_owned();
    const QGauss<dim>       quadrature(2);
    const unsigned int      n_dofs = space.fe().n_dofs_per_cell();
    FEValues<dim, spacedim> fe_values(surface.mapping(), space.fe(), quadrature,
                                      update_values | update_normal_vectors | update_JxW_values);
    FEValues<dim, spacedim> vector_values(surface.mapping(), surface.vector_space().fe(), quadrature, update_values);
    const FEValuesExtractors::Vector     all_components(0);
    std::vector<Tensor<1, spacedim>>     nu(quadrature.size());
    dealii::Vector<double>               local_column(n_dofs), local_row(n_dofs);
    std::vector<types::global_dof_index> dof_indices(n_dofs);
    for (const auto &cell : space.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          vector_values.reinit(surface.vector_space().cell(cell));
          vector_values[all_components].get_function_values(geometry.normal, nu);
          local_column = 0;
          local_row    = 0;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              const Tensor<1, spacedim> n  = fe_values.normal_vector(q); // outward cell normal
              const double              ds = fe_values.JxW(q);
              for (unsigned int i = 0; i < n_dofs; ++i)
                {
                  const unsigned int c   = space.fe().system_to_component_index(i).first;
                  const double       psi = fe_values.shape_value(i, q) * ds;
                  if (c == normal_row) // left side of the normal row: - tau L_X p (n.nu, psi)
                    local_column(i) -= tau_mobility * (n * nu[q]) * psi;
                  else if (c < spacedim) // delta V = integral W.n ds, exact for the bilinear surface
                    local_row(i) += n[c] * psi;
                }
            }
          cell->get_dof_indices(dof_indices);
          space.constraints().distribute_local_to_global(local_column, dof_indices, pressure_column);
          space.constraints().distribute_local_to_global(local_row, dof_indices, volume_row);
        }
    pressure_column.compress(VectorOperation::add);
    volume_row.compress(VectorOperation::add);
  }

  double ShapeSolver::apply_volume_coupling(Vector &solution, const bool same_matrix)
  {
    // A new matrix (a step) needs its own z = A^-1 c; corrections reuse it.
    if (!same_matrix)
      {
        pressure_response = space.make_owned();
        linear_solve(pressure_response, pressure_column, true);
      }
    double pressure = 0;
    if (!same_matrix)
      compliance = -(volume_row * pressure_response) / volume.compliance_scale;
    if (volume.fixed && !volume_held_by_areas())
      {
        // The bordered row b.(y - p z) = g (g: the volume defect).
        const double coupling = volume_row * pressure_response;
        AssertThrow(std::isfinite(coupling), ExcMessage("the volume coupling b.A^-1 c is not finite"));
        pressure = (volume_row * solution - volume.volume_defect) / coupling;
      }
    else if (!same_matrix)
      pressure = volume.pressure; // prescribed: once per step, not again in corrections
    if (pressure != 0)
      solution.add(-pressure, pressure_response);
    return pressure;
  }
} // namespace Membrane
