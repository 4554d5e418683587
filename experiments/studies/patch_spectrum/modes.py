#!/usr/bin/python3
"""The patch's thermal height modes reduced to their Fourier amplitudes, with one global area
constraint: the same time discretization as the simulator (bending implicit, tension explicit,
the multiplier of each step chosen so that the excess area is exactly restored), no finite
elements, no local area constraint, no tangential motion.

For a 16 x 16 set of modes x_k (q = 2 pi |k|, stiffness kappa q^4, area (1/2) q^2 x_k^2) a step is

    x* = (x + sqrt(2 k_BT tau L) xi) / (1 + L kappa q^4 tau),
    x' = x* - gamma L tau q^2 x / (1 + L kappa q^4 tau),

with gamma the root of (1/2) sum q^2 x'^2 = Delta A (the smaller one; where the quadratic has
no root, the gamma that minimizes the area: then the step cannot restore the area, as happens
in the simulator when the state is nearly flat). It prints, for the shells |k|^2 = 1 and 2, the
stationary <x^2> against k_BT / (kappa q^4 + Sigma q^2) times the factor of a fixed tau
(membrane_flow.spectra), once with Sigma the plain mean of gamma and once weighted by the mode.
If the plain mean falls short here too, the shortfall belongs to the constrained dynamics, not to
the finite elements or the noise of the simulator (docs/fluctuations.md).

Usage: modes.py            (about a minute; numpy only)
       modes.py physical   (k_BT = 0.05 = kappa/20, tau = 1e-4 and 2e-5, the excess areas of the
                            ALE runs of README.md, "At a physical temperature"; a few seconds)
"""
import math
import sys

import numpy as np


def run(tau, excess, cells=16, kT=1e-4, kappa=1.0, mobility=1.0, steps=30000, skip=4000, seed=1):
    rng = np.random.default_rng(seed)
    ks = [(i, j) for i in range(-cells // 2, cells // 2) for j in range(-cells // 2, cells // 2) if (i, j) != (0, 0)]
    q2 = np.array([4 * math.pi**2 * (i * i + j * j) for i, j in ks])
    bending = mobility * kappa * q2**2 * tau
    x = np.zeros(len(ks))
    shells = [np.array([i * i + j * j == s for i, j in ks]) for s in (1, 2)]
    gammas, heights, unreachable = [], [[], []], 0
    for step in range(steps):
        x_star = (x + math.sqrt(2 * kT * tau * mobility) * rng.standard_normal(len(x))) / (1 + bending)
        lever = mobility * tau * q2 * x / (1 + bending)
        a = 0.5 * np.sum(q2 * lever**2)
        b = -np.sum(q2 * x_star * lever)
        c = 0.5 * np.sum(q2 * x_star**2) - excess
        if a == 0:
            gamma = 0.0
        elif b * b < 4 * a * c:
            gamma, unreachable = -b / (2 * a), unreachable + 1
        else:
            gamma = (-b - math.sqrt(b * b - 4 * a * c)) / (2 * a)
        x = x_star - gamma * lever
        if step >= skip:
            gammas.append(gamma)
            for s in range(2):
                heights[s].append(np.mean(x[shells[s]] ** 2))
    gammas = np.array(gammas)
    rows = []
    for s in range(2):
        h = np.array(heights[s])
        q = 4 * math.pi**2 * (s + 1)
        ratios = []
        for sigma in (gammas.mean(), float(np.mean(gammas * h) / h.mean())):
            factor = 1 / (1 + mobility * (kappa * q * q - sigma * q) * tau / 2)
            ratios.append((sigma, h.mean() / (kT * factor / (kappa * q * q + sigma * q))))
        rows.append(ratios)
    return gammas.mean(), gammas.std(), unreachable / (steps - 0), rows


def physical():
    # The excess area of the initial cosine mode a cos(2 pi (2 u1 + u2)): (1/2) <|grad z|^2> = 5 pi^2 a^2.
    print('| tau | a | excess area | <gamma> | shell | ratio, mode-weighted | Sigma_q |')
    print('|---|---|---|---|---|---|---|')
    for tau in (1e-4, 2e-5):
        for a in (0.0135, 0.0115, 0.0095, 0.008, 0.005):
            excess = 5 * math.pi**2 * a * a
            mean, _, _, rows = run(tau, excess, kT=0.05)
            for s, (_, (weighted_sigma, weighted)) in enumerate(rows):
                print(f'| {tau:g} | {a:g} | {excess:.2e} | {mean:.1f} | |k|^2 = {s + 1} | {weighted:.3f} | '
                      f'{weighted_sigma:.1f} |')


def paper_temperature():
    print('| tau | excess area | <gamma> | std of gamma | steps without a root | shell | '
          'ratio, plain mean | Sigma_q | ratio, mode-weighted |')
    print('|---|---|---|---|---|---|---|---|---|')
    for tau, excess in ((2e-5, 3e-6), (2e-5, 5.5e-6), (1e-5, 5.5e-6), (5e-6, 5.5e-6)):
        mean, spread, unreachable, rows = run(tau, excess)
        for s, ((_, plain), (weighted_sigma, weighted)) in enumerate(rows):
            print(f'| {tau:g} | {excess:g} | {mean:.1f} | {spread:.1f} | {unreachable:.0%} | |k|^2 = {s + 1} | '
                  f'{plain:.3f} | {weighted_sigma:.1f} | {weighted:.3f} |')


if __name__ == '__main__':
    physical() if sys.argv[1:] == ['physical'] else paper_temperature()
