"""Critical-value search: bisection on one parameter for the change between outcome classes.

`bisect(evaluate, low, high, tolerance)` needs evaluate(low) != evaluate(high) (the
classes, e.g. 'incomplete bud' and 'complete bud'); it halves the bracket, keeping
one end in each class, until it is narrower than `tolerance` (absolute; or relative to
the midpoint with relative=True, or in log space with geometric=True). It returns the
final bracket, the two outcomes, every evaluation in order and whether the tolerance was
reached within `max_evaluations`. A monotone change is assumed.

Errors (both carry `runs`, the evaluations so far, and `bracket`, the last valid bracket
or None):
- NoChange (a ValueError): the two ends give the same outcome;
- FailedRun: an evaluation gave an outcome in `failed` (default: 'failed'). A failed run
  has no outcome class, so it never becomes a bracket end: the search stops at once.

`classifier(spec)` turns a class specification into a function of a run's summary (a dict
with the keys of summary.json): 'outcome' (the run's own outcome: flat / incomplete bud /
complete bud / ...), 'protrusion:X' (protruding when domain_protrusion >= X) or 'neck:X'
(necked when neck_ratio < X). A bad specification raises ValueError.
"""
import argparse
import json
import math
import os
import signal
import sys

from .. import launch
from .sweep import Sweep, SweepError, normalize_name, write_atomically


def classifier(spec):
    if spec == 'outcome':
        return lambda s: s['outcome']
    kind, _, threshold = spec.partition(':')
    try:
        x = float(threshold)
    except ValueError:
        x = None
    if x is not None and math.isfinite(x):
        if kind == 'protrusion':
            return lambda s: 'protruding' if s['domain_protrusion'] >= x else 'not protruding'
        if kind == 'neck':
            return lambda s: 'necked' if s['neck_ratio'] < x else 'no neck'
    raise ValueError(f'--classify {spec}: expected outcome, protrusion:X or neck:X (X a number)')


class BisectionError(ValueError):
    def __init__(self, message, runs, bracket=None, outcomes=None):
        super().__init__(message)
        self.runs, self.bracket, self.outcomes = list(runs), bracket, outcomes


class NoChange(BisectionError):
    pass


class FailedRun(BisectionError):
    def __init__(self, message, runs, value, bracket=None, outcomes=None):
        super().__init__(message, runs, bracket, outcomes)
        self.value = value


def bisect(evaluate, low, high, tolerance, geometric=False, relative=False, max_evaluations=60, failed=('failed',)):
    runs = []
    bracket, outcomes = None, None

    def run(x):
        outcome = evaluate(x)
        runs.append((x, outcome))
        if outcome in failed:
            where = (f'inside the bracket [{bracket[0]:.6g}, {bracket[1]:.6g}]' if bracket
                     else 'at an end of the interval')
            raise FailedRun(f'the run at {x:.6g} ({where}) failed: a failed run has no outcome class and cannot '
                            f'end a bracket', runs, x, bracket, outcomes)
        return outcome

    low_outcome, high_outcome = run(low), run(high)
    if low_outcome == high_outcome:
        raise NoChange(f'no change of outcome in [{low}, {high}]: both ends give "{low_outcome}"', runs,
                       outcomes=[low_outcome, high_outcome])
    bracket, outcomes = [low, high], [low_outcome, high_outcome]

    def width(a, b):
        return (b - a) / (0.5 * (a + b)) if relative else (math.log(b / a) if geometric else b - a)

    while width(low, high) > tolerance and len(runs) < max_evaluations:
        middle = math.sqrt(low * high) if geometric else 0.5 * (low + high)
        if run(middle) == low_outcome:
            low = middle
        else:
            high = middle
        bracket = [low, high]
    return {'bracket': [low, high], 'outcomes': [low_outcome, high_outcome], 'runs': runs,
            'converged': width(low, high) <= tolerance}


# -- the command line: python3 -m membrane_flow critical ---------------------------------------

COMMAND_HELP = """Find where the outcome class of a run changes as one parameter varies (bisection).

Every run is a case of a sweep directory (reused if run before; a directory of a different
search or sweep is refused unless --overwrite); the final bracket and all runs are written
to <output>/bisection.json and <output>/results.csv, and printed.

A failed run (simulator exit code != 0 or "failed": true) never ends a bracket: the search
stops there. Whatever happens, results.csv and bisection.json are written ("bracket": null
and an "error" when no bracket was found).

The class of a run is its outcome (summary.json's "outcome") by default; --classify
protrusion:X classes the runs as protruding (domain_protrusion >= X) or not, and --classify
neck:X as necked (neck_ratio < X) or not: the thresholds of the continuation command. A
protrusion threshold finds the flat-start threshold of a budding setup by an end time at which
no neck has closed yet; the outcome needs a complete bud (Outcome/Complete neck ratio).

Exit codes: 0 bracket found; 1 bad arguments or entry names, or both ends give the same
outcome; 2 a run failed; 130 / 143 stopped by SIGINT / SIGTERM.

Usage: python3 -m membrane_flow critical <base.prm> <Section/Entry> <low> <high> --tolerance T --output DIR
           [--geometric] [--classify outcome|protrusion:X|neck:X]
           [--set 'Section/Entry=value' ...] [--ranks R] [--exe PATH] [--overwrite]
Example (critical line tension of 7.3's setup, to 5 %):
  python3 -m membrane_flow critical experiments/7.3-budding.prm 'Material/Line tension' 300 1500 \\
      --tolerance 0.05 --geometric --output results/critical-sigma"""

NAME = 'membrane_flow critical'


class Interrupted(Exception):
    pass


