// Thermal noise (MODEL.md section 10). The Cahn-Hilliard step: equipartition
// of phi in one phase. On a flat 16 x 16 patch at phi_0 = -1 with sigma = 1, xi
// = 0.1, L_phi = 1, the fluctuating linearized Cahn-Hilliard equation is, mode
// by mode, an Ornstein-Uhlenbeck process with the stationary variance
// <|phi_q|^2> = k_BT / (A sigma (xi^2 q^2 + f''(phi_0))), f''(-1) = 9/4. The
// linearized scheme is backward Euler for it, whose stationary variance is that
// divided by 1 + lambda tau / 2 (lambda = L_phi sigma q^2 (xi^2 q^2 + f''), the
// mode's decay rate). The modes |q| = 2 pi (four real amplitudes) and 2 pi sqrt
// 2 are compared with it, with an error bar from batch means; the bar is small
// enough that a noise amplitude off by 20 % (variance off by 44 %) fails. The
// noise is conserved: integral phi ds does not change.
#include "fixed_surface.h"
#include "parameter_text.h"

#include <membrane/analysis/fourier_modes.h>
#include <membrane/physics/thermal_noise.h>
#include <membrane/simulator.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <complex>
#include <filesystem>
#include <iostream>
#include <numeric>
#include <vector>

using namespace Membrane;

TEST(Thermal, GeneratorIsAPureFunctionOfItsKeyWithUnitVariance)
{
  EXPECT_EQ(standard_normal(3, 17, 12345, 1), standard_normal(3, 17, 12345, 1));
  EXPECT_NE(standard_normal(3, 17, 12345, 1), standard_normal(3, 17, 12345, 0));
  EXPECT_NE(standard_normal(3, 17, 12345, 1), standard_normal(3, 18, 12345, 1));
  EXPECT_NE(standard_normal(3, 17, 12345, 1), standard_normal(4, 17, 12345, 1));
  const unsigned int n   = 200000;
  double             sum = 0, square = 0, fourth = 0;
  for (unsigned int i = 0; i < n; ++i)
    {
      const double x = standard_normal(1, i / 100, i % 100, i % 2);
      sum += x;
      square += x * x;
      fourth += x * x * x * x;
    }
  // Standard errors: 1/sqrt(n) for the mean, sqrt(2/n) for the variance,
  // sqrt(96/n) for the fourth moment (3 for a normal).
  EXPECT_LT(std::abs(sum / n), 4 / std::sqrt(n));
  EXPECT_LT(std::abs(square / n - 1), 4 * std::sqrt(2.0 / n));
  EXPECT_LT(std::abs(fourth / n - 3), 4 * std::sqrt(96.0 / n));
}

namespace
{
  /// <|phi_q|^2> of a flat 16 x 16 patch in one phase (phi_0 = -1, sigma = 1, xi = 0.1, L_phi = 1,
  /// k_BT = 1e-4, the linearized scheme) at a fixed tau, over the shells |k|^2 = 1 and 2, each
  /// divided by the continuum's equipartition k_BT / (A sigma (xi^2 q^2 + f''(phi_0))), with its
  /// error bar from 20 batch means.
  struct PhaseVariance
  {
    std::array<double, 2> ratio{}, error{}, lambda_tau{};
  };

