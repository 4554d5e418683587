#!/usr/bin/python3
"""Fault tests of membrane-flow itself: output directories, command lines, parameter
combinations, memory, signals, error messages, --version (docs/reliability.md).

Usage: test_reliability.py <membrane-flow> <tests/inputs/small.prm> [name-substring]

Each check runs the real program on a fault and asserts its exit code and message (the
message names the entry or option); error messages must be the last line of the output.
Prints one line per check and a closing line "N passed, M failed"; exits 1 if any failed.
About 50 s on 2 cores, four checks at a time (every run is tiny: 1-2 steps of small.prm, no VTU)."""
import itertools
import os
import re
import shutil
import json
import signal
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor

if len(sys.argv) < 3:
    sys.exit(__doc__)
EXE = os.path.abspath(sys.argv[1])
SMALL = os.path.abspath(sys.argv[2])
ONLY = sys.argv[3] if len(sys.argv) > 3 else None
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TINY = ['--set', 'Time stepping/Maximum steps=1', '--set', 'Output/Write VTU=false']
ENV = dict(os.environ, OMP_NUM_THREADS='1', OPENBLAS_NUM_THREADS='1')

CHECKS = []
RESULTS = []  # (name, passed, detail)
WORK = tempfile.mkdtemp(prefix='membrane-reliability-')


class Failure(Exception):
    pass


def check(function):
    CHECKS.append(function)
    return function


def run(args, cwd=None, timeout=120):
    """Run membrane-flow; (exit code, stdout and stderr merged in the order written)."""
    result = subprocess.run([EXE] + args, cwd=cwd or WORK, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            stdin=subprocess.DEVNULL, timeout=timeout, env=ENV)
    return result.returncode, result.stdout.decode('utf-8', 'replace')


def require(condition, message, output=None):
    if not condition:
        raise Failure(message + (('\n    ' + '\n    '.join(output.rstrip().splitlines()[-12:])) if output else ''))


def expect(args, code, regex, cwd=None, error_last=True):
    """Exit code and a message matching regex; with error_last, the last line is the 'Error: ...'."""
    got, output = run(args, cwd=cwd)
    require(got == code, f'exit code {got}, expected {code}', output)
    require(re.search(regex, output, re.S), f'output does not match /{regex}/', output)
    if error_last:
        lines = [line for line in output.splitlines() if line.strip()]
        require(lines and lines[-1].startswith('Error:'), 'the error message is not the last line', output)
        require('TimerOutput objects finalize' not in output, 'deal.II timer note in the output', output)
    return output


_COUNTER = itertools.count()


def fresh(name):
    """A path in the work directory that does not exist yet (unique: checks run in parallel)."""
    return os.path.join(WORK, f'{name}-{next(_COUNTER)}')


def out(directory):
    return ['--set', f'Output/Directory={directory}']


def snapshot(directory):
    """{name: (size, mtime_ns, content)} of the files in a directory."""
    state = {}
    for name in sorted(os.listdir(directory)):
        path = os.path.join(directory, name)
        if os.path.isfile(path):
            with open(path, 'rb') as f:
                state[name] = (os.stat(path).st_mtime_ns, f.read())
        else:
            state[name] = 'dir'
    return state


def tiny_run(directory, *extra):
    code, output = run(['--quiet'] + TINY + out(directory) + list(extra) + [SMALL])
    require(code == 0, f'setting up: a tiny run into {directory} ended with exit code {code}', output)


def last_step(directory):
    with open(os.path.join(directory, 'statistics.txt')) as f:
        rows = [line.split() for line in f if line.strip() and not line.startswith('#')]
    return int(rows[-1][0])


# ---- 1. a run owns its output directory -------------------------------------------------

@check
def rundir_rerun_refused_without_overwrite():
    d = fresh('rerun')
    tiny_run(d)
    before = snapshot(d)
    expect(['--quiet'] + TINY + out(d) + [SMALL], 1,
           r'Output/Directory.*already holds the output of a run.*--overwrite')
    require(snapshot(d) == before, 'the earlier run\'s files changed')


