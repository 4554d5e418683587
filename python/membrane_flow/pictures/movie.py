#!/usr/bin/python3
"""Render every snapshot of a PVD series and encode an MP4 movie (H.264, with ffmpeg).

Usage: python3 -m membrane_flow movie <surface.pvd> <out.mp4> [--fps 12] [--size 800x600] [--every K]
                                            [--from T0] [--to T1] [--hold SECONDS] [render options]

One frame per snapshot (or per K-th snapshot), each with its time stamp. The camera and the
colour range are the same in every frame: the camera frames all snapshots together, and the
colour range is [-1, 1] for phi (else the range over all snapshots, or --range). The render
options (--field, --view, --elev/--azim, --views, --tile, --projection, --cmap, --label, ...) are
those of the render command. Headless: without a DISPLAY the command starts its own Xvfb."""
import argparse
import os
import shutil
import subprocess
import sys

import numpy as np

from vtkmodules.util.numpy_support import vtk_to_numpy

from .render import (SurfaceRenderer, add_common_options, default_range, field_values, grid_time, options_from,
                     read_grid, snapshots, surface_polydata)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('input', help='surface.pvd of a run')
    parser.add_argument('output', help='MP4 file to write')
    parser.add_argument('--fps', type=float, default=12, help='frames per second (default 12)')
    parser.add_argument('--every', type=int, default=1, help='use every K-th snapshot (default 1; the last is always used)')
    parser.add_argument('--from', dest='start', type=float, help='first time (default: the first snapshot)')
    parser.add_argument('--to', dest='end', type=float, help='last time (default: the last snapshot)')
    parser.add_argument('--hold', type=float, default=1.0, help='show the last frame this many seconds longer (default 1)')
    parser.add_argument('--crf', type=int, default=23, help='H.264 quality, lower is better and larger (default 23)')
    add_common_options(parser)
    args = parser.parse_args(argv)
    if not os.path.isfile(args.input):
        parser.error(f'{args.input} does not exist (the surface.pvd of a run)')
    if not args.input.endswith('.pvd'):
        raise SystemExit('membrane_flow movie needs a PVD series (surface.pvd)')
    if shutil.which('ffmpeg') is None:
        raise SystemExit('ffmpeg not found: install it (scripts/install_dependencies.sh)')
    if args.fps <= 0 or args.every < 1:
        raise SystemExit('--fps must be positive and --every at least 1')
    options = options_from(args)
    # H.264 in yuv420p needs even sizes
    width, height = (v + v % 2 for v in options.pop('size'))
    tile, merge = options.pop('tile'), options.pop('merge')

    series = [s for s in snapshots(args.input)
              if (args.start is None or s[0] >= args.start - 1e-12) and (args.end is None or s[0] <= args.end + 1e-12)]
    if not series:
        raise SystemExit('no snapshots in the requested time interval')
    chosen = series[::args.every]
    if chosen[-1] is not series[-1]:
        chosen.append(series[-1])

    # First pass: the surfaces, the points of all of them (for one camera) and the value range.
    surfaces = []
    for t, path in chosen:
        grid = read_grid(path)
        surfaces.append((surface_polydata(grid, tile, merge), grid_time(grid, t)))
    if options['value_range'] is None:
        values = np.concatenate([field_values(poly, options['field'])[0] for poly, _ in surfaces])
        options['value_range'] = default_range(options['field'], values)
    all_points = np.concatenate([vtk_to_numpy(poly.GetPoints().GetData()) for poly, _ in surfaces])
    renderer = SurfaceRenderer((width, height), **options)
    renderer.set_surface(*surfaces[0])
    renderer.frame_to(all_points)

    partial = args.output + '.partial.mp4'
    os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
    encoder = subprocess.Popen(
        ['ffmpeg', '-hide_banner', '-loglevel', 'error', '-y', '-f', 'rawvideo', '-pix_fmt', 'rgb24',
         '-s', f'{width}x{height}', '-r', str(args.fps), '-i', '-', '-c:v', 'libx264', '-preset', 'medium',
         '-crf', str(args.crf), '-pix_fmt', 'yuv420p', '-movflags', '+faststart', '-f', 'mp4', partial],
        stdin=subprocess.PIPE)
    try:
        for k, (poly, t) in enumerate(surfaces):
            renderer.set_surface(poly, t)
            frame = renderer.image().tobytes()
            repeats = 1 + (int(round(args.hold * args.fps)) if k == len(surfaces) - 1 else 0)
            for _ in range(repeats):
                encoder.stdin.write(frame)
            if sys.stderr.isatty():
                print(f'\rframe {k + 1}/{len(surfaces)}  t = {t:.4g}', end='', file=sys.stderr, flush=True)
        encoder.stdin.close()
    except BrokenPipeError:
        pass
    if sys.stderr.isatty():
        print(file=sys.stderr)
    if encoder.wait() != 0:
        if os.path.exists(partial):
            os.remove(partial)
        raise SystemExit('ffmpeg failed')
    os.replace(partial, args.output)
    print(f'{args.output}: {len(surfaces)} snapshots, {width}x{height}, {args.fps:g} frames/s, '
          f'{os.path.getsize(args.output) / 1e6:.2f} MB')


if __name__ == '__main__':
    main()
