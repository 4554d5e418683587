"""Stationary fluctuation spectra of a run at k_BT > 0 against their equilibrium values
(docs/fluctuations.md): the height modes of the flat patch against
k_BT / (A (kappa q^4 + Sigma q^2)), and the spherical-harmonic modes of a quasi-spherical
vesicle against Milner and Safran, k_BT / (kappa (l - 1)(l + 2)(l (l + 1) + Sigma R^2 / kappa)).

Both read the statistics.txt of a run with a fixed tau (one row per step): the mode columns
(`height_mode_1`, `height_mode_2` on the patch; `shape_mode_2` .. `shape_mode_6` on a closed
surface), `gamma_mean` (the mean area multiplier) and the line-energy density
G = (gradient_energy + well_energy) / area.

The tension. Sigma is the area multiplier, but which mean of it: the local area constraint holds
the area of every vertex, so the total area is fixed and the multiplier fluctuates with the area
the modes hold (its standard deviation per step is of the order of its mean). A mode's amplitude
h obeys dh = -L_X (kappa q^4 + gamma q^2) h dt + noise, so its stationary variance is
k_BT / (kappa q^4 + Sigma_q q^2) with the multiplier weighted by the mode's own amplitude,

    Sigma_q = <(gamma + G) |h_q|^2> / <|h_q|^2>,

the tension the mode feels. The plain mean <gamma + G> underestimates it where the modes'
area and the multiplier correlate; both are reported, the comparison uses Sigma_q.

The time step. The scheme treats the bending implicitly and the tension explicitly (the normal
row couples the new multiplier to the curvature of the old surface), so a mode of bending rate
lambda_b (L_X kappa q^4 on the patch; sphere_rates on a sphere) and tension rate mu (L_X Sigma q^2)
has the stationary variance

    <|h|^2> = k_BT / (K (1 + (lambda_b - mu) tau / 2))

of the step h' = ((1 - mu tau) h + tau L_X eta) / (1 + lambda_b tau), the equilibrium value
divided by the factor of a fixed tau.

Error bars are batch means over `batches` consecutive blocks of the sampled steps.

    python3 -m membrane_flow spectrum patch results/thermal-patch --kT 1e-4
    python3 -m membrane_flow spectrum sphere results/quasi_spherical/n8 --kT 1e-4 --static results/.../n8_static
    python3 -m membrane_flow spectrum sphere results/studies/physical_temperature/vesicle16-kT20 --kT 0.05 --fit
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

from . import launch
from .run import read_statistics


def _statistics(path):
    return read_statistics(os.path.join(path, 'statistics.txt') if os.path.isdir(path) else path)


def batch_means(series, batches):
    """The means of `batches` consecutive blocks of `series` along its first axis (np.array_split:
    sizes differ by at most one)."""
    return np.array([b.mean(axis=0) for b in np.array_split(series, batches)])


def batch_error(series, batches):
    """The standard error of the mean of `series` from the means of `batches` consecutive blocks."""
    return batch_means(series, batches).std(ddof=1) / math.sqrt(batches)


class TooFewSteps(ValueError):
    """The run has too few steps after the skipped ones for the batch means."""


def _sampled(columns, skip, batches):
    rows = slice(skip + 1, None)  # row 0 is the initial state
    n = len(columns['step'][rows])
    if n < 2 * batches:
        raise TooFewSteps(f'{n} steps after the first {skip}: too few for {batches} batches')
    taus = columns['tau'][rows]
    if taus.max() - taus.min() > 1e-9 * taus.max():  # the last step lands on the end time to round-off
        raise ValueError('the stationary spectra need a fixed tau (Time stepping/Adaptive = false)')
    tension = columns['gamma_mean'] + (columns['gradient_energy'] + columns['well_energy']) / columns['area']
    return rows, n, taus.mean(), tension[rows]


def _compare(name, series, tension, stiffness, tension_weight, bending_rate, tension_rate, tau, kT, batches):
    """One mode: its measured <|h|^2> against k_BT / (stiffness(S) (1 + (lambda_b - mu(S)) tau / 2)),
    S the mode-weighted tension. stiffness(S) = K_b + S tension_weight."""
    mean = series.mean()
    sigma_mean = tension.mean()
    sigma_mode = float(np.mean(tension * series) / mean)
    stiffness_mode = stiffness + sigma_mode * tension_weight
    factor = 1 / (1 + (bending_rate - sigma_mode * tension_rate) * tau / 2)
    expected = kT * factor / stiffness_mode
    error = batch_error(series, batches)
    return {
        'mode': name, 'measured': float(mean), 'error': float(error),
        'sigma_mean': float(sigma_mean), 'sigma_mode': sigma_mode,
        'lambda_tau': float((bending_rate + sigma_mode * tension_rate) * tau), 'step_factor': float(factor),
        'expected': float(expected), 'ratio': float(mean / expected), 'ratio_error': float(error / expected),
        'ratio_plain_mean': float(mean / (kT / (1 + (bending_rate - sigma_mean * tension_rate) * tau / 2)
                                          / (stiffness + sigma_mean * tension_weight))),
    }


def patch_spectrum(path, kT, kappa=1.0, mobility=1.0, skip=200, batches=20):
    """The shells |k|^2 = 1, 2 of the height of a flat periodic patch (area 1) against
    k_BT / (kappa q^4 + Sigma_q q^2), q = 2 pi |k|."""
    columns = _statistics(path)
    rows, n, tau, tension = _sampled(columns, skip, batches)
    result = {'steps': n, 'tau': float(tau), 'modes': []}
    for shell in (1, 2):
        q2 = 4 * math.pi**2 * shell
        result['modes'].append(_compare(f'|k|^2 = {shell}', columns[f'height_mode_{shell}'][rows], tension,
                                        kappa * q2 * q2, q2, mobility * kappa * q2 * q2, mobility * q2, tau, kT,
                                        batches))
    return result


def sphere_rates(l, R, kappa, mobility):
    """(K_b, tension weight, lambda_b, mu per unit Sigma) of the degree-l mode u of a sphere of
    radius R: K = kappa (l - 1)(l + 2) l (l + 1) + Sigma R^2 (l - 1)(l + 2), and the decay rate
    L_X K / (R^4 (1 + 4 / (l (l + 1)))) with the tangential flow the local area constraint drags
    along (tests/test_spherical_modes.cc)."""
    drag = R**4 * (1 + 4 / (l * (l + 1)))
    bending = kappa * (l - 1) * (l + 2) * l * (l + 1)
    weight = R**2 * (l - 1) * (l + 2)
    return bending, weight, mobility * bending / drag, mobility * weight / drag


# Legendre polynomials P_l(c), c = z / |x|, as muparser expressions for sphere_stiffness.
_LEGENDRE = {2: '(3*c^2-1)/2', 3: '(5*c^3-3*c)/2', 4: '(35*c^4-30*c^2+3)/8', 5: '(63*c^5-70*c^3+15*c)/8',
             6: '(231*c^6-315*c^4+105*c^2-5)/16'}


def sphere_stiffness(exe, prm, settings=(), degrees=(2, 3), amplitude=0.01, kappa=1.0):
    """The bending stiffness of the mesh for the degree-l modes of a sphere, as a factor to the
    continuum kappa (l - 1) l (l + 1)(l + 2) per the observable's u_lm^2: the bending energy of
    the surface displaced radially by amplitude * P_l(z / r) against that of the undisplaced one,
    from the first statistics row of two one-step runs of `prm` with `settings` (the run's own
    --set list: mesh, material). It includes the observable's own attenuation, so that
    k_BT / (continuum K_l * factor) is what the run's shape_mode_l should read in equilibrium."""
    work = tempfile.mkdtemp(prefix='membrane_stiffness_')
    env = launch.environment()

    def bending(degree):
        out = os.path.join(work, str(degree))
        shift = '0' if degree == 0 else f'{amplitude}*{_LEGENDRE[degree]}'.replace('c', '(z/sqrt(x^2+y^2+z^2))')
        radial = '/sqrt(x^2+y^2+z^2)'
        expression = '; '.join(f'({shift})*{x}{radial}' for x in 'xyz')
        command = [exe, '--quiet', *[a for s in settings for a in ('--set', s)],
                   '--set', 'Initial shape/Shape=expression', '--set', f'Initial shape/Displacement expression={expression}',
                   '--set', 'Material/Temperature=0', '--set', 'Time stepping/Adaptive=false',
                   '--set', 'Time stepping/Time step=1e-9', '--set', 'Time stepping/Maximum steps=1',
                   '--set', 'Output/Write VTU=false', '--set', f'Output/Directory={out}', prm]
        subprocess.run(command, check=True, env=env, stdout=subprocess.DEVNULL)
        return read_statistics(os.path.join(out, 'statistics.txt'))

    flat = bending(0)
    factors = {}
    for l in degrees:
        row = bending(l)
        energy = row['bending_energy'][0] - flat['bending_energy'][0]
        u2 = (row[f'shape_mode_{l}'][0] - flat[f'shape_mode_{l}'][0]) * (2 * l + 1)  # sum over m
        factors[l] = float(energy / (0.5 * kappa * (l - 1) * l * (l + 1) * (l + 2) * u2))
    return factors


