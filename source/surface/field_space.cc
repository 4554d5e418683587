#include <membrane/solvers/vector_access.h>
#include <membrane/surface/field_space.h>

#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

namespace Membrane
{
  using namespace dealii;

  FieldSpace::FieldSpace(const Triangulation &triangulation, const unsigned int n_components)
    : element(FE_Q<dim, spacedim>(1), n_components)
    , dofs(triangulation)
  {}

  MPI_Comm FieldSpace::communicator() const
  {
    return dofs.get_triangulation().get_communicator();
  }

  void FieldSpace::setup(const bool periodic)
  {
    dofs.distribute_dofs(element);
    owned_dofs = dofs.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dofs, relevant_dofs);

    constraint_set.clear();
    constraint_set.reinit(relevant_dofs);
    DoFTools::make_hanging_node_constraints(dofs, constraint_set);
    if (periodic)
      {
        // Boundary ids from the colorized unit square: 0|1 at u1 = 0|1, 2|3 at u2 = 0|1.
        DoFTools::make_periodicity_constraints(dofs, 0, 1, 0, constraint_set);
        DoFTools::make_periodicity_constraints(dofs, 2, 3, 1, constraint_set);
      }
    constraint_set.close();
  }

  Vector FieldSpace::make_owned() const
  {
    return Vector(owned_dofs, communicator());
  }

  Vector FieldSpace::make_ghosted() const
  {
    return Vector(owned_dofs, relevant_dofs, communicator());
  }

  Vector FieldSpace::ghosted_copy(const Vector &owned_vector) const
  {
    Vector ghosted = make_ghosted();
    ghosted        = owned_vector;
    return ghosted;
  }

  void FieldSpace::reinit_matrix(SparseMatrix &matrix, const bool couple_components) const
  {
    DynamicSparsityPattern pattern(relevant_dofs);
    const unsigned int     n = element.n_components();
    Table<2, DoFTools::Coupling> coupling(n, n);
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int b = 0; b < n; ++b)
        coupling(a, b) = couple_components || a == b ? DoFTools::always : DoFTools::none;
    DoFTools::make_sparsity_pattern(dofs, coupling, pattern, constraint_set, false);
    SparsityTools::distribute_sparsity_pattern(pattern, owned_dofs, communicator(), relevant_dofs);
    matrix.reinit(owned_dofs, owned_dofs, pattern, communicator());
  }

  typename DoFHandler<dim, spacedim>::active_cell_iterator
  FieldSpace::cell(const typename Triangulation::active_cell_iterator &tria_cell) const
  {
    return typename DoFHandler<dim, spacedim>::active_cell_iterator(
      &dofs.get_triangulation(), tria_cell->level(), tria_cell->index(), &dofs);
  }

  std::pair<double, double> global_range(const Vector &vector)
  {
    double            low = std::numeric_limits<double>::max(), high = -low;
    const LocalValues values(vector);
    for (const auto i : vector.locally_owned_elements())
      {
        low  = std::min(low, values[i]);
        high = std::max(high, values[i]);
      }
    const MPI_Comm comm = vector.get_mpi_communicator();
    return {Utilities::MPI::min(low, comm), Utilities::MPI::max(high, comm)};
  }

  void copy_component(const FieldSpace  &from_space,
                      const Vector      &from_ghosted,
                      const unsigned int from_component,
                      const FieldSpace  &to_space,
                      Vector            &to_owned,
                      const unsigned int to_component)
  {
    {
      const LocalValues from(from_ghosted);
      OwnedValues       to(to_owned);
      for (const auto &cell : from_space.dof_handler().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const auto to_cell = to_space.cell(cell);
            for (const unsigned int v : cell->vertex_indices())
              {
                const auto to_dof = to_cell->vertex_dof_index(v, to_component);
                if (to_space.owned().is_element(to_dof))
                  to[to_dof] = from[cell->vertex_dof_index(v, from_component)];
              }
          }
    }
    to_owned.compress(VectorOperation::insert);
    to_space.constraints().distribute(to_owned);
  }
} // namespace Membrane
