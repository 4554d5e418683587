#!/usr/bin/python3
"""The implicit line stiffness (Shape/Line stiffness) removes the explicit limit of the phase force
and changes a step only at second order in tau.

Set-up: experiments/vesicle-domain-budding.prm at sigma = 100 (a 30 % cap domain, xi = 0.1, one level
of refinement at the interface), where the explicit force Y grad phi of the tangential law limits tau
to about 1e-5.
1. Fixed tau = 2e-4 for 10 steps: with the explicit force (s = 0) a step raises the energy (by 0.38 at
   the third step) and the run stops with exit code 2, naming the explicit limit h^2 / (L_X sigma) and
   Shape/Line stiffness in its message; with s = 1 the run ends at the end time and every step lowers
   the energy.
2. One step from the initial state at tau = 1e-5, 2.5e-6, 6.25e-7: the energy after the step with s = 1
   differs from that with s = 0 by an amount that falls faster than tau (measured: 1.9e-5, 2.1e-6,
   2.7e-7, factors 9.1 and 7.9 per 4x smaller tau; asserted > 5). The added term is tau L_X sigma xi^2
   times an O(tau) increment; a term of the wrong order in tau would shrink by at most 4.
Usage: test_line_stiffness.py <membrane-flow> <vesicle-domain-budding.prm>"""
import os
import subprocess
import sys
import tempfile

import numpy as np

from membrane_flow import launch  # PYTHONPATH: the build's python/
from membrane_flow.run import load_statistics
from checks import Checks  # tests/checks.py, next to this script

exe, prm = sys.argv[1], sys.argv[2]
env = launch.environment()
work = tempfile.mkdtemp(prefix="membrane_line_stiffness_")

check = Checks()


def run(name, stiffness, tau, *extra):
    out = os.path.join(work, name)
    result = subprocess.run([exe, "--quiet", "--set", "Output/Write VTU=false", "--set", "Checkpoint/Interval=0",
                             "--set", "Material/Line tension=100", "--set", "Time stepping/Adaptive=false",
                             "--set", f"Time stepping/Time step={tau}", "--set", f"Shape/Line stiffness={stiffness}",
                             "--set", f"Output/Directory={out}", *extra, prm],
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    energy = load_statistics(out)["energy"]
    return result, energy


explicit, e0 = run("explicit", 0, 2e-4, "--set", "Time stepping/End time=0.002")
check(explicit.returncode == 2 and "energy would rise" in explicit.stdout,
      f"explicit force at tau = 2e-4: the run stops on an energy rise (exit {explicit.returncode}, "
      f"{len(e0) - 1} steps kept)")
check("<Shape/Line stiffness> = 1 lifts" in explicit.stdout,
      "its message names the explicit limit of the phase force and the remedy")
implicit, e1 = run("implicit", 1, 2e-4, "--set", "Time stepping/End time=0.002")
rises = np.diff(e1)
check(implicit.returncode == 0 and len(e1) == 11 and np.all(rises < 0),
      f"implicit line stiffness at tau = 2e-4: {len(e1) - 1} steps to the end time (exit {implicit.returncode}), "
      f"largest energy change {rises.max():.3e} (< 0)")

differences = []
for tau in (1e-5, 2.5e-6, 6.25e-7):
    energies = [run(f"one_step_{s}_{tau:g}", s, tau, "--set", "Time stepping/Maximum steps=1")[1][1] for s in (0, 1)]
    differences.append(abs(energies[1] - energies[0]))
    print(f"tau = {tau:.3g}: F after one step, s = 1 minus s = 0: {energies[1] - energies[0]:.4e}")
for coarse, fine in zip(differences, differences[1:]):
    check(fine > 0 and coarse / fine > 5,
          f"the difference falls by {coarse / fine:.2f} (> 5) when tau falls by 4: higher than first order")

print(f"{check.passed} passed, {check.failed} failed")
sys.exit(check.exit_code())
