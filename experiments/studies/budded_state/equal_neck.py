#!/usr/bin/python3
"""Energies of the curvature-scaled runs (curvature_scaled.json) at equal neck radius: the first time after t = 0.5
that neck_radius falls to r, by linear interpolation between the rows of each run's statistics.txt, and the observed
order p = log2((E1 - E2) / (E2 - E3)) of the total, bending and line energy. Adds them to curvature_scaled.json.
Usage (from the repository root): /usr/bin/python3 experiments/studies/budded_state/equal_neck.py"""
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "..", "python"))
from membrane_flow.run import load_statistics  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
RUNS = "results/studies/budded-cr/L{}"
RADII = (0.13, 0.12, 0.11, 0.10)


def at_neck(column, radius, values):
    later = column["time"] > 0.5
    neck, v = column["neck_radius"][later], values[later]
    below = np.nonzero(neck <= radius)[0]
    if len(below) == 0 or below[0] == 0:
        return None
    i = below[0]
    f = (neck[i - 1] - radius) / (neck[i - 1] - neck[i])
    return float(v[i - 1] + f * (v[i] - v[i - 1]))


columns = [load_statistics(RUNS.format(level)) for level in (1, 2, 3)]
rows = []
for radius in RADII:
    row = {"neck_radius": radius}
    for name, of in (("energy", lambda c: c["energy"]), ("bending", lambda c: c["bending_energy"]),
                     ("line", lambda c: c["gradient_energy"] + c["well_energy"])):
        values = [at_neck(c, radius, of(c)) for c in columns]
        d1, d2 = (values[0] - values[1], values[1] - values[2]) if None not in values else (0, 0)
        row[name] = values
        row[name + "_order"] = math.log2(d1 / d2) if d1 * d2 > 0 else None
    rows.append(row)
    print(f"| {radius} | " + " | ".join(
        f"{', '.join(f'{v:.4f}' for v in row[n])} | " + (f"{row[n + '_order']:.2f}" if row[n + '_order'] is not None
                                                        else "none") for n in ("energy", "bending", "line")) + " |")
path = os.path.join(HERE, "curvature_scaled.json")
with open(path) as f:
    data = json.load(f)
data["equal_neck_radius"] = rows
with open(path, "w") as f:
    json.dump(data, f, indent=1)
