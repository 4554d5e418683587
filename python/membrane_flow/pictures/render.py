#!/usr/bin/python3
"""Render a membrane surface (a VTU file, or a snapshot of a PVD series) to PNG with VTK.

Usage: python3 -m membrane_flow render <surface.pvd|file.vtu> <out.png> [options]

The surface is drawn smooth-shaded and lit, coloured by a point field interpolated over the
cells (phi by default, on a red/blue diverging map fixed to [-1, 1]: phase A red, phase B
blue), with a colour bar and the time stamp, framed tightly. Points stored once per cell are
merged first, so shading and colours are continuous across cells. The points of a VTU are
taken as the surface positions: a `displacement` field, when present, is not applied again.

Snapshot of a PVD: --time T (closest to T) or --index K (K-th, negative from the end);
default the last one. Camera: --view oblique|top|side, or --elev/--azim in degrees
(matplotlib's convention), or --views 'elev,azim;elev,azim' for several views side by side.
Headless: without a DISPLAY the command starts its own Xvfb (package xvfb).

Importable: snapshots, select, read_vtu, surface_polydata, SurfaceRenderer, render_image."""
import argparse
import atexit
import os
import shutil
import subprocess
import sys
import weakref

import numpy as np

# VTK modules, imported one by one (much faster than `import vtk`).
from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkFiltersCore import vtkAppendPolyData, vtkCleanPolyData, vtkPolyDataNormals
from vtkmodules.vtkFiltersGeneral import vtkTransformPolyDataFilter
from vtkmodules.vtkFiltersGeometry import vtkGeometryFilter
from vtkmodules.vtkRenderingAnnotation import vtkScalarBarActor
from vtkmodules.vtkRenderingCore import (vtkActor, vtkLightKit, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow, vtkTextActor, vtkWindowToImageFilter)
import vtkmodules.vtkRenderingFreeType  # noqa: F401  (text rendering)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (the OpenGL render window)
from vtkmodules.util.numpy_support import vtk_to_numpy

from .. import run

VIEWS = {'oblique': (35.0, -60.0), 'top': (90.0, -90.0), 'side': (0.0, -90.0)}
PHASE_RANGE = (-1.0, 1.0)


# ---------------------------------------------------------------------------------------------
# Input
# ---------------------------------------------------------------------------------------------
def snapshots(pvd):
    """[(time, path)] of a PVD series, in order of time."""
    series = run.read_pvd(pvd)
    if not series:
        raise SystemExit(f'{pvd}: no snapshots listed')
    return series


def select(path, time=None, index=None):
    """(file, time or None) of `path`: a VTU itself, or the snapshot of a PVD closest to
    `time`, or its `index`-th (negative from the end), by default the last one."""
    if not path.endswith('.pvd'):
        return path, None
    series = snapshots(path)
    if time is not None:
        t, f = min(series, key=lambda s: abs(s[0] - time))
    else:
        if index is not None and not -len(series) <= index < len(series):
            raise SystemExit(f'{path}: no snapshot {index} (there are {len(series)})')
        t, f = series[-1 if index is None else index]
    return f, t


def read_grid(path):
    """The unstructured grid of a .vtu or .pvtu file (membrane_flow.run.read_grid; a missing or
    empty file ends the program with a message)."""
    if not os.path.exists(path):
        raise SystemExit(f'{path}: no such file')
    try:
        return run.read_grid(path)
    except ValueError:
        raise SystemExit(f'{path}: no cells') from None


grid_time = run.grid_time


def read_vtu(path, time=None, index=None):
    """The grid of a VTU, or of the snapshot of a PVD closest to `time` (default: the last).
    The time of the snapshot is in grid.snapshot_time (None if unknown)."""
    f, t = select(path, time, index)
    grid = read_grid(f)
    grid.snapshot_time = grid_time(grid, t)
    return grid


