// Moduli laws (values at the pure phases, derivatives against finite
// differences) and the initial order parameter (bounds, prescribed mass).
#include "fixed_surface.h"

#include <gtest/gtest.h>

using namespace Membrane;

namespace
{
  double slope(const ModulusLaw &law, const double phi)
  {
    return (law.value(phi + 1e-6) - law.value(phi - 1e-6)) / 2e-6;
  }
} // namespace

TEST(Moduli, LawsTakePhaseValuesAndConsistentDerivatives)
{
  const auto linear = make_linear_law(3, 1);
  const auto tanh   = make_tanh_law(3, 1);
  const auto user   = make_expression_law("2 + tanh(phi)/tanh(1)", "(1 - tanh(phi)^2)/tanh(1)", "test");
  for (const ModulusLaw *law : {linear.get(), tanh.get(), user.get()})
    {
      EXPECT_NEAR(law->value(1), 3, 1e-14);
      EXPECT_NEAR(law->value(-1), 1, 1e-14);
      for (const double phi : {-1.1, -0.5, 0.0, 0.3, 1.0})
        EXPECT_NEAR(law->derivative(phi), slope(*law, phi), 1e-7);
    }
  // Linear and tanh agree at the pure phases and differ in between (paper 7.2).
  EXPECT_NEAR(linear->value(0.5), 2.5, 1e-14);
  EXPECT_NEAR(tanh->value(0.5), 2 + std::tanh(0.5) / std::tanh(1.0), 1e-14);
}

TEST(Moduli, ExpressionWithWrongDerivativeIsRejected)
{
  EXPECT_THROW(make_expression_law("phi^2", "phi", "test"), dealii::ExceptionBase);
}

TEST(InitialPhase, RandomFieldWithinBoundsWithUniformStatistics)
{
  Testing::FixedSurface s(64);
  InitialPhaseOptions   initial;
  initial.random_min = -0.57;
  initial.random_max = -0.17;
  s.set_phase(initial);
  const auto [low, high] = global_range(s.phi);
  EXPECT_GE(low, -0.57);
  EXPECT_LE(high, -0.17);
  EXPECT_LT(low, -0.56);  // 4096 samples reach both ends of the range
  EXPECT_GT(high, -0.18);
  // Mean -0.37, standard error of the mean 0.4/sqrt(12 * 4096) = 1.8e-3.
  EXPECT_NEAR(s.mass(), -0.37, 0.01);
}

TEST(InitialPhase, BumpHitsPrescribedMass)
{
  Testing::FixedSurface s(32);
  set_bump(s.surface, 0.5, 1.3);
  EXPECT_NEAR(s.surface.area(), 1.3, 1e-12);
  InitialPhaseOptions initial;
  initial.type           = "bump";
  initial.prescribe_mass = true;
  initial.mass           = -0.85;
  s.set_phase(initial);
  EXPECT_NEAR(s.mass(), -0.85, 1e-12);
  // The bump's phase is -1 far from the centre and larger at the centre.
  const auto [low, high] = global_range(s.phi);
  EXPECT_NEAR(low, -1.0, 1e-12);
  EXPECT_GT(high, -1.0 + 0.1);
}
