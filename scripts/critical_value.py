#!/usr/bin/python3
"""Find where the outcome class of a run changes as one parameter varies (bisection).

Every run is a case of a sweep directory (reused if run before; a directory of a different
search or sweep is refused unless --overwrite); the final bracket and all runs are written
to <output>/bisection.json and <output>/results.csv, and printed.

A failed run (simulator exit code != 0 or "failed": true) never ends a bracket: the search
stops there. Whatever happens, results.csv and bisection.json are written ("bracket": null
and an "error" when no bracket was found).

The class of a run is its outcome (summary.json's "outcome") by default; --classify
protrusion:X classes the runs as protruding (domain_protrusion >= X) or not, and --classify
neck:X as necked (neck_ratio < X) or not: the thresholds of scripts/continuation.py. A
protrusion threshold finds the flat-start threshold of a budding setup by an end time at which
no neck has closed yet; the outcome needs a complete bud (Outcome/Complete neck ratio).

Exit codes: 0 bracket found; 1 bad arguments or entry names, or both ends give the same
outcome; 2 a run failed; 130 / 143 stopped by SIGINT / SIGTERM.

Usage: critical_value.py <base.prm> <Section/Entry> <low> <high> --tolerance T --output DIR
                         [--geometric] [--classify outcome|protrusion:X|neck:X]
                         [--set 'Section/Entry=value' ...] [--ranks R] [--exe PATH] [--overwrite]
Example (critical line tension of 7.3's setup, to 5 %):
  scripts/critical_value.py experiments/7.3-budding.prm 'Material/Line tension' 300 1500 \\
      --tolerance 0.05 --geometric --output results/critical-sigma"""
import argparse
import json
import os
import signal
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from membrane_workflow.critical import FailedRun, NoChange, bisect, classifier  # noqa: E402
from membrane_workflow.sweep import Sweep, SweepError, normalize_name, write_atomically  # noqa: E402

NAME = 'critical_value.py'


class Interrupted(Exception):
    pass


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
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
    parser.add_argument('--exe', default=os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'build',
                                                      'membrane-flow'))
    parser.add_argument('--overwrite', action='store_true',
                        help='the output directory holds a different search or sweep: delete its cases first')
    args = parser.parse_args()
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


if __name__ == '__main__':
    try:
        sys.exit(main())
    except KeyboardInterrupt:  # Ctrl-C before any run started
        print(f'{NAME}: interrupted before any run started', file=sys.stderr)
        sys.exit(130)