def surface_polydata(grid, tile=(1, 1), merge=True):
    """The surface of `grid` as polydata with point normals: periodic copies translated by the
    unit periods (tile = (copies in x, copies in y)), coincident points merged (each vertex is
    stored once per cell in deal.II's VTU output), normals averaged over the cells of a vertex."""
    geometry = vtkGeometryFilter()
    geometry.SetInputData(grid)
    geometry.Update()
    pieces = geometry.GetOutput()
    if tile != (1, 1):
        append = vtkAppendPolyData()
        for i in range(tile[0]):
            for j in range(tile[1]):
                transform = vtkTransform()
                transform.Translate(i - (tile[0] - 1) // 2, j - (tile[1] - 1) // 2, 0.0)  # whole periods
                moved = vtkTransformPolyDataFilter()
                moved.SetTransform(transform)
                moved.SetInputData(pieces)
                moved.Update()
                append.AddInputData(moved.GetOutput())
        append.Update()
        pieces = append.GetOutput()
    if merge:
        clean = vtkCleanPolyData()
        clean.SetInputData(pieces)
        clean.ToleranceIsAbsoluteOn()
        clean.SetAbsoluteTolerance(1e-6)
        clean.PointMergingOn()
        clean.Update()
        pieces = clean.GetOutput()
    normals = vtkPolyDataNormals()
    normals.SetInputData(pieces)
    normals.ComputePointNormalsOn()
    normals.ComputeCellNormalsOff()
    normals.SplittingOff()
    normals.ConsistencyOn()
    normals.AutoOrientNormalsOff()
    normals.Update()
    result = vtkPolyData()
    result.ShallowCopy(normals.GetOutput())
    return result


def field_values(poly, field):
    """(values, 'point' or 'cell') of a field of the surface."""
    for kind, data in (('point', poly.GetPointData()), ('cell', poly.GetCellData())):
        array = data.GetArray(field)
        if array is not None:
            values = vtk_to_numpy(array)
            return (np.linalg.norm(values, axis=1) if values.ndim > 1 else values), kind
    names = [poly.GetPointData().GetArrayName(k) for k in range(poly.GetPointData().GetNumberOfArrays())]
    names += [poly.GetCellData().GetArrayName(k) for k in range(poly.GetCellData().GetNumberOfArrays())]
    raise SystemExit(f"no field '{field}' in the file; fields: {', '.join(n for n in names if n != 'Normals')}")


def default_range(field, values):
    """[-1, 1] for phi; symmetric about 0 for a signed field; else its min..max."""
    if field == 'phi':
        return PHASE_RANGE
    low, high = float(np.min(values)), float(np.max(values))
    if low < 0 < high:
        bound = max(-low, high)
        return -bound, bound
    if high - low <= 1e-6 * max(abs(low), abs(high), 1e-30):  # constant up to round-off
        return low - 0.5 * max(abs(low), 1.0), high + 0.5 * max(abs(high), 1.0)
    return low, high


# ---------------------------------------------------------------------------------------------
# Display
# ---------------------------------------------------------------------------------------------
_xvfb = None
_windows = weakref.WeakSet()  # render windows to close before our Xvfb stops


def ensure_display():
    """VTK's Debian build renders through X: without a DISPLAY, start a private Xvfb."""
    global _xvfb
    if os.environ.get('DISPLAY') or _xvfb is not None or sys.platform != 'linux':
        return
    if shutil.which('Xvfb') is None:
        raise SystemExit('no DISPLAY and no Xvfb: install xvfb (scripts/install_dependencies.sh)')
    # Displays :0 to :9 are avoided: hwloc's GL plugin (loaded by MPI_Init) probes them, and a
    # process that connects to our Xvfb dies with it when it stops ("X connection broken").
    for number in range(99, 200):
        if os.path.exists(f'/tmp/.X{number}-lock') or os.path.exists(f'/tmp/.X11-unix/X{number}'):
            continue
        read_end, write_end = os.pipe()
        _xvfb = subprocess.Popen(['Xvfb', f':{number}', '-displayfd', str(write_end),
                                  '-screen', '0', '1280x1024x24', '-nolisten', 'tcp', '-noreset'],
                                 pass_fds=(write_end,), stdout=subprocess.DEVNULL,
                                 stderr=subprocess.DEVNULL, preexec_fn=_die_with_parent)
        os.close(write_end)
        ready = b''
        while not ready.endswith(b'\n'):
            chunk = os.read(read_end, 16)
            if not chunk:
                break
            ready += chunk
        os.close(read_end)
        if ready.endswith(b'\n'):
            os.environ['DISPLAY'] = ':' + ready.decode().strip()
            break
        _xvfb.wait()  # taken meanwhile by another server: try the next number
        _xvfb = None
    else:
        raise SystemExit('Xvfb did not start on any display from :99 to :199')
    atexit.register(_stop_xvfb)


def _die_with_parent():
    """In the Xvfb child: get SIGTERM when this script dies, however it dies (Linux prctl)."""
    try:
        import ctypes
        import signal
        ctypes.CDLL('libc.so.6', use_errno=True).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass


def _stop_xvfb():
    for window in list(_windows):
        window.Finalize()
    if _xvfb is not None and _xvfb.poll() is None:
        _xvfb.terminate()
        try:
            _xvfb.wait(5)
        except subprocess.TimeoutExpired:
            _xvfb.kill()


# ---------------------------------------------------------------------------------------------
# Rendering
# ---------------------------------------------------------------------------------------------
def lookup_table(cmap, low, high):
    """A 256-entry VTK lookup table sampled from a matplotlib colour map."""
    from matplotlib import colormaps
    colours = colormaps[cmap](np.linspace(0.0, 1.0, 256))
    table = vtkLookupTable()
    table.SetNumberOfTableValues(256)
    table.SetRange(low, high)
    table.SetVectorModeToMagnitude()  # vector fields by their length
    for k, (r, g, b, a) in enumerate(colours):
        table.SetTableValue(k, r, g, b, 1.0)
    table.Build()
    return table


def colorbar_fraction(width):
    """The fraction of the picture's width taken by the colour bar column at the right."""
    return min(0.16, 110.0 / width + 0.02)


def camera_vectors(elev, azim):
    """Unit direction from the focal point to the camera, and the view-up vector."""
    e, a = np.radians(elev), np.radians(azim)
    direction = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
    up = np.array([-np.sin(e) * np.cos(a), -np.sin(e) * np.sin(a), np.cos(e)])
    return direction, up


class SurfaceRenderer:
    """One off-screen render window: surface views side by side, an optional colour bar column
    at the right and a time stamp. Call set_surface() then frame_to() to fix the camera, then
    image(); the camera stays as it is for further surfaces (movies)."""

    def __init__(self, size=(800, 600), field='phi', value_range=None, cmap=None, views=(VIEWS['oblique'],),
                 colorbar=True, timestamp=True, projection='perspective', supersample=2,
                 background=(1.0, 1.0, 1.0), label=None, margin=0.02):
        ensure_display()
        self.size, self.field, self.views = tuple(size), field, list(views)
        self.value_range, self.cmap = value_range, cmap
        self.colorbar, self.timestamp, self.label = colorbar, timestamp, label
        self.projection, self.supersample, self.margin = projection, max(1, int(supersample)), margin
        self.background = background
        width, height = self.size[0] * self.supersample, self.size[1] * self.supersample
        self.window = vtkRenderWindow()
        self.window.SetOffScreenRendering(1)
        self.window.SetSize(width, height)
        self.window.SetMultiSamples(0)
        _windows.add(self.window)
        bar_width = colorbar_fraction(self.size[0]) if colorbar else 0.0
        self.bar_width = bar_width
        self.renderers, self.actors = [], []
        columns = len(self.views)
        for k in range(columns):
            renderer = vtkRenderer()
            renderer.SetBackground(*background)
            x0 = (1.0 - bar_width) * k / columns
            renderer.SetViewport(x0, 0.0, x0 + (1.0 - bar_width) / columns, 1.0)
            kit = vtkLightKit()
            kit.SetKeyLightIntensity(0.85)
            kit.AddLightsToRenderer(renderer)
            self.window.AddRenderer(renderer)
            self.renderers.append(renderer)
        self.text = None
        if timestamp or label:
            self.text = vtkTextActor()
            prop = self.text.GetTextProperty()
            prop.SetFontSize(int(round(max(11, 0.045 * self.size[1]) * self.supersample)))
            prop.SetColor(0.1, 0.1, 0.1)
            prop.SetVerticalJustificationToTop()
            self.text.SetPosition(0.02 * width / columns, height - 0.02 * height)
            self.renderers[0].AddActor2D(self.text)
        self.bar = None
        self.mapper_range = None

    # -- content ------------------------------------------------------------------------------
    def set_surface(self, poly, time=None):
        values, kind = field_values(poly, self.field)
        if self.mapper_range is None:
            self.mapper_range = tuple(self.value_range) if self.value_range else default_range(self.field, values)
            low, high = self.mapper_range
            cmap = self.cmap or ('coolwarm' if (self.field == 'phi' or low < 0 < high) else 'viridis')
            self.table = lookup_table(cmap, low, high)
            if self.colorbar:
                self._add_colorbar()
        for renderer, actor in zip(self.renderers, self.actors):
            renderer.RemoveActor(actor)
        self.actors = []
        for renderer in self.renderers:
            mapper = vtkPolyDataMapper()
            mapper.SetInputData(poly)
            mapper.SetLookupTable(self.table)
            mapper.UseLookupTableScalarRangeOn()
            mapper.ScalarVisibilityOn()
            if kind == 'point':
                mapper.SetScalarModeToUsePointFieldData()
                mapper.InterpolateScalarsBeforeMappingOn()  # colours interpolate in phi, not in RGB
            else:
                mapper.SetScalarModeToUseCellFieldData()
            mapper.SelectColorArray(self.field)
            actor = vtkActor()
            actor.SetMapper(mapper)
            prop = actor.GetProperty()
            prop.SetInterpolationToPhong()
            prop.SetAmbient(0.18)
            prop.SetDiffuse(0.82)
            prop.SetSpecular(0.12)
            prop.SetSpecularPower(25)
            renderer.AddActor(actor)
            self.actors.append(actor)
        if self.text is not None:
            parts = [self.label] if self.label else []
            if self.timestamp and time is not None:
                parts.append(f't = {time:.4g}')
            self.text.SetInput('   '.join(parts))
        self.points = vtk_to_numpy(poly.GetPoints().GetData()).astype(float)

    def _add_colorbar(self):
        bar_renderer = vtkRenderer()
        bar_renderer.SetBackground(*self.background)
        bar_renderer.SetViewport(1.0 - self.bar_width, 0.0, 1.0, 1.0)
        self.window.AddRenderer(bar_renderer)
        bar = vtkScalarBarActor()
        bar.SetLookupTable(self.table)
        bar.SetTitle(self.field)
        low, high = self.mapper_range
        bar.SetNumberOfLabels(5)
        span = max(abs(low), abs(high))
        bar.SetLabelFormat('%.1f' if span < 10 else '%.0f' if span < 1e4 else '%.1e')
        bar.SetMaximumWidthInPixels(int(self.bar_width * self.size[0] * self.supersample))
        bar.GetPositionCoordinate().SetCoordinateSystemToNormalizedViewport()
        bar.GetPositionCoordinate().SetValue(0.05, 0.12)
        bar.SetWidth(0.85)
        bar.SetHeight(0.76)
        bar.SetBarRatio(0.28)
        bar.SetTextPad(6 * self.supersample)
        bar.UnconstrainedFontSizeOn()
        size = int(round(max(10, 0.035 * self.size[1]) * self.supersample))
        for prop in (bar.GetTitleTextProperty(), bar.GetLabelTextProperty()):
            prop.SetColor(0.1, 0.1, 0.1)
            prop.SetFontSize(size)
            prop.BoldOff()
            prop.ItalicOff()
            prop.ShadowOff()
        bar.GetTitleTextProperty().SetFontSize(int(size * 1.15))
        bar_renderer.AddActor2D(bar)
        self.bar = bar

    # -- camera -------------------------------------------------------------------------------
    def frame_to(self, points=None):
        """Point each view's camera at the surface from its direction and zoom until `points`
        (default: the current surface) fill the view, less the margin and the time stamp."""
        points = self.points if points is None else np.asarray(points, float)
        centre = 0.5 * (points.min(axis=0) + points.max(axis=0))
        radius = max(0.5 * np.linalg.norm(points.max(axis=0) - points.min(axis=0)), 1e-6)
        for renderer, (elev, azim) in zip(self.renderers, self.views):
            camera = renderer.GetActiveCamera()
            direction, up = camera_vectors(elev, azim)
            camera.SetFocalPoint(*centre)
            camera.SetPosition(*(centre + 8.0 * radius * direction))
            camera.SetViewUp(*up)
            camera.SetParallelProjection(self.projection == 'parallel')
            camera.SetViewAngle(14.0)
            camera.SetParallelScale(radius)
            renderer.ResetCameraClippingRange(*np.ravel(list(zip(points.min(axis=0), points.max(axis=0)))))
            self._fit(renderer, points)
            lo, hi = points.min(axis=0) - radius, points.max(axis=0) + radius
            renderer.ResetCameraClippingRange(lo[0], hi[0], lo[1], hi[1], lo[2], hi[2])

    def _fit(self, renderer, points):
        x0, y0, x1, y1 = renderer.GetViewport()
        width, height = self.window.GetSize()
        aspect = (x1 - x0) * width / ((y1 - y0) * height)
        top = 1.0 - (2.0 * (0.02 + 0.055) if self.text is not None else 0.0)  # keep the time stamp clear
        target = np.array([-1.0 + 2 * self.margin, 1.0 - 2 * self.margin, -1.0 + 2 * self.margin,
                           top - 2 * self.margin])
        camera = renderer.GetActiveCamera()
        homogeneous = np.c_[points, np.ones(len(points))]
        for _ in range(6):
            matrix = camera.GetCompositeProjectionTransformMatrix(aspect, -1, 1)
            m = np.array([[matrix.GetElement(i, j) for j in range(4)] for i in range(4)])
            clip = homogeneous @ m.T
            ndc = clip[:, :2] / clip[:, 3:4]
            lo, hi = ndc.min(axis=0), ndc.max(axis=0)
            # shift the picture's centre to the target's centre (in the view plane at the focal point)
            shift = 0.5 * np.array([target[0] + target[1] - lo[0] - hi[0], target[2] + target[3] - lo[1] - hi[1]])
            if camera.GetParallelProjection():
                half_height = camera.GetParallelScale()
            else:
                half_height = camera.GetDistance() * np.tan(np.radians(camera.GetViewAngle()) / 2)
            right = np.cross(np.array(camera.GetDirectionOfProjection()), np.array(camera.GetViewUp()))
            right /= np.linalg.norm(right)
            up = np.array(camera.GetViewUp())
            move = -(shift[0] * half_height * aspect * right + shift[1] * half_height * up)
            camera.SetFocalPoint(*(np.array(camera.GetFocalPoint()) + move))
            camera.SetPosition(*(np.array(camera.GetPosition()) + move))
            zoom = min((target[1] - target[0]) / max(hi[0] - lo[0], 1e-12),
                       (target[3] - target[2]) / max(hi[1] - lo[1], 1e-12))
            camera.Zoom(zoom)

    # -- output -------------------------------------------------------------------------------
    def image(self):
        """The rendered picture as an (height, width, 3) uint8 array, at the requested size."""
        self.window.Render()
        grab = vtkWindowToImageFilter()
        grab.SetInput(self.window)
        grab.SetInputBufferTypeToRGB()
        grab.ReadFrontBufferOff()
        grab.Update()
        data = grab.GetOutput()
        w, h, _ = data.GetDimensions()
        pixels = vtk_to_numpy(data.GetPointData().GetScalars()).reshape(h, w, 3)[::-1].astype(float)
        s = self.supersample
        if s > 1:
            pixels = pixels.reshape(h // s, s, w // s, s, 3).mean(axis=(1, 3))
        return np.clip(np.round(pixels), 0, 255).astype(np.uint8)


def save_png(pixels, output):
    """Write an RGB array to PNG under a temporary name, then rename it into place."""
    from PIL import Image  # python3-pil, a dependency of python3-matplotlib
    directory = os.path.dirname(os.path.abspath(output))
    os.makedirs(directory, exist_ok=True)
    partial = output + '.partial.png'
    Image.fromarray(pixels, 'RGB').save(partial, format='PNG', optimize=True)
    os.replace(partial, output)


def parse_pair(text, name, separator='x'):
    try:
        a, b = (int(v) for v in text.lower().split(separator))
        assert a > 0 and b > 0
        return a, b
    except (ValueError, AssertionError):
        raise SystemExit(f"--{name}: expected two positive integers like 3{separator}3, got '{text}'")


def render_image(path, size=(800, 600), time=None, index=None, field='phi', value_range=None, cmap=None,
                 views=(VIEWS['oblique'],), tile=(1, 1), merge=True, colorbar=True, timestamp=True,
                 projection='perspective', supersample=2, label=None):
    """The picture of one snapshot as an RGB uint8 array (see the module's description)."""
    grid = read_vtu(path, time, index)
    poly = surface_polydata(grid, tile, merge)
    renderer = SurfaceRenderer(size, field, value_range, cmap, views, colorbar, timestamp, projection,
                               supersample, label=label)
    renderer.set_surface(poly, grid.snapshot_time)
    renderer.frame_to()
    return renderer.image()


def add_common_options(parser):
    """Options shared by the render and movie commands."""
    parser.add_argument('--field', default='phi', help='point (or cell) field to colour by (default phi)')
    parser.add_argument('--range', help="colour range 'low,high' (default: [-1, 1] for phi, else the data)")
    parser.add_argument('--cmap', help='matplotlib colour map (default coolwarm, viridis for unsigned fields)')
    parser.add_argument('--size', default='800x600', help='picture size WIDTHxHEIGHT in pixels (default 800x600)')
    parser.add_argument('--view', choices=sorted(VIEWS), help='camera preset (default oblique: elev 35, azim -60)')
    parser.add_argument('--elev', type=float, help='camera elevation in degrees')
    parser.add_argument('--azim', type=float, help='camera azimuth in degrees')
    parser.add_argument('--views', help="several views side by side: 'elev,azim;elev,azim'")
    parser.add_argument('--tile', default='1x1', help='periodic copies of the patch, e.g. 3x3 (default 1x1)')
    parser.add_argument('--projection', choices=['perspective', 'parallel'], default='perspective')
    parser.add_argument('--supersample', type=int, default=2, help='render at k times the size and average (anti-aliasing; default 2)')
    parser.add_argument('--no-colorbar', action='store_true')
    parser.add_argument('--no-time', action='store_true', help='leave out the time stamp')
    parser.add_argument('--label', help='text before the time stamp (top left)')
    parser.add_argument('--no-merge', action='store_true', help='keep the per-cell copies of vertices (faceted)')


def options_from(args):
    """Keyword arguments for SurfaceRenderer / render_image from parsed common options."""
    if args.views:
        try:
            views = [tuple(float(v) for v in view.split(',')) for view in args.views.split(';')]
            assert all(len(v) == 2 for v in views)
        except (ValueError, AssertionError):
            raise SystemExit(f"--views: expected 'elev,azim;elev,azim', got '{args.views}'")
    else:
        elev, azim = VIEWS[args.view or 'oblique']
        views = [(args.elev if args.elev is not None else elev, args.azim if args.azim is not None else azim)]
    value_range = None
    if args.range:
        try:
            value_range = tuple(float(v) for v in args.range.split(','))
            assert len(value_range) == 2 and value_range[1] > value_range[0]
        except (ValueError, AssertionError):
            raise SystemExit(f"--range: expected 'low,high' with low < high, got '{args.range}'")
    return dict(field=args.field, value_range=value_range, cmap=args.cmap, views=views,
                tile=parse_pair(args.tile, 'tile'), merge=not args.no_merge, colorbar=not args.no_colorbar,
                timestamp=not args.no_time, projection=args.projection, supersample=args.supersample,
                size=parse_pair(args.size, 'size'), label=args.label)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('input', help='surface.pvd (a series) or a .vtu/.pvtu file')
    parser.add_argument('output', help='PNG file to write')
    parser.add_argument('--time', type=float, help='PVD: the snapshot closest to this time (default: the last)')
    parser.add_argument('--index', type=int, help='PVD: the snapshot with this index (negative: from the end)')
    add_common_options(parser)
    args = parser.parse_args(argv)
    if not os.path.isfile(args.input):
        parser.error(f'{args.input} does not exist (a .vtu, .pvtu or .pvd file of a run)')
    pixels = render_image(args.input, time=args.time, index=args.index, **options_from(args))
    save_png(pixels, args.output)


if __name__ == '__main__':
    main()
