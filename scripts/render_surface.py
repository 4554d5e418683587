#!/usr/bin/python3
"""Render a surface VTU (or a snapshot of a PVD series) to PNG, coloured by a field.

Usage: render_surface.py <surface.pvd|file.vtu> <out.png> [--field phi] [--size 800x600]
                         [--elev 35] [--azim -60] [--views 'elev,azim;elev,azim;...'] [--time T]
--views draws several views side by side in one picture; --time picks the snapshot of a
PVD series closest to time T (default: the last one). Also importable: read_vtu,
snapshots, draw."""
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


def snapshots(pvd):
    """[(time, path)] of a PVD series, in order."""
    root = ET.parse(pvd).getroot()
    return [(float(d.get('timestep')), os.path.join(os.path.dirname(pvd), d.get('file')))
            for d in root.findall('.//DataSet')]


def read_vtu(path, time=None):
    """The VTU at `path`, or the snapshot of a PVD closest to `time` (default: the last)."""
    if path.endswith('.pvd'):
        series = snapshots(path)
        path = series[-1][1] if time is None else min(series, key=lambda s: abs(s[0] - time))[1]
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def draw(ax, grid, field='phi', elev=35, azim=-60):
    """Draw the quads of `grid` on a 3D axis coloured by `field`; returns the colour map and range."""
    points = vtk_to_numpy(grid.GetPoints().GetData())
    cells = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 4)
    values = vtk_to_numpy(grid.GetPointData().GetArray(field))
    cmap = plt.get_cmap('coolwarm')
    low, high = (-1.0, 1.0) if field == 'phi' else (values.min(), values.max())
    colours = cmap((values[cells].mean(axis=1) - low) / max(high - low, 1e-300))
    ax.add_collection3d(Poly3DCollection(points[cells], facecolors=colours, edgecolors='none'))
    lo, hi = points.min(axis=0), points.max(axis=0)
    ax.set_xlim(lo[0], hi[0]); ax.set_ylim(lo[1], hi[1]); ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(np.maximum(hi - lo, 1e-3))
    ax.view_init(elev=elev, azim=azim)
    ax.set_axis_off()
    return cmap, low, high


def save_atomically(fig, output):
    fig.savefig(output + '.partial.png')
    plt.close(fig)
    os.replace(output + '.partial.png', output)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('input')
    parser.add_argument('output')
    parser.add_argument('--field', default='phi')
    parser.add_argument('--size', default='800x600')
    parser.add_argument('--elev', type=float, default=35)
    parser.add_argument('--azim', type=float, default=-60)
    parser.add_argument('--views', help="several views 'elev,azim;elev,azim'")
    parser.add_argument('--time', type=float)
    args = parser.parse_args()

    grid = read_vtu(args.input, args.time)
    views = ([tuple(float(v) for v in view.split(',')) for view in args.views.split(';')] if args.views
             else [(args.elev, args.azim)])
    width, height = (int(v) for v in args.size.split('x'))
    fig = plt.figure(figsize=(width / 100, height / 100), dpi=100)
    for k, (elev, azim) in enumerate(views):
        ax = fig.add_subplot(1, len(views), k + 1, projection='3d')
        cmap, low, high = draw(ax, grid, args.field, elev, azim)
    mappable = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(low, high))
    fig.colorbar(mappable, ax=fig.axes, shrink=0.6, label=args.field)
    save_atomically(fig, args.output)


if __name__ == '__main__':
    main()
