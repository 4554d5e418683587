#include <membrane/physics/free_energy.h>
#include <membrane/physics/terms/area_difference.h>
#include <membrane/physics/terms/bending.h>
#include <membrane/physics/terms/gaussian.h>
#include <membrane/physics/terms/line_energy.h>

namespace Membrane
{
  FreeEnergy::FreeEnergy(const Material &material)
  {
    // The order fixes the order of every sum over the terms.
    terms.push_back(std::make_unique<BendingEnergy>(material));
    terms.push_back(std::make_unique<GaussianEnergy>(material));
    terms.push_back(std::make_unique<LineEnergy>(material));
    if (material.area_difference.active())
      terms.push_back(std::make_unique<AreaDifferenceEnergy>(material.area_difference));
  }

  void FreeEnergy::prepare(const Surface &surface, const Geometry &geometry)
  {
    for (const auto &term : terms)
      term->prepare(surface, geometry);
  }

  void FreeEnergy::add_global_energy(EnergyTerms &energy) const
  {
    for (const auto &term : terms)
      term->add_global_energy(energy);
  }

  void FreeEnergy::add_energy(const TermPoint &point, const double ds, EnergyTerms &energy) const
  {
    for (const auto &term : terms)
      term->add_energy(point, ds, energy);
  }

  double FreeEnergy::potential(const TermPoint &point) const
  {
    double Y = 0;
    for (const auto &term : terms)
      Y += term->potential(point);
    return Y;
  }

  NormalStiffness FreeEnergy::normal_stiffness(const TermPoint &point) const
  {
    NormalStiffness stiffness;
    for (const auto &term : terms)
      term->add_normal_stiffness(point, stiffness);
    return stiffness;
  }

  ShapeForce FreeEnergy::shape_force(const TermPoint &point, const bool without_stress_terms) const
  {
    ShapeForce force;
    for (const auto &term : terms)
      if (!(without_stress_terms && term->has_stress()))
        term->add_shape_force(point, force);
    return force;
  }

  dealii::Tensor<2, spacedim> FreeEnergy::stress(const TermPoint &point) const
  {
    dealii::Tensor<2, spacedim> T;
    for (const auto &term : terms)
      term->add_stress(point, T);
    return T;
  }

  double FreeEnergy::tangential_stiffness_weight() const
  {
    double weight = 0;
    for (const auto &term : terms)
      weight += term->tangential_stiffness_weight();
    return weight;
  }
} // namespace Membrane
