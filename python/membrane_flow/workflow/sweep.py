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
        "Material/Spontaneous curvature/Phase A value": {"logspace": [1, 10, 4]}
      }
    }

Optional free-text keys: "description", "comment". Entry names are normalized (each
`/`-separated part stripped, inner runs of whitespace made one space, as deal.II reads
them); two names that become equal, or one entry both in "set" and "vary", are an error.
Before any case runs, every name is checked against `<exe> --print-parameters`: an unknown
name stops the sweep with the closest valid names. JSON booleans are passed as true/false.

Each case runs in <output>/cases/<id>, where <id> is derived from all its parameter values
(the fixed "set" ones included), so a case is the same directory in every run of the sweep.
A case is finished when its summary.json exists; its case.json records the values and the
command, status.json the simulator's exit code. Started again, a sweep skips finished cases
and reruns (from scratch) cases that were interrupted or ended without a summary.

The sweep definition (normalized: base file content hash, "set", expanded "vary") is
recorded in <output>/sweep.json at the first run. A later run with a different definition
refuses to touch the directory (SweepError) unless `overwrite` is given, which deletes the
old cases first. results.csv holds only cases of the current definition: one row per case
that finished or failed, with the "vary" and "set" values as columns named by entry path.
A failed case (exit code != 0, or "failed": true in its summary) has outcome "failed" and
keeps the simulator's stop reason. The table is rebuilt after every case, written atomically.

Cases run in parallel as local processes (`workers`); with `ranks > 1` each case runs under
`mpirun -np ranks` (add e.g. `--hostfile` through `launcher` to spread cases across machines).
With several workers or ranks, OMP_NUM_THREADS and OPENBLAS_NUM_THREADS are 1 in each case's
environment unless already set. Each case is its own process group; after
`install_signal_handlers()`, SIGINT/SIGTERM terminate the running cases' groups (SIGKILL after
a grace period or a second signal), no further case starts, and `stopping` holds the signal.
A case's simulator also gets SIGTERM if the sweep process dies (Linux parent-death signal).
"""
import argparse
import csv
import difflib
import hashlib
import io
import itertools
import json
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import threading
from concurrent.futures import ThreadPoolExecutor, as_completed

import numpy as np

from .. import launch
from ..run import FileError, load_summary, read_json
from .budding_time import budding_time_of_run

SUMMARY_COLUMNS = ['outcome', 'stop_reason', 'failed', 'time', 'steps', 'rejected_steps', 'energy', 'bud_height',
                   'neck_radius', 'neck_ratio', 'domain_area', 'domain_protrusion', 'bud_direction', 'area_drift',
                   'mass_drift', 'wall_seconds']
FAILED = 'failed'                      # the outcome column of a failed case
CONTROLLED = ('Output/Directory',)     # set by the sweep for each case
THREAD_VARIABLES = launch.THREAD_VARIABLES
SPEC_KEYS = ('base', 'output', 'set', 'vary', 'description', 'comment')
KILL_GRACE_SECONDS = 10.0


class SweepError(ValueError):
    """A problem with a sweep's definition, names or output directory (reported in a line, exit 1)."""


def normalize_name(name):
    """'Material/ Line  tension ' -> 'Material/Line tension' (deal.II trims each part)."""
    parts = [' '.join(part.split()) for part in str(name).split('/')]
    if any(not part for part in parts):
        raise SweepError(f"entry name {name!r}: empty section or entry name (write 'Section/Entry')")
    return '/'.join(parts)


def normalize_entries(entries, where):
    """Names normalized; an error if two given names become the same entry."""
    if not isinstance(entries, dict):
        raise SweepError(f'"{where}" must be an object {{"Section/Entry": value, ...}}')
    result, raw = {}, {}
    for name, value in entries.items():
        key = normalize_name(name)
        if key in result:
            raise SweepError(f'"{where}" names the entry {key!r} twice: {raw[key]!r} and {name!r} differ only in '
                             f'whitespace')
        result[key], raw[key] = value, name
    return result


def check_value(value, name):
    if isinstance(value, bool) or isinstance(value, str) or isinstance(value, int):
        return value
    if isinstance(value, float):
        if not math.isfinite(value):
            raise SweepError(f'{name}: the value {value} is not finite')
        return value
    raise SweepError(f'{name}: the value {json.dumps(value)} is not a number, string or boolean')


