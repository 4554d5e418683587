"""Mesh-convergence study of the 7.3 budding setup: uniform meshes against local refinement.

For each line tension sigma (default 630 and 1000) the 7.3 setup (experiments/7.3-budding.prm,
end time 3.1 unless --end-time) runs on
  - uniform meshes of 32, 48 and 64 cells per side (Mesh/Maximum refinement level = 0; --uniform
    chooses others, e.g. 32,48,64,128);
  - the 32 x 32 input mesh with local refinement: level 1 with Interface cells per xi = 1.5,
    level 2 with 3, level 3 with 6 (--levels chooses which; default 1,2).
VTU output and checkpoints are off; every case runs in its own directory
<output>/s<sigma>/<case>/ with OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1.

A case is finished when its summary.json exists: started again, the command skips finished
cases and reruns the others from scratch (an interrupted, killed or timed-out case leaves no
summary.json). A run that exits with code 2 (blow-up) writes its summary with "failed": true;
it counts as finished and is listed as failed.

Then it reads every case's summary.json and statistics.txt and writes
docs/mesh-convergence.md (tables, conclusions drawn from the numbers) and the figures
docs/images/mesh-convergence.png (final energy against number of cells) and
docs/images/mesh-convergence-history.png (energy and cells against time).

Run from the repository's top directory (the runs, the page and its figures are written there).

Usage: python3 -m membrane_flow mesh-convergence [--workers 2] [--exe build/membrane-flow] [--levels 1,2]
           [--uniform 32,48,64] [--sigmas 630,1000] [--end-time T] [--timeout SECONDS] [--report-only]
"""
import argparse
import json
import os
import re
import shlex
import signal
import subprocess
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor, as_completed

import numpy as np

from .. import launch, run
from ..run import load_statistics

ROOT = os.getcwd()  # the repository's top directory: the input file, the runs and the page are relative to it

BASE = 'experiments/7.3-budding.prm'
DEFAULT_OUTPUT = 'results/studies/mesh-convergence'
UNIFORM = [32, 48, 64]
CELLS_PER_XI = {1: 1.5, 2: 3.0, 3: 6.0}
FILE_END_TIME = 3.1  # the base file's End time
DOC = 'docs/mesh-convergence.md'
# The sigma = 1000 budded state relaxed beyond t = 3.1 at levels 1-3 (its own study and script).
BUDDED = 'experiments/studies/budded_state/gauss_bonnet.json'
FIGURE = 'docs/images/mesh-convergence.png'
HISTORY = 'docs/images/mesh-convergence-history.png'


def budded_state_section():
    """The sigma = 1000 budded state beyond t = 3.1, from BUDDED (experiments/studies/budded_state/README.md):
    energies at equal times and at equal neck radii on levels 1-3, with their observed orders."""
    if not os.path.exists(os.path.join(ROOT, BUDDED)):
        return []
    data = run.read_json(os.path.join(ROOT, BUDDED))

    def order(o):  # the differences change sign, grow, or shrink with order p
        return 'not monotone' if o.get('p') is None else 'none (grows)' if o['p'] <= 0 else f"{o['p']:.1f}"

    def rows(key, label, unit):
        out = []
        for where, entry in data[key].items():
            levels = entry['levels']
            if not all(levels.get(f'L{l}', {}).get('energy') is not None for l in (1, 2, 3)):
                continue
            energies = ', '.join(f"{levels[f'L{l}']['energy']:.3f}" for l in (1, 2, 3))
            bending = ', '.join(f"{levels[f'L{l}']['bending']:.3f}" for l in (1, 2, 3))
            line = ', '.join(f"{levels[f'L{l}']['line']:.3f}" for l in (1, 2, 3))
            o = entry['orders']
            out.append(f"| {label} = {where}{unit} | {energies} | {order(o['energy'])} | {bending} | "
                       f"{order(o['bending'])} | {line} | {order(o['line'])} |")
        return out
    header = ['| state | energy, levels 1, 2, 3 | order | bending | order | line | order |', '|---|---|---|---|---|---|---|']
    lines = ['### The budded state beyond t = 3.1', '',
             'The t = 3.1 energies above are not equilibria: the sigma = 1000 bud keeps closing its neck. '
             f'[experiments/studies/budded_state](../experiments/studies/budded_state/README.md) ({BUDDED}) runs it '
             'on at levels 1, 2, 3 (1.5, 3, 6 cells per xi) and compares the levels at equal times and at equal '
             'neck radii, which the levels pass at different times (the Gaussian energy of the uniform kappa_G is '
             'exactly 0 there). "order": log2 of the ratio of the two differences, where they shrink.', '']
    table = rows('equal_time', 't', '') + rows('equal_neck_radius', 'neck radius', '')
    lines += header + table + ['']

    def count(column):  # rows whose order in this column (energy 2, bending 4, line 6) is at least 1
        return sum(1 for row in table if re.fullmatch(r'[0-9.]+', row.split('|')[column + 1].strip()) and
                   float(row.split('|')[column + 1]) >= 1)
    lines += [f'An observed order of at least 1 holds for the energy in {count(2)} of {len(table)} rows, for the '
              f'bending energy in {count(4)}, for the line energy in {count(6)}' +
              (': the budded state converges at these levels.' if count(2) == len(table) else
               ': the budded state has no mesh-converged energy on these runs, and its neck is still closing where '
               'they stop.'), '']
    return lines


# ----------------------------------------------------------------------------------------------
# cases

