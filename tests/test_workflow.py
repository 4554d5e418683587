#!/usr/bin/python3
"""Tests of the science workflow (membrane_flow.workflow): the budding-time definition
on synthetic statistics with a known answer, bisection on a cheap outcome function, and
the resume semantics of a sweep that is killed and started again.
Usage: test_workflow.py [membrane-flow] [small.prm]   (the sweep test needs both)"""
import csv
import json
import math
import os
import signal
import subprocess
import sys
import tempfile
import time
import unittest

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
from membrane_flow.workflow.budding_time import budding_time  # noqa: E402 (PYTHONPATH: the build's python/)
from membrane_flow.workflow.critical import bisect  # noqa: E402
from membrane_flow.workflow.threshold_time import brackets, first_crossing  # noqa: E402

EXE = sys.argv[1] if len(sys.argv) > 1 else None
SMALL = sys.argv[2] if len(sys.argv) > 2 else None


class BuddingTime(unittest.TestCase):
    def test_exponential_relaxation(self):
        # F = 10 + 5 exp(-t/0.3): the relative rate (50/3) e / (10 + 5 e), e = exp(-t/0.3),
        # reaches 1e-3 at e = 0.01 / (50/3 - 0.005), t = 0.3 ln(1666.17) = 2.2259.
        t = np.linspace(0, 5, 5001)
        expected = -0.3 * math.log(0.01 / (50 / 3 - 0.005))
        self.assertAlmostEqual(budding_time(t, 10 + 5 * np.exp(-t / 0.3), rate=1e-3, window=1e-3), expected, delta=2e-3)

    def test_two_stages(self):
        # Fast sorting (large drop) then slow budding (small drop): T_min is set by the slow
        # stage alone, (2/2) e^(-t/2) = 1e-3 (10 + 2 e^(-t/2)), t = 2 ln(100 - 0.2) = 9.2063.
        t = np.linspace(0, 20, 20001)
        F = 10 + 50 * np.exp(-t / 0.05) + 2 * np.exp(-t / 2.0)
        self.assertAlmostEqual(budding_time(t, F, rate=1e-3, window=1e-3), 2 * math.log(100 - 0.2), delta=2e-3)

    def test_complete_bud_is_the_protrusion_crossing(self):
        # The domain protrusion 0.5 + 0.6 (1 - exp(-t)) reaches 0.95 at t = ln 4.
        t = np.linspace(0, 5, 501)
        T = budding_time(t, 10 + np.exp(-t), protrusion=0.5 + 0.6 * (1 - np.exp(-t)))
        self.assertAlmostEqual(T, math.log(4), delta=1e-4)

    def test_pinch_off_is_the_stop_time(self):
        t = np.linspace(0, 0.7, 50)
        stop = 'pinch-off approach: neck radius 0.02 < 0.03'
        self.assertEqual(budding_time(t, 5 - t, stop), 0.7)
        # ... unless the domain became a complete bud earlier: then its protrusion crossing counts.
        self.assertAlmostEqual(budding_time(t, 5 - t, stop, protrusion=t / 0.5), 0.475, delta=1e-12)

    def test_window_averages_noise(self):
        # A plateau with alternating single-step jitter of 1e-4: the window sees the plateau.
        t = np.linspace(0, 3, 3001)
        F = 10 + 5 * np.exp(-t / 0.1) + 1e-4 * (-1) ** np.arange(len(t))
        self.assertIsNone(budding_time(t, F, rate=1e-2, window=1e-3))
        self.assertLess(budding_time(t, F, rate=1e-2, window=0.1), 1.0)

    def test_no_plateau_gives_none(self):
        t = np.linspace(0, 1, 100)
        self.assertIsNone(budding_time(t, 10 - t))


class Bisection(unittest.TestCase):
    def test_finds_threshold(self):
        threshold = 0.3712
        result = bisect(lambda x: 'complete' if x > threshold else 'incomplete', 0.0, 1.0, 1e-3)
        low, high = result['bracket']
        self.assertTrue(low <= threshold < high)
        self.assertLessEqual(high - low, 1e-3)
        self.assertEqual(len(result['runs']), 2 + math.ceil(math.log2(1.0 / 1e-3)))
        self.assertEqual(result['outcomes'], ['incomplete', 'complete'])

    def test_geometric(self):
        result = bisect(lambda x: x > 777.0, 100.0, 10000.0, 0.01, geometric=True)
        low, high = result['bracket']
        self.assertTrue(low <= 777.0 < high)
        self.assertLessEqual(math.log(high / low), 0.01)

    def test_no_change_is_an_error(self):
        with self.assertRaisesRegex(ValueError, 'no change of outcome'):
            bisect(lambda x: 'flat', 1.0, 2.0, 0.1)


