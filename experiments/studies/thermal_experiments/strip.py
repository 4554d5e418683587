#!/usr/bin/python3
"""A strip of snapshots of one run side by side, drawn by the project's renderer
(membrane_flow.pictures.render.render_image), for docs/fluctuations.md ("Experiments").
Usage: strip.py RUN/surface.pvd OUT.png --times 0,0.02,0.05 [--size 300x300] [render options:
--field, --range, --cmap, --elev, --azim, --projection, --no-colorbar]"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', '..', 'python'))
from membrane_flow.pictures.render import render_image, save_png  # noqa: E402


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('pvd')
    p.add_argument('out')
    p.add_argument('--times', required=True)
    p.add_argument('--size', default='300x300')
    p.add_argument('--field', default='phi')
    p.add_argument('--range')
    p.add_argument('--cmap')
    p.add_argument('--elev', type=float, default=20)
    p.add_argument('--azim', type=float, default=-60)
    p.add_argument('--projection', default='perspective')
    p.add_argument('--no-colorbar', action='store_true')
    a = p.parse_args()
    w, h = (int(x) for x in a.size.split('x'))
    value_range = tuple(float(x) for x in a.range.split(',')) if a.range else None
    images = []
    times = [float(t) for t in a.times.split(',')]
    for k, t in enumerate(times):
        images.append(render_image(a.pvd, size=(w, h), time=t, field=a.field, value_range=value_range,
                                   cmap=a.cmap, views=((a.elev, a.azim),), projection=a.projection,
                                   colorbar=(k == len(times) - 1 and not a.no_colorbar)))
    height = max(i.shape[0] for i in images)
    strip = np.concatenate([np.pad(i, ((0, height - i.shape[0]), (0, 0), (0, 0)), constant_values=255)
                            for i in images], axis=1)
    save_png(np.ascontiguousarray(strip), a.out)


if __name__ == '__main__':
    main()