class Case:
    def __init__(self, sigma, kind, value, output):
        self.sigma, self.kind, self.value = sigma, kind, value  # kind 'uniform' (value N) / 'adaptive' (level)
        self.name = f'uniform-{value}' if kind == 'uniform' else f'adaptive-L{value}'
        self.dir = os.path.join(output, f's{fmt_sigma(sigma)}', self.name)

    @property
    def label(self):
        if self.kind == 'uniform':
            return f'uniform {self.value}'
        return f'adaptive {self.value} ({CELLS_PER_XI[self.value]:g} per xi)'

    def settings(self, end_time):
        s = {'Material/Line tension': fmt_sigma(self.sigma),
             'Output/Write VTU': 'false',
             'Checkpoint/Interval': '0',
             'Output/Directory': self.dir}
        if end_time is not None:
            s['Time stepping/End time'] = f'{end_time:g}'
        if self.kind == 'uniform':
            s['Mesh/Cells per side'] = str(self.value)
            s['Mesh/Maximum refinement level'] = '0'
        else:
            s['Mesh/Cells per side'] = '32'
            s['Mesh/Maximum refinement level'] = str(self.value)
            s['Mesh/Interface cells per xi'] = f'{CELLS_PER_XI[self.value]:g}'
        return s

    def command(self, exe, end_time, overwrite=True):
        cmd = [exe, '--quiet']
        if overwrite:  # an interrupted case is rerun from scratch (older binaries lack the option)
            cmd.append('--overwrite')
        return cmd + launch.settings(self.settings(end_time)) + [BASE]

    def finished(self):
        return os.path.exists(os.path.join(self.dir, 'summary.json'))

    def cost_rank(self):
        """Rough expected cost, for running the slowest cases first."""
        if self.kind == 'uniform':
            return (self.value / 32) ** 2
        return {1: 1.5, 2: 5.0, 3: 20.0}[self.value]


def fmt_sigma(s):
    return f'{s:g}'


def make_cases(sigmas, levels, output):
    cases = []
    for s in sigmas:
        cases += [Case(s, 'uniform', n, output) for n in UNIFORM]
        cases += [Case(s, 'adaptive', lvl, output) for lvl in levels]
    return cases


# ----------------------------------------------------------------------------------------------
# running

class Runner:
    def __init__(self, exe, end_time, timeout):
        self.exe, self.end_time, self.timeout = exe, end_time, timeout
        self.overwrite = supports_overwrite(exe)
        self.lock = threading.Lock()
        self.running = set()
        self.stopping = False

    def run(self, case):
        if case.finished():
            return case, 'skipped'
        if self.stopping:
            return case, 'not started'
        if os.path.isdir(case.dir):
            for name in os.listdir(case.dir):  # an interrupted attempt starts over
                path = os.path.join(case.dir, name)
                if os.path.isfile(path):
                    os.remove(path)
        os.makedirs(case.dir, exist_ok=True)
        command = case.command(self.exe, self.end_time, self.overwrite)
        env = launch.environment()
        write_json(os.path.join(case.dir, 'case.json'),
                   {'command': command, 'shell': ' '.join(shlex.quote(c) for c in command),
                    'environment': 'OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1', 'cwd': ROOT})
        start = time.time()
        timed_out = False
        # The run's own log.txt: the simulator recognizes it as its stdout and does not write it twice
        # (any other file would be foreign to the run directory, which the simulator refuses).
        with open(os.path.join(case.dir, 'log.txt'), 'w') as log:
            process = launch.start(command, cwd=ROOT, env=env, stdout=log, stderr=subprocess.STDOUT)
            with self.lock:
                self.running.add(process)
            timer = None
            if self.timeout:
                def on_timeout():
                    nonlocal timed_out
                    timed_out = True
                    terminate(process)
                timer = threading.Timer(self.timeout, on_timeout)
                timer.start()
            # wait4 gives the CPU time of this child alone (cases run in parallel)
            _, status, usage = os.wait4(process.pid, 0)
            process.returncode = os.waitstatus_to_exitcode(status)
            if timer:
                timer.cancel()
            with self.lock:
                self.running.discard(process)
        code = process.returncode
        record = {'exit_code': code, 'wall_seconds': time.time() - start,
                  'cpu_seconds': usage.ru_utime + usage.ru_stime, 'max_rss_kb': usage.ru_maxrss,
                  'timed_out': timed_out, 'timeout_seconds': self.timeout}
        write_json(os.path.join(case.dir, 'status.json'), record)
        if self.stopping and not timed_out and code != 0:
            summary = os.path.join(case.dir, 'summary.json')
            if os.path.exists(summary):
                os.remove(summary)
            return case, 'interrupted'
        if timed_out:
            return case, f'timed out after {self.timeout:g} s'
        return case, 'finished' if code == 0 else f'exit code {code}'

    def stop(self, signum, frame):
        self.stopping = True
        with self.lock:
            for p in list(self.running):
                terminate(p)


def supports_overwrite(exe):
    """Whether the executable knows --overwrite (its --help names it; builds before it print only a usage)."""
    try:
        result = subprocess.run([exe, '--help'], capture_output=True, text=True, timeout=60, stdin=subprocess.DEVNULL)
    except (OSError, subprocess.TimeoutExpired):
        return True
    return '--overwrite' in result.stdout + result.stderr


def terminate(process):
    launch.kill_group(process, signal.SIGTERM)


def write_json(path, data):
    tmp = path + '.tmp'
    with open(tmp, 'w') as f:
        json.dump(data, f, indent=1)
        f.write('\n')
    os.replace(tmp, path)


