"""Budding time T_min: from the start to the numerical beginning of the equilibrium.

Definition (docs/workflow.md):
- a run whose domain becomes a complete bud (domain protrusion above `complete`, 0.95 as
  in the simulator's outcome classes) has T_min = the first time the protrusion reaches it
  (interpolated between rows): after that only the neck keeps thinning slowly;
- otherwise a run that stopped on approach to pinch-off has T_min = its stop time: a
  complete bud never reaches a resolved equilibrium, and the paper stops just before the
  blow-up;
- otherwise T_min is the time from which on the relative energy rate, measured over a
  window of `window` time units, |F(t + window) - F(t)| / (window |F(t)|), stays below
  `rate` (defaults 0.1 and 1e-2 per unit time): the end of the last window in which the
  rate exceeds it. The rate, unlike a fraction of the total energy drop, sees a slow budding
  stage after fast sorting; the window averages out single-step noise of adaptive steps.
- If the rate over the last full window is still above `rate`, T_min is None: the run
  ended before the equilibrium began.
For F(t) = F_e + A exp(-t/T) and a short window, T_min solves
(A/T) e^(-t/T) = rate (F_e + A e^(-t/T)).
"""
import numpy as np


def budding_time(time, energy, stop_reason='', rate=1e-2, window=0.1, protrusion=None, complete=0.95):
    time = np.asarray(time, dtype=float)
    energy = np.asarray(energy, dtype=float)
    if protrusion is not None:
        protrusion = np.asarray(protrusion, dtype=float)
        above = np.nonzero(protrusion >= complete)[0]
        if len(above):
            i = above[0]
            if i == 0:
                return float(time[0])
            s = (complete - protrusion[i - 1]) / (protrusion[i] - protrusion[i - 1])
            return float(time[i - 1] + s * (time[i] - time[i - 1]))
    if stop_reason.startswith('pinch-off'):
        return float(time[-1])
    ends = np.searchsorted(time, time + window * (1 - 1e-9))  # first row at or after t + window
    full = np.nonzero(ends < len(time))[0]
    if len(full) == 0:
        return None
    starts, ends = full, ends[full]
    rates = np.abs(energy[ends] - energy[starts]) / ((time[ends] - time[starts]) *
                                                     np.maximum(np.abs(energy[starts]), 1e-300))
    if rates[-1] > rate:
        return None
    fast = np.nonzero(rates > rate)[0]
    return float(time[ends[fast[-1]]]) if len(fast) else float(time[0])


def budding_time_of_run(run_dir, **kwargs):
    from ..run import load_statistics, load_summary
    stats, summary = load_statistics(run_dir), load_summary(run_dir)
    return budding_time(stats['time'], stats['energy'], summary.get('stop_reason', ''),
                        protrusion=stats.get('domain_protrusion'), **kwargs)


# -- the command line: python3 -m membrane_flow budding-time -----------------------------------

def main(argv=None):
    import argparse
    parser = argparse.ArgumentParser(description='The budding time T_min of finished runs (the definition of '
                                     'membrane_flow/workflow/budding_time.py, docs/workflow.md): one line per run, '
                                     '"-" where the run ended before the equilibrium began.')
    parser.add_argument('runs', nargs='+', help='output directories of runs')
    parser.add_argument('--rate', type=float, default=1e-2, help='relative energy rate per unit time (default 1e-2)')
    parser.add_argument('--window', type=float, default=0.1, help='window of the rate in time units (default 0.1)')
    parser.add_argument('--complete', type=float, default=0.95,
                        help='domain protrusion of a complete bud (default 0.95)')
    args = parser.parse_args(argv)
    for run in args.runs:
        t = budding_time_of_run(run, rate=args.rate, window=args.window, complete=args.complete)
        print(f"{run}\t{'-' if t is None else f'{t:.6g}'}")
    return 0
