"""Branch continuation in one parameter: follow an equilibrium as the parameter moves.

A bistable system (a flat or incomplete bud and a complete bud, over a range of line
tensions) has two branches of equilibria. Each is followed by continuation: relax at
the first value from a start state, then move the parameter one step and relax again
*from the previous equilibrium*, until the state leaves the branch (its class changes:
the bud reopens, or the domain buds) or the values run out.

`follow_branch(relax, values, state)` needs relax(value, state) -> dict with at least
'state' (what the next relaxation starts from), 'energy' and 'class'. The branch is the
class of the first relaxation; the first result of another class ends it and is kept
as `left_at`.

From two branches followed towards each other:
- `turning_point(branch)`: the bracket [last value on the branch, first value off it]
  where the branch ends (a saddle-node: the state it was in stops existing);
- `crossing(a, b)`: where the energies of the two branches are equal (linear
  interpolation of E_a - E_b between the values both branches hold), the thermodynamic
  threshold; None if they do not cross where both exist.
"""
import argparse
import json
import os
import sys

from .. import launch, run
from .critical import classifier
from .sweep import write_atomically


def follow_branch(relax, values, state):
    points, left_at, branch = [], None, None
    for value in values:
        result = dict(relax(value, state))
        result['value'] = value
        if branch is None:
            branch = result['class']
        if result['class'] != branch:
            left_at = result
            break
        points.append(result)
        state = result['state']
    return {'class': branch, 'points': points, 'left_at': left_at}


def turning_point(branch):
    """[last value on the branch, first value off it], or None if it never left."""
    if branch['left_at'] is None or not branch['points']:
        return None
    return [branch['points'][-1]['value'], branch['left_at']['value']]


def crossing(a, b):
    """The parameter where the two branches' energies are equal, or None."""
    energy_b = {p['value']: p['energy'] for p in b['points']}
    common = sorted(v for v in (p['value'] for p in a['points']) if v in energy_b)
    energy_a = {p['value']: p['energy'] for p in a['points']}
    return first_zero([(v, energy_a[v] - energy_b[v]) for v in common])


def first_zero(difference):
    """The lowest parameter where [(value, difference)], sorted by value, vanishes (linear
    interpolation at its first sign change), or None."""
    for (v0, d0), (v1, d1) in zip(difference, difference[1:]):
        if d0 == 0:
            return v0
        if d0 * d1 < 0:
            return v0 + (v1 - v0) * d0 / (d0 - d1)
    if difference and difference[-1][1] == 0:
        return difference[-1][0]
    return None


# -- the command line: python3 -m membrane_flow continuation follow / compare -------------------

COMMAND_HELP = """Follow a branch of equilibria of membrane-flow as one parameter moves (continuation).

  python3 -m membrane_flow continuation follow <base.prm> <Section/Entry> <v1> <v2> ... --output DIR
      [--start CHECKPOINT] [--classify outcome|protrusion:0.95|neck:0.4]
                  [--plateau RATE] [--plateau-time T0] [--max-time T] [--set 'Section/Entry=value' ...] [--exe PATH]
  python3 -m membrane_flow continuation compare DIR_A DIR_B

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
  python3 -m membrane_flow continuation follow experiments/7.3-budding.prm 'Material/Line tension' 1000 900 800 700 \\
      --start results/s1000/checkpoint.txt --classify protrusion:0.95 --output results/branch-down"""

NAME = 'membrane_flow continuation'


class RunFailed(Exception):
    pass


def checkpoint_time(path):
    try:
        return run.checkpoint_time(path)
    except ValueError as e:
        raise RunFailed(str(e)) from None


def follow(args):
    classify = classifier(args.classify)
    os.makedirs(args.output, exist_ok=True)
    exe = os.path.abspath(launch.find_executable(args.exe))

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
        result = launch.output(command)
        summary_path = os.path.join(directory, 'summary.json')
        if result.returncode != 0 or not os.path.exists(summary_path):
            last = (result.stderr or result.stdout).strip().splitlines()[-1:] or ['no output']
            raise RunFailed(f'{args.parameter} = {value:g}: exit code {result.returncode}: {last[0]}')
        summary = run.read_json(summary_path)
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
            print(f'{NAME}: error: {path} does not exist (the output of continuation follow)', file=sys.stderr)
            return 1
        branches.append(run.read_json(path))
    for b in branches:
        turn = b['turning_point']
        print(f"branch '{b['class']}' ({len(b['points'])} points): " +
              (f'ends between {turn[0]:g} and {turn[1]:g}' if turn else 'holds at every value followed'))
    value = crossing(*branches)
    print('energies cross at ' + (f'{value:.6g}' if value is not None else 'no value both branches hold'))
    return 0


def main(argv=None):
    parser = argparse.ArgumentParser(description=COMMAND_HELP, formatter_class=argparse.RawDescriptionHelpFormatter)
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
    f.add_argument('--exe', help='the program (default: see membrane_flow.launch.find_executable)')
    c = sub.add_parser('compare')
    c.add_argument('a')
    c.add_argument('b')
    args = parser.parse_args(argv)
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