def read_json(path):
    try:
        return run.read_json(path)
    except (OSError, ValueError):
        return None


def run_cases(cases, runner, workers):
    todo = sorted(cases, key=lambda c: -c.cost_rank())
    pending = [c for c in todo if not c.finished()]
    print(f'{len(cases) - len(pending)} of {len(cases)} cases finished; running {len(pending)} '
          f'with {workers} worker(s)', flush=True)
    signal.signal(signal.SIGINT, runner.stop)
    signal.signal(signal.SIGTERM, runner.stop)
    with ThreadPoolExecutor(max_workers=workers) as pool:
        futures = [pool.submit(runner.run, c) for c in pending]
        for future in as_completed(futures):
            case, status = future.result()
            print(f'  {time.strftime("%H:%M:%S")} s{fmt_sigma(case.sigma)} {case.name}: {status}', flush=True)
    return not runner.stopping


# ----------------------------------------------------------------------------------------------
# reading

WARNING_RE = re.compile(r'warn|error|fail|nan|inf\b|refus|could not|cannot', re.IGNORECASE)


def read_case(case):
    summary = read_json(os.path.join(case.dir, 'summary.json'))
    status = read_json(os.path.join(case.dir, 'status.json'))
    stats = None
    if os.path.exists(os.path.join(case.dir, 'statistics.txt')):
        try:
            stats = load_statistics(case.dir)
        except Exception:  # noqa: BLE001 -- a half-written or empty file: report without history
            stats = None
    warnings = []
    for name in ('log.txt',):  # the run's stdout/stderr as captured here
        log = os.path.join(case.dir, name)
        if os.path.exists(log):
            with open(log, errors='replace') as f:
                for line in f:
                    line = line.strip()
                    if line and WARNING_RE.search(line) and not line.startswith('Results:') \
                            and line not in warnings:
                        warnings.append(line)
    return {'case': case, 'summary': summary, 'status': status, 'stats': stats, 'warnings': warnings}


def state(r):
    """'ok', 'failed', 'timed out', 'killed', 'not run'."""
    s, st = r['summary'], r['status']
    if s is not None:
        if s.get('failed') or (st and st.get('exit_code') not in (0, None)):
            return 'failed'
        return 'ok'
    if st is None:
        return 'not run'
    if st.get('timed_out'):
        return 'timed out'
    return 'killed'


def line_energy(s):
    return s['gradient_energy'] + s['well_energy']


# ----------------------------------------------------------------------------------------------
# report

def order_estimate(sizes, energies):
    """p with (E1 - E2)/(E2 - E3) = (n1^-p - n2^-p)/(n2^-p - n3^-p) for the three finest uniform
    meshes n1 < n2 < n3 cells per side, i.e. E = E* + C h^p with h = 1/n; and the extrapolated
    E*. None when the differences change sign (not monotone)."""
    (n1, n2, n3), (e1, e2, e3) = [float(n) for n in sizes[-3:]], energies[-3:]
    d1, d2 = e1 - e2, e2 - e3
    if d1 == 0 or d2 == 0 or (d1 > 0) != (d2 > 0):
        return None
    ratio = d1 / d2

    def g(p):
        return (n1 ** -p - n2 ** -p) / (n2 ** -p - n3 ** -p) - ratio
    lo, hi = 1e-3, 20.0
    if g(lo) * g(hi) > 0:  # ratio outside what any p in (0, 20] gives
        return None
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if g(lo) * g(mid) <= 0:
            hi = mid
        else:
            lo = mid
    p = 0.5 * (lo + hi)
    c = d2 / (n2 ** -p - n3 ** -p)
    return p, e3 - c * n3 ** -p


def uniform_names(sizes):
    return ', '.join(str(n) for n in sizes)


def fmt(x, digits=4):
    if x is None:
        return '–'
    if isinstance(x, float) and not np.isfinite(x):
        return str(x)
    return f'{x:.{digits}g}'


def table(results, sigma):
    rows = [r for r in results if r['case'].sigma == sigma]
    ref = next((r for r in rows if r['case'].kind == 'uniform' and r['case'].value == max(UNIFORM)
                and state(r) == 'ok'), None)
    e_ref = ref['summary']['energy'] if ref else None
    head = ('| mesh | final cells | final energy | line energy | bending energy | outcome | domain_protrusion '
            f'| neck_radius at stop | steps | rejected steps | wall time (s) | energy vs uniform {max(UNIFORM)} |')
    lines = [head, '|' + '---|' * 12]
    for r in rows:
        c, s, st = r['case'], r['summary'], r['status']
        k = state(r)
        if s is None:
            if k == 'timed out':
                what = f'**timed out** (killed after {st["wall_seconds"]:.0f} s)'
            elif k == 'killed':
                what = f'**killed** (exit code {st.get("exit_code")}, no summary)'
            else:
                what = 'not run'
            wall = f'{st["wall_seconds"]:.0f}' if st else '–'
            lines.append(f'| {c.label} | – | – | – | – | {what} | – | – | – | – | {wall} | – |')
            continue
        outcome = s['outcome']
        if k == 'failed':
            outcome = f'**failed** ({s.get("stop_reason")}, exit {st.get("exit_code") if st else "?"}); ' \
                      f'last state: {outcome}'
        elif s.get('stop_reason') != 'end time':
            outcome = f'{outcome} (stop: {s.get("stop_reason")} at t = {s.get("time"):.3g})'
        rel = '–'
        if e_ref is not None:
            rel = 'reference' if r is ref else f'{100 * (s["energy"] - e_ref) / e_ref:+.2f} %'
        lines.append(
            f'| {c.label} | {s["cells"]} | {s["energy"]:.4f} | {line_energy(s):.4f} | {s["bending_energy"]:.4f} '
            f'| {outcome} | {s["domain_protrusion"]:.3f} | {s["neck_radius"]:.4f} | {s["steps"]} '
            f'| {s["rejected_steps"]} | {s["wall_seconds"]:.0f} | {rel} |')
    return '\n'.join(lines)


