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

The sampling, R, Sigma, the static part and the error bars are those of
membrane_flow.spectra.sphere_spectrum (the `spectrum sphere` command, which compares with the
tension each mode feels, and refuses a run whose tau varies); this script keeps the plain mean
Sigma in K_l and lambda_l, and the mean of the batch means (spectra.batch_means) as <u_lm^2>.

Usage: analyze.py STATISTICS --kT 1e-4 [--kappa 1] [--mobility 1] [--skip 500] [--batches 20]
                  [--static STATISTICS_AT_ZERO_TEMPERATURE]
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "python"))
from membrane_flow import spectra  # noqa: E402
from membrane_flow.run import read_statistics  # noqa: E402

DEGREES = (2, 3, 4)

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

try:
    result = spectra.sphere_spectrum(args.statistics, args.kT, args.kappa, args.mobility, args.skip, args.batches,
                                     args.static, DEGREES)
except spectra.TooFewSteps as e:
    # A run cut short (docs.commands_run runs 3 steps): nothing to compare.
    print(f"{args.statistics}: {e}")
    raise SystemExit(0)
except ValueError as e:  # tau not fixed
    sys.exit(f"{args.statistics}: {e}")
column = read_statistics(args.statistics)
rows = slice(args.skip + 1, None)  # row 0 is the initial state, as in sphere_spectrum
tau, R = result["tau"], result["R"]
# The tension: the mean area multiplier plus the mean line-energy density G (as on the patch).
sigma = result["modes"][0]["sigma_mean"]
line_density = (column["gradient_energy"] + column["well_energy"]) / column["area"]
print(f"steps sampled {result['steps']} (from step {int(column['step'][args.skip + 1])}), tau {tau:g}, R {R:.6f}, "
      f"Sigma = <gamma_mean + G> {sigma:.5g} (G {line_density[rows].mean():.3g})")
print(f"  gamma_mean batch error {spectra.batch_error(column['gamma_mean'][rows], args.batches):.3g}; "
      f"min_corner_sine {column['min_corner_sine'][rows].min():.3f}; area_drift {column['area_drift'][rows][-1]:.3g}")
if args.static:
    print("  subtracted (k_BT = 0): " + ", ".join(f"l = {l}: {v:.3g}" for l, v in result["static"].items()))


def expected(l, s):
    """Milner and Safran at the tension s, divided by the backward-Euler factor of the fixed tau."""
    bending, weight, bending_rate, tension_rate = spectra.sphere_rates(l, R, args.kappa, args.mobility)
    K, lam = bending + s * weight, bending_rate + s * tension_rate
    return args.kT / (K * (1 + lam * tau / 2)), lam * tau


print("| l | lambda tau (Sigma) | <u_lm^2> | error | MS, Sigma = <gamma_mean + G> | ratio | MS, Sigma = 0 | ratio | Sigma that fits |")
print("|---|---|---|---|---|---|---|---|---|")
for l, mode in zip(DEGREES, result["modes"]):
    # The mean of the batch means (mode["measured"], the plain mean, when the batches are of equal size).
    mean = spectra.batch_means(column[f"shape_mode_{l}"][rows] - result["static"][l], args.batches).mean()
    error = mode["error"]
    e_sigma, lt = expected(l, sigma)
    e_zero, _ = expected(l, 0.0)
    # The Sigma that fits: solve expected(l, s) = mean by bisection (monotone in s).
    lo, hi = -(l * (l + 1)) * args.kappa / R**2 * 0.999, 1e6
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if expected(l, mid)[0] > mean else (lo, mid)
    print(f"| {l} | {lt:.3f} | {mean:.4g} | {error:.2g} | {e_sigma:.4g} | {mean / e_sigma:.3f} +- {error / e_sigma:.3f} "
          f"| {e_zero:.4g} | {mean / e_zero:.3f} +- {error / e_zero:.3f} | {0.5 * (lo + hi):.3g} |")
