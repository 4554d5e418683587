#pragma once
// Adaptive choice of tau (docs/model.md, "Time steps"). The simulator proposes a
// step of length min(tau, time left); the controller then hears whether the step
// was rejected or accepted and how hard it was:
//  - rejected: tau <- trial / 2; the run cannot go on if stepping is not adaptive
//    or tau fell below its minimum;
//  - accepted at full length: tau grows by the growth factor (up to the maximum)
//    after an easy step (vertices moved less than 0.2 cells and the energy
//    changed less than 1 %), shrinks by 0.7 after a hard one (more than half a cell).
// Steps cut short to land on the end time leave tau unchanged.
// With an accuracy tolerance, the step's error estimate (relative to the tolerance:
// 1 = at tolerance) also sets tau: tau <- tau min(growth, 0.9 / sqrt(estimate)),
// never above what the rules above allow; a step above tolerance is rejected by the
// simulator and retried with tau max(0.2, 0.9 / sqrt(estimate)). A first-order step's
// local error falls like tau^2: an estimate above tolerance that has not fallen even in
// proportion to tau since the last rejection for it does not measure a time-discretization
// error but a part of the increment that does not scale with tau (a stiff mode relaxed in
// full by every step: the finest modes of a random initial mixture, or a bud the mesh
// barely resolves). A smaller tau would not lower it and only stall the run, so such a
// step is accepted at the tau it was tried with, and tau is held there until the
// estimate falls below the tolerance again.
// The controller is stalled when half of the last 20 attempted steps were rejected
// and tau is below 1e-3 of its maximum: the solution is approaching a singularity
// (a pinching neck) that steps of any size cannot pass, and the run should stop.

#include <deque>

namespace Membrane
{
  struct TimeStepLimits
  {
    bool   adaptive = true;
    double minimum  = 1e-9;
    double maximum  = 1e-2;
    double growth   = 1.25;
    double accuracy = 0; ///< tolerance of the error estimate (0: no accuracy control)
  };

  class TimeStepController
  {
  public:
    TimeStepController(const TimeStepLimits &limits, double initial_tau)
      : limits(limits)
      , current(initial_tau)
    {}

    double tau() const { return current; }
    void   set_tau(double tau) { current = tau; }

    /// After a rejected trial step; false if the run cannot continue. `factor`
    /// shrinks tau (0.5 unless the step's error estimate said otherwise).
    bool reject(double trial, double factor = 0.5);

    /// After an accepted trial step; `max_increment` is the largest vertex move,
    /// `cell_size` the reference cell size, `energy_change` |Delta F| / |F|, and
    /// `error` the error estimate relative to the tolerance (negative: none).
    /// `irreducible`: the estimate was above tolerance but irreducible() (tau is held).
    void accept(double trial, double max_increment, double cell_size, double energy_change, double error = -1,
                bool irreducible = false);

    /// The relative error estimate `error` of a trial step of length `trial` is above 1 and
    /// has not fallen in proportion to tau since the last rejection for the local error.
    bool irreducible(double trial, double error) const;

    /// A trial step of length `trial` is rejected for its relative error estimate `error`
    /// (also: restores the memory from a checkpoint).
    void note_error_rejection(double trial, double error) { last_error_rejection = {trial, error}; }

    /// The last rejection for the local error since a step within tolerance (tau 0: none).
    struct ErrorRejection
    {
      double tau = 0, error = 0;
    };
    ErrorRejection error_rejection() const { return last_error_rejection; }

    /// The factor by which tau shrinks after a step whose relative error estimate
    /// `error` exceeded 1.
    static double shrink_factor(double error);

    bool controls_accuracy() const { return limits.adaptive && limits.accuracy > 0; }
    double accuracy() const { return limits.accuracy; }

    /// Half of the last 20 attempts rejected at tau < 1e-3 maximum.
    bool stalled() const;

    /// The attempts stalled() judges, oldest first, for checkpoints: bit i of `rejected`
    /// is set if attempt i was rejected.
    struct AttemptHistory
    {
      unsigned int count = 0, rejected = 0;
    };
    AttemptHistory attempt_history() const;
    void           restore_attempt_history(const AttemptHistory &history);

  private:
    void record(bool rejected);

    TimeStepLimits    limits;
    double            current;
    std::deque<bool>  recent; ///< the last attempts, true = rejected
    ErrorRejection    last_error_rejection;
  };
} // namespace Membrane
