#!/usr/bin/python3
"""The cost of thermal noise per step (issue: the noise must cost less than 10 % of a step).

Runs the same fixed-tau steps of an input file at Temperature = 0 and at a small Temperature
(the noise is drawn and assembled, the trajectory barely changes) and compares the wall time
per step and the two assembly phases that draw the noise (Cahn-Hilliard and shape assembly),
from the run's timer table. Repeats each run and keeps the fastest, against machine noise.

Usage: thermal_noise_cost.py [--exe PATH] [--prm FILE] [--sizes 32,64] [--steps 40] [--repeats 3]
"""
import argparse
import subprocess
import tempfile
from pathlib import Path

from membrane_flow import launch  # the package on the path after ./scripts/setup.sh (docs/python.md)
from membrane_flow.run import read_timer_table

SECTIONS = ('Cahn-Hilliard assembly', 'shape assembly')


def timed_run(exe, prm, size, steps, temperature, directory):
    args = ['--overwrite', '--set', f'Mesh/Cells per side={size}', '--set', 'Time stepping/Adaptive=false',
            '--set', 'Time stepping/Time step=1e-5', '--set', f'Time stepping/Maximum steps={steps}',
            '--set', f'Material/Temperature={temperature}', '--set', 'Output/Write VTU=false',
            '--set', 'Output/Interval=0', '--set', 'Checkpoint/Interval=0', '--set', f'Output/Directory={directory}',
            prm]
    code, _ = launch.run([exe, *args], env=launch.environment(), stdout=subprocess.DEVNULL)
    if code != 0:
        raise SystemExit(f'membrane-flow failed (exit {code}) at {size} cells per side, Temperature = {temperature}')
    sections, total = read_timer_table(Path(directory, 'log.txt').read_text())
    parts = {name: sections.get(name, 0.0) for name in SECTIONS}
    return total / steps, {k: v / steps for k, v in parts.items()}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--exe', default=None)
    parser.add_argument('--prm', default='experiments/default.prm')
    parser.add_argument('--sizes', default='32,64')
    parser.add_argument('--steps', type=int, default=40)
    parser.add_argument('--repeats', type=int, default=3)
    options = parser.parse_args()
    exe = launch.find_executable(options.exe)
    print(f'{"cells/side":>10s} {"T":>6s} {"ms/step":>9s} {"CH asm":>8s} {"shape asm":>10s}')
    with tempfile.TemporaryDirectory() as scratch:
        for size in [int(s) for s in options.sizes.split(',')]:
            best = {}
            for temperature in (0, 1e-8):
                runs = [timed_run(exe, options.prm, size, options.steps, temperature, f'{scratch}/run')
                        for _ in range(options.repeats)]
                best[temperature] = min(runs, key=lambda r: r[0])
                step, parts = best[temperature]
                print(f'{size:10d} {temperature:6.0e} {1000 * step:9.2f} {1000 * parts[SECTIONS[0]]:8.2f} '
                      f'{1000 * parts[SECTIONS[1]]:10.2f}')
            extra = best[1e-8][0] - best[0][0]
            assembly = sum(best[1e-8][1].values()) - sum(best[0][1].values())
            print(f'{"":10s} noise: {1000 * extra:+.2f} ms/step ({100 * extra / best[0][0]:+.1f} % of a step); '
                  f'in the two assemblies {1000 * assembly:+.2f} ms ({100 * assembly / best[0][0]:+.1f} %)')


if __name__ == '__main__':
    main()
