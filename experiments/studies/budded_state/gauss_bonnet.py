#!/usr/bin/python3
"""Budded state of 7.3 at sigma = 1000, levels 1-3, with the Gauss-Bonnet Gaussian energy (06d7f30).

Reads results/studies/budded-state-gb/L<level>/{statistics.txt,summary.json} (run from /work/main, see
README.md, section "With the Gauss-Bonnet Gaussian energy"), writes gauss_bonnet.json and gauss_bonnet.png
next to this script and prints the tables.

    /usr/bin/python3 experiments/studies/budded_state/gauss_bonnet.py [results directory]
"""
import json
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = sys.argv[1] if len(sys.argv) > 1 else 'results/studies/budded-state-gb'
LEVELS = (1, 2, 3)
TIMES = (3.1, 8.0, 12.66, 14.04)
RADII = (0.12, 0.10, 0.09, 0.08, 0.07)
T_SHARPEN = 0.05


def load(level):
    path = os.path.join(ROOT, 'L%d' % level)
    with open(os.path.join(path, 'statistics.txt')) as f:
        names = f.readline().lstrip('#').split()
    data = np.loadtxt(os.path.join(path, 'statistics.txt'), ndmin=2)
    cols = {n: data[:, i] for i, n in enumerate(names)}
    cols['line_energy'] = cols['gradient_energy'] + cols['well_energy']
    summary = None
    if os.path.exists(os.path.join(path, 'summary.json')):
        with open(os.path.join(path, 'summary.json')) as f:
            summary = json.load(f)
    return cols, summary


OLD = {1: 'results/studies/budded-state/L1-r1e-4', 2: 'results/studies/budded-state/L2-r1e-3',
       3: 'results/studies/budded-state/L3-r3e-4'}


# Level 2 was started while the other study (branches-gb) was between two of its phases, and was held with
# SIGSTOP from 06:27:25 to 06:54:07 UTC (at t = 0.80) so that no more than 3 simulations ran at once.
SUSPENDED = {2: 1602.0}


def time_v(level):
    """User time and elapsed time from /usr/bin/time -v, written next to the run directory as L<level>.time."""
    path = os.path.join(ROOT, 'L%d.time' % level)
    out = {}
    if not os.path.exists(path):
        return out
    for line in open(path):
        line = line.strip()
        if line.startswith('User time (seconds):'):
            out['user_seconds'] = float(line.split(':')[1])
        elif line.startswith('Elapsed (wall clock) time'):
            parts = [float(x) for x in line.split(': ')[-1].split(':')]
            out['elapsed_seconds'] = sum(x * 60 ** k for k, x in enumerate(reversed(parts)))
        elif line.startswith('Exit status:'):
            out['exit_status'] = int(line.split(':')[1])
    return out


def compare_old(level, c):
    """Against the 773e5a6 run of the same level (older sections of the README), if its output is present:
    the first row where the time or energy - gaussian_energy differ (by > 1e-9 or 1e-6)."""
    path = os.path.join(OLD[level], 'statistics.txt')
    if not os.path.exists(path):
        return {}
    with open(path) as f:
        names = f.readline().lstrip('#').split()
    d = np.loadtxt(path, ndmin=2)
    o = {n: d[:, i] for i, n in enumerate(names)}
    m = min(len(o['time']), len(c['time']))
    de = np.abs(o['energy'][:m] - o['gaussian_energy'][:m] - c['energy'][:m])
    dt = np.abs(o['time'][:m] - c['time'][:m])
    bad = np.where((dt > 1e-9) | (de > 1e-6))[0]
    k = int(bad[0]) if len(bad) else m
    return {'old_run': OLD[level], 'rows_equal_to_old_minus_gaussian': k,
            'first_difference_at_t': float(c['time'][k]) if k < len(c['time']) else None,
            'max_difference_before': float(de[:k].max()) if k > 0 else None}


def row_at_or_before(t_col, t):
    i = int(np.searchsorted(t_col, t + 1e-9, side='right')) - 1
    return max(i, 0)


def order(e1, e2, e3):
    """Observed order for a refinement ratio of 2; None if the differences are not monotone."""
    d1, d2 = e1 - e2, e2 - e3
    out = {'values': [e1, e2, e3], 'differences': [d1, d2]}
    if d1 * d2 > 0 and d1 != d2:
        p = math.log2(d1 / d2)
        out['p'] = p
        out['extrapolated'] = e3 - d2 / (2.0 ** p - 1.0) if p > 0 else None  # only for a positive order
    else:
        out['p'] = None
        out['note'] = 'not monotone'
    return out


