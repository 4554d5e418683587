#!/usr/bin/python3
"""Continuation on a cheap bistable model with known thresholds.

E(x; p) = x^4/4 - x^2/2 + p x has two minima for |p| < 2/(3 sqrt 3) = 0.3849 (the
turning points, where one minimum merges with the maximum) whose depths are equal at
p = 0 (the crossing). Each relaxation is a gradient flow from the previous equilibrium
(as a resumed simulator run is); the class of a state is the sign of x. Asserts: the
branch x > 0 followed upwards from p = -0.6 ends between the two values around +0.3849,
the branch x < 0 followed downwards ends around -0.3849, both brackets no wider than the
step, and the energies cross at p = 0 to 1e-3.
Usage: test_continuation.py   (membrane_flow importable: PYTHONPATH=<build>/python)"""
import math
import unittest

from membrane_flow.workflow.continuation import crossing, follow_branch, turning_point

TURN = 2 / (3 * math.sqrt(3))


def energy(x, p):
    return x ** 4 / 4 - x ** 2 / 2 + p * x


def relax(p, x, rate=0.05, steps=20000):
    for _ in range(steps):  # explicit gradient flow to the plateau
        x -= rate * (x ** 3 - x + p)
    return {'state': x, 'energy': energy(x, p), 'class': 'right' if x > 0 else 'left'}


class Continuation(unittest.TestCase):
    def test_turning_points_and_crossing(self):
        step = 0.05
        up = [round(-0.6 + step * k, 10) for k in range(25)]      # -0.6 .. 0.6
        down = list(reversed(up))
        right = follow_branch(relax, up, 1.5)                      # starts in the right well
        left = follow_branch(relax, down, -1.5)
        self.assertEqual((right['class'], left['class']), ('right', 'left'))
        low, high = turning_point(right)
        self.assertTrue(low < TURN < high and high - low <= step + 1e-12, (low, high))
        high2, low2 = turning_point(left)
        self.assertTrue(low2 < -TURN < high2 and high2 - low2 <= step + 1e-12, (low2, high2))
        self.assertAlmostEqual(crossing(right, left), 0.0, delta=1e-3)
        # The branch that left keeps its last equilibrium; the state that ended it is in the other well.
        self.assertLess(right['left_at']['state'], 0)

    def test_no_crossing_where_only_one_branch_exists(self):
        right = follow_branch(relax, [-0.6, -0.5], 1.5)
        left = follow_branch(relax, [0.5, 0.6], -1.5)
        self.assertIsNone(crossing(right, left))
        self.assertIsNone(turning_point(right))


if __name__ == '__main__':
    unittest.main(verbosity=2)