@check
def rundir_overwrite_deletes_only_run_files():
    d = fresh('overwrite')
    tiny_run(d, '--set', 'Checkpoint/Interval=1')
    for name, text in (('summary.json.partial', '{'),            # left over by a killed run
                       ('log.txt', 'the earlier run\'s log\n'),  # the earlier run's log
                       ('case.json', '{}\n'), ('status.json', '{"exit_code": 0}\n')):  # a sweep's records
        with open(os.path.join(d, name), 'w') as f:
            f.write(text)
    code, output = run(['--overwrite'] + TINY + out(d) + [SMALL])
    require(code == 0, f'exit code {code}', output)
    require(re.search(r'Deleted 7 files of an earlier run', output), 'no note of the 7 deleted files', output)
    names = sorted(os.listdir(d))
    require('summary.json.partial' not in names and 'checkpoint.txt' not in names,
            f'old output files left: {names}')
    if 'log.txt' in names:  # written anew by the run itself
        with open(os.path.join(d, 'log.txt')) as f:
            require('the earlier run' not in f.read(), 'the earlier run\'s log.txt was kept')
    for name in ('case.json', 'status.json'):
        require(name in names, f'the launcher file {name} was deleted')


@check
def rundir_overwrite_keeps_the_log_that_is_its_own_output():
    d = fresh('own-log')
    tiny_run(d)
    log = os.path.join(d, 'log.txt')
    with open(log, 'w') as f:  # membrane-flow --overwrite ... > d/log.txt
        code = subprocess.run([EXE, '--overwrite'] + TINY + out(d) + [SMALL], cwd=WORK, stdout=f,
                              stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, env=ENV, timeout=120).returncode
    with open(log) as f:
        text = f.read()
    require(code == 0, f'exit code {code}', text)
    require('Deleted 4 files of an earlier run' in text and 'Results:' in text,
            'the run\'s own log.txt (its stdout) was deleted or is incomplete', text)


@check
def rundir_foreign_files_refused_even_with_overwrite():
    d = fresh('foreign')
    tiny_run(d)
    with open(os.path.join(d, 'notes.md'), 'w') as f:
        f.write('my notes\n')
    before = snapshot(d)
    for flags in ([], ['--overwrite']):
        expect(['--quiet'] + flags + TINY + out(d) + [SMALL], 1,
               r'Output/Directory.*did not write \(notes\.md\).*--overwrite never deletes them')
        require(snapshot(d) == before, f'files changed or deleted with {flags}')


@check
def rundir_foreign_only_and_subdirectory_refused():
    d = fresh('foreign-only')
    os.makedirs(os.path.join(d, 'old-run'))
    with open(os.path.join(d, 'data.csv'), 'w') as f:
        f.write('1,2\n')
    expect(['--quiet', '--overwrite'] + TINY + out(d) + [SMALL], 1, r'Output/Directory.*data\.csv, old-run')
    require(sorted(os.listdir(d)) == ['data.csv', 'old-run'], 'the directory changed')


@check
def rundir_output_directory_is_a_file():
    path = fresh('a-file')
    with open(path, 'w') as f:
        f.write('x\n')
    expect(['--quiet', '--overwrite'] + TINY + out(path) + [SMALL], 1, r'Output/Directory.*is not a directory')


@check
def rundir_launcher_files_only_accepted():
    d = fresh('sweep-case')
    os.makedirs(d)
    for name in ('case.json', 'log.txt'):
        with open(os.path.join(d, name), 'w') as f:
            f.write('{}\n')
    tiny_run(d)
    names = os.listdir(d)
    require('case.json' in names and 'log.txt' in names and 'summary.json' in names, f'files: {names}')


@check
def rundir_resume_in_own_directory_keeps_its_files():
    d = fresh('resume-own')
    tiny_run(d, '--set', 'Checkpoint/Interval=1', '--set', 'Time stepping/Maximum steps=2')
    code, output = run(['--quiet'] + TINY + out(d) + ['--set', 'Checkpoint/Interval=1', '--set',
                       'Time stepping/Maximum steps=3', '--set', f'Checkpoint/Resume from={d}/checkpoint.txt',
                       SMALL])
    require(code == 0, f'exit code {code}', output)
    require(last_step(d) == 3, f'statistics end at step {last_step(d)}, expected 3 (continued)')


