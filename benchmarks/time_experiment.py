#!/usr/bin/python3
"""Time one full experiment run and report the cost per step by phase.

Runs membrane-flow on an input file (VTU output off, everything else as in the
file), reads the run's wall-time table and statistics, and prints: total wall
time, accepted and rejected steps, and milliseconds per accepted step for
assembly, solves, grid control, geometry and the rest.

Usage: time_experiment.py <membrane-flow> <input.prm> [output-dir] [--set 'Section/Entry=value' ...]
Example: benchmarks/time_experiment.py build/membrane-flow experiments/7.3-budding.prm results/benchmark \
             --set "Mesh/Maximum refinement level=0"
"""
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python"))
from membrane_flow.run import read_timer_table  # noqa: E402

exe, prm = sys.argv[1], sys.argv[2]
extra = sys.argv[3:]
out = extra.pop(0) if extra and not extra[0].startswith("--") else "results/benchmark"
log = subprocess.run([exe, "--overwrite", "--set", "Output/Write VTU=false", "--set", f"Output/Directory={out}", *extra, prm],
                     check=True, capture_output=True, text=True).stdout
sections, total = read_timer_table(log)
with open(f"{out}/summary.json") as f:
    summary = json.load(f)
steps = summary["steps"]
groups = {
    "assembly": ["Cahn-Hilliard assembly", "shape assembly"],
    "solves": ["Cahn-Hilliard solve", "shape solve"],
    "grid control (incl. its geometry)": ["grid control"],
    "geometry": ["geometry"],
    "statistics": ["statistics"],
}
print(f"{prm}: {summary['stop_reason']}, outcome {summary['outcome']}")
print(f"wall time {total:.1f} s, {steps} accepted steps, {summary['rejected_steps']} rejected, t = {summary['time']:.4g}")
print(f"{'phase':36s} {'total s':>9s} {'ms/step':>9s} {'share':>7s}")
accounted = 0
for name, keys in groups.items():
    seconds = sum(sections.get(k, 0) for k in keys)
    accounted += seconds
    print(f"{name:36s} {seconds:9.2f} {1000 * seconds / steps:9.1f} {100 * seconds / total:6.1f}%")
    for k in keys:
        if len(keys) > 1 and k in sections:
            print(f"  {k:34s} {sections[k]:9.2f} {1000 * sections[k] / steps:9.1f}")
print(f"{'other (setup, output, checkpoints)':36s} {total - accounted:9.2f} {1000 * (total - accounted) / steps:9.1f} "
      f"{100 * (total - accounted) / total:6.1f}%")
