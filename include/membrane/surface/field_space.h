#pragma once
// A finite element space on the membrane: Q1 with n components, its DoFHandler,
// periodic and hanging-node constraints, and the parallel index sets.

#include <membrane/core/types.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/affine_constraints.h>

#include <array>

namespace Membrane
{
  class FieldSpace
  {
  public:
    FieldSpace(const Triangulation &triangulation, unsigned int n_components);

    /// Distribute DoFs and build constraints; call after every mesh change.
    void setup(bool periodic);

    const dealii::DoFHandler<dim, spacedim> &dof_handler() const { return dofs; }
    const dealii::AffineConstraints<double> &constraints() const { return constraint_set; }
    const dealii::FiniteElement<dim, spacedim> &fe() const { return element; }
    unsigned int n_components() const { return element.n_components(); }

    const dealii::IndexSet &owned() const { return owned_dofs; }
    const dealii::IndexSet &relevant() const { return relevant_dofs; }
    MPI_Comm communicator() const;

    Vector make_owned() const;
    Vector make_ghosted() const;
    /// A ghosted copy of an owned vector (with constraints already applied).
    Vector ghosted_copy(const Vector &owned_vector) const;
    /// A sparse matrix whose pattern couples all components on each cell, or with
    /// couple_components = false each component only with itself (a mass matrix of a
    /// vector field: a third of the entries, and of the work of a product with it).
    void reinit_matrix(SparseMatrix &matrix, bool couple_components = true) const;

    /// The cell of this space's DoFHandler that is `cell` of the triangulation.
    typename dealii::DoFHandler<dim, spacedim>::active_cell_iterator
    cell(const typename Triangulation::active_cell_iterator &cell) const;

  private:
    const dealii::FESystem<dim, spacedim> element;
    dealii::DoFHandler<dim, spacedim>     dofs;
    dealii::AffineConstraints<double>     constraint_set;
    dealii::IndexSet                      owned_dofs;
    dealii::IndexSet                      relevant_dofs;
  };

  /// Calls f(cell, v, dofs) for every vertex v of a locally owned cell whose DoFs are owned
  /// by this process and not constrained (dofs[c]: its DoF of component c < n_components,
  /// at most spacedim: scalar and vector fields); a vertex is visited once from each of its cells.
  template <typename Function>
  void for_each_free_vertex(const FieldSpace &space, Function &&f)
  {
    AssertThrow(space.n_components() <= spacedim,
                dealii::ExcMessage("for_each_free_vertex: a space of at most 3 components"));
    std::array<dealii::types::global_dof_index, spacedim> dofs{};
    for (const auto &cell : space.dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          {
            const auto first = cell->vertex_dof_index(v, 0);
            if (!space.owned().is_element(first) || space.constraints().is_constrained(first))
              continue;
            for (unsigned int c = 0; c < space.n_components(); ++c)
              dofs[c] = cell->vertex_dof_index(v, c);
            f(cell, v, dofs);
          }
  }

  /// Smallest and largest locally owned entry over all ranks.
  std::pair<double, double> global_range(const Vector &vector);

  /// Copy one component of a Q1 system vector into a (single-component) vector
  /// of another space on the same mesh; `to` is owned, constraints are applied.
  void copy_component(const FieldSpace &from_space,
                      const Vector     &from_ghosted,
                      unsigned int      from_component,
                      const FieldSpace &to_space,
                      Vector           &to_owned,
                      unsigned int      to_component = 0);
} // namespace Membrane
