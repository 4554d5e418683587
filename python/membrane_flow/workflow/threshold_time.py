"""The flat-start budding threshold as a function of the end time.

A flat start of the 7.3 setup protrudes like a sphere of its domain area
(domain_protrusion >= 0.95) at a time that grows without bound as sigma falls towards the
threshold. One run per sigma, long enough (to T_max), gives the threshold for every end time
T <= T_max at once: the runs that have crossed by T lie above it, the others below.

brackets() is pure (tested in tests/test_workflow.py); section() reads a sweep's case
directories and writes the part of docs/studies.md."""
import math
import os

from ..run import load_statistics, load_summary, read_json

THRESHOLD = 0.95


def first_crossing(times, protrusion, threshold=THRESHOLD):
    """First time at which protrusion >= threshold (linear between rows); inf if never."""
    for i, (t, p) in enumerate(zip(times, protrusion)):
        if p >= threshold:
            if i == 0:
                return float(t)
            t0, p0 = times[i - 1], protrusion[i - 1]
            return float(t0 + (t - t0) * (threshold - p0) / (p - p0))
    return math.inf


def brackets(runs, end_times):
    """runs: [(sigma, crossing time, time the run reached)]. For each end time T:
    (largest sigma not crossed by T, smallest sigma crossed by T, undecided sigmas), where a
    run that stopped before T without crossing is undecided at T."""
    result = {}
    for T in end_times:
        below = [s for s, c, reached in runs if c > T and reached >= T * (1 - 1e-9)]
        above = [s for s, c, reached in runs if c <= T]
        undecided = [s for s, c, reached in runs if c > T and reached < T * (1 - 1e-9)]
        low = max((s for s in below if not above or s < min(above)), default=None)
        result[T] = (low, min(above) if above else None, sorted(undecided))
    return result


# The studies of docs/studies.md: result directory (and sweep file) name, the mesh, its heading.
STUDIES = {
    'threshold-time': ('the uniform 32 x 32 mesh', '32 x 32'),
    'threshold-time-adaptive1': ('one level of local refinement at the interface (the setting that reproduces '
                                 'uniform 64 x 64)', 'one level of local refinement'),
}


def section(studies, end_times=(2.5, 5, 10), name='threshold-time'):
    """Lines of docs/studies.md for results/studies/<name> (empty without results)."""
    mesh, heading = STUDIES[name]
    cases = os.path.join(studies, name, 'cases')
    if not os.path.isdir(cases):
        return []
    runs, rows = [], []
    for case in sorted(os.listdir(cases)):
        run = os.path.join(cases, case)
        if not os.path.exists(os.path.join(run, 'summary.json')):
            continue
        sigma = float(read_json(os.path.join(run, 'case.json'))['vary']['Material/Line tension'])
        stats, summary = load_statistics(run), load_summary(run)
        crossing = first_crossing(stats['time'], stats['domain_protrusion'])
        runs.append((sigma, crossing, float(summary['time'])))
        rows.append((sigma, crossing, summary))
    if not runs:
        return []
    rows.sort(key=lambda r: r[0])
    table = ['| sigma | protrusion reaches 0.95 at t | run ended at t | stop reason | final protrusion | neck ratio |',
             '|---|---|---|---|---|---|']
    for sigma, crossing, s in rows:
        table.append(f"| {sigma:g} | {'never' if math.isinf(crossing) else f'{crossing:.2f}'} | {s['time']:.2f} | "
                     f"{s['stop_reason'].split(':')[0]} | {s['domain_protrusion']:.2f} | {s['neck_ratio']:.2f} |")
    found = brackets(runs, end_times)
    summary_lines = []
    for T in end_times:
        low, high, undecided = found[T]
        text = (f'between {low:g} and {high:g}' if low is not None and high is not None else
                f'above {low:g}' if low is not None else f'below {high:g}' if high is not None else 'not bracketed')
        if undecided:
            text += f" (undecided: {', '.join(f'{s:g}' for s in undecided)}, whose runs stopped earlier)"
        summary_lines.append(f'- by t = {T:g}: {text}')
    last, previous = end_times[-1], end_times[-2] if len(end_times) > 1 else None
    if previous is not None and found[last][:2] == found[previous][:2] and found[last][0] is not None:
        never = [(s['domain_protrusion'], sigma) for sigma, crossing, s in rows if math.isinf(crossing)]
        top = max(never) if never else None
        necked = [sigma for sigma, _, s in rows if s['neck_ratio'] < 0.4]
        summary_lines.append(
            f'\nThe bracket no longer moves between t = {previous:g} and t = {last:g}'
            + (f': below it the protrusion levels off under 0.95 ({top[0]:.2f} at sigma = {top[1]:g} by '
               f't = {last:g}), so it brackets the long-time state, not a transient. The final protrusions rise '
               'with sigma (' + ', '.join(f"{s['domain_protrusion']:.2f}" for _, _, s in rows) +
               f' from sigma = {rows[0][0]:g} to {rows[-1][0]:g}); ' +
               ('no final state has a neck (neck ratio below 0.4).' if not necked else
                'a neck (neck ratio below 0.4) has formed at sigma = ' + ', '.join(f'{s:g}' for s in necked) + '.')
               if top else '.'))
    sweep = 'experiments/studies/' + name + '.json'
    return [f'## The flat-start threshold against the end time ({heading})\n',
            f'```sh\n/usr/bin/python3 -m membrane_flow sweep {sweep} --workers 2\n```\n',
            f'Flat starts of the 7.3 setup on {mesh}, run to t = {end_times[-1]:g}. The time at which the domain '
            'first protrudes like a sphere of its area (protrusion 0.95, the threshold of the brackets above) grows '
            'as sigma falls, so the flat-start threshold depends on how long one waits:\n'] + summary_lines + [
            f'\nA run that stops before t = {end_times[-1]:g} ("stalled": the step control cannot lower the energy any '
            'more near equilibrium) leaves its sigma undecided for later end times. Every run:\n'] + table + ['']
