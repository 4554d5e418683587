#!/usr/bin/python3
"""Cost per step of the 7.3 setup from 32 x 32 to 256 x 256 cells, on 1 and 2 MPI ranks.

Runs a few accepted steps of experiments/7.3-budding.prm on uniform meshes (VTU output and
checkpoints off) for every combination of --sizes, --ranks and --solvers, and reports per
case: wall time per accepted step (setup and initial state excluded), time and peak memory
per unknown (9 per vertex: 7 of the shape system, 2 of Cahn-Hilliard; 7 with Shape/Curvature mass =
lumped, whose shape system has 5), the split by phase
from the run's own timer table (the slowest rank's time), the Krylov iterations per solve,
and the growth of the time per step against the vertex count (exponent of N between
neighbouring sizes). Writes <output>/scaling.json and <output>/scaling.md.

A case that would not fit in the memory (the simulator refuses it at start-up) or that
fails is listed with its reason; the others go on.

Solvers (--solvers): direct (MUMPS LU), gmres (block-Jacobi ILU), block (the shape system by FGMRES with
the block preconditioner of include/membrane/shape_preconditioner.h; its iterations per solve are
the shape system's, from summary.json), lumped (direct with the lumped
curvature mass), lowrank (lumped with Linear solver/Low-rank tolerance = 1e-8), lowrank-ooc (that with
Out of core = true; the factors go to the case's directory), lumped-reuse and lowrank-reuse (those with
Linear solver/Reuse iterations = 20: the LU factors of an earlier step precondition GMRES, a new
factorization only when GMRES would need more than 20 iterations).

Usage: scaling.py <membrane-flow> [--sizes 32,64,128,256] [--ranks 1,2] [--solvers direct,gmres,lumped]
                  [--steps 8] [--output results/benchmarks/scaling]
Example: benchmarks/scaling.py build/membrane-flow --sizes 32,64,128 --ranks 1
"""
import argparse
import glob
import json
import math
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, 'python'))
from membrane_flow.run import read_timer_table  # noqa: E402

PHASES = {
    'assembly': ['Cahn-Hilliard assembly', 'shape assembly'],
    'solves': ['Cahn-Hilliard solve', 'shape solve'],
    'grid control': ['grid control'],
    'geometry': ['geometry'],
    'statistics': ['statistics'],
}
SETUP = ['setup', 'initial state']


# The linear-solver variants: entries of the input file (Linear solver/..., Shape/Curvature mass).
SOLVERS = {
    'direct': {'Type': 'direct', 'Curvature mass': 'consistent'},
    'gmres': {'Type': 'gmres', 'Curvature mass': 'consistent'},
    'block': {'Type': 'block', 'Curvature mass': 'consistent'},
    'lumped': {'Type': 'direct', 'Curvature mass': 'lumped'},
    'lowrank': {'Type': 'direct', 'Curvature mass': 'lumped', 'Low-rank tolerance': '1e-8'},
    'lowrank-ooc': {'Type': 'direct', 'Curvature mass': 'lumped', 'Low-rank tolerance': '1e-8', 'Out of core': 'true'},
    'lumped-reuse': {'Type': 'direct', 'Curvature mass': 'lumped', 'Reuse iterations': '20'},
    'lowrank-reuse': {'Type': 'direct', 'Curvature mass': 'lumped', 'Low-rank tolerance': '1e-8',
                      'Reuse iterations': '20'},
}


