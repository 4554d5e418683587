#!/usr/bin/python3
"""Long relaxation of the protruding and flat 7.3 states at level 2 near the crossing (issue 33, follow-up of
tight-plateau.md): do the two states at the same sigma converge to one equilibrium?

Reads results/studies/branches-gb/level2/long/<run>/<sigma>/{statistics.txt,summary.json,run_info.json,log.txt}
and <run>.driver.log (run from /work/main, commands in long-relaxation.md), writes long-relaxation.json and
long-relaxation.png next to this script and prints the tables.

    /usr/bin/python3 experiments/studies/branches/gauss-bonnet/long_relaxation.py [results directory]
"""
import json
import os
import re
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
if len(sys.argv) > 1 and sys.argv[1].startswith('-'):
    print(__doc__)
    sys.exit(0)
ROOT = sys.argv[1] if len(sys.argv) > 1 else 'results/studies/branches-gb/level2/long'
if not os.path.isdir(ROOT):
    sys.exit(f'{ROOT}: no such directory (the runs of long-relaxation.md); nothing written')
LEVEL2 = os.path.dirname(ROOT.rstrip('/'))

# Each run: the checkpoint it started from (relative to level2/) and its segments (output directories under
# ROOT, in order; a later segment resumed from the previous segment's checkpoint, its statistics.txt holds the
# whole history).
RUNS = [
    dict(name='prot-655', sigma=655, branch='protruding', start='fine/down-tight-655/655/checkpoint.txt',
         segments=['prot-655-a']),
    dict(name='flat-655', sigma=655, branch='flat', start='fine/up-tight-655/655/checkpoint.txt',
         segments=['flat-655']),
    dict(name='prot-675', sigma=675, branch='protruding', start='down/675/checkpoint.txt', segments=['prot-675']),
    dict(name='flat-675', sigma=675, branch='flat', start='up/675/checkpoint.txt', segments=['flat-675']),
    dict(name='prot-700', sigma=700, branch='protruding', start='down/700/checkpoint.txt', segments=['prot-700']),
    dict(name='flat-700', sigma=700, branch='flat', start='up/700/checkpoint.txt', segments=['flat-700']),
]
# Continuations with a changed setting (not the template): diagnostics, not in the pairs. 'start_time' = the
# time the continuation resumed at.
DIAGNOSTIC_RUNS = [
    dict(name='prot-655 continued, Energy tolerance 1e-6', continues='prot-655', sigma=655, branch='protruding',
         start='long/prot-655-a/655/checkpoint.txt', segments=['prot-655'], diagnostic=True),
    dict(name='prot-655 continued, Energy tolerance 1e-6, no grid control', continues='prot-655', sigma=655,
         branch='protruding', start='long/prot-655-a/655/checkpoint.txt', segments=['prot-655-nogc'], diagnostic=True),
    dict(name='prot-675 continued, Energy tolerance 1e-6, no grid control', continues='prot-675', sigma=675,
         branch='protruding', start='long/prot-675/675/checkpoint.txt', segments=['prot-675-nogc'], diagnostic=True),
    dict(name='prot-700 continued, Energy tolerance 1e-6, no grid control', continues='prot-700', sigma=700,
         branch='protruding', start='long/prot-700/700/checkpoint.txt', segments=['prot-700-nogc'], diagnostic=True),
    dict(name='flat-675 continued (template settings, plateau 1e-8)', continues='flat-675', sigma=675, branch='flat',
         start='long/flat-675/675/checkpoint.txt', segments=['flat-675-more'], diagnostic=True),
    dict(name='flat-700 continued (template settings, plateau 1e-8)', continues='flat-700', sigma=700, branch='flat',
         start='long/flat-700/700/checkpoint.txt', segments=['flat-700-more'], diagnostic=True),
]
DT = 0.01                                  # resampling step of the time series (the steps' tau is at most 0.01)
MUS = np.logspace(-3, 2, 1001)             # the grid of decay rates scanned in the tail fits
STALL_TAU = 1e-3                           # a step below this tau counts as part of a tau collapse