@check
def rundir_resume_into_another_runs_directory_refused():
    own, other, new = fresh('resume-a'), fresh('resume-b'), fresh('resume-new')
    tiny_run(own, '--set', 'Checkpoint/Interval=1')
    tiny_run(other)
    before = snapshot(other)
    resume = ['--set', f'Checkpoint/Resume from={own}/checkpoint.txt', '--set', 'Time stepping/Maximum steps=2']
    expect(['--quiet'] + TINY + out(other) + resume + [SMALL], 1,
           r'Checkpoint/Resume from.*is not the checkpoint\.txt of <Output/Directory>.*another run.*--overwrite')
    require(snapshot(other) == before, 'the other run\'s files changed')
    code, output = run(['--quiet'] + TINY + out(new) + resume + [SMALL])  # a new directory is fine
    require(code == 0, f'resuming into a new directory: exit code {code}', output)


# ---- 5. signals (and a directory in use by a running run) -------------------------------

def long_run(directory):
    process = subprocess.Popen([EXE, '--quiet', '--set', 'Output/Write VTU=false', '--set',
                                'Time stepping/End time=1000'] + out(directory) + [SMALL], cwd=WORK, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, env=ENV)
    deadline = time.time() + 30
    while not os.path.exists(os.path.join(directory, 'statistics.txt')):
        if process.poll() is not None:
            raise Failure(f'the long run ended early (exit code {process.returncode})\n    '
                          + process.stdout.read().decode().rstrip().replace('\n', '\n    '))
        require(time.time() < deadline, 'the long run did not start stepping within 30 s')
        time.sleep(0.1)
    return process


def stop_with(sig):
    d = fresh('signal-' + signal.Signals(sig).name)
    process = long_run(d)
    try:
        time.sleep(0.5)
        start = time.time()
        process.send_signal(sig)
        try:
            process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            raise Failure(f'{signal.Signals(sig).name}: the process still runs after 10 s')
        name = signal.Signals(sig).name
        require(process.returncode == 128 + sig, f'{name}: exit code {process.returncode} (expected {128 + sig})')
        # The run stopped between steps and kept its state: summary with the reason, a
        # checkpoint to resume from, and the message as the last line on the screen.
        with open(os.path.join(d, 'summary.json')) as f:
            summary = json.load(f)
        require(summary['stop_reason'].startswith(f'interrupted by {name}'),
                f'{name}: stop reason {summary["stop_reason"]!r}')
        require(os.path.exists(os.path.join(d, 'checkpoint.txt')), f'{name}: no checkpoint written')
        last = process.stdout.read().decode().rstrip().splitlines()[-1]
        require(f'stopped by {name}' in last, f'{name}: last line {last!r}')
        return process.returncode, time.time() - start
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()


@check
def rundir_directory_in_use_by_a_running_run_refused():
    d = fresh('in-use')
    process = long_run(d)
    try:
        expect(['--quiet', '--overwrite'] + TINY + out(d) + [SMALL], 1,
               r'Output/Directory.*is in use by another membrane-flow run that is still running')
        require(process.poll() is None, 'the running run ended')
    finally:
        process.kill()
        process.wait()


@check
def signals_sigterm_ends_the_run():
    stop_with(signal.SIGTERM)


@check
def signals_sigint_ends_the_run():
    stop_with(signal.SIGINT)


@check
def signals_sigkill_out_of_core_files_removed_by_the_next_run():
    # MUMPS deletes its out-of-core factor files when its instance is destroyed, which a
    # killed process never does; each process keeps them in its own directory, and the next
    # out-of-core run on the host removes the directories of processes that are gone.
    base = fresh('ooc-base')
    os.makedirs(base)
    env = dict(ENV, MUMPS_OOC_TMPDIR=base)
    ooc = ['--set', 'Linear solver/Out of core=true', '--set', 'Output/Write VTU=false']
    d = fresh('ooc-killed')
    process = subprocess.Popen([EXE, '--quiet', '--set', 'Time stepping/End time=1000'] + ooc + out(d) + [SMALL],
                               cwd=WORK, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                               stdin=subprocess.DEVNULL, env=env)
    own = os.path.join(base, f'membrane-ooc-{os.uname().nodename}-{process.pid}')
    try:
        deadline = time.time() + 30
        while not (os.path.exists(os.path.join(d, 'statistics.txt')) and os.path.isdir(own) and os.listdir(own)):
            require(process.poll() is None, f'the out-of-core run ended early (exit code {process.returncode})')
            require(time.time() < deadline, f'no factor files in {own} within 30 s: {os.listdir(base)}')
            time.sleep(0.1)
    finally:
        process.kill()
        process.wait()
    require(os.listdir(own), 'the killed run left no factor files (nothing to test)')
    result = subprocess.run([EXE] + TINY + ooc + out(fresh('ooc-next')) + [SMALL], cwd=WORK, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, env=env, timeout=120)
    got, output = result.returncode, result.stdout.decode('utf-8', 'replace')
    require(got == 0, f'the next out-of-core run ended with exit code {got}', output)
    require(re.search(r'Removed 1 out-of-core directory of killed runs from ' + re.escape(base), output),
            'the next run did not report removing the killed run\'s directory', output)
    require(os.listdir(base) == [], f'left in {base} after the next run: {os.listdir(base)}')


