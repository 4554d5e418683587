"""Neck resolution of the 7.3 bud: uniform 32 x 32 mesh against local refinement.

The 7.3 budding setup (experiments/7.3-budding.prm) at a large line tension, end time 4, runs on
  - uniform32:  the uniform 32 x 32 mesh (Mesh/Maximum refinement level = 0);
  - adaptive2:  the 32 x 32 input mesh with 2 levels of local refinement and
                Mesh/Interface cells per xi = 3;
  - adaptive3:  3 levels and 6 cells per xi, only when adaptive2 does not reach a neck radius
                below half of the uniform one (and --max-level allows it).
The line tension is 1500. When the uniform mesh forms no neck there (neck_ratio never below
Outcome/Complete neck ratio = 0.4), uniform32 is also run at 2000; the adaptive cases use the
first of these line tensions at which the uniform mesh forms a neck, 1500 if it forms none;
if it forms none, adaptive2 is also run at 2000.
Case directories: results/studies/neck/<case> (a suffix -s<sigma> for sigma other than 1500).

--sigma S runs the study at the line tension S (fallback 4/3 S) into results/studies/neck-s<S>/,
reported in docs/neck-resolution-s<S>.md: at 3000 the neck closes (a complete bud) even on
the uniform mesh, which the lower line tensions do not show.

--xi X runs the same study with the transition length X in place of the file's 0.03, and every
line tension scaled by 0.03 / X, so that sigma xi, the line tension of the sharp-interface limit,
is the same, and the pinch-off radius (the file's 0.03 = xi) scaled with xi: into
results/studies/neck-xi<X>/, reported in docs/neck-resolution-xi<X>.md. The diffuse interface
(about 4 xi wide) sits in the neck, so the neck cannot become much narrower than about xi:
a thinner interface lets the bud's neck close further.

--end-time T runs to T instead of 4; --min-cell-quality Q sets Time stepping/Minimum cell
quality (the default 0.1 rejects the steps that close a corner of the rhombi in a closing neck).

Every run: OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1, working directory the repository root (the
current directory: run the command from there),
one run at a time, VTU output and checkpoints off. A case is finished when its summary.json
exists (also a failed run writes one); finished cases are not run again.

Then the report docs/neck-resolution.md and the figure docs/images/neck-resolution.png are
written from the statistics.txt and summary.json of every finished case.

Usage: python3 -m membrane_flow neck-resolution [--dry-run] [--report-only] [--max-level 3] [--exe PATH]
           [--timeout SECONDS] [--sigma S] [--xi X] [--end-time T] [--min-cell-quality Q]
"""
import argparse
import json
import os
import re
import signal
import subprocess
import sys
import time

import numpy as np

from .. import launch
from ..run import load_statistics, load_summary

ROOT = os.getcwd()  # the repository's top directory: the input file, the runs and the pages are relative to it
EXE = 'build/membrane-flow'  # as the report shows the runs (the one run: launch.find_executable)
BASE = 'experiments/7.3-budding.prm'
OUTPUT = 'results/studies/neck'
DOC = 'docs/neck-resolution.md'
FIGURE = 'docs/images/neck-resolution.png'
END_TIME = 4.0
FILE_XI = 0.03         # the base file's Material/Transition length
XI = FILE_XI           # --xi
OPTIONS = []           # the options of the study, as the report's command repeats them
SIGMA = 1500.0
SIGMA_FALLBACK = 2000.0
NECK_RATIO = 0.4       # Outcome/Complete neck ratio (default)
FILE_PINCH_RADIUS = 0.03  # Outcome/Pinch-off radius (default)
PINCH_RADIUS = FILE_PINCH_RADIUS  # scaled with --xi
MIN_CELL_QUALITY = None  # --min-cell-quality (None: the default 0.1)
CELLS_PER_XI = {2: 3.0, 3: 6.0}
ENV = {name: '1' for name in launch.THREAD_VARIABLES}  # as the report shows them (the runs: launch.environment)


