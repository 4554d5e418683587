"""Critical-value search: bisection on one parameter for the change between outcome classes.

`bisect(evaluate, low, high, tolerance)` needs evaluate(low) != evaluate(high) (the
classes, e.g. 'incomplete bud' and 'complete bud'); it halves the bracket, keeping
one end in each class, until it is narrower than `tolerance` (absolute; or relative to
the midpoint with relative=True, or in log space with geometric=True). It returns the
final bracket and every evaluation in order. A monotone change is assumed; if the two
ends agree the search stops with an error naming both outcomes.
"""
import math


def bisect(evaluate, low, high, tolerance, geometric=False, relative=False, max_evaluations=60):
    runs = []

    def run(x):
        outcome = evaluate(x)
        runs.append((x, outcome))
        return outcome

    low_outcome, high_outcome = run(low), run(high)
    if low_outcome == high_outcome:
        raise ValueError(f'no change of outcome in [{low}, {high}]: both ends give "{low_outcome}"')

    def width(a, b):
        return (b - a) / (0.5 * (a + b)) if relative else (math.log(b / a) if geometric else b - a)

    while width(low, high) > tolerance and len(runs) < max_evaluations:
        middle = math.sqrt(low * high) if geometric else 0.5 * (low + high)
        if run(middle) == low_outcome:
            low = middle
        else:
            high = middle
    return {'bracket': [low, high], 'outcomes': [low_outcome, high_outcome], 'runs': runs}
