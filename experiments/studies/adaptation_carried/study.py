#!/usr/bin/python3
"""The energy mesh adaptation leaves in the state, against its jump at the transfer: both 7.3 branches
followed at 1, 2 and 3 levels of refinement with Mesh/Measure carried energy, from the initial state.

Every adaptation is compared with a twin step on the old mesh: `adaptation_energy_jump` sums F right
after each transfer minus F before it, `adaptation_energy_carried` sums F after the first step on the
new mesh minus F after the same step on the old one. Runs the follows that have no branch.json yet
(results/studies/branches-carried/level<L>/<down|up>, two side by side), and the two-level run at
sigma = 1000 with Curvature resolution 0.15 (many refinements of a curved neck), then writes
results.json and prints the tables of README.md.
Usage (from the repository root): /usr/bin/python3 experiments/studies/adaptation_carried/study.py [--exe PATH]"""
import argparse
import json
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "..", "python"))
from membrane_flow.run import load_statistics  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = "results/studies/branches-carried"
CELLS_PER_XI = {1: 1.5, 2: 3, 3: 6}  # as in docs/branches.md
VALUES = {"down": ["1000", "800", "725", "700", "675", "650"], "up": ["600", "650", "675", "700", "725"]}
SHARPENING_END = 0.05  # as in docs/branches.md
ENV = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1",
           PYTHONPATH=os.path.join(HERE, "..", "..", "..", "python"))

parser = argparse.ArgumentParser()
parser.add_argument("--exe", default="build/membrane-flow")
args = parser.parse_args()


def follow_command(level, direction):
    return ["/usr/bin/python3", "-m", "membrane_flow", "continuation", "follow", "experiments/7.3-budding.prm",
            "Material/Line tension", *VALUES[direction], "--output", f"{OUT}/level{level}/{direction}",
            "--classify", "protrusion:0.95", "--max-time", "3", "--plateau", "1e-3", "--plateau-time", "0.3",
            "--set", "Output/Write VTU=false", "--set", f"Mesh/Maximum refinement level={level}",
            "--set", f"Mesh/Interface cells per xi={CELLS_PER_XI[level]}",
            "--set", "Mesh/Measure carried energy=true", "--exe", args.exe]


CURVED = f"{OUT}/curvature-0.15"
CURVED_COMMAND = [args.exe, "--quiet", "--overwrite", "experiments/7.3-budding.prm",
                  "--set", "Material/Line tension=1000", "--set", "Time stepping/End time=3.1",
                  "--set", "Time stepping/Equilibrium rate=0", "--set", "Mesh/Maximum refinement level=2",
                  "--set", "Mesh/Interface cells per xi=3", "--set", "Mesh/Curvature resolution=0.15",
                  "--set", "Mesh/Measure carried energy=true", "--set", "Output/Write VTU=false",
                  "--set", "Checkpoint/Interval=0", "--set", f"Output/Directory={CURVED}"]

for level in (3, 2, 1):
    missing = [d for d in ("down", "up") if not os.path.exists(f"{OUT}/level{level}/{d}/branch.json")]
    running = [subprocess.Popen(follow_command(level, d), env=ENV) for d in missing]
    if any(p.wait() for p in running):
        sys.exit("a follow failed")
if not os.path.exists(os.path.join(CURVED, "summary.json")):
    subprocess.run(CURVED_COMMAND, check=True, env=ENV)


def split(column, end=None):
    """Jumps and carried energies of the adaptations up to row `end`, for t <= SHARPENING_END and after."""
    t = column["time"][:end]
    jump = np.diff(column["adaptation_energy_jump"][:end], prepend=0.0)
    carried = np.diff(column["adaptation_energy_carried"][:end], prepend=0.0)
    adapted = np.diff(column["adaptations"][:end], prepend=0.0) > 0
    measured = np.diff(column["carried_measured"][:end], prepend=0.0) > 0
    early = t <= SHARPENING_END
    out = {}
    for name, part in (("sharpening", early), ("after", ~early)):
        out[name] = {"adaptations": int(adapted[part].sum()), "measured": int(measured[part].sum()),
                     "jump": float(jump[part].sum()), "carried": float(carried[part].sum()),
                     "largest_jump": float(np.abs(jump[part & adapted]).max()) if (part & adapted).any() else 0.0,
                     "largest_carried": float(np.abs(carried[part & measured]).max()) if (part & measured).any() else 0.0}
    return out


