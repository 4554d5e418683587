"""Sharp-interface limit of the 7.3 budding setup: a flat domain against a bud.

    python3 -m membrane_flow.sharp_interface [experiments/7.3-budding.prm] [--json out.json]

The phase-field energy of MODEL.md section 2 tends, for xi -> 0 at fixed sigma * xi, to a
sharp-interface energy (Juelicher and Lipowsky, Phys. Rev. E 53, 2670 (1996)):

    F = sum over the phases P = A, B of integral over P of 1/2 kappa_P (H - H0_P)^2 ds     (Helfrich)
      + sum over P of kappa_G,P integral over P of K ds                                    (Gaussian)
      + lambda * (length of the domain boundary)                                          (line energy)

with H the SUM of the principal curvatures in MODEL.md's sign convention (normal +e_z on the
flat patch, H = -2/R on a sphere with the outward normal, H < 0 on top of an upward bump), and

    lambda = c * sigma * xi,   c = integral from -1 to 1 of sqrt(2 f(phi)) dphi = 1 for
    f = 9/32 (phi^2 - 1)^2

(the one-dimensional equilibrium profile of sigma (xi^2/2 phi'^2 + f) has xi^2/2 phi'^2 = f, so
its energy per length is sigma * integral 2 f dx = sigma xi integral sqrt(2 f) dphi).

The setup of 7.3 (MODEL.md section 5, experiments/7.3-budding.prm): the periodic unit square
(projected area 1, the box is fixed) carries a membrane of area A_tot = `Initial shape/Bump area`
(1.3: it has 0.3 of excess area from the start, held in the initial bump), the domain of phase A
has the area A_d = integral (1 + phi0)/2 ds = (A_tot + Mass)/2 (0.225 for Mass = -0.85) and
phase B the rest. The flow conserves the area of every material element and phi is carried by
the material, so in the sharp limit each phase keeps its area: A_A = A_d and A_B = A_tot - A_d
are fixed, and a bud takes its area from the domain itself; the excess area of the patch is
shared between the bump under the domain and the matrix.

Approximations (stated in the report):
- axisymmetry: the square is replaced by a disk of the same projected area (rim radius
  R_p = 1/sqrt(pi)); at the rim the membrane is horizontal (psi = 0: the mirror symmetry of a
  centred bump across the cell edges) at a fixed radius (the fixed box); the height is free;
- the meridian is a polygon with nodes at a fixed fraction of each phase's arc length (the
  nodes are graded towards the domain boundary, where a neck forms), the tangent angle at the
  nodes are the unknowns; the bending energy is the midpoint rule on the segments (second order);
- the domain boundary is a sharp line; the Gaussian energy is evaluated exactly through
  Gauss-Bonnet (below); the bud is on the side of the initial bump (+z).

Method: for a fixed radius r_d of the domain boundary the line energy 2 pi lambda r_d is fixed,
so B(r_d) = min (bending + Gaussian) over the shapes with that boundary radius and the two phase
areas does not depend on sigma. The total energy along this reduced coordinate is
E(r_d; sigma) = B(r_d) + 2 pi c sigma xi r_d: its local minima in r_d are the equilibria (a
local minimum of the full problem is a local minimum of E over r_d), the flat (cap) branch at
large r_d, the budded branch at small r_d; r_d = 0 is the complete bud (a sphere of area A_d on
an ideal neck). B(r_d) is computed once by continuation in r_d (constrained minimization, SLSQP
with complex-step derivatives), and then the branches, the crossing and the turning points
follow for every sigma.
"""
import argparse
import json
import math
import os
import sys

import numpy as np

TWO_PI = 2.0 * math.pi


# ---------------------------------------------------------------------------------------------
# Line tension of the diffuse interface


def double_well(phi):
    """MODEL.md's f(phi) = 9/32 (phi^2 - 1)^2."""
    return 9.0 / 32.0 * (phi * phi - 1.0) ** 2


def line_tension_constant(f=double_well, points=200):
    """c = integral over -1..1 of sqrt(2 f(phi)) dphi (Gauss-Legendre; exactly 1 for MODEL.md's f).

    The sharp-interface line tension of sigma (xi^2/2 |grad phi|^2 + f(phi)) is lambda = c sigma xi.
    """
    x, w = np.polynomial.legendre.leggauss(points)
    return float(np.sum(w * np.sqrt(2.0 * f(x))))


# ---------------------------------------------------------------------------------------------
# The setup


class Setup:
    """Moduli, areas and the transition length of a patch with one domain (simulator units)."""

    def __init__(self, kappa_A=1.5, kappa_B=1.5, H0_A=0.0, H0_B=0.0, kappa_G_A=-1.0, kappa_G_B=-1.0,
                 xi=0.03, total_area=1.3, domain_area=0.225, projected_area=1.0):
        self.kappa_A, self.kappa_B = float(kappa_A), float(kappa_B)
        self.H0_A, self.H0_B = float(H0_A), float(H0_B)
        self.kappa_G_A, self.kappa_G_B = float(kappa_G_A), float(kappa_G_B)
        self.xi = float(xi)
        self.total_area = float(total_area)
        self.domain_area = float(domain_area)
        self.projected_area = float(projected_area)
        if not 0.0 < self.domain_area < self.total_area:
            raise ValueError(f"domain area {self.domain_area} must lie in (0, total area {self.total_area})")

    @property
    def matrix_area(self):
        return self.total_area - self.domain_area

    @property
    def rim_radius(self):
        """Radius of the disk with the patch's projected area (the axisymmetric approximation)."""
        return math.sqrt(self.projected_area / math.pi)

    @property
    def flat_domain_radius(self):
        return math.sqrt(self.domain_area / math.pi)

    @property
    def bud_radius(self):
        """Radius of the sphere of area A_d (the complete bud)."""
        return math.sqrt(self.domain_area / (4.0 * math.pi))

    def line_tension(self, sigma):
        """lambda = c sigma xi: `Material/Line tension` sigma -> the sharp line tension."""
        return line_tension_constant() * sigma * self.xi

    def sigma(self, line_tension):
        return line_tension / (line_tension_constant() * self.xi)

    def as_dict(self):
        return {key: getattr(self, key) for key in ('kappa_A', 'kappa_B', 'H0_A', 'H0_B', 'kappa_G_A', 'kappa_G_B',
                                                     'xi', 'total_area', 'domain_area', 'projected_area')}


