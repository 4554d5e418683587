#include <membrane/surface/projection.h>
#include <membrane/solvers/cell_assembly.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/petsc_precondition.h>
#include <deal.II/lac/petsc_solver.h>
#include <deal.II/lac/solver_control.h>

namespace Membrane
{
  using namespace dealii;

  void assemble_mass_matrix(const Surface &surface, const FieldSpace &space, SparseMatrix &mass)
  {
    mass = 0;
    const QGauss<dim>       quadrature(2);
    FEValues<dim, spacedim> fe_values(surface.mapping(), space.fe(), quadrature,
                                      update_values | update_JxW_values);
    const unsigned int      n_dofs = space.fe().n_dofs_per_cell();
    FullMatrix<double>      local(n_dofs, n_dofs);
    std::vector<types::global_dof_index> dof_indices(n_dofs);
    CellAssembler                        assembler(space.constraints(), mass);

    for (const auto &cell : space.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          local = 0;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            for (unsigned int i = 0; i < n_dofs; ++i)
              for (unsigned int j = 0; j < n_dofs; ++j)
                if (space.fe().system_to_component_index(i).first ==
                    space.fe().system_to_component_index(j).first)
                  local(i, j) += fe_values.shape_value(i, q) * fe_values.shape_value(j, q) * fe_values.JxW(q);
          cell->get_dof_indices(dof_indices);
          assembler.add(local, dof_indices);
        }
    mass.compress(VectorOperation::add);
  }

  Vector project(const Surface &surface, const FieldSpace &space, const Vector &rhs)
  {
    const SparseMatrix &mass = surface.mass_matrix(space);
    Vector                         solution = space.make_owned();
    SolverControl                  control(1000, 1e-13 * rhs.l2_norm() + 1e-300);
    PETScWrappers::SolverCG        cg(control);
    // ILU(0) of each rank's block: about 10 CG iterations to 1e-13 where Jacobi took
    // 40-49; at these sizes each iteration costs mostly PETSc's per-call overhead.
    PETScWrappers::PreconditionBlockJacobi ilu(mass);
    cg.solve(mass, solution, rhs, ilu);
    space.constraints().distribute(solution);
    return solution;
  }
} // namespace Membrane