def _main(argv):
    parser = argparse.ArgumentParser(description=COMMAND_HELP, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('base')
    parser.add_argument('parameter')
    parser.add_argument('low', type=float)
    parser.add_argument('high', type=float)
    parser.add_argument('--tolerance', type=float, required=True)
    parser.add_argument('--geometric', action='store_true', help='bisect in log space (tolerance on log(high/low))')
    parser.add_argument('--output', required=True)
    parser.add_argument('--classify', default='outcome',
                        help="class of a run: outcome (default), protrusion:X or neck:X")
    parser.add_argument('--set', action='append', default=[], help="fixed override 'Section/Entry=value'")
    parser.add_argument('--ranks', type=int, default=1)
    parser.add_argument('--exe', help='the program (default: see membrane_flow.launch.find_executable)')
    parser.add_argument('--overwrite', action='store_true',
                        help='the output directory holds a different search or sweep: delete its cases first')
    args = parser.parse_args(argv)
    if not args.low < args.high:
        parser.error(f'need low < high (got {args.low}, {args.high})')
    if args.geometric and args.low <= 0:
        parser.error(f'--geometric needs low > 0 (got {args.low})')
    if not args.tolerance > 0:
        parser.error(f'need --tolerance > 0 (got {args.tolerance})')
    if not os.path.isfile(args.base):
        parser.error(f'the base input file {args.base} does not exist')
    try:
        classify = classifier(args.classify)
    except ValueError as e:  # exit 1 like every bad argument of the search (2 is a failed run)
        print(f'{NAME}: error: {e}', file=sys.stderr)
        return 1
    for s in args.set:
        if '=' not in s:
            parser.error(f"--set {s!r}: write 'Section/Entry=value'")
    try:
        parameter = normalize_name(args.parameter)
        fixed = {}
        for s in args.set:
            name, value = s.split('=', 1)
            if normalize_name(name) in {normalize_name(n) for n in fixed}:
                raise SweepError(f'--set names {normalize_name(name)!r} twice')
            fixed[name] = value
        sweep = Sweep(args.base, args.output, fixed, exe=args.exe, ranks=args.ranks,
                      vary={parameter: 'bisection'}, source='the command line')
        sweep.check_names()
        sweep.prepare(overwrite=args.overwrite)
    except SweepError as e:
        print(f'{NAME}: error: {e}', file=sys.stderr)
        return 1
    sweep.install_signal_handlers()
    cases = []
    what = 'outcome' if args.classify == 'outcome' else f'class ({args.classify})'  # a run's class, in messages

    def evaluate(x):
        values = {parameter: x}
        _, status = sweep.run_case(values)
        if status in ('interrupted', 'not started'):
            raise Interrupted()
        row = sweep.row(sweep.case_dir(values), values)
        # a failed run keeps the class 'failed' whatever the classification
        cls = row['outcome'] if row.get('failed') else classify(row)
        cases.append({'value': x, 'case': row['case'], 'class': cls, 'outcome': row['outcome'],
                      'domain_protrusion': row['domain_protrusion'], 'neck_ratio': row['neck_ratio'],
                      'stop_reason': row['stop_reason'], 'exit_code': row['exit_code']})
        print(f'{parameter} = {x:.6g}: {cls} ({status.split(" (")[0]}, {row["stop_reason"]})', flush=True)
        return cls

    result, code, error = None, 0, None
    try:
        result = bisect(evaluate, args.low, args.high, args.tolerance, geometric=args.geometric)
    except NoChange as e:
        low_outcome = e.outcomes[0]
        error = (f'no change of {what} between {parameter} = {args.low:.6g} and {args.high:.6g}: both ends give '
                 f'"{low_outcome}"; choose an interval whose ends differ')
        result = {'bracket': None, 'outcomes': e.outcomes, 'runs': e.runs, 'status': 'no change'}
        code = 1
    except FailedRun as e:
        case = next((c for c in reversed(cases) if c['value'] == e.value), {})
        error = (f'the run at {parameter} = {e.value:.6g} failed (case {case.get("case")}: {case.get("stop_reason")}; '
                 f'see {os.path.join(args.output, "cases", str(case.get("case")), "log.txt")}). A failed run cannot '
                 f'end a bracket, so the search stops')
        result = {'bracket': None, 'outcomes': e.outcomes, 'runs': e.runs, 'status': 'failed run',
                  'failed_case': case.get('case'), 'last_valid_bracket': e.bracket}
        code = 2
    except Interrupted:
        runs = [[c['value'], c['class']] for c in cases]
        error = f'stopped by {signal.Signals(sweep.stopping).name} after {len(runs)} runs'
        result = {'bracket': None, 'outcomes': None, 'runs': runs, 'status': 'interrupted'}
        code = 128 + sweep.stopping
    if code == 0:
        result['status'] = 'converged' if result['converged'] else 'maximum evaluations'
        if sweep.stopping is not None:
            code = 128 + sweep.stopping
    if error:
        result['error'] = error
    result['parameter'] = parameter
    result['classify'] = args.classify
    result['cases'] = cases
    sweep.write_table()
    write_atomically(os.path.join(args.output, 'bisection.json'), json.dumps(result, indent=1) + '\n')
    if error:
        print(f'{NAME}: error: {error}. Runs: {os.path.join(args.output, "bisection.json")}', file=sys.stderr)
        return code
    low, high = result['bracket']
    print(f'{parameter}: the {what} changes from "{result["outcomes"][0]}" to "{result["outcomes"][1]}" '
          f'between {low:.6g} and {high:.6g} ({len(result["runs"])} runs)')
    if not result['converged']:
        print(f'{NAME}: warning: the bracket is still wider than the tolerance (maximum number of runs reached)',
              file=sys.stderr)
    return code


main = launch.interruptible(_main, NAME, 'run')


if __name__ == '__main__':
    sys.exit(main())
