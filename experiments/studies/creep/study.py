#!/usr/bin/python3
"""The creep of a protruding state near the end of its branch (issue 33): which part of the step raises
the energy. Resumes the level-2 protruding state at sigma = 700 where its relaxation collapsed
(results/studies/branches-gb/level2/long, experiments/studies/branches/gauss-bonnet/long-relaxation.md) for a
short stretch under variants of the step, and fits the rates of the energy and its parts over that stretch.

Usage (from the repository root):
  /usr/bin/python3 experiments/studies/creep/study.py run [--exe build/membrane-flow] [--jobs 2]
  /usr/bin/python3 experiments/studies/creep/study.py analyze      # writes results.json next to this file
Runs go to results/studies/creep/<name>/ (not committed)."""
import argparse
import json
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "python"))
from membrane_flow import launch  # noqa: E402
from membrane_flow.run import load_statistics  # noqa: E402

LONG = "results/studies/branches-gb/level2/long"
OUT = "results/studies/creep"
# The two states: without grid control (prot-700-nogc, Energy tolerance 1e-6, at t = 14.2667) and with it
# (prot-700 at its collapse, t = 8.2667; resumed here with Energy tolerance 1e-6 so that it can move).
NOGC = (f"{LONG}/prot-700-nogc/700", 14.2667)
GC = (f"{LONG}/prot-700/700", 8.2667)
FROZEN = ["Material/Phase mobility=1e-8"]
STRESS = ["Shape/Line force=stress"]
STIFF = ["Shape/Line stiffness=1"]
TOL = ["Time stepping/Energy tolerance=1e-6"]
TAC = ["Shape/Tangential area correction=3"]
# name: (state, stretch in time units, extra settings, what it asks)
RUNS = {
    "potential": (NOGC, 0.3, [], "the reference scheme (potential form)"),
    "potential-frozen": (NOGC, 0.03, FROZEN, "the same with phi frozen (Phase mobility 1e-8): the shape step alone"),
    "stress": (NOGC, 0.03, STRESS, "the exact derivative of the discrete line energy"),
    "stress-frozen": (NOGC, 0.03, STRESS + FROZEN, "the same with phi frozen"),
    "stress-stiff": (NOGC, 0.3, STRESS + STIFF, "stress form with the implicit line stiffness"),
    "potential-stiff": (NOGC, 0.3, STIFF, "potential form with the implicit line stiffness"),
    "stress-stiff-proj3": (NOGC, 0.3, STRESS + STIFF + ["Shape/Area projections=3"],
                           "stress form, line stiffness, three area projections per step"),
    "stress-stiff-tac": (NOGC, 0.3, STRESS + STIFF + TAC, "stress form, line stiffness, tangential area correction"),
    "gc-potential": (GC, 0.5, TOL, "with grid control, the reference scheme"),
    "gc-stress-stiff": (GC, 0.5, TOL + STRESS + STIFF, "with grid control, stress form and line stiffness"),
    "gc-stress-stiff-tac": (GC, 2.0, TOL + STRESS + STIFF + TAC,
                            "with grid control, stress form, line stiffness, tangential area correction: a longer "
                            "relaxation, does the drift stop"),
}


def run(name, exe):
    (state, t0), stretch, sets, _ = RUNS[name]
    sets = [f"Checkpoint/Resume from={state}/checkpoint.txt", f"Time stepping/End time={t0 + stretch:.4f}",
            f"Output/Directory={OUT}/{name}", "Output/Write VTU=false", "Output/Interval=0.01", *sets]
    cmd = [exe, "--quiet", "--overwrite", *launch.settings(sets), f"{state}/parameters.prm"]
    env = launch.environment()  # one OpenMP / OpenBLAS thread
    os.makedirs(OUT, exist_ok=True)
    with open(f"{OUT}/{name}.out", "w") as log:
        code = subprocess.call(cmd, stdout=log, stderr=subprocess.STDOUT, env=env)
    print(name, "exit", code, flush=True)


def analyze():
    results = {"runs": {}}
    for name, ((state, t0), stretch, sets, question) in RUNS.items():
        c = load_statistics(f"{OUT}/{name}")
        m = c["time"] > t0 + 1e-6
        t = c["time"][m]

        def rate(values):
            return float(np.polyfit(t, values[m], 1)[0])

        with open(f"{OUT}/{name}/summary.json") as f:
            summary = json.load(f)
        results["runs"][name] = {
            "question": question, "from": state, "t0": t0, "stretch": stretch, "set": sets,
            "t_end": float(t[-1]), "steps": int(m.sum()),
            "rejected": int(c["rejected_steps"][-1] - c["rejected_steps"][~m][-1]),
            "median_tau": float(np.median(c["tau"][m])),
            "rate": {"energy": rate(c["energy"]), "bending": rate(c["bending_energy"]),
                     "gradient": rate(c["gradient_energy"]), "well": rate(c["well_energy"]),
                     "protrusion": rate(c["domain_protrusion"])},
            "energy": [float(c["energy"][~m][-1]), float(c["energy"][m][-1])],
            "largest_area_error": float(c["area_error"][m].max()),
            "smallest_corner_sine": float(c["min_corner_sine"][m].min()),
            "code_version": summary.get("code_version"),
            "stop": summary.get("stop_reason"),
            # about 12 rows of the stretch: time, tau, energy, protrusion, smallest corner sine, area error
            "trajectory": [[float(c[k][i]) for k in ("time", "tau", "energy", "domain_protrusion", "min_corner_sine",
                                                     "area_error")]
                           for i in np.nonzero(m)[0][::max(1, int(m.sum()) // 12)]],
        }
        r = results["runs"][name]
        print(f"| {name} | {r['steps']} ({r['rejected']}) | {r['median_tau']:.1e} | {r['rate']['energy']:+.2e} | "
              f"{r['rate']['bending']:+.3f} | {r['rate']['gradient'] + r['rate']['well']:+.3f} | "
              f"{r['rate']['protrusion']:+.2e} | {r['largest_area_error']:.1e} |")
    with open(os.path.join(HERE, "results.json"), "w") as f:
        json.dump(results, f, indent=1)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("what", choices=["run", "analyze"])
    parser.add_argument("--exe", default="build/membrane-flow")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--only", nargs="*", default=list(RUNS))
    args = parser.parse_args()
    if args.what == "run":
        with ThreadPoolExecutor(args.jobs) as pool:
            list(pool.map(lambda n: run(n, args.exe), args.only))
    else:
        analyze()