def read_prm(path):
    """The entries of a parameter file as {'Section/Sub/Entry': 'value'} (no defaults)."""
    entries, sections = {}, []
    with open(path) as stream:
        for line in stream:
            line = line.split('#', 1)[0].strip()
            if not line:
                continue
            words = line.split(None, 1)
            if words[0] == 'subsection':
                sections.append(words[1].strip())
            elif words[0] == 'end':
                sections.pop()
            elif words[0] == 'set':
                key, _, value = words[1].partition('=')
                entries['/'.join(sections + [key.strip()])] = value.strip()
    return entries


def setup_from_prm(path):
    """The Setup of an experiment with a bump initial phase of prescribed mass (as 7.3).

    The domain area is integral (1 + phi0)/2 ds = (area + Mass)/2: the sharp domain that holds the
    experiment's mass of phase A. Defaults are those of the program (docs/parameters.md).
    """
    prm = read_prm(path)

    def value(key, default):
        return float(prm.get(key, default))

    def modulus(name, default):
        return (value(f'Material/{name}/Phase A value', default), value(f'Material/{name}/Phase B value', default))

    if prm.get('Initial shape/Shape', 'flat') != 'bump':
        raise ValueError(f"{path}: the sharp-interface model is set up for Initial shape/Shape = bump")
    if prm.get('Initial phase/Type') != 'bump' or prm.get('Initial phase/Prescribe mass', 'false') != 'true':
        raise ValueError(f"{path}: needs Initial phase/Type = bump with Prescribe mass = true "
                         "(else give --domain-area)")
    total = value('Initial shape/Bump area', 1.3)
    mass = value('Initial phase/Mass', 0.0)
    kappa = modulus('Bending rigidity', 1.0)
    kappa_G = modulus('Gaussian rigidity', 0.0)
    H0 = modulus('Spontaneous curvature', 0.0)
    return Setup(kappa_A=kappa[0], kappa_B=kappa[1], H0_A=H0[0], H0_B=H0[1], kappa_G_A=kappa_G[0],
                 kappa_G_B=kappa_G[1], xi=value('Material/Transition length', 0.03), total_area=total,
                 domain_area=(total + mass) / 2.0)


# ---------------------------------------------------------------------------------------------
# Closed forms


def sphere_bending_energy(kappa, H0, R):
    """1/2 kappa (H - H0)^2 * 4 pi R^2 for a sphere with the outward normal, H = -2/R (MODEL.md):
    = 2 pi kappa (2 + H0 R)^2; a bud on the +z side of the patch has the outward normal."""
    return 0.5 * kappa * (-2.0 / R - H0) ** 2 * 4.0 * math.pi * R * R


def cap_bending_energy(kappa, H0, R, theta):
    """A spherical cap of radius R and polar angle theta about the +z apex, normal outward."""
    return 0.5 * kappa * (-2.0 / R - H0) ** 2 * TWO_PI * R * R * (1.0 - math.cos(theta))


def cap_model_reduced_energy(kappa, domain_area, r_d):
    """Lipowsky's sphere-cap model (J. Phys. II France 2, 1825 (1992)) as B(r_d): a domain of area
    A = 4 pi R^2 shaped as a spherical cap with the boundary radius r_d, only its bending energy
    (H0 = 0, no matrix): B = 8 pi kappa (1 - r_d^2 / (4 R^2)). With the line energy 2 pi lambda r_d
    the complete bud (r_d = 0) and the flat disk (r_d = 2 R) have equal energies at
    lambda = 2 kappa / R = 4 kappa / L (L = 2 R the flat radius), and the flat disk is unstable
    above lambda = 4 kappa / R = 8 kappa / L."""
    R2 = domain_area / (4.0 * math.pi)
    return 8.0 * math.pi * kappa * (1.0 - np.asarray(r_d) ** 2 / (4.0 * R2))


# ---------------------------------------------------------------------------------------------
# The discretized meridian


def graded_grid(n, grading, towards_end):
    """n + 1 points in [0, 1], finer towards one end: eta = 1 - (1 - t)^g (or t^g at the start)."""
    t = np.linspace(0.0, 1.0, n + 1)
    eta = 1.0 - (1.0 - t) ** grading if towards_end else t ** grading
    eta[0], eta[-1] = 0.0, 1.0
    return eta