  PhaseVariance measure_phase_variance(const double tau, const unsigned int warm_up, const unsigned int steps)
  {
    constexpr int         n = 16;
    Testing::FixedSurface setup(n);
    setup.options.scheme = "linearized";
    InitialPhaseOptions uniform;
    uniform.type          = "uniform";
    uniform.uniform_value = -1;
    setup.set_phase(uniform);
    const double mass = setup.mass();

    const double kT = 1e-4, sigma = 1, xi = 0.1, f2 = 9.0 / 4;
    // Nodal positions of the scalar dofs, for the Fourier amplitudes (the patch
    // area is 1, n^2 vertices).
    const auto                   &space = setup.surface.scalar_space();
    std::vector<dealii::Point<3>> where(space.dof_handler().n_dofs());
    for (const auto &cell : space.dof_handler().active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        where[cell->vertex_dof_index(v, 0)] = cell->vertex(v);
    // Real amplitudes cos and sin of the modes k = (1,0), (0,1) (|q| = 2 pi) and
    // (1,1), (1,-1).
    const std::vector<std::pair<int, int>> modes      = {{1, 0}, {0, 1}, {1, 1}, {1, -1}};
    const auto                             amplitudes = [&]() {
      std::vector<double> a(2 * modes.size(), 0.0);
      for (std::size_t i = 0; i < where.size(); ++i)
        if (!space.constraints().is_constrained(i)) // the periodic copies are counted once
          for (std::size_t m = 0; m < modes.size(); ++m)
            {
              const double arg = 2 * M_PI * (modes[m].first * where[i][0] + modes[m].second * where[i][1]);
              a[2 * m] += setup.phi[i] * std::cos(arg) / (n * n);
              a[2 * m + 1] += setup.phi[i] * std::sin(arg) / (n * n);
            }
      return a;
    };

    const unsigned int               batches = 20;
    std::vector<std::vector<double>> batch(2, std::vector<double>(batches, 0.0)); // per |q| group
    for (unsigned int step = 0; step < warm_up + steps; ++step)
      {
        setup.step(tau, ThermalNoise{kT, 7, step});
        if (step < warm_up)
          continue;
        const auto   a         = amplitudes();
        const double per_batch = static_cast<double>(steps / batches);
        // |phi_q|^2 of a complex mode is cos^2 + sin^2 of its real amplitudes.
        batch[0][(step - warm_up) * batches / steps] +=
          (a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3]) / 2 / per_batch;
        batch[1][(step - warm_up) * batches / steps] +=
          (a[4] * a[4] + a[5] * a[5] + a[6] * a[6] + a[7] * a[7]) / 2 / per_batch;
      }
    EXPECT_LT(std::abs(setup.mass() - mass), 1e-12);

    PhaseVariance result;
    for (unsigned int group = 0; group < 2; ++group)
      {
        const double q2       = std::pow(2 * M_PI, 2) * (group == 0 ? 1 : 2);
        const double expected = kT / (sigma * (xi * xi * q2 + f2));
        const double mean     = std::accumulate(batch[group].begin(), batch[group].end(), 0.0) / batches;
        double       spread   = 0;
        for (const double b : batch[group])
          spread += (b - mean) * (b - mean) / (batches - 1);
        result.ratio[group]      = mean / expected;
        result.error[group]      = std::sqrt(spread / batches) / expected;
        result.lambda_tau[group] = setup.material.phase_mobility * sigma * q2 * (xi * xi * q2 + f2) * tau;
        std::cout << "tau = " << tau << ", |q|^2 = " << q2 << ", lambda tau = " << result.lambda_tau[group]
                  << ": <|phi_q|^2> / equipartition = " << result.ratio[group] << " +- " << result.error[group]
                  << ", backward Euler 1 / (1 + lambda tau / 2) = " << 1 / (1 + result.lambda_tau[group] / 2)
                  << std::endl;
      }
    return result;
  }
} // namespace

// Linearized about phi_0 every Fourier mode of phi is an Ornstein-Uhlenbeck process with the
// stationary variance of equipartition; the linearized scheme is backward Euler for it, whose
// stationary variance is that divided by 1 + lambda tau / 2 (lambda the mode's decay rate).
// At lambda tau <= 0.06 the bias is under 3 %.
TEST(Thermal, PhaseFluctuationsInOnePhaseFollowEquipartition)
{
  const PhaseVariance v = measure_phase_variance(2.5e-4, 400, 8000);
  for (unsigned int group = 0; group < 2; ++group)
    {
      const double expected = 1 / (1 + v.lambda_tau[group] / 2);
      EXPECT_LT(v.error[group], 0.07); // resolves a 44 % change of the variance
      EXPECT_LT(std::abs(v.ratio[group] / expected - 1), std::max(3 * v.error[group], 0.05));
    }
}

// The bias of a fixed tau (issue item: the stationary statistics against tau): at tau = 4e-3,
// lambda tau = 0.42 and 0.96 on the two shells, and the measured variances fall below
// equipartition by the backward-Euler factor 1 / (1 + lambda tau / 2) = 0.83 and 0.68, not by
// nothing (a ratio of 1 is more than three error bars away on the second shell).
TEST(Thermal, PhaseVarianceAtLargeStepsHasTheBackwardEulerBias)
{
  const PhaseVariance v = measure_phase_variance(4e-3, 100, 2000);
  for (unsigned int group = 0; group < 2; ++group)
    {
      const double expected = 1 / (1 + v.lambda_tau[group] / 2);
      EXPECT_LT(v.error[group], 0.06);
      EXPECT_LT(std::abs(v.ratio[group] / expected - 1), std::max(3 * v.error[group], 0.05));
    }
  EXPECT_GT(1 - v.ratio[1], 3 * v.error[1]); // the bias is measured, not within the noise
}

