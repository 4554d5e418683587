"""The xi = 0.015 pairs at sigma 1275 and 1300 (lambda 19.125, 19.5) relaxed further (plateau 1e-5).

Reads results/studies/branches-xi/xi0.015/long/{prot,flat}-<sigma>/<sigma>/statistics.txt (rows from the
checkpoint time on); prints start, end, rates over the last two time units and the gaps at equal relaxation
times; writes long-relaxation.json next to itself.  Run from anywhere:  /usr/bin/python3 long_relaxation.py
"""
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, '..', '..', '..', '..')
SIGMAS = (1275, 1300)


def read(path):
    lines = open(path).read().splitlines()
    header = lines[0].lstrip('#').split()
    return [dict(zip(header, map(float, l.split()))) for l in lines[1:] if l.strip()]


def slope(rows, key, t0, t1):
    pts = [(r['time'], r[key]) for r in rows if t0 <= r['time'] <= t1]
    n = len(pts)
    if n < 2:
        return None
    mt = sum(t for t, _ in pts) / n
    my = sum(y for _, y in pts) / n
    return sum((t - mt) * (y - my) for t, y in pts) / sum((t - mt) ** 2 for t, _ in pts)


def pair(sigma):
    out = {}
    runs = {k: f'results/studies/branches-xi/xi0.015/long/{k}-{sigma}/{sigma}' for k in ('prot', 'flat')}
    for name, run in runs.items():
        d = os.path.join(ROOT, run)
        info = json.load(open(os.path.join(d, 'run_info.json')))
        start = json.load(open(os.path.join(os.path.dirname(info['resumed_from']), 'summary.json')))['time']
        rows = [r for r in read(os.path.join(d, 'statistics.txt')) if r['time'] >= start - 1e-9]
        summary_path = os.path.join(d, 'summary.json')
        summary = json.load(open(summary_path)) if os.path.exists(summary_path) else {}
        a, b = rows[0], rows[-1]
        t1 = b['time']
        out[name] = {'run': run, 'from': info['resumed_from'], 't_start': a['time'], 't_end': t1,
                     'relaxed': t1 - a['time'], 'E_start': a['energy'], 'E_end': b['energy'],
                     'P_start': a['domain_protrusion'], 'P_end': b['domain_protrusion'],
                     'neck_end': b['neck_ratio'], 'cells': b['cells'],
                     'dE_dt_last_unit': slope(rows, 'energy', t1 - 1, t1),
                     'dP_dt_last_unit': slope(rows, 'domain_protrusion', t1 - 1, t1),
                     'dE_dt_previous_unit': slope(rows, 'energy', t1 - 2, t1 - 1),
                     'dP_dt_previous_unit': slope(rows, 'domain_protrusion', t1 - 2, t1 - 1),
                     'stop_reason': summary.get('stop_reason'), 'failed': summary.get('failed'),
                     'rejected_steps': summary.get('rejected_steps'), 'rejections': summary.get('rejections'),
                     'code_version': summary.get('code_version')}
        # the energy and protrusion at equal relaxation times, for the gap
        out[name]['samples'] = [{'relaxed': r['time'] - a['time'], 'E': r['energy'], 'P': r['domain_protrusion']}
                                for r in rows if abs(((r['time'] - a['time']) * 2) - round((r['time'] - a['time']) * 2)) < 0.006]
    p, f = out['prot'], out['flat']
    out['gap'] = {'dE_start': p['E_start'] - f['E_start'], 'dE_end': p['E_end'] - f['E_end'],
                  'dP_start': p['P_start'] - f['P_start'], 'dP_end': p['P_end'] - f['P_end']}
    print(f'sigma {sigma} (lambda {sigma * 0.015:g}):')
    for name in ('prot', 'flat'):
        r = out[name]
        print(f"{name}: relaxed {r['relaxed']:.2f} ({r['t_start']:.2f} -> {r['t_end']:.2f}), E {r['E_start']:.5f} -> "
              f"{r['E_end']:.5f}, P {r['P_start']:.4f} -> {r['P_end']:.4f}, neck {r['neck_end']:.3f}, "
              f"dE/dt {r['dE_dt_last_unit']:.2e} (before {r['dE_dt_previous_unit']}), dP/dt {r['dP_dt_last_unit']:.2e} "
              f"(before {r['dP_dt_previous_unit']}), stop: {r['stop_reason']}, rejected {r['rejected_steps']}")
    print('gap (prot - flat):', {k: round(v, 5) for k, v in out['gap'].items()})
    for sp, sf in zip(out['prot']['samples'], out['flat']['samples']):
        print(f"  after {sp['relaxed']:.1f} / {sf['relaxed']:.1f}: dE {sp['E'] - sf['E']:+.5f}, P {sp['P']:.4f} / {sf['P']:.4f}")
    return out


def main():
    out = {}
    for sigma in SIGMAS:
        if os.path.exists(os.path.join(ROOT, f'results/studies/branches-xi/xi0.015/long/flat-{sigma}/{sigma}/statistics.txt')):
            out[str(sigma)] = pair(sigma)
    with open(os.path.join(HERE, 'long-relaxation.json'), 'w') as fh:
        json.dump(out, fh, indent=1)
        fh.write('\n')


if __name__ == '__main__':
    main()
