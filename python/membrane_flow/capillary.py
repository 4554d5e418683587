"""Capillary waves of a straight phase boundary on the flat patch against k_BT / (L lambda q^2)
(docs/fluctuations.md, "Capillary waves of a phase boundary").

A stripe of one phase lies between x = 1/4 + u_L(y) and x = 3/4 + u_R(y) on the unit patch, phi
jumping by 2 across each boundary. To first order in u, the amplitudes f_k of phi
(docs/fluctuations.md, "Observables") at k = (0, n) and (1, n) are

    phi_(0,n) = -2 (u_L - u_R)_n,    phi_(1,n) = 2 i (u_L + u_R)_n,    u_n = integral u(y) exp(-2 pi i n y) dy,

and for two independent boundaries of line tension lambda on a patch of side L = 1 (capillary-wave
theory, <|u_n|^2> = k_BT / (L lambda q^2), q = 2 pi n) both have the mean square

    <|phi_(0,n)|^2> = <|phi_(1,n)|^2> = 8 k_BT / (lambda q^2).

A translation of the stripe only multiplies phi_k by a phase (its width is fixed by its mass), so
the drift of the stripe does not enter. phi's fluctuations in the two bulk phases add to these
amplitudes: a run with the same parameters in one phase (phi = -1 everywhere, no boundary)
measures them, B_n. They do not add in full: in the Gaussian theory of the boundary (the
fluctuation operator of the kink phi_0 = tanh(x / w), w = 4 xi / 3, whose zero mode phi_0' is the
translation), the translation mode of each boundary takes the weight 3 w of the projection of
phi onto exp(-2 pi i n y) from the bulk's continuum, so the stripe's amplitudes are
S_n = 8 k_BT / (lambda q^2) + (1 - 6 w) B_n, and the line tension of mode n is

    lambda_n = 8 k_BT / (q^2 (S_n - (1 - 6 w) B_n)),

S_n and B_n the means over k = (0, +-n) and (1, +-n), compared with sigma xi, the line tension of
the free energy (MODEL.md section 2). Across the diffuse boundary phi_(1,n) carries the form factor
F = pi^2 w / sinh(pi^2 w) of the profile (0.956 at xi = 0.04; the weight taken from the bulk is
then 3 w F^2): |phi_(1,n)|^2 is divided by F^2 in the stripe and the bulk run alike.

The time step. A boundary mode relaxes, in the thin-interface limit of the Cahn-Hilliard flow with
the mobility L_phi on both sides, at the rate Gamma_n = L_phi lambda q^3 / 2, and a fixed tau lowers
its stationary variance (the table gives Gamma_n tau as a guide; the bias measured with the
linearized scheme exceeds the backward-Euler factor 1 / (1 + Gamma_n tau / 2), by up to 2x at
Gamma_n tau = 0.6, experiments/studies/capillary_waves).
The stabilized scheme (Cahn-Hilliard/Scheme, the default) lowers it far more, by a factor of about
1 / (1 + c tau L_phi sigma q^2) with c of a few: it damps each step by its s (phi - phi^m) without
noise to match. Use the linearized scheme and compare the modes whose Gamma_n tau is small.

The amplitudes are taken from the VTU snapshots by the vertex rule of the uniform periodic mesh
(each vertex once, weight 1 / number of vertices), as the structure factor of phi does; the patch
must stay flat (Shape/Evolve shape = false), so that a vertex's position is its parameter.

    python3 -m membrane_flow capillary results/capillary_waves/stripe1 results/capillary_waves/stripe2 \\
        --bulk results/capillary_waves/bulk
"""
import argparse
import json
import math
import os
import sys

import numpy as np

from .run import load_parameters, load_snapshots, read_vtu
from .spectra import batch_means


def vertex_values(points, phi):
    """The periodic vertices of a flat unit patch once each: x, y in [0, 1) and phi there (a VTU
    repeats a vertex in every cell it belongs to)."""
    u = np.mod(np.round(points[:, :2], 9), 1.0)
    key = np.round(u * 2**20).astype(np.int64)
    _, first = np.unique(key[:, 0] * 2**21 + key[:, 1], return_index=True)
    return u[first, 0], u[first, 1], phi[first]


