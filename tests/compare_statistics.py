#!/usr/bin/python3
"""Assert that two statistics.txt files agree column by column to a tolerance
relative to the column's magnitude, or absolute for columns of magnitude below 1
(drifts are round-off-sized). Timing columns are excluded, and so is step_error: it needs
the previous step's increments, which a checkpoint does not hold, so it is undefined (-1) on
the first step after a resume (docs/model.md). With --shared, columns that only one file has
(a run of an older version) are listed and left out instead of failing the comparison.
Usage: compare_statistics.py a b [tol] [--shared]"""
import sys
import numpy as np

from membrane_flow.run import read_statistics  # PYTHONPATH: the build's python/


shared = '--shared' in sys.argv
args = [arg for arg in sys.argv[1:] if arg != '--shared']
columns_a, columns_b = read_statistics(args[0]), read_statistics(args[1])
if shared:
    only = sorted(set(columns_a) ^ set(columns_b))
    if only:
        print("columns in one file only (left out): " + ", ".join(only))
    columns_a = {name: column for name, column in columns_a.items() if name in columns_b}
    columns_b = {name: columns_b[name] for name in columns_a}
names_a, a = list(columns_a), np.column_stack(list(columns_a.values()))
names_b, b = list(columns_b), np.column_stack(list(columns_b.values()))
tol = float(args[2]) if len(args) > 2 else 1e-8
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