class ThresholdAgainstEndTime(unittest.TestCase):
    def test_first_crossing_interpolates(self):
        t = np.array([0.0, 1.0, 2.0, 3.0])
        self.assertAlmostEqual(first_crossing(t, np.array([0.5, 0.8, 1.0, 1.1])), 1.75)
        self.assertEqual(first_crossing(t, np.array([0.5, 0.6, 0.7, 0.9])), math.inf)

    def test_brackets_of_a_known_law(self):
        # Crossing time T(sigma) = 100 / (sigma - 800): the threshold for end time T is
        # 800 + 100 / T, i.e. 840 (T = 2.5), 820 (5), 810 (10).
        sigmas = [805, 815, 825, 835, 845, 900]
        runs = [(s, 100.0 / (s - 800), 10.0) for s in sigmas]
        found = brackets(runs, (2.5, 5, 10))
        self.assertEqual(found[2.5], (835, 845, []))
        self.assertEqual(found[5], (815, 825, []))
        self.assertEqual(found[10], (805, 815, []))

    def test_a_run_that_stopped_early_is_undecided_later(self):
        runs = [(800, math.inf, 10.0), (850, math.inf, 4.0), (900, 3.0, 10.0)]
        found = brackets(runs, (2.5, 5))
        self.assertEqual(found[2.5], (900, None, []))  # none has crossed by 2.5
        self.assertEqual(found[5], (800, 900, [850]))


@unittest.skipIf(EXE is None, 'needs the membrane-flow executable and small.prm')
class SweepResume(unittest.TestCase):
    def test_killed_sweep_resumes_without_duplicates(self):
        with tempfile.TemporaryDirectory() as root:
            spec = {'base': os.path.abspath(SMALL), 'output': 'out',
                    'set': {'Time stepping/Maximum steps': 25, 'Time stepping/End time': 1,
                            'Output/Write VTU': 'false'},
                    'vary': {'Initial phase/Seed': {'range': [1, 4]}}}
            sweep_file = os.path.join(root, 'sweep.json')
            with open(sweep_file, 'w') as f:
                json.dump(spec, f)
            command = ['/usr/bin/python3', '-m', 'membrane_flow', 'sweep', sweep_file,
                       '--exe', os.path.abspath(EXE), '--workers', '1']
            cases = os.path.join(root, 'out', 'cases')

            def finished():
                if not os.path.isdir(cases):
                    return []
                return sorted(c for c in os.listdir(cases) if os.path.exists(os.path.join(cases, c, 'summary.json')))

            process = subprocess.Popen(command, start_new_session=True, stdout=subprocess.DEVNULL)
            deadline = time.time() + 120
            while len(finished()) < 1 and time.time() < deadline:
                time.sleep(0.05)
            time.sleep(0.3)  # let the next case start
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()
            done_before = finished()
            self.assertGreaterEqual(len(done_before), 1)
            self.assertLess(len(done_before), 4, 'the sweep finished before it could be killed')
            stamps = {c: os.path.getmtime(os.path.join(cases, c, 'summary.json')) for c in done_before}

            output = subprocess.run(command, check=True, capture_output=True, text=True).stdout
            self.assertIn(f'{len(done_before)} already finished', output)
            self.assertEqual(len(finished()), 4)
            for c, stamp in stamps.items():  # finished cases were not run again
                self.assertEqual(os.path.getmtime(os.path.join(cases, c, 'summary.json')), stamp)
            with open(os.path.join(root, 'out', 'results.csv')) as f:
                rows = list(csv.DictReader(f))
            self.assertEqual(sorted(r['case'] for r in rows), finished())
            self.assertEqual(sorted(int(r['Initial phase/Seed']) for r in rows), [1, 2, 3, 4])
            for r in rows:
                self.assertEqual(r['failed'], 'False')


if __name__ == '__main__':
    unittest.main(argv=sys.argv[:1], verbosity=2)