def fmt(x):
    return f'{x:g}'


class Case:
    def __init__(self, level, sigma):
        self.level, self.sigma = level, sigma
        base = 'uniform32' if level == 0 else f'adaptive{level}'
        self.name = base if sigma == SIGMA else f'{base}-s{fmt(sigma)}'
        self.dir = os.path.join(OUTPUT, self.name)
        self.xi = XI
        self.mesh = ('uniform 32 x 32' if level == 0 else
                     f'32 x 32, {level} refinement levels, {fmt(CELLS_PER_XI[level])} cells per xi')

    def settings(self):
        s = [('Material/Line tension', fmt(self.sigma)),
             ('Time stepping/End time', fmt(END_TIME)),
             ('Output/Write VTU', 'false'),
             ('Checkpoint/Interval', '0'),
             ('Output/Directory', self.dir),
             ('Mesh/Maximum refinement level', str(self.level))]
        if self.xi != FILE_XI:
            s.append(('Material/Transition length', fmt(self.xi)))
        if PINCH_RADIUS != FILE_PINCH_RADIUS:
            s.append(('Outcome/Pinch-off radius', fmt(PINCH_RADIUS)))
        if MIN_CELL_QUALITY is not None:
            s.append(('Time stepping/Minimum cell quality', fmt(MIN_CELL_QUALITY)))
        if self.level > 0:
            s.append(('Mesh/Interface cells per xi', fmt(CELLS_PER_XI[self.level])))
        return s

    def command(self, exe):
        return [exe, '--quiet', '--overwrite', *launch.settings(self.settings()), BASE]

    def shell(self, exe):
        words = [f'{k}={v}' for k, v in ENV.items()] + [exe, '--quiet', '--overwrite']
        for k, v in self.settings():
            words.append(f'--set "{k}={v}"')
        return ' '.join(words + [BASE])

    @property
    def finished(self):
        return os.path.exists(os.path.join(ROOT, self.dir, 'summary.json'))

    @property
    def log(self):
        return os.path.join(ROOT, OUTPUT, 'logs', self.name + '.log')


# ----------------------------------------------------------------------------------------------
# analysis of one case

def analyse(case):
    st = load_statistics(os.path.join(ROOT, case.dir))
    sm = load_summary(os.path.join(ROOT, case.dir))
    t, r, q = st['time'], st['neck_radius'], st['neck_ratio']
    a = {'case': case, 'stats': st, 'summary': sm, 'time': t, 'radius': r, 'ratio': q}
    neck = q < NECK_RATIO
    a['neck_formed'] = bool(neck.any())
    if neck.any():
        i = np.flatnonzero(neck)[np.argmin(r[neck])]
        a['min_neck'] = (float(r[i]), float(t[i]), float(q[i]))
        a['first_neck_time'] = float(t[np.flatnonzero(neck)[0]])
    else:
        a['min_neck'] = None
        a['first_neck_time'] = None
    i = int(np.argmin(r))
    a['min_any'] = (float(r[i]), float(t[i]), float(q[i]))
    j = int(np.argmin(q))
    a['min_ratio'] = (float(q[j]), float(t[j]), float(r[j]))
    a['final_cells'] = int(st['cells'][-1])
    a['max_cells'] = int(st['cells'].max())
    a['cpu'] = None
    if os.path.exists(case.log):
        m = re.search(r'User time \(seconds\): ([0-9.]+)', open(case.log).read())
        if m:
            a['cpu'] = float(m.group(1))
    return a


def reference_radius(u):
    """The uniform run's smallest neck radius with a neck formed, else its smallest neck_radius."""
    if u['min_neck'] is not None:
        return u['min_neck'][0], True
    return u['min_any'][0], False


# ----------------------------------------------------------------------------------------------
# plan and runs

