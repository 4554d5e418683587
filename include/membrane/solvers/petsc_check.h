#pragma once
// Error check for direct PETSc calls (the deal.II wrappers check their own).

#include <deal.II/base/exceptions.h>

#include <petscsys.h>

#include <string>

namespace Membrane
{
  /// Throw (a solver failure, which rejects the step) if a PETSc call returned an error.
  inline void check_petsc(const PetscErrorCode code, const char *what)
  {
    AssertThrow(code == 0,
                dealii::ExcMessage(std::string("PETSc error in ") + what + " (code " + std::to_string(code) + ")"));
  }
} // namespace Membrane