class Meridian:
    """A meridian from the axis (r = 0, psi = 0) through the domain (n_A segments) to the rim
    (n_B segments of phase B, psi = 0 at r = R_p).

    Unknowns x = (psi_1 .. psi_{N-1}, L_A, L_B): the tangent angles at the inner nodes and the
    arc lengths of the two phases. The tangent is t = (cos psi, sin psi) in the (r, z) plane, the
    normal n = (-sin psi, cos psi) (+e_z where the patch is flat), so the principal curvatures are
    psi' (meridian) and sin(psi) / r (parallel) and H = psi' + sin(psi) / r: negative on top of an
    upward bump as in MODEL.md. A bud on the +z side has psi going from 0 at its apex to -pi at
    its bottom.
    """

    def __init__(self, setup, n_A=80, n_B=80, grading=1.6):
        self.setup = setup
        self.n_A, self.n_B = n_A, n_B
        self.N = n_A + n_B
        eta_A = graded_grid(n_A, grading, towards_end=True)   # fine at the domain boundary
        eta_B = graded_grid(n_B, grading, towards_end=False)
        self.d_A, self.d_B = np.diff(eta_A), np.diff(eta_B)
        self.kappa = np.r_[np.full(n_A, setup.kappa_A), np.full(n_B, setup.kappa_B)]
        self.H0 = np.r_[np.full(n_A, setup.H0_A), np.full(n_B, setup.H0_B)]
        self.node_s = None

    def split(self, x):
        x = np.atleast_2d(x)
        m = x.shape[0]
        psi = np.zeros((m, self.N + 1), dtype=x.dtype)
        psi[:, 1:self.N] = x[:, :self.N - 1]
        L_A, L_B = x[:, self.N - 1], x[:, self.N]
        h = np.concatenate([L_A[:, None] * self.d_A[None, :], L_B[:, None] * self.d_B[None, :]], axis=1)
        return psi, h

    def geometry(self, x):
        """Node radii and heights, segment lengths, midpoint radii and mean curvatures (batched)."""
        psi, h = self.split(x)
        mid = 0.5 * (psi[:, :-1] + psi[:, 1:])
        zeros = np.zeros((psi.shape[0], 1), dtype=psi.dtype)
        r = np.concatenate([zeros, np.cumsum(h * np.cos(mid), axis=1)], axis=1)
        z = np.concatenate([zeros, np.cumsum(h * np.sin(mid), axis=1)], axis=1)
        r_mid = 0.5 * (r[:, :-1] + r[:, 1:])
        H = np.diff(psi, axis=1) / h + np.sin(mid) / r_mid
        return psi, h, r, z, r_mid, H

    def evaluate(self, x):
        """Columns: bending + Gaussian energy, area of A, area of B, rim radius, domain-boundary radius,
        then the radii of the segment midpoints."""
        s = self.setup
        psi, h, r, z, r_mid, H = self.geometry(x)
        area = TWO_PI * r_mid * h  # lateral area of the cone frustum of each segment (exact for the polygon)
        # Helfrich: 1/2 kappa_P (H - H0_P)^2, H the sum of the principal curvatures, midpoint rule.
        bending = np.sum(0.5 * self.kappa * (H - self.H0) ** 2 * area, axis=1)
        # Gaussian: integral of K ds from the axis to arc length s is 2 pi (1 - cos psi(s)) (K ds =
        # psi' sin(psi) / r * 2 pi r ds), so each phase's kappa_G K integrates to boundary terms
        # (Gauss-Bonnet): kappa_G,A 2 pi (1 - cos psi_d) + kappa_G,B 2 pi (cos psi_d - cos psi_rim);
        # with psi_rim = 0 only the jump kappa_G,A - kappa_G,B enters, through psi_d at the domain boundary.
        psi_d = psi[:, self.n_A]
        gaussian = TWO_PI * (s.kappa_G_A * (1.0 - np.cos(psi_d)) + s.kappa_G_B * (np.cos(psi_d) - np.cos(psi[:, -1])))
        area_A = np.sum(area[:, :self.n_A], axis=1)
        area_B = np.sum(area[:, self.n_A:], axis=1)
        # Columns 5...: the radii of the segment midpoints, kept positive (an inequality): the meridian
        # must not cross the axis, where the area 2 pi r h and with it the energy would turn negative.
        return np.concatenate([np.stack([bending + gaussian, area_A, area_B, r[:, -1], r[:, self.n_A]], axis=1),
                               r_mid], axis=1)

    def evaluate_with_jacobian(self, x):
        """Values and exact derivatives (complex step: every operation above is analytic)."""
        x = np.asarray(x, dtype=float)
        n = x.size
        step = 1e-30
        X = np.tile(x.astype(complex), (n + 1, 1))
        X[1:, :] += 1j * step * np.eye(n)
        values = self.evaluate(X)
        return values[0].real, (values[1:].imag / step).T

    def lagrangian_gradient(self, x, mu):
        """Gradient of L = (bending + Gaussian) - mu . (A_A, A_B, r_rim, r_d) with respect to x, by
        hand (reverse mode through the recurrences of geometry()); batched over the rows of x and
        analytic in x, so its complex step gives the exact Hessian of L."""
        s = self.setup
        psi, h, r, z, r_mid, H = self.geometry(x)
        mid = 0.5 * (psi[:, :-1] + psi[:, 1:])
        c, sn = np.cos(mid), np.sin(mid)
        dpsi = np.diff(psi, axis=1)
        area = TWO_PI * r_mid * h
        dev = H - self.H0
        # e_k = 1/2 kappa dev^2 area_k; the area constraints add -mu_A area_k (k in A), -mu_B area_k (k in B)
        mu_area = np.r_[np.full(self.n_A, mu[0]), np.full(self.n_B, mu[1])]
        H_bar = self.kappa * dev * area
        area_bar = 0.5 * self.kappa * dev ** 2 - mu_area
        rm_bar = area_bar * TWO_PI * h - H_bar * sn / r_mid ** 2
        h_bar = area_bar * TWO_PI * r_mid - H_bar * dpsi / h ** 2
        psi_bar = np.zeros_like(psi)
        psi_bar[:, 1:] += H_bar / h
        psi_bar[:, :-1] -= H_bar / h
        mid_bar = H_bar * c / r_mid
        # r_mid_k = r_k + h_k c_k / 2
        r_bar = np.zeros_like(r)
        r_bar[:, :-1] += rm_bar
        h_bar += rm_bar * c / 2
        mid_bar -= rm_bar * h * sn / 2
        r_bar[:, -1] -= mu[2]
        r_bar[:, self.n_A] -= mu[3]
        # r_k = sum_{j<k} h_j c_j: the adjoint of h_j c_j is the sum of r_bar over the nodes after j
        hc_bar = np.cumsum(r_bar[:, :0:-1], axis=1)[:, ::-1]
        h_bar += hc_bar * c
        mid_bar -= hc_bar * h * sn
        psi_bar[:, :-1] += mid_bar / 2
        psi_bar[:, 1:] += mid_bar / 2
        psi_d = psi[:, self.n_A]
        psi_bar[:, self.n_A] += TWO_PI * (s.kappa_G_A - s.kappa_G_B) * np.sin(psi_d)
        L_A_bar = h_bar[:, :self.n_A] @ self.d_A
        L_B_bar = h_bar[:, self.n_A:] @ self.d_B
        return np.concatenate([psi_bar[:, 1:self.N], L_A_bar[:, None], L_B_bar[:, None]], axis=1)

    def lagrangian_hessian(self, x, mu):
        x = np.asarray(x, dtype=float)
        n = x.size
        step = 1e-30
        X = np.tile(x.astype(complex), (n, 1)) + 1j * step * np.eye(n)
        W = self.lagrangian_gradient(X, mu).imag / step
        return 0.5 * (W + W.T)

    def energy_parts(self, x):
        s = self.setup
        psi, h, r, z, r_mid, H = self.geometry(np.asarray(x, dtype=float))
        area = TWO_PI * r_mid * h
        parts = 0.5 * self.kappa * (H - self.H0) ** 2 * area
        psi_d = psi[0, self.n_A]
        return {'bending_A': float(np.sum(parts[0, :self.n_A])), 'bending_B': float(np.sum(parts[0, self.n_A:])),
                'gaussian': float(TWO_PI * (s.kappa_G_A * (1.0 - math.cos(psi_d)) + s.kappa_G_B * (math.cos(psi_d) - 1.0))),
                'psi_d': float(psi_d), 'r_d': float(r[0, self.n_A]), 'z_apex_over_rim': float(-z[0, -1]),
                # the simulator's neck ratio: the boundary (neck) radius over the widest radius of the domain
                'neck_ratio': float(r[0, self.n_A] / np.max(r[0, :self.n_A + 1])),
                'z_boundary_over_rim': float(z[0, self.n_A] - z[0, -1])}

    # ---- initial guesses -----------------------------------------------------------------

    def from_curve(self, r_curve, z_curve):
        """x that samples a curve (r(t), z(t)) starting at the axis, split at the arc length that
        encloses the domain area."""
        dr, dz = np.diff(r_curve), np.diff(z_curve)
        ds = np.hypot(dr, dz)
        s = np.r_[0.0, np.cumsum(ds)]
        seg_angle = np.unwrap(np.arctan2(dz, dr))
        rm = 0.5 * (r_curve[:-1] + r_curve[1:])
        cum_area = np.r_[0.0, np.cumsum(TWO_PI * rm * ds)]
        s_d = np.interp(self.setup.domain_area, cum_area, s)
        s_mid = 0.5 * (s[:-1] + s[1:])
        L_A, L_B = s_d, s[-1] - s_d
        nodes = np.r_[L_A * np.r_[0.0, np.cumsum(self.d_A)], L_A + L_B * np.cumsum(self.d_B)]
        psi = np.interp(nodes, s_mid, seg_angle)
        return np.r_[psi[1:self.N], L_A, L_B]

    def bump_guess(self, bump_radius=0.5, sign=1.0):
        """The 7.3 initial shape on the disk: z = a1 (1 + cos(pi r / R0)) for r < R0, with a1 for the
        total area (sign = -1: the same bump downwards)."""
        R_p = self.setup.rim_radius
        r = np.linspace(0.0, R_p, 4001)
        z = sign * _bump_for_area(r, 0.0, bump_radius, self.setup.total_area)
        return self.from_curve(r, z)

    def bud_guess(self, r_d, matrix_sign=-1.0):
        """A bud: a spherical cap of area A_d with the boundary radius r_d (more than a half sphere) on a
        bump of the matrix up (matrix_sign = +1) or down (-1) from the neck; the kink at the neck is
        left to the minimization."""
        s = self.setup
        # 2 pi R^2 (1 - cos t) = A_d with R sin t = r_d, t in (pi/2, pi): bisection on t
        lo, hi = math.pi / 2, math.pi
        for _ in range(100):
            t = 0.5 * (lo + hi)
            R = r_d / math.sin(t)
            lo, hi = (t, hi) if TWO_PI * R * R * (1 - math.cos(t)) < s.domain_area else (lo, t)
        theta = np.linspace(0.0, t, 2000)
        r_cap, z_cap = R * np.sin(theta), R * np.cos(theta)
        r_mat = np.linspace(r_d, s.rim_radius, 4000)[1:]
        z_mat = z_cap[-1] + matrix_sign * _bump_for_area(r_mat, r_d, 0.5, s.matrix_area, start_height=True)
        return self.from_curve(np.r_[r_cap, r_mat], np.r_[z_cap, z_mat])