# ---- records and checkpoints of the simulator ---------------------------------------------

@check
def records_are_valid_json_whatever_the_arguments():
    d = fresh('quote"back\\slash')
    got, output = run(['--quiet'] + TINY + out(d) + [SMALL])
    require(got == 0, f'exit code {got}', output)
    with open(os.path.join(d, 'run_info.json')) as f:
        info = json.load(f)
    with open(os.path.join(d, 'summary.json')) as f:
        json.load(f)
    require('quote"back\\slash' in info['command'], f'command not kept: {info["command"]!r}')


@check
def records_count_the_shape_factorizations():
    # One numeric factorization of the shape system per trial step with the direct solver;
    # with Reuse iterations the factors of the first step serve the following ones.
    counts = {}
    for reuse in (0, 20):
        d = fresh(f'factorizations-{reuse}')
        got, output = run(['--quiet', '--set', 'Time stepping/Maximum steps=4', '--set', 'Output/Write VTU=false',
                           '--set', f'Linear solver/Reuse iterations={reuse}'] + out(d) + [SMALL])
        require(got == 0, f'exit code {got}', output)
        with open(os.path.join(d, 'summary.json')) as f:
            summary = json.load(f)
        counts[reuse] = (summary['shape_factorizations'], summary['steps'] + summary['rejected_steps'])
    require(counts[0][0] == counts[0][1] == 4, f'without reuse: {counts[0][0]} factorizations for {counts[0][1]} trial steps')
    require(counts[20][0] == 1, f'with reuse: {counts[20][0]} factorizations for {counts[20][1]} trial steps (expected 1)')


@check
def resume_records_changed_parameters_and_total_wall_time():
    d = fresh('resume')
    first = ['--quiet', '--set', 'Output/Write VTU=false', '--set', 'Checkpoint/Interval=3'] + out(d)
    got, output = run(first + ['--set', 'Time stepping/Maximum steps=3', SMALL])
    require(got == 0, f'first segment: exit code {got}', output)
    with open(os.path.join(d, 'summary.json')) as f:
        first_wall = json.load(f)['wall_seconds']
    got, output = run(first + ['--set', 'Time stepping/Maximum steps=6', '--set', 'Material/Line tension=120',
                               '--set', f'Checkpoint/Resume from={d}/checkpoint.txt', SMALL])
    require(got == 0, f'resumed segment: exit code {got}', output)
    require('Material/Line tension: 90 -> 120' in output, 'the changed line tension is not reported', output)
    with open(os.path.join(d, 'run_info.json')) as f:
        info = json.load(f)
    require('Material/Line tension: 90 -> 120' in info.get('changed_on_resume', []),
            f'run_info.json: changed_on_resume = {info.get("changed_on_resume")!r}')
    with open(os.path.join(d, 'summary.json')) as f:
        summary = json.load(f)
    require(summary['steps'] == 6 and summary['wall_seconds'] > first_wall,
            f'summary after resume: steps {summary["steps"]}, wall {summary["wall_seconds"]} (first {first_wall})')
    trials = summary['steps'] + summary['rejected_steps']
    require(summary['shape_factorizations'] == trials,
            f'summary after resume: {summary["shape_factorizations"]} shape factorizations for {trials} trial steps '
            '(both segments count)')


