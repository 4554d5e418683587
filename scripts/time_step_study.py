#!/usr/bin/python3
"""Convergence in the time step: the 7.3 setup at sigma = 1500 on the uniform 32 x 32 mesh, run to
t = 1 with tau capped at decreasing values and with tau set by the accuracy tolerance, with grid
control at a rate per unit time (the default) and, for contrast, with the paper's fixed weight per
step (Shape/Grid control rate = 0).

Runs each case once (a case with a summary.json is reused), then writes
docs/time-step-accuracy.md: per case the accepted and rejected steps, the energy at t = 0.5 and
t = 1, the budding time T_min, their differences from the reference (the smallest cap with the
rate), and the observed order of the capped runs.

Usage: time_step_study.py [--exe build/membrane-flow] [--output results/studies/time-steps] [--no-docs]"""
import argparse
import json
import math
import os
import re
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from membrane_workflow.budding_time import budding_time_of_run  # noqa: E402
from membrane_workflow.statistics import load_statistics  # noqa: E402

root = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..')
parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument('--exe', default=os.path.join(root, 'build', 'membrane-flow'))
parser.add_argument('--output', default=os.path.join(root, 'results', 'studies', 'time-steps'))
parser.add_argument('--end-time', type=float, default=1.0)
parser.add_argument('--no-docs', action='store_true', help='run the cases only')
args = parser.parse_args()

CAPS = (1e-2, 5e-3, 2.5e-3, 1.25e-3)
TOLERANCES = (0.1, 0.01, 0.003, 0.001)
# (tolerance, maximum time step, grid control rate): capped tau with the rate (the reference:
# the smallest cap), accuracy control with the cap lifted, capped tau with a fixed weight per step.
cases = [(0, cap, 10) for cap in CAPS] + [(tol, 0.1, 10) for tol in TOLERANCES] + \
        [(0, cap, 0) for cap in CAPS[:3]]


def name_of(tolerance, cap, rate):
    return f'tol{tolerance:g}-cap{cap:g}' + ('' if rate else '-rate0')


def made_as_asked(out, rate):
    """A finished earlier run of this case (its parameters.prm has this study's settings)."""
    try:
        with open(os.path.join(out, 'parameters.prm')) as f:
            text = f.read()
        with open(os.path.join(out, 'summary.json')) as f:
            stop = json.load(f).get('stop_reason', '')
    except OSError:
        return False
    entry = re.search(r'set Grid control rate\s*=\s*(\S+)', text)
    level = re.search(r'set Maximum refinement level\s*=\s*(\S+)', text)
    return (entry is not None and float(entry.group(1)) == rate and level is not None and level.group(1) == '0'
            and not stop.startswith('interrupted'))


rows = []
for tolerance, cap, rate in cases:
    out = os.path.join(args.output, name_of(tolerance, cap, rate))
    if not made_as_asked(out, rate):
        command = [args.exe, '--quiet', '--overwrite', '--set', 'Material/Line tension=1500',
                   '--set', f'Time stepping/Accuracy tolerance={tolerance}',
                   '--set', f'Time stepping/Maximum time step={cap}',
                   '--set', f'Shape/Grid control rate={rate}',
                   '--set', f'Time stepping/End time={args.end_time}', '--set', 'Output/Write VTU=false',
                   '--set', 'Checkpoint/Interval=0', '--set', 'Mesh/Maximum refinement level=0',
                   '--set', f'Output/Directory={out}',
                   os.path.join(root, 'experiments', '7.3-budding.prm')]
        print(' '.join(command), flush=True)
        result = subprocess.run(command, check=False, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                                env=dict(os.environ, OMP_NUM_THREADS='1', OPENBLAS_NUM_THREADS='1'))
        if result.returncode == 1:
            sys.exit(f'{args.exe} refused the case: {result.stderr.strip()}')
    with open(os.path.join(out, 'summary.json')) as f:
        summary = json.load(f)
    stats = load_statistics(out)
    time, energy = np.asarray(stats['time']), np.asarray(stats['energy'])
    finished = summary.get('stop_reason') == 'end time'
    rows.append(dict(tolerance=tolerance, cap=cap, rate=rate, summary=summary, finished=finished,
                     t_min=budding_time_of_run(out),
                     half=float(np.interp(0.5 * args.end_time, time, energy)) if time[-1] >= 0.5 * args.end_time
                     else math.nan,
                     end=float(energy[-1]) if finished else math.nan, t_end=float(time[-1])))
if args.no_docs:
    sys.exit(0)

reference = rows[len(CAPS) - 1]
capped = [r for r in rows if r['tolerance'] == 0 and r['rate']]
controlled = [r for r in rows if r['tolerance'] > 0]
fixed = [r for r in rows if not r['rate']]


def rel(value, ref):
    return abs(value - ref) / abs(ref)


def fmt_rel(value, ref):
    if value is None or ref is None or math.isnan(value) or math.isnan(ref):
        return 'n/a'
    return f'{rel(value, ref):.1e}'


