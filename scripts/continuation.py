#!/usr/bin/python3
"""Follow a branch of equilibria of membrane-flow as one parameter moves (continuation).

  continuation.py follow <base.prm> <Section/Entry> <v1> <v2> ... --output DIR
                  [--start CHECKPOINT] [--classify outcome|protrusion:0.95|neck:0.4]
                  [--plateau RATE] [--plateau-time T0] [--max-time T] [--set 'Section/Entry=value' ...] [--exe PATH]
  continuation.py compare DIR_A DIR_B

`follow` relaxes at v1 (from CHECKPOINT, or from the input's initial state), then at each
next value resumes from the previous equilibrium's checkpoint with the changed parameter
(recorded as a change on resume in the run's run_info.json) and relaxes again. A run stops
on the plateau criterion `Time stepping/Equilibrium rate` = RATE (relative energy change
per unit time; default 1e-3), held for T0 time units (`Time stepping/Equilibrium time`,
default 0: one step), or after T more time units (default 10; such a point is
marked "not at plateau"). The branch ends at the first state of another class: the bud
reopens, or the domain buds. Each value's run is DIR/<value>/; DIR/branch.json holds the
points, the class, and the turning-point bracket [last value on the branch, first off it].

Classes: `outcome` is the simulator's outcome class (flat / incomplete bud / complete bud,
a complete bud needs a neck); `protrusion:X` is "protruding" when domain_protrusion >= X;
`neck:X` is "necked" when neck_ratio < X.

`compare` reads two branch.json files (followed towards each other) and prints where their
energies cross (the thermodynamic threshold) and both turning points.

Exit codes: 0 done; 1 bad arguments; 2 a run failed (the branch so far is written);
130 / 143 interrupted.

Example (the complete-bud branch of 7.3 followed down in line tension from a budded state):
  scripts/continuation.py follow experiments/7.3-budding.prm 'Material/Line tension' 1000 900 800 700 \\
      --start results/s1000/checkpoint.txt --classify protrusion:0.95 --output results/branch-down"""
import argparse
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from membrane_workflow.critical import classifier  # noqa: E402
from membrane_workflow.continuation import crossing, follow_branch, turning_point  # noqa: E402
from membrane_workflow.sweep import write_atomically  # noqa: E402

NAME = 'continuation.py'


class RunFailed(Exception):
    pass


def checkpoint_time(path):
    with open(path) as f:
        for line in f:
            if line.startswith('time '):
                return float(line.split()[1])
            if line.startswith('parameters'):
                break
    raise RunFailed(f'{path} is not a checkpoint of membrane-flow (no time)')


