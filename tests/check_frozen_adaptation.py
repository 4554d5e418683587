#!/usr/bin/python3
"""Mesh adaptation on a frozen surface is a fixed point.

The run directory holds a run resumed from a budded state with a time step so small
(1e-10) that the surface does not move, adapting after every step. The first adaptation
may still refine or coarsen (the resumed run's indicators see the state once); after it
the mesh must stay as it is: same number of cells, and an energy change of each further
adaptation at round-off level. An indicator that reacts to its own refinement (noise of the
discrete curvature next to a coarse-fine border) refines a ring of cells around the refined
region at every adaptation, each raising the energy.
The frozen steps are the rows with 0 < tau < 1e-9.
Usage: check_frozen_adaptation.py <dir> [--min-adaptations N]"""
import argparse
import os
import sys

import numpy as np

from membrane_flow.run import load_statistics  # noqa: E402 (PYTHONPATH: the build's python/)
from checks import Checks  # tests/checks.py, next to this script

parser = argparse.ArgumentParser()
parser.add_argument("dir")
parser.add_argument("--min-adaptations", type=int, default=4)
args = parser.parse_args()

column = load_statistics(args.dir)
after = (column["tau"] > 0) & (column["tau"] < 1e-9)
steps, cells = column["step"][after], column["cells"][after]
adaptations, jump = column["adaptations"][after], column["adaptation_energy_jump"][after]
energy = column["energy"][after]

check = Checks()

n = int(adaptations[-1] - adaptations[0]) if len(adaptations) else 0
check(len(steps) > 0 and n >= args.min_adaptations,
      f"{n} adaptations in {len(steps)} steps after the resume (at least {args.min_adaptations} expected)")
if len(steps) > 0:
    # rows after the first adaptation that follows the resume
    first = np.flatnonzero(adaptations > adaptations[0])
    settled = slice(first[0], None) if len(first) else slice(len(steps), None)
    check(len(np.unique(cells[settled])) == 1,
          f"cells after the first adaptation: {sorted(set(int(c) for c in cells[settled]))} (one value expected)")
    further = np.abs(np.diff(jump[settled])).sum() if len(jump[settled]) > 1 else 0.0
    check(further <= 1e-9 * np.abs(energy).max(),
          f"energy change of the further adaptations {further:.3g} <= 1e-9 x energy {np.abs(energy).max():.6g}")
sys.exit(check.exit_code())
