#include <membrane/time_step_control.h>

#include <algorithm>
#include <cmath>

namespace Membrane
{
  namespace
  {
    constexpr std::size_t window = 20;
  }

  void TimeStepController::record(const bool rejected)
  {
    recent.push_back(rejected);
    if (recent.size() > window)
      recent.pop_front();
  }

  bool TimeStepController::stalled() const
  {
    return recent.size() == window && 2 * std::count(recent.begin(), recent.end(), true) >= long(window) &&
           current < 1e-3 * limits.maximum;
  }

  TimeStepController::AttemptHistory TimeStepController::attempt_history() const
  {
    AttemptHistory history;
    for (const bool rejected : recent)
      history.rejected |= static_cast<unsigned int>(rejected) << history.count++;
    return history;
  }

  void TimeStepController::restore_attempt_history(const AttemptHistory &history)
  {
    recent.clear();
    for (unsigned int i = 0; i < std::min<unsigned int>(history.count, window); ++i)
      recent.push_back((history.rejected >> i) & 1U);
  }

  double TimeStepController::shrink_factor(const double error)
  {
    return std::clamp(0.9 / std::sqrt(error), 0.2, 0.5);
  }

  bool TimeStepController::reject(const double trial, const double factor)
  {
    record(true);
    current = factor * trial;
    return limits.adaptive && current >= limits.minimum;
  }

  bool TimeStepController::irreducible(const double trial, const double error) const
  {
    return controls_accuracy() && error > 1 && last_error_rejection.tau > trial &&
           error > trial / last_error_rejection.tau * last_error_rejection.error;
  }

  void TimeStepController::accept(const double trial, const double max_increment, const double cell_size,
                                  const double energy_change, const double error, const bool irreducible)
  {
    record(false);
    if (irreducible)
      return; // tau held; the rejection it was measured against is kept
    last_error_rejection = {};
    if (!limits.adaptive || trial != current)
      return;
    double next = current;
    if (max_increment < 0.2 * cell_size && energy_change < 1e-2)
      next = std::min(limits.growth * current, limits.maximum);
    else if (max_increment > 0.5 * cell_size)
      next = std::max(0.7 * current, limits.minimum);
    if (controls_accuracy() && error >= 0)
      next = std::min(next, std::max(limits.minimum, current * std::min(limits.growth, 0.9 / std::sqrt(std::max(error, 1e-12)))));
    current = next;
  }
} // namespace Membrane