def run_case(exe, n, ranks, solver, steps, directory):
    shutil.rmtree(directory, ignore_errors=True)
    os.makedirs(directory)
    variant = SOLVERS[solver]
    lumped = variant['Curvature mass'] == 'lumped'
    args = [exe, '--overwrite', '--set', f'Mesh/Cells per side={n}', '--set', 'Mesh/Maximum refinement level=0',
            '--set', f"Shape/Curvature mass={variant['Curvature mass']}"]
    for entry in ('Type', 'Low-rank tolerance', 'Out of core', 'Reuse iterations'):
        if entry in variant:
            args += ['--set', f'Linear solver/{entry}={variant[entry]}']
    args += ['--set', f'Time stepping/Maximum steps={steps}',
             '--set', 'Time stepping/End time=10', '--set', 'Output/Write VTU=false', '--set', 'Checkpoint/Interval=0',
             '--set', f'Output/Directory={directory}/run', os.path.join(ROOT, 'experiments', '7.3-budding.prm')]
    # Peak resident memory of every rank: GNU time around each process.
    rss = os.path.join(directory, 'rss')
    timed = ['sh', '-c', '/usr/bin/time -f %M -o "$0.${OMPI_COMM_WORLD_RANK:-0}" "$@"', rss] + args
    env = dict(os.environ, OMP_NUM_THREADS='1', OPENBLAS_NUM_THREADS='1', OMPI_ALLOW_RUN_AS_ROOT='1',
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM='1', MUMPS_OOC_TMPDIR=directory)
    command = (['mpirun', '--oversubscribe', '-np', str(ranks)] + timed) if ranks > 1 else timed
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
    case = {'cells_per_side': n, 'ranks': ranks, 'solver': solver, 'vertices': (n + 1) ** 2,
            'unknowns': (7 if lumped else 9) * (n + 1) ** 2}
    if result.returncode != 0:
        errors = [line for line in result.stdout.splitlines() if line.startswith('Error')]
        case['failed'] = errors[-1] if errors else f'exit code {result.returncode}'
        return case
    sections, total = read_timer_table(result.stdout)
    with open(os.path.join(directory, 'run', 'summary.json')) as f:
        summary = json.load(f)
    accepted = summary['steps']
    stepping = total - sum(sections.get(k, 0) for k in SETUP)
    case.update({
        'steps': accepted, 'rejected': summary['rejected_steps'], 'wall_seconds': total,
        'ms_per_step': 1000 * stepping / accepted,
        'phases_ms_per_step': {p: 1000 * sum(sections.get(k, 0) for k in keys) / accepted for p, keys in PHASES.items()},
        'peak_memory_bytes': sum(int(open(f).read().split()[-1]) * 1024 for f in glob.glob(rss + '.*')),
    })
    case['factorizations_per_step'] = summary.get('shape_factorizations', math.nan) / accepted
    case['us_per_unknown_step'] = 1e6 * stepping / accepted / case['unknowns']
    case['bytes_per_unknown'] = case['peak_memory_bytes'] / case['unknowns']
    with open(os.path.join(directory, 'run', 'statistics.txt')) as f:
        names = f.readline().split()[1:]
        rows = [line.split() for line in f if line.strip() and not line.startswith('#')]
    if 'solver_iterations' in names and solver == 'gmres':
        its = [float(r[names.index('solver_iterations')]) for r in rows[1:]]
        case['iterations_per_solve'] = sum(its) / max(len(its), 1)
    if summary.get('shape_krylov_solves'):
        case['iterations_per_solve'] = summary['shape_krylov_iterations'] / summary['shape_krylov_solves']
    return case


def markdown(cases):
    lines = ['| solver | cells per side | ranks | unknowns | ms / step | us / (unknown step) | peak memory | '
             'bytes / unknown | assembly | solves | grid control | geometry | statistics | iterations / solve | '
             'shape factorizations / step | time exponent |', '|' + '---|' * 16]
    previous = {}
    for c in cases:
        key = (c['solver'], c['ranks'])
        if 'failed' in c:
            lines.append(f"| {c['solver']} | {c['cells_per_side']} | {c['ranks']} | {c['unknowns']} | "
                         f"{c['failed']} |" + ' |' * 11)
            continue
        exponent = ''
        if key in previous:
            p = previous[key]
            exponent = f"{math.log(c['ms_per_step'] / p['ms_per_step']) / math.log(c['vertices'] / p['vertices']):.2f}"
        previous[key] = c
        ph = c['phases_ms_per_step']
        lines.append(f"| {c['solver']} | {c['cells_per_side']} | {c['ranks']} | {c['unknowns']} | "
                     f"{c['ms_per_step']:.0f} | {c['us_per_unknown_step']:.2f} | "
                     f"{c['peak_memory_bytes'] / 1e9:.2f} GB | {c['bytes_per_unknown']:.0f} | "
                     + ' | '.join(f'{ph[p]:.0f}' for p in PHASES) +
                     f" | {c.get('iterations_per_solve', float('nan')):.0f}"
                     f" | {c.get('factorizations_per_step', float('nan')):.2f} | {exponent} |")
    return '\n'.join(lines).replace('| nan |', '| - |')


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('exe')
    parser.add_argument('--sizes', default='32,64,128,256')
    parser.add_argument('--ranks', default='1,2')
    parser.add_argument('--solvers', default='direct,gmres', help=', '.join(SOLVERS))
    parser.add_argument('--steps', type=int, default=8)
    parser.add_argument('--output', default='results/benchmarks/scaling')
    a = parser.parse_args()
    exe = os.path.abspath(a.exe)
    unknown = [s for s in a.solvers.split(',') if s not in SOLVERS]
    if unknown:
        parser.error(f"--solvers: unknown {', '.join(unknown)}; accepted: {', '.join(SOLVERS)}")
    cases = []
    for solver in a.solvers.split(','):
        for ranks in (int(r) for r in a.ranks.split(',')):
            for n in (int(s) for s in a.sizes.split(',')):
                case = run_case(exe, n, ranks, solver, a.steps, os.path.join(a.output, f'{solver}-n{n}-np{ranks}'))
                cases.append(case)
                print(json.dumps(case), flush=True)
    os.makedirs(a.output, exist_ok=True)
    with open(os.path.join(a.output, 'scaling.json'), 'w') as f:
        json.dump(cases, f, indent=1)
    table = markdown(cases)
    with open(os.path.join(a.output, 'scaling.md'), 'w') as f:
        f.write(table + '\n')
    print(table)
    return 0


if __name__ == '__main__':
    sys.exit(main())