def run_case(case, exe, timeout):  # a run stopped by the timeout keeps its last good state (SIGTERM)
    os.makedirs(os.path.dirname(case.log), exist_ok=True)
    cmd = ['/usr/bin/time', '-v'] + case.command(exe)
    print('running', case.name, flush=True)
    with open(case.log, 'w') as log:
        p = launch.start(cmd, cwd=ROOT, env=launch.environment(), stdout=log, stderr=subprocess.STDOUT)
        try:
            code = p.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            launch.kill_group(p, signal.SIGTERM)  # the run's own process group: time and the solver
            p.wait()
            # /usr/bin/time exits at once; the solver still writes its checkpoint and summary.json
            for _ in range(600):
                try:
                    os.killpg(p.pid, 0)
                except ProcessLookupError:
                    break
                time.sleep(0.1)
            code = 'timeout'
        log.flush()
        log.write(f'exit {code}\n')
    print(f'  {case.name}: exit {code}', flush=True)


def plan(args, execute):
    """The cases in order; with execute the unfinished ones are run as they are reached."""
    cases = []

    def step(case):
        cases.append(case)
        if case.finished:
            return True
        if execute:
            run_case(case, args.exe, args.timeout)
            return case.finished
        if not args.report_only:
            print(case.shell(args.exe))
        return False

    u = Case(0, SIGMA)
    if not step(u):
        if not execute and not args.report_only:
            print(f'# then, depending on the result: uniform32-s{fmt(SIGMA_FALLBACK)} (if no neck at {fmt(SIGMA)}), '
                  'adaptive2, adaptive3 (if adaptive2 does not halve the neck radius)')
        return cases
    sigma = SIGMA
    u2 = None
    if not analyse(u)['neck_formed']:
        u2 = Case(0, SIGMA_FALLBACK)
        if not step(u2):
            if not execute and not args.report_only:
                print('# then adaptive2 (and possibly adaptive3) at the line tension at which '
                      f'uniform 32 forms a neck, {fmt(SIGMA)} if none')
            return cases
        if analyse(u2)['neck_formed']:
            sigma, u = SIGMA_FALLBACK, u2
    a2 = Case(2, sigma)
    if not step(a2):
        if not execute and not args.report_only:
            print('# then adaptive3 if adaptive2 does not reach half the uniform neck radius')
        return cases
    ref, _ = reference_radius(analyse(u))
    r2 = analyse(a2)
    best = r2['min_neck'][0] if r2['min_neck'] else r2['min_any'][0]
    if args.max_level >= 3 and not (r2['min_neck'] and best <= 0.5 * ref):
        step(Case(3, sigma))
    elif Case(3, sigma).finished:
        cases.append(Case(3, sigma))
    # no neck on the uniform mesh at either line tension: adaptive2 also at the larger one,
    # where the uniform mesh comes closer to a neck
    if u2 is not None and u2.sigma != sigma:
        step(Case(2, u2.sigma))
    return cases


# ----------------------------------------------------------------------------------------------
# report

def f4(x):
    return '-' if x is None else f'{x:.4f}'


def figure(results):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for a in results:
        c = a['case']
        label = f"{c.name} (sigma {fmt(c.sigma)})"
        line, = ax1.plot(a['time'], a['radius'], label=label, lw=1.4,
                         ls='-' if c.level else '--')
        ax2.plot(a['time'], a['ratio'], color=line.get_color(), lw=1.4, ls='-' if c.level else '--')
        if a['min_neck']:
            r, t, _ = a['min_neck']
            ax1.plot([t], [r], 'o', color=line.get_color(), ms=5)
        ax1.plot([a['time'][-1]], [a['radius'][-1]], 'x', color=line.get_color(), ms=7)
    ax1.axhline(PINCH_RADIUS, color='grey', lw=0.8, ls=':')
    ax1.text(0.05, PINCH_RADIUS * 1.06, 'pinch-off radius', color='grey', fontsize=8)
    ax1.set_yscale('log')
    lo = min([0.025] + [0.8 * float(a['radius'].min()) for a in results])
    ax1.set_ylim(lo, 0.6)
    ticks = [t for t in (0.01, 0.02, 0.03, 0.05, 0.1, 0.2, 0.5) if t >= lo]
    ax1.set_yticks(ticks)
    ax1.set_yticklabels([f'{t:g}' for t in ticks])
    ax1.minorticks_off()
    ax1.set_xlabel('time')
    ax1.set_ylabel('neck_radius')
    ax1.set_xlim(0, END_TIME)
    ax1.legend(fontsize=8)
    ax2.axhline(NECK_RATIO, color='grey', lw=0.8, ls=':')
    ax2.text(0.05, NECK_RATIO + 0.015, 'complete neck ratio', color='grey', fontsize=8)
    ax2.set_xlabel('time')
    ax2.set_ylabel('neck_ratio')
    ax2.set_xlim(0, END_TIME)
    ax2.set_ylim(0, 1.05)
    fig.tight_layout()
    fig.savefig(os.path.join(ROOT, FIGURE), dpi=120)
    plt.close(fig)


