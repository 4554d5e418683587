#!/usr/bin/python3
"""membrane_flow.capillary on synthetic snapshots whose boundary spectrum is known.

Two stripe runs and one bulk run are written as VTU series on 32 x 32 cells of the unit patch
(tests/synthetic_vtu.py: each vertex once per cell, in single precision, as the simulator writes
them): phi = tanh((x - x_L(y)) / w) - tanh((x - x_R(y)) / w) - 1 with w = 4 xi / 3 (the profile of
MODEL.md's f), x_L = 1/4 + u_L, x_R = 3/4 + u_R, and u_L, u_R independent Gaussian boundaries
with <|u_n|^2> = k_BT / (lambda q^2) for n = 1..8, lambda = 20; every vertex gets white noise of
standard deviation 0.14 (the bulk run has no boundary); in the stripe runs its part along each
boundary's translation mode sech^2((x - x_0) / w) is removed in every vertex row, as in the
Gaussian theory of a boundary. 600 independent snapshots per run. capillary_spectrum must return lambda_n / (sigma xi) within three
error bars of 1 and within 8 % for n = 1..3, with error bars below 4 %, and from k1 = 0 and k1 = 1
alone within 12 % each. A factor 8 replaced by 4 fails, and so does a missing bulk subtraction
(the floor is 4 % of the n = 1 signal and 36 % of n = 3's) or a subtraction of the whole floor
(12 % at n = 3, where the boundaries take 6 w = 0.32 of it); the form factor F(1) is checked
against its formula (without it, k1 = 1 alone would be 9 % high, within the noise of one mode).
Usage: test_capillary.py <scratch directory>"""
import math
import os
import sys

import numpy as np

from membrane_flow import capillary
from checks import NARROW, Checks  # tests/checks.py, next to this script
from synthetic_vtu import write_pvd, write_vtu  # tests/synthetic_vtu.py

scratch = sys.argv[1]
check = Checks(*NARROW)
N, kT, sigma, xi, snapshots, noise = 32, 0.05, 500.0, 0.04, 600, 0.14
lam, width = sigma * xi, 4 * xi / 3
rng = np.random.default_rng(11)
x, y = np.meshgrid(np.arange(N) / N, np.arange(N) / N, indexing='ij')
x, y = x.ravel(), y.ravel()


def boundary():
    """u(y) at the vertex rows: sum over n = 1..8 of 2 Re(u_n exp(2 pi i n y)), <|u_n|^2> = k_BT / (lambda q^2)."""
    u = np.zeros_like(y)
    for n in range(1, 9):
        s = math.sqrt(kT / (lam * (2 * math.pi * n) ** 2) / 2)
        c = complex(rng.normal(0, s), rng.normal(0, s))
        u += 2 * (c * np.exp(2j * math.pi * n * y)).real
    return u


def write_run(name, stripe):
    run = os.path.join(scratch, name)
    os.makedirs(run, exist_ok=True)
    with open(os.path.join(run, 'parameters.prm'), 'w') as f:
        f.write(f'subsection Cahn-Hilliard\n  set Scheme = linearized\nend\n'
                f'subsection Material\n  set Temperature = {kT}\n  set Line tension = {sigma}\n'
                f'  set Transition length = {xi}\n  set Phase mobility = 0.2\nend\n'
                f'subsection Mesh\n  set Cells per side = {N}\nend\n'
                f'subsection Time stepping\n  set Time step = 1e-5\nend\n')
    entries = []
    for k in range(snapshots):
        if stripe:
            phi = np.tanh((x - 0.25 - boundary()) / width) - np.tanh((x - 0.75 - boundary()) / width) - 1
        else:
            phi = -np.ones_like(x)
        # The bulk's noise, less its part along each boundary's translation mode (row by row, as
        # the Gaussian theory of the boundary has it): that part is the boundary's displacement.
        eta = rng.normal(0, noise, (N, N))
        if stripe:
            for centre in (0.25, 0.75):
                mode = 1 / np.cosh((np.arange(N) / N - centre) / width) ** 2
                eta -= np.outer(mode, mode @ eta) / (mode @ mode)
        table = (phi + eta.ravel()).reshape(N, N)
        # Each vertex once per cell, as the simulator writes it; x = 1 and y = 1 are x = 0 and y = 0.
        name = f'surface-{k:06d}.vtu'
        write_vtu(os.path.join(run, name), N, lambda u, v: np.zeros_like(u),
                  lambda u, v: table[np.rint(u * N).astype(int) % N, np.rint(v * N).astype(int) % N], True, 0.01 * k)
        entries.append((0.01 * k, name))
    write_pvd(os.path.join(run, 'surface.pvd'), entries)
    return run


runs = [write_run('stripe1', True), write_run('stripe2', True)]
bulk = write_run('bulk', False)
result = capillary.capillary_spectrum(runs, bulk, skip=0, modes=3, batches=20)
print(capillary.table(result))
F = math.pi**2 * width / math.sinh(math.pi**2 * width)
check(abs(result['form_factor'] - F) < 1e-12, f"form factor F(1) = {result['form_factor']:.4f} at w = 4 xi / 3")
for m in result['modes']:
    n, r, e = m['n'], m['ratio'], m['ratio_error']
    check(e < 0.04 and abs(r - 1) < 3 * e and abs(r - 1) < 0.08,
          f'n = {n}: lambda_n / (sigma xi) = {r:.3f} +- {e:.3f} (within 3 error bars and 8 % of 1, error < 0.04)')
    for k1 in (0, 1):
        check(abs(m[f'ratio_k1_{k1}'] - 1) < 0.12, f"n = {n}: from k1 = {k1} alone {m[f'ratio_k1_{k1}']:.3f} (within 12 %)")
floor = [m['bulk'] / m['expected'] for m in result['modes']]
check(floor[0] > 0.03 and floor[2] > 0.3, f'bulk floor / signal {floor[0]:.2f} at n = 1, {floor[2]:.2f} at n = 3 '
      '(the subtraction is tested)')
sys.exit(check.exit_code())
