#!/usr/bin/python3
"""Numbers of the thermal experiments (docs/fluctuations.md, "Experiments") from their runs.

  analyze.py flicker RUN [--kT 0.05] [--skip T] [--plot OUT.png]
                                                    shape spectrum, time mean over t >= T, against
                                                    Milner and Safran at Sigma = 0 (--plot: its history)
  analyze.py domains RUN [RUN ...] [--min-area A] [--plot OUT.png]
                                                    phase-A domains (connected phi > 0) per snapshot
  analyze.py budding RUN [RUN ...]                  neck ratio, protrusion and outcome at t = 0.05, 0.1
  --json FILE adds the result under the run's name (after --prefix) to FILE (a JSON object).
Runs cut short (the docs test runs 3 steps) give what they have."""
import argparse
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', '..', 'python'))
import membrane_flow as mf  # noqa: E402


def milner_safran(kT, kappa, l, sigma=0.0):
    return kT / (kappa * (l - 1) * (l + 2) * (l * (l + 1) + sigma))


def flicker(run, kT, skip):
    s = mf.load_run(run).statistics
    t = s['time']
    keep = t >= skip if np.any(t >= skip) else np.ones_like(t, bool)
    out = {'steps': int(s['step'][-1]), 't_end': float(t[-1]), 'sampled_from': float(skip),
           'energy_start': float(s['energy'][0]), 'energy_mean': float(np.mean(s['energy'][keep])),
           'min_corner_sine': float(np.min(s['min_corner_sine'])),
           'area_error_max': float(np.max(s['area_error'])),
           'area_error_mean': float(np.mean(s['area_error'][keep])),
           'reduced_volume': [float(s['reduced_volume'][0]), float(s['reduced_volume'][-1])],
           'gamma_mean': float(np.mean(s['gamma_mean'][keep]))}
    for l in (2, 3, 4):
        x = s[f'shape_mode_{l}'][keep]
        n = 10 if len(x) >= 10 else 1
        batches = [b.mean() for b in np.array_split(x, n)]
        out[f'shape_mode_{l}'] = {'mean': float(x.mean()), 'error': float(np.std(batches) / np.sqrt(n)) if n > 1 else None,
                                  'milner_safran': milner_safran(kT, 1.0, l),
                                  'ratio': float(x.mean() / milner_safran(kT, 1.0, l)),
                                  'rms_radius_change_percent': float(100 * np.sqrt((2 * l + 1) * x.mean() / (4 * np.pi)))}
    return out


def plot_flicker(run, kT, skip, path):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    s = mf.load_run(run).statistics
    fig, ax = plt.subplots(figsize=(6, 3.2), dpi=100)
    for l, colour in ((2, 'C0'), (3, 'C1'), (4, 'C2')):
        ax.semilogy(s['time'][1:], s[f'shape_mode_{l}'][1:], colour, lw=0.6, label=f'l = {l}')
        ax.axhline(milner_safran(kT, 1.0, l), color=colour, ls='--', lw=1.2)
    ax.axvline(skip, color='0.5', lw=0.8, ls=':')
    ax.set_xlabel('t')
    ax.set_ylabel('shape_mode_l')
    ax.set_title('flickering vesicle: spectrum (dashed: Milner-Safran, Sigma = 0)', fontsize=9)
    ax.legend(fontsize=8, ncol=3, loc='lower right')
    fig.tight_layout()
    fig.savefig(path)


def domains_of(snapshot, min_area):
    """Connected sets of vertices with phi > 0 (neighbours along cell edges), with their areas
    (a quarter of each cell's area per vertex)."""
    points, cells, phi = snapshot['points'], np.asarray(snapshot['cells']), snapshot['point_data']['phi']
    # merge coincident points (a file may store every vertex once per cell)
    key = np.round(points / 1e-9).astype(np.int64)
    _, index = np.unique(key, axis=0, return_inverse=True)
    index = index.ravel()
    n = index.max() + 1
    phi_v = np.zeros(n)
    phi_v[index] = phi
    c = index[cells]
    p = points[cells]
    area = 0.5 * (np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 3] - p[:, 0]), axis=1) +
                  np.linalg.norm(np.cross(p[:, 1] - p[:, 2], p[:, 3] - p[:, 2]), axis=1))
    vertex_area = np.zeros(n)
    np.add.at(vertex_area, c.ravel(), np.repeat(area / 4, 4))
    parent = np.arange(n)

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i
    inside = phi_v > 0
    for k in range(4):
        for a, b in zip(c[:, k], c[:, (k + 1) % 4]):
            if inside[a] and inside[b]:
                ra, rb = find(a), find(b)
                if ra != rb:
                    parent[ra] = rb
    sizes = {}
    for i in np.nonzero(inside)[0]:
        r = find(i)
        sizes[r] = sizes.get(r, 0.0) + vertex_area[i]
    areas = sorted((a for a in sizes.values() if a >= min_area), reverse=True)
    return areas, float(vertex_area.sum())