lines = ['# Time-step convergence and accuracy-based time steps', '',
         f'The 7.3 setup at `sigma = 1500` on the uniform 32 x 32 mesh, run to t = {args.end_time:g}: tau '
         'capped at decreasing values (it grows by 1.25 after easy steps from 1e-4 up to the cap), and tau set '
         'by the accuracy tolerance (`Time stepping/Accuracy tolerance`, cap lifted to 0.1). Grid control moves '
         'the mesh at a rate per unit time (`Shape/Grid control rate` = 10); the last rows use the '
         "paper's fixed weight per step (rate 0, the default). Differences are relative to the smallest cap with the rate. "
         'Regenerate with `scripts/time_step_study.py` (about 30 minutes on one core).', '',
         f'| grid control | tolerance | maximum tau | steps | rejected | energy at t = {0.5 * args.end_time:g} | '
         f'energy at t = {args.end_time:g} | difference at t = {args.end_time:g} | T_min | difference in T_min | wall s |',
         '|---|---|---|---|---|---|---|---|---|---|---|']
for r in rows:
    s = r['summary']
    lines.append(f"| {'rate 10' if r['rate'] else 'fixed 0.1 per step'} | {r['tolerance'] if r['tolerance'] else 'off'} | "
                 f"{r['cap']:g} | {s['steps']} | {s['rejected_steps']} | {r['half']:.5f} | "
                 f"{'stopped at t = ' + format(r['t_end'], '.4f') if not r['finished'] else format(r['end'], '.5f')} | "
                 f"{fmt_rel(r['end'], reference['end'])} | "
                 f"{'undefined' if r['t_min'] is None else format(r['t_min'], '.4f')} | "
                 f"{fmt_rel(r['t_min'], reference['t_min'])} | {s['wall_seconds']:.1f} |")

# Observed order of the capped runs with the rate, from successive differences of the energy.
text = []
ends = [r['end'] for r in capped]
if len(ends) >= 3 and all(math.isfinite(e) for e in ends):
    diffs = [abs(ends[i] - ends[i + 1]) for i in range(len(ends) - 1)]
    orders = [math.log2(diffs[i] / diffs[i + 1]) for i in range(len(diffs) - 1) if diffs[i] > 0 and diffs[i + 1] > 0]
    text.append('With the rate, halving the cap changes the energy at the end time by ' +
                ', '.join(f'{d / abs(ends[-1]):.1e}' for d in diffs) + ' (relative)' +
                (', an observed order of ' + ', '.join(f'{o:.2f}' for o in orders) if orders else '') +
                '. The changes are small but shrink slowly: a part of the step that depends weakly on the number '
                'of steps remains at this level (candidates: the restoration of the whole vertex-area defect in '
                'every step longer than `Shape/Area relaxation time`, the mass correction by a constant).')
fixed_ends = [r['end'] for r in fixed if math.isfinite(r['end'])]
if len(fixed_ends) >= 2:
    diffs = [abs(fixed_ends[i] - fixed_ends[i + 1]) / abs(fixed_ends[-1]) for i in range(len(fixed_ends) - 1)]
    text.append("With the paper's fixed weight per step the same halvings change it by " +
                ', '.join(f'{d:.1e}' for d in diffs) + ': the mesh is smoothed and phi remapped once per step, so '
                'the state at a fixed time depends on the number of steps and does not settle as tau shrinks.')
good = [r for r in controlled if r['finished'] and math.isfinite(reference['end'])]
coarsest = capped[0]
if good and math.isfinite(coarsest['end']):
    text.append('With accuracy control the energy at the end time lies within ' +
                ', '.join(f"{rel(r['end'], reference['end']):.1e} ({r['summary']['steps']} steps, tolerance "
                          f"{r['tolerance']:g})" for r in good) + ' of the reference; the coarsest cap, '
                f"{coarsest['cap']:g}, is within {rel(coarsest['end'], reference['end']):.1e} in "
                f"{coarsest['summary']['steps']} steps.")
stalled = [r for r in controlled if not r['finished']]
for r in stalled:
    text.append(f"At tolerance {r['tolerance']:g} the run stopped at t = {r['t_end']:.4f}: "
                f"{r['summary'].get('stop_reason', '').split(';')[0]}.")
text.append('The estimate (the change of the increments from one step to the next, in cells and in phi) does '
            'not see the lag of the slow growth of the bud behind the frozen geometry, whose increments are small '
            'and vary smoothly: the controlled runs take their largest steps there, and their error at t = 1 falls '
            'only slowly as the tolerance shrinks. For accurate results cap tau (`Time stepping/Maximum time step`) '
            'with grid control at a rate; the accuracy tolerance is off by default.')
lines += [''] + text
lines += ['', 'T_min is the first time the domain protrusion reaches 0.95 or, without that, the end of the '
          'last window in which the relative energy rate exceeds 1e-2 per unit time '
          '(`scripts/membrane_workflow/budding_time.py`); where it comes from the rate criterion it inherits '
          'the shallow crossing of a threshold and scatters more than the energy.']
text = '\n'.join(lines) + '\n'
with open(os.path.join(root, 'docs', 'time-step-accuracy.md'), 'w') as f:
    f.write(text)
print(text)
