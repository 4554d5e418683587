#!/usr/bin/env python3
"""membrane_flow.sharp_interface (experiments/studies/sharp_interface): numbers that are wrong when
the code is wrong.

- the line-tension constant c = integral sqrt(2 f) against direct quadrature (and the profile's
  energy per length: the tanh profile of sigma (xi^2/2 phi'^2 + f) integrates to c sigma xi);
- the discrete energy of exact spherical caps against the closed form 1/2 kappa (H - H0)^2 area with
  H = -2/R (MODEL.md's sign), converging at second order, and Gauss-Bonnet's boundary term;
- the analytic gradient and Hessian of the Lagrangian against the complex-step Jacobian;
- Lipowsky's sphere-cap model: crossing at lambda = 2 kappa / R (4 kappa / L), flat instability at
  4 kappa / R (8 kappa / L) found by sheet_minima;
- the constrained minimization of the 7.3 setup: constraints held, the multiplier is dB/dr_d,
  convergence with the number of segments, and B(r_d) -> the complete bud as r_d -> 0.
"""
import math
import sys

import numpy as np
from scipy.integrate import quad

from membrane_flow import sharp_interface as si
from checks import NARROW, Checks  # tests/checks.py, next to this script

check = Checks(*NARROW)

# 1. Line tension: c against adaptive quadrature of sqrt(2 f), and against the energy per length of the
#    equilibrium profile phi = tanh(3 x / (4 xi)) of sigma (xi^2/2 phi'^2 + f(phi)).
c_direct = quad(lambda p: math.sqrt(2.0 * si.double_well(p)), -1.0, 1.0, epsabs=1e-14)[0]
check(abs(si.line_tension_constant() - c_direct) < 1e-12, f"c = {si.line_tension_constant():.15f} = quad {c_direct:.15f}")
check(abs(c_direct - 1.0) < 1e-12, "c = 1 for f = 9/32 (phi^2 - 1)^2 (MODEL.md: line tension sigma xi)")
xi, sigma = 0.03, 630.0
profile = lambda x: math.tanh(3.0 * x / (4.0 * xi))
slope = lambda x: 3.0 / (4.0 * xi) / math.cosh(3.0 * x / (4.0 * xi)) ** 2
per_length = quad(lambda x: sigma * (0.5 * xi ** 2 * slope(x) ** 2 + si.double_well(profile(x))), -40 * xi, 40 * xi,
                  epsabs=1e-12, limit=200)[0]
check(abs(per_length - si.Setup(xi=xi).line_tension(sigma)) < 1e-9 * per_length,
      f"profile energy per length {per_length:.12f} = c sigma xi = {si.Setup(xi=xi).line_tension(sigma):.12f}")

# 2. Exact spherical caps (psi = -s / R about the +z apex, outward normal): discrete bending energy against
#    the closed form, with H0 != 0 so that the sign of H matters; second-order convergence.
R, H0, kappa = 0.3, -2.5, 1.7
setup = si.Setup(kappa_A=kappa, kappa_B=1.0, H0_A=H0, kappa_G_A=-1.0, kappa_G_B=0.4, domain_area=0.3, total_area=1.3)
theta_A = 2.4  # more than a half sphere


def cap(n):
    """The domain on the exact cap psi = -s / R up to the polar angle theta_A (the matrix bends back to
    psi = 0 linearly; it does not enter the domain's bending energy)."""
    meridian = si.Meridian(setup, n, n, grading=1.3)
    nodes_A = R * theta_A * np.r_[0.0, np.cumsum(meridian.d_A)]
    psi = np.r_[-nodes_A / R, -theta_A * (1.0 - np.cumsum(meridian.d_B))]
    x = np.r_[psi[1:-1], R * theta_A, 0.5]
    return meridian.energy_parts(x), meridian.evaluate(x)[0, 1]


exact = si.cap_bending_energy(kappa, H0, R, theta_A)
exact_area = 2 * math.pi * R * R * (1 - math.cos(theta_A))
check(abs(si.sphere_bending_energy(kappa, H0, R) - 2 * math.pi * kappa * (2 + H0 * R) ** 2) < 1e-12,
      "sphere: 1/2 kappa (-2/R - H0)^2 4 pi R^2 = 2 pi kappa (2 + H0 R)^2")
check(abs(si.sphere_bending_energy(1.0, -2.0 / R, R)) < 1e-12, "a sphere with H0 = -2/R costs no bending energy")
errors = []
for n in (20, 40, 80, 160):
    parts, area_A = cap(n)
    errors.append(abs(parts['bending_A'] - exact))
    print(f"      cap, {n} segments: bending {parts['bending_A']:.10f} (exact {exact:.10f}), area {area_A:.10f} "
          f"(exact {exact_area:.10f}), r_d {parts['r_d']:.10f} (exact {R * math.sin(theta_A):.10f})")
orders = [math.log2(errors[i] / errors[i + 1]) for i in range(len(errors) - 1)]
print(f"      errors {['%.2e' % e for e in errors]}, orders {['%.2f' % o for o in orders]}")
check(errors[-1] < 1e-3 * exact and min(orders) > 1.8,
      f"cap bending energy with H0 = {H0}: relative error {errors[-1] / exact:.1e}, order {min(orders):.2f} >= 1.8")
wrong = 0.5 * kappa * (2.0 / R - H0) ** 2 * exact_area  # H = +2/R, the wrong sign
check(abs(cap(80)[0]['bending_A'] - wrong) > 0.3 * exact, "the sign convention H = -2/R on a +z bud matters here")
gauss = 2 * math.pi * (-1.0 * (1 - math.cos(-theta_A)) + 0.4 * (math.cos(-theta_A) - 1.0))
check(abs(cap(40)[0]['gaussian'] - gauss) < 1e-12, "Gauss-Bonnet: kappa_G terms through psi at the boundary")

