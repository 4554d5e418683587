#!/usr/bin/python3
"""Write damaged copies of a good checkpoint: <out>/nan.txt (one vertex value NaN) and
<out>/truncated.txt (cut off inside its statistics).
Usage: make_bad_checkpoints.py <checkpoint.txt> <out dir>"""
import os
import sys

source, out = sys.argv[1], sys.argv[2]
os.makedirs(out, exist_ok=True)
lines = open(source).read().split('\n')
first_vertex = next(i for i, line in enumerate(lines) if line.startswith('vertices')) + 1
words = lines[first_vertex].split()
words[6] = 'nan'  # phi of the first vertex (x y z D D D phi area)
damaged = lines[:first_vertex] + [' '.join(words)] + lines[first_vertex + 1:]
open(os.path.join(out, 'nan.txt'), 'w').write('\n'.join(damaged))
text = '\n'.join(lines)
open(os.path.join(out, 'truncated.txt'), 'w').write(text[:len(text) - 200])
