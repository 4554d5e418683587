// The adaptive step-size rules (include/membrane/time_step_control.h) and the grid-control
// sweeps of a step (include/membrane/parameters.h).
#include <membrane/parameters.h>
#include <membrane/time_step_control.h>

#include <gtest/gtest.h>

using Membrane::TimeStepController;
using Membrane::TimeStepLimits;

TEST(TimeSteps, EasyStepsGrowUpToTheMaximum)
{
  TimeStepController control(TimeStepLimits{true, 1e-9, 1e-2, 1.25}, 4e-3);
  control.accept(4e-3, 0.0, 1.0 / 32, 1e-4);
  EXPECT_DOUBLE_EQ(control.tau(), 5e-3);
  for (int i = 0; i < 10; ++i)
    control.accept(control.tau(), 0.0, 1.0 / 32, 1e-4);
  EXPECT_DOUBLE_EQ(control.tau(), 1e-2);
}

TEST(TimeSteps, HardOrLargeEnergyChangeStepsDoNotGrow)
{
  TimeStepController control(TimeStepLimits{true, 1e-9, 1e-2, 1.25}, 1e-3);
  control.accept(1e-3, 0.3 / 32, 1.0 / 32, 1e-4); // between 0.2 and 0.5 cells: keep
  EXPECT_DOUBLE_EQ(control.tau(), 1e-3);
  control.accept(1e-3, 0.0, 1.0 / 32, 0.05); // energy changed by 5 %: keep
  EXPECT_DOUBLE_EQ(control.tau(), 1e-3);
  control.accept(1e-3, 0.6 / 32, 1.0 / 32, 1e-4); // over half a cell: shrink
  EXPECT_DOUBLE_EQ(control.tau(), 7e-4);
  control.accept(2e-4, 0.0, 1.0 / 32, 1e-4); // a step cut to the end time: unchanged
  EXPECT_DOUBLE_EQ(control.tau(), 7e-4);
}

TEST(TimeSteps, RejectionHalvesAndStopsBelowTheMinimum)
{
  TimeStepController control(TimeStepLimits{true, 1e-4, 1e-2, 1.25}, 1e-3);
  EXPECT_TRUE(control.reject(1e-3));
  EXPECT_DOUBLE_EQ(control.tau(), 5e-4);
  EXPECT_TRUE(control.reject(5e-4));
  EXPECT_TRUE(control.reject(2.5e-4));
  EXPECT_FALSE(control.reject(1.25e-4)); // 6.25e-5 < 1e-4

  TimeStepController fixed(TimeStepLimits{false, 1e-9, 1e-2, 1.25}, 1e-3);
  EXPECT_FALSE(fixed.reject(1e-3));
  fixed.set_tau(1e-3);
  fixed.accept(1e-3, 0.0, 1.0 / 32, 0.0);
  EXPECT_DOUBLE_EQ(fixed.tau(), 1e-3);
}

TEST(TimeSteps, StalledWhenHalfOfRecentStepsFailAtTinyTau)
{
  TimeStepController control(TimeStepLimits{true, 1e-12, 1e-2, 1.25}, 1e-3);
  for (int i = 0; i < 10; ++i) // rejections down to tau ~ 1e-6, alternating with hard accepted steps
    {
      control.reject(control.tau());
      EXPECT_FALSE(control.stalled()) << "fewer than 20 attempts so far";
      control.accept(control.tau(), 1.0, 1.0 / 32, 0.0);
    }
  EXPECT_LT(control.tau(), 1e-5);
  control.reject(control.tau());
  EXPECT_TRUE(control.stalled());

  // The same rejection pattern at a tau near the maximum is not a stall.
  TimeStepController large(TimeStepLimits{true, 1e-12, 1e-2, 1.25}, 1e-2);
  for (int i = 0; i < 11; ++i)
    {
      large.reject(large.tau());
      large.set_tau(1e-2);
      large.accept(1e-2, 0.0, 1.0 / 32, 0.0);
    }
  EXPECT_FALSE(large.stalled());
}

