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
import math


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
