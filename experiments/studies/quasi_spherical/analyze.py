#!/usr/bin/python3
"""Stationary shape spectrum of a quasi-spherical vesicle against Milner and Safran.

Reads the statistics.txt of a run at k_BT > 0 with a fixed tau (docs/fluctuations.md,
"Quasi-spherical vesicle") and compares the columns shape_mode_l = <u_lm^2> (mean over m) with

    <u_lm^2> = k_BT / (K_l (1 + lambda_l tau / 2)),
    K_l = kappa (l - 1)(l + 2)(l (l + 1) + Sigma R^2 / kappa),
    lambda_l = L_X K_l / (R^4 (1 + 4 / (l (l + 1)))),

the Milner-Safran variance divided by the backward-Euler factor of a fixed tau; lambda_l is the
mode's decay rate with the tangential flow the local area constraint drags along (the factor
1 + 4 / (l (l + 1)), tests/test_spherical_modes.cc). Sigma is the run's mean of gamma_mean + G (G the mean line-energy
density, (gradient_energy + well_energy) / area), R
the radius of the sphere of the run's volume. Error bars: batch means. Also prints the Sigma
that would fit each l.

The discrete cube-sphere is not exactly a discrete equilibrium: at k_BT = 0 it settles into a
slightly cubic shape (l = 4), whose u_lm^2 adds to the thermal variance; --static subtracts it.

Usage: analyze.py STATISTICS --kT 1e-4 [--kappa 1] [--mobility 1] [--skip 500] [--batches 20]
                  [--static STATISTICS_AT_ZERO_TEMPERATURE]
"""
import argparse

import numpy as np

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("statistics")
parser.add_argument("--kT", type=float, required=True)
parser.add_argument("--kappa", type=float, default=1.0)
parser.add_argument("--mobility", type=float, default=1.0)
parser.add_argument("--skip", type=int, default=500, help="steps left out at the start")
parser.add_argument("--batches", type=int, default=20)
parser.add_argument("--static", help="statistics.txt of the same run at k_BT = 0: its last shape_mode_l (the "
                    "discrete sphere's own deformation, the mean shape) is subtracted")
args = parser.parse_args()

with open(args.statistics) as f:
    names = f.readline()[1:].split()
data = np.loadtxt(args.statistics, ndmin=2)
column = {n: data[:, i] for i, n in enumerate(names)}
rows = slice(args.skip + 1, None)  # row 0 is the initial state
n = len(column["step"][rows])
if n < 2 * args.batches:
    # A run cut short (docs.commands_run runs 3 steps): nothing to compare.
    print(f"{args.statistics}: {n} steps after the first {args.skip}, too few for {args.batches} batches")
    raise SystemExit(0)
tau = column["tau"][rows].mean()
R = (3 * column["volume"][rows].mean() / (4 * np.pi)) ** (1 / 3)
# The tension: the mean area multiplier plus the mean line-energy density G (as on the patch).
line_density = (column["gradient_energy"] + column["well_energy"]) / column["area"]
sigma = (column["gamma_mean"] + line_density)[rows].mean()
print(f"steps sampled {n} (from step {int(column['step'][args.skip + 1])}), tau {tau:g}, R {R:.6f}, "
      f"Sigma = <gamma_mean + G> {sigma:.5g} (G {line_density[rows].mean():.3g})")
gm_batches = np.array([b.mean() for b in np.array_split(column["gamma_mean"][rows], args.batches)])
print(f"  gamma_mean batch error {gm_batches.std(ddof=1) / np.sqrt(args.batches):.3g}; "
      f"min_corner_sine {column['min_corner_sine'][rows].min():.3f}; area_drift {column['area_drift'][rows][-1]:.3g}")


static = {l: 0.0 for l in (2, 3, 4)}
if args.static:
    with open(args.static) as f:
        static_names = f.readline()[1:].split()
    last = np.loadtxt(args.static, ndmin=2)[-1]
    static = {l: last[static_names.index(f"shape_mode_{l}")] for l in (2, 3, 4)}
    print("  subtracted (k_BT = 0): " + ", ".join(f"l = {l}: {static[l]:.3g}" for l in static))


def expected(l, s):
    K = args.kappa * (l - 1) * (l + 2) * (l * (l + 1) + s * R**2 / args.kappa)
    lam = args.mobility * K / (R**4 * (1 + 4 / (l * (l + 1))))
    return args.kT / (K * (1 + lam * tau / 2)), lam * tau


print("| l | lambda tau (Sigma) | <u_lm^2> | error | MS, Sigma = <gamma_mean + G> | ratio | MS, Sigma = 0 | ratio | Sigma that fits |")
print("|---|---|---|---|---|---|---|---|---|")
for l in (2, 3, 4):
    series = column[f"shape_mode_{l}"][rows] - static[l]
    batches = np.array([b.mean() for b in np.array_split(series, args.batches)])
    mean, error = batches.mean(), batches.std(ddof=1) / np.sqrt(args.batches)
    e_sigma, lt = expected(l, sigma)
    e_zero, _ = expected(l, 0.0)
    # The Sigma that fits: solve expected(l, s) = mean by bisection (monotone in s).
    lo, hi = -(l * (l + 1)) * args.kappa / R**2 * 0.999, 1e6
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if expected(l, mid)[0] > mean else (lo, mid)
    print(f"| {l} | {lt:.3f} | {mean:.4g} | {error:.2g} | {e_sigma:.4g} | {mean / e_sigma:.3f} +- {error / e_sigma:.3f} "
          f"| {e_zero:.4g} | {mean / e_zero:.3f} +- {error / e_zero:.3f} | {0.5 * (lo + hi):.3g} |")
