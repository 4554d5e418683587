"""Figure of the xi series (issue 33 item 4): branch energies and branch ends against lambda = sigma xi.

Reads tables.json (written by tables.py), results.json (this study) and the sharp-interface results;
writes xi-series.png next to itself. Run from anywhere:  /usr/bin/python3 figure.py
"""
import json
import os

import matplotlib

matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SHARP = os.path.join(HERE, '..', '..', 'sharp_interface', 'results.json')


def reference(lam):
    """Common reference line subtracted from every energy (only to flatten the plot)."""
    return 40.0 + 1.0 * (lam - 19.5)


def main():
    tables = json.load(open(os.path.join(HERE, 'tables.json')))
    results = json.load(open(os.path.join(HERE, 'results.json')))
    sharp = json.load(open(SHARP))
    colours = {0.03: 'tab:blue', 0.02: 'tab:orange', 0.015: 'tab:green'}
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.8))

    lam = [p['line_tension_lambda'] for p in sharp['by_sigma'] if 15 <= p['line_tension_lambda'] <= 23]
    e = [p['bump']['energy'] for p in sharp['by_sigma'] if 15 <= p['line_tension_lambda'] <= 23]
    ax.plot(lam, [y - reference(x) for x, y in zip(lam, e)], 'k-', lw=1, label='sharp interface (axisymmetric)')
    for entry in tables:
        c = colours[entry['xi']]
        for name, marker, fill in (('down', 'o', c), ('up', 's', 'none')):
            rows = {r['sigma']: r for r in entry[name]['rows']}
            for sup in entry['supplementary']:
                if sup['side'] == name:
                    for r in sup['rows']:
                        rows.setdefault(r['sigma'], r)
            rows = [rows[k] for k in sorted(rows)]
            if not rows:
                continue
            own = 'protruding' if name == 'down' else 'not protruding'
            on = [r for r in rows if r['class'] == own]
            off = [r for r in rows if r['class'] != own]
            label = f"xi {entry['xi']}: " + ('protruding (down)' if name == 'down' else 'flat start (up)')
            ax.plot([r['lambda'] for r in on], [r['energy'] - reference(r['lambda']) for r in on], marker=marker,
                    color=c, mfc=fill, ls='-' if name == 'down' else '--', label=label)
            ax.plot([r['lambda'] for r in off], [r['energy'] - reference(r['lambda']) for r in off], marker='x',
                    color=c, ls='none')
    ax.set_xlim(17.5, 23)
    ax.set_ylim(-1.2, 0.4)
    ax.set_xlabel('line tension lambda = sigma xi')
    ax.set_ylabel('E - (40 + (lambda - 19.5))')
    ax.set_title('branch energies, main and half-step follows (x: state off its class)')
    ax.legend(fontsize=7)

    for s in results['series']:
        xi = s['xi']
        for key, dx, c, label in (('protruding_ends', -0.0005, 'tab:red', 'protruding branch ends'),
                                  ('flat_ends', 0.0005, 'tab:blue', 'flat-start branch ends')):
            main, refined = s[key + '_lambda'], s[key + '_refined_lambda']
            bx.plot([xi + dx] * 2, main, color=c, lw=2, alpha=0.5, label=label + ' (main follows)' if xi == 0.03 else None)
            bx.plot([xi + dx] * 2, refined, color=c, lw=6, alpha=0.8, label=label + ' (with half steps)' if xi == 0.03 else None)
        if s.get('threshold_if_states_merge_lambda'):
            bx.plot([xi + 0.0012] * 2, [18.6, s['threshold_if_states_merge_lambda'][1]], color='k', lw=1.5, ls='--',
                    label='0.015: crossing not resolved (< 19.125 or in [19.125, 19.5])')
        if s.get('crossing_bracket_lambda'):
            bx.plot([xi + 0.0012] * 2, s['crossing_bracket_lambda'], color='k', lw=2, label='energy crossing (long relaxations)')
    ex = results['extrapolation']
    for key, c in (('protruding_ends_lambda', 'tab:red'), ('flat_ends_lambda', 'tab:blue')):
        r = ex[key]['linear_in_xi_intercept_range']
        if r:
            bx.plot([0, 0], r, color=c, lw=2, ls=':', label='xi -> 0, straight line through the main brackets' if c == 'tab:red' else None)
    si = results['sharp_interface']
    bx.axhline(si['waist_lambda'], color='grey', ls='--', lw=1, label=f"sharp: waist ({si['waist_lambda']:.2f})")
    bx.axhline(si['vertical_boundary_lambda'], color='grey', ls=':', lw=1,
               label=f"sharp: vertical boundary ({si['vertical_boundary_lambda']:.2f})")
    bx.axhline(18.9, color='tab:purple', ls='-.', lw=1, label='paper: complete bud at 630 (18.9)')
    bx.axhline(16.2, color='tab:purple', ls=(0, (1, 3)), lw=1, label='paper: no bud at 540 (16.2)')
    bx.set_xlim(-0.001, 0.034)
    bx.set_ylim(15.5, 23)
    bx.set_xlabel('transition length xi (mesh scaled with xi)')
    bx.set_ylabel('lambda')
    bx.set_title('branch ends and crossing against xi')
    bx.legend(fontsize=7, loc='lower right')
    fig.tight_layout()
    fig.savefig(os.path.join(HERE, 'xi-series.png'), dpi=120)


if __name__ == '__main__':
    main()
