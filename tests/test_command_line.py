#!/usr/bin/python3
"""The command line of the Python package, python3 -m membrane_flow, and its launcher.

Asserts: --help lists every command and exits 0; each command answers --help with its usage
(exit 0) without running anything; an unknown command or option exits 2 naming it; the shared
--exe before the command reaches the command (the sweep's name check runs that program); and
membrane_flow.launch: the program's lookup order (explicit, MEMBRANE_FLOW_EXE, the build of the
package), the environment of a run (thread variables forced or kept) and a run as its own
process group, whose exit code and timeout are reported.
Usage: test_command_line.py <membrane-flow>   (membrane_flow importable: PYTHONPATH=<build>/python)"""
import json
import os
import subprocess
import sys
import tempfile
import unittest

from membrane_flow import launch
from membrane_flow.__main__ import COMMANDS

EXE = os.path.abspath(sys.argv.pop(1)) if len(sys.argv) > 1 else None
PYTHON = '/usr/bin/python3'


def command_line(*args, env=None, cwd=None):
    return subprocess.run([PYTHON, '-m', 'membrane_flow', *args], capture_output=True, text=True, env=env, cwd=cwd,
                          timeout=120)


class CommandLine(unittest.TestCase):
    def test_help_lists_every_command(self):
        result = command_line('--help')
        self.assertEqual(result.returncode, 0, result.stderr)
        for name in COMMANDS:
            self.assertIn(f'  {name} ', result.stdout)

    def test_each_command_answers_help_without_running(self):
        with tempfile.TemporaryDirectory() as scratch:
            for name in COMMANDS:
                result = command_line(name, '--help', cwd=scratch)
                self.assertEqual(result.returncode, 0, f'{name}: {result.stderr}')
                self.assertIn('usage', result.stdout.lower(), name)
            self.assertEqual(os.listdir(scratch), [], 'a --help wrote files')

    def test_unknown_command_and_option(self):
        result = command_line('swep')
        self.assertEqual(result.returncode, 2)
        self.assertIn("unknown command 'swep' (did you mean 'sweep'?)", result.stderr)
        result = command_line('--fast', 'sweep')
        self.assertEqual(result.returncode, 2)
        self.assertIn('unknown option --fast', result.stderr)

    def test_spectrum_names_the_bad_option_and_the_missing_column(self):
        with tempfile.TemporaryDirectory() as scratch:
            with open(os.path.join(scratch, 'statistics.txt'), 'w') as f:
                f.write('# step time tau gamma_mean gradient_energy well_energy area\n0 0 1e-3 0 0 0 1\n')
            result = command_line('spectrum', 'patch', scratch, '--kT', '-1')
            self.assertEqual(result.returncode, 2)
            self.assertIn('--kT must be > 0 (got -1)', result.stderr)
            result = command_line('spectrum', 'patch', scratch, '--kT', '1e-4', '--batches', '1')
            self.assertEqual(result.returncode, 2)
            self.assertIn('--batches must be >= 2 (got 1)', result.stderr)
            # a run without the height columns (not a patch run): exit 1 naming the column
            with open(os.path.join(scratch, 'statistics.txt'), 'a') as f:
                f.writelines(f'{i} {i * 1e-3} 1e-3 0 0 0 1\n' for i in range(1, 60))
            result = command_line('spectrum', 'patch', scratch, '--kT', '1e-4', '--skip', '0')
            self.assertEqual(result.returncode, 1, result.stdout)
            self.assertIn("no statistics column 'height_mode_1'", result.stderr)

    def test_shared_exe_option_reaches_the_command(self):
        with tempfile.TemporaryDirectory() as scratch:
            spec = os.path.join(scratch, 'sweep.json')
            with open(os.path.join(scratch, 'base.prm'), 'w') as f:
                f.write('')
            with open(spec, 'w') as f:
                json.dump({'base': 'base.prm', 'output': 'out', 'vary': {'Material/Line tension': [1, 2]}}, f)
            result = command_line('--exe', '/nonexistent/membrane-flow', 'sweep', spec, '--dry-run')
            self.assertEqual(result.returncode, 1)
            self.assertIn('cannot run the simulator /nonexistent/membrane-flow', result.stderr)


class Launcher(unittest.TestCase):
    def test_lookup_order(self):
        saved = os.environ.pop(launch.EXECUTABLE_VARIABLE, None)
        try:
            self.assertEqual(launch.find_executable('/my/exe'), '/my/exe')
            os.environ[launch.EXECUTABLE_VARIABLE] = '/from/environment'
            self.assertEqual(launch.find_executable(), '/from/environment')
            self.assertEqual(launch.find_executable('/my/exe'), '/my/exe')
            del os.environ[launch.EXECUTABLE_VARIABLE]
            if EXE:  # the package of this build finds this build's program
                self.assertEqual(os.path.realpath(launch.find_executable()), os.path.realpath(EXE))
        finally:
            if saved is not None:
                os.environ[launch.EXECUTABLE_VARIABLE] = saved

    def test_environment(self):
        base = {'OMP_NUM_THREADS': '4', 'PATH': '/bin'}
        self.assertEqual(launch.environment(base=base)['OMP_NUM_THREADS'], '1')
        kept = launch.environment(force=False, base=base)
        self.assertEqual((kept['OMP_NUM_THREADS'], kept['OPENBLAS_NUM_THREADS']), ('4', '1'))
        self.assertNotIn('OPENBLAS_NUM_THREADS', launch.environment(threads=False, base=base))
        if os.geteuid() == 0:
            self.assertEqual(launch.environment(mpi=True, base=base)['OMPI_ALLOW_RUN_AS_ROOT'], '1')
        self.assertEqual(launch.command('exe', ['a'], ranks=3, launcher='mpirun --oversubscribe'),
                         ['mpirun', '--oversubscribe', '-np', '3', 'exe', 'a'])
        self.assertEqual(launch.command('exe', ['a']), ['exe', 'a'])

    def test_process_group_exit_code_and_timeout(self):
        process = launch.start(['sh', '-c', 'exit 3'])
        self.assertEqual(process.wait(), 3)
        self.assertEqual(os.getpgid(0) != process.pid, True)
        code, timed_out = launch.run(['sh', '-c', 'sleep 30 & wait'], timeout=0.5, grace=5)
        self.assertTrue(timed_out)
        self.assertLess(code, 0)  # ended by SIGTERM to its group, the background sleep included
        result = launch.output(['sh', '-c', 'echo out; echo err >&2; exit 4'])
        self.assertEqual((result.returncode, result.stdout, result.stderr), (4, 'out\n', 'err\n'))


if __name__ == '__main__':
    unittest.main(verbosity=2)