@check
def disk_write_failure_keeps_the_last_good_files():
    # A write that fails part-way (a full disk, a quota): here the file-size limit RLIMIT_FSIZE,
    # under which write() fails with EFBIG once a file would grow past it, as it fails with
    # ENOSPC on a full disk (SIGXFSZ ignored, so the error reaches the program). The limit
    # lets the snapshots and the first checkpoint (step 5) through and stops the second one
    # (step 10, whose statistics are longer); both sizes come from reference runs.
    import resource
    base = ['--quiet', '--set', 'Checkpoint/Interval=5', '--set', 'Output/Interval=0.0005']
    reference = fresh('write-reference')
    got, output = run(base + ['--set', 'Time stepping/Maximum steps=5'] + out(reference) + [SMALL])
    require(got == 0, f'reference run: exit code {got}', output)
    first_checkpoint = os.path.getsize(os.path.join(reference, 'checkpoint.txt'))
    largest_other = max(os.path.getsize(os.path.join(reference, n)) for n in os.listdir(reference)
                        if n != 'checkpoint.txt')
    longer = fresh('write-reference-10')
    got, output = run(base + ['--set', 'Time stepping/Maximum steps=10'] + out(longer) + [SMALL])
    require(got == 0, f'reference run to step 10: exit code {got}', output)
    second_checkpoint = os.path.getsize(os.path.join(longer, 'checkpoint.txt'))
    limit = max(first_checkpoint, largest_other) + 200
    require(limit < second_checkpoint,
            f'set-up: the checkpoint of step 10 ({second_checkpoint} bytes) would fit under {limit}')

    def limit_file_size():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    d = fresh('write-failure')
    result = subprocess.run([EXE] + base + ['--set', 'Time stepping/Maximum steps=20'] + out(d) + [SMALL], cwd=WORK,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                            env=dict(ENV, PMIX_MCA_gds='hash'),  # MPI start-up without shared-memory files
                            timeout=120, preexec_fn=limit_file_size, restore_signals=False)
    output = result.stdout.decode('utf-8', 'replace')
    require(result.returncode == 1, f'exit code {result.returncode}, expected 1', output)
    partial = os.path.join(d, 'checkpoint.txt.partial')
    require(re.search(r'Error: .*Writing <' + re.escape(partial) + r'> failed: File too large \(the file under its '
                      r'final name is unchanged\)', output), 'the write error does not name the file and the cause',
            output)
    lines = [line for line in output.splitlines() if line.strip()]
    require(lines[-1].startswith('Error:'), 'the error message is not the last line', output)
    # Under their final names: the complete first checkpoint, and only complete snapshots.
    def checkpoint_lines(directory):
        with open(os.path.join(directory, 'checkpoint.txt')) as f:
            return f.readlines()
    kept = checkpoint_lines(d)  # as long as the reference's (their wall times differ), of step 5
    require(len(kept) == len(checkpoint_lines(reference)) and 'step 5\n' in kept,
            'checkpoint.txt is not the complete checkpoint of step 5')
    for name in os.listdir(d):
        if name.endswith('.vtu'):
            with open(os.path.join(d, name), 'rb') as f:
                require(f.read().rstrip().endswith(b'</VTKFile>'), f'{name} is truncated')
    # The run continues from its last good checkpoint once there is room again.
    got, output = run(['--quiet', '--set', 'Time stepping/Maximum steps=8', '--set',
                       f'Checkpoint/Resume from={d}/checkpoint.txt'] + out(d) + [SMALL])
    require(got == 0 and last_step(d) == 8, f'resume after the failure: exit code {got}', output)


# ---- 2. command line and input path -----------------------------------------------------

def expect_no_run(args, regex):
    """Exit 1 with the message, and nothing created (no default run)."""
    cwd = fresh('cli')
    os.makedirs(cwd)
    expect(args, 1, regex, cwd=cwd)
    require(os.listdir(cwd) == [], f'the program created {os.listdir(cwd)}: it ran')


@check
def cli_set_without_equals():
    expect_no_run(['--set', 'Material/Line tension', SMALL], r"--set Material/Line tension: expected 'Section/Entry=value'")


@check
def cli_set_without_argument():
    expect_no_run([SMALL, '--set'], r'--set needs an argument')


@check
def cli_set_empty_entry_path():
    expect_no_run(['--set', '=630', SMALL], r'--set =630: the entry path before .=. is empty')