def conclusions(results, sigma, levels):
    rows = {(r['case'].kind, r['case'].value): r for r in results if r['case'].sigma == sigma}
    ok = {k: r for k, r in rows.items() if state(r) == 'ok'}
    out = []
    nmax = max(UNIFORM)
    ref = ok.get(('uniform', nmax))
    # adaptive at its finest level against the finest uniform mesh
    finest = max(levels) if levels else None
    if finest is not None:
        a = rows.get(('adaptive', finest))
        if a is None or state(a) != 'ok':
            out.append(f'Adaptive level {finest}: {state(a) if a else "not run"}, so no comparison with the '
                       f'finest uniform mesh.')
        elif ref is None:
            out.append(f'The uniform {nmax} run is missing or failed, so adaptive level {finest} has no reference.')
        else:
            ea, er = a['summary']['energy'], ref['summary']['energy']
            rel = (ea - er) / er
            wa, wr = a['summary']['wall_seconds'], ref['summary']['wall_seconds']
            verdict = 'agrees with' if abs(rel) <= 0.01 else 'does **not** agree with'
            out.append(f'Adaptive level {finest}, the finest interface resolution run ({CELLS_PER_XI[finest]:g} cells '
                       f'per xi), {verdict} uniform {nmax} within 1 %: final energy {ea:.4f} against {er:.4f} '
                       f'({100 * rel:+.2f} %), at {wa / wr:.2f} times its wall time ({wa:.0f} s against {wr:.0f} s).')
            for lvl in sorted(levels):
                b = ok.get(('adaptive', lvl))
                if not b:
                    continue
                sb, sr = b['summary'], ref['summary']
                eb = sb['energy']
                cb, cr = (b['status'] or {}).get('cpu_seconds'), (ref['status'] or {}).get('cpu_seconds')
                cpu = f', CPU time {cb:.0f} s against {cr:.0f} s ({cb / cr:.2f}x)' if cb and cr else ''
                out.append(f'Adaptive level {lvl} ({CELLS_PER_XI[lvl]:g} per xi, {sb["cells"]} final cells against '
                           f'{nmax * nmax}): energy {100 * (eb - er) / er:+.2f} % from uniform {nmax}, of which line '
                           f'energy {line_energy(sb) - line_energy(sr):+.3f} and bending energy '
                           f'{sb["bending_energy"] - sr["bending_energy"]:+.3f}; wall time '
                           f'{sb["wall_seconds"] / wr:.2f}x{cpu}.')
    # like for like: level L against the uniform mesh of its finest cells, 32 x 2^L per side
    for lvl in sorted(levels):
        b, u = ok.get(('adaptive', lvl)), ok.get(('uniform', 32 * 2 ** lvl))
        if not b or not u:
            continue
        sb, su = b['summary'], u['summary']
        rel = (sb['energy'] - su['energy']) / su['energy']
        wall = sb['wall_seconds'] / su['wall_seconds']
        cb, cu = (b['status'] or {}).get('cpu_seconds'), (u['status'] or {}).get('cpu_seconds')
        cpu = f', CPU time {cb / cu:.2f}x ({cb:.0f} s against {cu:.0f} s)' if cb and cu else ''
        both = abs(rel) <= 0.01 and wall <= 1 / 3
        out.append(f'Adaptive level {lvl} against uniform {32 * 2 ** lvl}, whose cells are everywhere as small as '
                   f'its finest: energy {100 * rel:+.2f} %, neck radius {sb["neck_radius"]:.4f} against '
                   f'{su["neck_radius"]:.4f}, outcome {sb["outcome"]} against {su["outcome"]}, with '
                   f'{sb["cells"]} cells against {su["cells"]} at {wall:.2f} times the wall time{cpu}: '
                   + ('**within 1 % at no more than a third of the wall time**.' if both else
                      f'{"within" if abs(rel) <= 0.01 else "**not** within"} 1 %, '
                      f'{"at no more" if wall <= 1 / 3 else "at **more**"} than a third of the wall time.'))
    # uniform convergence
    us = [ok.get(('uniform', n)) for n in UNIFORM]
    names = uniform_names(UNIFORM[-3:])
    if all(us):
        e = [u['summary']['energy'] for u in us]
        seq = ', '.join(f'{x:.4f}' for x in e)
        changes = ', '.join(f'{a}->{b} {e[i + 1] - e[i]:+.4f}' for i, (a, b) in enumerate(zip(UNIFORM, UNIFORM[1:])))
        est = order_estimate(UNIFORM, e)
        if est is None:
            out.append(f'Uniform energies ({uniform_names(UNIFORM)}): {seq}; changes {changes}. The changes between '
                       f'{names} are not monotone in a way a power law fits, so no order is estimated.')
        elif est[0] < 0.5:
            out.append(f'Uniform energies ({uniform_names(UNIFORM)}): {seq}; changes {changes}. Fitting '
                       f'E = E* + C h^p to {names} gives an observed order p = {est[0]:.2f}: the uniform sequence is '
                       f'far from its asymptotic range at this end time, and an extrapolation would mean nothing.')
        else:
            p, einf = est
            out.append(f'Uniform energies ({uniform_names(UNIFORM)}): {seq}; changes {changes}. Fitting '
                       f'E = E* + C h^p to {names} gives an observed order p = {p:.2f} and an extrapolated '
                       f'E* = {einf:.4f}; uniform {nmax} is then {100 * (e[-1] - einf) / einf:+.2f} % from E*. Three '
                       f'points determine p exactly, so this is an estimate, not a test of the asymptotic range.')
            for lvl in sorted(levels):
                b = ok.get(('adaptive', lvl))
                if b:
                    eb = b['summary']['energy']
                    out.append(f'Adaptive level {lvl} is {100 * (eb - einf) / einf:+.2f} % from that E*.')
    else:
        out.append('Not every uniform run finished, so no order of convergence is estimated.')
    # the adaptive sequence: each level halves the interface cells
    ad = [ok.get(('adaptive', lvl)) for lvl in sorted(levels)]
    if len(ad) >= 3 and all(ad) and sorted(levels)[-3:] == list(range(sorted(levels)[-3], sorted(levels)[-3] + 3)):
        e = [b['summary']['energy'] for b in ad[-3:]]
        d1, d2 = e[0] - e[1], e[1] - e[2]
        text = (f'Adaptive energies (levels {", ".join(str(l) for l in sorted(levels)[-3:])}): '
                f'{", ".join(f"{x:.4f}" for x in e)}; changes {-d1:+.4f}, {-d2:+.4f}')
        p = np.log2(d1 / d2) if d1 != 0 and d2 != 0 and (d1 > 0) == (d2 > 0) and abs(d1) > abs(d2) else None
        if p is not None and p < 0.5:
            text += (f': the second change is {100 * d2 / d1:.0f} % of the first (observed order {p:.2f} in the '
                     f'interface cell size), so the adaptive sequence is far from converged and an extrapolation '
                     f'would mean nothing')
        elif p is not None:
            einf = e[2] - d2 / (2 ** p - 1)
            text += (f': with the interface cell size halved per level, an observed order {p:.2f} and an extrapolated '
                     f'{einf:.4f}')
            if all(ok.get(('uniform', n)) for n in UNIFORM) and (order_estimate(
                    UNIFORM, [ok[('uniform', n)]['summary']['energy'] for n in UNIFORM]) or (0,))[0] >= 0.5:
                eu = order_estimate(UNIFORM, [ok[('uniform', n)]['summary']['energy'] for n in UNIFORM])[1]
                text += f', {100 * (einf - eu) / eu:+.2f} % from the uniform E*'
        else:
            text += ': the changes do not shrink, so the adaptive sequence shows no convergence yet'
        out.append(text + '.')
    # is the state at the end time settled?
    late = []
    for r in rows.values():
        st = r['stats']
        if st is None or len(st['time']) < 2:
            continue
        i = int(np.searchsorted(st['time'], st['time'][-1] - 0.5))
        late.append((r['case'].label, st['energy'][-1] - st['energy'][i], st['neck_radius'][-1] - st['neck_radius'][i]))
    if late:
        out.append('Change over the last 0.5 time units (energy; neck radius): ' +
                   ', '.join(f'{l} {de:+.3f}; {dn:+.4f}' for l, de, dn in late) +
                   '. Where these are comparable to the differences between meshes, the meshes are compared at '
                   'different stages of a still-running relaxation, not at a common equilibrium.')
    buds = [r for r in rows.values() if r['summary'] is not None and r['summary']['outcome'] == 'complete bud'
            and r['summary']['neck_radius'] > 0]
    if len(buds) >= 2:
        ratio = [line_energy(r['summary']) / r['summary']['neck_radius'] for r in buds]
        out.append(f'For the complete buds, line energy / neck radius is {min(ratio):.0f} to {max(ratio):.0f} on '
                   f'every mesh (spread {100 * (max(ratio) - min(ratio)) / np.mean(ratio):.1f} %) while the line '
                   f'energy itself varies by {100 * (max(line_energy(r["summary"]) for r in buds) - min(line_energy(r["summary"]) for r in buds)) / np.mean([line_energy(r["summary"]) for r in buds]):.0f} %: '
                   f'the interface sits in the neck, so the line-energy differences between meshes are those of '
                   f'the neck radius reached at the end time.')
    # outcome and protrusion
    done = [r for r in rows.values() if r['summary'] is not None]
    if done:
        outcomes = sorted({r['summary']['outcome'] for r in done})
        prot = [r['summary']['domain_protrusion'] for r in done]
        neck = [r['summary']['neck_radius'] for r in done]
        if len(outcomes) == 1:
            out.append(f'The outcome is "{outcomes[0]}" on every mesh.')
        else:
            per = '; '.join(f'{r["case"].label}: {r["summary"]["outcome"]}' for r in done)
            out.append(f'The outcome **changes with resolution**: {per}.')
        out.append(f'domain_protrusion ranges from {min(prot):.3f} to {max(prot):.3f} across the meshes, '
                   f'neck_radius at stop from {min(neck):.4f} to {max(neck):.4f}.')
        stops = sorted({r['summary'].get('stop_reason') for r in done})
        if stops != ['end time']:
            out.append('Stop reasons: ' + '; '.join(f'{r["case"].label}: {r["summary"].get("stop_reason")} at t = '
                                                    f'{r["summary"].get("time"):.3g}' for r in done) + '.')
    # sudden jumps of the bud observables (a change of shape cannot happen in one step of tau <= 1e-2)
    jumps = []
    for r in rows.values():
        st = r['stats']
        if st is None or len(st['time']) < 2 or 'domain_protrusion' not in st:
            continue
        dp = np.diff(st['domain_protrusion'])
        flip = np.diff(np.sign(st['bud_direction'])) != 0 if 'bud_direction' in st else np.zeros_like(dp, bool)
        adapt = np.diff(st['adaptations']) != 0 if 'adaptations' in st else np.zeros_like(dp, bool)
        for i in np.nonzero((np.abs(dp) > 0.25) | flip)[0]:
            jumps.append(f'{r["case"].label} at step {int(st["step"][i + 1])} (t = {st["time"][i + 1]:.4g}'
                         f'{", the first step after a mesh adaptation" if adapt[i] else ""}): domain_protrusion '
                         f'{st["domain_protrusion"][i]:.3f} -> {st["domain_protrusion"][i + 1]:.3f}, bud_direction '
                         f'{st["bud_direction"][i]:+.0f} -> {st["bud_direction"][i + 1]:+.0f}, bud_height '
                         f'{st["bud_height"][i]:.3f} -> {st["bud_height"][i + 1]:.3f}, while the energy changes by '
                         f'{st["energy"][i + 1] - st["energy"][i]:+.3g}')
    if jumps:
        out.append('**Bud observables jump within one step** (not a plausible change of shape at tau <= 1e-2, '
                   'so the final outcome and protrusion of such a run are suspect): ' + '; '.join(jumps) + '.')
    else:
        out.append('No run has a one-step jump of domain_protrusion above 0.25 or a flip of bud_direction.')
    # budding time: first time domain_protrusion reaches the complete-bud threshold 0.95
    tb = []
    for r in rows.values():
        st = r['stats']
        if st is not None and 'domain_protrusion' in st:
            i = np.nonzero(st['domain_protrusion'] >= 0.95)[0]
            if len(i):
                tb.append((r['case'].label, st['time'][i[0]]))
    if tb:
        out.append('Time at which domain_protrusion first reaches 0.95 (the complete-bud threshold; T_min of '
                   '[workflow.md](workflow.md)): ' + ', '.join(f'{l} {t:.3f}' for l, t in tb) + '.')
    # adaptation energy jumps
    for lvl in sorted(levels):
        b = rows.get(('adaptive', lvl))
        if b and b['summary'] is not None:
            s = b['summary']
            jump = s.get('adaptation_energy_jump', 0.0)
            text = (f'Adaptive level {lvl}: {s.get("adaptations")} mesh adaptations with a total energy jump '
                    f'(adaptation_energy_jump) of {jump:+.4f}, {100 * jump / s["energy"]:+.2f} % of its final '
                    f'energy')
            st = b['stats']
            if st is not None and 'adaptation_energy_jump' in st and len(st['time']) > 1:
                cum = st['adaptation_energy_jump']
                inc = np.diff(cum)
                idx = np.nonzero(inc)[0]
                if len(idx):
                    big = idx[np.argsort(-np.abs(inc[idx]))][:3]
                    first = cum[st['time'] <= 0.05][-1] if np.any(st['time'] <= 0.05) else 0.0
                    text += (f'; {fmt(first)} of it by t = 0.05 (the initial sharpening of phi); largest single '
                             f'jumps ' + ', '.join(f'{inc[i]:+.3g} at t = {st["time"][i + 1]:.3g}' for i in big))
                    small = 1e-9 * abs(st['energy'][-1])
                    pos, neg = inc[inc > small], inc[inc < -small]
                    late = inc[st['time'][1:] > 0.5].sum()
                    text += (f'; {len(pos)} adaptations raised the energy (sum {pos.sum():+.4g}), {len(neg)} lowered it'
                             f'{f" (sum {neg.sum():+.3g})" if len(neg) else ""}, the others changed it by round-off '
                             f'at most; after t = 0.5 they add {late:+.3g}. For scale: the energy falls by '
                             f'{st["energy"][0] - st["energy"][-1]:.3g} over the run')
            out.append(text + '.')
    return out


