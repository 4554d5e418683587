#!/usr/bin/python3
"""Fluctuating membranes at a real membrane's temperature with the ALE mesh motion (issue 46, item 1):
the unit-sphere vesicle (experiments/thermal-flicker.prm) and the two-phase patch (experiments/default.prm)
at k_BT = kappa/20 and kappa/10, 10^4 fixed steps of tau = 1e-4 each, with the settings docs/model.md
("Mesh motion") recommends at a temperature: Mesh motion = ale, Pressure stabilization = 0.01, Area
projections = 3, Tangential area correction = 2, Area relaxation time = 1e-3 (10 tau). Each run is judged by: no failed step, every cell's smallest corner sine >= 0.5 throughout,
local area error <= 1e-2, and phi's mass to round-off.

Usage (from the repository root):
  /usr/bin/python3 experiments/studies/physical_temperature/study.py run [--exe build/membrane-flow]
      [--jobs 2] [--only vesicle16-kT20 ...]
  /usr/bin/python3 experiments/studies/physical_temperature/study.py analyze   # writes results.json here
      # and docs/data/physical_temperature.json; --plot draws docs/images/physical_temperature.png
Runs go to results/studies/physical_temperature/<name>/ (not committed). One vesicle16 run takes about
40 minutes, one patch32 run about 28 minutes on one core; the 32-cell vesicle and the 64 x 64 patch
about four times as long. Each run writes a checkpoint every 500 steps; `run` again continues an
interrupted run from it (statistics included) instead of starting over."""
import argparse
import json
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..", "..")
sys.path.insert(0, os.path.join(ROOT, "python"))
from membrane_flow import launch  # noqa: E402
from membrane_flow.run import load_parameters, load_statistics  # noqa: E402

OUT = "results/studies/physical_temperature"
STEPS = 10000
TAU = 1e-4
ALE = ["Time stepping/Adaptive=false", f"Time stepping/Time step={TAU:g}",
       f"Time stepping/End time={STEPS * TAU:g}", "Shape/Mesh motion=ale", "Shape/Pressure stabilization=0.01",
       "Shape/Area projections=3", "Shape/Tangential area correction=2", "Shape/Area relaxation time=1e-3",
       "Output/Interval=0.1", "Checkpoint/Interval=500"]
# Area relaxation time = 10 tau: restoring the whole area defect in every step (T_a = tau) with three
# projections made the two-phase patch at kappa/10 unstable at the cell scale (the largest local area
# error doubled about every 200 steps, to a degenerate cell at step 2468); restored over ten steps
# its largest value stays at 1.4e-3 for 10^4 steps.
# At 32 cells per side a thermal step moves a vertex about one cell of the input mesh (1.06 at kappa/10 on
# the vesicle), which the default guard (1 cell) refuses; the guard only rejects, so raising it changes no step.
FINE = ["Time stepping/Maximum increment=3"]
# kappa = 1 on the vesicle (thermal-flicker.prm), 1.5 for the patch's majority phase (default.prm)
KAPPA = {"vesicle": 1.0, "patch": 1.5}
PRM = {"vesicle": "experiments/thermal-flicker.prm", "patch": "experiments/default.prm"}
CELLS = {"vesicle16": ("vesicle", 16), "vesicle32": ("vesicle", 32), "patch32": ("patch", 32),
         "patch64": ("patch", 64)}
RUNS = {f"{mesh}-kT{d}": (mesh, d) for mesh in CELLS for d in (20, 10)}
LIMITS = {"min_corner_sine": 0.5, "area_error": 1e-2}
SHAPE_ENTRIES = ("Pressure stabilization", "Area projections", "Tangential area correction", "Area relaxation time")


def finished(name):
    """The run stopped by a rule of its own (end time or a failure), not by an interruption."""
    try:
        with open(f"{OUT}/{name}/summary.json") as f:
            return not json.load(f)["stop_reason"].startswith("interrupted")
    except FileNotFoundError:
        return False


