#!/usr/bin/python3
"""Plot the history of one or more runs from their statistics.txt: the free
energy and its terms, the conservation errors (area and integral phi ds) and
the bud observables (height, neck radius, domain protrusion) against time.
The legends sit below the panels, clear of the curves.
Usage: python3 -m membrane_flow plot-history <run-dir> [<run-dir> ...] -o out.png [--labels a,b] [--title T]"""
import argparse
import os

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.ticker import MaxNLocator

from ..run import load_statistics as load


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('runs', nargs='+')
    parser.add_argument('-o', '--output', required=True)
    parser.add_argument('--labels')
    parser.add_argument('--title', default='')
    args = parser.parse_args(argv)
    labels = args.labels.split(',') if args.labels else [os.path.basename(r.rstrip('/')) for r in args.runs]

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2))
    single = len(args.runs) == 1
    for run, label in zip(args.runs, labels):
        s = load(run)
        t = s['time']
        prefix = '' if single else f'{label}: '
        line, = axes[0].plot(t, s['energy'], label=f'{prefix}F' if not single else 'F (total)')
        if single:
            for term in ('bending_energy', 'gradient_energy', 'well_energy', 'gaussian_energy'):
                axes[0].plot(t, s[term], '--', lw=1, label=term.replace('_energy', ''))
        colour = line.get_color()
        axes[1].semilogy(t[1:], np.abs(s['area_drift'][1:]) + 1e-17, color=colour, label=f'{prefix}area')
        axes[1].semilogy(t[1:], np.abs(s['mass_drift'][1:]) + 1e-17, ':', color=colour,
                         label=f'{prefix}integral phi ds')
        axes[2].plot(t, s['bud_height'], color=colour, label=f'{prefix}bud height')
        axes[2].plot(t, s['domain_protrusion'], '--', color=colour, label=f'{prefix}domain protrusion')
        axes[2].plot(t, s['neck_radius'], ':', color=colour, label=f'{prefix}neck radius')
    axes[0].set(xlabel='t', ylabel='free energy', title='energy')
    axes[1].set(xlabel='t', ylabel='|relative drift|', title='conservation')
    axes[2].set(xlabel='t', title='bud observables')
    for ax in axes:
        ax.grid(alpha=0.3)
        # few ticks, so that labels such as 0.0025 do not run together at 80 dpi
        ax.xaxis.set_major_locator(MaxNLocator(nbins=5, steps=[1, 2, 2.5, 5, 10]))
        if ax.get_yscale() == 'linear':
            ax.yaxis.set_major_locator(MaxNLocator(nbins=6, steps=[1, 2, 2.5, 5, 10]))
        else:
            ax.yaxis.set_major_locator(matplotlib.ticker.LogLocator(numticks=6))
        handles = ax.get_legend_handles_labels()[0]
        # below the axes: a legend inside would cover the curves
        ax.legend(loc='upper center', bbox_to_anchor=(0.5, -0.2), fontsize=8, frameon=False,
                  ncol=min(len(handles), 3 if single else 2))
    if args.title:
        fig.suptitle(args.title)
    fig.tight_layout()
    fig.savefig(args.output, dpi=80, bbox_inches='tight', pad_inches=0.08)

if __name__ == '__main__':
    main()