@check
def cli_set_empty_path_parts():
    for path in ('Material//Line tension', '/Line tension', 'Material/', 'Material/ /Line tension'):
        expect_no_run(['--set', f'{path}=630', SMALL], re.escape(f'--set {path}=630') + r'.*(empty part|is empty)')


@check
def cli_set_unknown_entry():
    expect_no_run(['--set', 'Material/Line tensoin=630', SMALL], r'--set Material/Line tensoin=630: no such entry')


@check
def cli_unknown_option():
    for option in ('--overwirte', '-q', '--set-foo'):
        expect_no_run([option, SMALL], re.escape(f'unknown option <{option}>'))


@check
def cli_input_is_a_directory():
    expect_no_run([ROOT], r'Cannot open the parameter file <.*>: it is a directory')


@check
def cli_input_missing_or_not_regular():
    expect_no_run([os.path.join(WORK, 'missing.prm')], r'Cannot open the parameter file <.*missing\.prm>: no such file')
    expect_no_run(['/dev/null'], r'Cannot open the parameter file </dev/null>: it is not a regular file')


@check
def cli_two_inputs_or_none():
    expect_no_run([SMALL, SMALL], r'more than one input file')
    expect_no_run(['--quiet'], r'no input file given')


@check
def cli_print_parameters_bad_format():
    expect_no_run(['--print-parameters', 'xml'], r'--print-parameters takes one optional format, prm or json')


# ---- 3. values that make no sense together ----------------------------------------------

GAUSS = 'Material/Gaussian rigidity/'
KAPPA = 'Material/Bending rigidity/'


def expect_combination(settings, regex):
    d = fresh('combination')
    args = ['--quiet'] + TINY + out(d)
    for setting in settings:
        args += ['--set', setting]
    expect(args + [SMALL], 1, regex)
    require(not os.path.exists(d), 'the output directory was created')


@check
def combination_gaussian_rigidity_positive():
    expect_combination([GAUSS + 'Phase A value=0.5'],
                       r'Material/Gaussian rigidity.*Material/Bending rigidity.*-2 kappa < kappa_G <= 0.*'
                       r'phi = 1 \(phase A\).*kappa_G = 0\.5.*\(-2, 0\]')


@check
def combination_gaussian_rigidity_below_minus_two_kappa():
    expect_combination([KAPPA + 'Phase B value=1.5', GAUSS + 'Phase B value=-3'],
                       r'Material/Gaussian rigidity.*phi = -1 \(phase B\).*kappa = 1\.5.*kappa_G = -3.*\(-3, 0\]')


@check
def combination_gaussian_expression_positive_between_phases():
    expect_combination([GAUSS + 'Law=expression', GAUSS + 'Expression=1 - 2*phi^2',
                        GAUSS + 'Derivative expression=-4*phi'],
                       r'Material/Gaussian rigidity.*phi = -0\.7 kappa = 1 and kappa_G = 0\.02')


@check
def combination_bending_rigidity_vanishes_between_phases():
    expect_combination([KAPPA + 'Law=expression', KAPPA + 'Expression=phi^2', KAPPA + 'Derivative expression=2*phi'],
                       r'Material/Bending rigidity.*kappa must be > 0.*kappa = 0 at phi = 0\b')


@check
def combination_bending_rigidity_negative_phase():
    expect_combination([KAPPA + 'Phase B value=-1'],
                       r'Material/Bending rigidity.*kappa must be > 0.*kappa = -1 at phi = -1 \(phase B\)')


@check
def combination_mass_outside_bump_area():
    expect_combination(['Initial phase/Prescribe mass=true', 'Initial phase/Mass=1.2'],
                       r'Initial phase/Mass.*Prescribe mass.*A = 1\.1 \(<Initial shape/Bump area>\).*'
                       r'\(-1\.1, 1\.1\); got Mass = 1\.2')


@check
def combination_mass_of_a_pure_phase_on_the_flat_patch():
    expect_combination(['Initial shape/Shape=flat', 'Initial phase/Prescribe mass=true', 'Initial phase/Mass=-1'],
                       r'Initial phase/Mass.*A = 1 \(flat patch\).*\(-1, 1\); got Mass = -1')


@check
def combination_mass_beyond_cosine_modes_area_bound():
    expect_combination(['Initial shape/Shape=cosine modes', 'Initial shape/Cosine modes=0.1 1 0',
                        'Initial phase/Prescribe mass=true', 'Initial phase/Mass=5'],
                       r'Initial phase/Mass.*A <= 1\.18.*upper bound.*got Mass = 5')


