#!/usr/bin/python3
"""Check the VTK surface renderer (python3 -m membrane_flow render, membrane_flow/pictures/render.py)
and the movie command (python3 -m membrane_flow movie) on synthetic surfaces whose pictures are
known, by pixel colours. membrane_flow must be importable (PYTHONPATH=<build>/python).

Usage: check_render.py                        synthetic checks (files in ./render_check)
       check_render.py <surface.pvd> <out.png>  a run's last snapshot: size, both phases

Synthetic checks, each on VTU files written here in both layouts the simulator may write
(every vertex stored once per cell with a `displacement` field, as deal.II writes them, and
shared vertices without it):
  halves      flat patch, phi = +1 for x < 1/2, -1 for x > 1/2, top view: the left half of the
              patch is red, the right half blue, the patch square and tight in its view, and
              the background white around it;
  layouts     the two layouts give the same picture, and from the side the egg-crate
              z = 0.15 cos(2 pi x) cos(2 pi y) is 0.3 high for 1 wide (the displacement is not
              applied again);
  depth       from the side, a low blue ridge in front hides the lower part of a higher red
              ridge behind it, whose top shows above it (z-buffer order);
  shading     a curved patch z = 0.15 cos(2 pi x) on 6 x 6 cells: along a row of pixels the
              shade varies continuously (points merged, normals averaged) whereas the same
              picture without merging jumps at the cell edges;
  colours     phi = cos(2 pi x) on 4 x 4 cells: the colour varies inside each cell
              (interpolated at points, not one colour per cell) and without jumps;
  tile, time  --tile 2x2 from the command line shows red, blue, red, blue across the picture
              at the requested size, with a time stamp (dark pixels top left) unless --no-time;
  movie       the movie command encodes one H.264 frame per snapshot at the requested size."""
import json
import os
import subprocess
import sys

import numpy as np

import membrane_flow.pictures.render as rs  # noqa: E402
from checks import NARROW, Checks  # tests/checks.py, next to this script
from synthetic_vtu import write_pvd, write_vtu  # tests/synthetic_vtu.py

python = sys.executable
check = Checks(*NARROW)


def picture(path, size=(400, 400), **options):
    """Render `path` from the top (x to the right, y up) in parallel projection; float RGB 0..255."""
    options.setdefault('views', [rs.VIEWS['top']])
    options.setdefault('projection', 'parallel')
    return rs.render_image(path, size=size, **options).astype(float)


def patch_box(image, width):
    """Bounding box (rows, columns) of the coloured (non-grey) pixels in the first `width` columns."""
    part = image[:, :width]
    coloured = part.max(axis=2) - part.min(axis=2) > 40
    rows, cols = np.nonzero(coloured)
    return rows.min(), rows.max(), cols.min(), cols.max()


def is_red(p):
    return (p[..., 0] > 120) & (p[..., 0] - p[..., 2] > 80) & (p[..., 0] - p[..., 1] > 80)


def is_blue(p):
    return (p[..., 2] > 120) & (p[..., 2] - p[..., 0] > 60)


def is_background(p):
    return np.all(p > 245, axis=-1)


def run_on(pvd, png):
    """The older check on a simulator run: requested size, both phases visible."""
    import matplotlib.image as mpimg
    subprocess.run([python, '-m', 'membrane_flow', 'render', pvd, png, '--size', '640x480'], check=True)
    image = mpimg.imread(png)[:, :, :3] * 255
    check(image.shape[:2] == (480, 640), f'picture size {image.shape[1]}x{image.shape[0]} is 640x480')
    surface = image[:, :int(0.8 * 640)]  # the colour bar holds both colours whatever the surface shows
    red, blue = is_red(surface).sum(), is_blue(surface).sum()
    check(red > 200 and blue > 200, f'both phases visible: {red} red and {blue} blue pixels')