def plot(results, sigmas, levels):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    colors = {s: c for s, c in zip(sigmas, ['tab:blue', 'tab:red', 'tab:green', 'tab:purple'])}
    markers = {1: 's', 2: 'D', 3: '^'}
    fig, ax = plt.subplots(figsize=(7, 4.8))
    for s in sigmas:
        us = [r for r in results if r['case'].sigma == s and r['case'].kind == 'uniform' and state(r) == 'ok']
        if us:
            ax.plot([r['summary']['cells'] for r in us], [r['summary']['energy'] for r in us], 'o-', color=colors[s],
                    label=f'sigma = {fmt_sigma(s)}, uniform {"/".join(map(str, UNIFORM))}')
        for r in results:
            c = r['case']
            if c.sigma == s and c.kind == 'adaptive' and state(r) == 'ok':
                ax.plot([r['summary']['cells']], [r['summary']['energy']], markers.get(c.value, 'x'),
                        color=colors[s], markersize=9, markerfacecolor='none', markeredgewidth=1.8,
                        label=f'sigma = {fmt_sigma(s)}, adaptive level {c.value} ({CELLS_PER_XI[c.value]:g}/xi)')
    ax.set_xscale('log')
    ax.set_xlabel('cells at the end of the run')
    ax.set_ylabel('final energy')
    ax.set_title('7.3 budding setup: final energy against mesh size')
    ax.grid(True, which='both', alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(ROOT, FIGURE), dpi=110)
    plt.close(fig)

    fig, axes = plt.subplots(len(sigmas), 3, figsize=(15, 3.8 * len(sigmas)), squeeze=False)
    styles = {('uniform', n): ls for n, ls in zip(UNIFORM, [':', '--', '-.', '-', '-'])}
    for i, s in enumerate(sigmas):
        for r in results:
            c, st = r['case'], r['stats']
            if c.sigma != s or st is None or len(st['time']) < 2:
                continue
            ls = styles.get((c.kind, c.value), '-')
            lw = 1.2 if c.kind == 'uniform' else 1.8
            color = 'k' if c.kind == 'uniform' else {1: 'tab:orange', 2: 'tab:green', 3: 'tab:purple'}[c.value]
            late = st['time'] >= 0.05
            axes[i, 0].plot(st['time'][late], st['energy'][late], ls, color=color, lw=lw, label=c.label)
            axes[i, 1].plot(st['time'], st['domain_protrusion'], ls, color=color, lw=lw, label=c.label)
            cells = st['cells'] if 'cells' in st else np.full_like(st['time'], c.value ** 2)
            axes[i, 2].plot(st['time'], cells, ls, color=color, lw=lw, label=c.label)
        for ax, what in zip(axes[i], ['energy (t >= 0.05)', 'domain_protrusion', 'cells']):
            ax.set_title(f'sigma = {fmt_sigma(s)}: {what}')
            if what == 'cells':
                ax.set_yscale('log')
            ax.set_xlabel('t')
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(ROOT, HISTORY), dpi=90)
    plt.close(fig)


