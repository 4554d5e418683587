#!/usr/bin/python3
"""Accuracy-based time steps: the budding time T_min of the 7.3 setup at sigma = 1500 (32 x 32
cells) against the accuracy tolerance, next to today's rule (tau capped at 1e-2).

Runs each case once (a case with a summary.json is reused), then writes
docs/time-step-accuracy.md with the table: tolerance, cap, accepted and rejected steps, T_min,
its difference from the tightest tolerance, final energy, wall time.

Usage: time_step_study.py [--exe build/membrane-flow] [--output results/studies/time-steps]"""
import argparse
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from membrane_workflow.budding_time import budding_time_of_run  # noqa: E402

root = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..')
parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument('--exe', default=os.path.join(root, 'build', 'membrane-flow'))
parser.add_argument('--output', default=os.path.join(root, 'results', 'studies', 'time-steps'))
parser.add_argument('--end-time', type=float, default=1.0)
args = parser.parse_args()

# (tolerance, maximum time step): the rule without accuracy control at decreasing caps
# (the reference: T_min as tau -> 0), then accuracy control with the cap lifted.
cases = [(0, cap) for cap in (1e-2, 5e-3, 2.5e-3, 1.25e-3)] + [(tol, 0.1) for tol in (0.3, 0.1, 0.03, 0.01, 0.003, 0.001)]
rows = []
for tolerance, cap in cases:
    name = f'tol{tolerance:g}-cap{cap:g}'
    out = os.path.join(args.output, name)
    if not os.path.exists(os.path.join(out, 'summary.json')):
        command = [args.exe, '--quiet', '--overwrite', '--set', 'Material/Line tension=1500',
                   '--set', f'Time stepping/Accuracy tolerance={tolerance}',
                   '--set', f'Time stepping/Maximum time step={cap}',
                   '--set', f'Time stepping/End time={args.end_time}', '--set', 'Output/Write VTU=false',
                   '--set', 'Checkpoint/Interval=0', '--set', f'Output/Directory={out}',
                   os.path.join(root, 'experiments', '7.3-budding.prm')]
        print(' '.join(command), flush=True)
        subprocess.run(command, check=False, stdout=subprocess.DEVNULL,
                       env=dict(os.environ, OMP_NUM_THREADS='1', OPENBLAS_NUM_THREADS='1'))
    with open(os.path.join(out, 'summary.json')) as f:
        summary = json.load(f)
    rows.append((tolerance, cap, summary, budding_time_of_run(out)))

reference = rows[3][3]  # the smallest cap without accuracy control
lines = ['# Accuracy-based time steps', '',
         'The budding time `T_min` of the 7.3 setup at `sigma = 1500` (32 x 32 cells, end time '
         f'{args.end_time:g}) with tau set by the accuracy tolerance (`Time stepping/Accuracy tolerance`, '
         'maximum time step raised to 0.1), next to the rule without it (tau grows after easy steps up to '
         '1e-2). Regenerate with `scripts/time_step_study.py`.', '',
         '| tolerance | maximum tau | steps | rejected | T_min | T_min vs cap 1.25e-3 | energy | wall s |',
         '|---|---|---|---|---|---|---|---|']
for tolerance, cap, summary, t_min in rows:
    diff = 'n/a' if t_min is None or reference is None else f'{(t_min - reference) / reference:+.2%}'
    lines.append(f"| {tolerance if tolerance else 'off'} | {cap:g} | {summary['steps']} | {summary['rejected_steps']} | "
                 f"{'undefined' if t_min is None else f'{t_min:.4f}'} | {diff} | {summary['energy']:.6g} | "
                 f"{summary['wall_seconds']:.1f} |")
capped = [r for r in rows if r[0] == 0 and r[3] is not None]
controlled = [r for r in rows if r[0] > 0 and r[3] is not None]
if reference is not None and len(capped) >= 2 and controlled:
    deviations = [(r[3] - reference) / reference for r in controlled]
    lines += ['', f'Without accuracy control, T_min at the two smallest caps differs by '
              f'{abs(capped[-1][3] - capped[-2][3]) / capped[-1][3]:.2%}: it has converged in tau there, at '
              f'{capped[-2][2]["steps"]}-{capped[-1][2]["steps"]} steps. With accuracy control, T_min lies between '
              f'{min(deviations):+.2%} and {max(deviations):+.2%} of that value at '
              f'{min(r[2]["steps"] for r in controlled)}-{max(r[2]["steps"] for r in controlled)} steps, and it does '
              'not approach it as the tolerance shrinks. The estimate measures the change of the increments from '
              'one step to the next (the local error of a first-order step on a smooth trajectory); the lag that '
              'the semi-implicit step accumulates over the slow growth of the bud changes the increments little '
              'from step to step and escapes it. So the accuracy tolerance gives a few per cent in T_min with fewer '
              'steps than the caps, but not convergence: for T_min to better than ~5 %, refine the cap on tau. The '
              'option is off by default. Wall times were measured while other runs shared the 2 cores; compare the '
              'steps.']
text = '\n'.join(lines) + '\n'
with open(os.path.join(root, 'docs', 'time-step-accuracy.md'), 'w') as f:
    f.write(text)
print(text)