def value_at(a, key, t):
    times = a['time']
    if t > times[-1] + 1e-9:
        return None
    return float(a[key][int(np.argmin(np.abs(times - t)))])


def report(cases, exe):
    results = [analyse(c) for c in cases if c.finished]
    if not results:
        print('no finished case; no report written')
        return
    figure(results)
    L = []
    L.append('# Neck resolution of the 7.3 bud: uniform mesh against local refinement')
    L.append('')
    L.append('A bud on a neck is followed only as far as the mesh resolves the neck. The 7.3 budding '
             'setup ([experiments/7.3-budding.prm](../experiments/7.3-budding.prm): bump of area 1.3, '
             f'phase-A domain of mass -0.85, kappa = 1.5, kappa_G = -1, xi = {fmt(FILE_XI)}) '
             + (f'with the transition length xi = {fmt(XI)} in place of {fmt(FILE_XI)} (and the line tension scaled '
                f'by {fmt(FILE_XI)} / {fmt(XI)}, so that sigma xi is the same) ' if XI != FILE_XI else '') +
             f'is run at a large line tension to t = {fmt(END_TIME)} on the uniform 32 x 32 mesh and on the 32 x 32 input mesh with local '
             'refinement (`Mesh/Maximum refinement level` 2 with `Mesh/Interface cells per xi` 3, finest cells '
             '1/128 in the parameter plane; level 3 with 6 per xi, 1/256). The neck observables are those '
             'of [model.md](model.md) (bud observables and outcome): of 64 closed cross-sections around '
             'the bud axis (radii of circles of equal area), the neck is the one narrowest relative to the '
             'widest section above it; `neck_radius` is its radius and `neck_ratio` its radius over that of '
             'the widest section above; a neck has formed when `neck_ratio` '
             f'< {NECK_RATIO} (`Outcome/Complete neck ratio`), and a run stops on approach to pinch-off when a '
             f'complete bud\'s neck radius falls below {PINCH_RADIUS} (`Outcome/Pinch-off radius`) or its steps '
             'keep failing; the same stall without a complete bud is a failure (exit code 2, last good '
             'state kept).')
    L.append('')
    L.append(f'Line tension {fmt(SIGMA)}; where the uniform 32 x 32 mesh forms no neck at {fmt(SIGMA)}, it is '
             f'also run at {fmt(SIGMA_FALLBACK)}, and the refined meshes use the first of these line tensions at '
             f'which the uniform mesh forms a neck ({fmt(SIGMA)} if it forms none; then level 2 is also run at '
             f'{fmt(SIGMA_FALLBACK)}). Level 3 is run only if level 2 does not reach half the uniform neck radius.')
    L.append('')
    L.append('Regenerate (runs only the cases without a `summary.json`, one at a time, then rewrites this '
             'page and its figure; `--dry-run` prints the commands):')
    L.append('')
    L.append('```sh')
    L.append(' '.join(['/usr/bin/python3 -m membrane_flow neck-resolution'] + OPTIONS))
    L.append('```')
    L.append('')
    L.append('The runs it makes (from the repository root):')
    L.append('')
    L.append('```text')
    for a in results:
        L.append(a['case'].shell(exe))
    L.append('```')
    L.append('')
    L.append('## Results')
    L.append('')
    L.append('Smallest neck radius: the smallest `neck_radius` among the steps with `neck_ratio` < 0.4 (a '
             'neck has formed), with its time and `neck_ratio`; "-" where no step has a neck. Narrowest '
             'section: the smallest `neck_radius` of the whole run, whatever its `neck_ratio`. Wall time: '
             "the run's own `wall_seconds` (one run at a time, the machine shared with other work); CPU: "
             'user time of the process.')
    L.append('')
    L.append('| case | sigma | mesh | outcome | stop reason | exit | smallest neck radius (neck formed) | at t | neck_ratio there | narrowest section (any ratio) | at t | neck_ratio there | smallest neck_ratio | final time | final cells | steps | rejected | wall (s) | CPU (s) |')
    L.append('|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|')
    for a in results:
        c, s = a['case'], a['summary']
        mn = a['min_neck'] or (None, None, None)
        stop = s['stop_reason']
        stop_short = stop.split(':')[0] if len(stop) > 60 else stop
        cpu = '-' if a['cpu'] is None else f"{a['cpu']:.0f}"
        L.append(f"| {c.name} | {fmt(c.sigma)} | {c.mesh} | {s['outcome']} | {stop_short} | "
                 f"{'2 (failed)' if s.get('failed') else '0'} | {f4(mn[0])} | "
                 f"{'-' if mn[1] is None else f'{mn[1]:.3f}'} | {f4(mn[2])} | {a['min_any'][0]:.4f} | "
                 f"{a['min_any'][1]:.3f} | {a['min_any'][2]:.4f} | {a['min_ratio'][0]:.4f} | "
                 f"{s['time']:.4f} | {a['final_cells']} | {s['steps']} | {s['rejected_steps']} | "
                 f"{s['wall_seconds']:.0f} | {cpu} |")
    L.append('')
    L.append('Stop reasons in full:')
    L.append('')
    for a in results:
        kinds = {k: n for k, n in (a['summary'].get('rejections') or {}).items() if n}
        why = ('; rejected steps by reason: ' + ', '.join(f'{k} {n}' for k, n in kinds.items())) if kinds else ''
        L.append(f"- {a['case'].name}: {a['summary']['stop_reason']}{why}")
    L.append('')
    if any((a['summary'].get('rejections') or {}).get('degenerate_cell') for a in results):
        L.append('A step is rejected as degenerate_cell when a corner of a cell would close below '
                 f'`Time stepping/Minimum cell quality` (sine {fmt(MIN_CELL_QUALITY or 0.1)}). In a closing neck the cells along the diagonals '
                 'of the input grid become rhombi (the neck shrinks them around its circumference and the local '
                 'area constraint stretches them along it), and the smallest corner sine sits at this bound for '
                 'step after step, so that tau stays near the value at which the next corner would close.')
        L.append('')

    # the comparison
    uniforms = [a for a in results if a['case'].level == 0]
    adaptives = [a for a in results if a['case'].level > 0]
    L.append('## The factor 2')
    L.append('')
    L.append(f'The diffuse interface, about 4 xi wide between phi = -0.9 and 0.9, sits in the neck. Narrowest '
             f'section of each run in units of xi = {fmt(XI)}: ' +
             ', '.join(f"{a['case'].name} {a['min_any'][0] / XI:.2f}" for a in results) + '.')
    L.append('')
    if uniforms and adaptives:
        for a in uniforms:
            if a['min_neck'] is None:
                L.append(f"- {a['case'].name} (sigma {fmt(a['case'].sigma)}) forms **no neck**: its smallest "
                         f"neck_ratio is {a['min_ratio'][0]:.4f} (t = {a['min_ratio'][1]:.3f}), above {NECK_RATIO}; "
                         f"outcome {a['summary']['outcome']}; narrowest section {a['min_any'][0]:.4f} at "
                         f"t = {a['min_any'][1]:.3f}; the run stops at t = {a['summary']['time']:.3f} "
                         f"({'failed, ' if a['summary'].get('failed') else ''}{a['summary']['stop_reason'].split(':')[0]}).")
            else:
                L.append(f"- {a['case'].name} (sigma {fmt(a['case'].sigma)}) forms a neck at "
                         f"t = {a['first_neck_time']:.3f}; smallest neck radius {a['min_neck'][0]:.4f} at "
                         f"t = {a['min_neck'][1]:.3f}.")
        for a in adaptives:
            te = float(a['time'][-1])
            r0, q0 = value_at(a, 'radius', te - 0.5), value_at(a, 'ratio', te - 0.5)
            drift = (f" Over the last 0.5 time units neck_radius changes by {a['radius'][-1] - r0:+.4f} and "
                     f"neck_ratio by {a['ratio'][-1] - q0:+.4f}.")
            if a['min_neck'] is None:
                L.append(f"- {a['case'].name} (sigma {fmt(a['case'].sigma)}) forms **no neck**: smallest "
                         f"neck_ratio {a['min_ratio'][0]:.4f}; narrowest section {a['min_any'][0]:.4f} at "
                         f"t = {a['min_any'][1]:.3f}; the run stops at t = {te:.3f} "
                         f"({a['summary']['stop_reason'].split(':')[0]}).{drift}")
            else:
                L.append(f"- {a['case'].name} (sigma {fmt(a['case'].sigma)}) forms a neck at "
                         f"t = {a['first_neck_time']:.3f}; smallest neck radius {a['min_neck'][0]:.4f} at "
                         f"t = {a['min_neck'][1]:.3f} (neck_ratio {a['min_neck'][2]:.4f}); outcome "
                         f"{a['summary']['outcome']}, stop: {a['summary']['stop_reason'].split(':')[0]} at "
                         f"t = {te:.3f}.{drift}")
        L.append('')
        verdicts = []
        for a in adaptives:
            u = next((b for b in uniforms if b['case'].sigma == a['case'].sigma), None)
            if u is None:
                continue
            un, an = u['case'].name, a['case'].name
            tu = float(u['time'][-1])
            ra, qa = value_at(a, 'radius', tu), value_at(a, 'ratio', tu)
            if ra is not None:
                L.append(f"- sigma {fmt(a['case'].sigma)}, at t = {tu:.3f} where {un} stops: {an} has "
                         f"neck_radius {ra:.4f} and neck_ratio {qa:.4f} against {u['radius'][-1]:.4f} and "
                         f"{u['ratio'][-1]:.4f}.")
            if u['min_neck'] is not None and a['min_neck'] is not None:
                f = u['min_neck'][0] / a['min_neck'][0]
                L.append(f"- Ratio of the smallest neck radii with a neck formed, {un} / {an}: "
                         f"{u['min_neck'][0]:.4f} / {a['min_neck'][0]:.4f} = **{f:.2f}**.")
                verdicts.append((f, an, un, 'smallest neck radius with a neck formed', True))
                continue
            ref = u['min_neck'][0] if u['min_neck'] else u['min_any'][0]
            refname = ('smallest neck radius with a neck formed' if u['min_neck'] else
                       'narrowest section (no neck formed)')
            r = a['min_neck'][0] if a['min_neck'] else a['min_any'][0]
            what = 'smallest neck radius with a neck formed' if a['min_neck'] else 'narrowest section (no neck formed)'
            f = ref / r
            missing = ' and '.join(n for n, b in ((un, u), (an, a)) if b['min_neck'] is None)
            L.append(f"- sigma {fmt(a['case'].sigma)}: no neck on {missing}, so the ratio of smallest neck radii "
                     f"with a neck formed on both meshes is undefined. {un} {refname} {ref:.4f} / {an} {what} "
                     f"{r:.4f} = **{f:.2f}**.")
            verdicts.append((f, an, un, f'{un}: {refname}; {an}: {what}', a['min_neck'] is not None))
        L.append('')
        reached = [v for v in verdicts if v[0] >= 2 and v[4]]
        if reached:
            f, an, un, basis, _ = max(reached)
            L.append(f"**The factor 2 is reached**: {an} follows a complete bud to a neck radius {f:.2f} times "
                     f"smaller than {un} reaches ({basis}).")
        else:
            best = max(verdicts) if verdicts else None
            L.append('**The factor 2 is not reached.** ' + (
                f"The largest ratio is {best[0]:.2f} ({best[1]} against {best[2]}; {best[3]})"
                + ('' if best[4] else ', and that refined run forms no neck') + '.' if best else ''))
            L.append('')
            for u in uniforms:
                ref = u['min_neck'][0] if u['min_neck'] else u['min_any'][0]
                ads = [a for a in adaptives if a['case'].sigma == u['case'].sigma]
                if not ads:
                    continue
                L.append(f"- sigma {fmt(u['case'].sigma)}: half of {u['case'].name}'s {ref:.4f} is {ref / 2:.4f}"
                         f"{' (below the pinch-off radius ' + fmt(PINCH_RADIUS) + ')' if ref / 2 < PINCH_RADIUS else ''}; "
                         + '; '.join(f"{a['case'].name} ends at neck_radius {a['radius'][-1]:.4f} "
                                     f"(t = {a['time'][-1]:.3f}, {a['summary']['rejected_steps']} rejected steps)"
                                     for a in ads) + '.')
        L.append('')
    elif uniforms:
        L.append('No refined case has finished; no comparison.')
        L.append('')

    # time series
    L.append('## Time series')
    L.append('')
    L.append('`neck_radius` / `neck_ratio` at the step nearest each time ("-" after the run has stopped).')
    L.append('')
    times = [0, 0.25, 0.5, 0.75, 1, 1.5, 2, 2.5, 3, 3.5, 4]
    L.append('| t | ' + ' | '.join(a['case'].name for a in results) + ' |')
    L.append('|---|' + '---|' * len(results))
    for t in times:
        row = []
        for a in results:
            r, q = value_at(a, 'radius', t), value_at(a, 'ratio', t)
            row.append('-' if r is None else f'{r:.4f} / {q:.3f}')
        L.append(f'| {t:g} | ' + ' | '.join(row) + ' |')
    row = [f"{a['radius'][-1]:.4f} / {a['ratio'][-1]:.3f} (t = {a['time'][-1]:.3f})" for a in results]
    L.append('| end | ' + ' | '.join(row) + ' |')
    L.append('')
    L.append(f'![neck radius and neck ratio against time](images/{os.path.basename(FIGURE)})')
    L.append('')
    L.append('Left: `neck_radius` against time (log scale; dashed: uniform, solid: refined; circle: smallest '
             'neck radius with a neck formed; cross: end of the run). Right: `neck_ratio`; below the dotted '
             'line at 0.4 a neck has formed. While `neck_ratio` is 1 the narrowest section is the base of '
             'the dome; once the domain has risen into a finger it is the finger\'s waist, hence the drop '
             'of `neck_radius` early in every run.')
    L.append('')

    # messages
    msgs = []
    for a in results:
        path = os.path.join(ROOT, a['case'].dir, 'log.txt')
        if not os.path.exists(path):
            continue
        for line in open(path):
            if re.search(r'warning|error|fail', line, re.I):
                msgs.append(f"- {a['case'].name}: `{line.strip()}`")
    if msgs:
        L.append('## Messages from the runs')
        L.append('')
        L += msgs
        L.append('')
    versions = sorted({a['summary'].get('code_version', '?') for a in results})
    L.append(f"Binary: `{exe}`; code version of the runs: {', '.join(versions)}.")
    L.append('')
    with open(os.path.join(ROOT, DOC), 'w') as f:
        f.write('\n'.join(L))
    print('wrote', DOC, 'and', FIGURE)