def write_report(results, sigmas, levels, command, end_time, exe):
    t_end = FILE_END_TIME if end_time is None else end_time
    parts = ['# Mesh convergence: uniform meshes against local refinement', '',
             'The 7.3 budding setup ([experiments/7.3-budding.prm](../experiments/7.3-budding.prm)) at line tension '
             + ' and '.join(f'sigma = {fmt_sigma(s)}' for s in sigmas) +
             f', run to t = {t_end:g}, on uniform meshes of {uniform_names(UNIFORM[:-1])} and {UNIFORM[-1]} cells '
             'per side and on the 32 x 32 '
             'input mesh with local refinement (`Mesh/Maximum refinement level` L with `Mesh/Interface cells per xi`'
             ' ' + ', '.join(f'{CELLS_PER_XI[l]:g} for L = {l}' for l in sorted(levels)) +
             '; the other refinement entries at their defaults: adaptation every 10 accepted steps, curvature '
             'resolution 0.3). At its finest level L the adaptive mesh has cells of 1/(32 x 2^L) in the parameter '
             'plane: 1/64 (as uniform 64) for L = 1, 1/128 (as uniform 128) for L = 2, 1/256 for L = 3. The '
             'interface indicator refines cells where phi is sharp (model.md, local refinement). VTU output and '
             'checkpoints are off; one case per core.',
             '', 'Regenerate everything (runs only the cases without a `summary.json`, then rewrites this page and '
             'its figures):', '', '```sh', command, '```', '']
    if end_time is not None and end_time != FILE_END_TIME:
        parts += [f'**Shortened study:** every case, uniform and adaptive, ends at t = {end_time:g} instead of the '
                  f'file\'s {FILE_END_TIME:g}.', '']
    parts += ['Each case runs `membrane-flow --quiet --set "Material/Line tension=SIGMA" --set "Output/Write VTU=false"'
              ' --set "Checkpoint/Interval=0" --set "Output/Directory=results/studies/mesh-convergence/sSIGMA/CASE" '
              '[mesh entries] experiments/7.3-budding.prm` with `OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1`. '
              'Columns: line energy = gradient_energy + well_energy; final cells = `cells` at the end '
              '(the adaptive meshes change every 10 steps); wall time = the run\'s own `wall_seconds`, measured while '
              'two cases shared the machine\'s 2 cores with other work, so it is indicative only (the CPU time of '
              'each case is listed further down); the last column is the final energy relative to the uniform '
              f'{UNIFORM[-1]} run of the same sigma.', '']
    for s in sigmas:
        parts += [f'## sigma = {fmt_sigma(s)}', '', table(results, s), '']
        parts += ['Findings (computed from the table):', '']
        parts += [f'- {t}' for t in conclusions(results, s, levels)]
        parts += ['']
    parts += budded_state_section()
    parts += [f'![final energy against cells]({os.path.relpath(FIGURE, "docs")})', '',
              'Final energy against the number of cells at the end of the run (log scale). Lines: uniform '
              f'{uniform_names(UNIFORM)}; '
              'open markers: adaptive runs.', '',
              f'![energy and cells against time]({os.path.relpath(HISTORY, "docs")})', '',
              'Energy (from t = 0.05, after the initial sharpening of phi), domain_protrusion and number of '
              'cells against time for every case.', '']
    # costs
    parts += ['## Cost', '', '| sigma | mesh | exit code | wall (s, own clock) | CPU (s) | peak memory (MB) | '
              'adaptations | adaptation energy jump |', '|---|---|---|---|---|---|---|---|']
    total_cpu = 0.0
    for r in results:
        c, s, st = r['case'], r['summary'], r['status']
        cpu = st.get('cpu_seconds') if st else None
        total_cpu += cpu or 0.0
        parts.append(f'| {fmt_sigma(c.sigma)} | {c.label} | {st.get("exit_code") if st else "–"} '
                     f'| {fmt(s["wall_seconds"], 4) if s else (fmt(st["wall_seconds"], 4) if st else "–")} '
                     f'| {fmt(cpu, 4)} | {fmt(st["max_rss_kb"] / 1024, 4) if st else "–"} '
                     f'| {s.get("adaptations", 0) if s else "–"} '
                     f'| {fmt(s.get("adaptation_energy_jump"), 4) if s else "–"} |')
    parts += ['', f'Total CPU time of the {sum(1 for r in results if r["status"])} cases: {total_cpu:.0f} s '
              f'({total_cpu / 3600:.2f} h).', '']
    # warnings
    warn = [(r['case'], w) for r in results for w in r['warnings']]
    parts += ['## Messages from the runs', '']
    if warn:
        parts += ['Lines of the runs\' logs that mention a warning, error or failure:', '']
        parts += [f'- s{fmt_sigma(c.sigma)} {c.name}: `{w}`' for c, w in warn[:40]]
        if len(warn) > 40:
            parts.append(f'- ... and {len(warn) - 40} more')
    else:
        parts.append('No run printed a warning or error (the logs hold only the start-up and final lines).')
    parts += ['', f'Binary: `{exe}`; code version of the runs: ' +
              ', '.join(sorted({r['summary'].get('code_version', '?') for r in results if r['summary']})) + '.', '']
    with open(os.path.join(ROOT, DOC) + '.tmp', 'w') as f:
        f.write('\n'.join(parts))
    os.replace(os.path.join(ROOT, DOC) + '.tmp', os.path.join(ROOT, DOC))


