#pragma once
// Gaussian bending energy with a phase-dependent modulus (MODEL.md section 2):
//   F_G = integral kappa_G(phi) K ds.
// With a constant kappa_G it is a topological invariant (Gauss-Bonnet) and moves nothing; a
// jump of kappa_G across a domain boundary pulls on the boundary's geodesic curvature.
#include <membrane/physics/free_energy.h>

namespace Membrane
{
  class GaussianEnergy : public FreeEnergyTerm
  {
  public:
    explicit GaussianEnergy(const Material &material)
      : material(material)
    {}
    void   add_energy(const TermPoint &point, double ds, EnergyTerms &energy) const override;
    double potential(const TermPoint &point) const override;
    void   add_shape_force(const TermPoint &point, ShapeForce &force) const override;

  private:
    const Material &material;
  };
} // namespace Membrane
