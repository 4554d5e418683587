#include <membrane/solvers/petsc_check.h>
#include <membrane/solvers/vector_access.h>

#include <algorithm>
#include <string>

namespace Membrane
{
  LocalValues::LocalValues(const Vector &v)
    : vector(v)
  {
    check_petsc(VecGetOwnershipRange(vector, &begin, &end), "VecGetOwnershipRange");
    if (!v.has_ghost_elements())
      {
        check_petsc(VecGetArrayRead(vector, &data), "VecGetArrayRead");
        return;
      }
    check_petsc(VecGhostGetLocalForm(vector, &local_form), "VecGhostGetLocalForm");
    check_petsc(VecGetArrayRead(local_form, &data), "VecGetArrayRead");
    // The ghost entries follow the owned ones in the local form; their global indices
    // come from the vector's local-to-global mapping.
    PetscInt n_local = 0;
    check_petsc(VecGetSize(local_form, &n_local), "VecGetSize");
    ISLocalToGlobalMapping mapping = nullptr;
    check_petsc(VecGetLocalToGlobalMapping(vector, &mapping), "VecGetLocalToGlobalMapping");
    const PetscInt *global = nullptr;
    check_petsc(ISLocalToGlobalMappingGetIndices(mapping, &global), "ISLocalToGlobalMappingGetIndices");
    const PetscInt n_owned = end - begin;
    ghosts.reserve(n_local - n_owned);
    for (PetscInt k = n_owned; k < n_local; ++k)
      ghosts.emplace_back(global[k], k);
    check_petsc(ISLocalToGlobalMappingRestoreIndices(mapping, &global), "ISLocalToGlobalMappingRestoreIndices");
    std::sort(ghosts.begin(), ghosts.end());
  }

  LocalValues::~LocalValues()
  {
    if (local_form != nullptr)
      {
        VecRestoreArrayRead(local_form, &data);
        VecGhostRestoreLocalForm(vector, &local_form);
      }
    else
      VecRestoreArrayRead(vector, &data);
  }

  PetscInt LocalValues::ghost_position(const PetscInt index) const
  {
    const auto found = std::lower_bound(ghosts.begin(), ghosts.end(), std::make_pair(index, PetscInt(0)));
    AssertThrow(found != ghosts.end() && found->first == index,
                dealii::ExcMessage("LocalValues: entry " + std::to_string(index) +
                                   " is neither owned nor a ghost entry of this process"));
    return found->second;
  }

  OwnedValues::OwnedValues(Vector &v)
    : vector(v)
  {
    AssertThrow(!v.has_ghost_elements(), dealii::ExcMessage("OwnedValues: the vector has ghost entries"));
    PetscInt end = 0;
    check_petsc(VecGetOwnershipRange(vector, &begin, &end), "VecGetOwnershipRange");
    check_petsc(VecGetArray(vector, &data), "VecGetArray");
  }

  OwnedValues::~OwnedValues()
  {
    VecRestoreArray(vector, &data);
  }
} // namespace Membrane