def domains(run, min_area):
    r = mf.load_run(run)
    rows = []
    for i, (t, _) in enumerate(r.snapshots):
        areas, total = domains_of(r.snapshot(i), min_area)
        rows.append({'t': t, 'domains': len(areas), 'area_fraction_A': float(sum(areas) / total),
                     'largest_area': float(areas[0]) if areas else 0.0})
    s = r.statistics
    first = next((row['t'] for row in rows if row['domains'] > 0), None)
    # a domain that stays: from this snapshot on, every later one has a domain
    lasting = next((row['t'] for k, row in enumerate(rows) if all(x['domains'] > 0 for x in rows[k:])), None)
    above = np.nonzero(s['phi_max'] > 0.9)[0]
    if 'phase_wavenumber' in s:
        # the structure factor's mean wavenumber (degree l on a closed surface) at each snapshot
        for row in rows:
            row['phase_wavenumber'] = float(s['phase_wavenumber'][int(np.argmin(np.abs(s['time'] - row['t'])))])
    return {'steps': int(s['step'][-1]), 't_end': float(s['time'][-1]),
            'energy': [float(s['energy'][0]), float(s['energy'][-1])],
            'phi_range_end': [float(s['phi_min'][-1]), float(s['phi_max'][-1])],
            'mass_drift_max': float(np.max(np.abs(s['mass_drift']))),
            'min_corner_sine': float(np.min(s['min_corner_sine'])),
            'area_error_max': float(np.max(s['area_error'])),
            'first_snapshot_with_a_domain': first, 'domain_from_snapshot_on': lasting,
            'first_t_phi_max_above_0.9': float(s['time'][above[0]]) if above.size else None,
            'max_domains': max(row['domains'] for row in rows), 'snapshots': rows}


def plot_domains(run, result, path):
    """Number of domains, the largest domain's area and (with Output/Structure factor shells) the
    structure factor's mean wavenumber q_1 against time."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    rows = result['snapshots']
    t = [r['t'] for r in rows]
    s = mf.load_run(run).statistics
    panels = 3 if 'phase_wavenumber' in s else 2
    fig, axes = plt.subplots(panels, 1, figsize=(6, 1.9 * panels), sharex=True)
    axes[0].step(t, [r['domains'] for r in rows], where='post')
    axes[0].set_ylabel('domains')
    axes[1].plot(t, [r['largest_area'] for r in rows], 'o-', ms=3)
    axes[1].set_ylabel('largest domain area')
    if panels == 3:
        axes[2].plot(s['time'], s['phase_wavenumber'], lw=0.8)
        axes[2].set_ylabel('q_1 (degree l)')
    axes[-1].set_xlabel('t')
    axes[0].set_title(f'{os.path.basename(os.path.normpath(run))}: phase-A domains (phi > 0)', fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def budding(run):
    r = mf.load_run(run)
    s = r.statistics
    out = {'steps': int(s['step'][-1]), 't_end': float(s['time'][-1]),
           'outcome': r.summary.get('outcome') if os.path.exists(os.path.join(run, 'summary.json')) else None,
           'min_corner_sine': float(np.min(s['min_corner_sine'])),
           'area_error_max': float(np.max(s['area_error']))}
    for t in (0.05, 0.1):
        i = int(np.argmin(np.abs(s['time'] - t)))
        out[f't={t}'] = {'t': float(s['time'][i]), 'neck_ratio': float(s['neck_ratio'][i]),
                         'neck_radius': float(s['neck_radius'][i]), 'bud_radius': float(s['bud_radius'][i]),
                         'protrusion': float(s['domain_protrusion'][i]), 'energy': float(s['energy'][i])}
    below = np.nonzero(s['neck_ratio'] < 0.4)[0]
    out['first_t_neck_ratio_below_0.4'] = float(s['time'][below[0]]) if below.size else None
    out['min_neck_ratio'] = float(np.min(s['neck_ratio']))
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('what', choices=['flicker', 'domains', 'budding'])
    parser.add_argument('runs', nargs='+')
    parser.add_argument('--kT', type=float, default=0.05)
    parser.add_argument('--skip', type=float, default=0.03)
    parser.add_argument('--min-area', type=float, default=0.02)
    parser.add_argument('--json')
    parser.add_argument('--prefix', default='', help='put before each run name in the results')
    parser.add_argument('--plot', help='flicker: plot the spectrum against time; domains: the domains and the '
                        'structure factor\'s mean wavenumber against time (of the last run); into this PNG')
    a = parser.parse_args()
    results = {}
    for run in a.runs:
        name = a.prefix + os.path.basename(os.path.normpath(run))
        if a.what == 'flicker':
            results[name] = flicker(run, a.kT, a.skip)
            if a.plot:
                plot_flicker(run, a.kT, a.skip, a.plot)
        elif a.what == 'domains':
            results[name] = domains(run, a.min_area)
            if a.plot:
                plot_domains(run, results[name], a.plot)
        else:
            results[name] = budding(run)
    print(json.dumps(results, indent=1))
    if a.json:
        old = json.load(open(a.json)) if os.path.exists(a.json) else {}
        old.update(results)
        with open(a.json, 'w') as f:
            json.dump(old, f, indent=1)
            f.write('\n')


if __name__ == '__main__':
    main()
