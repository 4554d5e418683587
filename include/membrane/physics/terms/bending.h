#pragma once
// Helfrich bending energy with phase-dependent moduli (MODEL.md section 2):
//   F_b = integral 1/2 kappa(phi) (H - H0(phi))^2 ds.
#include <membrane/physics/free_energy.h>

namespace Membrane
{
  class BendingEnergy : public FreeEnergyTerm
  {
  public:
    explicit BendingEnergy(const Material &material)
      : material(material)
    {}
    void   add_energy(const TermPoint &point, double ds, EnergyTerms &energy) const override;
    double potential(const TermPoint &point) const override;
    void   add_normal_stiffness(const TermPoint &point, NormalStiffness &stiffness) const override;
    void   add_shape_force(const TermPoint &point, ShapeForce &force) const override;

  private:
    const Material &material;
  };
} // namespace Membrane