def _bump_for_area(r, r0, bump_radius, area, start_height=False):
    """z = a (1 + cos(pi (r - r0) / (R0 - r0))) on r0 <= r < R0 (0 outside), a >= 0 such that the
    surface of revolution over r has the given area (if reachable; else a = 0)."""
    def shape(a):
        x = np.clip((r - r0) / (bump_radius - r0), 0.0, 1.0)
        return np.where(r < bump_radius, a * (1.0 + np.cos(np.pi * x)), 0.0)

    def surface(a):
        z = shape(a)
        return np.sum(TWO_PI * 0.5 * (r[:-1] + r[1:]) * np.hypot(np.diff(r), np.diff(z)))

    lo, hi = 0.0, 2.0
    for _ in range(80):
        a = 0.5 * (lo + hi)
        lo, hi = (a, hi) if surface(a) < area else (lo, a)
    z = shape(a)
    return z - z[0] if start_height else z


# ---------------------------------------------------------------------------------------------
# Constrained minimization


def _solve(meridian, targets, x0, equalities, maxiter=20000):
    """Least bending + Gaussian energy under equality constraints on columns 1.. of
    Meridian.evaluate (trust-constr: SQP in a trust region, BFGS Hessians, exact gradients; SLSQP's
    unbounded first steps throw the meridian across the axis). Returns (energy, x, result)."""
    from scipy.optimize import BFGS, NonlinearConstraint, minimize

    cache = {}

    def evaluated(x):
        key = x.tobytes()
        if key not in cache:
            cache.clear()
            cache[key] = meridian.evaluate_with_jacobian(x)
        return cache[key]

    rows = slice(1, 1 + equalities)
    constraint = NonlinearConstraint(lambda x: evaluated(x)[0][rows] - targets, 0.0, 0.0,
                                     jac=lambda x: evaluated(x)[1][rows], hess=BFGS())
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter('ignore')
        result = minimize(lambda x: evaluated(x)[0][0], np.asarray(x0, float), jac=lambda x: evaluated(x)[1][0],
                          hess=BFGS(), method='trust-constr', constraints=[constraint],
                          options={'maxiter': maxiter, 'gtol': 1e-10, 'xtol': 1e-13})
    values = evaluated(result.x)[0]
    result.constraint_violation = float(np.max(np.abs(values[rows] - targets)))
    result.min_radius = float(np.min(values[1 + 4:]))  # the midpoint radii: the meridian must stay off the axis
    result.success = bool(result.status in (1, 2) and result.constraint_violation < 1e-9 and result.min_radius > 0)
    return float(values[0]), result.x, result


