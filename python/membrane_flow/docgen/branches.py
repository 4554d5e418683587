"""Write docs/branches.md and docs/images/studies/branches.png: both branches of the 7.3 budding
setup in line tension sigma, on the uniform 32 x 32 mesh and with one level of local refinement
at the interface (the setting that reproduces uniform 64 x 64, docs/mesh-convergence.md), from
the runs of `/usr/bin/python3 -m membrane_flow continuation follow` (the commands are in the page); and
docs/branches-small-domain.md with docs/images/studies/branches-small-domain.png, the same for the
smaller domain of 7.4 D (<studies>/branches-7.4D-adaptive1) against the 7.3 result. Each page is
written when its runs are present.

Usage (from the repository's top directory): python3 -m membrane_flow branch-docs [results/studies] [docs]

Per mesh it reads <studies>/<mesh>/down and <studies>/<mesh>/up (the protruding branch followed
down from sigma = 2000, the flat-start branch followed up from 600) and, when present, further
follows in <studies>/<mesh>/fine/down-* and fine/up-* that start (--start) from a state of a
branch and fill in values between its points; every directory is optional. A follow is read
from its branch.json; if that is missing (the follow was stopped from outside) or records an
error, it is rebuilt from the summary.json of its finished runs and the page says so.

The points of one direction are merged by value: the first follow that ran a value keeps it,
unless a later follow relaxed that same state further (started from the state at that value).
The branch is the class of the main follow (--classify protrusion:0.95); its turning point is
turning_point() of membrane_flow/workflow/continuation.py on [last value on the branch, nearest value
off it beyond], and the energy crossing is crossing() of the two merged branches, as
continuation.py compare computes them."""
import math
import os
import re
import sys

from . import results_and_docs
from .. import run as reader
from ..run import load_statistics
from ..workflow.continuation import crossing, follow_branch, turning_point
from ..workflow.critical import classifier

CLASSIFY = 'protrusion:0.95'
MESHES = [  # result directory, refinement level, label, colour in the figure
    ('branches-32', 0, 'uniform 32 x 32', 'tab:blue'),
    ('branches-adaptive1', 1, 'one level of local refinement', 'tab:red'),
]
SHORT = {'uniform 32 x 32': '32 x 32', 'one level of local refinement': 'level 1',  # labels of the bottom panel
         '7.4 D, one level of local refinement': '7.4 D'}
# The domain-size analysis (paper 7.4 D: integral phi ds = -0.95 against -0.85 of 7.3), on the mesh
# setting of the 7.3 number to quote; its page is docs/branches-small-domain.md.
SMALL_DOMAIN = ('branches-7.4D-adaptive1', 1, '7.4 D, one level of local refinement', 'tab:green')
# The 7.3 result with one level of refinement that the smaller domain is compared with (docs/branches.md).
REFERENCE_73 = {'cross': 692, 'down': (650, 675), 'up': (725, 750), 'domain_area': 0.21}
DIRECTIONS = {'down': 'the protruding branch, followed down', 'up': 'the flat-start branch, followed up'}
SHARP_INTERFACE = 770  # Lipowsky's estimate, quoted in docs/studies.md and docs/experiments.md
COMPLETE_NECK = 0.4    # neck_ratio below which the simulator calls a bud complete


def read_json(path):
    if not os.path.exists(path):
        return None
    return reader.read_json(path)


def finished(summary):
    return summary is not None and not summary['failed'] and not summary['stop_reason'].startswith('interrupted')


def result_of(run, classify):
    """A run of a follow as continuation.py records it, plus where it started from, the time it relaxed
    and its wall time (time and wall_seconds of a resumed run count from the start of the branch)."""
    s = read_json(os.path.join(run, 'summary.json'))
    info = read_json(os.path.join(run, 'run_info.json')) or {}
    start = os.path.dirname(info['resumed_from']) if info.get('resumed_from') else None
    before = read_json(os.path.join(start, 'summary.json')) if start else None
    end_time = re.search(r'Time stepping/End time=(\S+)', info.get('command', ''))
    return {'value': float(os.path.basename(run)), 'state': os.path.join(run, 'checkpoint.txt'),
            'energy': s['energy'], 'class': classify(s), 'time': s['time'],
            'at_plateau': s['stop_reason'].startswith('equilibrium'),
            **{k: s[k] for k in ('outcome', 'domain_protrusion', 'neck_ratio', 'neck_radius', 'stop_reason')},
            'from': os.path.basename(start) if start else 'initial state',
            'relaxed': s['time'] - (before['time'] if before else 0.0),
            'wall': s['wall_seconds'] - (before['wall_seconds'] if before else 0.0),
            'max_time': float(end_time.group(1)) - (before['time'] if before else 0.0) if end_time else None}


