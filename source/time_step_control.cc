#include <membrane/time_step_control.h>

#include <algorithm>

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

  bool TimeStepController::reject(const double trial)
  {
    record(true);
    current = 0.5 * trial;
    return limits.adaptive && current >= limits.minimum;
  }

  void TimeStepController::accept(const double trial, const double max_increment, const double cell_size,
                                  const double energy_change)
  {
    record(false);
    if (!limits.adaptive || trial != current)
      return;
    if (max_increment < 0.2 * cell_size && energy_change < 1e-2)
      current = std::min(limits.growth * current, limits.maximum);
    else if (max_increment > 0.5 * cell_size)
      current = std::max(0.7 * current, limits.minimum);
  }
} // namespace Membrane