def main(argv=None):
    global XI, SIGMA, SIGMA_FALLBACK, OUTPUT, DOC, FIGURE, OPTIONS, PINCH_RADIUS, END_TIME, MIN_CELL_QUALITY
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('--dry-run', action='store_true', help='print the commands of the cases to run')
    p.add_argument('--report-only', action='store_true', help='run nothing; write the report')
    p.add_argument('--max-level', type=int, default=3, help='highest refinement level to run (2 or 3)')
    p.add_argument('--exe', help='the program (default: see membrane_flow.launch.find_executable)')
    p.add_argument('--timeout', type=float, default=None, help='seconds per run')
    p.add_argument('--sigma', type=float, default=None,
                   help=f'line tension of the study (default {SIGMA:g}; the fallback is 4/3 of it)')
    p.add_argument('--xi', type=float, default=FILE_XI,
                   help=f'transition length (default the file\'s {FILE_XI:g}); the line tensions scale by {FILE_XI:g} / xi')
    p.add_argument('--end-time', type=float, default=END_TIME, help=f'end time of every run (default {END_TIME:g})')
    p.add_argument('--min-cell-quality', type=float, default=None,
                   help='Time stepping/Minimum cell quality of every run (default: the file\'s 0.1)')
    args = p.parse_args(argv)
    shown_exe = args.exe or EXE  # the report shows the runs with build/membrane-flow unless --exe was given
    args.exe = launch.find_executable(args.exe)
    if not 0 < args.end_time <= 100:
        p.error('--end-time takes a time in (0, 100]')
    if args.min_cell_quality is not None and not 0 < args.min_cell_quality < 1:
        p.error('--min-cell-quality takes a corner sine in (0, 1)')
    if not 0 < args.xi <= 1:
        p.error('--xi takes a transition length in (0, 1]')
    if args.sigma is not None and not 0 < args.sigma < 1e6:
        p.error('--sigma takes a line tension in (0, 1e6)')
    OPTIONS = ([f'--sigma {fmt(args.sigma)}'] if args.sigma is not None else []) + \
              ([f'--xi {fmt(args.xi)}'] if args.xi != FILE_XI else []) + \
              ([f'--max-level {args.max_level}'] if args.max_level != 3 else []) + \
              ([f'--timeout {fmt(args.timeout)}'] if args.timeout else []) + \
              ([f'--end-time {fmt(args.end_time)}'] if args.end_time != END_TIME else []) + \
              ([f'--min-cell-quality {fmt(args.min_cell_quality)}'] if args.min_cell_quality is not None else [])
    END_TIME, MIN_CELL_QUALITY = args.end_time, args.min_cell_quality
    if args.sigma is not None:
        SIGMA, SIGMA_FALLBACK = args.sigma, args.sigma * 4 / 3
        OUTPUT, DOC = f'{OUTPUT}-s{fmt(SIGMA)}', f'docs/neck-resolution-s{fmt(SIGMA)}.md'
        FIGURE = f'docs/images/neck-resolution-s{fmt(SIGMA)}.png'
    if args.xi != FILE_XI:
        XI = args.xi
        PINCH_RADIUS = FILE_PINCH_RADIUS * XI / FILE_XI
        SIGMA, SIGMA_FALLBACK = SIGMA * FILE_XI / XI, SIGMA_FALLBACK * FILE_XI / XI
        OUTPUT, DOC = f'{OUTPUT}-xi{fmt(XI)}', f'{DOC[:-3]}-xi{fmt(XI)}.md'
        FIGURE = f'{FIGURE[:-4]}-xi{fmt(XI)}.png'
    os.chdir(ROOT)
    if args.dry_run:
        if all(c.finished for c in plan(args, execute=False)):
            print('# every case has a summary.json; nothing to run')
        return
    cases = plan(args, execute=not args.report_only)
    report(cases, shown_exe)


if __name__ == '__main__':
    main()
