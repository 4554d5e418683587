#!/usr/bin/python3
"""Fault tests of the sweep and critical-value commands (python3 -m membrane_flow sweep / critical):
a reused output directory with a changed definition, parameter columns, booleans, entry names
checked before any case (against the real simulator), malformed JSON, failed cases, SIGINT /
SIGTERM / SIGKILL of a sweep, thread variables with several workers, and bisections that meet a
failed run or no change of outcome. Faults the real simulator cannot produce quickly (chosen exit
codes, long runs, a grandchild process) come from a fake simulator written to a temporary directory.
Usage: test_sweep_faults.py <membrane-flow> <small.prm>   (ends with a line "N passed, N failed")"""
import csv
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
from membrane_flow.workflow.critical import FailedRun, NoChange, bisect  # noqa: E402 (PYTHONPATH: the build's python/)

if len(sys.argv) != 3:
    sys.exit(__doc__)
EXE, SMALL = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
PYTHON = '/usr/bin/python3'
SWEEP = [PYTHON, '-m', 'membrane_flow', 'sweep']
CRITICAL = [PYTHON, '-m', 'membrane_flow', 'critical']

# A stand-in for membrane-flow: the same command line, --print-parameters for a few entries,
# behaviour chosen by its own 'Fake/...' entries. It records its argv, environment and pid (and
# the pid of a grandchild 'sleep' when it sleeps) in <output>/fake.json.
FAKE = r'''#!/usr/bin/python3
import json, os, subprocess, sys, time
PRM = """# Listing of Parameters
subsection Fake
  set Exit code = 0
  set Sleep     = 0
  set Fail from = -1
  set Fail to   = -1
  set Threshold = 800
end
subsection Material
  subsection Bending rigidity
    set Phase A value = 1
  end
  set Line tension = 90
end
subsection Output
  set Directory = results
  set Write VTU = true
end
subsection Time stepping
  set End time = 1
end
"""
args = sys.argv[1:]
if args[:1] == ['--print-parameters']:
    print(PRM)
    sys.exit(0)
sets, i = {}, 0
while i < len(args):
    if args[i] == '--set':
        name, value = args[i + 1].split('=', 1)
        sets[name] = value
        i += 2
    else:
        i += 1
out = sets['Output/Directory']
os.makedirs(out, exist_ok=True)
record = {'argv': sys.argv, 'sets': sets, 'pid': os.getpid(),
          'env': {k: os.environ.get(k) for k in ('OMP_NUM_THREADS', 'OPENBLAS_NUM_THREADS')}}
sleep = float(sets.get('Fake/Sleep', 0))
if sleep > 0:
    record['grandchild'] = subprocess.Popen(['sleep', str(sleep + 60)]).pid
with open(os.path.join(out, 'fake.json.tmp'), 'w') as f:
    json.dump(record, f)
os.replace(os.path.join(out, 'fake.json.tmp'), os.path.join(out, 'fake.json'))
time.sleep(sleep)
code = int(sets.get('Fake/Exit code', 0))
sigma = float(sets.get('Material/Line tension', 90))
if float(sets.get('Fake/Fail from', -1)) <= sigma <= float(sets.get('Fake/Fail to', -1)):
    code = 2
if code == 1:
    print('Error: fake bad input', file=sys.stderr)
    sys.exit(1)
with open(os.path.join(out, 'statistics.txt'), 'w') as f:
    f.write('# time energy domain_protrusion\n0 10 0.1\n0.5 9 0.2\n1 8.999 0.3\n')
outcome = 'complete bud' if sigma > float(sets.get('Fake/Threshold', 800)) else 'incomplete bud'
summary = {'stop_reason': 'end time' if code == 0 else 'step failed at t = 0.5: fake', 'failed': code == 2,
           'outcome': outcome, 'time': 1.0, 'steps': 3, 'energy': 8.999,
           'domain_protrusion': sigma / 1000, 'neck_ratio': min(1.0, 2.5 - sigma / 400)}
with open(os.path.join(out, 'summary.json'), 'w') as f:
    json.dump(summary, f)
sys.exit(code)
'''