def newton(meridian, targets, x0, mu0=None, equalities=4, tol=1e-10, maxiter=200, max_step=0.25):
    """Newton's method on the KKT conditions of min (bending + Gaussian) subject to the first
    `equalities` constraints of Meridian.evaluate equal to `targets`, with the exact Hessian of the
    Lagrangian. Where the Hessian, restricted to the constraints' tangent space, is not positive
    definite it is shifted (so each step descends), and steps are limited to max_step in every
    unknown. Returns (energy, x, info) with info['stable']: the restricted Hessian is positive
    definite at the solution (a local minimum, not a saddle)."""
    x = np.asarray(x0, float).copy()
    rows = slice(1, 1 + equalities)
    mu_full = np.zeros(4)
    values, J = meridian.evaluate_with_jacobian(x)
    if mu0 is None:
        mu_full[:equalities] = np.linalg.lstsq(J[rows].T, J[0], rcond=None)[0]
    else:
        mu_full[:equalities] = mu0
    info = {'converged': False, 'stable': False, 'iterations': 0}
    for iteration in range(maxiter):
        values, J = meridian.evaluate_with_jacobian(x)
        Jc = J[rows]
        residual_c = values[rows] - targets
        gradient = J[0] - Jc.T @ mu_full[:equalities]
        W = meridian.lagrangian_hessian(x, mu_full)
        # Tangent space of the constraints: the last n - m right singular vectors of Jc.
        Z = np.linalg.svd(Jc)[2][equalities:].T
        reduced = Z.T @ W @ Z
        lowest = float(np.linalg.eigvalsh(reduced)[0])
        scale = max(1.0, float(np.max(np.abs(np.diag(W)))))
        converged = np.max(np.abs(Z.T @ gradient)) < tol * scale and np.max(np.abs(residual_c)) < tol
        info.update(iterations=iteration, lowest_curvature=lowest, gradient=float(np.max(np.abs(Z.T @ gradient))),
                    constraint_violation=float(np.max(np.abs(residual_c))))
        if converged:
            info['converged'] = True
            info['stable'] = lowest > 0.0
            break
        if lowest <= 1e-8 * scale:
            W = W + (1e-3 * scale - lowest) * (Z @ Z.T)
        n = x.size
        K = np.zeros((n + equalities, n + equalities))
        K[:n, :n] = W
        K[:n, n:] = Jc.T
        K[n:, :n] = Jc
        solution = np.linalg.solve(K, -np.r_[gradient, residual_c])
        dx, nu = solution[:n], solution[n:]
        factor = min(1.0, max_step / max(1e-300, float(np.max(np.abs(dx)))))
        x = x + factor * dx
        mu_full[:equalities] -= factor * nu
    energy = float(meridian.evaluate(x)[0, 0])
    info['mu'] = mu_full[:equalities].tolist()
    return energy, x, info


