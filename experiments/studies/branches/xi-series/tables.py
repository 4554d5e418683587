"""Tables of the xi series of the 7.3 branch continuation (issue 33 item 4).

Reads the follows' branch.json and each run's summary.json / run_info.json / statistics.txt and prints
markdown tables per follow plus the energy differences at the common values; writes tables.json (the rows).
Run from /work/main:  /usr/bin/python3 experiments/studies/branches/xi-series/tables.py
"""
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SERIES = [  # xi, cells per side, directory of the down and up follows
    (0.03, 32, 'results/studies/branches-gb/level2'),
    (0.02, 48, 'results/studies/branches-xi/xi0.02'),
    (0.015, 64, 'results/studies/branches-xi/xi0.015'),
]
# supplementary follows (one or two values each, resumed from a state of the main follows):
# name, side ('down': from the protruding branch, 'up': from the flat-start branch)
SUPPLEMENTARY = {
    0.03: [('results/studies/branches-xi/xi0.03/fine-down', 'down'), ('results/studies/branches-xi/xi0.03/fine-up', 'up'),
           ('results/studies/branches-xi/xi0.03/flat-end', 'up')],
    0.02: [('results/studies/branches-xi/xi0.02/fine-down', 'down'), ('results/studies/branches-xi/xi0.02/fine-down2', 'down'),
           ('results/studies/branches-xi/xi0.02/fine-up', 'up'), ('results/studies/branches-xi/xi0.02/flat-end', 'up')],
    0.015: [('results/studies/branches-xi/xi0.015/fine-down', 'down'), ('results/studies/branches-xi/xi0.015/fine-up', 'up'),
            ('results/studies/branches-xi/xi0.015/flat-end', 'up')],
}


def read_statistics(path):
    lines = open(path).read().splitlines()
    header = lines[0].lstrip('#').split()
    return [dict(zip(header, map(float, l.split()))) for l in lines[1:] if l.strip()]


def start_state(checkpoint):
    """time, wall_seconds, adaptations, adaptation_energy_jump of the run that wrote `checkpoint`."""
    s = json.load(open(os.path.join(os.path.dirname(checkpoint), 'summary.json')))
    return {k: s[k] for k in ('time', 'wall_seconds', 'adaptations', 'adaptation_energy_jump')}


def follow_rows(directory, xi):
    path = os.path.join(directory, 'branch.json')
    if not os.path.exists(path):
        return None, []
    branch = json.load(open(path))
    points = list(branch['points']) + ([branch['left_at']] if branch['left_at'] else [])
    rows, previous = [], (start_state(branch['start']) if branch.get('start') else None)
    for i, p in enumerate(points):
        run = os.path.join(directory, f"{p['value']:g}")
        s = json.load(open(os.path.join(run, 'summary.json')))
        info = json.load(open(os.path.join(run, 'run_info.json')))
        stats = read_statistics(os.path.join(run, 'statistics.txt'))
        start = 0.0
        if info.get('resumed_from'):
            # first row of this run's own history after the resume: the time at the checkpoint
            start = previous['time'] if previous else 0.0
        wall_before = previous['wall_seconds'] if previous else 0.0
        adapt_before = previous['adaptations'] if previous else 0
        jump_before = previous['adaptation_energy_jump'] if previous else 0.0
        row = {'sigma': p['value'], 'lambda': round(p['value'] * xi, 6), 'energy': s['energy'],
               'bending': s['bending_energy'], 'gaussian': s['gaussian_energy'],
               'protrusion': s['domain_protrusion'], 'neck_ratio': s['neck_ratio'], 'class': p['class'],
               'on_branch': i < len(branch['points']), 'at_plateau': p['at_plateau'], 'stop_reason': s['stop_reason'],
               'time': s['time'], 'relaxed_for': s['time'] - start, 'wall_seconds': s['wall_seconds'],
               'run_wall': s['wall_seconds'] - wall_before, 'cells': s['cells'], 'adaptations': s['adaptations'],
               'adaptations_added': s['adaptations'] - adapt_before,
               'adaptation_energy_jump': s['adaptation_energy_jump'],
               'jump_added': s['adaptation_energy_jump'] - jump_before, 'rejected_steps': s['rejected_steps'],
               'irreducible_error_steps': s.get('irreducible_error_steps'), 'failed': s['failed'],
               'grid_control_refused_fraction': s.get('grid_control_refused_fraction'),
               'area_error': s.get('area_error'), 'code_version': s['code_version'],
               'finest_level': stats[-1].get('refinement_level'), 'follow': directory,
               'from': (os.path.basename(os.path.dirname(info['resumed_from'])) if info.get('resumed_from') else 'initial state')}
        rows.append(row)
        previous = {'time': s['time'], 'wall_seconds': s['wall_seconds'], 'adaptations': s['adaptations'],
                    'adaptation_energy_jump': s['adaptation_energy_jump']}
    return branch, rows