def read_follow(directory, direction, studies):
    """One `continuation.py follow`: its branch.json (or None), its runs in the order followed (the
    branch, then the first state of another class) and a note if it had to be rebuilt."""
    record = read_json(os.path.join(directory, 'branch.json'))
    classify = classifier(record['classify'] if record else CLASSIFY)
    note = None
    if record and record.get('error') is None:
        values = [p['value'] for p in record['points'] + ([record['left_at']] if record['left_at'] else [])]
    else:
        done = [float(d) for d in os.listdir(directory) if re.fullmatch(r'[0-9.e+-]+', d) and
                finished(read_json(os.path.join(directory, d, 'summary.json')))]
        wanted = [float(v) for v in record['values']] if record else sorted(done, reverse=direction == 'down')
        ran = []
        for v in wanted:
            if v not in done:
                break
            ran.append(v)
        branch = follow_branch(lambda v, state: {'class': result_of(os.path.join(directory, f'{v:g}'), classify)['class'],
                                                 'state': None, 'energy': None}, ran, None)
        values = [p['value'] for p in branch['points'] + ([branch['left_at']] if branch['left_at'] else [])]
        why = (f"continuation.py stopped with an error: {record['error']}" if record else
               'the follow was stopped before it wrote branch.json')
        note = (f'rebuilt from the summaries of its finished runs ({why})' +
                ('; the branch may go on beyond the last value run' if not branch['left_at'] else ''))
    results = [result_of(os.path.join(directory, f'{v:g}'), classify) for v in values]
    if not results:
        return None
    return {'name': os.path.basename(directory), 'directory': directory, 'studies': studies, 'record': record, 'note': note,
            'class': results[0]['class'], 'results': results}


def merge(follows, direction):
    """The branch of one direction from its follows (the main follow first), in the form of
    membrane_flow/workflow/continuation.py: points on the branch in the order followed, left_at the
    nearest state off it beyond the last one; 'inside' lists states off the branch between its points."""
    main = follows[0]['class']
    by_value = {}
    for follow in follows:
        for r in follow['results']:
            if r['from'] == f"{r['value']:g}":  # relaxed further at the same sigma: replaces that state
                before = by_value.get(r['value'])
                by_value[r['value']] = {**r, 'follow': follow['name']}
                if before:  # the time and wall time at this sigma of both runs
                    by_value[r['value']].update(relaxed=before['relaxed'] + r['relaxed'], wall=before['wall'] + r['wall'],
                                                **{'from': f"{before['from']}, relaxed twice"})
            else:
                by_value.setdefault(r['value'], {**r, 'follow': follow['name']})
    down = direction == 'down'
    on = sorted((r for r in by_value.values() if r['class'] == main), key=lambda r: r['value'], reverse=down)
    off = [r for r in by_value.values() if r['class'] != main]
    beyond = [r for r in off if on and (r['value'] < on[-1]['value'] if down else r['value'] > on[-1]['value'])]
    left_at = min(beyond, key=lambda r: abs(r['value'] - on[-1]['value'])) if beyond else None
    return {'class': main, 'points': on, 'left_at': left_at, 'off': sorted(off, key=lambda r: r['value'], reverse=down),
            'inside': [r for r in off if r not in beyond], 'follows': follows,
            'incomplete': any(f['note'] for f in follows)}


def load_mesh(studies, directory):
    """{'down': branch, 'up': branch} of one mesh, from <studies>/<directory> (also used by the study-docs command)."""
    branches = {}
    for direction in ('down', 'up'):
        follows = []
        main = os.path.join(studies, directory, direction)
        if os.path.isdir(main):
            follows.append(read_follow(main, direction, studies))
        fine = os.path.join(studies, directory, 'fine')
        if os.path.isdir(fine):
            follows += [read_follow(os.path.join(fine, d), direction, studies) for d in sorted(os.listdir(fine))
                        if d.startswith(direction + '-') and os.path.isdir(os.path.join(fine, d))]
        follows = [f for f in follows if f]
        if follows and os.path.basename(follows[0]['directory']) == direction:
            branches[direction] = merge(follows, direction)
    return branches


def command(follow):
    """The command that ran a follow, from its branch.json and its first run."""
    r, out = follow['record'], os.path.join('results', 'studies', os.path.relpath(follow['directory'], follow['studies']))
    if r is None:
        return f'# {out}: no branch.json, command not recorded'
    start = f" --start {r['start']}" if r['start'] else ''
    max_time = follow['results'][0]['max_time']
    options = f"--classify {r['classify']}" + (f' --max-time {max_time:.4g}' if max_time else '') + \
        ('' if r['plateau'] == 1e-3 else f" --plateau {r['plateau']:g}")
    sets = ' '.join(f'--set "{s}"' for s in r['set'])
    return (f"/usr/bin/python3 -m membrane_flow continuation follow {r['base']} \"{r['parameter']}\" {' '.join(f'{v:g}' for v in r['values'])}"
            f"{start} \\\n    {options} --output {out} \\\n    {sets}")