// The attempts the stall detector judges survive a checkpoint: a controller restored from
// the history of a stalling one is stalled too, and one more accepted step is judged on the
// same 20 attempts as without the interruption.
TEST(TimeSteps, StallHistoryRoundTrips)
{
  TimeStepController control(TimeStepLimits{true, 1e-12, 1e-2, 1.25}, 1e-6);
  for (int i = 0; i < 25; ++i) // alternate: half of the attempts rejected, tau stays tiny
    {
      if (i % 2 == 0)
        control.accept(1e-6, 0.0, 1.0 / 32, 1e-4);
      else
        ASSERT_TRUE(control.reject(2e-6));
      control.set_tau(1e-6);
    }
  ASSERT_TRUE(control.stalled());
  const auto history = control.attempt_history();
  EXPECT_EQ(history.count, 20U);
  EXPECT_EQ(history.rejected, 0xAAAAAU >> 1); // attempts 5..24: odd ones rejected, oldest (5) first

  TimeStepController resumed(TimeStepLimits{true, 1e-12, 1e-2, 1.25}, 1e-6);
  EXPECT_FALSE(resumed.stalled()); // a fresh controller has no history
  resumed.restore_attempt_history(history);
  EXPECT_TRUE(resumed.stalled());
  control.accept(1e-6, 0.0, 1.0 / 32, 1e-4);
  resumed.accept(1e-6, 0.0, 1.0 / 32, 1e-4);
  control.set_tau(1e-6);
  resumed.set_tau(1e-6);
  EXPECT_EQ(control.stalled(), resumed.stalled());
  EXPECT_EQ(control.attempt_history().rejected, resumed.attempt_history().rejected);
}

// Accuracy control: the error estimate (relative to the tolerance) caps the growth by
// 0.9 / sqrt(estimate), and a rejected step retries with that factor, between 0.2 and 0.5.
TEST(TimeSteps, ErrorEstimateSetsTheStep)
{
  TimeStepController control(TimeStepLimits{true, 1e-9, 1e-2, 1.25, 1e-2}, 1e-3);
  ASSERT_TRUE(control.controls_accuracy());
  control.accept(1e-3, 0.0, 1.0 / 32, 1e-4, 0.01); // far below tolerance: the growth factor limits
  EXPECT_DOUBLE_EQ(control.tau(), 1.25e-3);
  control.accept(1.25e-3, 0.0, 1.0 / 32, 1e-4, 0.81); // 0.9 / sqrt(0.81) = 1: keep
  EXPECT_DOUBLE_EQ(control.tau(), 1.25e-3);
  control.accept(1.25e-3, 0.0, 1.0 / 32, 1e-4, 0.9 * 0.9 / 0.64); // 0.9 / sqrt(.) = 0.8
  EXPECT_NEAR(control.tau(), 1e-3, 1e-15);
  control.accept(1e-3, 0.0, 1.0 / 32, 1e-4, -1); // no estimate: the rules alone
  EXPECT_DOUBLE_EQ(control.tau(), 1.25e-3);

  EXPECT_DOUBLE_EQ(TimeStepController::shrink_factor(2.0), 0.5);          // 0.64 capped at 0.5
  EXPECT_NEAR(TimeStepController::shrink_factor(9.0), 0.3, 1e-15);        // 0.9 / 3
  EXPECT_DOUBLE_EQ(TimeStepController::shrink_factor(1e4), 0.2);          // floor
  EXPECT_TRUE(control.reject(1.25e-3, TimeStepController::shrink_factor(9.0)));
  EXPECT_NEAR(control.tau(), 3.75e-4, 1e-15);

  TimeStepController without(TimeStepLimits{true, 1e-9, 1e-2, 1.25}, 1e-3);
  EXPECT_FALSE(without.controls_accuracy());
  without.accept(1e-3, 0.0, 1.0 / 32, 1e-4, 100.0); // estimates are ignored without a tolerance
  EXPECT_DOUBLE_EQ(without.tau(), 1.25e-3);
}