def read_table(path):
    with open(path) as f:
        names = f.readline().lstrip('#').split()
    data = np.loadtxt(path, ndmin=2)
    return {n: data[:, i] for i, n in enumerate(names)}


def read_json(path):
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


def driver_info(path):
    """Elapsed wall time and exit status from /usr/bin/time -v, and the driver's error line."""
    info = {'wall': None, 'wall_seconds': None, 'exit_status': None, 'driver_error': None}
    if not os.path.exists(path):
        return info
    with open(path) as f:
        text = f.read()
    m = re.search(r'Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (\S+)', text)
    if m:
        info['wall'] = m.group(1)
        parts = [float(p) for p in m.group(1).split(':')]
        info['wall_seconds'] = sum(p * 60 ** i for i, p in enumerate(reversed(parts)))
    m = re.search(r'Exit status: (\d+)', text)
    if m:
        info['exit_status'] = int(m.group(1))
    m = re.search(r'^membrane_flow continuation: error: (.*)$', text, re.M)
    if m:
        info['driver_error'] = m.group(1)
    m = re.search(r'Percent of CPU this job got: (\S+)', text)
    if m:
        info['cpu_percent'] = m.group(1)
    return info


def log_warnings(path):
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return [line.strip() for line in f if re.search(r'warn|error|fail', line, re.I)]


def source_time(run):
    """Time of the starting checkpoint = the last time of the source run's statistics.txt."""
    stats = read_table(os.path.join(LEVEL2, os.path.dirname(run['start']), 'statistics.txt'))
    return float(stats['time'][-1])


def resample(t, y, grid):
    t_u, idx = np.unique(t, return_index=True)
    return np.interp(grid, t_u, y[idx])


def slope(t, y):
    if len(t) < 2:
        return None
    return float(np.polyfit(t, y, 1)[0])


def exp_fit(t, y, rate_factor=1.0, mus=MUS, fixed_mu=None):
    """y = y_inf + c exp(-rate_factor mu (t - t[0])): scan mu, linear least squares for y_inf and c."""
    best = None
    for mu in ([fixed_mu] if fixed_mu is not None else mus):
        basis = np.column_stack([np.ones_like(t), np.exp(-rate_factor * mu * (t - t[0]))])
        coef, *_ = np.linalg.lstsq(basis, y, rcond=None)
        rms = float(np.sqrt(np.mean((basis @ coef - y) ** 2)))
        if best is None or rms < best['rms']:
            best = {'mu': float(mu), 'inf': float(coef[0]), 'amplitude': float(coef[1]), 'rms': rms}
    if fixed_mu is None:
        best['mu_at_grid_edge'] = 'low' if best['mu'] <= mus[0] * 1.0001 else (
            'high' if best['mu'] >= mus[-1] * 0.9999 else None)
    best['t_ref'] = float(t[0])
    return best


def noise(y):
    """Point noise of a sampled series from its second differences (a smooth trend hardly contributes)."""
    return float(np.std(np.diff(y, 2)) / np.sqrt(6)) if len(y) > 3 else 0.0


def joint_fit(t, P, E, mus=MUS):
    """P = P_inf + C exp(-mu s), E = E_inf + D exp(-2 mu s) with one mu: scan mu, linear least squares for the
    rest, objective the sum of the squared residuals of each series over its own point noise squared."""
    sP, sE = max(noise(P), 1e-12), max(noise(E), 1e-12)
    best = None
    for mu in mus:
        out = {}
        obj = 0.0
        for key, y, rate, sig in (('P', P, mu, sP), ('E', E, 2 * mu, sE)):
            basis = np.column_stack([np.ones_like(t), np.exp(-rate * (t - t[0]))])
            coef, *_ = np.linalg.lstsq(basis, y, rcond=None)
            r = basis @ coef - y
            out[key] = (float(coef[0]), float(coef[1]), float(np.sqrt(np.mean(r ** 2))))
            obj += float(np.mean(r ** 2)) / sig ** 2
        if best is None or obj < best['objective']:
            best = {'mu': float(mu), 'P_inf': out['P'][0], 'P_amplitude': out['P'][1], 'P_rms': out['P'][2],
                    'E_inf': out['E'][0], 'E_amplitude': out['E'][1], 'E_rms': out['E'][2], 'objective': obj}
    best['noise_P'], best['noise_E'] = sP, sE
    best['mu_at_grid_edge'] = 'low' if best['mu'] <= mus[0] * 1.0001 else (
        'high' if best['mu'] >= mus[-1] * 0.9999 else None)
    best['t_ref'] = float(t[0])
    return best


