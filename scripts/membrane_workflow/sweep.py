"""Parameter sweeps: many runs of membrane-flow into one results table.

A sweep file (JSON) names a base input file and the parameters to vary:

    {
      "base": "experiments/7.3-budding.prm",      # relative to the sweep file
      "output": "sweeps/sigma",                   # relative to the sweep file
      "set": {"Time stepping/End time": 1.0},     # fixed overrides for every case
      "vary": {                                   # the Cartesian product of these
        "Material/Line tension": [540, 630, 1000],
        "Initial phase/Seed": {"range": [1, 3]},              # 1, 2, 3
        "Material/Bending rigidity/Phase A value": {"linspace": [1, 2, 3]},
        "Material/Line tension ": {"logspace": [100, 1000, 4]}
      }
    }

Each case runs in <output>/cases/<id>, where <id> is derived from all its parameter values
(the fixed "set" ones included), so a case is the same directory in every run of the sweep,
and changing a fixed value never reuses a stale case. A case is finished when
its summary.json exists; its case.json records the values. Started again, a sweep skips
finished cases and reruns (from scratch) cases that were interrupted. results.csv is rebuilt
from the finished case directories after every case, written atomically, so it never holds
a case twice and never a half-written row.

Cases run in parallel as local processes (`workers`); with `ranks > 1` each case runs under
`mpirun -np ranks` (add e.g. `--hostfile` through `launcher` to spread cases across machines).
"""
import csv
import hashlib
import io
import itertools
import json
import os
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor, as_completed

import numpy as np

from .budding_time import budding_time_of_run
from .statistics import load_summary

SUMMARY_COLUMNS = ['outcome', 'stop_reason', 'failed', 'time', 'steps', 'rejected_steps', 'energy', 'bud_height',
                   'neck_radius', 'neck_ratio', 'domain_area', 'domain_protrusion', 'bud_direction', 'area_drift',
                   'mass_drift', 'wall_seconds']


def expand_values(spec, name):
    if isinstance(spec, list):
        return spec
    if isinstance(spec, dict):
        if 'range' in spec:
            lo, hi = spec['range'][:2]
            step = spec['range'][2] if len(spec['range']) > 2 else 1
            return list(range(int(lo), int(hi) + 1, int(step)))
        if 'linspace' in spec:
            lo, hi, n = spec['linspace']
            return [float(v) for v in np.linspace(lo, hi, int(n))]
        if 'logspace' in spec:
            lo, hi, n = spec['logspace']
            return [float(v) for v in np.geomspace(lo, hi, int(n))]
    raise ValueError(f"sweep parameter <{name}>: give a list, or {{'range': [lo, hi(, step)]}}, "
                     f"{{'linspace': [lo, hi, n]}} or {{'logspace': [lo, hi, n]}}")


def case_id(values):
    """Stable id of a case from its parameter values (order-independent)."""
    text = json.dumps({k: values[k] for k in sorted(values)}, sort_keys=True)
    return hashlib.sha1(text.encode()).hexdigest()[:12]


def write_atomically(path, text):
    tmp = path + '.tmp'
    with open(tmp, 'w') as f:
        f.write(text)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


class Sweep:
    def __init__(self, base, output, fixed=None, exe='build/membrane-flow', workers=1, ranks=1, launcher='mpirun',
                 extra_args=()):
        self.base, self.output = base, output
        self.fixed = dict(fixed or {})
        self.exe, self.workers, self.ranks, self.launcher = exe, workers, ranks, launcher
        self.extra_args = list(extra_args)
        os.makedirs(os.path.join(output, 'cases'), exist_ok=True)

    @classmethod
    def from_file(cls, path, **kwargs):
        with open(path) as f:
            spec = json.load(f)
        root = os.path.dirname(os.path.abspath(path))
        for key in ('base', 'output'):
            if key not in spec:
                raise ValueError(f"sweep file {path}: missing entry <{key}>")
        sweep = cls(os.path.join(root, spec['base']), os.path.join(root, spec['output']), spec.get('set'), **kwargs)
        names = list(spec.get('vary', {}))
        grids = [expand_values(spec['vary'][n], n) for n in names]
        cases = [dict(zip([n.strip() for n in names], combo)) for combo in itertools.product(*grids)]
        return sweep, cases

    def case_dir(self, values):
        return os.path.join(self.output, 'cases', case_id({**self.fixed, **values}))

    def is_finished(self, values):
        return os.path.exists(os.path.join(self.case_dir(values), 'summary.json'))

    def command(self, values, directory):
        args = [self.exe, '--quiet']
        for name, value in list(self.fixed.items()) + list(values.items()):
            args += ['--set', f'{name}={value}']
        args += ['--set', f'Output/Directory={directory}'] + self.extra_args + [self.base]
        if self.ranks > 1:
            args = self.launcher.split() + ['-np', str(self.ranks)] + args
        return args

    def run_case(self, values):
        directory = self.case_dir(values)
        if self.is_finished(values):
            return values, 'skipped'
        shutil.rmtree(directory, ignore_errors=True)  # an interrupted attempt starts over
        os.makedirs(directory)
        write_atomically(os.path.join(directory, 'case.json'),
                         json.dumps({'vary': values, 'set': self.fixed}, indent=1) + '\n')
        with open(os.path.join(directory, 'log.txt'), 'w') as log:
            result = subprocess.run(self.command(values, directory), stdout=log, stderr=subprocess.STDOUT)
        if not self.is_finished(values):
            return values, f'no summary (exit code {result.returncode}; see {directory}/log.txt)'
        return values, 'finished'

    def run(self, cases, progress=print):
        todo = [c for c in cases if not self.is_finished(c)]
        progress(f'{len(cases)} cases, {len(cases) - len(todo)} already finished, {len(todo)} to run '
                 f'({self.workers} at a time)')
        with ThreadPoolExecutor(max_workers=self.workers) as pool:
            futures = [pool.submit(self.run_case, c) for c in todo]
            for future in as_completed(futures):
                values, status = future.result()
                progress(f'{os.path.basename(self.case_dir(values))} {values}: {status}')
                self.write_table()
        return self.write_table()

    def rows(self):
        rows = []
        cases_dir = os.path.join(self.output, 'cases')
        for name in sorted(os.listdir(cases_dir)):
            directory = os.path.join(cases_dir, name)
            if not os.path.exists(os.path.join(directory, 'summary.json')):
                continue
            with open(os.path.join(directory, 'case.json')) as f:
                values = json.load(f)['vary']
            summary = load_summary(directory)
            row = {'case': name, **values}
            row.update({c: summary.get(c) for c in SUMMARY_COLUMNS})
            row['T_min'] = budding_time_of_run(directory)
            rows.append(row)
        return rows

    def write_table(self):
        rows = self.rows()
        columns = ['case']
        for row in rows:
            columns += [c for c in row if c not in columns]
        text = io.StringIO()
        writer = csv.DictWriter(text, fieldnames=columns)
        writer.writeheader()
        for row in rows:
            writer.writerow({c: ('' if row.get(c) is None else row.get(c)) for c in columns})
        write_atomically(os.path.join(self.output, 'results.csv'), text.getvalue())
        return rows
