#pragma once
// Shape step on the current surface Gamma^m (MODEL.md section 4, step 3).
//
// Unknowns (seven Q1 fields): the increment W = X^{m+1} - X^m (3 components),
// the surface pressure gamma, the new mean curvature H~ and the tangential parts
// B~_1, B~_2 of the mean-curvature vector. Equations, each multiplied by tau L_X
// where it carries the velocity (so that all rows are O(1)):
//
//   normal:     (W.nu, psi) - tau L_X [ (kappa grad H~, grad psi) + 1/2 (kappa (H - H0)^2 H~, psi)
//                                     + (H gamma, psi) ]
//               = tau L_X [ ((H - H0) kappa' grad phi - kappa H0' grad phi
//                            + kappa_G' c^ij d_j phi a_i, grad psi)
//                          + (-kappa (H - H0) |grad nu|^2 - sigma xi^2 b^ij d_i phi d_j phi + H G, psi) ]
//   tangential: (W.a_k, psi) - tau L_X (d_k gamma, psi) = tau L_X (Y d_k phi, psi),   k = 1, 2
//   area:       (div_s W, psi) + delta [ (W, grad psi) - tau L_X (grad gamma + Y grad phi, grad psi) ]
//               - epsilon (gamma, psi) = a_ref(psi) - a^m(psi)
//   curvature:  (H~ nu + B~_1 t_1 + B~_2 t_2, psi_vec) + (grad_s W, grad_s psi_vec) = -(grad_s X^m, grad_s psi_vec)
//
// with everything else (H = H^m, K, nu, phi = phi^m, moduli at phi^m, Y of the
// Cahn-Hilliard step) frozen at t_m. The energy terms' parts of the normal row (the stiffness
// on H~, the flux and source) come from physics/free_energy.h, one file per term; the
// velocity, area, pressure, curvature and noise parts are the system's own. Sign conventions of MODEL.md: H is the sum
// of principal curvatures, b_ij = X_,ij . n, c^ij = H g^ij - b^ij.
//
// Discrete choices (documented in docs/model.md):
//  - a_k = dX/du_k, the tangents along the parameter directions of the patch;
//  - b^ij d_i phi d_j phi = -grad phi . grad_s nu . grad phi and
//    c^ij d_j phi a_i = H_nu grad phi + sym(grad_s nu) grad phi with H_nu = -tr grad_s nu,
//    all from the gradient of the Q1 vertex-normal field;
//  - G = sigma (xi^2/2 |grad phi|^2 + f(phi)) is used at the quadrature points;
//  - pressure stabilization (delta > 0): equal-order Q1 for (W, gamma) admits a
//    checkerboard gamma (the wide-stencil Schur complement does not see it). The
//    delta term adds the residual of the tangential law, tested with grad psi
//    (Masud-Hughes type). It vanishes for the exact solution and gives gamma a
//    compact-stencil Laplacian;
//  - epsilon = 1e-12 only fixes the constant gamma on a flat patch, where H = 0
//    leaves the global pressure undetermined;
//  - local area: a(psi) = integral psi ds is the area carried by each vertex. The
//    linearized constraint a^{m+1}(psi) ~ a^m(psi) + (div_s W, psi) targets the
//    reference areas a_ref(psi) of the membrane, not the current ones, so errors
//    of earlier steps are fed back instead of accumulating;
//  - the linearization leaves an O(|grad W|^2) error in each step. correct_area()
//    removes it within the step: the same operator (its factorization is reused)
//    with the measured defect of X^m + W as the only right-hand side gives a
//    constrained projection W' that is added to W.
//
// Curvature mass (ShapeOptions::curvature_mass):
//  - consistent: the curvature rows above as written (seven fields per vertex);
//  - lumped: the mass term of the curvature rows lumped to the vertices,
//      a_i (H~_i nu_i + B~_1,i t_1,i + B~_2,i t_2,i) + (grad_s W, grad_s psi_i e) = -(grad_s X^m, grad_s psi_i e),
//    with an orthonormal frame (nu_i, t_1,i, t_2,i) at every vertex and a_i = integral psi_i ds.
//    Then B~ sits in vertex i's three rows only, and the row's component along nu_i is
//      a_i H~_i + sum_c nu_i,c (grad_s W_c, grad_s psi_i) = -(nu_i . grad_s X^m, grad_s psi_i)
//    (the lumped mean-curvature vector of Dziuk and of Barrett-Garcke-Nurnberg, projected on
//    the normal); the two tangential components only define B~. The system keeps five
//    fields (W, gamma, H~) with this row in place of the three curvature rows: the
//    factorization costs about (5/7)^3 = 0.36 of the consistent one. lumped_full keeps the
//    seven fields of the lumped scheme and serves to verify the elimination.
//
// Thermal noise (MODEL.md section 10): at k_BT > 0 the force balance gains a random force
// F_noise of covariance (2 k_BT / (tau L_X)) M, M the consistent mass of the velocity term.
// It is white noise per quadrature point: a vector eta_q of three independent normals of
// variance 2 k_BT / (tau L_X w_q) (w_q the point's weight), tested like the drift,
//   normal row + tau L_X (eta, psi nu),   tangential row k + tau L_X (eta, psi a_k),
// so that (eta, V) has exactly the covariance (2 k_BT / (tau L_X)) (V, V) for every V of
// the discrete velocity space (2 x 2 Gauss is exact for the Q1 mass). The pressure
// stabilization keeps the noisy tangential law's residual, + delta tau L_X (eta, grad psi).
// The constraints (area rows, the volume row) project the noise as they project the drift.
//
// Closed surfaces (MODEL.md section 8; shape_solver/volume.cc): the enclosed volume
// adds a global pressure p. Its force p n, tested with psi nu, enters the normal row
// as - tau L_X p (n.nu, psi) on the left (p > 0 moves the surface along the outward
// normal: it inflates). With a fixed volume p is the multiplier of the bordered row
//   integral over Gamma^m of W.n ds = V_target - V(X^m),
// solved with the factorization of the step: A y = r and A z = c (c: the p column)
// give p = (b.y - g) / (b.z) and the solution y - p z (Schur complement of size 1).
// Where the local area constraint already fixes V (near a sphere) b.z -> 0: below a
// floor of the compliance -b.z / (tau L_X A) the row is dropped (shape_solver/volume.cc).

