#!/usr/bin/python3
"""The energy that mesh adaptation adds while a broad initial profile sharpens.

Two runs of the 7.3 bump start at sigma = 1000 with one level of refinement, through the
sharpening of phi (t <= 0.003): one refines only sharpened interfaces, so its mesh is refined
while the interface forms, and each refinement raises the bending energy (about 0.49 in three
adaptations); the other refines the broad profile before the first step (Refine broad
profiles) and only coarsens afterwards. The check asserts both numbers: the second adds less
than `--most` (measured 0.047), the first at least `--least`, so that the comparison shows
what the option removes and fails if refinement during the sharpening stopped adding energy
for another reason (then the bound on the second run proves nothing).
Usage: check_adaptation_jumps.py <broad run dir> <plain run dir> [--most X] [--least Y]"""
import argparse
import json
import os
import sys

from checks import Checks  # tests/checks.py, next to this script

parser = argparse.ArgumentParser()
parser.add_argument("broad")
parser.add_argument("plain")
parser.add_argument("--most", type=float, default=0.1)
parser.add_argument("--least", type=float, default=0.3)
args = parser.parse_args()


def summary(directory):
    with open(os.path.join(directory, "summary.json")) as f:
        return json.load(f)


broad, plain = summary(args.broad), summary(args.plain)
check = Checks()
for name, run, condition, bound in (("broad profile refined first", broad, lambda j: j <= args.most, f"<= {args.most}"),
                                    ("refined as the interface sharpens", plain, lambda j: j >= args.least,
                                     f">= {args.least}")):
    jump = run["adaptation_energy_jump"]
    check(condition(jump) and run["adaptations"] >= 1,
          f"{name}: {run['adaptations']} adaptations, energy jump {jump:.4g} (expected {bound})")
sys.exit(check.exit_code())
