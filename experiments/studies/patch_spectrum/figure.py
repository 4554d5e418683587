#!/usr/bin/python3
"""docs/images/thermal-stationary-spectra.png: the stationary spectra of docs/fluctuations.md
against equilibrium. Left: the patch's height shells |k|^2 = 1, 2 (run.sh of this directory),
measured / expected with the tension each mode feels (filled) and with the plain mean of the area
multiplier (open), for each run. Right: the sphere's l = 2, 3 on 6 x 8 x 8 cells
(experiments/studies/quasi_spherical/run.sh, case n8_tau1e-3) against Milner and Safran with the
continuum's bending stiffness (open) and the mesh's (filled, membrane_flow.spectra.sphere_stiffness).
Error bars: batch means.

Usage: figure.py [build/membrane-flow] [output.png]   (after both run.sh; a few seconds)
"""
import os
import sys

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', '..', 'python'))
from membrane_flow import spectra  # noqa: E402

exe = sys.argv[1] if len(sys.argv) > 1 else 'build/membrane-flow'
out = sys.argv[2] if len(sys.argv) > 2 else 'docs/images/thermal-stationary-spectra.png'
patch_runs = [('2.4e-6, 2e-5', 'a2.2e-4_tau2e-5'), ('4.4e-6, 2e-5', 'a3e-4_tau2e-5'),
              ('4.4e-6, 1e-5', 'a3e-4_tau1e-5'), ('4.4e-6, 5e-6', 'a3e-4_tau5e-6'), ('none, 2e-5', 'a0_tau2e-5')]
fig, (left, right) = plt.subplots(1, 2, figsize=(10, 3.8), gridspec_kw={'width_ratios': [5, 2]})
for x, (label, case) in enumerate(patch_runs):
    try:
        result = spectra.patch_spectrum(os.path.join('results', 'patch_spectrum', case), 1e-4, skip=800)
    except (OSError, spectra.TooFewSteps) as e:  # a run not made or cut short
        print(f'{case}: {e}')
        continue
    for shell, (mode, color) in enumerate(zip(result['modes'], ('C0', 'C1'))):
        position = x + (shell - 0.5) * 0.25
        left.errorbar(position, mode['ratio'], yerr=mode['ratio_error'], fmt='o', color=color,
                      label=f'{mode["mode"]}, tension the mode feels' if x == 0 else None)
        left.plot(position, mode['ratio_plain_mean'], 'o', mfc='none', color=color,
                  label=f'{mode["mode"]}, plain mean of gamma' if x == 0 else None)
left.axhline(1, color='k', lw=0.8)
left.set_xticks(range(len(patch_runs)), [label for label, _ in patch_runs], fontsize=8)
left.set_xlabel('prescribed excess area, tau')
left.set_ylabel('<|h_q|^2> / equilibrium')
left.set_title('flat 16 x 16 patch, k_BT = 1e-4', fontsize=9)
left.legend(fontsize=7, loc='lower left')
left.set_ylim(0.7, 1.15)

sphere = os.path.join('results', 'quasi_spherical', 'n8_tau1e-3')
try:
    stiffness = spectra.sphere_stiffness(exe, 'experiments/vesicle-sphere.prm', ['Mesh/Cells per side=8'], (2, 3))
    result = spectra.sphere_spectrum(sphere, 1e-4, skip=500, degrees=(2, 3), stiffness=stiffness)
    for mode in result['modes']:
        l = int(mode['mode'].split()[-1])
        right.errorbar(l, mode['ratio'], yerr=mode['ratio_error'], fmt='o', color='C2',
                       label='mesh stiffness' if l == 2 else None)
        right.plot(l, mode['ratio_continuum'], 's', mfc='none', color='C2',
                   label='continuum stiffness' if l == 2 else None)
except (OSError, spectra.TooFewSteps) as e:
    print(f'{sphere}: {e}')
right.axhline(1, color='k', lw=0.8)
right.set_xticks([2, 3])
right.set_xlim(1.5, 3.5)
right.set_ylim(0.7, 1.15)
right.set_xlabel('degree l')
right.set_ylabel('<u_lm^2> / Milner-Safran')
right.set_title('sphere, 6 x 8 x 8 cells', fontsize=9)
right.legend(fontsize=7, loc='lower left')
fig.tight_layout()
fig.savefig(out, dpi=110)
print(f'wrote {out}')