def run(name, exe):
    mesh, divisor = RUNS[name]
    kind, cells = CELLS[mesh]
    sets = ALE + (FINE if cells > 16 else []) + [f"Mesh/Cells per side={cells}",
                                                 f"Material/Temperature={KAPPA[kind] / divisor:g}",
                                                 f"Output/Directory={OUT}/{name}"]
    # A run cut off (killed, or stopped with Ctrl-C) continues from its last checkpoint, in its own directory.
    checkpoint = f"{OUT}/{name}/checkpoint.txt"
    resume = os.path.exists(checkpoint) and not finished(name)
    if resume:
        sets.append(f"Checkpoint/Resume from={checkpoint}")
    cmd = [exe, "--quiet", *([] if resume else ["--overwrite"]), *launch.settings(sets), PRM[kind]]
    os.makedirs(OUT, exist_ok=True)
    with open(f"{OUT}/{name}.out", "a" if resume else "w") as log:
        code = subprocess.call(cmd, stdout=log, stderr=subprocess.STDOUT, env=launch.environment())
    print(name, "exit", code, flush=True)


SPECTRUM_SKIP = 1000  # steps: 14 relaxation times of l = 6, 1.4 of l = 2 (1 / lambda_2 = 0.07)
DEGREES = (2, 3, 4, 5, 6)
_stiffness = {}


def cells_of(mesh):
    return CELLS[mesh][1]


def spectrum(name, cells, kT, exe):
    """Milner and Safran fitted to the run's shape_mode_2..6 (membrane_flow.spectra.sphere_fit): kappa
    and Sigma, once with the continuum's bending stiffness of each mode and once with this mesh's
    (spectra.sphere_stiffness: the discrete sphere's bending energy of a small P_l displacement). The
    input kappa is 1."""
    from membrane_flow import spectra
    if cells not in _stiffness:
        _stiffness[cells] = spectra.sphere_stiffness(exe, PRM["vesicle"], [f"Mesh/Cells per side={cells}"],
                                                     degrees=DEGREES)
    path = f"{OUT}/{name}"
    continuum = spectra.sphere_fit(path, kT, skip=SPECTRUM_SKIP, degrees=DEGREES)
    mesh = spectra.sphere_fit(path, kT, skip=SPECTRUM_SKIP, degrees=DEGREES, stiffness=_stiffness[cells])
    # Each mode against the input (kappa = 1, Sigma = 0) with the mesh's stiffness and the factor of
    # the fixed tau: the measured / expected ratio that the two-parameter fit trades against Sigma.
    R, tau = mesh["R"], mesh["tau"]
    against_input = {}
    for m in mesh["modes"]:
        l = m["l"]
        bending = _stiffness[cells][l] * (l - 1) * l * (l + 1) * (l + 2)
        step = 1 / (1 + bending * tau / (2 * R**4 * (1 + 4 / (l * (l + 1)))))
        expected = kT * step / bending
        against_input[str(l)] = {"expected": expected, "ratio": m["measured"] / expected,
                                 "ratio_error": m["error"] / expected}
    return {"skip_steps": SPECTRUM_SKIP, "continuum": continuum, "mesh_stiffness": mesh,
            "against_input_kappa": against_input}