@check
def combination_patch_shape_on_a_closed_surface():
    # A closed surface takes flat or an expression; the bump is the patch's.
    expect_combination(['Mesh/Reference surface=sphere', 'Mesh/Cells per side=4', 'Initial phase/Type=uniform',
                        'Initial shape/Shape=bump'],
                       r'Initial shape/Shape.*bump.*periodic patch.*flat.*expression')


def accepted(path):
    """The shipped input runs (one step): the checks above refuse nothing that is in use."""
    def check_input():
        code, output = run(['--quiet'] + TINY + ['--set', 'Checkpoint/Interval=0']
                           + out(fresh('accepted')) + [path])
        require(code == 0, f'{os.path.relpath(path, ROOT)} is refused (exit code {code})', output)
    check_input.__name__ = 'accepted_' + os.path.splitext(os.path.basename(path))[0]
    return check_input


for _path in sorted(os.path.join(ROOT, 'experiments', f) for f in os.listdir(os.path.join(ROOT, 'experiments'))
                    if f.endswith('.prm')) + [SMALL, os.path.join(os.path.dirname(SMALL), 'sorting.prm')]:
    check(accepted(_path))


# ---- 4. a mesh far too large --------------------------------------------------------------

@check
def memory_mesh_far_too_large():
    start = time.time()
    d = fresh('huge')
    expect(['--quiet', '--set', 'Mesh/Cells per side=4096'] + out(d) + [SMALL], 1,
           r'Mesh/Cells per side> = 4096: the run needs an estimated [0-9.]+ TB of memory.*'
           r'only [0-9.]+ [GT]B is available \(MemAvailable in /proc/meminfo.*--no-memory-check')
    require(time.time() - start < 10, f'the refusal took {time.time() - start:.1f} s (anything allocated?)')
    require(not os.path.exists(d), 'the output directory was created')


@check
def memory_refinement_beyond_the_limit_refused():
    # Local refinement checks the memory before it refines: with <Mesh/Refinement memory
    # limit> below what any process uses (1 MB) no cell flagged for refinement is refined,
    # with one warning; with a high limit the same run refines (928 -> 1024 cells). A limit
    # near the run's own use would make the outcome depend on the machine's libraries.
    budding = os.path.join(ROOT, 'experiments', '7.3-budding.prm')
    args = ['--set', 'Mesh/Cells per side=16', '--set', 'Mesh/Maximum refinement level=1', '--set',
            'Mesh/Adaptivity interval=2', '--set', 'Time stepping/End time=0.006', '--set', 'Output/Write VTU=false', '--set', 'Checkpoint/Interval=0']
    cells = {}
    for limit in ('0.001', '100'):
        d = fresh('memory-limit')
        code, output = run(args + ['--set', f'Mesh/Refinement memory limit={limit}'] + out(d) + [budding])
        require(code == 0, f'limit {limit} GB: exit code {code}', output)
        with open(os.path.join(d, 'statistics.txt')) as f:
            names = f.readline().split()[1:]
            rows = [line.split() for line in f if line.strip() and not line.startswith('#')]
        cells[limit] = [int(float(r[names.index('cells')])) for r in rows]
        warnings = output.count('the mesh is not refined further') + output.count('The mesh is not refined further')
        if limit == '0.001':
            require(warnings == 1 and 'below <Mesh/Refinement memory limit>' in output,
                    f'limit {limit} GB: {warnings} warnings', output)
        else:
            require(warnings == 0, f'limit {limit} GB: a warning', output)
    low, high = cells['0.001'], cells['100']
    # (Coarsening can still add a few cells: p4est keeps neighbours within one level.)
    require(max(high) >= max(low) + 40,
            f'cells below the limit {low}, with a high limit {high}: no refinement was refused')


# ---- 7. errors are the last thing on screen; exit codes -----------------------------------

@check
def errors_failed_run_message_after_timer_table():
    d = fresh('failed')
    output = expect(['--set', 'Cahn-Hilliard/Scheme=explicit', '--set', 'Time stepping/Adaptive=false', '--set',
                     'Time stepping/Time step=1e-2', '--set', 'Time stepping/End time=0.05', '--set',
                     'Output/Write VTU=false'] + out(d) + [SMALL], 2,
                    r'\+-{10}.*Error: the run failed: step failed at t = .*energy would rise')
    require(os.path.exists(os.path.join(d, 'summary.json')), 'no summary.json of the failed run', output)


