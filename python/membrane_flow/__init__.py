"""membrane_flow: Python access to membrane-flow (docs/python.md).

Simulation   a run driven from Python: set up from a .prm file and/or a dict of entries,
             step it, read its state as numpy arrays (needs the compiled module, built
             with the program)
load_run     what a run wrote: statistics, summary, parameters, snapshots and their fields
             (pure Python)
"""
from .results import (Run, load_parameters, load_run, load_run_info, load_snapshots, load_statistics,
                      load_summary, parse_prm, read_statistics, read_vtu)

try:
    from ._core import Error, code_version
    from .simulation import Simulation
except ImportError as _error:  # the pure-Python part works without the compiled module
    _import_error = _error

    class Error(RuntimeError):
        pass

    def _missing(*args, **kwargs):
        raise ImportError("membrane_flow's compiled module (_core) is not available: build the project "
                          f"(./scripts/build.sh) with pybind11-dev and python3-dev installed ({_import_error})")

    Simulation = code_version = _missing

__all__ = ['Simulation', 'Error', 'code_version', 'Run', 'load_run', 'load_statistics', 'load_summary',
           'load_run_info', 'load_parameters', 'load_snapshots', 'parse_prm', 'read_statistics', 'read_vtu']
