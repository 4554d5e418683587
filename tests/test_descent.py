#!/usr/bin/python3
"""Near equilibrium a step is still a descent step, and its energy change tends to 0 like tau.

Runs the 7.3 setup (sigma = 630, uniform 16 x 16 cells, xi = 0.06) to t = 1, where the energy falls by
about 0.3 % per unit time (the bud is near its equilibrium), and from that checkpoint takes 12 steps of
fixed length tau for tau = 1e-3, 2.5e-4 and 6.25e-5. Asserts: every step lowers the energy, and with each
4x smaller tau the energy change of the last step shrinks by a factor between 2.5 and 6 (first order in
tau). A part of the step whose energy change does not shrink with tau (as the area correction once had)
would show as a rise, or as a |Delta F| that stops shrinking.
The last step, not the first, is compared: after the switch from the run's last step (tau ~ 6e-3) to a
much shorter one the state relaxes over a few 1e-4 time units, releasing an energy that does not depend
on the new tau (with the tangential area correction about 4e-5, Delta F / tau -0.46, -0.36, -0.29, ...,
-0.20 over the first steps at tau = 6.25e-5); a part of every step that does not shrink with tau would
stay in the last step.
Further arguments (`--set "Section/Entry=value"` ...) apply to the run to t = 1 and to the steps alike,
so that the steps start from a state the same scheme produced.
Usage: test_descent.py <membrane-flow> <7.3-budding.prm> [--set ...]"""
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

from membrane_flow import launch  # PYTHONPATH: the build's python/
from membrane_flow.run import load_statistics
from checks import Checks  # tests/checks.py, next to this script

exe, prm, extra = sys.argv[1], sys.argv[2], sys.argv[3:]
common = ["--quiet", "--set", "Mesh/Cells per side=16", "--set", "Mesh/Maximum refinement level=0", "--set", "Material/Line tension=630",
          "--set", "Material/Transition length=0.06", "--set", "Output/Write VTU=false", *extra]
env = launch.environment()


def energies(directory):
    return load_statistics(directory)["energy"]


check = Checks()

work = tempfile.mkdtemp(prefix="membrane_descent_")
base = os.path.join(work, "base")
subprocess.run([exe, *common, "--set", "Time stepping/End time=1", "--set", "Checkpoint/Interval=100000",
                "--set", f"Output/Directory={base}", prm], check=True, env=env, stdout=subprocess.DEVNULL)
steps = len(energies(base)) - 1
steps_per_tau = 12
changes = {}
for tau in (1e-3, 2.5e-4, 6.25e-5):
    out = os.path.join(work, f"tau{tau:g}")
    os.makedirs(out)
    shutil.copy(os.path.join(base, "checkpoint.txt"), out)
    subprocess.run([exe, *common, "--set", "Time stepping/End time=2", "--set", "Time stepping/Adaptive=false",
                    "--set", f"Time stepping/Time step={tau}", "--set", f"Time stepping/Maximum steps={steps + steps_per_tau}",
                    "--set", "Checkpoint/Interval=0", "--set", f"Output/Directory={out}",
                    "--set", f"Checkpoint/Resume from={out}/checkpoint.txt", prm], check=True, env=env, stdout=subprocess.DEVNULL)
    e = energies(out)
    rates = np.diff(e)[-steps_per_tau:] / tau
    changes[tau] = e[-1] - e[-2]
    print(f"tau = {tau:.3g}: Delta F of the last step = {changes[tau]:.4e}; Delta F / tau of the {steps_per_tau} steps: "
          + " ".join(f"{r:.3f}" for r in rates))
    check(rates.max() < 0, f"all {steps_per_tau} steps with tau = {tau:g} lower the energy")

taus = sorted(changes, reverse=True)
for big, small in zip(taus, taus[1:]):
    ratio = changes[big] / changes[small]
    check(2.5 < ratio < 6, f"Delta F({big:g}) / Delta F({small:g}) = {ratio:.2f} (last steps, tau ratio 4)")
shutil.rmtree(work)
print(f"{check.passed} passed, {check.failed} failed")
sys.exit(check.exit_code())
