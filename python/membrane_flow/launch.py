"""Starting membrane-flow from Python: the one launcher of the package.

- find_executable(): which program to run: an explicit path, else $MEMBRANE_FLOW_EXE
  (`python3 -m membrane_flow --exe PATH <command>` sets it for every command), else the
  program of the build this package belongs to (<build>/membrane-flow next to
  <build>/python/membrane_flow, or build/membrane-flow of the checkout holding
  python/membrane_flow), else `membrane-flow` on PATH.
- environment(): the environment of a run: one OpenMP / OpenBLAS thread per process (runs
  share the cores), and under mpirun as root the two OMPI_ALLOW_RUN_AS_ROOT variables.
- command(): the argument list: the program, its options and input, under `mpirun -np R`
  (or another launcher) for R > 1 ranks.
- start() / run(): a run as its own process group (mpirun and its ranks with it), stdin
  closed; on Linux it gets SIGTERM if the thread that started it dies. kill_group() signals
  the whole group; run() waits, with an optional timeout after which the group gets SIGTERM
  (a run then stops with a checkpoint and its summary) and, after a grace period, SIGKILL.

Pure Python: the compiled part of membrane_flow is not needed."""
import ctypes
import os
import shutil
import signal
import subprocess
import sys

THREAD_VARIABLES = ('OMP_NUM_THREADS', 'OPENBLAS_NUM_THREADS')
ROOT_VARIABLES = ('OMPI_ALLOW_RUN_AS_ROOT', 'OMPI_ALLOW_RUN_AS_ROOT_CONFIRM')
EXECUTABLE_VARIABLE = 'MEMBRANE_FLOW_EXE'
NAME = 'membrane-flow'


def find_executable(exe=None):
    """The path of membrane-flow (see the module's description). Never raises: without any
    candidate it returns 'membrane-flow', which fails with a clear message when started."""
    if exe:
        return exe
    if os.environ.get(EXECUTABLE_VARIABLE):
        return os.environ[EXECUTABLE_VARIABLE]
    package = os.path.dirname(os.path.abspath(__file__))
    top = os.path.dirname(os.path.dirname(package))  # <build> or the checkout
    for candidate in (os.path.join(top, NAME), os.path.join(top, 'build', NAME)):
        if os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return candidate
    return shutil.which(NAME) or NAME


def environment(threads=True, force=True, mpi=False, base=None):
    """The environment of a run: a copy of `base` (default os.environ) with
    OMP_NUM_THREADS=1 and OPENBLAS_NUM_THREADS=1 if `threads` (overriding values already set
    if `force`, else only where unset), and for `mpi` runs as root the variables that let
    Open MPI run as root."""
    env = dict(os.environ if base is None else base)
    if threads:
        for name in THREAD_VARIABLES:
            if force:
                env[name] = '1'
            else:
                env.setdefault(name, '1')
    if mpi and hasattr(os, 'geteuid') and os.geteuid() == 0:
        for name in ROOT_VARIABLES:
            env.setdefault(name, '1')
    return env


def settings(entries):
    """--set options for {'Section/Entry': value} or [(name, value)] or ['Section/Entry=value']."""
    if isinstance(entries, dict):
        entries = entries.items()
    args = []
    for entry in entries:
        args += ['--set', entry if isinstance(entry, str) else f'{entry[0]}={entry[1]}']
    return args


def command(exe, args=(), ranks=1, launcher='mpirun'):
    """[exe, *args], under `<launcher> -np ranks` for ranks > 1."""
    result = [exe] + list(args)
    if ranks > 1:
        result = launcher.split() + ['-np', str(ranks)] + result
    return result


def _parent_death_signal():
    """In the child before exec: SIGTERM when the thread that started it dies (Linux)."""
    try:
        _PRCTL(1, signal.SIGTERM, 0, 0, 0)  # PR_SET_PDEATHSIG
    except Exception:  # noqa: BLE001 -- best effort, never stop the run from starting
        pass


try:
    _PRCTL = ctypes.CDLL(None, use_errno=True).prctl
    _PRCTL.argtypes = [ctypes.c_int, ctypes.c_ulong, ctypes.c_ulong, ctypes.c_ulong, ctypes.c_ulong]
    _PRCTL.restype = ctypes.c_int
    _PREEXEC = _parent_death_signal if sys.platform.startswith('linux') else None
except (OSError, AttributeError):
    _PREEXEC = None


def start(command, stdout=None, stderr=None, cwd=None, env=None, parent_death=True, **kwargs):
    """A run started as its own process group (subprocess.Popen; stdin closed)."""
    return subprocess.Popen(command, stdout=stdout, stderr=stderr, stdin=subprocess.DEVNULL, cwd=cwd, env=env,
                            start_new_session=True, preexec_fn=_PREEXEC if parent_death else None, **kwargs)


def kill_group(process, sig=signal.SIGTERM):
    """Send sig to the run's process group: the program, or mpirun and its ranks."""
    if process is None:
        return
    try:
        os.killpg(process.pid, sig)
    except (ProcessLookupError, PermissionError):
        pass


def run(command, stdout=None, stderr=None, cwd=None, env=None, timeout=None, grace=60.0, **kwargs):
    """Start a run (start()) and wait for it. With a timeout in seconds the group gets
    SIGTERM when it passes, and SIGKILL `grace` seconds later. Returns (exit code, timed out);
    Ctrl-C terminates the run's group and raises KeyboardInterrupt."""
    process = start(command, stdout=stdout, stderr=stderr, cwd=cwd, env=env, **kwargs)
    timed_out = False
    try:
        try:
            code = process.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            timed_out = True
            kill_group(process, signal.SIGTERM)
            try:
                code = process.wait(timeout=grace)
            except subprocess.TimeoutExpired:
                kill_group(process, signal.SIGKILL)
                code = process.wait()
    except KeyboardInterrupt:
        kill_group(process, signal.SIGTERM)
        process.wait()
        raise
    return code, timed_out


def output(command, cwd=None, env=None, timeout=None):
    """Run a command as its own process group and collect its output: a
    subprocess.CompletedProcess with stdout and stderr as text. Past the timeout its group
    gets SIGKILL and subprocess.TimeoutExpired is raised; Ctrl-C terminates its group
    (SIGTERM: a run stops with a checkpoint) and raises KeyboardInterrupt."""
    process = start(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, cwd=cwd, env=env, text=True)
    try:
        out, err = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        kill_group(process, signal.SIGKILL)
        process.communicate()
        raise
    except KeyboardInterrupt:
        kill_group(process, signal.SIGTERM)
        process.communicate()
        raise
    return subprocess.CompletedProcess(command, process.returncode, out, err)


def interruptible(main, name, what):
    """Runs main(argv) and turns a Ctrl-C that arrives before any `what` started (the runs catch
    their own) into a message and the exit code 130."""
    def run(argv=None):
        try:
            return main(argv)
        except KeyboardInterrupt:
            print(f'{name}: interrupted before any {what} started', file=sys.stderr)
            return 130
    return run