def table(rows):
    out = ['| sigma | lambda | energy | bending | protrusion | neck ratio | class | at plateau | relaxed for | run wall | '
           'cells | adaptations | adaptation_energy_jump | rejected |',
           '|---|---|---|---|---|---|---|---|---|---|---|---|---|---|']
    for r in rows:
        cls = r['class'] + ('' if r['on_branch'] else ' (off the branch)')
        plateau = 'yes' if r['at_plateau'] else 'no: ' + r['stop_reason']
        out.append(f"| {r['sigma']:g} | {r['lambda']:.4g} | {r['energy']:.4f} | {r['bending']:.4f} | "
                   f"{r['protrusion']:.3f} | {r['neck_ratio']:.3f} | {cls} | {plateau} | {r['relaxed_for']:.2f} | "
                   f"{r['run_wall']:.0f} s | {r['cells']} | {r['adaptations']} (+{r['adaptations_added']}) | "
                   f"{r['adaptation_energy_jump']:+.3f} ({r['jump_added']:+.3f}) | {r['rejected_steps']} |")
    return '\n'.join(out)


def main():
    os.chdir(os.path.join(HERE, '..', '..', '..', '..'))
    result = []
    for xi, n, base in SERIES:
        entry = {'xi': xi, 'cells_per_side': n}
        print(f'## xi = {xi} (cells per side {n}, level 2, interface cells per xi 3)\n')
        for name in ('down', 'up'):
            branch, rows = follow_rows(os.path.join(base, name), xi)
            entry[name] = {'rows': rows, 'turning_point': branch and branch.get('turning_point'),
                           'error': branch and branch.get('error')}
            print(f'### {name} ({os.path.join(base, name)})\n')
            print(table(rows) if rows else '(not available)')
            print(f"\nturning point: {branch and branch.get('turning_point')}, error: {branch and branch.get('error')}\n")
        entry['supplementary'] = []
        for directory, side in SUPPLEMENTARY.get(xi, []):
            branch, rows = follow_rows(directory, xi)
            if not rows:
                continue
            for r in rows:
                r['side'] = side
            entry['supplementary'].append({'follow': directory, 'side': side, 'start': branch.get('start'), 'rows': rows})
            print(f'### supplementary, {side} side ({directory}, from {branch.get("start")})\n')
            print(table(rows))
            print()
        down = {r['sigma']: r for r in entry['down']['rows'] if r['on_branch']}
        up = {r['sigma']: r for r in entry['up']['rows'] if r['on_branch']}
        common = sorted(set(down) & set(up))
        entry['differences'] = [{'sigma': s, 'lambda': round(s * xi, 6),
                                 'E_protruding': down[s]['energy'], 'E_flat': up[s]['energy'],
                                 'difference': down[s]['energy'] - up[s]['energy'],
                                 'both_at_plateau': down[s]['at_plateau'] and up[s]['at_plateau']} for s in common]
        # also every sigma where both follows have a state, on or off the branch
        alld = {r['sigma']: r for r in entry['down']['rows']}
        allu = {r['sigma']: r for r in entry['up']['rows']}
        for sup in entry['supplementary']:
            for r in sup['rows']:
                (alld if sup['side'] == 'down' else allu).setdefault(r['sigma'], r)
        entry['all_pairs'] = [{'sigma': s, 'lambda': round(s * xi, 6), 'E_down': alld[s]['energy'],
                               'E_up': allu[s]['energy'], 'difference': alld[s]['energy'] - allu[s]['energy'],
                               'P_down': alld[s]['protrusion'], 'P_up': allu[s]['protrusion'],
                               'class_down': alld[s]['class'], 'class_up': allu[s]['class'],
                               'cells_down': alld[s]['cells'], 'cells_up': allu[s]['cells'],
                               'plateau_down': alld[s]['at_plateau'], 'plateau_up': allu[s]['at_plateau']}
                              for s in sorted(set(alld) & set(allu))]
        print('| sigma | lambda | E(protruding) | E(flat) | difference | both at plateau |\n|---|---|---|---|---|---|')
        for d in entry['differences']:
            print(f"| {d['sigma']:g} | {d['lambda']:.4g} | {d['E_protruding']:.4f} | {d['E_flat']:.4f} | "
                  f"{d['difference']:+.4f} | {'yes' if d['both_at_plateau'] else 'no'} |")
        print('\nall states at the same sigma, main and supplementary follows, on or off their branch '
              '(down side minus up side):\n')
        print('| sigma | lambda | E down side | E up side | difference | protrusion down / up | class down / up | '
              'cells down / up | at plateau down / up |\n|---|---|---|---|---|---|---|---|---|')
        for d in entry['all_pairs']:
            print(f"| {d['sigma']:g} | {d['lambda']:.4g} | {d['E_down']:.4f} | {d['E_up']:.4f} | {d['difference']:+.4f} | "
                  f"{d['P_down']:.3f} / {d['P_up']:.3f} | {d['class_down']} / {d['class_up']} | "
                  f"{d['cells_down']} / {d['cells_up']} | {'yes' if d['plateau_down'] else 'no'} / "
                  f"{'yes' if d['plateau_up'] else 'no'} |")
        print()
        result.append(entry)
    with open(os.path.join(HERE, 'tables.json'), 'w') as f:
        json.dump(result, f, indent=1)
        f.write('\n')


if __name__ == '__main__':
    sys.exit(main())
