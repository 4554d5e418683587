#!/usr/bin/python3
"""Plot an observable of a sweep against the varied parameter, from its results.csv.
Usage: plot_study.py <results.csv> <parameter column> [--y T_min] [--logy] [--logx] -o out.png
Several CSVs can be given (comma-separated) with matching parameter columns."""
import argparse
import csv

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('csv')
    parser.add_argument('x')
    parser.add_argument('--y', default='T_min')
    parser.add_argument('--logy', action='store_true')
    parser.add_argument('--logx', action='store_true')
    parser.add_argument('--title', default='')
    parser.add_argument('-o', '--output', required=True)
    args = parser.parse_args()
    fig, ax = plt.subplots(figsize=(5, 3.8), dpi=90)
    for path in args.csv.split(','):
        with open(path) as f:
            rows = [r for r in csv.DictReader(f) if r.get(args.y) not in (None, '')]
        points = sorted((float(r[args.x]), float(r[args.y]), r.get('outcome', '')) for r in rows)
        ax.plot([p[0] for p in points], [p[1] for p in points], 'o-')
        for x, y, outcome in points:
            ax.annotate(outcome.replace(' bud', ''), (x, y), fontsize=7, xytext=(3, 3), textcoords='offset points')
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