def format_value(value):
    """A value as the simulator's ParameterHandler reads it: JSON true/false -> 'true'/'false'."""
    if isinstance(value, bool):
        return 'true' if value else 'false'
    return str(value)


def expand_values(spec, name):
    try:
        if isinstance(spec, list):
            values = spec
        elif isinstance(spec, dict) and len(spec) == 1 and 'range' in spec:
            lo, hi = spec['range'][:2]
            step = spec['range'][2] if len(spec['range']) > 2 else 1
            values = list(range(int(lo), int(hi) + 1, int(step)))
        elif isinstance(spec, dict) and len(spec) == 1 and 'linspace' in spec:
            lo, hi, n = spec['linspace']
            values = [float(v) for v in np.linspace(lo, hi, int(n))]
        elif isinstance(spec, dict) and len(spec) == 1 and 'logspace' in spec:
            lo, hi, n = spec['logspace']
            if not (lo > 0 and hi > 0):
                raise ValueError
            values = [float(v) for v in np.geomspace(lo, hi, int(n))]
        else:
            raise ValueError
    except (ValueError, TypeError, IndexError):
        raise SweepError(f'"vary" entry {name!r}: give a list of values, or {{"range": [lo, hi(, step)]}}, '
                         f'{{"linspace": [lo, hi, n]}} or {{"logspace": [lo, hi, n]}} (lo, hi > 0); got '
                         f'{json.dumps(spec)}') from None
    if not values:
        raise SweepError(f'"vary" entry {name!r}: no values')
    return [check_value(v, f'"vary" entry {name!r}') for v in values]


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


def read_json_file(path, what='file'):
    """A JSON file, or SweepError with the file, line and column of a syntax error."""
    try:
        return read_json(path, what)
    except FileError as e:
        raise SweepError(str(e)) from None


def declared_entries(exe):
    """Every 'Section/Sub/Entry' path the simulator declares (from `exe --print-parameters`)."""
    try:
        result = launch.output([exe, '--print-parameters'], timeout=120)
    except OSError as e:
        raise SweepError(f'cannot run the simulator {exe}: {e.strerror}') from None
    except subprocess.TimeoutExpired:
        raise SweepError(f'{exe} --print-parameters did not finish in 120 s') from None
    if result.returncode != 0:
        last = (result.stderr.strip().splitlines() or [''])[-1]
        raise SweepError(f'{exe} --print-parameters failed (exit code {result.returncode}): {last}')
    entries, sections = [], []
    for line in result.stdout.splitlines():
        line = line.strip()
        if not line or line.startswith('#'):
            continue
        if m := re.match(r'subsection\s+(.*?)\s*$', line):
            sections.append(' '.join(m.group(1).split()))
        elif re.match(r'end\s*$', line):
            if sections:
                sections.pop()
        elif m := re.match(r'set\s+(.*?)\s*=', line):
            entries.append('/'.join(sections + [' '.join(m.group(1).split())]))
    if not entries:
        raise SweepError(f'{exe} --print-parameters printed no entries: is it membrane-flow?')
    return entries


def check_entry_names(names, declared, exe):
    """names: [(entry path, where it was given)]. SweepError naming every unknown entry."""
    declared_set = set(declared)
    problems = []
    for name, where in names:
        if name in CONTROLLED:
            problems.append(f'{where}: {name!r} is set by the sweep for each case (<output>/cases/<id>); remove it')
        elif name not in declared_set:
            close = difflib.get_close_matches(name, declared, n=3, cutoff=0.6)
            if not close:  # a misspelled section: compare the entry name alone
                last = name.rsplit('/', 1)[-1]
                close = [d for d in declared if d.rsplit('/', 1)[-1] in
                         difflib.get_close_matches(last, [e.rsplit('/', 1)[-1] for e in declared], n=3, cutoff=0.6)][:3]
            hint = ('closest valid names: ' + ', '.join(repr(c) for c in close)) if close else 'no similar entry'
            problems.append(f'{where}: unknown entry {name!r}; {hint} (every entry: {exe} --print-parameters)')
    if problems:
        raise SweepError('\n'.join(problems))


def describe_values(values):
    return ', '.join(f'{name}={format_value(value)}' for name, value in values.items()) or '(no varied entry)'


def describe_exit(code):
    if code is None:
        return 'no exit code recorded'
    if code < 0:
        try:
            return f'killed by signal {signal.Signals(-code).name}'
        except ValueError:
            return f'killed by signal {-code}'
    return f'exit code {code}'