def synthetic():
    os.makedirs('render_check', exist_ok=True)
    os.chdir('render_check')
    halves = lambda x, y: np.where(x < 0.5 - 1e-9, 1.0, np.where(x > 0.5 + 1e-9, -1.0, 0.0))  # noqa: E731
    flat = lambda x, y: np.zeros_like(x)  # noqa: E731
    wave = lambda x, y: 0.15 * np.cos(2 * np.pi * x)  # noqa: E731
    for per_cell, suffix in ((True, 'cells'), (False, 'shared')):
        write_vtu(f'halves-{suffix}.vtu', 16, flat, halves, per_cell, 0.25)
        write_vtu(f'wave-{suffix}.vtu', 6, wave, lambda x, y: np.full_like(x, 0.8), per_cell, 0.5)
        write_vtu(f'cosine-{suffix}.vtu', 4, flat, lambda x, y: np.cos(2 * np.pi * x), per_cell, 0.0)
        write_vtu(f'ridges-{suffix}.vtu', 32,
                  lambda x, y: 0.2 * np.exp(-((y - 0.3) / 0.07) ** 2) + 0.3 * np.exp(-((y - 0.7) / 0.07) ** 2),
                  lambda x, y: np.where(y < 0.5, -1.0, 1.0), per_cell, 0.0)
        write_vtu(f'crate-{suffix}.vtu', 12, lambda x, y: 0.15 * np.cos(2 * np.pi * x) * np.cos(2 * np.pi * y),
                  lambda x, y: np.full_like(x, 0.8), per_cell, 0.0)

    # halves: phases where they must be, tight square framing, white background
    size = 400
    image = picture('halves-cells.vtu', (size, size))
    bar_width = int(round(size * rs.colorbar_fraction(size)))
    view_width = size - bar_width
    r0, r1, c0, c1 = patch_box(image, view_width)
    w, h = c1 - c0 + 1, r1 - r0 + 1
    print(f'      patch at rows {r0}-{r1}, columns {c0}-{c1} of the {view_width} x {size} view')
    check(abs(w - h) <= 2, f'the unit square is drawn square ({w} x {h} pixels)')
    check(w >= 0.85 * min(view_width, size * 0.85), f'tight framing: the patch spans {w} of {view_width} pixels')
    rows = slice(r0 + h // 10, r1 - h // 10)
    left = image[rows, c0 + w // 20: c0 + 2 * w // 5]
    right = image[rows, c0 + 3 * w // 5: c1 - w // 20]
    check(is_red(left).all(), f'phase A (x < 1/2) red: {is_red(left).mean():.1%} of {left.shape[0] * left.shape[1]} pixels, '
          f'mean colour {left.reshape(-1, 3).mean(axis=0).round()}')
    check(is_blue(right).all(), f'phase B (x > 1/2) blue: {is_blue(right).mean():.1%} of {right.shape[0] * right.shape[1]} '
          f'pixels, mean colour {right.reshape(-1, 3).mean(axis=0).round()}')
    # around the patch (2 pixels off its edges), less the time stamp's corner (top left)
    outside = np.ones(image.shape[:2], bool)
    outside[max(r0 - 2, 0): r1 + 3, max(c0 - 2, 0): c1 + 3] = False
    outside[:, view_width:] = False
    outside[: r0 - 2, : view_width // 2] = False
    check(outside.sum() > 1000 and is_background(image[outside]).all(),
          f'background white around the patch ({is_background(image[outside]).mean():.1%} of {outside.sum()} pixels)')
    stamp = image[: r0, : view_width // 2]
    dark = (stamp.max(axis=2) < 100).sum()
    check(dark > 30, f'time stamp drawn above the patch ({dark} dark pixels)')
    no_stamp = picture('halves-cells.vtu', (size, size), timestamp=False)[: r0, : view_width // 2]
    check((no_stamp.max(axis=2) < 100).sum() == 0, 'no dark pixels there with the time stamp off')

    # layouts: per-cell points with displacement == shared points without it
    for name in ('halves', 'wave'):
        a = picture(f'{name}-cells.vtu')
        b = picture(f'{name}-shared.vtu')
        difference = np.abs(a - b).mean()
        check(difference < 1.0, f'{name}: per-cell and shared layouts agree (mean difference {difference:.2f} levels)')

    # geometry: from the side (parallel projection) the egg-crate z = 0.15 cos(2 pi x) cos(2 pi y)
    # spans 0.3 in height for 1 in width; applying the displacement field again would double it
    for name in ('crate-cells', 'crate-shared'):
        image = picture(f'{name}.vtu', views=[rs.VIEWS['side']], timestamp=False)
        r0, r1, c0, c1 = patch_box(image, view_width)
        ratio = (r1 - r0 + 1) / (c1 - c0 + 1)
        check(abs(ratio - 0.3) < 0.03, f'{name}: side view height / width = {ratio:.3f} (expected 0.30: points not displaced twice)')

    # depth order: from the side (-y), the lower blue ridge (y = 0.3, height 0.2) stands in front
    # of the higher red one (y = 0.7, height 0.3): below z = 0.2 the blue ridge must hide the red
    image = picture('ridges-cells.vtu', views=[rs.VIEWS['side']], timestamp=False)
    r0, r1, c0, c1 = patch_box(image, view_width)
    column = image[:, (c0 + c1) // 2]
    at = lambda z: column[int(round(r1 - z / 0.3 * (r1 - r0)))]  # noqa: E731
    low, high = at(0.1), at(0.26)
    check(is_blue(low) and is_red(high), f'depth order: at z = 0.1 the front ridge (blue) {low.round()}, '
          f'at z = 0.26 the back ridge above it (red) {high.round()}')

    # shading: continuous across cells once merged, faceted without merging
    def row_jumps(image):
        r0, r1, c0, c1 = patch_box(image, view_width)
        row = image[(r0 + r1) // 2, c0 + 3: c1 - 2].mean(axis=1)
        return np.abs(np.diff(row)), np.ptp(row)
    view = [(60.0, -90.0)]
    merged, spread = row_jumps(picture('wave-cells.vtu', views=view))
    faceted, _ = row_jumps(picture('wave-cells.vtu', views=view, merge=False))
    check(spread > 20, f'the curved patch is shaded (brightness spread {spread:.0f} levels along the row)')
    check(merged.max() < 6, f'merged points: smooth shading, largest step between neighbouring pixels {merged.max():.1f} levels')
    check(faceted.max() > 3 * merged.max() + 6,
          f'(the check sees facets: without merging the largest step is {faceted.max():.1f} levels)')

    # colours: interpolated inside the cells, no jumps
    image = picture('cosine-cells.vtu')
    r0, r1, c0, c1 = patch_box(image, view_width)
    row = image[(r0 + r1) // 2, c0 + 2: c1 - 1]
    contrast = row[:, 0] - row[:, 2]  # red minus blue: increases with phi
    cell = len(row) // 4
    inside = contrast[int(0.2 * cell): int(0.8 * cell)]  # inside the first cell, phi from ~0.95 to ~0.3
    check(inside[0] - inside[-1] > 40, f'colour varies inside a cell: red-blue contrast {inside[0]:.0f} -> {inside[-1]:.0f}')
    step = np.abs(np.diff(row, axis=0)).max()
    check(step < 10, f'no colour jumps at cell edges: largest step between neighbouring pixels {step:.0f} levels')
    middle = row[2 * cell - 3: 2 * cell + 4]  # around x = 1/2, phi = -1
    check(is_blue(middle).all(), 'phi = -1 at x = 1/2 is blue')

    # command line: --tile, --size, a PVD and its last snapshot, the time stamp
    write_pvd('halves.pvd', [(0.0, 'halves-shared.vtu'), (0.25, 'halves-cells.vtu')])
    subprocess.run([python, '-m', 'membrane_flow', 'render', 'halves.pvd', 'tiled.png', '--size', '500x300',
                    '--tile', '2x2', '--view', 'top', '--projection', 'parallel'], check=True)
    import matplotlib.image as mpimg
    image = mpimg.imread('tiled.png')[:, :, :3] * 255
    check(image.shape[:2] == (300, 500), f'--size 500x300 gives {image.shape[1]}x{image.shape[0]}')
    view_width = 500 - int(round(500 * rs.colorbar_fraction(500)))
    r0, r1, c0, c1 = patch_box(image, view_width)
    w = c1 - c0 + 1
    samples = [image[(r0 + r1) // 2, int(c0 + f * w)] for f in (0.125, 0.375, 0.625, 0.875)]
    pattern = ''.join('R' if is_red(p) else 'B' if is_blue(p) else '?' for p in samples)
    check(pattern == 'RBRB', f'--tile 2x2 shows the periodic copies across x: {pattern} (expected RBRB)')

    # movie: one frame per snapshot
    write_pvd('series.pvd', [(0.0, 'cosine-cells.vtu'), (0.25, 'halves-cells.vtu'), (0.5, 'wave-cells.vtu')])
    subprocess.run([python, '-m', 'membrane_flow', 'movie', 'series.pvd', 'series.mp4', '--size', '321x240',
                    '--fps', '4', '--hold', '0'], check=True)
    probe = subprocess.run(['ffprobe', '-v', 'error', '-count_frames', '-select_streams', 'v:0', '-show_entries',
                            'stream=codec_name,width,height,nb_read_frames', '-of', 'json', 'series.mp4'],
                           check=True, capture_output=True, text=True)
    stream = json.loads(probe.stdout)['streams'][0]
    check(stream['codec_name'] == 'h264' and int(stream['nb_read_frames']) == 3
          and (stream['width'], stream['height']) == (322, 240),
          f"movie: {stream['codec_name']}, {stream['nb_read_frames']} frames, {stream['width']}x{stream['height']} "
          '(expected h264, 3 frames, 322x240: widths are made even)')


if len(sys.argv) == 3:
    run_on(sys.argv[1], sys.argv[2])
else:
    synthetic()
if check.failures:
    sys.exit(f'{check.failed} check(s) failed')
print('all checks passed')
