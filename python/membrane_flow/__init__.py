"""membrane_flow: Python access to membrane-flow (docs/python.md).

Simulation   a run driven from Python: set up from a .prm file and/or a dict of entries,
             step it, read its state as numpy arrays (needs the compiled module, built
             with the program)
load_run     what a run wrote: statistics, summary, parameters, snapshots and their fields
             (pure Python, membrane_flow.run)

The rest is pure Python and needs only the program: launch (the program's path, the
environment and process group of a run), workflow (sweeps, critical values, continuation,
budding time, thresholds), studies, pictures (surface renderings, movies, plots) and docgen
(the generated pages of docs/). `python3 -m membrane_flow <command>` runs them from the
command line (`python3 -m membrane_flow --help` lists the commands).
The compiled module (_core) is loaded on first use of Simulation, Error or code_version.
"""
from .run import (Run, load_parameters, load_run, load_run_info, load_snapshots, load_statistics,
                  load_summary, parse_prm, read_statistics, read_vtu)

_COMPILED = ('Simulation', 'Error', 'code_version')


def __getattr__(name):
    if name not in _COMPILED:
        raise AttributeError(f"module 'membrane_flow' has no attribute {name!r}")
    try:
        from . import _core
        from .simulation import Simulation
        values = {'Simulation': Simulation, 'Error': _core.Error, 'code_version': _core.code_version}
    except ImportError as error:  # the pure-Python part works without the compiled module
        import_error = error

        class Error(RuntimeError):
            pass

        def _missing(*args, **kwargs):
            raise ImportError("membrane_flow's compiled module (_core) is not available: build the project "
                              f"(./scripts/build.sh) with pybind11-dev and python3-dev installed ({import_error})")

        values = {'Simulation': _missing, 'Error': Error, 'code_version': _missing}
    globals().update(values)
    return values[name]


__all__ = ['Simulation', 'Error', 'code_version', 'Run', 'load_run', 'load_statistics', 'load_summary',
           'load_run_info', 'load_parameters', 'load_snapshots', 'parse_prm', 'read_statistics', 'read_vtu']
