"""Synthetic VTU and PVD files of a periodic patch, in the layouts the simulator writes, for the
test scripts that read them back (tests/check_render.py, tests/test_capillary.py). They run as
`python3 tests/<script>.py`, which puts this directory first on sys.path."""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
from vtkmodules.vtkCommonCore import vtkFloatArray, vtkPoints
from vtkmodules.vtkCommonDataModel import VTK_QUAD, vtkCellArray, vtkUnstructuredGrid
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter


def write_vtu(path, n, height, phi, per_cell, time):
    """A periodic-patch VTU on n x n quads of the unit square with z = height(x, y) and the
    point field phi(x, y); per_cell: each vertex once per cell plus a `displacement` field (the
    points already displaced), else shared vertices and no displacement."""
    s = np.linspace(0.0, 1.0, n + 1)
    x, y = np.meshgrid(s, s, indexing='ij')
    reference = np.c_[x.ravel(), y.ravel(), np.zeros(x.size)]
    index = lambda i, j: i * (n + 1) + j  # noqa: E731
    quads = np.array([[index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)]
                      for i in range(n) for j in range(n)])
    if per_cell:
        reference, quads = reference[quads.ravel()], np.arange(4 * n * n).reshape(n * n, 4)
    displacement = np.zeros_like(reference)
    displacement[:, 2] = height(reference[:, 0], reference[:, 1])
    points = reference + displacement
    grid = vtkUnstructuredGrid()
    vtk_points = vtkPoints()
    vtk_points.SetData(numpy_to_vtk(points.astype(np.float32), deep=True))
    grid.SetPoints(vtk_points)
    cells = vtkCellArray()
    offsets = np.arange(0, 4 * len(quads) + 1, 4)
    cells.SetData(numpy_to_vtkIdTypeArray(offsets.astype(np.int64), deep=True),
                  numpy_to_vtkIdTypeArray(quads.ravel().astype(np.int64), deep=True))
    grid.SetCells(VTK_QUAD, cells)
    fields = {'phi': phi(reference[:, 0], reference[:, 1])}
    if per_cell:
        fields['displacement'] = displacement
    for name, values in fields.items():
        array = numpy_to_vtk(np.ascontiguousarray(values, dtype=np.float32), deep=True)
        array.SetName(name)
        grid.GetPointData().AddArray(array)
    stamp = vtkFloatArray()
    stamp.SetName('TIME')
    stamp.InsertNextValue(time)
    grid.GetFieldData().AddArray(stamp)
    writer = vtkXMLUnstructuredGridWriter()
    writer.SetFileName(path)
    writer.SetInputData(grid)
    writer.Write()


def write_pvd(path, entries):
    with open(path, 'w') as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n  <Collection>\n')
        for t, name in entries:
            f.write(f'    <DataSet timestep="{t}" group="" part="0" file="{name}"/>\n')
        f.write('  </Collection>\n</VTKFile>\n')
