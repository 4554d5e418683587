#pragma once
// Loops over vertices that read or write PETSc vectors entry by entry. Element access
// through deal.II's PETSc wrappers makes PETSc calls for every entry (for a ghosted
// vector: the local form, the array, a search of the ghost set), which made such loops
// a sizeable part of a step. These views take the array once per loop.

#include <membrane/core/types.h>

#include <deal.II/base/types.h>

#include <petscvec.h>

#include <vector>

namespace Membrane
{
  /// Read-only view of the locally stored entries of a vector, addressed by global
  /// index: the owned ones and, for a ghosted vector, its ghost entries.
  class LocalValues
  {
  public:
    explicit LocalValues(const Vector &vector);
    ~LocalValues();
    LocalValues(const LocalValues &)            = delete;
    LocalValues &operator=(const LocalValues &) = delete;

    double operator[](const dealii::types::global_dof_index i) const
    {
      const auto index = static_cast<PetscInt>(i);
      return index >= begin && index < end ? data[index - begin] : data[ghost_position(index)];
    }

  private:
    PetscInt ghost_position(PetscInt index) const; ///< throws if index is not stored here

    Vec                vector     = nullptr;
    Vec                local_form = nullptr; ///< owned then ghost entries (ghosted vectors only)
    const PetscScalar *data       = nullptr;
    PetscInt           begin = 0, end = 0;
    std::vector<std::pair<PetscInt, PetscInt>> ghosts; ///< (global index, position in data), sorted
  };

  /// Writable view of the owned entries of a vector without ghost entries. Writes go
  /// straight into the vector's array (no compress() needed, none harmful).
  class OwnedValues
  {
  public:
    explicit OwnedValues(Vector &vector);
    ~OwnedValues();
    OwnedValues(const OwnedValues &)            = delete;
    OwnedValues &operator=(const OwnedValues &) = delete;

    double &operator[](const dealii::types::global_dof_index i)
    {
      return data[static_cast<PetscInt>(i) - begin];
    }

  private:
    Vec          vector = nullptr;
    PetscScalar *data   = nullptr;
    PetscInt     begin  = 0;
  };
} // namespace Membrane