def sphere_spectrum(path, kT, kappa=1.0, mobility=1.0, skip=500, batches=20, static=None, degrees=(2, 3, 4),
                    stiffness=None):
    """shape_mode_l = <u_lm^2> (mean over m) of a closed run against Milner and Safran with the
    tension the mode feels. `static`: the statistics of the same run at k_BT = 0, whose last
    shape_mode_l (the discrete sphere's own deformation, the mean shape) is subtracted.
    `stiffness`: {l: factor} of sphere_stiffness, the mesh's bending stiffness of the mode; without
    it the continuum's."""
    columns = _statistics(path)
    rows, n, tau, tension = _sampled(columns, skip, batches)
    R = (3 * columns['volume'][rows].mean() / (4 * math.pi)) ** (1 / 3)
    base = {l: 0.0 for l in degrees}
    if static:
        last = _statistics(static)
        base = {l: float(last[f'shape_mode_{l}'][-1]) for l in degrees}
    result = {'steps': n, 'tau': float(tau), 'R': float(R), 'static': base, 'modes': []}
    for l in degrees:
        bending, weight, bending_rate, tension_rate = sphere_rates(l, R, kappa, mobility)
        series = columns[f'shape_mode_{l}'][rows] - base[l]
        continuum = _compare(f'l = {l}', series, tension, bending, weight, bending_rate, tension_rate, tau, kT, batches)
        if stiffness:
            mode = _compare(f'l = {l}', series, tension, bending * stiffness[l], weight, bending_rate * stiffness[l],
                            tension_rate, tau, kT, batches)
            mode['stiffness_factor'] = stiffness[l]
            mode['ratio_continuum'] = continuum['ratio']
        else:
            mode = continuum
        result['modes'].append(mode)
    return result