def minimize_at_radius(meridian, r_d, x0, mu0=None):
    """B(r_d): the least bending + Gaussian energy with the domain boundary at radius r_d, the areas
    of both phases and the rim radius held (Newton on the KKT conditions, a trust-region SQP first
    when Newton does not converge to a minimum from x0). Returns (B, x, info); info['mu'][3] is
    dB/dr_d (the multiplier of the radius constraint)."""
    s = meridian.setup
    targets = np.array([s.domain_area, s.matrix_area, s.rim_radius, r_d])
    B, x, info = newton(meridian, targets, x0, mu0)
    if not (info['converged'] and info['stable']):
        _, x_sqp, _ = _solve(meridian, targets, x0, 4, maxiter=3000)
        B, x, info = newton(meridian, targets, x_sqp)
        info['sqp_start'] = True
    info['min_radius'] = float(np.min(meridian.evaluate(x)[0, 5:]))
    return B, x, info


def matrix_without_domain(setup, n=160, grading=1.0, x0=None):
    """The matrix of a complete bud: phase B of area A_tot - A_d spanning the disk, smooth through
    the ideal neck at r = 0 (a cone there would cost infinite bending energy). Returns its least
    bending energy (Gaussian: 0, the neck's part is in complete_bud_energy)."""
    matrix = Setup(kappa_A=setup.kappa_B, kappa_B=setup.kappa_B, H0_A=setup.H0_B, H0_B=setup.H0_B,
                   kappa_G_A=setup.kappa_G_B, kappa_G_B=setup.kappa_G_B, xi=setup.xi,
                   total_area=setup.matrix_area, domain_area=setup.matrix_area / 2, projected_area=setup.projected_area)
    meridian = Meridian(matrix, n // 2, n - n // 2, grading=grading)
    if x0 is None:
        x0 = meridian.bump_guess()
    # The "domain" here is only a split of phase B; its boundary radius is left free.
    targets = np.array([matrix.domain_area, matrix.matrix_area, matrix.rim_radius])
    _, x, _ = _solve(meridian, targets, x0, 3, maxiter=3000)
    energy, x, info = newton(meridian, targets, x, equalities=3)
    return energy, info


def complete_bud_energy(setup, matrix_energy):
    """r_d -> 0: a sphere of area A_d on the +z side (bending 2 pi kappa_A (2 + H0_A R)^2), the matrix,
    no line energy (zero neck radius) and the Gaussian jump 2 pi (kappa_G,A - kappa_G,B)(1 - cos psi_d)
    with the boundary anywhere along the ideal neck (psi_d from -pi, the bud's side, to 0, the
    matrix's side) at no bending cost: its least value min(0, 4 pi (kappa_G,A - kappa_G,B)) (0 in 7.3)."""
    R = setup.bud_radius
    return (sphere_bending_energy(setup.kappa_A, setup.H0_A, R)
            + min(0.0, 4.0 * math.pi * (setup.kappa_G_A - setup.kappa_G_B)) + matrix_energy)


def scan(setup, radii, n_A=80, n_B=80, grading=1.6, log=None, x0=None):
    """B(r_d) by continuation over the given radii (in the given order), from x0 or the 7.3 bump.

    Each row: r_d, B, dB/dr_d (the radius constraint's multiplier), whether the state is a local
    minimum at that radius ('stable'), the parts of the energy and the shape's heights."""
    meridian = Meridian(setup, n_A, n_B, grading)
    x = meridian.bump_guess() if x0 is None else x0
    mu = None
    rows = []
    for r_d in radii:
        B, x_new, info = minimize_at_radius(meridian, r_d, x, mu)
        parts = meridian.energy_parts(x_new)
        ok = info['converged'] and info['stable'] and info['min_radius'] > 0
        row = {'r_d': float(r_d), 'B': B, 'dB_dr': info['mu'][3], 'success': bool(ok), 'stable': bool(info['stable']),
               'iterations': info['iterations'], 'constraint_violation': info['constraint_violation'], **parts}
        rows.append(row)
        if log:
            log(f"r_d = {r_d:.5f}  B = {B:.6f}  dB/dr = {info['mu'][3]:+.4f}  psi_d = {parts['psi_d']:+.4f}  "
                f"apex height {parts['z_apex_over_rim']:.4f}  ({info['iterations']} Newton steps"
                f"{' after SQP' if info.get('sqp_start') else ''}, {'ok' if ok else 'NOT CONVERGED/STABLE'})")
        if ok:
            x, mu = x_new, info['mu']
    return rows, x


# ---------------------------------------------------------------------------------------------
# Branches in sigma


def sheet_minima(radii, B, line_tension, points=20001):
    """Local minima over r_d of E = B(r_d) + 2 pi lambda r_d (B interpolated monotonically between
    the radii, ascending; the ends count when E rises away from them). Returns [(r_d, E), ...]."""
    from scipy.interpolate import PchipInterpolator

    fine = np.linspace(radii[0], radii[-1], points)
    E = PchipInterpolator(radii, B)(fine) + TWO_PI * line_tension * fine
    index = list(np.flatnonzero((E[1:-1] < E[:-2]) & (E[1:-1] <= E[2:])) + 1)
    if E[0] < E[1]:
        index.insert(0, 0)
    if E[-1] < E[-2]:
        index.append(len(E) - 1)
    return [(float(fine[i]), float(E[i])) for i in index]


def stationary_sigma(setup, dB_dr):
    """The sigma at which a state of the reduced problem is an equilibrium: dE/dr_d = dB/dr_d +
    2 pi c sigma xi = 0."""
    return -np.asarray(dB_dr, float) / (TWO_PI * line_tension_constant() * setup.xi)


def crossing_of(x, y, level):
    """First x where y (sampled at increasing x) passes level, by linear interpolation (or None)."""
    y = np.asarray(y, float) - level
    for i in range(len(y) - 1):
        if y[i] == 0.0:
            return float(x[i])
        if y[i] * y[i + 1] < 0.0:
            return float(x[i] + (x[i + 1] - x[i]) * y[i] / (y[i] - y[i + 1]))
    return None


def default_radii(setup, count=100):
    """Domain-boundary radii, from near the flat disk down to small necks (denser at small r_d)."""
    top = 0.98 * setup.flat_domain_radius
    t = np.linspace(0.0, 1.0, count)
    return top * (0.02 + 0.98 * (1.0 - (1.0 - t) ** 2))[::-1]


def compute(setup, n_A=80, n_B=80, grading=1.6, count=100, sigmas=None, report_sigmas=(540, 630, 692, 1000), log=None):
    """B(r_d) on both sheets, the complete bud, and the equilibria for each sigma (see the module's doc)."""
    if setup.matrix_area < setup.projected_area:
        raise ValueError("phase B must at least cover the projected patch (else no complete bud fits)")
    say = log or (lambda text: None)
    radii = default_radii(setup, count)
    # Sheet 1 ("bump"): the domain on top of the 7.3 bump, followed from the bump's cap down to small necks.
    say('sheet 1: from the 7.3 bump, r_d decreasing')
    cap_rows, _ = scan(setup, radii, n_A, n_B, grading, log=say)
    # Sheet 2 ("dimple"): a bud whose matrix bulges the other way (a bud on a dimple), followed from a
    # small neck up until it falls onto sheet 1 (the domain boundary rises above the rim).
    say('sheet 2: a bud on a dimple, r_d increasing')
    meridian = Meridian(setup, n_A, n_B, grading)
    dimple_rows, _ = scan(setup, radii[::-1], n_A, n_B, grading, log=say, x0=meridian.bud_guess(radii[-1], -1.0))
    end = next((i for i, row in enumerate(dimple_rows) if row['z_boundary_over_rim'] > 0.0 or not row['success']),
               len(dimple_rows))
    dimple_rows = dimple_rows[:end]
    matrix_energy, _ = matrix_without_domain(setup, n=n_A + n_B)
    E0 = complete_bud_energy(setup, matrix_energy)
    say(f"complete bud: B(0) = {E0:.6f} (matrix {matrix_energy:.6f})")

    def arrays(rows):
        rows = sorted([row for row in rows if row['success']], key=lambda row: row['r_d'])
        return rows, np.r_[0.0, [row['r_d'] for row in rows]], np.r_[E0, [row['B'] for row in rows]]

    cap_rows, r1, B1 = arrays(cap_rows)
    dimple_rows, r2, B2 = arrays(dimple_rows)
    sigma_1 = stationary_sigma(setup, [row['dB_dr'] for row in cap_rows])
    sigma_2 = stationary_sigma(setup, [row['dB_dr'] for row in dimple_rows])
    psi_1 = np.array([row['psi_d'] for row in cap_rows])
    neck_1 = np.array([row['neck_ratio'] for row in cap_rows])

    def state(sigma):
        lam = setup.line_tension(sigma)
        first = min(sheet_minima(r1, B1, lam), key=lambda m: m[1])
        # on sheet 2 only its own minima count, not the end where the sheet was left (its largest r_d)
        second = [m for m in sheet_minima(r2, B2, lam) if m[0] < r2[-1]]
        second = min(second, key=lambda m: m[1]) if second else None
        r = first[0]
        row = {'sigma': float(sigma), 'line_tension_lambda': lam,
               'bump': {'energy': first[1], 'r_d': r,
                        'psi_d': -math.pi if r == 0.0 else float(np.interp(r, r1[1:], psi_1)),
                        'neck_ratio': 0.0 if r == 0.0 else float(np.interp(r, r1[1:], neck_1))},
               'dimple_bud': None if second is None else {'energy': second[1], 'r_d': second[0]}}
        b = row['bump']
        # the simulator's classes (docs/experiments.md): a neck ratio below 0.4 is a complete bud
        b['shape'] = ('complete bud (zero neck)' if r == 0.0 else 'complete bud (neck ratio < 0.4)'
                      if b['neck_ratio'] < 0.4 else 'incomplete bud (waist)' if b['neck_ratio'] < 0.999
                      else 'cap (no waist)')
        return row

    sigmas = np.arange(300.0, 1500.0 + 0.5, 1.0) if sigmas is None else np.asarray(sigmas, float)
    table = [state(sigma) for sigma in sigmas]
    # Sheet 1: the sigma of each equilibrium; its steepest point (d sigma / d r_d closest to zero, where
    # the domain boundary moves fastest with sigma) is the midpoint of the cap-to-bud transition.
    order = np.argsort(r1[1:])
    slope = np.gradient(sigma_1[order], r1[1:][order])
    window = (r1[1:][order] > 0.05) & (r1[1:][order] < 0.2)
    steepest = int(np.flatnonzero(window)[np.argmax(slope[window])])
    monotonic = bool(np.all(slope < 0.0))
    # Where both sheets have a minimum that is not the same complete bud (r_d = 0 on both): does the bud on
    # a dimple ever lie below the state of sheet 1?
    diffs = [(row['sigma'], row['dimple_bud']['energy'] - row['bump']['energy']) for row in table
             if row['dimple_bud'] and row['bump']['r_d'] > 0.0]
    crossing = crossing_of([d[0] for d in diffs], [d[1] for d in diffs], 0.0) if diffs else None
    summary = {
        'sheet1_single_valued': monotonic,
        'sheet1_transition_midpoint_sigma': float(sigma_1[order][steepest]),
        'sheet1_transition_midpoint_r_d': float(r1[1:][order][steepest]),
        'sheet1_waist_forms_sigma': crossing_of(sigma_1[::-1], neck_1[::-1], 0.999),
        'sheet1_boundary_vertical_sigma': crossing_of(sigma_1[::-1], psi_1[::-1], -math.pi / 2),
        'sheet1_neck_ratio_0.4_sigma': crossing_of(sigma_1[::-1], neck_1[::-1], 0.4),
        'sheet1_complete_bud_sigma_secant': float(stationary_sigma(setup, (B1[1] - B1[0]) / r1[1])),
        'sheet1_smallest_r_d': float(r1[1]), 'sheet1_sigma_at_smallest_r_d': float(sigma_1[0]),
        'dimple_bud_turning_point_sigma': float(np.min(sigma_2)) if len(sigma_2) else None,
        'dimple_bud_turning_point_r_d': float(r2[1:][np.argmin(sigma_2)]) if len(sigma_2) else None,
        'dimple_bud_minus_bump_crossing_sigma': crossing,
        'dimple_bud_minus_bump_min_difference': float(min(d[1] for d in diffs)) if diffs else None,
    }
    at = {str(sigma): state(sigma) for sigma in report_sigmas}
    keep = ('r_d', 'B', 'dB_dr', 'psi_d', 'neck_ratio', 'bending_A', 'bending_B', 'gaussian', 'z_apex_over_rim',
            'z_boundary_over_rim', 'iterations', 'constraint_violation')
    return {'setup': setup.as_dict(), 'line_tension_constant_c': line_tension_constant(),
            'line_tension_per_sigma': setup.line_tension(1.0),
            'rim_radius': setup.rim_radius, 'bud_radius': setup.bud_radius, 'flat_domain_radius': setup.flat_domain_radius,
            'discretization': {'segments_per_phase': n_A, 'grading': grading, 'radii': count},
            'complete_bud': {'energy': E0, 'matrix_bending': matrix_energy,
                             'sphere_bending': sphere_bending_energy(setup.kappa_A, setup.H0_A, setup.bud_radius)},
            'summary': summary, 'at_sigma': at,
            'sheet1_bump': [{**{k: row[k] for k in keep}, 'sigma_stationary': float(sg)}
                            for row, sg in zip(cap_rows, sigma_1)],
            'sheet2_dimple': [{**{k: row[k] for k in keep}, 'sigma_stationary': float(sg)}
                              for row, sg in zip(dimple_rows, sigma_2)],
            'by_sigma': [row for row in table if row['sigma'] % 10 == 0]}


def main(argv=None):
    parser = argparse.ArgumentParser(prog='python3 -m membrane_flow.sharp_interface', description=__doc__.split('\n\n')[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('prm', nargs='?', default=None,
                        help='experiment file (default: experiments/7.3-budding.prm of this repository)')
    parser.add_argument('--domain-area', type=float, help='area of phase A (default: (Bump area + Mass) / 2)')
    parser.add_argument('--segments', type=int, default=80, help='segments of the meridian per phase (default 80)')
    parser.add_argument('--grading', type=float, default=1.6, help='node grading towards the domain boundary (1.6)')
    parser.add_argument('--radii', type=int, default=100, help='domain-boundary radii per sheet (default 100)')
    parser.add_argument('--json', help='write the results here')
    parser.add_argument('--quiet', action='store_true', help='no progress on stderr')
    args = parser.parse_args(argv)
    prm = args.prm or os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'experiments',
                                   '7.3-budding.prm')
    setup = setup_from_prm(prm)
    if args.domain_area is not None:
        setup = Setup(**{**setup.as_dict(), 'domain_area': args.domain_area})
    log = None if args.quiet else (lambda text: print(text, file=sys.stderr, flush=True))
    results = compute(setup, n_A=args.segments, n_B=args.segments, grading=args.grading, count=args.radii, log=log)
    results['prm'] = os.path.relpath(os.path.abspath(prm))
    results['command'] = 'python3 -m membrane_flow.sharp_interface ' + ' '.join(argv if argv is not None else sys.argv[1:])
    summary = results['summary']
    print(f"lambda = c sigma xi with c = {results['line_tension_constant_c']:.12f}, xi = {setup.xi}: "
          f"lambda = {results['line_tension_per_sigma']:.6g} sigma")
    print(f"areas: domain {setup.domain_area:.6g}, total {setup.total_area:.6g}, projected 1 (disk radius "
          f"{setup.rim_radius:.6f}); complete bud energy {results['complete_bud']['energy']:.6f}")
    for key, value in summary.items():
        print(f"{key}: {value}")
    for sigma, row in results['at_sigma'].items():
        b, d = row['bump'], row['dimple_bud']
        print(f"sigma = {sigma}: sheet 1 {b['shape']}, E = {b['energy']:.4f}, r_d = {b['r_d']:.4f}, psi_d = {b['psi_d']:.3f}, "
              f"neck ratio {b['neck_ratio']:.3f}; bud on a dimple: "
              + ('none' if d is None else f"E = {d['energy']:.4f}, r_d = {d['r_d']:.4f}"))
    if args.json:
        with open(args.json, 'w') as stream:
            json.dump(results, stream, indent=1)
            stream.write('\n')
    return 0


if __name__ == '__main__':
    sys.exit(main())