// An estimate above tolerance that has not fallen in proportion to tau since the last
// rejection for it is irreducible: the step is accepted and tau held, not shrunk further.
// An estimate that falls like tau^2 (a true first-order local error) stays reducible.
TEST(TimeSteps, EstimateThatDoesNotFallWithTauIsAcceptedAndTauHeld)
{
  TimeStepController control(TimeStepLimits{true, 1e-9, 1e-2, 1.25, 1e-2}, 1e-3);
  EXPECT_FALSE(control.irreducible(1e-3, 2.0)); // no rejection to compare with yet
  control.note_error_rejection(1e-3, 2.0);
  ASSERT_TRUE(control.reject(1e-3, TimeStepController::shrink_factor(2.0)));
  EXPECT_DOUBLE_EQ(control.tau(), 5e-4);
  EXPECT_FALSE(control.irreducible(5e-4, 2.0 * 0.25)); // fell like tau^2: below tolerance anyway
  EXPECT_FALSE(control.irreducible(5e-4, 0.99));       // fell more than tau: reducible
  EXPECT_TRUE(control.irreducible(5e-4, 1.9));         // fell less than tau (2 x 0.5 = 1)
  EXPECT_FALSE(control.irreducible(1e-3, 1.9));        // not a smaller step than the rejected one

  control.accept(5e-4, 0.0, 1.0 / 32, 1e-4, 1.9, true);
  EXPECT_DOUBLE_EQ(control.tau(), 5e-4);              // held, not grown or shrunk
  EXPECT_TRUE(control.irreducible(5e-4, 1.9));         // the rejection it is measured against is kept
  control.accept(5e-4, 0.0, 1.0 / 32, 1e-4, 0.5);     // within tolerance again: the memory is cleared
  EXPECT_FALSE(control.irreducible(5e-4, 1.9));

  TimeStepController without(TimeStepLimits{true, 1e-9, 1e-2, 1.25}, 1e-3);
  without.note_error_rejection(1e-3, 2.0);
  EXPECT_FALSE(without.irreducible(5e-4, 1.9)); // no tolerance, no estimate to judge
}

// With a grid-control rate r, a step of length tau is smoothed in ceil(r tau / w) sweeps of
// weight r tau / sweeps <= w, so the total weight per unit time is r whatever tau; without
// a rate, one sweep of the weight w per step (the paper's rule).
TEST(TimeSteps, GridControlSweepsKeepTheRatePerUnitTime)
{
  Membrane::Parameters parameters;
  parameters.grid_control_weight = 0.1;
  parameters.grid_control_rate   = 10;
  for (const double tau : {1e-4, 5e-3, 1e-2, 1.5e-2, 8e-2})
    {
      const unsigned int sweeps = parameters.grid_control_sweeps_of_step(tau);
      const double       weight = parameters.grid_control_weight_of_step(tau);
      EXPECT_NEAR(sweeps * weight, 10 * tau, 1e-14) << "tau = " << tau;
      EXPECT_LE(weight, 0.1 + 1e-15) << "tau = " << tau;
      if (sweeps > 1)
        {
          EXPECT_GT(weight, 0.05 - 1e-15) << "tau = " << tau; // no more sweeps than needed
        }
    }
  EXPECT_EQ(parameters.grid_control_sweeps_of_step(1e-2), 1u);
  EXPECT_EQ(parameters.grid_control_sweeps_of_step(8e-2), 8u);
  parameters.grid_control_rate = 0;
  EXPECT_EQ(parameters.grid_control_sweeps_of_step(8e-2), 1u);
  EXPECT_DOUBLE_EQ(parameters.grid_control_weight_of_step(8e-2), 0.1);
}
