#!/usr/bin/python3
"""Run a parameter sweep of membrane-flow (see scripts/membrane_workflow/sweep.py for the
sweep-file format). Results: <output>/results.csv plus each case's own run directory.
A killed sweep started again skips its finished cases.

Usage: sweep.py <sweep.json> [--workers N] [--ranks R] [--launcher 'mpirun --hostfile h'] [--exe PATH]
Example: scripts/sweep.py experiments/sweeps/sigma.json --workers 2"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from membrane_workflow.sweep import Sweep  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('sweep_file')
    parser.add_argument('--workers', type=int, default=1, help='cases run at the same time')
    parser.add_argument('--ranks', type=int, default=1, help='MPI ranks per case (mpirun -np R)')
    parser.add_argument('--launcher', default='mpirun', help='MPI launcher command for --ranks > 1')
    parser.add_argument('--exe', default=os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'build',
                                                      'membrane-flow'))
    args = parser.parse_args()
    sweep, cases = Sweep.from_file(args.sweep_file, exe=args.exe, workers=args.workers, ranks=args.ranks,
                                   launcher=args.launcher)
    rows = sweep.run(cases)
    print(f'{len(rows)} finished cases in {os.path.join(sweep.output, "results.csv")}')


if __name__ == '__main__':
    main()
