#!/usr/bin/python3
"""Energy added by mesh adaptation while the 7.3 bump profile sharpens, with and without
Mesh/Refine broad profiles, at 1, 2 and 3 levels of refinement (sigma = 1000, t <= 0.1).

Runs the six cases that have no summary.json yet (results/studies/adaptation-sharpening/,
one at a time), then writes results.json and prints the table of README.md.
Usage (from the repository root): /usr/bin/python3 experiments/studies/adaptation_sharpening/study.py [--exe PATH]"""
import argparse
import json
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "..", "python"))
from membrane_flow.run import load_statistics  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = "results/studies/adaptation-sharpening"
CELLS_PER_XI = {1: 1.5, 2: 3, 3: 6}  # as in docs/mesh-convergence.md and docs/branches.md

parser = argparse.ArgumentParser()
parser.add_argument("--exe", default="build/membrane-flow")
args = parser.parse_args()

rows = []
for level in (1, 2, 3):
    for broad in ("false", "true"):
        directory = f"{OUT}/L{level}-broad-{broad}"
        if not os.path.exists(os.path.join(directory, "summary.json")):
            subprocess.run([args.exe, "--quiet", "--overwrite", "experiments/7.3-budding.prm",
                            "--set", "Material/Line tension=1000", "--set", "Time stepping/End time=0.1",
                            "--set", f"Mesh/Maximum refinement level={level}",
                            "--set", f"Mesh/Interface cells per xi={CELLS_PER_XI[level]}",
                            "--set", f"Mesh/Refine broad profiles={broad}", "--set", "Output/Write VTU=false",
                            "--set", "Checkpoint/Interval=0", "--set", f"Output/Directory={directory}"],
                           check=True, env=dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1"))
        column = load_statistics(directory)
        with open(os.path.join(directory, "summary.json")) as f:
            summary = json.load(f)
        t, cumulative = column["time"], column["adaptation_energy_jump"]
        jumps = np.diff(cumulative, prepend=0.0)
        adapted = np.diff(column["adaptations"], prepend=0.0) > 0
        early = t <= 0.05
        rows.append({"level": level, "refine_broad_profiles": broad == "true",
                     "adaptations": int(column["adaptations"][-1]),
                     "jump_total": float(cumulative[-1]),
                     "jump_until_0.05": float(jumps[early].sum()),
                     "jump_after_0.05": float(jumps[~early].sum()),
                     "largest_jump": float(np.abs(jumps[adapted]).max()) if adapted.any() else 0.0,
                     "initial_cells": int(column["cells"][0]), "final_cells": int(column["cells"][-1]),
                     "energy": float(column["energy"][-1]), "steps": int(column["step"][-1]),
                     "wall_seconds": float(column["wall_seconds"][-1]),
                     "code_version": summary.get("code_version")})

with open(os.path.join(HERE, "results.json"), "w") as f:
    json.dump({"setup": "experiments/7.3-budding.prm, Line tension 1000, End time 0.1",
               "interface_cells_per_xi": CELLS_PER_XI, "runs": rows}, f, indent=1)

print("| levels | Refine broad profiles | adaptations | jumps t <= 0.05 | jumps 0.05 < t <= 0.1 | largest | "
      "cells at t = 0 / 0.1 | energy at t = 0.1 | wall time |")
print("|---|---|---|---|---|---|---|---|---|")
for r in rows:
    print(f"| {r['level']} | {'true' if r['refine_broad_profiles'] else 'false'} | {r['adaptations']} | "
          f"{r['jump_until_0.05']:+.4f} | {r['jump_after_0.05']:+.4f} | {r['largest_jump']:.4f} | "
          f"{r['initial_cells']} / {r['final_cells']} | {r['energy']:.4f} | {r['wall_seconds']:.0f} s |")
