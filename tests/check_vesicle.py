#!/usr/bin/python3
"""Check the vesicle columns of a finished run (statistics.txt and summary.json).
Usage: check_vesicle.py <dir> [--max-step-volume-drift X] [--max-volume-drift X]
                               [--laplace-pressure VALUE --tolerance X] [--min-reduced-volume-change X]
Always asserts: the discrete Gauss map covers 4 pi (discrete Gauss-Bonnet) in every row to 1e-10,
and summary.json carries volume, reduced_volume, pressure and integral_K."""
import argparse
import sys

import numpy as np

from membrane_flow.run import load_statistics, load_summary  # PYTHONPATH: the build's python/
from checks import Checks  # tests/checks.py, next to this script

parser = argparse.ArgumentParser()
parser.add_argument("dir")
parser.add_argument("--max-step-volume-drift", type=float,
                    help="bound on the change of (V - V_target) / V_0 per step (|V_m+1 - V_m| / V_0 for a fixed target)")
parser.add_argument("--max-volume-drift", type=float, help="bound on |V - V_target| / V_0 in every row")
parser.add_argument("--laplace-pressure", type=float, help="expected last laplace_pressure")
parser.add_argument("--tolerance", type=float, default=1e-2, help="relative tolerance of --laplace-pressure")
args = parser.parse_args()

column = load_statistics(args.dir)
summary = load_summary(args.dir)

check = Checks()

gauss = np.abs(column["gauss_map_area"] - 4 * np.pi).max()
check(gauss < 1e-10, f"Gauss map area - 4 pi: {gauss:.2e} in every row")
check(all(k in summary for k in ("volume", "reduced_volume", "pressure", "integral_K")),
      "summary.json has volume, reduced_volume, pressure, integral_K")
volume = column["volume"]
if args.max_step_volume_drift is not None:
    step = np.abs(np.diff(column["volume_drift"])).max()  # the target moves when it is ramped
    check(step <= args.max_step_volume_drift, f"volume change per step {step:.2e} <= {args.max_step_volume_drift:g}")
if args.max_volume_drift is not None:
    drift = np.abs(column["volume_drift"]).max()
    check(drift <= args.max_volume_drift, f"|V - V_target| / V_0 {drift:.2e} <= {args.max_volume_drift:g}")
if args.laplace_pressure is not None:
    value = column["laplace_pressure"][-1]
    error = abs(value - args.laplace_pressure) / max(abs(args.laplace_pressure), 1e-300)
    check(error <= args.tolerance, f"laplace_pressure {value:.6g} against {args.laplace_pressure:.6g} "
          f"(relative error {error:.2e} <= {args.tolerance:g})")
sys.exit(check.exit_code())
