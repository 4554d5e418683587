#!/usr/bin/python3
"""Draw history.png of this study from the runs' statistics.txt in results/studies/budded-state/.
Usage (from the repository root): /usr/bin/python3 experiments/studies/budded_state/plot.py"""
import os
import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt

B = 'results/studies/budded-state/'
RUNS = [('L1-r1e-4', 'level 1 (1.5 per xi)', 'C0', 0), ('L2-r1e-3', 'level 2 (3 per xi)', 'C1', 0),
        ('L3-r3e-4', 'level 3 (6 per xi)', 'C2', 0),
        ('L3-from-L2-r3e-4', 'level 3, from the level-2 state at t = 27.79', 'C3', 27.79)]


def load(d):
    rows, hdr = [], None
    for line in open(os.path.join(d, 'statistics.txt')):
        if line.startswith('#'):
            hdr = line[1:].split()
            continue
        v = line.split()
        if hdr and len(v) == len(hdr):
            rows.append(dict(zip(hdr, map(float, v))))
    return rows


fig, ax = plt.subplots(3, 1, figsize=(7, 9), sharex=True)
for name, label, c, t0 in RUNS:
    if not os.path.exists(B + name + '/statistics.txt'):
        continue
    r = [x for x in load(B + name) if x['time'] >= max(0.5, t0)]
    t = [x['time'] for x in r]
    ax[0].plot(t, [x['energy'] for x in r], c, label=label)
    ax[1].plot(t, [x['neck_radius'] for x in r], c)
    ax[2].plot(t, [x['bending_energy'] for x in r], c, ls='-')
    ax[2].plot(t, [x['gradient_energy'] + x['well_energy'] for x in r], c, ls='--')
ax[0].axhline(42.364, color='k', lw=0.7, ls=':')
ax[0].text(0.6, 42.6, 'sharp-interface complete bud 42.364', fontsize=8)
ax[0].set_ylabel('energy')
ax[0].legend(fontsize=8)
ax[0].set_ylim(42, 53)
ax[1].set_ylabel('neck_radius')
ax[1].set_ylim(0.0, 0.14)
ax[1].axhline(0.03, color='k', lw=0.7, ls=':')
ax[1].text(0.6, 0.032, 'xi = Pinch-off radius = 0.03', fontsize=8)
ax[2].set_ylabel('bending (solid), line (dashed)')
ax[2].set_xlabel('t')
for a in ax:
    a.grid(alpha=0.3)
fig.tight_layout()
fig.savefig('experiments/studies/budded_state/history.png', dpi=80)
