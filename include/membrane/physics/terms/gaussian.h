#pragma once
// Gaussian bending energy with a phase-dependent modulus (MODEL.md section 2):
//   F_G = integral kappa_G(phi) K ds.
// With a constant kappa_G it is a topological invariant (Gauss-Bonnet) and moves nothing; a
// jump of kappa_G across a domain boundary pulls on the boundary's geodesic curvature.
// Discrete energy: kappa_G_c 2 pi chi (Gauss-Bonnet, exact) + integral (kappa_G(phi) - kappa_G_c) K^m ds
// with kappa_G_c = (kappa_G(+1) + kappa_G(-1)) / 2, so that a uniform kappa_G adds a constant.
#include <membrane/physics/free_energy.h>

namespace Membrane
{
  class GaussianEnergy : public FreeEnergyTerm
  {
  public:
    explicit GaussianEnergy(const Material &material)
      : material(material)
    {}
    void   prepare(const Surface &surface, const Geometry &geometry) override;
    void   add_energy(const TermPoint &point, double ds, EnergyTerms &energy) const override;
    void   add_global_energy(EnergyTerms &energy) const override;
    double potential(const TermPoint &point) const override;
    void   add_shape_force(const TermPoint &point, ShapeForce &force) const override;

  private:
    const Material &material;
    int             euler_characteristic = 0;
    /// kappa_G_c, the part of kappa_G(phi) whose energy Gauss-Bonnet gives exactly (set by prepare).
    double constant_part = 0;
  };
} // namespace Membrane
