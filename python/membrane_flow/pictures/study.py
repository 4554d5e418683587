#!/usr/bin/python3
"""Plot an observable of a sweep against the varied parameter, from its results.csv.
Usage: python3 -m membrane_flow plot-study <results.csv> <parameter column> [--y T_min] [--logy] [--logx] -o out.png
Several CSVs can be given (comma-separated) with matching parameter columns.
Runs where the observable is undefined (T_min of a run that ended before equilibrium) are
listed in the figure and on stderr; if it is undefined in every run, the figure says so
instead of drawing empty axes."""
import argparse
import csv
import sys

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('csv')
    parser.add_argument('x')
    parser.add_argument('--y', default='T_min')
    parser.add_argument('--logy', action='store_true')
    parser.add_argument('--logx', action='store_true')
    parser.add_argument('--title', default='')
    parser.add_argument('-o', '--output', required=True)
    args = parser.parse_args(argv)
    fig, ax = plt.subplots(figsize=(5, 3.8), dpi=90)
    undefined = []  # (x, outcome) of the runs without a value of y
    plotted = 0
    for path in args.csv.split(','):
        with open(path) as f:
            all_rows = list(csv.DictReader(f))
        if all_rows and args.x not in all_rows[0]:
            raise SystemExit(f"{path}: no column '{args.x}'; columns: {', '.join(all_rows[0])}")
        rows = [r for r in all_rows if r.get(args.y) not in (None, '')]
        undefined += sorted((float(r[args.x]), r.get('outcome', '') or 'no outcome')
                            for r in all_rows if r.get(args.y) in (None, ''))
        points = sorted((float(r[args.x]), float(r[args.y]), r.get('outcome', '')) for r in rows)
        plotted += len(points)
        if points:
            ax.plot([p[0] for p in points], [p[1] for p in points], 'o-')
        for x, y, outcome in points:
            ax.annotate(outcome.replace(' bud', ''), (x, y), fontsize=7, xytext=(3, 3), textcoords='offset points')
    if undefined:
        listing = ', '.join(f'{x:g} ({outcome})' for x, outcome in undefined)
        reason = ' (still far from equilibrium at the end of the run)' if args.y == 'T_min' else ''
        print(f'{args.output}: {args.y} undefined{reason} in {len(undefined)} run(s), {args.x} = {listing}',
              file=sys.stderr)
    if plotted == 0:
        message = (f'{args.y} is undefined in all {len(undefined)} runs' if undefined else f'no runs in {args.csv}')
        if undefined and args.y == 'T_min':
            message += '\n(still far from equilibrium at the end of the run:\nlonger runs are needed; docs/workflow.md)'
        if undefined:
            message += '\n' + '\n'.join(f'{args.x} = {x:g}: {outcome}' for x, outcome in undefined[:8])
            if len(undefined) > 8:
                message += f'\n... and {len(undefined) - 8} more'
        ax.text(0.5, 0.5, message, transform=ax.transAxes, ha='center', va='center', fontsize=9, wrap=True)
        ax.set_xticks([])
        ax.set_yticks([])
        ax.set(xlabel=args.x, ylabel=args.y, title=args.title)
        fig.tight_layout()
        fig.savefig(args.output)
        return
    if undefined:
        ax.text(0.02, 0.02, f'{args.y} undefined at {args.x} = ' + ', '.join(f'{x:g}' for x, _ in undefined),
                transform=ax.transAxes, fontsize=7, color='0.3', va='bottom', wrap=True)
    if args.logy:
        ax.set_yscale('log')
    if args.logx:
        ax.set_xscale('log')
    ax.set(xlabel=args.x, ylabel=args.y, title=args.title)
    ax.grid(alpha=0.3, which='both')
    fig.tight_layout()
    fig.savefig(args.output)


if __name__ == '__main__':
    main()