def energy_difference(branches):
    """[(sigma, E(protruding) - E(flat start))] at the values both branches hold."""
    if not (branches.get('down') and branches.get('up')):
        return []
    up = {p['value']: p['energy'] for p in branches['up']['points']}
    return sorted((p['value'], p['energy'] - up[p['value']]) for p in branches['down']['points'] if p['value'] in up)


def plot(results, path, title='7.3 setup: both branches in the line tension', sharp=SHARP_INTERFACE):
    """Top: energy of both branches against sigma; middle: their difference where both exist (zoomed on the
    bistable range); bottom: the turning-point brackets and the crossing of each mesh on the same axis."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    figure = plt.figure(figsize=(7.5, 9.5))
    grid = figure.add_gridspec(3, 1, height_ratios=[3, 2, 1.3])
    top = figure.add_subplot(grid[0])
    middle = figure.add_subplot(grid[1])
    bottom = figure.add_subplot(grid[2], sharex=middle)
    style = {'down': ('o', '-', 'protruding branch, followed down'), 'up': ('s', '--', 'flat-start branch, followed up')}
    rows, labels, edges = 0, [], [sharp]
    for _, _, label, colour, branches, cross in reversed(results):
        for name in ('up', 'down'):
            b = branches.get(name)
            if not b:
                continue
            marker, line, text = style[name]
            turn = turning_point(b)
            if turn:
                lo, hi = sorted(turn)
                edges += [lo, hi]
                bottom.plot([lo, hi], [rows, rows], line, color=colour, linewidth=5, alpha=0.7, solid_capstyle='butt')
                bottom.text(hi + 8, rows, f'[{lo:g}, {hi:g}]', color=colour, va='center', fontsize=8)
            else:
                bottom.text(0.02, rows, 'no turning point reached', color=colour, va='center', fontsize=8,
                            transform=bottom.get_yaxis_transform())
            labels.append(f"{SHORT[label]}: {'protruding' if name == 'down' else 'flat start'} ends")
            rows += 1
        labels.append(f'{SHORT[label]}: energies cross')
        if cross is not None:
            bottom.plot(cross, rows, '*', color=colour, markersize=12)
            bottom.text(cross + 8, rows, f'{cross:.0f}', color=colour, va='center', fontsize=8)
            edges.append(cross)
        else:
            bottom.text(0.02, rows, 'no crossing where both branches were followed', color=colour, va='center',
                        fontsize=8, transform=bottom.get_yaxis_transform())
        rows += 1
    for _, _, label, colour, branches, cross in results:
        for name in ('down', 'up'):
            b = branches.get(name)
            if not b:
                continue
            marker, line, text = style[name]
            top.plot([r['value'] for r in b['points']], [r['energy'] for r in b['points']], line, color=colour,
                     marker=marker, label=f'{label}: {text}')
            for r in b['points']:  # open markers: not at plateau
                if not r['at_plateau']:
                    top.plot(r['value'], r['energy'], marker, color='white', markeredgecolor=colour)
            for r in b['off']:  # crosses: states that have left the branch
                top.plot(r['value'], r['energy'], 'x', color=colour, markersize=8, markeredgewidth=2)
        difference = energy_difference(branches)
        if difference:
            middle.plot(*zip(*difference), '-', color=colour, marker='d', label=label)
        if cross is not None:
            for axis in (top, middle):
                axis.axvline(cross, color=colour, linestyle=':', linewidth=1.5)
    for axis in (top, middle, bottom):
        axis.axvline(sharp, color='gray', linestyle='-.', linewidth=1)
        axis.grid(alpha=0.3)
    middle.text(sharp, 0.97, ' sharp-interface estimate', color='gray', fontsize=8, va='top',
                transform=middle.get_xaxis_transform())
    middle.axhline(0, color='black', linewidth=0.8)
    middle.set_xlim(min(edges) - 60, max(edges) + 110)
    top.set_ylabel('total energy')
    top.set_xlabel('line tension sigma')
    top.set_title(title)
    top.legend(fontsize=7.5, loc='lower right')
    middle.set_ylabel('E(protruding) - E(flat start)')
    middle.legend(fontsize=8, loc='lower left')
    plt.setp(middle.get_xticklabels(), visible=False)
    bottom.set_yticks(range(rows), labels, fontsize=7.5)
    bottom.set_ylim(-0.7, rows - 0.3)
    bottom.set_xlabel('line tension sigma')
    figure.tight_layout()
    os.makedirs(os.path.dirname(path), exist_ok=True)
    figure.savefig(path, dpi=110)
    plt.close(figure)


def mesh_section(directory, level, label, branches, cross, heading=None, fence=None):
    follows = [f for b in branches.values() for f in b['follows']]
    # The uniform-mesh commands are those of studies.md, whose shell blocks the docs test runs
    # already; here they are a plain listing.
    fence = fence or ('text' if level == 0 else 'sh')
    heading = heading or f'## {label[0].upper() + label[1:]} (`Mesh/Maximum refinement level={level}`)'
    lines = [heading + '\n',
             f'```{fence}\n' + '\n'.join(command(f) for f in follows) +
             (f'\n/usr/bin/python3 -m membrane_flow continuation compare results/studies/{directory}/down results/studies/{directory}/up'
              if len(branches) == 2 else '') + '\n```\n']
    if any('fine' in f['directory'] for f in follows):
        lines.append('The follows with `--start` fill in values between the points of the main follows, each from '
                     'the state of the branch at the value given in the column "from"; `continuation.py compare` '
                     'reads only the main follows, the turning points and the crossing below are of all points.\n')
    for name in ('down', 'up'):
        if name not in branches:
            lines.append(f'No data for {DIRECTIONS[name]} on this mesh (no run in results/studies/{directory}/{name}).\n')
    for f in follows:
        if f['note']:
            lines.append(f"**The follow {f['name']} is incomplete**: {f['note']}.\n")
    lines += ['| branch | sigma | from | energy | domain_protrusion | neck_ratio | class | at plateau | relaxed for | run wall time |',
              '|---|---|---|---|---|---|---|---|---|---|']
    necks, walls = [], {}
    for name in ('down', 'up'):
        b = branches.get(name)
        if not b:
            continue
        for r in b['points'] + b['off']:
            necks.append(r['neck_ratio'])
            cls = r['class'] + ('' if r in b['points'] else ' (off the branch)')
            plateau = 'yes' if r['at_plateau'] else 'no: ' + r['stop_reason'].split(':')[0]
            lines.append(f"| {name} | {r['value']:g} | {r['from']} | {r['energy']:.3f} | {r['domain_protrusion']:.3f} | "
                         f"{r['neck_ratio']:.3f} | {cls} | {plateau} | {r['relaxed']:.2f} | {r['wall']:.0f} s |")
        for f in b['follows']:
            walls[f['name']] = sum(r['wall'] for r in f['results'])
    complete = [n for n in necks if n < COMPLETE_NECK]
    lines.append('\n"from": the sigma of the state the run started from; "relaxed for": the time units it relaxed at '
                 'this sigma; "run wall time": its wall time (one run at a time on a 2-core machine shared with other '
                 'work). Wall time of the follows: ' + ', '.join(f'{n} {w / 60:.1f} min' for n, w in walls.items()) +
                 f'. Smallest neck ratio of any state: {min(necks):.3f} ' +
                 (f"({len(complete)} states below {COMPLETE_NECK}, the simulator's complete bud)." if complete else
                  f"(none below {COMPLETE_NECK}, the simulator's complete bud: every state here is at most an "
                  'incomplete bud by its outcome class).') + '\n')
    facts = []
    for name in ('down', 'up'):
        b = branches.get(name)
        if not b:
            continue
        t = turning_point(b)
        first, last = b['points'][0]['value'], b['points'][-1]['value'] if b['points'] else None
        if name == 'down':
            facts.append(f'- The protruding branch, followed down from sigma = {first:g}, ' +
                         (f'holds to sigma = {t[0]:g} and falls back (protrusion below 0.95) between {t[1]:g} and '
                          f'{t[0]:g}.' if t else f'holds at every value followed (down to {last:g}).'))
        else:
            facts.append(f'- The flat-start branch, followed up from sigma = {first:g}, ' +
                         (f'stays below protrusion 0.95 to sigma = {t[0]:g} and protrudes between {t[0]:g} and {t[1]:g}.'
                          if t else f'stays below protrusion 0.95 at every value followed (up to {last:g}).'))
        if b['inside']:
            facts.append(f"- Off the {name} branch between its points: " +
                         ', '.join(f"sigma = {r['value']:g} ({r['class']}, from {r['from']})" for r in b['inside']) +
                         '; the bracket above uses the nearest state beyond the last one on the branch.')
    difference = energy_difference(branches)
    if len(branches) == 2:
        listed = ', '.join(f'{v:g}: {d:+.3f}' for v, d in difference)
        if cross is not None:
            facts.append(f'- Their energies are equal at sigma = {cross:.0f} (linear interpolation of '
                         f'E(protruding) - E(flat start) between the values both branches hold; at sigma = {listed}): '
                         'the thermodynamic threshold on this mesh.')
        elif difference:
            sign = 'lower' if difference[0][1] < 0 else 'higher'
            facts.append(f'- Their energies do not cross where both branches were followed: E(protruding) - '
                         f'E(flat start) at sigma = {listed}; the protruding state is {sign} at every value both hold.')
        else:
            facts.append('- No value is held by both branches: no energy crossing.')
    down = branches.get('down')
    threshold = float(CLASSIFY.partition(':')[2])
    if down and len(down['points']) >= 2 and down['points'][-1]['domain_protrusion'] < threshold + 0.05:
        last, before = down['points'][-1], down['points'][-2]
        facts.append(f"- The last state on the protruding branch, at sigma = {last['value']:g}, protrudes "
                     f"{last['domain_protrusion']:.3f}, just above the class threshold {threshold:g}, with neck ratio "
                     f"{last['neck_ratio']:.3f}, against {before['domain_protrusion']:.3f} and {before['neck_ratio']:.3f} "
                     f"at sigma = {before['value']:g}: the bracket depends on that threshold (with one between "
                     f"{last['domain_protrusion']:.3f} and {before['domain_protrusion']:.3f} this branch would end in "
                     f"[{last['value']:g}, {before['value']:g}]).")
    creeping = [(n, r) for n, b in branches.items() for r in b['points'] if not r['at_plateau']]
    if creeping:
        facts.append('- Not at plateau after their time limit (still relaxing: their energies are upper bounds on '
                     'those of the equilibria they approach): ' + ', '.join(f"{n} {r['value']:g}" for n, r in creeping) + '.')
    return lines + facts + ['']


def quote(summary):
    """The paragraph saying which number to quote, from what the data hold."""
    coarse, fine = summary.get('branches-32'), summary.get('branches-adaptive1')
    lines = ['## Which number to quote\n']
    flat_start = ('Do not quote a flat-start bisection as the critical line tension: it is the line tension above '
                  'which a run from the initial state protrudes by a given end time, a kinetic number that moves with '
                  'the end time (on 32 x 32: 900-925 by t = 2.5, 875-900 by t = 5 and 10; with one level of '
                  'refinement: 775-800 by t = 2.5, 725-750 by t = 5, 700-725 by t = 10, approaching the crossing from '
                  'above; [studies.md](studies.md)).')
    bisections = {'branches-32': (875, 925), 'branches-adaptive1': (771.1, 793.7)}  # from studies.md
    where = []
    for key, label in (('branches-32', 'on 32 x 32'), ('branches-adaptive1', 'with one level of refinement')):
        turn = summary.get(key, {}).get('turns', {}).get('up')
        if turn:
            lo, hi = sorted(turn)
            side = ('below' if bisections[key][1] <= lo else 'above' if bisections[key][0] >= hi else 'inside')
            where.append(f'{label} they lie {side} it, [{lo:g}, {hi:g}]')
    if where:
        flat_start += (' By t = 2.5 it also depends on the path, against the turning bracket of the flat-start '
                       'branch followed here: ' + ', '.join(where) + ' (a run from the initial state and a '
                       'state followed step by step in sigma, relaxing up to 3 time units at each value, reach or miss '
                       'the protruding state differently; with one level of refinement a flat start at 725 protrudes '
                       'at t = 6.35, so that branch\'s bracket is an upper bound at its plateau tolerance).')
    if fine and fine['cross'] is not None:
        text = (f"Quote **sigma_c = {fine['cross']:.0f}**, the energy crossing with one level of local refinement, as "
                'the critical line tension of the 7.3 setup: it is the thermodynamic threshold (above it the '
                'protruding, budded state has the lower energy) on the mesh setting that reproduces uniform 64 x 64.')
        if fine['incomplete']:
            text += ' (Some of its follows are incomplete: see below.)'
        pair = next(((v0, v1) for (v0, d0), (v1, d1) in zip(fine['difference'], fine['difference'][1:])
                     if d0 * d1 <= 0), None)
        if pair:
            settled = all(v in fine['settled'] for v in pair)
            text += (f' The energy difference changes sign between sigma = {pair[0]:g} and {pair[1]:g}, where '
                     + ('all four states are at plateau' if settled else 'not all four states are at plateau') +
                     ', so at this plateau tolerance the crossing lies in that interval whatever the interpolation.')
        if coarse and coarse['cross'] is not None:
            change = 100 * (coarse['cross'] - fine['cross']) / fine['cross']
            text += (f" The uniform 32 x 32 mesh puts the crossing at {coarse['cross']:.0f}, {change:+.0f} % from it" +
                     (': the coarse mesh overstates the line tension needed, as it does for the flat-start threshold.'
                      if change > 0 else '.'))
        turns = '; '.join(f"{'protruding' if n == 'down' else 'flat-start'} branch ends in [{min(t):g}, {max(t):g}]"
                          for n, t in fine['turns'].items() if t)
        text += (f' The sharp-interface estimate is about {SHARP_INTERFACE}. Give the turning-point brackets with it '
                 f'(where each state ceases to exist, at the plateau tolerance 1e-3 per unit time and the 0.95 '
                 f'protrusion class): {turns}. ' + flat_start)
        text += (' Finer interface resolution (levels 2 and 3 in [mesh-convergence.md](mesh-convergence.md)) lowers '
                 'the energy of a run from the initial state at t = 3.1 by 2-4 % at sigma = 1000 (protruding) and by '
                 '0.5-0.7 % at 630 (not protruding) against uniform 64; the branches have not been followed at those '
                 'levels, so how far the crossing would move there is not known.')
        lines.append(text + '\n')
    else:
        if fine:
            text = ('With one level of local refinement the energies of the two branches do not cross where both '
                    'were followed (see its section), so the converged-mesh crossing is not obtained here.')
        else:
            text = ('The branches with local refinement have not been followed, so the converged-mesh crossing is not '
                    'obtained here.')
        if coarse and coarse['cross'] is not None:
            text += (f" On the uniform 32 x 32 mesh the energy crossing is at sigma = {coarse['cross']:.0f}: quote it only "
                     'as the thermodynamic threshold of that mesh, which overstates the flat-start threshold by about '
                     '20 % against local refinement ([studies.md](studies.md)).')
        text += (' The number to quote for the 7.3 setup is the energy crossing with one level of local refinement, '
                 'once it is bracketed; until then, the turning-point brackets of that mesh bound where each state '
                 'exists. ' + flat_start)
        lines.append(text + '\n')
    return lines


def sharp_interface(domain_area, kappa=1.5, xi=0.03):
    """Lipowsky's estimate of the line tension above which a spherical bud of a flat domain of this
    area is the lower-energy state: 8 pi kappa = 2 pi r sigma xi, r = sqrt(A / pi) (docs/experiments.md)."""
    return 4 * kappa / (xi * math.sqrt(domain_area / math.pi))


def small_domain_page(studies, docs):
    """docs/branches-small-domain.md and its figure: both branches of 7.4 D on the mesh setting of the
    7.3 number to quote, against that number. False without data."""
    directory, level, label, colour = SMALL_DOMAIN
    branches = load_mesh(studies, directory)
    if not branches:
        print(f'skipping 7.4 D: no runs in {os.path.join(studies, directory)}')
        return False
    cross = crossing(branches['down'], branches['up']) if len(branches) == 2 else None
    png = os.path.join(docs, 'images', 'studies', 'branches-small-domain.png')
    # The area of the sorted flat domain: phase A of the first state of the flat-start branch.
    first = (branches.get('up') or branches['down'])['points'][0]
    area = load_statistics(os.path.dirname(first['state']))['domain_area'][-1]
    estimate = sharp_interface(area)
    turns = {n: turning_point(b) for n, b in branches.items()}
    difference = energy_difference(branches)
    # Without a sign change where both branches hold, the zero of the difference extrapolated
    # linearly from the two lowest common values, when it shrinks towards them.
    extrapolated = None
    if cross is None and len(difference) >= 2:
        (v0, d0), (v1, d1) = difference[:2]
        if d0 * d1 > 0 and abs(d0) < abs(d1):
            extrapolated = v0 - d0 * (v1 - v0) / (d1 - d0)
    threshold = cross if cross is not None else extrapolated
    plot([(directory, level, label, colour, branches, threshold)], png,
         title='7.4 D (smaller domain): both branches in the line tension', sharp=estimate)
    ref = REFERENCE_73
    ref_estimate = sharp_interface(ref['domain_area'])

    def bracket(t):
        return f'[{min(t):g}, {max(t):g}]' if t else 'not reached'
    lines = ['# Domain size: both branches of the 7.4 D setup\n',
             'The paper\'s Fig. 7.4 D: a smaller domain (`integral phi ds = -0.95`, '
             '[experiments/7.4D-small-domain.prm](../experiments/7.4D-small-domain.prm)) does not bud at a line '
             'tension where the larger one of 7.3 / 7.4 C (`-0.85`) does. The same analysis as for 7.3 '
             '([branches.md](branches.md)), shorter: both branches followed in sigma by `/usr/bin/python3 -m membrane_flow continuation` on '
             'the mesh setting of the 7.3 number to quote (one level of local refinement at the interface), the '
             'protruding branch down from sigma = 2000 and the flat-start branch up from 600, with the protrusion '
             'class 0.95, the plateau tolerance 1e-3 per unit time and at most 3 time units per value. '
             'This page is written by `/usr/bin/python3 -m membrane_flow branch-docs`.\n',
             '![both branches of 7.4 D](images/studies/branches-small-domain.png)\n',
             'Top: total energy at each sigma (circles, solid: the protruding branch followed down; squares, dashed: '
             'the flat-start branch followed up; open markers: not at plateau; crosses: states that have left their '
             'branch). Middle: the energy difference of the two branches; bottom: the turning-point brackets and the '
             'crossing (star; extrapolated when the branches do not cross where both hold, see below). The '
             'dash-dotted line is the sharp-interface estimate for this domain.\n',
             '## Summary\n',
             '| setup | domain area | energy crossing | protruding branch ends in | flat-start branch ends in | '
             'sharp-interface estimate |',
             '|---|---|---|---|---|---|',
             f"| 7.3 (`-0.85`, [branches.md](branches.md)) | {ref['domain_area']:.2f} | {ref['cross']} | "
             f"{bracket(ref['down'])} | {bracket(ref['up'])} | {ref_estimate:.0f} |",
             f"| 7.4 D (`-0.95`) | {area:.3f} | " +
             (f'{cross:.0f}' if cross is not None else f'about {extrapolated:.0f} (extrapolated)' if extrapolated
              else 'not obtained') + ' | ' +
             f"{bracket(turns.get('down'))} | {bracket(turns.get('up'))} | {estimate:.0f} |\n",
             '"domain area": the area of phase A (phi > 0) of the sorted flat domain, the first state of the '
             'flat-start branch; the sharp-interface estimate is `4 kappa / (xi r)` with `r = sqrt(A / pi)` '
             '([experiments.md](experiments.md)).\n']
    if extrapolated is not None:
        listed = ', '.join(f'{v:g}: {d:+.3f}' for v, d in difference)
        down = turns.get('down')
        lines.append('The energies of the two branches do not cross where both hold: E(protruding) - E(flat start) at '
                     f'sigma = {listed}. The difference shrinks towards the lowest common value, and extrapolated '
                     f'linearly from {difference[0][0]:g} and {difference[1][0]:g} it vanishes at sigma = '
                     f'{extrapolated:.0f}' + (f', at the end of the protruding branch ([{min(down):g}, {max(down):g}])'
                                                if down else '') +
                     ': for the smaller domain the protruding state ceases to exist about where it stops being the '
                     'lower-energy one, so the crossing and that turning point agree within the spacing of the values '
                     'followed.\n')
    if threshold is not None:
        shift = 100 * (threshold - ref['cross']) / ref['cross']
        predicted = 100 * (estimate - ref_estimate) / ref_estimate
        lines.append(f"The smaller domain needs a higher line tension to bud: its threshold, sigma_c = {threshold:.0f}, "
                     f"lies {shift:+.0f} % above that of 7.3 ({ref['cross']}), where the sharp-interface theory, in "
                     f"which the threshold scales as 1 / r, predicts {predicted:+.0f} %. Quote sigma_c = {threshold:.0f} "
                     'for the 7.4 D setup, with its turning-point brackets. At the paper\'s sigma = 630 both domains '
                     'lie below their thresholds (on the flat-start branch), so neither buds there with this energy; '
                     'the paper\'s statement that the smaller domain stays unbudded where the larger one buds holds '
                     f"between the two thresholds, {ref['cross']} < sigma < {threshold:.0f}.\n")
    lines += mesh_section(directory, level, label, branches, cross,
                          heading=f'## The runs (`Mesh/Maximum refinement level={level}`)', fence='text')
    with open(os.path.join(docs, 'branches-small-domain.md'), 'w') as f:
        f.write('\n'.join(lines) + '\n')
    print(f"wrote {os.path.join(docs, 'branches-small-domain.md')} and {png}")
    return True


def main(argv=None):
    arguments = results_and_docs(sys.argv[1:] if argv is None else list(argv), 'branch-docs', __doc__)
    if arguments is None:
        return 0
    studies, docs = arguments
    images = os.path.join(docs, 'images', 'studies')
    small = small_domain_page(studies, docs)
    results = []
    for directory, level, label, colour in MESHES:
        branches = load_mesh(studies, directory)
        if not branches:
            print(f'skipping {label}: no runs in {os.path.join(studies, directory)}')
            continue
        cross = crossing(branches['down'], branches['up']) if len(branches) == 2 else None
        results.append((directory, level, label, colour, branches, cross))
    if not results:
        print('no branch data of 7.3: branches.md not written')
        return 0 if small else 1
    png = os.path.join(images, 'branches.png')
    plot(results, png)

    summary = {directory: {'cross': cross, 'turns': {n: turning_point(b) for n, b in branches.items()},
                           'difference': energy_difference(branches),
                           'settled': {p['value'] for p in branches.get('down', {}).get('points', []) if p['at_plateau']}
                           & {p['value'] for p in branches.get('up', {}).get('points', []) if p['at_plateau']},
                           'incomplete': len(branches) < 2 or any(b['incomplete'] for b in branches.values())}
               for directory, level, label, colour, branches, cross in results}
    lines = ['# The critical line tension of the 7.3 setup: both branches\n',
             'The 7.3 budding setup ([experiments/7.3-budding.prm](../experiments/7.3-budding.prm)) is bistable over a '
             'range of line tensions sigma: a flat start that stays an incomplete bud and a protruding (budded) '
             'state are both equilibria. `/usr/bin/python3 -m membrane_flow continuation` ([workflow.md](workflow.md)) follows each branch '
             'in sigma: the protruding branch down from sigma = 2000, the flat-start branch up from 600. Each value '
             'relaxes from the previous one\'s equilibrium until the relative energy rate falls below 1e-3 per unit '
             'time, or for at most 3 time units ("at plateau: no"). The class is that of the protrusion threshold '
             '0.95 (`--classify protrusion:0.95`, as in [studies.md](studies.md)); the neck ratio is listed beside '
             'it. Three numbers come out of this:\n',
             '- the **energy crossing**, where both branches have the same energy: the thermodynamic threshold, '
             'above which the protruding state is the lower-energy one;',
             '- the two **turning points**, brackets [last value on a branch, first value off it] where each state '
             'ceases to exist (a state followed past its turning point falls to the other branch);',
             '- the **flat-start threshold** of a bisection ([studies.md](studies.md)), where a run from the initial '
             'state protrudes by a given end time, is none of these: it depends on how long one waits, a kinetic, not '
             'an equilibrium, number.\n',
             'The same analysis for the smaller domain of 7.4 D is in '
             '[branches-small-domain.md](branches-small-domain.md).\n',
             'The runs use `--set "Mesh/Maximum refinement level=0"` (the paper\'s uniform 32 x 32 mesh) and `=1` '
             '(one level of local refinement at the interface, which reproduces the uniform 64 x 64 energy within '
             '0.1 % at sigma = 630 and 1000, [mesh-convergence.md](mesh-convergence.md)), one run at a time with '
             '`OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1`. This page is written by `/usr/bin/python3 -m membrane_flow branch-docs`.\n',
             '![both branches](images/studies/branches.png)\n',
             'Top: total energy at each sigma (circles, solid: the protruding branch followed down; squares, dashed: '
             'the flat-start branch followed up; open markers: not at plateau; crosses: states that have left their '
             'branch). Middle: the energy difference of the two branches where both exist; it changes sign at the '
             'crossing (dotted lines). Bottom: the turning-point brackets and the crossing of each mesh. The '
             'dash-dotted line is the sharp-interface estimate.\n',
             '## Summary\n',
             '| mesh | energy crossing | protruding branch ends in | flat-start branch ends in | data |',
             '|---|---|---|---|---|']
    for directory, level, label, colour, branches, cross in results:
        s = summary[directory]
        td, tu = s['turns'].get('down'), s['turns'].get('up')
        lines.append(f"| {label} | {f'{cross:.0f}' if cross is not None else 'not obtained'} | "
                     f"{f'[{min(td):g}, {max(td):g}]' if td else 'not reached'} | "
                     f"{f'[{min(tu):g}, {max(tu):g}]' if tu else 'not reached'} | "
                     f"{'incomplete' if s['incomplete'] else 'both branches'} |")
    lines.append(f'| sharp-interface estimate (Lipowsky 1992, [experiments.md](experiments.md)) | about '
                 f'{SHARP_INTERFACE} | | | |\n')
    lines += quote(summary)
    for directory, level, label, colour, branches, cross in results:
        lines += mesh_section(directory, level, label, branches, cross)
    os.makedirs(docs, exist_ok=True)
    with open(os.path.join(docs, 'branches.md'), 'w') as f:
        f.write('\n'.join(lines) + '\n')
    print(f"wrote {os.path.join(docs, 'branches.md')} and {png}")
    return 0


if __name__ == '__main__':
    sys.exit(main())
