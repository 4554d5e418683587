#!/usr/bin/python3
"""Check a finished run directory (statistics.txt and summary.json).
Usage: check_run.py <dir> [--direction +1|-1] [--max-drift X] [--outcome NAME] [--min-rejected N] [--stop-reason REGEX]
       [--max-mass-drift X] [--max-area-error X] [--min-adaptations N] [--min-protrusion X]
Always asserts: the run did not fail, and the discrete energy never increases
from one accepted step to the next (beyond 1e-10 relative). Mesh adaptations are not
steps of the gradient flow: their energy changes (column adaptation_energy_jump,
cumulative) are taken out before the comparison, and so is the work p dV done on a
vesicle by a moving volume target or a prescribed pressure (column pressure_work)."""
import argparse
import sys

import numpy as np

from membrane_flow.run import load_statistics, load_summary  # PYTHONPATH: the build's python/
from checks import Checks  # tests/checks.py, next to this script

parser = argparse.ArgumentParser()
parser.add_argument("dir")
parser.add_argument("--direction", type=int)
parser.add_argument("--max-drift", type=float)
parser.add_argument("--outcome")
parser.add_argument("--min-rejected", type=int)
parser.add_argument("--stop-reason", help="regular expression the stop reason must match")
parser.add_argument("--min-adaptations", type=int, help="mesh adaptations the run must have made")
parser.add_argument("--max-mass-drift", type=float, help="bound on |mass_drift| in every row")
parser.add_argument("--min-protrusion", type=float, help="lower bound on the final domain_protrusion")
parser.add_argument("--max-area-error", type=float, help="bound on the local vertex-area error area_error in every row")
parser.add_argument("--min-corner-sine", type=float, help="lower bound on min_corner_sine in every row")
parser.add_argument("--fluctuating", action="store_true",
                    help="a run at k_BT > 0: its energy fluctuates, so the descent is not checked")
args = parser.parse_args()

column = load_statistics(args.dir)
summary = load_summary(args.dir)

check = Checks()

check(not summary["failed"], f"run finished: {summary['stop_reason']} after {summary['steps']} steps")
energy = column["energy"]
# F - (the work p dV of a moving volume target or a prescribed pressure) decreases.
# With Mesh motion = ale the physical steps descend; what the mesh motion changes is recorded apart.
flow_energy = energy - column.get("adaptation_energy_jump", 0 * energy) - column.get("pressure_work", 0 * energy) \
    - np.cumsum(column.get("mesh_motion_energy", 0 * energy))
rises = np.diff(flow_energy) / np.abs(energy[:-1])
if not args.fluctuating:
    check(len(energy) > 5 and rises.max() <= 1e-10,
          f"energy {energy[0]:.6g} -> {energy[-1]:.6g} over {len(energy) - 1} steps, largest relative rise {rises.max():.2e}")
if args.max_drift is not None:
    area, mass = np.abs(column["area_drift"]).max(), np.abs(column["mass_drift"]).max()
    check(max(area, mass) <= args.max_drift, f"area drift {area:.2e}, mass drift {mass:.2e} <= {args.max_drift:g}")
if args.direction is not None:
    check(summary["bud_direction"] == args.direction,
          f"bud direction {summary['bud_direction']:+g} (expected {args.direction:+d})")
if args.min_rejected is not None:
    check(summary["rejected_steps"] >= args.min_rejected,
          f"{summary['rejected_steps']} rejected steps (at least {args.min_rejected} expected)")
# Every rejected step is counted under one reason.
kinds = summary.get("rejections", {})
check(set(kinds) == {"energy_rise", "local_error", "large_move", "degenerate_cell", "solver_failure", "non_finite"}
      and sum(kinds.values()) == summary["rejected_steps"],
      f"rejections by reason {kinds} add up to the {summary['rejected_steps']} rejected steps")
if args.stop_reason is not None:
    import re
    check(re.search(args.stop_reason, summary["stop_reason"]) is not None,
          f"stop reason '{summary['stop_reason']}' matches /{args.stop_reason}/")
if args.min_adaptations is not None:
    n = int(column["adaptations"][-1])
    check(n >= args.min_adaptations, f"{n} mesh adaptations (at least {args.min_adaptations} expected), cells "
          f"{int(column['cells'].min())}-{int(column['cells'].max())}")
if args.max_mass_drift is not None:
    drift = np.abs(column["mass_drift"]).max()
    check(drift <= args.max_mass_drift, f"mass drift {drift:.2e} <= {args.max_mass_drift:g} in every row")
if args.max_area_error is not None:
    error = column["area_error"].max()
    check(error <= args.max_area_error, f"local area error {error:.2e} <= {args.max_area_error:g} in every row")
if args.min_corner_sine is not None:
    sine = column["min_corner_sine"].min()
    check(sine >= args.min_corner_sine, f"smallest corner sine {sine:.3f} >= {args.min_corner_sine:g} in every row")
if args.min_protrusion is not None:
    check(summary["domain_protrusion"] >= args.min_protrusion,
          f"domain protrusion {summary['domain_protrusion']:.3f} >= {args.min_protrusion:g} "
          f"(neck ratio {summary['neck_ratio']:.3f})")
if args.outcome is not None:
    check(summary["outcome"] == args.outcome, f"outcome '{summary['outcome']}' (expected '{args.outcome}')")
sys.exit(check.exit_code())
