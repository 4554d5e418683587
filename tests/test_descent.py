#!/usr/bin/python3
"""Near equilibrium a step is still a descent step, and its energy change tends to 0 like tau.

Runs the 7.3 setup (sigma = 630, uniform 16 x 16 cells, xi = 0.06) to t = 1, where the energy falls by
about 0.3 % per unit time (the bud is near its equilibrium), and takes one step of fixed length tau from that
checkpoint for tau = 1e-3, 2.5e-4 and 6.25e-5. Asserts: every step lowers the energy, and each
4x smaller tau lowers |Delta F| by a factor between 2.5 and 6 (first order in tau). A part of
the step whose energy change does not shrink with tau (as the area correction once had) would
show as a rise, or as a |Delta F| that stops shrinking.
Usage: test_descent.py <membrane-flow> <7.3-budding.prm>"""
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

exe, prm = sys.argv[1], sys.argv[2]
common = ["--quiet", "--set", "Mesh/Cells per side=16", "--set", "Mesh/Maximum refinement level=0", "--set", "Material/Line tension=630",
          "--set", "Material/Transition length=0.06", "--set", "Output/Write VTU=false"]
env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")


def energies(directory):
    return np.atleast_2d(np.loadtxt(os.path.join(directory, "statistics.txt")))[:, 3]


work = tempfile.mkdtemp(prefix="membrane_descent_")
base = os.path.join(work, "base")
subprocess.run([exe, *common, "--set", "Time stepping/End time=1", "--set", "Checkpoint/Interval=100000",
                "--set", f"Output/Directory={base}", prm], check=True, env=env, stdout=subprocess.DEVNULL)
steps = len(energies(base)) - 1
changes = {}
for tau in (1e-3, 2.5e-4, 6.25e-5):
    out = os.path.join(work, f"tau{tau:g}")
    os.makedirs(out)
    shutil.copy(os.path.join(base, "checkpoint.txt"), out)
    subprocess.run([exe, *common, "--set", "Time stepping/End time=2", "--set", "Time stepping/Adaptive=false",
                    "--set", f"Time stepping/Time step={tau}", "--set", f"Time stepping/Maximum steps={steps + 1}",
                    "--set", "Checkpoint/Interval=0", "--set", f"Output/Directory={out}",
                    "--set", f"Checkpoint/Resume from={out}/checkpoint.txt", prm], check=True, env=env, stdout=subprocess.DEVNULL)
    e = energies(out)
    changes[tau] = e[-1] - e[-2]
    print(f"tau = {tau:.3g}: Delta F = {changes[tau]:.4e}, Delta F / tau = {changes[tau] / tau:.4e}")

passed = failed = 0
def check(condition, message):
    global passed, failed
    print(("ok      " if condition else "FAILED  ") + message)
    passed, failed = passed + bool(condition), failed + (not condition)

taus = sorted(changes, reverse=True)
for tau in taus:
    check(changes[tau] < 0, f"the step with tau = {tau:g} lowers the energy ({changes[tau]:.3e})")
for big, small in zip(taus, taus[1:]):
    ratio = changes[big] / changes[small]
    check(2.5 < ratio < 6, f"Delta F({big:g}) / Delta F({small:g}) = {ratio:.2f} (tau ratio 4)")
shutil.rmtree(work)
print(f"{passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