def monotone_part(c):
    """From the first step with a detected neck (neck_ratio < 1) to the end. Returns its first index and the
    largest increase of neck_radius from one step to the next inside it (0 if strictly non-increasing)."""
    below = np.where(c['neck_ratio'] < 1.0)[0]
    if len(below) == 0:
        return None, None
    i0 = int(below[0])
    r = c['neck_radius'][i0:]
    rise = float(np.max(np.diff(r), initial=0.0))
    return i0, max(rise, 0.0)


def at_radius(c, i0, radius, column):
    """Linear interpolation of column in neck_radius at the first crossing of radius after i0."""
    r = c['neck_radius'][i0:]
    y = c[column][i0:]
    t = c['time'][i0:]
    if r[0] < radius:
        return None  # already below at neck formation
    hit = np.where(r <= radius)[0]
    if len(hit) == 0:
        return None  # not reached
    j = int(hit[0])
    if j == 0:
        return float(y[0]), float(t[0])
    w = (r[j - 1] - radius) / (r[j - 1] - r[j])
    return float(y[j - 1] + w * (y[j] - y[j - 1])), float(t[j - 1] + w * (t[j] - t[j - 1]))


def main():
    runs = {lv: load(lv) for lv in LEVELS}
    out = {'root': ROOT, 'runs': {}, 'equal_time': {}, 'equal_neck_radius': {}, 'adaptation': {}}

    for lv, (c, s) in runs.items():
        i0, rise = monotone_part(c)
        info = {
            'final_t': float(c['time'][-1]), 'rows': int(len(c['time'])), 'cells': int(c['cells'][-1]),
            'final_energy': float(c['energy'][-1]), 'final_neck_radius': float(c['neck_radius'][-1]),
            'final_gaussian_energy': float(c['gaussian_energy'][-1]),
            'max_abs_gaussian_energy': float(np.max(np.abs(c['gaussian_energy']))),
            'neck_formed_at_t': float(c['time'][i0]) if i0 is not None else None,
            'neck_radius_at_formation': float(c['neck_radius'][i0]) if i0 is not None else None,
            'largest_neck_radius_rise_after_formation': rise,
        }
        j = row_at_or_before(c['time'], c['time'][-1] - 0.5)
        dt = c['time'][-1] - c['time'][j]
        info['rates_over_last_0.5'] = {
            'from_t': float(c['time'][j]),
            'energy': float((c['energy'][-1] - c['energy'][j]) / dt),
            'relative_energy': float((c['energy'][-1] - c['energy'][j]) / dt / c['energy'][-1]),
            'bending': float((c['bending_energy'][-1] - c['bending_energy'][j]) / dt),
            'line': float((c['line_energy'][-1] - c['line_energy'][j]) / dt),
            'neck_radius': float((c['neck_radius'][-1] - c['neck_radius'][j]) / dt)}
        info.update(compare_old(lv, c))
        info.update(time_v(lv))
        if s is not None:
            for k in ('code_version', 'steps', 'rejected_steps', 'wall_seconds', 'stop_reason', 'outcome',
                      'failed'):
                info[k] = s.get(k)
            info['summary_time'] = s.get('time')
            info['summary_cells'] = s.get('cells')
        if lv in SUSPENDED:
            info['suspended_seconds'] = SUSPENDED[lv]
            info['wall_seconds_running'] = info.get('wall_seconds', 0) - SUSPENDED[lv]
        out['runs']['L%d' % lv] = info

    print('runs:')
    for k, v in out['runs'].items():
        print(' ', k, {x: v.get(x) for x in ('code_version', 'steps', 'rejected_steps', 'wall_seconds', 'final_t',
                                             'cells', 'stop_reason', 'max_abs_gaussian_energy',
                                             'neck_formed_at_t', 'largest_neck_radius_rise_after_formation',
                                             'rows_equal_to_old_minus_gaussian', 'first_difference_at_t',
                                             'user_seconds', 'elapsed_seconds', 'wall_seconds_running')})
        print('    rates over the last 0.5:', {k: round(x, 6) for k, x in v['rates_over_last_0.5'].items()})

    # 1. equal time
    quantities = (('energy', 'energy'), ('bending', 'bending_energy'), ('line', 'line_energy'),
                  ('gaussian', 'gaussian_energy'), ('neck_radius', 'neck_radius'))
    print('\nequal time (row at or before t):')
    for t in TIMES:
        entry = {'levels': {}, 'orders': {}}
        vals = {q: [] for q, _ in quantities}
        for lv, (c, _) in runs.items():
            i = row_at_or_before(c['time'], t)
            e = {'t_row': float(c['time'][i]), 'reached': bool(c['time'][-1] >= t - 1e-9)}
            for q, col in quantities:
                e[q] = float(c[col][i])
                vals[q].append(e[q])
            entry['levels']['L%d' % lv] = e
            print('  t=%5.2f L%d t_row=%.4f%s E=%.5f bend=%.5f line=%.5f gauss=%.2e neck=%.5f' % (
                t, lv, e['t_row'], '' if e['reached'] else ' (NOT REACHED)', e['energy'], e['bending'],
                e['line'], e['gaussian'], e['neck_radius']))
        for q, _ in quantities:
            if q != 'gaussian':
                entry['orders'][q] = order(*vals[q])
        for q in ('energy', 'bending', 'line', 'neck_radius'):
            o = entry['orders'][q]
            print('    %-11s diffs %+.5f %+.5f  p=%s' % (q, o['differences'][0], o['differences'][1],
                                                        'none (not monotone)' if o['p'] is None
                                                        else '%.2f' % o['p']))
        out['equal_time']['%g' % t] = entry

    # 2. equal neck radius
    print('\nequal neck radius (first crossing after the neck forms, linear interpolation):')
    for radius in RADII:
        entry = {'levels': {}, 'orders': {}}
        vals = {'energy': [], 'bending': [], 'line': []}
        for lv, (c, _) in runs.items():
            i0, _ = monotone_part(c)
            e = {}
            for q, col in (('energy', 'energy'), ('bending', 'bending_energy'), ('line', 'line_energy')):
                res = at_radius(c, i0, radius, col) if i0 is not None else None
                e[q] = res[0] if res else None
                e['t'] = res[1] if res else None
                vals[q].append(e[q])
            entry['levels']['L%d' % lv] = e
        for q in vals:
            if all(v is not None for v in vals[q]):
                entry['orders'][q] = order(*vals[q])
        out['equal_neck_radius']['%g' % radius] = entry
        line = '  r=%.2f ' % radius
        for lv in LEVELS:
            e = entry['levels']['L%d' % lv]
            line += ' L%d: E=%s bend=%s t=%s;' % (lv, '%.5f' % e['energy'] if e['energy'] is not None else '-',
                                                 '%.5f' % e['bending'] if e['bending'] is not None else '-',
                                                 '%.3f' % e['t'] if e['t'] is not None else '-')
        print(line)
        for q in ('energy', 'bending', 'line'):
            if q in entry['orders']:
                o = entry['orders'][q]
                print('    %-8s diffs %+.5f %+.5f  p=%s' % (q, o['differences'][0], o['differences'][1],
                                                         'none (not monotone)' if o['p'] is None
                                                         else '%.2f' % o['p']))

    # 3. adaptation
    print('\nadaptation_energy_jump (cumulative):')
    for lv, (c, _) in runs.items():
        i = row_at_or_before(c['time'], T_SHARPEN)
        a = {'at_t_0.05': float(c['adaptation_energy_jump'][i]), 't_row': float(c['time'][i]),
             'at_end': float(c['adaptation_energy_jump'][-1]), 't_end': float(c['time'][-1]),
             'adaptations_at_end': int(c['adaptations'][-1])}
        a['after_t_0.05'] = a['at_end'] - a['at_t_0.05']
        out['adaptation']['L%d' % lv] = a
        print('  L%d: at t=%.3f %+.4f, at end t=%.3f %+.4f (after 0.05: %+.4f), adaptations %d' % (
            lv, a['t_row'], a['at_t_0.05'], a['t_end'], a['at_end'], a['after_t_0.05'], a['adaptations_at_end']))

    with open(os.path.join(HERE, 'gauss_bonnet.json'), 'w') as f:
        json.dump(out, f, indent=1)

    # 4. figure
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(13, 4))
    for lv, (c, _) in runs.items():
        i0, _ = monotone_part(c)
        ax[0].plot(c['neck_radius'][i0:], c['energy'][i0:], label='level %d' % lv)
        ax[1].plot(c['neck_radius'][i0:], c['bending_energy'][i0:], label='level %d' % lv)
        m = c['time'] >= 0.5
        ax[2].plot(c['time'][m], c['energy'][m], label='level %d' % lv)
    for r in RADII:
        ax[0].axvline(r, color='0.85', lw=0.8, zorder=0)
        ax[1].axvline(r, color='0.85', lw=0.8, zorder=0)
    ax[0].set_xlabel('neck radius')
    ax[0].set_ylabel('energy')
    ax[0].invert_xaxis()
    ax[1].set_xlabel('neck radius')
    ax[1].set_ylabel('bending energy')
    ax[1].invert_xaxis()
    ax[2].set_xlabel('time')
    ax[2].set_ylabel('energy')
    for a in ax:
        a.grid(alpha=0.3)
        a.legend()
    fig.suptitle('7.3 at line tension 1000, Gauss-Bonnet Gaussian energy (06d7f30); from neck formation (left, middle)')
    fig.tight_layout()
    fig.savefig(os.path.join(HERE, 'gauss_bonnet.png'), dpi=100)


if __name__ == '__main__':
    main()