# 3. The Lagrangian's analytic gradient and Hessian against the complex-step Jacobian.
setup3 = si.Setup(kappa_A=1.5, kappa_B=2.0, H0_A=-3.0, H0_B=1.0, kappa_G_A=-1.0, kappa_G_B=0.5)
meridian = si.Meridian(setup3, 20, 25)
x = meridian.bump_guess()
mu = np.array([0.3, -0.7, 1.1, 2.3])
values, J = meridian.evaluate_with_jacobian(x)
reference = J[0] - mu @ J[1:5]
gradient = meridian.lagrangian_gradient(x[None, :], mu)[0]
check(np.max(np.abs(gradient - reference)) < 1e-10 * np.max(np.abs(reference)), "Lagrangian gradient = complex step")
W = meridian.lagrangian_hessian(x, mu)
step = 1e-6
fd = np.array([(meridian.lagrangian_gradient((x + step * e)[None, :], mu)[0]
                - meridian.lagrangian_gradient((x - step * e)[None, :], mu)[0]) / (2 * step) for e in np.eye(x.size)]).T
check(np.max(np.abs(W - fd)) < 1e-5 * np.max(np.abs(W)), "Lagrangian Hessian = central differences of the gradient")

# 4. Lipowsky's sphere-cap model through sheet_minima: domain area 4 pi R^2, H0 = 0, no Gaussian jump:
#    the complete bud (r_d = 0) and the flat disk (r_d = 2 R) have equal energies at lambda = 2 kappa / R
#    (= 4 kappa / L, L = 2 R the flat radius), and the flat disk is a minimum up to 4 kappa / R (= 8 kappa / L).
kappa_c, Rb = 1.5, 0.13
radii = np.linspace(0.0, 2 * Rb, 2001)
B = si.cap_model_reduced_energy(kappa_c, 4 * math.pi * Rb ** 2, radii)
lams = np.linspace(0.5, 5.0, 901) * kappa_c / Rb
flat_exists, crossing = [], None
for lam in lams:
    energy = dict(si.sheet_minima(radii, B, lam))
    flat_exists.append(2 * Rb in energy)
    if crossing is None and 2 * Rb in energy and 0.0 in energy and energy[0.0] <= energy[2 * Rb]:
        crossing = lam
last_flat = lams[np.flatnonzero(flat_exists)[-1]]
check(abs(crossing - 2 * kappa_c / Rb) < 0.01 * kappa_c / Rb,
      f"cap model: crossing lambda {crossing:.3f} = 2 kappa / R = {2 * kappa_c / Rb:.3f}")
check(abs(last_flat - 4 * kappa_c / Rb) < 0.01 * kappa_c / Rb,
      f"cap model: flat disk unstable above {last_flat:.3f} = 4 kappa / R = {4 * kappa_c / Rb:.3f}")

# 5. The constrained minimization on the 7.3 setup.
setup73 = si.setup_from_prm(sys.argv[1]) if len(sys.argv) > 1 else si.Setup()
check(abs(setup73.domain_area - 0.225) < 1e-12 and setup73.total_area == 1.3, "7.3: domain area (1.3 - 0.85) / 2 = 0.225")
results = {}
for n in (20, 40, 80):
    m = si.Meridian(setup73, n, n, 1.6)
    Bv, xv, info = si.minimize_at_radius(m, 0.2, m.bump_guess())
    v = m.evaluate(xv)[0]
    held = max(abs(v[1] - 0.225), abs(v[2] - 1.075), abs(v[3] - setup73.rim_radius), abs(v[4] - 0.2))
    check(info['converged'] and info['stable'] and held < 1e-10,
          f"{n} segments: B(0.2) = {Bv:.8f}, a stable minimum, constraints held to {held:.0e}")
    B2, _, _ = si.minimize_at_radius(m, 0.2 + 1e-4, xv, info['mu'])
    B1, _, _ = si.minimize_at_radius(m, 0.2 - 1e-4, xv, info['mu'])
    check(abs((B2 - B1) / 2e-4 - info['mu'][3]) < 1e-3 * abs(info['mu'][3]),
          f"{n} segments: the multiplier {info['mu'][3]:.5f} is dB/dr_d = {(B2 - B1) / 2e-4:.5f}")
    results[n] = Bv
d1, d2 = abs(results[20] - results[40]), abs(results[40] - results[80])
check(d2 < d1 / 3 and d2 < 1e-3 * results[80], f"B(0.2) converges with the segments: differences {d1:.2e}, {d2:.2e}")
matrix_energy, _ = si.matrix_without_domain(setup73, n=80)
E0 = si.complete_bud_energy(setup73, matrix_energy)
check(abs(E0 - (8 * math.pi * 1.5 + matrix_energy)) < 1e-12, f"complete bud {E0:.6f} = 8 pi kappa + matrix {matrix_energy:.6f}")
rows, _ = si.scan(setup73, [0.2, 0.1, 0.05, 0.02, 0.01], 40, 40)
gaps = [E0 - row['B'] for row in rows]
print(f"      B(0) - B(r_d) at r_d = 0.2, 0.1, 0.05, 0.02, 0.01: {['%.4f' % g for g in gaps]}")
check(all(row['success'] for row in rows) and all(g > 0 for g in gaps) and gaps[-1] < 0.6 * gaps[-2],
      "B(r_d) rises towards the complete bud's energy (sphere + matrix) as the neck closes")

if check.failures:
    print(f"{check.failed} check(s) failed")
    sys.exit(1)
print("all checks passed")
