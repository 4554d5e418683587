#!/usr/bin/python3
"""What the ALE mesh motion costs (issue 46, item 8), side by side in one run on one machine.

1. The deterministic 7.3 run (experiments/7.3-budding.prm, full length, VTU output off) with
   Shape/Mesh motion = lagrangian (the paper's scheme) and = ale: wall time, steps, ms per step.
   Target: ale <= 1.2 x lagrangian.
2. Fixed steps of experiments/default.prm (32 x 32, tau = 1e-4) with the ALE mesh at k_BT = 0 and at
   k_BT = kappa/20 = 0.075 (the noise drawn, split into its irrotational and solenoidal parts, and
   the lipids carried by the solenoidal part): ms per step. Target: T > 0 <= 1.1 x T = 0.

Each case is run --repeats times and the fastest kept, against the machine's noise. The per-phase
times come from each run's timer table (log.txt).

Usage: /usr/bin/python3 benchmarks/mesh_motion_cost.py [--exe build/membrane-flow] [--repeats 2] [--steps 40]
"""
import argparse
import json
import subprocess
import tempfile
from pathlib import Path

from membrane_flow import launch  # the package on the path after ./scripts/setup.sh (docs/python.md)
from membrane_flow.run import read_timer_table

PHASES = ('shape assembly', 'shape solve', 'Cahn-Hilliard assembly', 'Cahn-Hilliard solve', 'area projection',
          'mesh motion', 'grid control', 'geometry', 'statistics')
QUIET = ['Output/Write VTU=false', 'Output/Interval=0', 'Checkpoint/Interval=0']


def timed_run(exe, prm, sets, directory):
    """Wall time of the whole run, its accepted steps and the seconds per timer section."""
    args = ['--overwrite', *launch.settings(QUIET + sets + [f'Output/Directory={directory}']), prm]
    code, _ = launch.run([exe, *args], env=launch.environment(), stdout=subprocess.DEVNULL)
    if code != 0:
        raise SystemExit(f'membrane-flow failed (exit {code}) on {prm} with {sets}')
    sections, total = read_timer_table(Path(directory, 'log.txt').read_text())
    parts = {name: sections.get(name, 0.0) for name in PHASES}
    summary = json.loads(Path(directory, 'summary.json').read_text())
    return {'wall': total, 'steps': summary['steps'], 'rejected': summary['rejected_steps'],
            'energy': summary['energy'], 'parts': parts}


def fastest(exe, prm, sets, repeats, directory):
    return min((timed_run(exe, prm, sets, directory) for _ in range(repeats)), key=lambda r: r['wall'])


def report(label, run):
    per_step = 1000 * run['wall'] / run['steps']
    phases = ', '.join(f'{k} {1000 * v / run["steps"]:.1f}' for k, v in run['parts'].items() if v > 0)
    print(f'  {label:28s} {run["wall"]:7.2f} s  {run["steps"]:4d} steps ({run["rejected"]} rejected)  '
          f'{per_step:7.1f} ms/step  E = {run["energy"]:.6g}')
    print(f'  {"":28s} ms/step by phase: {phases}')
    return per_step


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--exe', default=None)
    parser.add_argument('--repeats', type=int, default=2)
    parser.add_argument('--steps', type=int, default=40)
    options = parser.parse_args()
    exe = launch.find_executable(options.exe)
    with tempfile.TemporaryDirectory() as scratch:
        print('1. experiments/7.3-budding.prm, deterministic, full length')
        runs = {motion: fastest(exe, 'experiments/7.3-budding.prm', [f'Shape/Mesh motion={motion}'],
                                options.repeats, f'{scratch}/run') for motion in ('lagrangian', 'ale')}
        for motion, run in runs.items():
            report(f'Mesh motion = {motion}', run)
        ratio = runs['ale']['wall'] / runs['lagrangian']['wall']
        print(f'  wall time ale / lagrangian: {ratio:.3f} (target <= 1.2)')

        print(f'2. experiments/default.prm, 32 x 32, Mesh motion = ale, {options.steps} steps of tau = 1e-4')
        fixed = ['Shape/Mesh motion=ale', 'Time stepping/Adaptive=false', 'Time stepping/Time step=1e-4',
                 f'Time stepping/Maximum steps={options.steps}', 'Shape/Pressure stabilization=0.01',
                 'Shape/Area projections=3']
        steps = {t: fastest(exe, 'experiments/default.prm', fixed + [f'Material/Temperature={t}'],
                            options.repeats, f'{scratch}/run') for t in ('0', '0.075')}
        per_step = {t: report(f'k_BT = {t}', run) for t, run in steps.items()}
        print(f'  step at k_BT = kappa/20 / step at k_BT = 0: {per_step["0.075"] / per_step["0"]:.3f} '
              f'(target <= 1.1)')


if __name__ == '__main__':
    main()