// Shape noise (MODEL.md section 10): one step from a flat patch at rest, where the linearized
// step decouples the Fourier modes. The height of mode k obeys (1 + lambda tau) h_k = tau L_X
// eta_k with lambda = L_X kappa q^4 (the bending, implicit), so <|h_k|^2> = 2 k_BT tau L_X /
// (1 + lambda tau)^2 exactly when the force's covariance is (2 k_BT / (tau L_X)) times the mass
// matrix (the Q1 mass symbol and that of the interpolant's Fourier integral cancel to O(q^4 h^4)).
// The tangential motion has no restoring force, but the local area constraint removes its
// longitudinal (compressive) part: the transverse amplitude has the variance 2 k_BT tau L_X,
// the longitudinal one almost none. Independent trials differ in the noise seed; a noise off
// by 20 % (variance off by 44 %) fails.
TEST(Thermal, OneShapeStepHasTheCovarianceOfTheDissipation)
{
  const double kT = 1e-4, mobility = 1, tau = 3.2e-4; // lambda tau = 0.5 for |k| = 1
  const auto   dir = std::filesystem::temp_directory_path() / "membrane_thermal_shape_step";
  const std::vector<std::array<int, 2>> modes = {{{1, 0}}, {{0, 1}}, {{1, 1}}, {{1, -1}}};
  const unsigned int                    trials = 300;
  // Per shell |k|^2 = 1, 2: the sums of |h_k|^2, |W_T,k|^2 and |W_L,k|^2 over its two modes.
  std::array<double, 2> height{}, transverse{}, longitudinal{};
  std::array<std::vector<double>, 2> height_samples;
  for (unsigned int trial = 0; trial < trials; ++trial)
    {
      const Parameters parameters = Testing::noisy_step_parameters(R"(
subsection Mesh
  set Cells per side = 16
end
)", kT, trial + 1, mobility, tau, 0.1, dir.string());
      Simulator simulator(parameters, RunOptions{true, "", "test"});
      simulator.initialize();
      ASSERT_TRUE(simulator.advance());
      const Surface &surface = simulator.current_surface();
      std::array<std::vector<std::complex<double>>, spacedim> amplitude;
      for (unsigned int c = 0; c < spacedim; ++c)
        amplitude[c] = fourier_amplitudes(surface.vector_space(), surface.displacement(), c, modes);
      for (std::size_t m = 0; m < modes.size(); ++m)
        {
          const unsigned int  shell = m / 2;
          const double        k1 = modes[m][0], k2 = modes[m][1], norm = std::hypot(k1, k2);
          const auto          along = (k1 * amplitude[0][m] + k2 * amplitude[1][m]) / norm;
          const auto          across = (-k2 * amplitude[0][m] + k1 * amplitude[1][m]) / norm;
          height[shell] += std::norm(amplitude[2][m]);
          transverse[shell] += std::norm(across);
          longitudinal[shell] += std::norm(along);
        }
    }
  for (unsigned int shell = 0; shell < 2; ++shell)
    {
      const double q4        = std::pow(4 * M_PI * M_PI * (shell + 1), 2);
      const double free_step = 2 * kT * tau * mobility; // <|W_k|^2> of one component without a force
      const double samples   = 2.0 * trials;            // two modes per shell
      const double h2        = height[shell] / samples / (free_step / std::pow(1 + mobility * q4 * tau, 2));
      const double t2        = transverse[shell] / samples / free_step;
      const double l2        = longitudinal[shell] / samples / free_step;
      // |h_k|^2 of a complex Gaussian amplitude is exponential: relative standard error 1/sqrt(n).
      const double error = 1 / std::sqrt(samples);
      std::cout << "|k|^2 = " << shell + 1 << ": <|h_k|^2> / expected = " << h2 << ", transverse " << t2
                << ", longitudinal " << l2 << " (standard error " << error << ")" << std::endl;
      EXPECT_LT(std::abs(h2 - 1), 3 * error + 0.03);
      EXPECT_LT(std::abs(t2 - 1), 3 * error + 0.03);
      EXPECT_LT(l2, 0.05);
    }
  std::filesystem::remove_all(dir);
}
