#!/usr/bin/python3
"""Find where the outcome class of a run changes as one parameter varies (bisection).

Every run is a case of a sweep directory (reused if run before); the final bracket and all
runs are written to <output>/bisection.json and printed.

Usage: critical_value.py <base.prm> <Section/Entry> <low> <high> --tolerance T --output DIR
                         [--geometric] [--set 'Section/Entry=value' ...] [--ranks R] [--exe PATH]
Example (critical line tension of 7.3's setup, to 5 %):
  scripts/critical_value.py experiments/7.3-budding.prm 'Material/Line tension' 300 1500 \\
      --tolerance 0.05 --geometric --output results/critical-sigma"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from membrane_workflow.critical import bisect  # noqa: E402
from membrane_workflow.statistics import load_summary  # noqa: E402
from membrane_workflow.sweep import Sweep, write_atomically  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('base')
    parser.add_argument('parameter')
    parser.add_argument('low', type=float)
    parser.add_argument('high', type=float)
    parser.add_argument('--tolerance', type=float, required=True)
    parser.add_argument('--geometric', action='store_true', help='bisect in log space (tolerance on log(high/low))')
    parser.add_argument('--output', required=True)
    parser.add_argument('--set', action='append', default=[], help="fixed override 'Section/Entry=value'")
    parser.add_argument('--ranks', type=int, default=1)
    parser.add_argument('--exe', default=os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'build',
                                                      'membrane-flow'))
    args = parser.parse_args()
    if not args.low < args.high:
        parser.error(f'need low < high (got {args.low}, {args.high})')
    fixed = dict(s.split('=', 1) for s in args.set)
    sweep = Sweep(args.base, args.output, fixed, exe=args.exe, ranks=args.ranks)

    def evaluate(x):
        values = {args.parameter: x}
        _, status = sweep.run_case(values)
        summary = load_summary(sweep.case_dir(values))
        print(f'{args.parameter} = {x:.6g}: {summary["outcome"]} ({status}, {summary["stop_reason"]})', flush=True)
        return summary['outcome']

    result = bisect(evaluate, args.low, args.high, args.tolerance, geometric=args.geometric)
    sweep.write_table()
    result['parameter'] = args.parameter
    write_atomically(os.path.join(args.output, 'bisection.json'), json.dumps(result, indent=1) + '\n')
    low, high = result['bracket']
    print(f'{args.parameter}: outcome changes from "{result["outcomes"][0]}" to "{result["outcomes"][1]}" '
          f'between {low:.6g} and {high:.6g} ({len(result["runs"])} runs)')


if __name__ == '__main__':
    main()
