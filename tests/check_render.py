#!/usr/bin/python3
"""Render a run's last snapshot and check the PNG: requested size, and both
phases visible in different colours (red for phi = +1, blue for phi = -1).
Usage: check_render.py <render script> <surface.pvd> <out.png>"""
import subprocess
import sys

import matplotlib.image as mpimg
import numpy as np

script, pvd, png = sys.argv[1:4]
subprocess.run(['/usr/bin/python3', script, pvd, png, '--size', '640x480'], check=True)
image = mpimg.imread(png)[:, :, :3]
assert image.shape[:2] == (480, 640), f"size {image.shape[1]}x{image.shape[0]}, expected 640x480"
# The colour bar (right quarter) holds both colours whatever the surface shows: leave it out.
image = image[:, : int(0.75 * image.shape[1])]
# coolwarm: phi > 0 red-dominated, phi < 0 blue-dominated; white background and grey text are neither.
red = np.sum(image[:, :, 0] > image[:, :, 2] + 0.25)
blue = np.sum(image[:, :, 2] > image[:, :, 0] + 0.25)
print(f"{red} red pixels (phase A), {blue} blue pixels (phase B)")
assert red > 200 and blue > 200, "both phases must be visible"
