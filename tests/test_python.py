#!/usr/bin/python3
"""The Python module membrane_flow against the program (docs/python.md).
Usage: test_python.py <input.prm> <directory of the program's run of it> <scratch directory>

- Stepping the same input from Python gives the program's statistics (every column but the
  timing, to 1e-12) and the same summary; run_until / advance stop where they must; a run
  stopped after 5 steps with a checkpoint and resumed from Python gives them too (1e-10).
- The state arrays: one row per vertex DoF and one per cell as in the statistics; the area
  of the bilinear cells through `positions` and `cells` (2 x 2 Gauss points, as the code
  integrates) equals the statistics' area, and integral phi ds (by the same quadrature and
  as sum(phi * vertex_areas)) the statistics' mass, to round-off; every vertex of the
  program's last snapshot carries the same position, phi, H, K, gamma and Y as the arrays;
  the energies equal the last statistics row.
- Bad input raises membrane_flow.Error with the program's message; two simulations open
  at once, closed in any order, do not crash.
"""
import os
import sys

import numpy as np

import membrane_flow as mf
from checks import NARROW, Checks  # tests/checks.py, next to this script

prm, program_dir, scratch = sys.argv[1], sys.argv[2], sys.argv[3]
os.makedirs(scratch, exist_ok=True)
check = Checks(*NARROW)


