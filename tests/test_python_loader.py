#!/usr/bin/python3
"""membrane_flow's loader of finished runs (pure Python) on a run the program wrote.
Usage: test_python_loader.py <run directory> <line tension the run was given>

The statistics columns equal the file's numbers; the summary's energy, steps and time
are the last statistics row; the parameters hold the value given with --set; the PVD
lists one snapshot per output time with the VTU files that exist, at the times of
statistics rows; the last snapshot's fields span the statistics' phi and gamma ranges
and its cells are the run's."""
import os
import sys

import numpy as np

import membrane_flow as mf
from checks import NARROW, Checks  # tests/checks.py, next to this script

directory, line_tension = sys.argv[1], float(sys.argv[2])
check = Checks(*NARROW)


run = mf.load_run(directory)
stats, summary = run.statistics, run.summary
with open(os.path.join(directory, 'statistics.txt')) as f:
    header = f.readline().lstrip('#').split()
    raw = np.loadtxt(f)
check(list(stats) == header and all(np.array_equal(stats[n], raw[:, i], equal_nan=True) for i, n in enumerate(header)),
      f"{len(header)} statistics columns of {len(raw)} rows as in the file")
for key in ['energy', 'area', 'mass', 'bud_height', 'cells']:
    check(summary[key] == stats[key][-1], f"summary {key} {summary[key]} = last statistics row")
check(summary['steps'] == stats['step'][-1] and summary['time'] == stats['time'][-1],
      f"summary steps {summary['steps']}, t = {summary['time']} = last row")
check(float(run.parameters['Material/Line tension']) == line_tension,
      f"parameters.prm: Material/Line tension = {run.parameters['Material/Line tension']}")
check(run.run_info['cells'] == stats['cells'][0] and run.run_info['parameter_file'] == 'parameters.prm',
      f"run_info.json: {run.run_info['cells']} cells")

snapshots = run.snapshots
interval = float(run.parameters['Output/Interval'])
expected = int(round(summary['time'] / interval)) + 1
check(len(snapshots) == expected, f"{len(snapshots)} snapshots, expected {expected} (t = 0 and every {interval})")
check(all(os.path.isfile(path) for _, path in snapshots), "every listed VTU exists")
# (the PVD's times have 6 significant digits, the VTU's single precision)
check(all(np.min(np.abs(stats['time'] - t)) <= 1e-6 * t for t in run.times), "snapshot times are statistics times")
last = run.snapshot(-1)
check(abs(last['time'] - summary['time']) <= 1e-6 * summary['time'] and last['file'] == run.snapshots[-1][1],
      f"last snapshot at t = {last['time']}")
vtu_time = mf.read_vtu(run.snapshots[-1][1])['time']
check(abs(vtu_time - summary['time']) <= 1e-6 * summary['time'], f"the VTU records t = {vtu_time}")
check(len(last['cells']) == summary['cells'], f"{len(last['cells'])} cells in the last snapshot")
phi = last['point_data']['phi']
gamma = last['point_data']['gamma']
check(abs(phi.min() - stats['phi_min'][-1]) <= 1e-6 and abs(phi.max() - stats['phi_max'][-1]) <= 1e-6,
      f"snapshot phi range [{phi.min():.6f}, {phi.max():.6f}] = statistics")
check(abs(gamma.min() - stats['gamma_min'][-1]) <= 1e-6 * max(1, abs(gamma.min())),
      f"snapshot gamma min {gamma.min():.6g} = statistics {stats['gamma_min'][-1]:.6g}")
first = run.snapshot(0.0)
check(np.ptp(first['point_data']['phi']) > 0 and first['points'].shape[1] == 3, "the snapshot nearest t = 0")

# The rest of the package reads runs with the same reader (membrane_flow.run).
from membrane_flow.workflow.budding_time import budding_time_of_run  # noqa: E402
check(mf.run.load_statistics is mf.load_statistics, "membrane_flow.run is the reader of the package")
budding_time_of_run(directory)  # reads statistics and summary through it

for bad in [lambda: mf.load_run('/nonexistent/run'), lambda: mf.read_vtu('/nonexistent/surface.vtu')]:
    try:
        bad()
        check(False, "a missing file raises")
    except FileNotFoundError as e:
        check(True, f"FileNotFoundError: {e}")

print(f"{check.failed} failures")
sys.exit(check.exit_code())