# ----------------------------------------------------------------------------------------------

def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--workers', type=int, default=2, help='cases run at the same time (default 2)')
    parser.add_argument('--exe', help='the program (default: see membrane_flow.launch.find_executable)')
    parser.add_argument('--levels', default='1,2', help='adaptive refinement levels, from 1,2,3 (default 1,2)')
    parser.add_argument('--sigmas', default='630,1000', help='line tensions (default 630,1000)')
    parser.add_argument('--uniform', default='32,48,64',
                        help='cells per side of the uniform meshes, at least three, ascending (default 32,48,64; '
                             '128 adds the uniform mesh as fine as level 2 everywhere)')
    parser.add_argument('--end-time', type=float, default=None,
                        help=f'End time of every case (default: the file\'s {FILE_END_TIME:g})')
    parser.add_argument('--output', default=DEFAULT_OUTPUT, help=f'run directory (default {DEFAULT_OUTPUT})')
    parser.add_argument('--timeout', type=float, default=7200,
                        help='wall seconds after which a case is killed and reported as timed out (0: none; '
                             'default 7200)')
    parser.add_argument('--report-only', action='store_true', help='run nothing; rewrite the report from what exists')
    args = parser.parse_args(argv)
    levels = sorted({int(x) for x in args.levels.split(',') if x.strip()})
    if any(l not in CELLS_PER_XI for l in levels):
        parser.error('--levels takes levels from 1, 2, 3')
    sigmas = [float(x) for x in args.sigmas.split(',')]
    global UNIFORM
    UNIFORM = sorted({int(x) for x in args.uniform.split(',') if x.strip()})
    if len(UNIFORM) < 3 or UNIFORM[0] < 2:
        parser.error('--uniform takes at least three mesh sizes, e.g. 32,48,64')
    if args.workers < 1:
        parser.error('--workers must be at least 1')
    exe = os.path.abspath(launch.find_executable(args.exe))
    output = args.output if os.path.isabs(args.output) else os.path.relpath(os.path.join(ROOT, args.output), ROOT)
    if args.end_time is not None and args.end_time != FILE_END_TIME and args.output == DEFAULT_OUTPUT:
        output = os.path.join(DEFAULT_OUTPUT, f'end-{args.end_time:g}')
    cases = make_cases(sigmas, levels, output)

    command = '/usr/bin/python3 -m membrane_flow mesh-convergence'
    if args.workers != 2:
        command += f' --workers {args.workers}'
    # the page names the command a user runs (the default executable), whichever binary made the numbers
    command += f' --levels {",".join(map(str, levels))}'
    if args.uniform != parser.get_default('uniform'):
        command += f' --uniform {",".join(map(str, UNIFORM))}'
    if args.sigmas != parser.get_default('sigmas'):
        command += f' --sigmas {args.sigmas}'
    if args.end_time is not None:
        command += f' --end-time {args.end_time:g}'
    if args.output != DEFAULT_OUTPUT:
        command += f' --output {args.output}'
    completed = True
    if not args.report_only:
        if not os.access(exe, os.X_OK):
            print(f'membrane_flow mesh-convergence: error: {exe} is not an executable', file=sys.stderr)
            return 1
        completed = run_cases(cases, Runner(exe, args.end_time, args.timeout), args.workers)
    results = [read_case(c) for c in cases]
    plot(results, sigmas, levels)
    write_report(results, sigmas, levels, command, args.end_time, exe)
    print(f'wrote {DOC}, {FIGURE}, {HISTORY}')
    if not completed:
        return 130
    return 2 if any(state(r) != 'ok' for r in results) else 0


if __name__ == '__main__':
    sys.exit(main())
