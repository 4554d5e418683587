#!/usr/bin/python3
"""Read a run's PVD and its last VTU with VTK, as ParaView would, and check that
the surface is a 3D quad mesh carrying every expected field with finite values.
Usage: check_vtu.py <results dir> <expected cells>"""
import os
import sys
import xml.etree.ElementTree as ET
import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

directory, n_cells = sys.argv[1], int(sys.argv[2])
datasets = ET.parse(os.path.join(directory, 'surface.pvd')).getroot().findall('.//DataSet')
assert len(datasets) >= 2, f"expected a time series, found {len(datasets)} snapshots"
times = [float(d.get('timestep')) for d in datasets]
assert times == sorted(times), "snapshot times are not increasing"

reader = vtk.vtkXMLUnstructuredGridReader()
reader.SetFileName(os.path.join(directory, datasets[-1].get('file')))
reader.Update()
grid = reader.GetOutput()
assert grid.GetNumberOfCells() == n_cells, f"{grid.GetNumberOfCells()} cells, expected {n_cells}"
points = vtk_to_numpy(grid.GetPoints().GetData())
assert np.ptp(points[:, 2]) > 1e-3, "the surface is not displaced in z"
data = grid.GetPointData()
for name, components in [('phi', 1), ('Y', 1), ('H', 1), ('K', 1), ('displacement', 3), ('normal', 3)]:
    array = data.GetArray(name)
    assert array is not None, f"field {name} missing"
    assert array.GetNumberOfComponents() == components, f"{name}: {array.GetNumberOfComponents()} components"
    values = vtk_to_numpy(array)
    assert np.all(np.isfinite(values)), f"{name} has non-finite values"
    print(f"{name:12s} range [{values.min():+.4f}, {values.max():+.4f}]")
print(f"OK: {len(datasets)} snapshots, {grid.GetNumberOfCells()} cells, times {times[0]}..{times[-1]}")
