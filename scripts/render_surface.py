#!/usr/bin/python3
"""Render a surface VTU (or the last snapshot of a PVD) to PNG, coloured by a field.
Usage: render_surface.py <surface.pvd|file.vtu> <out.png> [--field phi] [--size 800x600]
                         [--elev 35] [--azim -60]"""
import argparse
import os
import xml.etree.ElementTree as ET

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt
import numpy as np
import vtk
from mpl_toolkits.mplot3d.art3d import Poly3DCollection
from vtk.util.numpy_support import vtk_to_numpy


def read_vtu(path):
    if path.endswith('.pvd'):
        last = ET.parse(path).getroot().findall('.//DataSet')[-1]
        path = os.path.join(os.path.dirname(path), last.get('file'))
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('input')
    parser.add_argument('output')
    parser.add_argument('--field', default='phi')
    parser.add_argument('--size', default='800x600')
    parser.add_argument('--elev', type=float, default=35)
    parser.add_argument('--azim', type=float, default=-60)
    args = parser.parse_args()

    grid = read_vtu(args.input)
    points = vtk_to_numpy(grid.GetPoints().GetData())
    cells = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 4)
    values = vtk_to_numpy(grid.GetPointData().GetArray(args.field))
    width, height = (int(v) for v in args.size.split('x'))

    fig = plt.figure(figsize=(width / 100, height / 100), dpi=100)
    ax = fig.add_subplot(projection='3d')
    cmap = plt.get_cmap('coolwarm')
    low, high = (-1.0, 1.0) if args.field == 'phi' else (values.min(), values.max())
    colours = cmap((values[cells].mean(axis=1) - low) / max(high - low, 1e-300))
    ax.add_collection3d(Poly3DCollection(points[cells], facecolors=colours, edgecolors='none'))
    lo, hi = points.min(axis=0), points.max(axis=0)
    ax.set_xlim(lo[0], hi[0]); ax.set_ylim(lo[1], hi[1]); ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(np.maximum(hi - lo, 1e-3))
    ax.view_init(elev=args.elev, azim=args.azim)
    ax.set_axis_off()
    mappable = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(low, high))
    fig.colorbar(mappable, ax=ax, shrink=0.6, label=args.field)
    fig.savefig(args.output + '.partial.png')
    os.replace(args.output + '.partial.png', args.output)


if __name__ == '__main__':
    main()