def stripe_amplitudes(x, y, phi, modes):
    """phi_(k1, n) for k1 = 0, 1 (rows) and n = 1..modes, -1..-modes (columns), by the vertex rule."""
    ns = np.concatenate([np.arange(1, modes + 1), -np.arange(1, modes + 1)])
    return np.array([[np.mean(phi * np.exp(-2j * math.pi * (k1 * x + n * y))) for n in ns] for k1 in (0, 1)])


def form_factor(k1, width):
    """F of the boundary profile tanh(x / width) at the wavenumber 2 pi k1 across it: a shift u of the
    boundary changes phi_(k1, n) by -2 F u_n (F = 1 at k1 = 0)."""
    a = math.pi**2 * k1 * width
    return a / math.sinh(a) if a > 0 else 1.0


def mode_powers(run, modes, skip, width):
    """Times and, per snapshot after `skip`, the mean over the sign of n of |phi_(0, n)|^2 and of
    |phi_(1, n)|^2 / F(1)^2, and their mean (rows 0, 1, 2): an array (snapshots, 3, modes)."""
    times, rows = [], []
    scale = np.array([1.0, 1 / form_factor(1, width) ** 2])[:, None]
    for t, path in load_snapshots(run):
        if t < skip:
            continue
        data = read_vtu(path)
        amplitudes = stripe_amplitudes(*vertex_values(data['points'], data['point_data']['phi']), modes)
        power = scale * np.mean(np.abs(amplitudes.reshape(2, 2, modes)) ** 2, axis=1)
        rows.append(np.vstack([power, power.mean(axis=0)]))
        times.append(t)
    return np.array(times), np.array(rows)


def _pooled(runs, modes, skip, width, batches):
    """The mode_powers of several runs: the mean of their batch means, `batches` per run (so the runs
    weigh alike whatever their length), with its standard error."""
    means, total, spans = [], 0, []
    for run in runs:
        times, series = mode_powers(run, modes, skip, width)
        if len(times) < 2 * batches:
            raise ValueError(f'{run}: {len(times)} snapshots after t = {skip:g}, too few for {batches} batches')
        means += list(batch_means(series, batches))
        total += len(times)
        spans.append(float(times[-1] - times[0]))
    means = np.array(means)
    return means.mean(axis=0), means.std(axis=0, ddof=1) / math.sqrt(len(means)), total, spans


def capillary_spectrum(stripes, bulk, skip=0.01, modes=5, batches=20):
    """lambda_n of the stripe runs (pooled) against sigma xi, with the bulk run's amplitudes subtracted:
    from k = (0, n) and (1, n) together, and from each alone."""
    prm = load_parameters(stripes[0])
    names = ('Material/Temperature', 'Material/Line tension', 'Material/Transition length',
             'Material/Phase mobility', 'Time stepping/Time step', 'Cahn-Hilliard/Scheme', 'Mesh/Cells per side')
    for other in stripes[1:] + [bulk]:
        theirs = load_parameters(other)
        for name in names:
            if theirs[name] != prm[name]:
                raise ValueError(f'{other} differs from {stripes[0]} in {name} ({theirs[name]} against {prm[name]})')
    kT = float(prm['Material/Temperature'])
    xi = float(prm['Material/Transition length'])
    line_tension = float(prm['Material/Line tension']) * xi
    mobility, tau = float(prm['Material/Phase mobility']), float(prm['Time stepping/Time step'])
    width = 4 * xi / 3  # phi = tanh(3 x / (4 xi)), the boundary profile of f = 9/32 (phi^2 - 1)^2
    s, ds, n_s, span_s = _pooled(stripes, modes, skip, width, batches)
    b, db, n_b, span_b = _pooled([bulk], modes, skip, width, batches)
    result = {'k_BT': kT, 'sigma_xi': line_tension, 'phase_mobility': mobility, 'tau': tau, 'skip': skip,
              'scheme': prm['Cahn-Hilliard/Scheme'], 'form_factor': form_factor(1, width), 'width': width,
              'stripe_runs': len(stripes), 'stripe_snapshots': n_s, 'stripe_span': sum(span_s),
              'bulk_snapshots': n_b, 'bulk_span': span_b[0], 'modes': []}

    # The weight 3 w F^2 that each boundary's translation mode takes from the bulk's continuum,
    # in the scaled rows (|phi_(1,n)|^2 / F^2): 6 w F^2 of the bulk's scaled power.
    taken = 6 * width * np.array([1.0, form_factor(1, width) ** 2])

    def tension(row, i, q):
        if row == 2:  # k1 = 0 and 1 together: the mean of their excesses
            excess = sum(s[k, i] - (1 - taken[k]) * b[k, i] for k in (0, 1)) / 2
            bulk_error = (1 - taken.mean()) * db[2, i]
        else:
            excess = s[row, i] - (1 - taken[row]) * b[row, i]
            bulk_error = (1 - taken[row]) * db[row, i]
        lam = 8 * kT / (q * q * excess)
        return float(lam), float(lam * math.hypot(ds[row, i], bulk_error) / excess)

    for i in range(modes):
        n, q = i + 1, 2 * math.pi * (i + 1)
        lam, error = tension(2, i, q)
        result['modes'].append({
            'n': n, 'stripe': float(s[2, i]), 'stripe_error': float(ds[2, i]), 'bulk': float(b[2, i]),
            'bulk_error': float(db[2, i]), 'expected': 8 * kT / (line_tension * q * q), 'lambda_n': lam,
            'lambda_n_error': error, 'ratio': lam / line_tension, 'ratio_error': error / line_tension,
            'ratio_k1_0': tension(0, i, q)[0] / line_tension, 'ratio_k1_1': tension(1, i, q)[0] / line_tension,
            'rate_tau': mobility * line_tension * q**3 / 2 * tau})
    return result


