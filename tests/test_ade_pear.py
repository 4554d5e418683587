#!/usr/bin/python3
"""The area-difference elasticity drives a prolate vesicle into a pear (docs/vesicles.md).

Runs experiments/vesicle-ade-pear.prm (v = 0.9, k = 4, the egg-perturbed prolate) at two
preferred area differences:
- m_0 = 1.2 to t = 1: the prolate holds. Its up-down asymmetry shape_mode_3 decays (4.0e-5 ->
  2e-6 measured) and its reduced area difference m stays at the prolate's 1.052.
- m_0 = 1.4 to t = 2: the pear mode grows (shape_mode_3 to 5.5e-3 measured, > 30x its start) and
  the elongation mode shape_mode_2 falls (0.092 -> 0.060), while F - pressure_work never rises.
A missing or wrong-signed area-difference force leaves the second run prolate; a force that
ignores the lagged factor (M - M_0) makes the first run leave the prolate.
Usage: test_ade_pear.py <membrane-flow> <vesicle-ade-pear.prm>"""
import os
import subprocess
import sys
import tempfile

import numpy as np

from membrane_flow import launch  # PYTHONPATH: the build's python/
from membrane_flow.run import load_statistics

exe, prm = sys.argv[1], sys.argv[2]
env = launch.environment()


def run(m0, end_time, directory):
    subprocess.run([exe, "--quiet", "--set", f"Material/Area difference/Reduced difference={m0}",
                    "--set", f"Time stepping/End time={end_time}", "--set", "Output/Write VTU=false",
                    "--set", "Checkpoint/Interval=0", "--set", "Time stepping/Equilibrium rate=0",
                    "--set", f"Output/Directory={directory}", prm], check=True, env=env, stdout=subprocess.DEVNULL)
    return load_statistics(directory)


failures = []
with tempfile.TemporaryDirectory() as tmp:
    prolate = run(1.2, 1, os.path.join(tmp, "prolate"))
    pear = run(1.4, 2, os.path.join(tmp, "pear"))

l3 = prolate["shape_mode_3"]
m = prolate["reduced_area_difference"][-1]
print(f"m_0 = 1.2: shape_mode_3 {l3[0]:.3e} -> {l3[-1]:.3e}, m = {m:.5f}")
if not l3[-1] < 0.2 * l3[0]:
    failures.append("m_0 = 1.2: the pear mode did not decay")
if abs(m - 1.052) > 2e-3:
    failures.append(f"m_0 = 1.2: m = {m:.5f} is not the prolate's 1.052")

# The volume ramp (to v = 0.9 over t = 0.05) does work p dV on the membrane: F - pressure_work
# is what the constrained flow decreases.
l3, l2, energy = pear["shape_mode_3"], pear["shape_mode_2"], pear["energy"] - pear["pressure_work"]
rise = np.max(np.diff(energy) / np.abs(energy[:-1]))
print(f"m_0 = 1.4: shape_mode_3 {l3[0]:.3e} -> {l3[-1]:.3e}, shape_mode_2 {l2[0]:.4f} -> {l2[-1]:.4f}, "
      f"largest relative energy rise per step {rise:.2e}")
if not l3[-1] > 30 * l3[0]:
    failures.append("m_0 = 1.4: the pear mode did not grow 30-fold")
if not l2[-1] < 0.8 * l2[0]:
    failures.append("m_0 = 1.4: the prolate did not shorten")
if rise > 1e-10:
    failures.append(f"m_0 = 1.4: the energy rose by {rise:.2e} (relative) in a step")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
