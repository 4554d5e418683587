#!/usr/bin/python3
"""The energy mesh adaptation leaves in the state (Mesh/Measure carried energy).

Two runs of the same adaptive 7.3 start through the sharpening of phi, one with Measure carried
energy. The measurement steps the old mesh as a trial that is discarded, so the two runs must be
the same run: times, energies, cells and jumps of every row equal to 1e-12. Every adaptation is
compared with its twin step (carried_measured = adaptations; no step is rejected here). While the
interface sharpens, each refinement raises F at the transfer (adaptation_energy_jump: bending
energy of the new vertices' mesh-scale offsets, about +1.0 in all), and the first step removes that
and more: the finer mesh resolves the steepening profile, so the energy the state carries falls
(measured -0.25). A twin that compared the wrong energies (before the step, or of the same mesh)
would give the jump or 0 instead.
Usage: check_carried_energy.py <run with the measurement> <the same run without> [--least-jump J]"""
import argparse
import sys

import numpy as np

from membrane_flow.run import load_statistics  # noqa: E402 (PYTHONPATH: the build's python/)
from checks import Checks  # tests/checks.py, next to this script

parser = argparse.ArgumentParser()
parser.add_argument("measured")
parser.add_argument("plain")
parser.add_argument("--least-jump", type=float, default=0.5)
args = parser.parse_args()

m, p = load_statistics(args.measured), load_statistics(args.plain)
check = Checks()
same_rows = len(m["time"]) == len(p["time"])
check(same_rows, f"same number of rows ({len(m['time'])}, {len(p['time'])})")
if same_rows:
    for c in ("time", "energy", "cells", "adaptation_energy_jump"):
        d = np.max(np.abs(m[c] - p[c]) / np.maximum(1, np.abs(p[c])))
        check(d <= 1e-12, f"{c} equal with and without the measurement (largest difference {d:.2g})")
adaptations, measured = int(m["adaptations"][-1]), int(m["carried_measured"][-1])
check(adaptations >= 3 and measured == adaptations, f"{measured} of {adaptations} adaptations compared with their twin step")
jump, carried = m["adaptation_energy_jump"][-1], m["adaptation_energy_carried"][-1]
check(jump >= args.least_jump, f"jumps at the transfers {jump:+.4f} (expected >= {args.least_jump})")
check(carried < 0, f"energy carried after the first steps {carried:+.4f} (expected < 0: refinement lowers it)")
steps = np.diff(m["adaptation_energy_carried"])
check(np.max(steps) <= 1e-3, f"largest carried by one adaptation {np.max(steps):+.2e} (expected <= 1e-3)")
sys.exit(check.exit_code())