@check
def steps_fixed_time_step_far_too_large():
    # 7.3 on 16 x 16 input cells: tau = 3 moves the surface 3 cells in its first step, which a
    # semi-implicit step survives without any energy rise (it used to end with exit 0 and
    # a wrong outcome). The bound <Time stepping/Maximum increment> stops it.
    budding = os.path.join(ROOT, 'experiments', '7.3-budding.prm')
    coarse = ['--quiet', '--set', 'Mesh/Cells per side=16', '--set', 'Output/Write VTU=false', '--set',
              'Checkpoint/Interval=0', '--set', 'Time stepping/Maximum time step=3', '--set',
              'Time stepping/Time step=3', '--set', 'Time stepping/End time=3']
    d = fresh('tau-too-large')
    expect(coarse + ['--set', 'Time stepping/Adaptive=false'] + out(d) + [budding], 2,
           r'step failed at t = 0: a vertex would move [0-9.]+ cell sizes in one step \(more than '
           r'<Time stepping/Maximum increment> = 1; 0 there: no bound\); reduce <Time stepping/Time step>, or set <Time stepping/Adaptive> = true')
    with open(os.path.join(d, 'summary.json')) as f:
        summary = json.load(f)
    require(summary['steps'] == 0 and summary['stop_reason'].startswith('step failed'),
            f'summary.json: steps {summary["steps"]}, stop_reason {summary["stop_reason"]!r}')
    # Adaptive steps: the same first step is rejected and retried with a smaller tau.
    d = fresh('tau-too-large-adaptive')
    code, output = run(coarse + ['--set', 'Time stepping/Maximum steps=1'] + out(d) + [budding])
    require(code == 0, f'adaptive run: exit code {code}', output)
    with open(os.path.join(d, 'summary.json')) as f:
        summary = json.load(f)
    require(summary['rejected_steps'] >= 1, f'adaptive run: {summary["rejected_steps"]} rejected steps', output)


@check
def errors_input_error_inside_the_run_is_last():
    expect(['--set', f'Checkpoint/Resume from={WORK}/nonexistent-checkpoint.txt'] + TINY
           + out(fresh('bad-checkpoint')) + [SMALL], 1, r'Error: .*Checkpoint/Resume from.*cannot open the checkpoint')


# ---- 8. --version, --help ---------------------------------------------------------------

@check
def version_and_help():
    code, output = run(['--version'])
    require(code == 0 and re.fullmatch(r'membrane-flow \S+\n', output), f'--version: exit code {code}', output)
    code, output = run(['--help'])
    require(code == 0 and output.startswith('Usage: membrane-flow') and '--overwrite' in output,
            f'--help: exit code {code}', output)


def run_check(function):
    name = function.__name__.replace('_', '.', 1)
    t0 = time.time()
    try:
        function()
        return name, True, f'({time.time() - t0:.1f} s)'
    except Failure as e:
        return name, False, str(e)
    except Exception as e:  # a broken check is a failure too, never a crash of the script
        return name, False, f'{type(e).__name__}: {e}'


def main():
    start = time.time()
    selected = [f for f in CHECKS if not ONLY or ONLY in f.__name__.replace('_', '.', 1)]
    try:
        # Most of a check's time is the start-up of MPI, not computation: run 4 at a time.
        with ThreadPoolExecutor(max_workers=4) as pool:
            for name, ok, detail in pool.map(run_check, selected):
                RESULTS.append((name, ok, detail))
                print(f'ok    {name} {detail}' if ok else f'FAIL  {name}: {detail}', flush=True)
    finally:
        (print(WORK) if os.environ.get("KEEP") else shutil.rmtree(WORK, ignore_errors=True))
    passed = sum(1 for _, ok, _ in RESULTS if ok)
    failed = len(RESULTS) - passed
    print(f'time: {time.time() - start:.1f} s')
    print(f'{passed} passed, {failed} failed')
    return 1 if failed or not RESULTS else 0


if __name__ == '__main__':
    sys.exit(main())
