#pragma once
// Cahn-Hilliard line energy of the domain boundaries (MODEL.md section 2):
//   F_l = integral G ds,   G = sigma (xi^2 / 2 |grad_s phi|^2 + f(phi)),
// with the double well f of physics/double_well.h (sharp-interface line tension sigma xi).
// Its part of Y, sigma (f'(phi) - xi^2 lap_s phi), is the Cahn-Hilliard operator itself and
// is treated (semi-)implicitly by that step (cahn_hilliard.cc), so potential() is 0 here.
#include <membrane/physics/free_energy.h>

namespace Membrane
{
  class LineEnergy : public FreeEnergyTerm
  {
  public:
    explicit LineEnergy(const Material &material)
      : sigma(material.line_tension)
      , xi(material.transition_length)
      , xi2(xi * xi)
    {}
    void   add_energy(const TermPoint &point, double ds, EnergyTerms &energy) const override;
    void   add_shape_force(const TermPoint &point, ShapeForce &force) const override;
    double tangential_stiffness_weight() const override { return sigma * xi2; }
    bool   has_stress() const override { return true; }
    void   add_stress(const TermPoint &point, dealii::Tensor<2, spacedim> &T) const override;

  private:
    const double sigma, xi, xi2;
  };
} // namespace Membrane
