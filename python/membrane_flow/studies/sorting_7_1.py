"""Why the 7.1 patch experiment ends as an incomplete bud (docs/experiments.md): the paper's input
(experiments/7.1-sorting-patch.prm) with one change each - time, resolution, line tension,
spontaneous curvature, and the amplitude of the patch, which the paper does not give.

Usage (from the repository's top directory):
  python3 -m membrane_flow study-7.1 [--exe build/membrane-flow] [--output results/studies/7.1-variants]

Each variant runs into <output>/<name> unless its summary.json is there already (so the study
resumes after a kill); then the table of docs/experiments.md is printed. Every run is written
without VTU output, one at a time, with OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1."""
import argparse
import os
import sys

from .. import launch
from ..run import load_statistics, load_summary

BASE = os.path.join('experiments', '7.1-sorting-patch.prm')
# name, what changes, --set entries
VARIANTS = [
    ('paper', 'the paper\'s parameters (amplitude 0.1, sigma = 450, t = 3)', []),
    ('t10', 'run to t = 10', ['Time stepping/End time=10']),
    ('level1', 'one level of local refinement', ['Mesh/Maximum refinement level=1']),
    ('sigma900', 'sigma = 900', ['Material/Line tension=900']),
    ('sigma1500', 'sigma = 1500', ['Material/Line tension=1500']),
    ('H0B0', 'H0_B = 0 (phase A keeps H0 = -10)', ['Material/Spontaneous curvature/Phase B value=0']),
    ('H0zero', 'H0_A = H0_B = 0', ['Material/Spontaneous curvature/Phase A value=0',
                                   'Material/Spontaneous curvature/Phase B value=0']),
    ('amplitude0.15', 'patch amplitude 0.15', ['Initial shape/Cosine modes=0.15 1 0; 0.15 0 1']),
    ('amplitude0.2', 'patch amplitude 0.2', ['Initial shape/Cosine modes=0.2 1 0; 0.2 0 1']),
    ('amplitude0.25', 'patch amplitude 0.25', ['Initial shape/Cosine modes=0.25 1 0; 0.25 0 1']),
    ('amplitude0.2-t10', 'patch amplitude 0.2, run to t = 10', ['Initial shape/Cosine modes=0.2 1 0; 0.2 0 1',
                                                              'Time stepping/End time=10']),
]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--exe', help='the program (default: see membrane_flow.launch.find_executable)')
    parser.add_argument('--output', default='results/studies/7.1-variants')
    args = parser.parse_args(argv)
    args.exe = launch.find_executable(args.exe)
    env = launch.environment()
    rows = []
    for name, change, sets in VARIANTS:
        run = os.path.join(args.output, name)
        if not os.path.exists(os.path.join(run, 'summary.json')):
            command = [args.exe, '--quiet', '--overwrite', BASE,
                       *launch.settings([f'Output/Directory={run}', 'Output/Write VTU=false', 'Checkpoint/Interval=0',
                                         *sets])]
            print(f'running {name}', flush=True)
            if launch.run(command, env=env)[0] != 0:
                print(f'{name}: the run failed (see {run}/log)')
                continue
        s = load_summary(run)
        first = load_statistics(run)
        area = s['area']
        rows.append(f"| {change} | {area:.3f} | {area - s['domain_area']:.3f} | {s['time']:g} | {s['energy']:.2f} | "
                    f"{s['domain_protrusion']:.2f} | {s['neck_ratio']:.2f} | {s['outcome']} | "
                    f"{first['energy'][0]:.2f} |")
    print('| variant | area | area of phase B | t end | energy | protrusion | neck ratio | outcome | initial energy |')
    print('|---|---|---|---|---|---|---|---|---|')
    print('\n'.join(rows))
    return 0


if __name__ == '__main__':
    sys.exit(main())