def analyze(plot, exe):
    # Runs measured before (another session, another code version: each entry names its own)
    # are kept until their directory holds a finished run again.
    try:
        with open(os.path.join(HERE, "results.json")) as f:
            kept = json.load(f)["runs"]
    except FileNotFoundError:
        kept = {}
    results = {"steps": STEPS, "tau": TAU, "settings": ALE, "limits": LIMITS, "runs": kept}
    print("| run | k_BT | steps | failed | smallest corner sine | largest area error | mean area error | "
          "mean area drift | mass drift | s/step | kappa fitted (continuum) | kappa fitted (mesh) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    series = {}
    for name, (mesh, divisor) in RUNS.items():
        if not finished(name):
            continue
        c = load_statistics(f"{OUT}/{name}")
        with open(f"{OUT}/{name}/summary.json") as f:
            summary = json.load(f)
        parameters = load_parameters(f"{OUT}/{name}")
        steps = int(c["step"][-1])
        kind = CELLS[mesh][0]
        # per block of a tenth of the run: is the area error stationary (no slow drift)?
        blocks = np.array_split(np.arange(1, len(c["step"])), 10)
        r = {
            "mesh": mesh, "k_BT": KAPPA[kind] / divisor, "kappa_over_k_BT": divisor, "cells": int(c["cells"][-1]),
            "steps": steps, "complete": steps >= STEPS and not summary["failed"],
            "failed_steps": int(c["rejected_steps"][-1]), "stop": summary["stop_reason"],
            "smallest_corner_sine": float(c["min_corner_sine"].min()),
            "largest_area_error": float(c["area_error"].max()),
            "mean_area_error": float(c["area_error"][1:].mean()),
            "steps_above_area_limit": int((c["area_error"] > LIMITS["area_error"]).sum()),
            "largest_mass_drift": float(np.abs(c["mass_drift"]).max()),
            "area_drift": float(c["area_drift"][-1]),
            "mean_area_drift": float(c["area_drift"][1:].mean()),
            "wall_seconds_per_step": float(summary["wall_seconds"] / max(1, steps)),
            "area_error_per_tenth": [float(c["area_error"][b].max()) for b in blocks if len(b)],
            "code_version": summary.get("code_version"),
            # the entries that decide the local area error (entries of older runs lack them)
            "shape_settings": {k: parameters[f"Shape/{k}"] for k in SHAPE_ENTRIES},
        }
        if kind == "vesicle":
            r["spectrum"] = spectrum(name, cells_of(mesh), KAPPA[kind] / divisor, exe)
        r["within_limits"] = bool(r["complete"] and r["failed_steps"] == 0
                                  and r["smallest_corner_sine"] >= LIMITS["min_corner_sine"]
                                  and r["largest_area_error"] <= LIMITS["area_error"])
        results["runs"][name] = r
        series[name] = (c["time"], c["area_error"], c["min_corner_sine"])
        fits = ["%.3f +- %.3f" % (r["spectrum"][k]["kappa"], r["spectrum"][k]["kappa_error"]) if "spectrum" in r
                else "-" for k in ("continuum", "mesh_stiffness")]
        print(f"| {name} | {r['k_BT']:g} | {steps} | {r['failed_steps']} | {r['smallest_corner_sine']:.3f} | "
              f"{r['largest_area_error']:.2e} | {r['mean_area_error']:.2e} | {r['mean_area_drift']:.2e} | "
              f"{r['largest_mass_drift']:.1e} | {r['wall_seconds_per_step']:.2f} | {fits[0]} | {fits[1]} |")
    for path in (os.path.join(HERE, "results.json"), os.path.join(ROOT, "docs", "data", "physical_temperature.json")):
        with open(path + ".tmp", "w") as f:
            json.dump(results, f, indent=1)
        os.replace(path + ".tmp", path)
    if plot:
        draw(series, os.path.join(ROOT, "docs", "images", "physical_temperature.png"))


def draw(series, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.6), constrained_layout=True)
    for name, (t, error, sine) in series.items():
        every = max(1, len(t) // 500)  # the largest value of each window, so that no peak is lost
        peaks = [error[i:i + every].max() for i in range(1, len(t), every)]
        ax1.plot(t[1::every][:len(peaks)], peaks, lw=0.8, label=name)
        ax2.plot(t[1::every], [sine[i:i + every].min() for i in range(1, len(t), every)], lw=0.8, label=name)
    ax1.axhline(LIMITS["area_error"], color="k", ls="--", lw=0.8)
    ax1.set(xlabel="t", ylabel="local area error (window maximum)", yscale="log")
    ax2.axhline(LIMITS["min_corner_sine"], color="k", ls="--", lw=0.8)
    ax2.set(xlabel="t", ylabel="smallest corner sine (window minimum)", ylim=(0.4, 1.0))
    ax1.legend(fontsize=7)
    fig.savefig(path, dpi=110)
    print("wrote", path)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("what", choices=["run", "analyze"])
    parser.add_argument("--exe", default="build/membrane-flow")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--only", nargs="*", default=list(RUNS))
    parser.add_argument("--plot", action="store_true")
    args = parser.parse_args()
    if args.what == "run":
        with ThreadPoolExecutor(args.jobs) as pool:
            list(pool.map(lambda n: run(n, args.exe), args.only))
    else:
        analyze(args.plot, args.exe)