def alive(pid):
    """True if the process exists and is not a zombie."""
    try:
        with open(f'/proc/{pid}/stat') as f:
            return f.read().rsplit(')', 1)[1].split()[0] != 'Z'
    except OSError:
        return False


class Base(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = self.tmp.name
        self.fake = os.path.join(self.root, 'fake-membrane-flow')
        with open(self.fake, 'w') as f:
            f.write(FAKE)
        os.chmod(self.fake, 0o755)

    def tearDown(self):
        self.tmp.cleanup()

    def write_sweep(self, spec, name='sweep.json'):
        path = os.path.join(self.root, name)
        with open(path, 'w') as f:
            f.write(spec if isinstance(spec, str) else json.dumps(spec, indent=1))
        return path

    def spec(self, vary, set_=None, output='out'):
        return {'base': SMALL, 'output': output, 'set': set_ or {}, 'vary': vary}

    def sweep(self, sweep_file, *args, exe=None, env=None, timeout=120):
        return subprocess.run([*SWEEP, sweep_file, '--exe', exe or self.fake,
                               *args], capture_output=True, text=True, timeout=timeout, env=env)

    def critical(self, low, high, *args, output='crit', timeout=120):
        return subprocess.run([*CRITICAL, SMALL, 'Material/Line tension',
                               str(low), str(high), '--output', os.path.join(self.root, output), '--exe', self.fake,
                               *args], capture_output=True, text=True, timeout=timeout)

    def table(self, output='out'):
        with open(os.path.join(self.root, output, 'results.csv')) as f:
            return list(csv.DictReader(f))

    def assertExit(self, result, code):
        self.assertEqual(result.returncode, code, f'stdout:\n{result.stdout}\nstderr:\n{result.stderr}')
        self.assertNotIn('Traceback', result.stderr)


class EntryNames(Base):
    """Item 4, with the real simulator: names are checked before any case runs."""

    def test_misspelled_entry_stops_before_any_case(self):
        path = self.write_sweep(self.spec({'Material/Line tensoin': [90, 120]}, {'Materail/Transition length': 0.06}))
        result = self.sweep(path, exe=EXE)
        self.assertExit(result, 1)
        self.assertIn("unknown entry 'Material/Line tensoin'; closest valid names: 'Material/Line tension'",
                      result.stderr)
        self.assertIn("unknown entry 'Materail/Transition length'; closest valid names: "
                      "'Material/Transition length'", result.stderr)
        self.assertFalse(os.path.exists(os.path.join(self.root, 'out')), 'nothing may be created or run')

    def test_names_equal_after_whitespace_normalization_are_an_error(self):
        path = self.write_sweep(self.spec({'Material/Line tension': [90], 'Material/ Line tension ': [120]}))
        result = self.sweep(path, exe=EXE)
        self.assertExit(result, 1)
        self.assertIn("names the entry 'Material/Line tension' twice", result.stderr)
        path = self.write_sweep(self.spec({'Material/Line tension': [90]}, {'Material/Line tension ': 120}))
        result = self.sweep(path, exe=EXE)
        self.assertExit(result, 1)
        self.assertIn("'Material/Line tension' is both in \"set\" and in \"vary\"", result.stderr)
        self.assertFalse(os.path.exists(os.path.join(self.root, 'out')))

    def test_output_directory_is_not_a_sweep_entry(self):
        path = self.write_sweep(self.spec({'Material/Line tension': [90]}, {'Output/Directory': 'x'}))
        result = self.sweep(path, exe=EXE)
        self.assertExit(result, 1)
        self.assertIn("'Output/Directory' is set by the sweep", result.stderr)

    def test_critical_value_checks_its_names(self):
        result = subprocess.run([*CRITICAL, SMALL, 'Material/Line tensoin',
                                 '500', '1000', '--tolerance', '0.1', '--output', os.path.join(self.root, 'c'),
                                 '--set', 'Time stepping/End tme=0.001', '--exe', EXE], capture_output=True, text=True)
        self.assertExit(result, 1)
        self.assertIn("unknown entry 'Material/Line tensoin'; closest valid names: 'Material/Line tension'",
                      result.stderr)
        self.assertIn("closest valid names: 'Time stepping/End time'", result.stderr)


class RealSweep(Base):
    """Items 2, 3, 4, 6, 9 with the real simulator: two tiny runs, one of them fails (exit 2)."""

    def test_columns_booleans_normalized_names_and_a_failed_case(self):
        path = self.write_sweep(self.spec(
            {'Time stepping/Adaptive ': [True, False]},  # JSON booleans; a trailing space is normalized
            {'Cahn-Hilliard/Scheme': 'explicit', 'Time stepping/Time step': 1e-2, 'Time stepping/End time': 0.03,
             'Output/Write VTU': False}))
        result = self.sweep(path, exe=EXE)
        self.assertExit(result, 2)
        self.assertIn('1 of 2 cases failed', result.stderr)
        rows = {r['Time stepping/Adaptive']: r for r in self.table()}
        self.assertEqual(sorted(rows), ['false', 'true'])
        for r in rows.values():  # fixed values are columns too, named by entry path, booleans as true/false
            self.assertEqual(r['Output/Write VTU'], 'false')
            self.assertEqual(r['Cahn-Hilliard/Scheme'], 'explicit')
            self.assertEqual(float(r['Time stepping/End time']), 0.03)
            case = os.path.join(self.root, 'out', 'cases', r['case'])
            with open(os.path.join(case, 'parameters.prm')) as f:
                self.assertRegex(f.read(), r'Write VTU\s*=\s*false')
            self.assertFalse([n for n in os.listdir(case) if n.endswith('.vtu')])
        self.assertEqual(rows['true']['outcome'], 'incomplete bud')
        self.assertEqual(rows['true']['exit_code'], '0')
        failed = rows['false']
        self.assertEqual(failed['outcome'], 'failed')  # the simulator said "incomplete bud" but failed
        self.assertTrue(failed['stop_reason'].startswith('step failed'), failed['stop_reason'])
        self.assertEqual((failed['failed'], failed['exit_code'], failed['T_min']), ('True', '2', ''))


class Definition(Base):
    """Item 1: a reused output directory with a changed definition."""

    def test_changed_definition_is_refused_unless_overwrite(self):
        path = self.write_sweep(self.spec({'Material/Line tension': [100, 200]}))
        self.assertExit(self.sweep(path), 0)
        with open(os.path.join(self.root, 'out', 'sweep.json')) as f:
            self.assertEqual(json.load(f)['vary'], {'Material/Line tension': [100, 200]})
        cases = sorted(os.listdir(os.path.join(self.root, 'out', 'cases')))

        self.write_sweep(self.spec({'Material/Line tension': [100, 300]}))
        result = self.sweep(path)
        self.assertExit(result, 1)
        self.assertIn('holds the results of a different sweep', result.stderr)
        self.assertIn('"vary" \'Material/Line tension\': [100, 200] -> [100, 300]', result.stderr)
        self.assertIn('--overwrite', result.stderr)
        self.assertEqual(sorted(os.listdir(os.path.join(self.root, 'out', 'cases'))), cases, 'nothing touched')
        self.assertEqual([r['Material/Line tension'] for r in self.table()], ['100', '200'])

        self.write_sweep(self.spec({'Material/Line tension': [100, 300]}, {'Time stepping/End time': 0.5}))
        result = self.sweep(path)  # a changed fixed value is a different definition too
        self.assertExit(result, 1)
        self.assertIn('"set" now has \'Time stepping/End time\'', result.stderr)

        result = self.sweep(path, '--overwrite')
        self.assertExit(result, 0)
        self.assertEqual([r['Material/Line tension'] for r in self.table()], ['100', '300'])
        self.assertEqual(len(os.listdir(os.path.join(self.root, 'out', 'cases'))), 2, 'old cases deleted')
        result = self.sweep(path)  # the same definition again resumes
        self.assertExit(result, 0)
        self.assertIn('2 already finished', result.stdout)

    def test_changed_base_file_is_refused(self):
        base = os.path.join(self.root, 'base.prm')
        with open(base, 'w') as f:
            f.write('subsection Material\n  set Line tension = 90\nend\n')
        path = self.write_sweep({'base': 'base.prm', 'output': 'out', 'vary': {'Material/Line tension': [1]}})
        self.assertExit(self.sweep(path), 0)
        with open(base, 'a') as f:
            f.write('# edited\n')
        result = self.sweep(path)
        self.assertExit(result, 1)
        self.assertIn('the content of the base file', result.stderr)

    def test_critical_value_directory_with_other_settings_is_refused(self):
        self.assertExit(self.critical(500, 1000, '--tolerance', '0.5', '--geometric'), 0)
        result = self.critical(500, 1000, '--tolerance', '0.5', '--geometric', '--set', 'Fake/Threshold=600')
        self.assertExit(result, 1)
        self.assertIn('holds the results of a different sweep', result.stderr)


class MalformedInput(Base):
    """Item 5: malformed JSON is one clear line with file and line, exit 1, no traceback."""

    def test_malformed_json(self):
        path = self.write_sweep('{\n "base": "x.prm",\n "output": "out",\n}\n')
        result = self.sweep(path)
        self.assertExit(result, 1)
        self.assertEqual(result.stderr.strip(), f"membrane_flow sweep: error: {path}:4:1: malformed JSON in sweep file: "
                                                f"Expecting property name enclosed in double quotes")

    def test_duplicate_key_missing_file_bad_values(self):
        path = self.write_sweep('{"base": "x", "base": "y", "output": "out"}')
        result = self.sweep(path)
        self.assertExit(result, 1)
        self.assertIn("the key 'base' appears twice", result.stderr)
        result = self.sweep(os.path.join(self.root, 'missing.json'))
        self.assertExit(result, 1)
        self.assertIn('cannot read sweep file', result.stderr)
        for vary, message in (({'Material/Line tension': {'linspace': [1, 2]}}, 'give a list of values'),
                              ({'Material/Line tension': []}, 'no values'),
                              ({'Material/Line tension': [[1, 2]]}, 'is not a number, string or boolean')):
            result = self.sweep(self.write_sweep(self.spec(vary)))
            self.assertExit(result, 1)
            self.assertIn(message, result.stderr)
            self.assertEqual(len(result.stderr.strip().splitlines()), 1)
        result = self.sweep(self.write_sweep({'base': SMALL, 'output': 'out', 'vray': {}}))
        self.assertExit(result, 1)
        self.assertIn("unknown key 'vray' (did you mean 'vary'?)", result.stderr)


class FailedCases(Base):
    """Items 6 and 9: failed cases make exit 2, are counted and have outcome 'failed'."""

    def test_failed_cases(self):
        path = self.write_sweep(self.spec({'Fake/Exit code': [0, 2, 1]}))
        result = self.sweep(path)
        self.assertExit(result, 2)
        self.assertIn('2 of 3 cases failed', result.stderr)
        rows = {r['Fake/Exit code']: r for r in self.table()}
        self.assertEqual(sorted(rows), ['0', '1', '2'])
        self.assertEqual((rows['0']['outcome'], rows['0']['failed'], rows['0']['exit_code']),
                         ('incomplete bud', 'False', '0'))
        self.assertNotEqual(rows['0']['T_min'], '')
        self.assertEqual((rows['2']['outcome'], rows['2']['failed'], rows['2']['exit_code']), ('failed', 'True', '2'))
        self.assertEqual(rows['2']['stop_reason'], 'step failed at t = 0.5: fake')  # the original stop reason
        self.assertEqual(rows['1']['outcome'], 'failed')
        self.assertEqual(rows['1']['stop_reason'], 'exit code 1: Error: fake bad input')
        # Again: the cases with a summary are kept, the one without is run again; still exit 2.
        result = self.sweep(path)
        self.assertExit(result, 2)
        self.assertIn('3 cases, 2 already finished, 1 to run', result.stdout)
        self.assertIn('2 of 3 cases failed', result.stderr)


class Booleans(Base):
    """Item 3 (fake simulator): JSON booleans reach the simulator as true/false."""

    def test_booleans(self):
        path = self.write_sweep(self.spec({'Fake/Sleep': [0]}, {'Output/Write VTU': False}))
        self.assertExit(self.sweep(path), 0)
        (case,) = os.listdir(os.path.join(self.root, 'out', 'cases'))
        with open(os.path.join(self.root, 'out', 'cases', case, 'fake.json')) as f:
            record = json.load(f)
        self.assertIn('Output/Write VTU=false', record['argv'])
        self.assertNotIn('False', ' '.join(record['argv']))


class ThreadVariables(Base):
    """Item 8: several workers give each case one thread, unless the user set the variables."""

    def envs(self, workers, env):
        path = self.write_sweep(self.spec({'Material/Line tension': [1, 2]}))
        self.assertExit(self.sweep(path, '--workers', str(workers), env=env), 0)
        cases = os.path.join(self.root, 'out', 'cases')
        result = []
        for case in os.listdir(cases):
            with open(os.path.join(cases, case, 'fake.json')) as f:
                result.append(json.load(f)['env'])
        self.tmp.cleanup()
        self.setUp()
        return result

    def test_thread_variables(self):
        env = {k: v for k, v in os.environ.items() if k not in ('OMP_NUM_THREADS', 'OPENBLAS_NUM_THREADS')}
        for e in self.envs(2, env):
            self.assertEqual(e, {'OMP_NUM_THREADS': '1', 'OPENBLAS_NUM_THREADS': '1'})
        for e in self.envs(2, {**env, 'OMP_NUM_THREADS': '3'}):
            self.assertEqual(e, {'OMP_NUM_THREADS': '3', 'OPENBLAS_NUM_THREADS': '1'})
        for e in self.envs(1, env):
            self.assertEqual(e, {'OMP_NUM_THREADS': None, 'OPENBLAS_NUM_THREADS': None})


class Signals(Base):
    """Item 7: SIGTERM / SIGINT stop the running cases (process group included), start no new
    case, write results.csv of the finished cases and exit 143 / 130. SIGKILL of the sweep
    still ends its cases (parent-death signal)."""

    def start(self, vary, workers=2):
        path = self.write_sweep(self.spec(vary))
        process = subprocess.Popen([*SWEEP, path, '--exe', self.fake,
                                    '--workers', str(workers)], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                   text=True, start_new_session=True)
        cases = os.path.join(self.root, 'out', 'cases')
        records = []
        deadline = time.time() + 30
        while time.time() < deadline:  # wait until two sleeping cases run
            records = []
            for case in os.listdir(cases) if os.path.isdir(cases) else []:
                try:
                    with open(os.path.join(cases, case, 'fake.json')) as f:
                        records.append(json.load(f))
                except (OSError, ValueError):
                    pass
            if len([r for r in records if 'grandchild' in r]) == 2:
                break
            time.sleep(0.05)
        sleeping = [r for r in records if 'grandchild' in r]
        self.assertEqual(len(sleeping), 2, 'two sleeping cases should be running')
        return process, sleeping, cases

    def check_stopped(self, sleeping, cases):
        deadline = time.time() + 5
        pids = [p for r in sleeping for p in (r['pid'], r['grandchild'])]
        while any(alive(p) for p in pids) and time.time() < deadline:
            time.sleep(0.05)
        self.assertFalse([p for p in pids if alive(p)], 'the cases and their children must be gone')
        self.assertEqual(len(os.listdir(cases)), 3, 'the fourth case must not start')

    def stop_with(self, sig, code, send):
        process, sleeping, cases = self.start({'Fake/Sleep': [0, 30, 31, 32]})
        send(process)
        stdout, stderr = process.communicate(timeout=20)
        self.assertEqual(process.returncode, code, stdout + stderr)
        self.assertNotIn('Traceback', stderr)
        self.assertIn(f'stopped by {signal.Signals(sig).name}', stderr)
        self.check_stopped(sleeping, cases)
        rows = self.table()
        self.assertEqual([r['Fake/Sleep'] for r in rows], ['0'])  # only the finished case
        self.assertEqual(rows[0]['outcome'], 'incomplete bud')

    def test_sigterm(self):
        self.stop_with(signal.SIGTERM, 143, lambda p: p.send_signal(signal.SIGTERM))

    def test_sigint_to_the_process_group_like_ctrl_c(self):
        self.stop_with(signal.SIGINT, 130, lambda p: os.killpg(p.pid, signal.SIGINT))

    def test_sigkill_of_the_sweep_still_ends_its_cases(self):
        process, sleeping, cases = self.start({'Fake/Sleep': [0, 30, 31, 32]})
        process.kill()
        process.communicate(timeout=20)
        deadline = time.time() + 5
        while any(alive(r['pid']) for r in sleeping) and time.time() < deadline:
            time.sleep(0.05)
        self.assertFalse([r['pid'] for r in sleeping if alive(r['pid'])])
        for r in sleeping:  # the grandchildren (like MPI ranks under mpirun) are cleaned up here
            try:
                os.kill(r['grandchild'], signal.SIGKILL)
            except ProcessLookupError:
                pass

    def test_critical_value_interrupted(self):
        process = subprocess.Popen([*CRITICAL, SMALL,
                                    'Material/Line tension', '500', '1000', '--tolerance', '0.1', '--output',
                                    os.path.join(self.root, 'crit'), '--exe', self.fake, '--set', 'Fake/Sleep=30'],
                                   stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        cases = os.path.join(self.root, 'crit', 'cases')
        deadline = time.time() + 30
        record = None
        while record is None and time.time() < deadline:
            for case in os.listdir(cases) if os.path.isdir(cases) else []:
                try:
                    with open(os.path.join(cases, case, 'fake.json')) as f:
                        record = json.load(f)
                except (OSError, ValueError):
                    pass
            time.sleep(0.05)
        self.assertIsNotNone(record)
        process.send_signal(signal.SIGTERM)
        stdout, stderr = process.communicate(timeout=20)
        self.assertEqual(process.returncode, 143, stdout + stderr)
        self.assertNotIn('Traceback', stderr)
        with open(os.path.join(self.root, 'crit', 'bisection.json')) as f:
            result = json.load(f)
        self.assertEqual((result['bracket'], result['status'], result['runs']), (None, 'interrupted', []))
        self.assertTrue(os.path.exists(os.path.join(self.root, 'crit', 'results.csv')))
        self.assertEqual(len(os.listdir(cases)), 1)
        deadline = time.time() + 5
        while (alive(record['pid']) or alive(record['grandchild'])) and time.time() < deadline:
            time.sleep(0.05)
        self.assertFalse(alive(record['pid']) or alive(record['grandchild']))


class CriticalValue(Base):
    """Items 9 and 10: the bisection never uses a failed run as a bracket end, and reports no
    change of outcome plainly; both write results.csv and bisection.json."""

    def bisection(self):
        with open(os.path.join(self.root, 'crit', 'bisection.json')) as f:
            return json.load(f)

    def test_finds_the_threshold(self):
        result = self.critical(500, 1000, '--tolerance', '20')
        self.assertExit(result, 0)
        b = self.bisection()
        self.assertTrue(b['bracket'][0] <= 800 < b['bracket'][1])
        self.assertEqual((b['status'], b['outcomes']), ('converged', ['incomplete bud', 'complete bud']))
        self.assertEqual(len(self.table('crit')), len(b['runs']))

    def test_failed_run_inside_the_bracket_stops_the_search(self):
        result = self.critical(500, 1000, '--tolerance', '20', '--set', 'Fake/Fail from=700',
                               '--set', 'Fake/Fail to=760')
        self.assertExit(result, 2)
        b = self.bisection()
        self.assertEqual(b['runs'], [[500.0, 'incomplete bud'], [1000.0, 'complete bud'], [750.0, 'failed']])
        self.assertIsNone(b['bracket'])
        self.assertEqual((b['status'], b['last_valid_bracket']), ('failed run', [500.0, 1000.0]))
        self.assertIn(f"the run at Material/Line tension = 750 failed (case {b['failed_case']}: step failed",
                      result.stderr)
        self.assertIn('cannot end a bracket', result.stderr)
        rows = {r['Material/Line tension']: r['outcome'] for r in self.table('crit')}
        self.assertEqual(rows, {'500.0': 'incomplete bud', '750.0': 'failed', '1000.0': 'complete bud'})

    def test_failed_end_stops_the_search(self):
        result = self.critical(500, 1000, '--tolerance', '20', '--set', 'Fake/Fail from=990',
                               '--set', 'Fake/Fail to=2000')
        self.assertExit(result, 2)
        b = self.bisection()
        self.assertEqual(b['runs'], [[500.0, 'incomplete bud'], [1000.0, 'failed']])
        self.assertEqual((b['bracket'], b['last_valid_bracket']), (None, None))
        self.assertIn('the run at Material/Line tension = 1000 failed', result.stderr)

    def test_classify_by_protrusion_and_neck(self):
        # outcome changes at 800 (Fake/Threshold); protrusion sigma / 1000 crosses 0.95 at 950;
        # neck ratio 2.5 - sigma / 400 falls below 0.4 at 840
        result = self.critical(500, 1000, '--tolerance', '5', '--classify', 'protrusion:0.95')
        self.assertExit(result, 0)
        b = self.bisection()
        self.assertTrue(b['bracket'][0] < 950 <= b['bracket'][1], b['bracket'])
        self.assertEqual((b['outcomes'], b['classify']), (['not protruding', 'protruding'], 'protrusion:0.95'))
        self.assertTrue(all(c['outcome'] == ('complete bud' if c['value'] > 800 else 'incomplete bud')
                            for c in b['cases']))
        result = self.critical(500, 1000, '--tolerance', '5', '--classify', 'neck:0.4', '--overwrite')
        self.assertExit(result, 0)
        b = self.bisection()
        self.assertTrue(b['bracket'][0] <= 840 < b['bracket'][1], b['bracket'])
        self.assertEqual(b['outcomes'], ['no neck', 'necked'])
        result = self.critical(500, 1000, '--tolerance', '5', '--classify', 'protrusion:high')
        self.assertExit(result, 1)
        self.assertIn('--classify protrusion:high: expected outcome, protrusion:X or neck:X', result.stderr)

    def test_no_change_of_outcome(self):
        result = self.critical(630, 700, '--tolerance', '0.05', '--geometric')
        self.assertExit(result, 1)
        self.assertIn('no change of outcome between Material/Line tension = 630 and 700: both ends give '
                      '"incomplete bud"', result.stderr)
        b = self.bisection()
        self.assertEqual((b['bracket'], b['status']), (None, 'no change'))
        self.assertEqual(b['runs'], [[630.0, 'incomplete bud'], [700.0, 'incomplete bud']])
        self.assertEqual(len(self.table('crit')), 2)


class BisectFunction(unittest.TestCase):
    """Item 9 on a cheap outcome function: a failed run is never a bracket end."""

    def test_failed_middle(self):
        outcome = {0.5: 'failed'}
        with self.assertRaises(FailedRun) as raised:
            bisect(lambda x: outcome.get(x, 'complete' if x > 0.3 else 'incomplete'), 0.0, 1.0, 1e-3)
        self.assertEqual((raised.exception.value, raised.exception.bracket), (0.5, [0.0, 1.0]))
        self.assertEqual(raised.exception.runs[-1], (0.5, 'failed'))

    def test_no_change_keeps_the_runs(self):
        with self.assertRaises(NoChange) as raised:
            bisect(lambda x: 'flat', 1.0, 2.0, 0.1)
        self.assertEqual(raised.exception.runs, [(1.0, 'flat'), (2.0, 'flat')])


if __name__ == '__main__':
    start = time.time()
    result = unittest.TextTestRunner(verbosity=2).run(unittest.defaultTestLoader.loadTestsFromModule(
        sys.modules[__name__]))
    bad = len(result.failures) + len(result.errors) + len(result.unexpectedSuccesses)
    print(f'{result.testsRun - bad} passed, {bad} failed ({time.time() - start:.1f} s)')
    sys.exit(1 if bad or not result.wasSuccessful() else 0)
