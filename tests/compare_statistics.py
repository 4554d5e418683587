#!/usr/bin/python3
"""Assert that two statistics.txt files agree column by column to a tolerance
relative to the column's magnitude, or absolute for columns of magnitude below 1
(drifts are round-off-sized). Timing columns are excluded, and so is step_error: it needs
the previous step's increments, which a checkpoint does not hold, so it is undefined (-1) on
the first step after a resume (docs/model.md).
Usage: compare_statistics.py a b [tol]"""
import sys
import numpy as np

from membrane_flow.run import read_statistics  # PYTHONPATH: the build's python/


def load(path):
    columns = read_statistics(path)
    return list(columns), np.column_stack(list(columns.values()))

names_a, a = load(sys.argv[1])
names_b, b = load(sys.argv[2])
tol = float(sys.argv[3]) if len(sys.argv) > 3 else 1e-8
assert names_a == names_b, f"columns differ: {names_a} vs {names_b}"
assert a.shape == b.shape, f"shapes differ: {a.shape} vs {b.shape}"
worst = 0.0
for i, name in enumerate(names_a):
    if name.endswith('seconds') or name == 'step_error':
        continue
    scale = max(np.max(np.abs(a[:, i])), 1.0)
    diff = np.max(np.abs(a[:, i] - b[:, i])) / scale
    print(f"{name:20s} max relative difference {diff:.3e}")
    worst = max(worst, diff)
print(f"worst {worst:.3e}, tolerance {tol:.1e}")
sys.exit(0 if worst <= tol else 1)
