#pragma once
// Tangential correction of the vertex areas (docs/model.md, local area).
//
// The shape step meets the local area constraint a_i(X) = a_target,i only up to the
// linearization error and, on locally refined meshes, up to what its pressure-stabilized
// area row leaves: the stabilized operator removes about a tenth of a defect per projection.
// This correction moves the vertices tangentially instead, by the least-squares move
// that meets the linearized constraint:
//     w = D B^T q,   (B D B^T) q = a_target - a(X),
// with (B w)_i = integral psi_i div_s w ds the linearized change of the vertex areas and
// D = blockdiag(P_j / a_j) (P_j the tangent projector of vertex j, a_j its area), so
// that w is the tangential move of least area-weighted kinetic norm. B D B^T is a
// (wide-stencil) surface Laplacian, formed as a sparse product and factorized (MUMPS);
// a few iterations with the measured areas remove the O(|grad w|^2) error of
// each move.
// Tangential moves carry the material with them (phi rides on the vertices), like the
// tangential velocity of the shape step itself; they change the shape only through the
// discretization.

#include <membrane/surface/surface.h>

#include <memory>

namespace Membrane
{
  struct TangentialAreaCorrection
  {
    unsigned int iterations    = 0; ///< moves applied (each kept lowered the error)
    double       initial_error = 0; ///< max_i |a_i - a_target,i| / a_target,i before
    double       final_error   = 0; ///< the same after
  };

  /// The correction with its matrices kept across steps: B, D and the products B D and
  /// B D B^T keep their sparsity while the mesh is unchanged, so a step assembles values,
  /// multiplies numerically and refactorizes numerically (MUMPS keeps its analysis).
  /// Within a step the iterations reuse one factorization (a chord iteration: each
  /// move is small, so the Jacobian of the first one serves the rest) and refactorize only
  /// if an iteration lowers the error by less than a factor 10.
  class TangentialAreaCorrector
  {
  public:
    TangentialAreaCorrector();
    ~TangentialAreaCorrector();
    TangentialAreaCorrector(const TangentialAreaCorrector &)            = delete;
    TangentialAreaCorrector &operator=(const TangentialAreaCorrector &) = delete;

    /// Forget matrices and factorization: the mesh (and so every pattern) changed.
    void reset();

    /// Move the surface tangentially (at most `max_iterations` trial moves, each kept only
    /// if it lowers the error; a rejected one is retried with more damping) until the
    /// vertex areas meet `target` (owned, scalar space) to `tolerance` (relative, largest
    /// over the vertices). `normal_ghosted`: vertex normals
    /// of the vector space for the tangent projectors.
    TangentialAreaCorrection correct(Surface &surface, const Vector &normal_ghosted, const Vector &target,
                                     double tolerance, unsigned int max_iterations);

  private:
    /// Assemble B and D at the current surface, form B D B^T, shift it by `shift` times
    /// its largest diagonal entry (the damping, see the .cc) and factorize it.
    void factorize(const Surface &surface, const Vector &normal_ghosted, const Vector &areas, double shift);
    /// The linearized least-squares move w = D B^T q, (B D B^T + epsilon) q = defect.
    Vector move(const Surface &surface, const Vector &defect) const;

    SparseMatrix B, D;
    struct Petsc;                 ///< products, the regularized matrix and the solver
    std::unique_ptr<Petsc> petsc; ///< null until the first factorization on this mesh
  };

  /// One correction with a fresh TangentialAreaCorrector (tests, one-off uses).
  TangentialAreaCorrection correct_areas_tangentially(Surface &surface, const Vector &normal_ghosted,
                                                      const Vector &target, double tolerance,
                                                      unsigned int max_iterations);
} // namespace Membrane