#include <membrane/physics/material.h>
#include <membrane/physics/thermal_noise.h>
#include <membrane/shape_options.h>
#include <membrane/shape_preconditioner.h>
#include <membrane/solvers/linear_solver.h>
#include <membrane/surface/geometry.h>

#include <deal.II/base/timer.h>

#include <memory>

namespace Membrane
{
  /// Components of the shape system's Q1 fields: W (0, 1, 2), gamma, H~ and, with the
  /// consistent curvature mass, B~_1, B~_2 (the normal row is the one tested with the H~
  /// component). Shared by the assembly, the constraints, the volume term and the block
  /// preconditioner.
  namespace ShapeComponents
  {
    constexpr unsigned int pressure = 3, curvature = 4, first_tangent = 5;
  } // namespace ShapeComponents

  /// Result of one shape step; all vectors owned.
  struct ShapeUpdate
  {
    Vector increment;      ///< W = X^{m+1} - X^m (vector space)
    Vector pressure;       ///< gamma (scalar space)
    Vector mean_curvature; ///< H~ (scalar space)
    double volume_pressure = 0; ///< p of the volume term (0 without one)
  };

  /// The global volume term of a closed surface in a shape step (see above).
  struct VolumeCoupling
  {
    bool   active        = false; ///< false: no volume term (patch, or Volume/Constraint = free)
    bool   fixed         = false; ///< true: p is the multiplier of integral W.n ds = volume_defect
    double pressure      = 0;     ///< the prescribed p when not fixed (not added again by corrections)
    double volume_defect = 0;     ///< V_target - V(X^m), or of X^m + W for a correction
    double compliance_scale = 0;  ///< tau L_X A, set by the step (the free surface's -b.A^-1 c)
  };

  class ShapeSolver
  {
  public:
    ShapeSolver(const Triangulation &triangulation, bool periodic,
                CurvatureMass curvature_mass = CurvatureMass::consistent);
    void setup();

    /// One step; `area_defect` (owned, scalar space) is a_target(psi_i) - a^m(psi_i) per
    /// vertex (the areas the step aims at, Simulator::area_target(), minus those of
    /// Gamma^m; zero to keep the current areas). `timer` (optional) gets "shape assembly" and "shape solve".
    /// An active `noise` adds the thermal force of this step (see above).
    ShapeUpdate step(const Surface &surface, const Geometry &geometry, const Material &material,
                     const ShapeOptions &options, const LinearSolverOptions &solver, double tau,
                     const Vector &area_defect, const Vector &phi_ghosted, const Vector &potential_ghosted,
                     dealii::TimerOutput *timer = nullptr, const VolumeCoupling &volume = {},
                     const ThermalNoise &noise = {});

