#!/usr/bin/python3
"""Run a parameter sweep of membrane-flow (see scripts/membrane_workflow/sweep.py for the
sweep-file format). Results: <output>/results.csv plus each case's own run directory.
A killed sweep started again skips its finished cases.

Before any case runs, every entry name is checked against `membrane-flow --print-parameters`,
and the output directory against the sweep recorded in <output>/sweep.json: a directory of a
different sweep is refused unless --overwrite (which deletes its old cases).

Exit codes: 0 every case finished; 1 bad sweep file, entry name or output directory (nothing
run); 2 some case failed (results.csv is written; failed cases have outcome "failed");
130 / 143 stopped by SIGINT / SIGTERM (running cases are terminated, results.csv is written).

Usage: sweep.py <sweep.json> [--workers N] [--ranks R] [--launcher 'mpirun --hostfile h'] [--exe PATH]
                [--overwrite] [--dry-run]
Example: scripts/sweep.py experiments/sweeps/sigma.json --workers 2"""
import argparse
import os
import signal
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from membrane_workflow.sweep import FAILED, Sweep, SweepError, describe_values  # noqa: E402

NAME = 'sweep.py'


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('sweep_file')
    parser.add_argument('--workers', type=int, default=1,
                        help='cases run at the same time (with N > 1 each case gets OMP_NUM_THREADS=1 and '
                             'OPENBLAS_NUM_THREADS=1 unless set)')
    parser.add_argument('--ranks', type=int, default=1, help='MPI ranks per case (mpirun -np R)')
    parser.add_argument('--launcher', default='mpirun', help='MPI launcher command for --ranks > 1')
    parser.add_argument('--exe', default=os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'build',
                                                      'membrane-flow'))
    parser.add_argument('--overwrite', action='store_true',
                        help='the output directory holds a different sweep: delete its cases and start over')
    parser.add_argument('--dry-run', action='store_true',
                        help='check the sweep file, entry names and output directory, list the cases, run nothing')
    args = parser.parse_args()
    if args.workers < 1 or args.ranks < 1:
        parser.error('--workers and --ranks must be at least 1')
    try:
        sweep, cases = Sweep.from_file(args.sweep_file, exe=args.exe, workers=args.workers, ranks=args.ranks,
                                       launcher=args.launcher)
        sweep.check_names()
        sweep.prepare(overwrite=args.overwrite, dry_run=args.dry_run)
    except SweepError as e:
        print(f'{NAME}: error: {e}', file=sys.stderr)
        return 1
    if args.dry_run:
        for values in cases:
            print(f'{os.path.basename(sweep.case_dir(values))} {describe_values(values)}'
                  f'{" (finished)" if sweep.is_finished(values) else ""}')
        print(f'{len(cases)} cases; output {sweep.output}')
        return 0
    sweep.install_signal_handlers()
    rows = sweep.run(cases, progress=lambda text: print(text, flush=True))
    table = os.path.join(sweep.output, 'results.csv')
    failed = [r for r in rows if r['outcome'] == FAILED]
    print(f'{len(rows)} of {len(cases)} cases in {table}', flush=True)
    if failed:
        print(f'{NAME}: {len(failed)} of {len(rows)} cases failed: ' +
              '; '.join(f'{r["case"]} ({r["stop_reason"]})' for r in failed[:5]) +
              ('; ...' if len(failed) > 5 else ''), file=sys.stderr)
    if sweep.stopping is not None:
        print(f'{NAME}: stopped by {signal.Signals(sweep.stopping).name}: {len(cases) - len(rows)} cases not run '
              f'or interrupted; start the sweep again to run them', file=sys.stderr)
        return 128 + sweep.stopping
    return 2 if failed else 0


if __name__ == '__main__':
    try:
        sys.exit(main())
    except KeyboardInterrupt:  # Ctrl-C before any case started
        print(f'{NAME}: interrupted before any case started', file=sys.stderr)
        sys.exit(130)
