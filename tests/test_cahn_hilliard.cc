// Cahn-Hilliard on fixed surfaces: linear growth rates against the analytic
// dispersion relation, exact mass conservation, energy decay in spinodal
// decomposition, and the sign of the curvature coupling.
#include "fixed_surface.h"

#include <deal.II/base/numbers.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <gtest/gtest.h>

using namespace Membrane;
using dealii::numbers::PI;

namespace
{
  /// integral over the flat patch of phi * cos(2 pi k.u).
  double mode_amplitude(const Testing::FixedSurface &s, const int k1, const int k2)
  {
    const dealii::QGauss<dim>             quadrature(3);
    dealii::FEValues<dim, spacedim>       fe_values(s.surface.mapping(), s.surface.scalar_space().fe(), quadrature,
                                                    dealii::update_values | dealii::update_quadrature_points |
                                                      dealii::update_JxW_values);
    std::vector<double>                   values(quadrature.size());
    double                                local = 0;
    for (const auto &cell : s.surface.scalar_space().dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values.get_function_values(s.phi, values);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              const auto &x = fe_values.quadrature_point(q);
              local += values[q] * std::cos(2 * PI * (k1 * x[0] + k2 * x[1])) * fe_values.JxW(q);
            }
        }
    return dealii::Utilities::MPI::sum(local, MPI_COMM_WORLD);
  }

  /// Mean of phi over the disc |u - (1/2,1/2)| < radius, by vertex average.
  double cap_mean(const Testing::FixedSurface &s, const double radius)
  {
    double sum = 0, count = 0;
    for (const auto &cell : s.surface.scalar_space().dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          if (cell->vertex(v).distance(dealii::Point<spacedim>(0.5, 0.5, 0)) < radius)
            {
              sum += s.phi[cell->vertex_dof_index(v, 0)];
              count += 1;
            }
    return dealii::Utilities::MPI::sum(sum, MPI_COMM_WORLD) / dealii::Utilities::MPI::sum(count, MPI_COMM_WORLD);
  }
} // namespace

TEST(CahnHilliard, GrowthRatesMatchDispersionRelation)
{
  // omega(q) = -L_phi sigma q^2 (f''(0) + xi^2 q^2), f''(0) = -9/8, xi = 0.1:
  // modes (1,0) and (1,1) grow, (2,0) decays. The three evolve independently
  // in the linear regime, so one run measures all of them.
  Testing::FixedSurface s(64);
  const std::vector<std::array<int, 2>> modes{{{1, 0}}, {{1, 1}}, {{2, 0}}};
  InitialPhaseOptions   initial;
  initial.type       = "expression";
  initial.expression = "1e-6 * (cos(2*pi*x) + cos(2*pi*(x+y)) + cos(4*pi*x))";
  s.set_phase(initial);

  std::vector<double> start;
  for (const auto &k : modes)
    start.push_back(mode_amplitude(s, k[0], k[1]));
  const double tau = 1e-5, t_end = 1e-3;
  for (double t = 0; t < t_end - 1e-12; t += tau)
    s.step(tau);

  for (unsigned int m = 0; m < modes.size(); ++m)
    {
      const double q2       = 4 * PI * PI * (modes[m][0] * modes[m][0] + modes[m][1] * modes[m][1]);
      const double expected = -q2 * (-9.0 / 8.0 + 0.01 * q2);
      const double measured = std::log(mode_amplitude(s, modes[m][0], modes[m][1]) / start[m]) / t_end;
      std::printf("mode (%d,%d): omega measured %.4f, analytic %.4f, relative error %.2e\n", modes[m][0],
                  modes[m][1], measured, expected, std::abs(measured / expected - 1));
      EXPECT_NEAR(measured / expected, 1.0, 0.03);
    }
}

TEST(CahnHilliard, MassConservedToRoundOffOnCurvedSurface)
{
  Testing::FixedSurface s(32);
  set_bump(s.surface, 0.5, 1.3);
  s.update_geometry();
  s.material.line_tension = 450;
  s.material.transition_length = 0.03;
  s.material.phase_mobility = 0.05;
  s.material.spontaneous_curvature = make_linear_law(-10, 5);
  InitialPhaseOptions initial;
  initial.random_min = -0.6;
  initial.random_max = -0.2;
  s.set_phase(initial);
  const double mass0 = s.mass();
  for (unsigned int i = 0; i < 20; ++i)
    s.step(1e-3);
  std::printf("mass %.16e -> %.16e, relative change %.2e\n", mass0, s.mass(), std::abs(s.mass() / mass0 - 1));
  EXPECT_LT(std::abs(s.mass() / mass0 - 1), 1e-12);
}

TEST(CahnHilliard, EnergyNeverIncreasesInSpinodalDecomposition)
{
  // The paper's sigma, xi, L_phi; tau = 1e-4 is ~ 20x the explicit scheme's limit.
  Testing::FixedSurface s(32);
  s.material.line_tension      = 450;
  s.material.transition_length = 0.03;
  s.material.phase_mobility    = 0.05;
  InitialPhaseOptions initial;
  initial.random_min = -0.1;
  initial.random_max = 0.1;
  initial.seed       = 7;
  s.set_phase(initial);
  const double initial_energy = s.energy();
  double       previous = initial_energy, largest_increase = -1e300;
  for (unsigned int i = 0; i < 150; ++i)
    {
      s.step(1e-4);
      const double e = s.energy();
      largest_increase = std::max(largest_increase, e - previous);
      previous = e;
    }
  const auto [low, high] = global_range(s.phi);
  std::printf("energy %.6e -> %.6e, largest step increase %.3e, phi in [%.3f, %.3f]\n", initial_energy, previous,
              largest_increase, low, high);
  EXPECT_LE(largest_increase, 1e-10 * initial_energy);
  // The run really separated: energy halved, both pure phases present.
  EXPECT_LT(previous, 0.5 * initial_energy);
  EXPECT_LT(low, -0.9);
  EXPECT_GT(high, 0.9);
}

TEST(CahnHilliard, PhaseWithFittingSpontaneousCurvatureCollectsOnCap)
{
  // On the bump's cap H < 0. With H0_A = -10 phase A (phi = +1) fits the cap;
  // with the signs exchanged phase B does.
  double cap_excess[2];
  for (const int sign : {1, -1})
    {
      Testing::FixedSurface s(32);
      set_bump(s.surface, 0.5, 1.3);
      s.update_geometry();
      s.material.line_tension          = 90;
      s.material.transition_length     = 0.03;
      s.material.phase_mobility        = 0.05;
      s.material.bending_rigidity      = make_linear_law(1.5, 1.5);
      s.material.spontaneous_curvature = make_linear_law(-10.0 * sign, 10.0 * sign);
      InitialPhaseOptions initial;
      initial.type = "uniform";
      s.set_phase(initial);
      for (unsigned int i = 0; i < 50; ++i)
        s.step(2e-4);
      cap_excess[sign > 0 ? 0 : 1] = cap_mean(s, 0.15) - s.mass() / s.surface.area();
      std::printf("H0_A = %+.0f: cap mean phi - global mean = %+.4f\n", -10.0 * sign, cap_excess[sign > 0 ? 0 : 1]);
    }
  EXPECT_GT(cap_excess[0], 0.1);
  EXPECT_LT(cap_excess[1], -0.1);
}