    /// The projection of the last step's result back onto the area constraint: the
    /// last operator with the defect a_target - a(X^m + W) as the only right-hand side.
    /// Its result is added to that of step(); it costs one back-substitution.
    /// With a fixed volume the projection also restores V = V_target (`volume`'s defect
    /// is that of X^m + W); a prescribed pressure is not added again.
    ShapeUpdate correct_area(const Surface &surface, const Vector &area_defect, dealii::TimerOutput *timer = nullptr,
                             const VolumeCoupling &volume = {});

    /// -b.A^-1 c / (tau L_X A) of the last step with a volume term: 1 for a free surface,
    /// 0 where the local areas fix the volume; below the floor a fixed volume is left to them.
    double volume_compliance() const { return compliance; }
    bool   volume_held_by_areas() const { return compliance < volume_compliance_floor; }
    /// See shape_solver/volume.cc.
    static constexpr double volume_compliance_floor = 5e-3;

    /// Numeric factorizations so far, over all meshes (one per step and none for corrections,
    /// fewer with Linear solver/Reuse iterations).
    unsigned int n_factorizations() const
    {
      return earlier_factorizations + (solver ? solver->n_factorizations() : 0);
    }
    /// Type = block: FGMRES iterations and solves so far (this run segment).
    unsigned int n_krylov_iterations() const { return krylov_iterations; }
    unsigned int n_krylov_solves() const { return krylov_solves; }
    /// A resumed run continues the count of the run it continues (its checkpoint's).
    void resume_factorization_count(const unsigned int earlier) { earlier_factorizations += earlier; }

  private:
    void assemble(const Surface &surface, const Geometry &geometry, const Material &material,
                  const ShapeOptions &options, double tau, const Vector &phi, const Vector &potential,
                  const ThermalNoise &noise);
    /// Add the vertex area defect to the right-hand side of the area equation.
    void add_area_defect(const Surface &surface, const Vector &area_defect);
    ShapeUpdate solve(const Surface &surface, dealii::TimerOutput *timer, bool same_matrix = false);
    /// shape_solver/volume.cc: the p column c and the volume row b on Gamma^m.
    void assemble_volume_coupling(const Surface &surface, const Geometry &geometry, double tau_mobility);
    /// Eliminate p from the solution y of A y = r (z = A^-1 c computed after each new
    /// factorization); returns p.
    double apply_volume_coupling(Vector &solution, bool same_matrix);
    /// matrix * solution = right_hand_side with the step's solver: the LU of `solver`, or
    /// with Linear solver/Type = block, FGMRES with the block preconditioner.
    void linear_solve(Vector &solution, const Vector &right_hand_side, bool same_matrix);

    const bool                    periodic;
    const CurvatureMass           curvature_mass;
    /// Components: W (0-2), gamma (3), H~ (4), and B~_1 (5), B~_2 (6) unless lumped.
    /// Rows: with seven fields, those tested with W are the curvature rows and those of B~ the
    /// tangential law; with five, the W_0 row is the normal-projected curvature row and the
    /// W_1, W_2 rows hold the tangential law.
    FieldSpace                    space;
    SparseMatrix                  matrix;
    Vector                        rhs;
    std::unique_ptr<LinearSolver> solver; ///< kept across steps: the ordering is reused
    LinearSolverOptions           solver_options; ///< of the current step
    std::unique_ptr<ShapePreconditioner> block_preconditioner; ///< Type = block: one per mesh, operators of every step
    /// FGMRES basis size: the patch and vesicle solves converge in 15-60 iterations without a restart.
    static constexpr unsigned int krylov_restart = 80;
    unsigned int krylov_iterations = 0, krylov_solves = 0; ///< Type = block: FGMRES iterations and solves so far
    VolumeCoupling                volume;   ///< of the current solve
    Vector pressure_column, volume_row, pressure_response; ///< c, b and z = A^-1 c of the last step
    double compliance = 1; ///< volume_compliance()
    unsigned int earlier_factorizations = 0; ///< by the solvers of earlier meshes and run segments
  };
} // namespace Membrane
