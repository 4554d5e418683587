#pragma once
// A block preconditioner for the shape system (shape_solver.h, seven fields), for FGMRES
// solves whose cost grows like the number of unknowns (Linear solver/Type = block).
//
// Per vertex the system couples the increment W (3), the surface pressure gamma, the mean
// curvature H~ and the tangential curvature parts B~ (2). One application is a block
// Gauss-Seidel sweep, each block's couplings to the others taken from the assembled matrix
// (a residual update with it after each block):
//  1. gamma, the multiplier of the local area constraint. Eliminating W from the tangential
//     law W.t = tau L_X d_t gamma and the normal law leaves a Schur complement that acts like
//     -tau L_X ((1 + delta)(-lap_s) + H^2), a shifted surface Laplacian (delta: the pressure
//     stabilization): one V-cycle of algebraic multigrid (BoomerAMG) on it;
//  2. the tangential motion: the tangential law is a mass matrix acting on W.a_k; with the
//     implicit line stiffness (Shape/Line stiffness) plus its isotropic bound
//     s tau L_X sigma xi^2 |grad phi|^2 (grad, grad), solved by CG (Jacobi, or AMG);
//  3. the normal motion w_n and H~, a mixed fourth-order pair like a Cahn-Hilliard step,
//       [ M   -K_e ] [w_n]   K_e = tau L_X ((kappa grad, grad) + 1/2 (kappa (H - H0)^2, .)),
//       [ K    M   ] [H~ ]   K the surface stiffness matrix,
//     preconditioned as Axelsson, Neytcheva and co-workers precondition Cahn-Hilliard, by
//       [ M   -K_e ; K   M + 2 K_s ],   K_s = (sqrt(tau L_X kappa) grad, grad),
//     whose factorization needs two solves of M + K_s (one V-cycle each) and whose condition
//     number relative to the pair is at most 2 whatever the mesh and tau;
//  4. B~ from the tangential part of the curvature rows (a mass matrix).
// The vertex frames (normal, test tangents, B~ directions) are those of the assembly,
// averaged over each vertex's support. Measured iteration counts do not grow with the mesh
// (benchmarks/README.md).

#include <membrane/physics/material.h>
#include <membrane/surface/field_space.h>
#include <membrane/surface/geometry.h>
#include <membrane/surface/surface.h>

#include <deal.II/lac/petsc_precondition.h>

#include <array>
#include <vector>

namespace Membrane
{
  struct ShapeOptions;

  class ShapePreconditioner
  {
  public:
    /// Build the scalar operators and vertex data on Gamma^m for the assembled
    /// system `matrix` on `system` (seven fields, shape_solver.h). `periodic`:
    /// the test tangents of the tangential law are the patch's parameter
    /// directions a_k.
    void build(const FieldSpace &system, const SparseMatrix &matrix, const Surface &surface, const Geometry &geometry,
               const Material &material, const ShapeOptions &options, double tau, const Vector &phi_ghosted,
               bool periodic);

    /// dst = P^-1 src (one sweep).
    void vmult(Vector &dst, const Vector &src) const;

  private:
    struct VertexData
    {
      std::array<dealii::types::global_dof_index, 7> system;      ///< the vertex's seven DoFs
      dealii::types::global_dof_index                scalar;      ///< its DoF in the scalar space
      dealii::Tensor<1, spacedim>                    unit_normal; ///< the averaged normal, normalized
      /// W from (W.nu, W.t_1, W.t_2) with the averaged normal and test tangents of the
      /// normal and tangential laws (the inverse of the matrix of those rows).
      dealii::Tensor<2, spacedim> displacement;
      /// (H~, B~_1, B~_2) from the curvature rows' vector H~ nu + B~_k t_k (the inverse of the
      /// matrix with the averaged normal and B~ directions as columns).
      dealii::Tensor<2, spacedim> curvature;
    };

    /// rho = src - A z.
    void update_residual(Vector &rho, const Vector &src, const Vector &z) const;

    const FieldSpace                            *system  = nullptr;
    const FieldSpace                            *scalars = nullptr;
    SparseMatrix                                 mass;                ///< M
    SparseMatrix                                 tangential_operator; ///< M + the line stiffness' isotropic bound
    SparseMatrix                                 stiffness;           ///< K
    SparseMatrix                                 bending;             ///< K_e
    SparseMatrix                                 pair_operator;       ///< M + K_s
    SparseMatrix                                 pressure_schur;      ///< -(Schur complement of gamma), SPD
    dealii::PETScWrappers::PreconditionBoomerAMG pair_amg, pressure_amg;
    dealii::PETScWrappers::PreconditionJacobi    mass_jacobi;
    dealii::PETScWrappers::PreconditionBoomerAMG tangential_amg;
    bool                                         with_line_stiffness = false;
    void                                         tangential_solve(Vector &x, const Vector &b) const;
    void                                         mass_solve(Vector &x, const Vector &b) const;
    /// x = matrix^-1 b by CG to 1e-8 relative.
    template <typename Preconditioner>
    static void cg_solve(const SparseMatrix &matrix, const Preconditioner &preconditioner, Vector &x, const Vector &b);
    const SparseMatrix     *system_matrix  = nullptr;
    bool                    patterns_ready = false; ///< the scalar matrices have the mesh's pattern
    std::vector<VertexData> vertices;               ///< owned vertices without constraints
    std::vector<std::pair<dealii::types::global_dof_index, double>> constrained; ///< owned constrained DoFs, 1/A_ii
  };
} // namespace Membrane
