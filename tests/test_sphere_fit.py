#!/usr/bin/python3
"""membrane_flow.spectra.sphere_fit on a synthetic spectrum whose kappa and Sigma are known.

The statistics of a fixed-tau run are written with shape_mode_2 .. shape_mode_6 equal to
k_BT / (K_l (1 + (lambda_b - mu) tau / 2)) times 1 +- 2 % of noise, K_l = kappa s_l (l - 1) l (l + 1)(l + 2)
+ Sigma R^2 (l - 1)(l + 2) with kappa = 1.3, Sigma = 2, a mesh stiffness s_l = 1 + 0.02 l and
tau = 1e-3 (step factors 0.99 to 0.48, so that a fit without them, or with their sign
wrong, misses kappa by far more than its error). The fit with the same stiffness must return
kappa and Sigma within three standard errors and within 1 % and 5 %; the fit with the
continuum's stiffness must return the kappa that absorbs s_l (larger by 7 to 13 %), and
`python3 -m membrane_flow spectrum sphere RUN --fit` prints it.
Usage: test_sphere_fit.py <scratch directory>"""
import contextlib
import io
import math
import os
import sys

import numpy as np

from membrane_flow import spectra
from checks import NARROW, Checks  # tests/checks.py, next to this script

scratch = sys.argv[1]
os.makedirs(scratch, exist_ok=True)
check = Checks(*NARROW)
kT, kappa, sigma, tau, R, rows = 0.05, 1.3, 2.0, 1e-3, 1.0, 4000
degrees = (2, 3, 4, 5, 6)
stiffness = {l: 1 + 0.02 * l for l in degrees}
rng = np.random.default_rng(7)
columns = {'step': np.arange(rows + 1), 'time': tau * np.arange(rows + 1), 'tau': np.r_[0, np.full(rows, tau)],
           'volume': np.full(rows + 1, 4 * math.pi * R**3 / 3), 'gamma_mean': np.full(rows + 1, sigma),
           'gradient_energy': np.zeros(rows + 1), 'well_energy': np.zeros(rows + 1),
           'area': np.full(rows + 1, 4 * math.pi)}
factors = {}
for l in degrees:
    bending = kappa * stiffness[l] * (l - 1) * l * (l + 1) * (l + 2)
    tension = sigma * R**2 * (l - 1) * (l + 2)
    rate = (bending - tension) / (R**4 * (1 + 4 / (l * (l + 1))))
    factors[l] = 1 / (1 + rate * tau / 2)
    expected = kT * factors[l] / (bending + tension)
    columns[f'shape_mode_{l}'] = expected * (1 + 0.02 * rng.standard_normal(rows + 1))
path = os.path.join(scratch, 'statistics.txt')
with open(path, 'w') as f:
    f.write('# ' + ' '.join(columns) + '\n')
    for i in range(rows + 1):
        f.write(' '.join(f'{columns[name][i]:.17g}' for name in columns) + '\n')

fit = spectra.sphere_fit(path, kT, skip=0, batches=20, degrees=degrees, stiffness=stiffness)
print(f"kappa {fit['kappa']:.5f} +- {fit['kappa_error']:.5f}, Sigma {fit['sigma']:.4f} +- {fit['sigma_error']:.4f}")
check(abs(fit['kappa'] - kappa) <= max(3 * fit['kappa_error'], 1e-12) and abs(fit['kappa'] / kappa - 1) <= 0.01,
      f"kappa {fit['kappa']:.5f} +- {fit['kappa_error']:.5f} recovers {kappa} (1 %)")
check(abs(fit['sigma'] - sigma) <= 3 * fit['sigma_error'] and abs(fit['sigma'] / sigma - 1) <= 0.05,
      f"Sigma {fit['sigma']:.4f} +- {fit['sigma_error']:.4f} recovers {sigma} (5 %)")
steps = [m['step_factor'] for m in fit['modes']]
worst = max(abs(m['step_factor'] / factors[m['l']] - 1) for m in fit['modes'])
check(worst <= 1e-3, f"the step factors ({steps[0]:.3f} to {steps[-1]:.3f}) are the input's to {worst:.1e}")
continuum = spectra.sphere_fit(path, kT, skip=0, batches=20, degrees=degrees)
check(1.07 <= continuum['kappa'] / kappa <= 1.13,
      f"with the continuum's stiffness kappa reads {continuum['kappa'] / kappa:.3f} x the input (the s_l it absorbs)")
# The command line prints the same fit.
out = io.StringIO()
with contextlib.redirect_stdout(out):
    code = spectra.main(['sphere', path, '--kT', str(kT), '--skip', '0', '--fit'])
check(code == 0 and f"kappa {continuum['kappa']:.4f}" in out.getvalue(),
      f"spectrum sphere --fit prints kappa {continuum['kappa']:.4f} (exit {code})")
sys.exit(check.exit_code())
