#pragma once
// The free energy as a sum of terms (MODEL.md section 2). Each term lives in one file pair
// under physics/terms/ and gives every scheme what it needs from it, at one quadrature point
// of the current surface Gamma^m with the fields of step m:
//  - its energy density (compute_energy, physics/energy.cc);
//  - its explicit part of the chemical potential Y = dF/dphi (the Cahn-Hilliard step);
//  - its part of the shape system's normal row (shape_solver/assembly.cc), split into
//      the implicit stiffness on H~, -tau L_X kappa ((grad H~, grad psi) + m (H~, psi)),
//      which the block preconditioner takes too (shape_preconditioner.cc), and
//      the explicit force, + tau L_X ((flux, grad psi) + (source, psi));
//  - the weight of its implicit stiffness in the tangential law (Shape/Line stiffness);
//  - for a term that does not depend on the curvature, its stress T (dF[V] = integral
//    T : grad_s V ds), from which Shape/Line force = stress takes its whole shape force as
//    the exact derivative of the discrete energy (physics/stress_force.h).
// The tangential law's force Y grad phi is the chemical potential's, so a term that
// depends on phi enters it through potential(). The local area constraint, the volume
// term and the thermal noise are not energy terms of X and phi alone: they stay with the
// shape system (shape_solver.h).
//
// Adding a term: a class derived from FreeEnergyTerm in physics/terms/, its parameters,
// and one line in FreeEnergy's constructor (free_energy.cc).

#include <membrane/physics/energy.h>
#include <membrane/physics/material.h>
#include <membrane/surface/geometry.h>

#include <deal.II/base/tensor.h>

#include <memory>
#include <vector>

namespace Membrane
{
  /// The fields of Gamma^m at one quadrature point. Each scheme fills what its calls read:
  /// energy and potential read phi, grad_phi, H, K; the shape terms also nu and grad_nu.
  struct TermPoint
  {
    double                      phi = 0, H = 0, K = 0;
    dealii::Tensor<1, spacedim> grad_phi, nu;
    dealii::Tensor<2, spacedim> grad_nu; ///< grad_s nu: grad_nu[c][e] = d nu_c / dx_e
  };

  /// The normal row's implicit stiffness on H~ (see above): kappa and m.
  struct NormalStiffness
  {
    double kappa = 0, curvature_mass = 0;
  };

  /// The normal row's explicit force (see above): multipliers of grad psi and of psi.
  struct ShapeForce
  {
    dealii::Tensor<1, spacedim> flux;
    double                      source = 0;
  };

  class FreeEnergyTerm
  {
  public:
    virtual ~FreeEnergyTerm() = default;
    /// Global quantities of Gamma^m that the pointwise calls use (collective); once per
    /// surface, before them.
    virtual void   prepare(const Surface &, const Geometry &) {}
    /// Adds density * ds to its entries of `energy`.
    virtual void   add_energy(const TermPoint &point, double ds, EnergyTerms &energy) const = 0;
    /// Its explicit part of Y at phi^m (0: none, or treated implicitly by the Cahn-Hilliard step).
    virtual double potential(const TermPoint &) const { return 0; }
    /// Adds the part of its energy that is not an integral of a density (after the sum over ranks).
    virtual void   add_global_energy(EnergyTerms &) const {}
    virtual void   add_normal_stiffness(const TermPoint &, NormalStiffness &) const {}
    virtual void   add_shape_force(const TermPoint &, ShapeForce &) const {}
    /// Multiplies Shape/Line stiffness * tau L_X in the tangential law's implicit stiffness.
    virtual double tangential_stiffness_weight() const { return 0; }
    /// Whether the term has a stress (add_stress); such a term's add_shape_force is the same
    /// force in the potential form of the reference scheme.
    virtual bool   has_stress() const { return false; }
    /// Adds its stress T at (phi, grad_phi): dF[V] = integral T : grad_s V ds for a variation
    /// V of X with phi carried by the material (T[c][e] multiplies d V_c / dx_e).
    virtual void   add_stress(const TermPoint &, dealii::Tensor<2, spacedim> &) const {}
  };

  /// The terms of a material, in a fixed order (sums over them are reproducible).
  class FreeEnergy
  {
  public:
    explicit FreeEnergy(const Material &material);

    /// Call once per surface before the pointwise calls (collective).
    void            prepare(const Surface &surface, const Geometry &geometry);
    void            add_global_energy(EnergyTerms &energy) const;
    void            add_energy(const TermPoint &point, double ds, EnergyTerms &energy) const;
    double          potential(const TermPoint &point) const;
    NormalStiffness normal_stiffness(const TermPoint &point) const;
    /// The normal row's force; without_stress_terms: only of the terms without a stress.
    ShapeForce      shape_force(const TermPoint &point, bool without_stress_terms = false) const;
    /// The sum of the terms' stresses (reads phi and grad_phi).
    dealii::Tensor<2, spacedim> stress(const TermPoint &point) const;
    double          tangential_stiffness_weight() const;

  private:
    std::vector<std::unique_ptr<FreeEnergyTerm>> terms;
  };
} // namespace Membrane