class Sweep:
    def __init__(self, base, output, fixed=None, exe=None, workers=1, ranks=1, launcher='mpirun',
                 extra_args=(), vary=None, cases=None, source='sweep'):
        """fixed: {'Section/Entry': value} for every case; vary: {'Section/Entry': [values]} of a sweep, or
        {'Section/Entry': 'bisection'} for values chosen as the cases run (cases=None)."""
        self.base, self.output = base, output
        self.source = source
        self.fixed = {k: check_value(v, f'"set" entry {k!r}') for k, v in normalize_entries(fixed or {}, 'set').items()}
        self.vary = normalize_entries(vary or {}, 'vary')
        both = sorted(set(self.fixed) & set(self.vary))
        if both:
            raise SweepError(f'the entry {both[0]!r} is both in "set" and in "vary"')
        self.cases = cases
        self.exe, self.workers, self.ranks, self.launcher = launch.find_executable(exe), workers, ranks, launcher
        self.extra_args = list(extra_args)
        self.stopping = None  # the signal that stops the sweep
        self._running = set()
        self._lock = threading.Lock()

    @classmethod
    def from_file(cls, path, **kwargs):
        spec = read_json_file(path, 'sweep file')
        if not isinstance(spec, dict):
            raise SweepError(f'{path}: a sweep file is a JSON object with "base", "output", "set" and "vary"')
        for key in spec:
            if key not in SPEC_KEYS:
                close = difflib.get_close_matches(key, SPEC_KEYS, n=1)
                raise SweepError(f'{path}: unknown key {key!r}' + (f' (did you mean {close[0]!r}?)' if close else '') +
                                 f'; a sweep file has {", ".join(SPEC_KEYS)}')
        for key in ('base', 'output'):
            if not isinstance(spec.get(key), str) or not spec[key]:
                raise SweepError(f'{path}: missing entry "{key}" (a path relative to the sweep file)')
        root = os.path.dirname(os.path.abspath(path))
        base = os.path.normpath(os.path.join(root, spec['base']))
        if not os.path.isfile(base):
            raise SweepError(f'{path}: the base input file {base} does not exist')
        try:
            vary = normalize_entries(spec.get('vary', {}), 'vary')
            grids = {name: expand_values(values, name) for name, values in vary.items()}
            cases = [dict(zip(grids, combo)) for combo in itertools.product(*grids.values())]
            sweep = cls(base, os.path.normpath(os.path.join(root, spec['output'])), spec.get('set'), vary=grids,
                        cases=cases,
                        source=path, **kwargs)
        except SweepError as e:
            raise SweepError(f'{path}: {e}') from None
        return sweep, cases

    # -- definition and output directory ------------------------------------------------------

    def definition(self):
        with open(self.base, 'rb') as f:
            digest = hashlib.sha1(f.read()).hexdigest()
        return {'base': os.path.abspath(self.base), 'base_sha1': digest, 'set': self.fixed, 'vary': self.vary}

    def check_names(self, declared=None):
        """Every entry name against the simulator's declared entries (runs `exe --print-parameters`)."""
        declared = declared_entries(self.exe) if declared is None else declared
        check_entry_names([(n, f'"set" of {self.source}') for n in self.fixed] +
                          [(n, f'"vary" of {self.source}') for n in self.vary], declared, self.exe)

    @staticmethod
    def differences(old, new):
        changes = []
        if old.get('base_sha1') != new['base_sha1']:
            changes.append(f'base file {old.get("base")} -> {new["base"]} (content differs)'
                           if old.get('base') != new['base'] else f'the content of the base file {new["base"]}')
        for key in ('set', 'vary'):
            a, b = old.get(key) or {}, new[key]
            for name in sorted(set(a) | set(b)):
                if name not in b:
                    changes.append(f'"{key}" no longer has {name!r}')
                elif name not in a:
                    changes.append(f'"{key}" now has {name!r}')
                elif a[name] != b[name]:
                    changes.append(f'"{key}" {name!r}: {json.dumps(a[name])} -> {json.dumps(b[name])}')
        return changes

    def prepare(self, overwrite=False, dry_run=False):
        """Check the output directory against the recorded definition; record it (sweep.json).
        A different recorded definition is a SweepError unless overwrite (then old cases are deleted)."""
        record = os.path.join(self.output, 'sweep.json')
        current = self.definition()
        cases_dir = os.path.join(self.output, 'cases')
        old_cases = sorted(os.listdir(cases_dir)) if os.path.isdir(cases_dir) else []
        if os.path.exists(record):
            try:
                old = read_json_file(record, 'sweep record')
                changes = self.differences(old, current) if isinstance(old, dict) else ['unreadable record']
            except SweepError as e:
                changes = [str(e)]
            if changes:
                if not overwrite:
                    shown = '; '.join(changes[:4]) + (f'; and {len(changes) - 4} more' if len(changes) > 4 else '')
                    raise SweepError(f'{self.output} holds the results of a different sweep ({shown}). Rerun with '
                                     f'--overwrite to delete its {len(old_cases)} cases and start over, or choose '
                                     f'another output directory')
                if not dry_run:
                    self.clear()
        elif overwrite and old_cases and not dry_run:
            self.clear()  # cases of unknown definition (made before sweep.json existed)
        if not dry_run:
            os.makedirs(cases_dir, exist_ok=True)
            write_atomically(record, json.dumps(current, indent=1, sort_keys=True) + '\n')

    def clear(self):
        shutil.rmtree(os.path.join(self.output, 'cases'), ignore_errors=True)
        for name in ('results.csv', 'bisection.json', 'sweep.json'):
            if os.path.exists(os.path.join(self.output, name)):
                os.remove(os.path.join(self.output, name))

    # -- cases --------------------------------------------------------------------------------

    def case_dir(self, values):
        return os.path.join(self.output, 'cases', case_id({**self.fixed, **values}))

    def is_finished(self, values):
        return os.path.exists(os.path.join(self.case_dir(values), 'summary.json'))

    def command(self, values, directory):
        args = [self.exe, '--quiet']
        for name, value in list(self.fixed.items()) + list(values.items()):
            args += ['--set', f'{name}={format_value(value)}']
        args += ['--set', f'Output/Directory={directory}'] + self.extra_args + [self.base]
        return launch.command(args[0], args[1:], self.ranks, self.launcher)

    def environment(self):
        # one thread per process when cases or ranks share the cores (a value already set is kept)
        return launch.environment(threads=self.workers > 1 or self.ranks > 1, force=False, mpi=self.ranks > 1)

    def run_case(self, values):
        """Run one case unless finished. Returns (values, status): 'skipped', 'finished', 'failed (...)',
        'not started' or 'interrupted' (the last two only after a stop signal)."""
        directory = self.case_dir(values)
        if self.is_finished(values):
            return values, 'skipped'
        if self.stopping is not None:
            return values, 'not started'
        shutil.rmtree(directory, ignore_errors=True)  # an interrupted attempt starts over
        os.makedirs(directory)
        command = self.command(values, directory)
        write_atomically(os.path.join(directory, 'case.json'),
                         json.dumps({'vary': values, 'set': self.fixed, 'command': command}, indent=1) + '\n')
        with open(os.path.join(directory, 'log.txt'), 'w') as log:
            try:
                process = launch.start(command, stdout=log, stderr=subprocess.STDOUT, env=self.environment())
            except OSError as e:
                log.write(f'cannot start {command[0]}: {e.strerror}\n')
                process = None
            if process is not None:
                with self._lock:
                    self._running.add(process)
                if self.stopping is not None:  # the signal came while it started
                    self._kill(process, signal.SIGTERM)
                code = process.wait()
                with self._lock:
                    self._running.discard(process)
            else:
                code = 127
        if self.stopping is not None and code != 0:
            self._kill(process, signal.SIGKILL)  # anything left in its group
            summary = os.path.join(directory, 'summary.json')
            if os.path.exists(summary):
                os.remove(summary)  # cut short: run it again next time
            return values, 'interrupted'
        write_atomically(os.path.join(directory, 'status.json'), json.dumps({'exit_code': code}) + '\n')
        row = self.row(directory, values)
        if row is None or row['outcome'] == FAILED:
            return values, f'failed ({row["stop_reason"] if row else describe_exit(code)}; see {directory}/log.txt)'
        return values, 'finished'

    def run(self, cases=None, progress=print):
        cases = self.cases if cases is None else cases
        todo = [c for c in cases if not self.is_finished(c)]
        progress(f'{len(cases)} cases, {len(cases) - len(todo)} already finished, {len(todo)} to run '
                 f'({self.workers} at a time)')
        with ThreadPoolExecutor(max_workers=max(1, self.workers)) as pool:
            futures = [pool.submit(self.run_case, c) for c in todo]
            for future in as_completed(futures):
                values, status = future.result()
                if status != 'not started':
                    progress(f'{os.path.basename(self.case_dir(values))} {describe_values(values)}: {status}')
                    self.write_table()
        return self.write_table()

    # -- signals --------------------------------------------------------------------------------

    def install_signal_handlers(self):
        for sig in (signal.SIGINT, signal.SIGTERM):
            signal.signal(sig, self._on_signal)

    def _on_signal(self, signum, frame):
        first = self.stopping is None
        if first:
            self.stopping = signum
        running = list(self._running)
        for process in running:
            self._kill(process, signal.SIGTERM if first else signal.SIGKILL)
        if first:
            # os.write, not print: the main thread may be inside a print when the signal comes.
            os.write(2, f'{signal.Signals(signum).name}: stopping the sweep: terminating {len(running)} running '
                        f'case(s), no new case starts\n'.encode())
            timer = threading.Timer(KILL_GRACE_SECONDS, self._kill_all, (signal.SIGKILL,))
            timer.daemon = True
            timer.start()

    def _kill_all(self, sig):
        for process in list(self._running):
            self._kill(process, sig)

    @staticmethod
    def _kill(process, sig):
        launch.kill_group(process, sig)  # the case's own process group: the simulator, mpirun and its ranks

    # -- results --------------------------------------------------------------------------------

    def row(self, directory, values):
        """The results row of a case directory; None if it has not ended (never run, or interrupted)."""
        status_path = os.path.join(directory, 'status.json')
        code = None
        if os.path.exists(status_path):
            try:
                code = read_json_file(status_path, 'case status').get('exit_code')
            except (SweepError, AttributeError):
                code = None
        summary, problem = None, None
        if os.path.exists(os.path.join(directory, 'summary.json')):
            try:
                summary = load_summary(directory)
                if not isinstance(summary, dict):
                    raise ValueError('not a JSON object')
            except (OSError, ValueError) as e:
                summary, problem = None, f'unreadable summary.json ({e})'
        elif code is None or code == 0:
            if code is None:
                return None
            problem = 'no summary.json'
        row = {'case': os.path.basename(directory)}
        row.update({name: format_value(values[name]) for name in self.vary if name in values})
        row.update({name: format_value(value) for name, value in self.fixed.items()})
        row.update({c: (summary or {}).get(c) for c in SUMMARY_COLUMNS})
        row['exit_code'] = code
        failed = summary is None or bool(summary.get('failed')) or code not in (None, 0)
        row['T_min'] = None
        if failed:
            row['outcome'], row['failed'] = FAILED, True
            if summary is None:
                row['stop_reason'] = f'{describe_exit(code)}: {problem or self._last_log_line(directory)}'
        else:
            try:
                row['T_min'] = budding_time_of_run(directory)
            except (OSError, ValueError, IndexError, KeyError):
                row['T_min'] = None
        return row

    @staticmethod
    def _last_log_line(directory):
        try:
            with open(os.path.join(directory, 'log.txt'), errors='replace') as f:
                lines = [line.strip() for line in f if line.strip()]
        except OSError:
            lines = []
        return lines[-1][:300] if lines else 'no output in log.txt'

    def case_values(self, directory):
        try:
            values = read_json_file(os.path.join(directory, 'case.json'), 'case record')['vary']
        except (SweepError, KeyError, TypeError):
            return None
        return values if isinstance(values, dict) else None

    def rows(self):
        """Rows of the cases of the current definition only (never a stale case of an older one)."""
        rows = []
        if self.cases is not None:
            for values in self.cases:
                row = self.row(self.case_dir(values), values)
                if row is not None:
                    rows.append(row)
            return rows
        cases_dir = os.path.join(self.output, 'cases')
        keyed = []
        for name in sorted(os.listdir(cases_dir)) if os.path.isdir(cases_dir) else []:
            directory = os.path.join(cases_dir, name)
            values = self.case_values(directory)
            if values is None or set(values) != set(self.vary) or case_id({**self.fixed, **values}) != name:
                continue
            row = self.row(directory, values)
            if row is not None:
                keyed.append(([json.dumps(values[n]) if not isinstance(values[n], (int, float)) else values[n]
                               for n in self.vary], row))
        try:
            keyed.sort(key=lambda k: k[0])
        except TypeError:
            pass
        return [row for _, row in keyed]

    def columns(self):
        return ['case'] + list(self.vary) + list(self.fixed) + SUMMARY_COLUMNS + ['exit_code', 'T_min']

    def write_table(self):
        rows = self.rows()
        columns = self.columns()
        text = io.StringIO()
        writer = csv.DictWriter(text, fieldnames=columns, extrasaction='ignore')
        writer.writeheader()
        for row in rows:
            writer.writerow({c: ('' if row.get(c) is None else row.get(c)) for c in columns})
        os.makedirs(self.output, exist_ok=True)
        write_atomically(os.path.join(self.output, 'results.csv'), text.getvalue())
        return rows


