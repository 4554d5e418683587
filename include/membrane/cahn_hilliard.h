#pragma once
// Cahn-Hilliard step on the current surface (MODEL.md section 4, step 2):
// unknowns (phi~, Y) in Q1 x Q1,
//   ((phi~ - phi^m)/tau, psi) + L_phi (grad_s Y, grad_s psi) = 0
//   (Y, chi) - sigma xi^2 (grad_s phi~, grad_s chi) - sigma S (phi~ - phi^m, chi)
//       = (sigma f'(phi^m) + c(phi^m, H^m, K^m), chi)
// with the curvature coupling c = 1/2 kappa'(H - H0)^2 - kappa (H - H0) H0' + kappa_G' K.
// The implicit part S(phi~ - phi^m) selects the scheme:
//   stabilized (default): S = s, a constant, energy stable for
//       s >= max|f''|/2 = 9/8 on [-1, 1] (Shen & Yang 2010); s = 1.5 covers |phi| <= 1.1;
//   linearized: S = f''(phi^m), Newton linearisation of f' (accurate, not unconditionally stable);
//   explicit:   S = 0, the paper's choice (tau limited by the double well).

#include <membrane/cahn_hilliard_options.h>
#include <membrane/physics/material.h>
#include <membrane/physics/thermal_noise.h>
#include <membrane/solvers/linear_solver.h>
#include <membrane/surface/geometry.h>

#include <deal.II/base/timer.h>

#include <memory>
#include <string>

namespace Membrane
{
  class CahnHilliardSolver
  {
  public:
    CahnHilliardSolver(const Triangulation &triangulation, bool periodic);
    void setup();

    /// phi^m -> phi^{m+1}; returns the linear-solver iteration count. `timer`
    /// (optional) gets the sections "Cahn-Hilliard assembly" and "Cahn-Hilliard solve".
    unsigned int step(const Surface &surface, const Geometry &geometry, const Material &material,
                      const CahnHilliardOptions &options, const LinearSolverOptions &solver, double tau,
                      const Vector &phi_old_ghosted, Vector &phi_new_owned, Vector &chemical_potential_owned,
                      dealii::TimerOutput *timer = nullptr, const ThermalNoise &noise = {});

  private:
    void assemble(const Surface &surface, const Geometry &geometry, const Material &material,
                  const CahnHilliardOptions &options, double tau, const Vector &phi_old, const ThermalNoise &noise);

    const bool                    periodic;
    FieldSpace                    space; ///< component 0: phi, component 1: Y
    SparseMatrix                  matrix;
    Vector                        rhs;
    std::unique_ptr<LinearSolver> solver; ///< kept across steps: the ordering is reused
  };
} // namespace Membrane
