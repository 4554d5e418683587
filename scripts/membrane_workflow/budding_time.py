"""Budding time T_min: from the start to the numerical beginning of the equilibrium.

Definition (docs/workflow.md):
- a run that stopped on approach to pinch-off has T_min = its stop time: a complete bud
  never reaches a resolved equilibrium, and the paper stops just before the blow-up;
- otherwise T_min is the time from which on the relative energy rate
  |F^{m+1} - F^m| / ((t^{m+1} - t^m) |F^m|) stays below `rate` (default 1e-3 per unit
  time): the end of the last interval in which the rate exceeds it. The rate, unlike a
  fraction of the total energy drop, sees a slow budding stage after fast sorting.
- If the rate at the end of the run is still above `rate`, T_min is None: the run
  ended before the equilibrium began.
For F(t) = F_e + A exp(-t/T), T_min solves (A/T) e^(-t/T) = rate (F_e + A e^(-t/T)).
"""
import numpy as np


def budding_time(time, energy, stop_reason='', rate=1e-3):
    time = np.asarray(time, dtype=float)
    energy = np.asarray(energy, dtype=float)
    if stop_reason.startswith('pinch-off'):
        return float(time[-1])
    if len(time) < 2:
        return None
    rates = np.abs(np.diff(energy)) / (np.maximum(np.diff(time), 1e-300) * np.maximum(np.abs(energy[:-1]), 1e-300))
    if rates[-1] > rate:
        return None
    fast = np.nonzero(rates > rate)[0]
    return float(time[fast[-1] + 1]) if len(fast) else float(time[0])


def budding_time_of_run(run_dir, **kwargs):
    from .statistics import load_statistics, load_summary
    stats, summary = load_statistics(run_dir), load_summary(run_dir)
    return budding_time(stats['time'], stats['energy'], summary.get('stop_reason', ''), **kwargs)
