#!/usr/bin/python3
"""Read a run's PVD and its last VTU with VTK, as ParaView would, and check that
the surface is a 3D quad mesh with shared vertices carrying every expected field
with finite values, and that the cells go around the vertices the way the normal
field says (counterclockwise seen from the normal).
With a second results directory (another number of ranks), the last snapshots
must hold the same points and phi to 1e-8.
Usage: check_vtu.py <results dir> <expected cells> [<expected points> [<other results dir>]]
('-' for a count that is not known in advance)."""
import os
import sys
import xml.etree.ElementTree as ET
import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

from membrane_flow.run import load_statistics  # noqa: E402 (PYTHONPATH: the build's python/)

directory = sys.argv[1]
n_cells = int(sys.argv[2]) if sys.argv[2] != '-' else None
n_points = int(sys.argv[3]) if len(sys.argv) > 3 and sys.argv[3] != '-' else None
other = sys.argv[4] if len(sys.argv) > 4 else None
datasets = ET.parse(os.path.join(directory, 'surface.pvd')).getroot().findall('.//DataSet')
assert len(datasets) >= 2, f"expected a time series, found {len(datasets)} snapshots"
times = [float(d.get('timestep')) for d in datasets]
assert times == sorted(times), "snapshot times are not increasing"



def last_snapshot(directory):
    entries = ET.parse(os.path.join(directory, 'surface.pvd')).getroot().findall('.//DataSet')
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(os.path.join(directory, entries[-1].get('file')))
    reader.Update()
    return reader.GetOutput()


grid = last_snapshot(directory)
if n_cells is None:
    n_cells = grid.GetNumberOfCells()
assert grid.GetNumberOfCells() == n_cells, f"{grid.GetNumberOfCells()} cells, expected {n_cells}"
points = vtk_to_numpy(grid.GetPoints().GetData())
if n_points is not None:
    assert len(points) == n_points, f"{len(points)} points, expected {n_points} (one per vertex)"
assert np.ptp(points[:, 2]) > 1e-3, "the surface is not displaced in z"
data = grid.GetPointData()
assert data.GetArray('displacement') is None, "the points are displaced already: no displacement field"
for name, components in [('phi', 1), ('Y', 1), ('gamma', 1), ('H', 1), ('K', 1), ('normal', 3), ('area_error', 1)]:
    array = data.GetArray(name)
    assert array is not None, f"field {name} missing"
    assert array.GetNumberOfComponents() == components, f"{name}: {array.GetNumberOfComponents()} components"
    values = vtk_to_numpy(array)
    assert np.all(np.isfinite(values)), f"{name} has non-finite values"
    print(f"{name:12s} range [{values.min():+.4f}, {values.max():+.4f}]")
# The vertex area error field of the last snapshot (written at the last step) has the
# largest magnitude that statistics.txt records for that step.
statistics = os.path.join(directory, 'statistics.txt')
if os.path.isfile(statistics):
    recorded = float(load_statistics(directory)['area_error'][-1])
    largest = np.abs(vtk_to_numpy(data.GetArray('area_error'))).max()
    assert abs(largest - recorded) <= 1e-6 * max(recorded, 1e-12) + 1e-13, \
        f"largest |area_error| in the snapshot {largest:.6e}, statistics.txt {recorded:.6e}"
    print(f"area_error: largest {largest:.3e} = statistics.txt {recorded:.3e}")
level = grid.GetCellData().GetArray('level')
assert level is not None and level.GetNumberOfTuples() == n_cells, "cell field level missing"

# Orientation: the cross product of a quad's diagonals points along the vertex normals.
cells = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 4)
corners = points[cells]
area_normals = np.cross(corners[:, 2] - corners[:, 0], corners[:, 3] - corners[:, 1])
vertex_normals = vtk_to_numpy(data.GetArray('normal'))[cells].mean(axis=1)
agreement = np.einsum('ij,ij->i', area_normals, vertex_normals) / np.linalg.norm(area_normals, axis=1)
assert agreement.min() > 0.5, f"a cell is ordered against the normal (cos = {agreement.min():.3f})"
if other is not None:
    def sorted_points(grid):
        xyz = vtk_to_numpy(grid.GetPoints().GetData())
        phi = vtk_to_numpy(grid.GetPointData().GetArray('phi'))
        table = np.column_stack([np.round(xyz, 6), xyz, phi])
        return table[np.lexsort(table[:, 2::-1].T)][:, 3:]
    a, b = sorted_points(grid), sorted_points(last_snapshot(other))
    assert a.shape == b.shape, f"{a.shape} vs {b.shape} in {other}"
    difference = np.abs(a - b).max()
    assert difference < 1e-8, f"points or phi differ from {other} by {difference:.2e}"
    print(f"same points and phi as {other} to {difference:.1e}")
# The ParaView state next to the series is Python that names this series.
state = open(os.path.join(directory, 'paraview_state.py')).read()
compile(state, 'paraview_state.py', 'exec')
assert os.path.abspath(os.path.join(directory, 'surface.pvd')) in state, "paraview_state.py names another series"
print(f"OK: {len(datasets)} snapshots, {grid.GetNumberOfCells()} cells, times {times[0]}..{times[-1]}")