def sphere_fit(path, kT, mobility=1.0, skip=500, batches=20, degrees=(2, 3, 4, 5, 6), stiffness=None):
    """The two-parameter fit of Milner and Safran to a closed run's spectrum: kappa and the
    tension Sigma such that shape_mode_l = k_BT / (K_l (1 + (lambda_b - mu) tau / 2)) for the
    given degrees, with K_l = kappa b_l + Sigma w_l, b_l = s_l (l - 1) l (l + 1)(l + 2) (s_l the mesh's
    stiffness factor, `stiffness` from sphere_stiffness; 1 without it), w_l = R^2 (l - 1)(l + 2), and
    the factor of a fixed tau of _compare, (lambda_b - mu) = L_X (kappa b_l - Sigma w_l) / d_l with the
    drag d_l of sphere_rates. Then
        k_BT / shape_mode_l = kappa b_l + Sigma w_l + L_X tau (kappa^2 b_l^2 - Sigma^2 w_l^2) / (2 d_l),
    fitted by Gauss-Newton (from the solution without the step factor), each degree weighted by the
    batch-means error of its mean. Returns kappa and Sigma with their standard errors, and per degree
    the measured and the fitted value."""
    columns = _statistics(path)
    rows, n, tau, _ = _sampled(columns, skip, batches)
    R = (3 * columns['volume'][rows].mean() / (4 * math.pi)) ** (1 / 3)
    measured = np.array([columns[f'shape_mode_{l}'][rows].mean() for l in degrees])
    errors = np.array([batch_error(columns[f'shape_mode_{l}'][rows], batches) for l in degrees])
    factor_of = {l: (stiffness or {}).get(l, 1.0) for l in degrees}
    b = np.array([factor_of[l] * (l - 1) * l * (l + 1) * (l + 2) for l in degrees], dtype=float)
    w = np.array([R**2 * (l - 1) * (l + 2) for l in degrees], dtype=float)
    c = mobility * tau / (2 * np.array([R**4 * (1 + 4 / (l * (l + 1))) for l in degrees]))
    y = kT / measured
    dy = y * errors / measured

    def model(p):
        return p[0] * b + p[1] * w + c * (p[0]**2 * b**2 - p[1]**2 * w**2)

    def jacobian(p):
        return np.stack([b + 2 * c * p[0] * b**2, w - 2 * c * p[1] * w**2], axis=1) / dy[:, None]

    p = np.linalg.lstsq(np.stack([b, w], axis=1) / dy[:, None], y / dy, rcond=None)[0]
    for _ in range(50):
        delta = np.linalg.lstsq(jacobian(p), (y - model(p)) / dy, rcond=None)[0]
        p = p + delta
        if np.all(np.abs(delta) <= 1e-12 * (np.abs(p) + 1e-300)):
            break
    covariance = np.linalg.inv(jacobian(p).T @ jacobian(p))
    kappa, sigma = p
    step = 1 / (1 + c * (kappa * b - sigma * w))
    expected = kT * step / (kappa * b + sigma * w)
    return {'steps': n, 'tau': float(tau), 'R': float(R), 'degrees': list(degrees),
            'kappa': float(kappa), 'kappa_error': float(math.sqrt(covariance[0, 0])),
            'sigma': float(sigma), 'sigma_error': float(math.sqrt(covariance[1, 1])),
            'stiffness': {str(l): float(factor_of[l]) for l in degrees},
            'modes': [{'l': l, 'measured': float(m), 'error': float(e), 'fitted': float(x),
                       'step_factor': float(f)} for l, m, e, x, f in zip(degrees, measured, errors, expected, step)]}