# -- the command line: python3 -m membrane_flow sweep ------------------------------------------

COMMAND_HELP = """Run a parameter sweep of membrane-flow (see membrane_flow/workflow/sweep.py for the
sweep-file format). Results: <output>/results.csv plus each case's own run directory.
A killed sweep started again skips its finished cases.

Before any case runs, every entry name is checked against `membrane-flow --print-parameters`,
and the output directory against the sweep recorded in <output>/sweep.json: a directory of a
different sweep is refused unless --overwrite (which deletes its old cases).

Exit codes: 0 every case finished; 1 bad sweep file, entry name or output directory (nothing
run); 2 some case failed (results.csv is written; failed cases have outcome "failed");
130 / 143 stopped by SIGINT / SIGTERM (running cases are terminated, results.csv is written).

Usage: python3 -m membrane_flow sweep <sweep.json> [--workers N] [--ranks R] [--launcher 'mpirun --hostfile h'] [--exe PATH]
                                      [--overwrite] [--dry-run]
Example: python3 -m membrane_flow sweep experiments/sweeps/sigma.json --workers 2"""

NAME = 'membrane_flow sweep'


def _main(argv):
    parser = argparse.ArgumentParser(description=COMMAND_HELP, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('sweep_file')
    parser.add_argument('--workers', type=int, default=1,
                        help='cases run at the same time (with N > 1 each case gets OMP_NUM_THREADS=1 and '
                             'OPENBLAS_NUM_THREADS=1 unless set)')
    parser.add_argument('--ranks', type=int, default=1, help='MPI ranks per case (mpirun -np R)')
    parser.add_argument('--launcher', default='mpirun', help='MPI launcher command for --ranks > 1')
    parser.add_argument('--exe', help='the program (default: see membrane_flow.launch.find_executable)')
    parser.add_argument('--overwrite', action='store_true',
                        help='the output directory holds a different sweep: delete its cases and start over')
    parser.add_argument('--dry-run', action='store_true',
                        help='check the sweep file, entry names and output directory, list the cases, run nothing')
    args = parser.parse_args(argv)
    if args.workers < 1 or args.ranks < 1:
        parser.error('--workers and --ranks must be at least 1')
    try:
        sweep, cases = Sweep.from_file(args.sweep_file, exe=args.exe, workers=args.workers, ranks=args.ranks,
                                       launcher=args.launcher)
        sweep.check_names()
        sweep.prepare(overwrite=args.overwrite, dry_run=args.dry_run)
    except SweepError as e:
        print(f'{NAME}: error: {e}', file=sys.stderr)
        return 1
    if args.dry_run:
        for values in cases:
            print(f'{os.path.basename(sweep.case_dir(values))} {describe_values(values)}'
                  f'{" (finished)" if sweep.is_finished(values) else ""}')
        print(f'{len(cases)} cases; output {sweep.output}')
        return 0
    sweep.install_signal_handlers()
    rows = sweep.run(cases, progress=lambda text: print(text, flush=True))
    table = os.path.join(sweep.output, 'results.csv')
    failed = [r for r in rows if r['outcome'] == FAILED]
    print(f'{len(rows)} of {len(cases)} cases in {table}', flush=True)
    if failed:
        print(f'{NAME}: {len(failed)} of {len(rows)} cases failed: ' +
              '; '.join(f'{r["case"]} ({r["stop_reason"]})' for r in failed[:5]) +
              ('; ...' if len(failed) > 5 else ''), file=sys.stderr)
    if sweep.stopping is not None:
        print(f'{NAME}: stopped by {signal.Signals(sweep.stopping).name}: {len(cases) - len(rows)} cases not run '
              f'or interrupted; start the sweep again to run them', file=sys.stderr)
        return 128 + sweep.stopping
    return 2 if failed else 0


main = launch.interruptible(_main, NAME, 'case')


if __name__ == '__main__':
    sys.exit(main())
