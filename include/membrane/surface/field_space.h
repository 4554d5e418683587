#pragma once
// A finite element space on the membrane: Q1 with n components, its DoFHandler,
// periodic and hanging-node constraints, and the parallel index sets.

#include <membrane/types.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/affine_constraints.h>

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
