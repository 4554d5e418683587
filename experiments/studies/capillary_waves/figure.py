#!/usr/bin/python3
"""docs/images/capillary_waves.png from results.json (README.md beside this script): left, the
boundary's spectrum, the stripe's excess S_n - (1 - 6 w) B_n against 8 k_BT / (sigma xi q^2);
right, lambda_n / (sigma xi) of every run of the study against n.
Usage: figure.py [results.json] [out.png]"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import NullFormatter, ScalarFormatter  # noqa: E402

here = os.path.dirname(os.path.abspath(__file__))
source = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, 'results.json')
target = sys.argv[2] if len(sys.argv) > 2 else os.path.join(here, '..', '..', '..', 'docs', 'images',
                                                            'capillary_waves.png')
result = json.load(open(source))
fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))

modes = result['modes']
n = [m['n'] for m in modes]
excess = [8 * result['k_BT'] / ((2 * math.pi * m['n']) ** 2 * m['lambda_n']) for m in modes]
left.loglog(n, [m['expected'] for m in modes], 'k-', label='8 k_BT / (sigma xi q^2)')
left.loglog(n, excess, 'o', label='stripe less (1 - 6 w) bulk')
left.loglog(n, [m['stripe'] for m in modes], 's', mfc='none', label='stripe')
left.loglog(n, [m['bulk'] for m in modes], '^', mfc='none', label='bulk')
left.set_xlabel('n (q = 2 pi n)')
left.set_ylabel('<|phi_(k1, n)|^2>')
left.set_title(f"k_BT = {result['k_BT']:g}, sigma xi = {result['sigma_xi']:g}, tau = {result['tau']:g}")
left.legend(fontsize=8)

cases = [(f"{result['scheme']}, tau = {result['tau']:g}", result)]
cases += [(f"{c['scheme']}, tau = {c['tau']:g}", c) for c in result.get('scheme_comparison', {}).values()]
for label, case in cases:
    right.errorbar([m['n'] for m in case['modes']], [m['ratio'] for m in case['modes']],
                   yerr=[m['ratio_error'] for m in case['modes']], marker='o', capsize=3, label=label)
right.axhline(1, color='k', lw=0.8)
right.axhspan(0.9, 1.1, color='0.9')
right.set_xlabel('n')
right.set_ylabel('lambda_n / (sigma xi)')
right.set_yscale('log')
right.legend(fontsize=8)
for axis in (left.xaxis, right.yaxis):
    axis.set_major_formatter(ScalarFormatter())
    axis.set_minor_formatter(NullFormatter())
left.set_xticks(n)
right.set_yticks([0.5, 0.7, 1, 1.5, 2, 3])
fig.tight_layout()
fig.savefig(target + '.part.png', dpi=110)
os.replace(target + '.part.png', target)
print(target)