def summarize(column, energy):
    s = split(column)
    return dict(s, final_energy=float(energy))


REFERENCE = "results/studies/branches-gb"  # the follows of docs/branches.md (code 06d7f30), when present


def reference_energies(level, direction):
    """sigma -> energy of the states of docs/branches.md's main follow of the same level and direction."""
    path = f"{REFERENCE}/level{level}/{direction}/branch.json"
    if not os.path.exists(path):
        return {}
    with open(path) as f:
        return {p["value"]: p["energy"] for p in json.load(f)["points"]}


follows = []
for level in (1, 2, 3):
    for direction in ("down", "up"):
        with open(f"{OUT}/level{level}/{direction}/branch.json") as f:
            branch = json.load(f)
        points = branch["points"]
        column = load_statistics(os.path.dirname(points[-1]["state"]))
        states, reference = [], reference_energies(level, direction)
        for p in points:
            end = int(np.searchsorted(column["time"], p["time"] + 1e-9))
            s = split(column, end)
            states.append({"sigma": p["value"], "time": p["time"], "energy": p["energy"], "class": p["class"],
                           "at_plateau": p["at_plateau"], "jump_after_sharpening": s["after"]["jump"],
                           "carried_after_sharpening": s["after"]["carried"],
                           "energy_in_docs": reference.get(p["value"])})
        with open(os.path.join(os.path.dirname(points[-1]["state"]), "summary.json")) as f:
            version = json.load(f).get("code_version")
        follows.append(dict(split(column), level=level, direction=direction, states=states, code_version=version,
                            adaptations=int(column["adaptations"][-1]), measured=int(column["carried_measured"][-1])))

curved = load_statistics(CURVED)
with open(os.path.join(CURVED, "summary.json")) as f:
    curved_summary = json.load(f)
result = {"setup": "experiments/7.3-budding.prm; both branches by continuation follow (plateau 1e-3 for 0.3, "
                   "at most 3 time units per value, --classify protrusion:0.95), Mesh/Measure carried energy",
          "interface_cells_per_xi": CELLS_PER_XI, "sharpening_end": SHARPENING_END, "follows": follows,
          "curvature_0.15": dict(split(curved), energy=float(curved["energy"][-1]), time=float(curved["time"][-1]),
                                 adaptations=int(curved["adaptations"][-1]),
                                 measured=int(curved["carried_measured"][-1]),
                                 code_version=curved_summary.get("code_version"))}
with open(os.path.join(HERE, "results.json"), "w") as f:
    json.dump(result, f, indent=1)

print("| level | follow | adaptations (compared) | jumps, t <= 0.05 | carried, t <= 0.05 | jumps after | carried after "
      "| largest carried after | largest share of a state's energy, carried after |")
print("|---|---|---|---|---|---|---|---|---|")
for r in follows:
    share = max(abs(s["carried_after_sharpening"]) / s["energy"] for s in r["states"])
    print(f"| {r['level']} | {r['direction']} | {r['adaptations']} ({r['measured']}) | {r['sharpening']['jump']:+.4f} | "
          f"{r['sharpening']['carried']:+.4f} | {r['after']['jump']:+.4f} | {r['after']['carried']:+.5f} | "
          f"{r['after']['largest_carried']:.1e} | {100 * share:.4f} % |")
differences = [abs(s["energy"] - s["energy_in_docs"]) for r in follows for s in r["states"]
               if s["energy_in_docs"] is not None]
if differences:
    print(f"\nStates against docs/branches.md (same sigma, same follow): largest energy difference "
          f"{max(differences):.4f} over {len(differences)} states")
c = result["curvature_0.15"]
print(f"\nCurvature resolution 0.15, level 2, sigma 1000 to t = {c['time']:g}: {c['adaptations']} adaptations "
      f"({c['measured']} compared), jumps {c['sharpening']['jump']:+.4f} / {c['after']['jump']:+.4f}, carried "
      f"{c['sharpening']['carried']:+.4f} / {c['after']['carried']:+.5f} (t <= 0.05 / after), energy {c['energy']:.5f}")
