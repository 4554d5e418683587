#pragma once
// Area-difference elasticity of a closed bilayer (MODEL.md section 11):
//   F_ADE = pi k / (2 A) (M - M_0)^2,   M = integral H ds,
// k = alpha kappa (Area difference/Stiffness), A the membrane area, and
// M_0 = -8 pi R_0 m_0 with R_0 = sqrt(A / (4 pi)): H = -2/R on a sphere with outward normals
// (docs/vesicles.md), so M = -8 pi R there and the reduced difference m = -M / (8 pi R_0) is 1.
// The two monolayers at distance D differ in area by D M; m_0 is the preferred difference
// Delta A_0 / (8 pi D R_0).
//
// Its first variation is a global factor times that of M. For a normal move V_n,
//   dM[V_n n] = integral (dH + H div_s(V_n n)) ds = integral (lap_s V_n + |b|^2 V_n - H^2 V_n) ds
//             = -2 integral K V_n ds,
// and tangential moves do not change M on a closed surface. So E_n gains
// -2 (pi k / A)(M - M_0) K, with the factor lagged at Gamma^m (explicit), and the normal row's
// right-hand side + tau L_X (2 (pi k / A)(M - M_0) K, psi). No dependence on phi.
#include <membrane/physics/free_energy.h>

#include <deal.II/base/parameter_handler.h>

namespace Membrane
{
  /// The subsection Area difference of Material (the caller enters Material).
  void                  declare_area_difference_parameters(dealii::ParameterHandler &prm);
  AreaDifferenceOptions parse_area_difference_parameters(dealii::ParameterHandler &prm);

  /// M = integral H ds and the area A of Gamma^m; collective.
  std::pair<double, double> total_mean_curvature_and_area(const Surface &surface, const Geometry &geometry);

  class AreaDifferenceEnergy : public FreeEnergyTerm
  {
  public:
    explicit AreaDifferenceEnergy(const AreaDifferenceOptions &options)
      : options(options)
    {}
    void   prepare(const Surface &surface, const Geometry &geometry) override;
    void   add_energy(const TermPoint &, double, EnergyTerms &) const override {}
    void   add_global_energy(EnergyTerms &energy) const override;
    void   add_shape_force(const TermPoint &point, ShapeForce &force) const override;

  private:
    const AreaDifferenceOptions options;
    double                      area = 0, excess = 0; ///< A and M - M_0 of Gamma^m (prepare())
  };
} // namespace Membrane
