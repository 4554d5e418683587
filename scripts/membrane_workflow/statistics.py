"""Reading a run's statistics.txt and summary.json: the loader of the Python package
(python/membrane_flow/results.py), taken from this source tree without needing the
compiled module or an installed membrane_flow."""
import importlib.util
import os

_path = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'python', 'membrane_flow',
                     'results.py')
_spec = importlib.util.spec_from_file_location('_membrane_flow_results', _path)
_results = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_results)

load_statistics = _results.load_statistics
load_summary = _results.load_summary