def table(result):
    """A markdown table of the comparison; with the mesh's stiffness, also the ratio to the continuum's."""
    discrete = 'stiffness_factor' in result['modes'][0]
    head = ['mode', 'lambda tau', '<|h|^2>', 'Sigma (plain mean)', 'Sigma_q (mode-weighted)', 'expected',
            'measured / expected', 'with the plain mean']
    if discrete:
        head += ['mesh stiffness / continuum', 'measured / continuum']
    lines = [f"{result['steps']} steps sampled, tau {result['tau']:g}", '| ' + ' | '.join(head) + ' |',
             '|' + '---|' * len(head)]
    for m in result['modes']:
        cells = [m['mode'], f"{m['lambda_tau']:.3f}", f"{m['measured']:.4g}", f"{m['sigma_mean']:.4g}",
                 f"{m['sigma_mode']:.4g}", f"{m['expected']:.4g}", f"{m['ratio']:.3f} +- {m['ratio_error']:.3f}",
                 f"{m['ratio_plain_mean']:.3f}"]
        if discrete:
            cells += [f"{m['stiffness_factor']:.3f}", f"{m['ratio_continuum']:.3f}"]
        lines.append('| ' + ' | '.join(cells) + ' |')
    return '\n'.join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(prog='python3 -m membrane_flow spectrum',
                                     description=__doc__.splitlines()[0])
    parser.add_argument('surface', choices=('patch', 'sphere'))
    parser.add_argument('run', help='the run directory (or its statistics.txt)')
    parser.add_argument('--kT', type=float, required=True, help='Material/Temperature of the run')
    parser.add_argument('--kappa', type=float, default=1.0)
    parser.add_argument('--mobility', type=float, default=1.0, help='Material/Shape mobility of the run')
    parser.add_argument('--skip', type=int, help='steps left out at the start (default 200 patch, 500 sphere)')
    parser.add_argument('--batches', type=int, default=20)
    parser.add_argument('--static', help='sphere: the same run at k_BT = 0, whose mean shape is subtracted')
    parser.add_argument('--fit', action='store_true',
                        help='sphere: fit kappa and Sigma to shape_mode_2..6 (sphere_fit, the continuum\'s stiffness)')
    args = parser.parse_args(argv)
    for name, value, low in (('--kT', args.kT, 0), ('--kappa', args.kappa, 0), ('--mobility', args.mobility, 0)):
        if not value > low:  # also NaN
            parser.error(f'{name} must be > 0 (got {value:g})')
    if args.batches < 2:
        parser.error(f'--batches must be >= 2 (got {args.batches})')
    if args.skip is not None and args.skip < 0:
        parser.error(f'--skip must be >= 0 (got {args.skip})')
    try:
        if args.surface == 'patch':
            result = patch_spectrum(args.run, args.kT, args.kappa, args.mobility,
                                    200 if args.skip is None else args.skip, args.batches)
        elif args.fit:
            fit = sphere_fit(args.run, args.kT, args.mobility, 500 if args.skip is None else args.skip, args.batches)
            print(f"{fit['steps']} steps sampled, tau {fit['tau']:g}, R {fit['R']:.4f}: kappa {fit['kappa']:.4f} +- "
                  f"{fit['kappa_error']:.4f}, Sigma {fit['sigma']:.3f} +- {fit['sigma_error']:.3f}")
            for m in fit['modes']:
                print(f"l = {m['l']}: {m['measured']:.4g} +- {m['error']:.2g}, fitted {m['fitted']:.4g} "
                      f"(step factor {m['step_factor']:.3f})")
            return 0
        else:
            result = sphere_spectrum(args.run, args.kT, args.kappa, args.mobility,
                                     500 if args.skip is None else args.skip, args.batches, args.static)
    except TooFewSteps as e:
        # A run cut short (the docs test runs 3 steps of each command): nothing to compare.
        print(f'spectrum: {args.run}: {e}')
        return 0
    except KeyError as e:
        print(f'spectrum: {args.run}: no statistics column {e} (a {args.surface} run at k_BT > 0?)', file=sys.stderr)
        return 1
    except (OSError, ValueError) as e:
        print(f'spectrum: {e}', file=sys.stderr)
        return 1
    print(table(result))
    return 0


if __name__ == '__main__':
    sys.exit(main())
