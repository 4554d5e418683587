// Shape step, local area constraint: the reference-area defect as the right-hand side of the
// area rows, and the in-step projection that removes the linearization error (correct_area()).
// Part of ShapeSolver.
#include <membrane/shape_solver.h>
#include <membrane/solvers/vector_access.h>

namespace Membrane
{
  using namespace dealii;

  void ShapeSolver::add_area_defect(const Surface &surface, const Vector &area_defect)
  {
    // Both vectors hold the assembled (condensed) vertex values: constrained rows are
    // decoupled by the condensation, so their entries do not matter.
    const FieldSpace &scalars = surface.scalar_space();
    const Vector      defect  = scalars.ghosted_copy(area_defect);
    Vector            rows    = space.make_owned();
    {
      const LocalValues defect_values(defect);
      OwnedValues       row_values(rows);
      for (const auto &cell : space.dof_handler().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const auto scalar_cell = scalars.cell(cell);
            for (const unsigned int v : cell->vertex_indices())
              {
                const auto row = cell->vertex_dof_index(v, ShapeComponents::pressure);
                if (space.owned().is_element(row) && !space.constraints().is_constrained(row))
                  row_values[row] = defect_values[scalar_cell->vertex_dof_index(v, 0)];
              }
          }
    }
    rows.compress(VectorOperation::insert);
    rhs += rows;
  }
  ShapeUpdate ShapeSolver::correct_area(const Surface &surface, const Vector &area_defect, TimerOutput *timer,
                                        const VolumeCoupling &volume_term)
  {
    Assert(solver || block_preconditioner, ExcMessage("correct_area() needs a step() first"));
    Assert(volume_term.active == volume.active, ExcMessage("the volume term must be that of the step"));
    const double scale      = volume.compliance_scale; // of the step's operator
    volume                  = volume_term;
    volume.compliance_scale = scale;
    rhs = 0;
    add_area_defect(surface, area_defect);
    return solve(surface, timer, /*same_matrix=*/true);
  }
} // namespace Membrane