def follow(args):
    classify = classifier(args.classify)
    os.makedirs(args.output, exist_ok=True)
    exe = os.path.abspath(args.exe)

    def relax(value, checkpoint):
        directory = os.path.join(args.output, f'{value:g}')
        command = [exe, '--quiet', '--overwrite', *sum((['--set', s] for s in args.set), []),
                   '--set', f'{args.parameter}={value:g}', '--set', f'Output/Directory={directory}',
                   '--set', 'Checkpoint/Interval=1000000', '--set', f'Time stepping/Equilibrium rate={args.plateau:g}',
                   '--set', f'Time stepping/Equilibrium time={args.plateau_time:g}']
        start = 0.0
        if checkpoint:
            start = checkpoint_time(checkpoint)
            command += ['--set', f'Checkpoint/Resume from={os.path.abspath(checkpoint)}']
        command += ['--set', f'Time stepping/End time={start + args.max_time:g}', args.base]
        result = subprocess.run(command, capture_output=True, text=True)
        summary_path = os.path.join(directory, 'summary.json')
        if result.returncode != 0 or not os.path.exists(summary_path):
            last = (result.stderr or result.stdout).strip().splitlines()[-1:] or ['no output']
            raise RunFailed(f'{args.parameter} = {value:g}: exit code {result.returncode}: {last[0]}')
        with open(summary_path) as f:
            summary = json.load(f)
        point = {'state': os.path.join(directory, 'checkpoint.txt'), 'energy': summary['energy'],
                 'class': classify(summary), 'time': summary['time'],
                 'at_plateau': summary['stop_reason'].startswith('equilibrium'),
                 **{k: summary[k] for k in ('outcome', 'domain_protrusion', 'neck_ratio', 'neck_radius',
                                            'stop_reason')}}
        print(f"{args.parameter} = {value:g}: {point['class']}, energy {point['energy']:.6g}, t = {point['time']:.4g}"
              f"{'' if point['at_plateau'] else ' (not at plateau)'}", flush=True)
        return point

    error, branch = None, {'class': None, 'points': [], 'left_at': None}
    try:
        branch = follow_branch(relax, args.values, args.start)
    except RunFailed as e:
        error = str(e)
    record = {'parameter': args.parameter, 'base': args.base, 'values': args.values, 'set': args.set,
              'classify': args.classify, 'plateau': args.plateau,
              'plateau_time': args.plateau_time, 'start': args.start, **branch,
              'turning_point': turning_point(branch) if error is None else None, 'error': error}
    write_atomically(os.path.join(args.output, 'branch.json'), json.dumps(record, indent=1) + '\n')
    if error:
        print(f'{NAME}: error: {error}; the branch so far is in {args.output}/branch.json', file=sys.stderr)
        return 2
    turn = record['turning_point']
    print(f"branch '{branch['class']}': " + (f'ends between {turn[0]:g} and {turn[1]:g}' if turn else
                                            'holds at every value'))
    return 0


def compare(args):
    branches = []
    for directory in (args.a, args.b):
        path = os.path.join(directory, 'branch.json')
        if not os.path.isfile(path):
            print(f'{NAME}: error: {path} does not exist (the output of continuation.py follow)', file=sys.stderr)
            return 1
        with open(path) as f:
            branches.append(json.load(f))
    for b in branches:
        turn = b['turning_point']
        print(f"branch '{b['class']}' ({len(b['points'])} points): " +
              (f'ends between {turn[0]:g} and {turn[1]:g}' if turn else 'holds at every value followed'))
    value = crossing(*branches)
    print('energies cross at ' + (f'{value:.6g}' if value is not None else 'no value both branches hold'))
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest='command', required=True)
    f = sub.add_parser('follow')
    f.add_argument('base')
    f.add_argument('parameter')
    f.add_argument('values', type=float, nargs='+')
    f.add_argument('--output', required=True)
    f.add_argument('--start', default=None, help='checkpoint to start from (default: the initial state)')
    f.add_argument('--classify', default='outcome')
    f.add_argument('--plateau', type=float, default=1e-3)
    f.add_argument('--plateau-time', type=float, default=0.0,
                   help='how long the rate must stay below --plateau (Time stepping/Equilibrium time)')
    f.add_argument('--max-time', type=float, default=10.0)
    f.add_argument('--set', action='append', default=[])
    f.add_argument('--exe', default=os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'build',
                                                 'membrane-flow'))
    c = sub.add_parser('compare')
    c.add_argument('a')
    c.add_argument('b')
    args = parser.parse_args()
    if args.command == 'compare':
        return compare(args)
    try:
        classifier(args.classify)
    except ValueError as e:
        parser.error(str(e))
    if not os.path.isfile(args.base):
        parser.error(f'the base input file {args.base} does not exist')
    if args.start and not os.path.isfile(args.start):
        parser.error(f'--start {args.start} does not exist')
    if not (args.plateau > 0 and args.max_time > 0):
        parser.error('--plateau and --max-time must be positive')
    if not 0 <= args.plateau_time < args.max_time:
        parser.error('--plateau-time must be at least 0 and less than --max-time')
    try:
        return follow(args)
    except KeyboardInterrupt:
        return 130


if __name__ == '__main__':
    sys.exit(main())