def table(result):
    lines = [f"{result['stripe_snapshots']} snapshots of {result['stripe_runs']} stripe run(s) and "
             f"{result['bulk_snapshots']} of the bulk over times {result['stripe_span']:.3g} and "
             f"{result['bulk_span']:.3g}; k_BT = {result['k_BT']:g}, "
             f"sigma xi = {result['sigma_xi']:g}, tau = {result['tau']:g}",
             '| n | stripe <\\|phi_n\\|^2> | bulk | 8 k_BT / (sigma xi q^2) | lambda_n | lambda_n / (sigma xi) '
             '| from k1 = 0 alone | from k1 = 1 alone | Gamma_n tau |', '|---|---|---|---|---|---|---|---|---|']
    for m in result['modes']:
        lines.append(f"| {m['n']} | {m['stripe']:.4g} +- {m['stripe_error']:.2g} | {m['bulk']:.3g} +- "
                     f"{m['bulk_error']:.1g} | {m['expected']:.4g} | {m['lambda_n']:.4g} +- {m['lambda_n_error']:.2g} "
                     f"| {m['ratio']:.3f} +- {m['ratio_error']:.3f} | {m['ratio_k1_0']:.3f} | {m['ratio_k1_1']:.3f} "
                     f"| {m['rate_tau']:.3f} |")
    return '\n'.join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(prog='python3 -m membrane_flow capillary', description=__doc__.splitlines()[0])
    parser.add_argument('stripes', nargs='+', help='the run directories of the stripe (pooled)')
    parser.add_argument('--bulk', required=True, help='the run directory of the same parameters in one phase')
    parser.add_argument('--skip', type=float, default=0.01, help='snapshots before this time are left out')
    parser.add_argument('--modes', type=int, default=5, help='n = 1 .. modes')
    parser.add_argument('--batches', type=int, default=20)
    parser.add_argument('--json', help='also write the result to this file')
    args = parser.parse_args(argv)
    if args.modes < 1:
        parser.error(f'--modes must be >= 1 (got {args.modes})')
    if args.batches < 2:
        parser.error(f'--batches must be >= 2 (got {args.batches})')
    try:
        result = capillary_spectrum(args.stripes, args.bulk, args.skip, args.modes, args.batches)
    except (OSError, KeyError, ValueError) as e:
        print(f'capillary: {e}', file=sys.stderr)
        return 1
    print(table(result))
    if args.json:
        with open(args.json + '.part', 'w') as f:
            json.dump(result, f, indent=1)
        os.replace(args.json + '.part', args.json)
    return 0


if __name__ == '__main__':
    sys.exit(main())