def relative_difference(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    if a.shape != b.shape:
        return np.inf
    both_nan = np.isnan(a) & np.isnan(b)
    scale = max(np.max(np.abs(np.where(both_nan, 0, a)), initial=0), 1.0)
    return np.max(np.where(both_nan, 0, np.abs(a - b)), initial=0) / scale


program = mf.load_run(program_dir)
reference = program.statistics
settings = {'Output/Interval': float(program.parameters['Output/Interval'])}

# ---- the same run stepped from Python -----------------------------------------------------
sim = mf.Simulation(prm, settings, output_directory=os.path.join(scratch, 'stepped'), overwrite=True)
check(sim.steps == 0 and sim.time == 0.0, f"a new simulation is at step 0, t = 0 (got {sim.steps}, {sim.time})")
check(sim.result['stop_reason'] == '' and not sim.stopped, "no stop reason before the run stops")
n_vertices, n_cells = int(reference['dofs'][0]), int(reference['cells'][0])
positions, cells = sim.positions, sim.cells
check(positions.shape == (n_vertices, 3), f"positions {positions.shape}, expected ({n_vertices}, 3)")
check(cells.shape == (n_cells, 4) and cells.min() == 0 and cells.max() == n_vertices - 1,
      f"cells {cells.shape} indexing 0..{cells.max()}, expected ({n_cells}, 4) indexing 0..{n_vertices - 1}")
for name in ['phi', 'H', 'K', 'gamma', 'Y', 'vertex_areas']:
    check(getattr(sim, name).shape == (n_vertices,), f"{name} has one value per vertex")
check(sim.normals.shape == (n_vertices, 3), "normals n x 3")

# Two steps, then five, then to a time, then to the end: the step count and time add up.
check(sim.step() and sim.steps == 1, "step() takes one accepted step")
check(sim.advance(5) == 5 and sim.steps == 6, f"advance(5) takes five more (step {sim.steps})")
t_mid = reference['time'][len(reference['time']) // 2]
sim.run_until(t_mid)
check(sim.time >= t_mid * (1 - 1e-12) and sim.statistics()['time'][-2] < t_mid,
      f"run_until({t_mid:.6g}) stops at the first step at or after it (t = {sim.time:.6g})")
result = sim.run()
check(result['stop_reason'] == program.summary['stop_reason'] and result['outcome'] == program.summary['outcome'],
      f"same stop reason and outcome as the program ({result})")
check(not sim.step() and sim.advance(3) == 0, "no steps after the run has stopped")

stats = sim.statistics()
check(list(stats) == list(reference), "same statistics columns as the program")
worst = max(relative_difference(stats[c], reference[c]) for c in reference if not c.endswith('seconds'))
check(worst <= 1e-12, f"statistics equal the program's: worst relative difference {worst:.2e} over "
      f"{len(reference['time'])} rows")
stepped = mf.load_run(sim.output_directory)
check(relative_difference(stepped.statistics['energy'], reference['energy']) <= 1e-12,
      "statistics.txt written by the Python run equals the program's")
for key in ['steps', 'time', 'energy', 'area', 'mass', 'bud_height', 'outcome']:
    check(stepped.summary[key] == program.summary[key],
          f"summary {key}: Python {stepped.summary[key]} = program {program.summary[key]}")

# ---- the arrays of the final state ----------------------------------------------------------
energies = sim.energies
for name, value in energies.items():
    check(abs(value - stats[name][-1]) <= 1e-14 * max(1, abs(value)), f"{name} = {value:.10g} = statistics")
positions, cells, phi = sim.positions, sim.cells, sim.phi
check(np.ptp(positions[:, 2]) > 1e-3, f"the surface is curved (z range {np.ptp(positions[:, 2]):.4f})")

# 2 x 2 Gauss points on each bilinear cell X(s, t) (VTK_QUAD order: corners 0, 1, 3, 2 of the unit square).
g = 0.5 + np.array([-1, 1]) / (2 * np.sqrt(3))
area = mass = 0.0
X, P = positions[cells], phi[cells]  # n_cells x 4 (x 3)
for s in g:
    for t in g:
        shape = np.array([(1 - s) * (1 - t), s * (1 - t), s * t, (1 - s) * t])
        ds = np.array([-(1 - t), 1 - t, t, -t])
        dt = np.array([-(1 - s), -s, s, 1 - s])
        Xs, Xt = np.einsum('k,ckd->cd', ds, X), np.einsum('k,ckd->cd', dt, X)
        jxw = 0.25 * np.linalg.norm(np.cross(Xs, Xt), axis=1)
        area += jxw.sum()
        mass += (jxw * (P @ shape)).sum()
check(abs(area - stats['area'][-1]) <= 1e-12, f"area from positions and cells {area:.15f} = statistics "
      f"{stats['area'][-1]:.15f}")
check(abs(mass - stats['mass'][-1]) <= 1e-12, f"integral phi ds from the arrays {mass:.15f} = statistics "
      f"{stats['mass'][-1]:.15f}")
weighted = np.sum(phi * sim.vertex_areas)
check(abs(weighted - stats['mass'][-1]) <= 1e-12, f"sum(phi * vertex_areas) {weighted:.15f} = statistics mass")
check(abs(np.sum(sim.vertex_areas) - stats['area'][-1]) <= 1e-12, "sum(vertex_areas) = statistics area")
check(abs(phi.min() - stats['phi_min'][-1]) <= 1e-14 and abs(phi.max() - stats['phi_max'][-1]) <= 1e-14,
      "phi range = statistics phi_min, phi_max")
gamma = sim.gamma
check(abs(gamma.min() - stats['gamma_min'][-1]) <= 1e-12 * max(1, abs(gamma.min())) and
      abs(gamma.max() - stats['gamma_max'][-1]) <= 1e-12 * max(1, abs(gamma.max())),
      "gamma range = statistics gamma_min, gamma_max")

# Every point of the program's last snapshot (written by deal.II's DataOut) against the arrays.
snapshot = program.snapshot(-1)
check(abs(snapshot['time'] - sim.time) <= 1e-6 * sim.time, "last snapshot at the final time")
points = snapshot['points']
candidates = [points]
if 'displacement' in snapshot['point_data']:  # reference positions plus the displacement
    candidates.append(points + snapshot['point_data']['displacement'])
match = None
for candidate in candidates:  # the nearest vertex of each point, within single precision
    distance = np.linalg.norm(candidate[:, None, :] - positions[None, :, :], axis=2)
    nearest = np.argmin(distance, axis=1)
    if np.max(distance[np.arange(len(candidate)), nearest]) <= 1e-6:
        match = nearest
        break
check(match is not None and len(set(match.tolist())) == n_vertices,
      f"each of the {len(points)} snapshot points is one of the {n_vertices} vertices, all of them used")
if match is not None:
    check(np.max(np.abs(candidate - positions[match])) <= 1e-6, "snapshot points = positions (VTU float32)")
    for name in ['phi', 'H', 'K', 'gamma', 'Y']:
        values = snapshot['point_data'][name]
        mine = sim.field(name)[match]
        error = np.max(np.abs(values - mine)) / max(np.max(np.abs(mine)), 1.0)
        check(error <= 1e-6, f"snapshot {name} = array (relative difference {error:.1e}, VTU float32)")
sim.close()
try:
    sim.time
    check(False, "a closed simulation raises")
except mf.Error as e:
    check('closed' in str(e), f"a closed simulation raises membrane_flow.Error: {e}")

# ---- 5 steps with a checkpoint, then resumed to the end: the same statistics ---------------
split = os.path.join(scratch, 'resumed')
first = dict(settings, **{'Checkpoint/Interval': 5, 'Output/Write VTU': False})
with mf.Simulation(prm, dict(first, **{'Time stepping/Maximum steps': 5}), output_directory=split,
                   overwrite=True) as part:
    check(part.run()['stop_reason'] == 'maximum steps' and part.steps == 5, "first part: 5 steps")
with mf.Simulation(prm, dict(first, **{'Checkpoint/Resume from': os.path.join(split, 'checkpoint.txt')}),
                   output_directory=split) as part:
    check(part.steps == 5 and part.time == reference['time'][5], f"resumed at step 5, t = {part.time}")
    part.run()
    resumed = part.statistics()
# step_error needs the previous step's increments, which a checkpoint does not hold: it is
# undefined (-1) on the first step after a resume (docs/model.md).
worst = max(relative_difference(resumed[c], reference[c]) for c in reference
            if not c.endswith('seconds') and c != 'step_error')
check(worst <= 1e-10, f"5 steps + resume from the checkpoint = the program's run: worst difference {worst:.2e}")

# ---- from a dict only, and two open at once closed in any order ---------------------------
a = mf.Simulation(parameters={'Mesh/Cells per side': 8, 'Material/Transition length': 0.2,
                              'Initial phase/Type': 'random', 'Time stepping/End time': 1e-3,
                              'Output/Write VTU': False},
                  output_directory=os.path.join(scratch, 'dict_a'), overwrite=True)
b = mf.Simulation(parameters={'Mesh/Cells per side': 4, 'Material/Transition length': 0.4,
                              'Output/Write VTU': False}, output_directory=os.path.join(scratch, 'dict_b'),
                  overwrite=True)
check(a.positions.shape == (81, 3) and b.cells.shape == (16, 4), "8 x 8 and 4 x 4 cells from dicts")
check(a.parameters['Mesh/Cells per side'] == '8' and a.parameters['Output/Write VTU'] == 'false',
      "the dict entries are the run's parameters")
a.step()
a.close()
b.step()
b.close()
for d in ['dict_a', 'dict_b']:
    with open(os.path.join(scratch, d, 'log.txt')) as f:
        check('Membrane patch' in f.read(), f"{d}/log.txt written")
    check(os.path.isfile(os.path.join(scratch, d, 'summary.json')), f"{d}/summary.json written by close()")
check(mf.load_summary(os.path.join(scratch, 'dict_a'))['stop_reason'].startswith('finished by the caller'),
      "a run closed early says so in summary.json")

# ---- bad input: membrane_flow.Error with the program's message, never a crash -------------
bad = [({'Material/Line tensoin': 3}, None, 'Line tensoin=3: no such entry'),
       ({'Material/Line tension': -1}, None, 'Line tension=-1: the value does not match'),
       ({'Time stepping/Time step': 0.5}, None, 'Minimum time step <= Time step <= Maximum time step'),
       ({}, '/nonexistent/input.prm', 'Cannot open the parameter file </nonexistent/input.prm>: no such file'),
       ({}, prm, 'Output/Directory')]  # the directory of an earlier run, without overwrite
for entries, input_file, expected in bad:
    try:
        mf.Simulation(input_file, entries, output_directory=os.path.join(scratch, 'stepped'))
        check(False, f"{entries or input_file} raises")
    except mf.Error as e:
        check(expected in str(e) and 'Stacktrace' not in str(e), f"{entries or input_file}: {e}")
try:
    mf.Simulation(parameters={'Material/Line tension': {'a': 1}})
    check(False, "a dict value raises TypeError")
except TypeError as e:
    check(True, f"TypeError: {e}")
check(isinstance(mf.Error('x'), RuntimeError), "membrane_flow.Error is a RuntimeError")

print(f"{check.failed} failures")
sys.exit(check.exit_code())