def linear_rms(t, y):
    p = np.polyfit(t, y, 1)
    return float(np.sqrt(np.mean((np.polyval(p, t) - y) ** 2)))


def tau_collapses(t, tau):
    """Stretches of more than 50 consecutive steps with tau < STALL_TAU."""
    small = tau < STALL_TAU
    out, i = [], 0
    while i < len(small):
        if small[i]:
            j = i
            while j < len(small) and small[j]:
                j += 1
            if j - i > 50:
                out.append({'from_time': float(t[i]), 'to_time': float(t[j - 1]), 'steps': int(j - i),
                            'min_tau': float(tau[i:j].min())})
            i = j
        else:
            i += 1
    return out


def analyse(run):
    segs = []
    for s in run['segments']:
        d = os.path.join(ROOT, s, str(run['sigma']))
        seg = {'output': os.path.join(ROOT, s), 'summary': read_json(os.path.join(d, 'summary.json')),
               'run_info': read_json(os.path.join(d, 'run_info.json')),
               'warnings_in_log': log_warnings(os.path.join(d, 'log.txt'))}
        seg.update(driver_info(os.path.join(ROOT, s + '.driver.log')))
        segs.append(seg)
    stats = read_table(os.path.join(ROOT, run['segments'][-1], str(run['sigma']), 'statistics.txt'))
    t0 = source_time(run)
    keep = stats['time'] >= t0 - 1e-9
    c = {k: v[keep] for k, v in stats.items()}
    t = c['time']
    t_end = float(t[-1])
    collapses = tau_collapses(t, c['tau'])
    # The analysis window: up to the first tau collapse (after it the run hardly moves, and a state that
    # the scheme can no longer lower in energy is not evidence of an equilibrium either way).
    t_win = collapses[0]['from_time'] if collapses else t_end
    grid = np.arange(t0, t_win + 1e-12, DT)
    if grid[-1] < t_win - 1e-9:
        grid = np.append(grid, t_win)
    E = resample(t, c['energy'], grid)
    P = resample(t, c['domain_protrusion'], grid)
    i_win = int(np.searchsorted(t, t_win + 1e-12)) - 1

    res = {'name': run['name'], 'sigma': run['sigma'], 'branch': run['branch'],
           'diagnostic': bool(run.get('diagnostic')), 'continues': run.get('continues'),
           'start_checkpoint': os.path.join(LEVEL2, run['start']), 't_start': t0, 't_end': t_end,
           'relaxed': t_end - t0, 't_window_end': float(t_win), 'relaxed_in_window': float(t_win - t0),
           'steps': int(c['step'][-1] - c['step'][0]), 'tau_collapses': collapses}
    qs = ('energy', 'domain_protrusion', 'bending_energy', 'gradient_energy', 'well_energy', 'neck_ratio',
          'area_error', 'mass_drift', 'adaptation_energy_jump', 'cells')
    for key, i in (('start', 0), ('window_end', i_win), ('end', -1)):
        res[key] = {q: float(c[q][i]) for q in qs}
        res[key]['time'] = float(t[i])
    last = grid >= t_win - 1.0 - 1e-9
    res['rate_last_1'] = {'dE_dt': slope(grid[last], E[last]), 'dP_dt': slope(grid[last], P[last]),
                          'over': [float(grid[last][0]), float(grid[last][-1])]}

    # Tail = last half of the window.
    tail = grid >= t0 + 0.5 * (t_win - t0) - 1e-9
    tt, Pt, Et = grid[tail], P[tail], E[tail]
    fitP = exp_fit(tt, Pt)
    fitE_coupled = exp_fit(tt, Et, rate_factor=2.0, fixed_mu=fitP['mu'])
    fitE_free = exp_fit(tt, Et, rate_factor=2.0)
    half = len(tt) // 2
    sP1, sP2 = slope(tt[:half], Pt[:half]), slope(tt[half:], Pt[half:])
    sE1, sE2 = slope(tt[:half], Et[:half]), slope(tt[half:], Et[half:])
    res['tail'] = {
        'from': float(tt[0]), 'to': float(tt[-1]),
        'joint_fit': joint_fit(tt, Pt, Et),
        'P_fit': fitP, 'E_fit_with_2mu_of_P': fitE_coupled, 'E_fit_free (mu = half its rate)': fitE_free,
        'P_linear_rms': linear_rms(tt, Pt), 'E_linear_rms': linear_rms(tt, Et),
        'dP_dt_first_half': sP1, 'dP_dt_second_half': sP2,
        'P_deceleration (second/first)': sP2 / sP1 if sP1 else None,
        'dE_dt_first_half': sE1, 'dE_dt_second_half': sE2,
        'E_deceleration (second/first)': sE2 / sE1 if sE1 else None,
    }
    # Energy minimum along the whole run.
    i_min = int(np.argmin(c['energy']))
    res['energy_minimum'] = {'time': float(t[i_min]), 'energy': float(c['energy'][i_min]),
                             'domain_protrusion': float(c['domain_protrusion'][i_min])}
    # Possible creep: the constraint and remap diagnostics (over the window).
    diag = {}
    for q in ('area_error', 'mass_drift', 'remap_mass_correction', 'area_drift', 'shape_mass_correction'):
        if q in c:
            y = resample(t, c[q], grid)
            diag[q] = {'start': float(y[0]), 'middle': float(y[len(y) // 2]), 'end': float(y[-1]),
                       'max_abs': float(np.abs(c[q][:i_win + 1]).max()), 'tail_slope': slope(tt, y[tail])}
    step_rows = np.diff(c['step']) > 0
    gcs = np.diff(c['grid_control_skipped'])[step_rows]
    tw = t[1:][step_rows]
    in_win = tw <= t_win + 1e-12
    in_tail = in_win & (tw >= tt[0])
    diag['grid_control_skipped_fraction'] = float(np.mean(gcs[in_win] > 0)) if in_win.any() else None
    diag['grid_control_skipped_fraction_tail'] = float(np.mean(gcs[in_tail] > 0)) if in_tail.any() else None
    diag['grid_control_skipped_fraction_after_window'] = (
        float(np.mean(gcs[~in_win] > 0)) if (~in_win).any() else None)
    skipped_at = tw[gcs > 0]
    diag['grid_control_first_refused_at'] = float(skipped_at[0]) if len(skipped_at) else None
    diag['rejected_steps'] = int(c['rejected_steps'][-1] - c['rejected_steps'][0])
    diag['adaptation_energy_jump_change'] = float(c['adaptation_energy_jump'][i_win] - c['adaptation_energy_jump'][0])
    diag['cells_start_end'] = [int(c['cells'][0]), int(c['cells'][-1])]
    res['diagnostics'] = diag
    res['segments'] = segs
    # The whole run (including any collapse), every 0.05 time units, for the plot and the record.
    full = np.arange(t0, t_end + 1e-12, 0.05)
    res['series'] = {'t_minus_t_start': [round(x - t0, 4) for x in full],
                     'energy': [float(x) for x in resample(t, c['energy'], full)],
                     'domain_protrusion': [float(x) for x in resample(t, c['domain_protrusion'], full)]}
    return res, (grid, E, P)


def main():
    results, series = [], {}
    for run in RUNS + DIAGNOSTIC_RUNS:
        if not os.path.exists(os.path.join(ROOT, run['segments'][-1], str(run['sigma']), 'statistics.txt')):
            print('missing:', run['name'])
            continue
        r, s = analyse(run)
        results.append(r)
        series[run['name']] = s
    main_runs = [r for r in results if not r['diagnostic']]

    pairs = []
    for sigma in sorted({r['sigma'] for r in main_runs}):
        pr = [r for r in main_runs if r['sigma'] == sigma and r['branch'] == 'protruding']
        fl = [r for r in main_runs if r['sigma'] == sigma and r['branch'] == 'flat']
        if not pr or not fl:
            continue
        p, f = pr[0], fl[0]
        gp, Ep, Pp = series[p['name']]
        gf, Ef, Pf = series[f['name']]
        common = min(gp[-1] - gp[0], gf[-1] - gf[0])
        gap_by_relaxation = []
        for x in list(np.arange(0, common + 1e-9, 1.0)) + [common]:
            i = min(int(round(x / DT)), len(Pp) - 1, len(Pf) - 1)
            gap_by_relaxation.append({'relaxed': round(float(x), 3), 'dP': float(Pp[i] - Pf[i]),
                                      'dE': float(Ep[i] - Ef[i])})
        pe, fe = p['window_end'], f['window_end']
        pairs.append({
            'sigma': sigma, 'protruding': p['name'], 'flat': f['name'],
            'dP_start': p['start']['domain_protrusion'] - f['start']['domain_protrusion'],
            'dE_start': p['start']['energy'] - f['start']['energy'],
            'dP_window_end': pe['domain_protrusion'] - fe['domain_protrusion'],
            'dE_window_end': pe['energy'] - fe['energy'],
            'dP_end': p['end']['domain_protrusion'] - f['end']['domain_protrusion'],
            'dE_end': p['end']['energy'] - f['end']['energy'],
            'dP_inf (joint fits)': p['tail']['joint_fit']['P_inf'] - f['tail']['joint_fit']['P_inf'],
            'dE_inf (joint fits)': p['tail']['joint_fit']['E_inf'] - f['tail']['joint_fit']['E_inf'],
            'dP_inf (P-only fits)': p['tail']['P_fit']['inf'] - f['tail']['P_fit']['inf'],
            'dE_inf (free fits)': (p['tail']['E_fit_free (mu = half its rate)']['inf'] -
                                   f['tail']['E_fit_free (mu = half its rate)']['inf']),
            'gap_at_equal_relaxation': gap_by_relaxation,
        })

    out = {'script': 'experiments/studies/branches/gauss-bonnet/long_relaxation.py', 'results': ROOT,
           'resample_dt': DT, 'mu_grid': [float(MUS[0]), float(MUS[-1]), len(MUS)],
           'stall_tau': STALL_TAU, 'runs': results, 'pairs': pairs}
    with open(os.path.join(HERE, 'long-relaxation.json'), 'w') as fh:
        json.dump(out, fh, indent=1)

    print('window = start .. first tau collapse (or the end); "end" values at the window end')
    print('%-10s %6s %7s %7s %10s %10s %7s %7s %10s %10s %8s %8s %9s %8s %8s' % (
        'run', 't0', 't_win', 't_end', 'E start', 'E win', 'P start', 'P win', 'dE/dt(1)', 'dP/dt(1)',
        'mu', 'P_inf', 'E_inf', 'rmsP', 'rmsE'))
    for r in results:
        j = r['tail']['joint_fit']
        print('%-10s %6.2f %7.2f %7.2f %10.5f %10.5f %7.4f %7.4f %10.2e %10.2e %8.3g %8.4f %9.5f %8.1e %8.1e%s' % (
            r['name'][:10], r['t_start'], r['t_window_end'], r['t_end'], r['start']['energy'],
            r['window_end']['energy'], r['start']['domain_protrusion'], r['window_end']['domain_protrusion'],
            r['rate_last_1']['dE_dt'], r['rate_last_1']['dP_dt'], j['mu'], j['P_inf'], j['E_inf'], j['P_rms'],
            j['E_rms'], ' (mu at grid edge: %s)' % j['mu_at_grid_edge'] if j['mu_at_grid_edge'] else ''))
    print()
    for r in results:
        tl = r['tail']
        ff = tl['E_fit_free (mu = half its rate)']
        print('%s: P-only fit mu %.3g P_inf %.4f rms %.1e%s; noise P %.1e E %.1e' % (
            r['name'], tl['P_fit']['mu'], tl['P_fit']['inf'], tl['P_fit']['rms'],
            ' (grid edge %s)' % tl['P_fit']['mu_at_grid_edge'] if tl['P_fit']['mu_at_grid_edge'] else '',
            tl['joint_fit']['noise_P'], tl['joint_fit']['noise_E']))
        print('%s: tail %.2f-%.2f: dP/dt %.2e -> %.2e (ratio %.2f), dE/dt %.2e -> %.2e (ratio %.2f); linear rms P '
              '%.1e E %.1e; E free fit mu %.3g E_inf %.5f rms %.1e; E min %.6f at t %.3f (P %.4f); collapses %s; '
              'end (t %.2f): E %.5f P %.4f; grid control skipped %.2f (tail %.2f, after window %s, first at %s); rejected %d' % (
                  r['name'], tl['from'], tl['to'], tl['dP_dt_first_half'], tl['dP_dt_second_half'],
                  tl['P_deceleration (second/first)'] or float('nan'), tl['dE_dt_first_half'],
                  tl['dE_dt_second_half'], tl['E_deceleration (second/first)'] or float('nan'),
                  tl['P_linear_rms'], tl['E_linear_rms'], ff['mu'], ff['inf'], ff['rms'],
                  r['energy_minimum']['energy'], r['energy_minimum']['time'], r['energy_minimum']['domain_protrusion'],
                  [(round(x['from_time'], 3), round(x['to_time'], 3), x['steps'], '%.1e' % x['min_tau'])
                   for x in r['tau_collapses']],
                  r['end']['time'], r['end']['energy'], r['end']['domain_protrusion'],
                  r['diagnostics']['grid_control_skipped_fraction'],
                  r['diagnostics']['grid_control_skipped_fraction_tail'] or 0,
                  r['diagnostics']['grid_control_skipped_fraction_after_window'],
                  r['diagnostics']['grid_control_first_refused_at'], r['diagnostics']['rejected_steps']))
        for q in ('area_error', 'mass_drift', 'remap_mass_correction'):
            d = r['diagnostics'].get(q)
            if d:
                print('    %-22s start %.2e mid %.2e end %.2e max|.| %.2e tail slope %.2e' % (
                    q, d['start'], d['middle'], d['end'], d['max_abs'], d['tail_slope']))
        print('    energy parts start -> window end: bending %.4f -> %.4f, gradient %.4f -> %.4f, well %.4f -> %.4f; '
              'adaptation jump change %.2e; cells %s' % (
                  r['start']['bending_energy'], r['window_end']['bending_energy'], r['start']['gradient_energy'],
                  r['window_end']['gradient_energy'], r['start']['well_energy'], r['window_end']['well_energy'],
                  r['diagnostics']['adaptation_energy_jump_change'], r['diagnostics']['cells_start_end']))
        for s in r['segments']:
            sm = s['summary'] or {}
            print('    segment %s: wall %s (cpu %s), exit %s, stop: %s; rejections %s; grid refused %.3f; '
                  'log warnings %d' % (
                      s['output'], s['wall'], s.get('cpu_percent'), s['exit_status'], sm.get('stop_reason'),
                      {k: v for k, v in (sm.get('rejections') or {}).items() if v}, sm.get(
                          'grid_control_refused_fraction', float('nan')), len(s['warnings_in_log'])))
    print()
    for p in pairs:
        print('sigma %d: dP start %+.4f window end %+.4f inf %+.4f | dE start %+.5f window end %+.5f inf %+.5f '
              '(E-only fits %+.5f)' % (p['sigma'], p['dP_start'], p['dP_window_end'], p['dP_inf (joint fits)'],
                                       p['dE_start'], p['dE_window_end'], p['dE_inf (joint fits)'],
                                       p['dE_inf (free fits)']))
        print('   at equal relaxation:', ', '.join('%g: dP %+.4f dE %+.5f' % (g['relaxed'], g['dP'], g['dE'])
                                                 for g in p['gap_at_equal_relaxation']))

    try:
        import matplotlib
        matplotlib.use('Agg')
        import matplotlib.pyplot as plt
    except ImportError:
        return
    sigmas = sorted({r['sigma'] for r in results})
    fig, axes = plt.subplots(2, len(sigmas), figsize=(4.8 * len(sigmas), 7.5), squeeze=False)
    for k, sigma in enumerate(sigmas):
        for r in results:
            if r['sigma'] != sigma:
                continue
            col = 'tab:red' if r['branch'] == 'protruding' else 'tab:blue'
            ls = ':' if r['diagnostic'] else '-'
            if 'no grid control' in r['name']:
                col, ls = 'darkorange', (0, (1, 1))
            s = r['series']
            t_rel = np.array(s['t_minus_t_start'])
            if r['diagnostic']:  # plotted on the time axis of the run it continues
                t_rel = t_rel + r['t_start'] - [q for q in results if q['name'] == r['continues']][0]['t_start']
            label = r['name'] if r['diagnostic'] else '%s (t0 = %.2f)' % (r['name'], r['t_start'])
            axes[0, k].plot(t_rel, s['domain_protrusion'], color=col, ls=ls, label=label)
            axes[1, k].plot(t_rel, s['energy'], color=col, ls=ls, label=label)
            if r['diagnostic']:
                continue
            j = r['tail']['joint_fit']
            tt = np.linspace(j['t_ref'], r['t_window_end'], 100)
            axes[0, k].plot(tt - r['t_start'], j['P_inf'] + j['P_amplitude'] * np.exp(-j['mu'] * (tt - j['t_ref'])),
                            'k--', lw=0.8)
            axes[1, k].plot(tt - r['t_start'],
                            j['E_inf'] + j['E_amplitude'] * np.exp(-2 * j['mu'] * (tt - j['t_ref'])), 'k--', lw=0.8)
            if r['branch'] == 'flat':  # the protruding P(t) is nearly linear: its P_inf is not determined
                axes[0, k].axhline(j['P_inf'], color=col, lw=0.5, ls='--')
            axes[1, k].axhline(j['E_inf'], color=col, lw=0.5, ls='--')
            for st in r['tau_collapses']:
                for ax in axes[:, k]:
                    ax.axvline(st['from_time'] - r['t_start'], color=col, ls='-.', lw=0.8)
        axes[0, k].axhline(0.95, color='gray', lw=0.5)
        axes[0, k].set_title('sigma = %d' % sigma)
        axes[0, k].set_ylabel('domain_protrusion')
        axes[1, k].set_ylabel('energy')
        axes[1, k].set_xlabel('time relaxed in this study (t - t0)')
        axes[0, k].legend(fontsize=7)
        axes[1, k].legend(fontsize=7)
    fig.suptitle('7.3, level 2: long relaxation of the protruding (red) and flat (blue) states; black dashed: joint tail '
                 'fits; thin dashed: their E_inf and (flat states only) P_inf;\ndash-dot: tau collapse (the run was stopped there); dotted: '
                 'continuations from the collapse with Energy tolerance 1e-6 (red: with grid control, orange: without)',
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(HERE, 'long-relaxation.png'), dpi=110)


if __name__ == '__main__':
    main()
