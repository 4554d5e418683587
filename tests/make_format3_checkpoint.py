#!/usr/bin/python3
"""Write a copy of a checkpoint in format 3 (before the last step's increments were kept):
the vertex lines without their last four values (increment of X and of phi), and without the
scalars that came with format 4.
Usage: make_format3_checkpoint.py <checkpoint.txt> <out.txt>"""
import os
import sys

source, out = sys.argv[1], sys.argv[2]
lines = open(source).read().split('\n')
assert lines[0] == 'membrane-checkpoint 4', f'{source} is not a checkpoint of format 4'
new_scalars = ('previous_tau', 'error_rejection_tau', 'error_rejection_estimate')
result, vertices = ['membrane-checkpoint 3'], 0
for line in lines[1:]:
    words = line.split()
    if vertices:
        result.append(' '.join(words[:8]))
        vertices -= 1
        continue
    if words and words[0] in new_scalars:
        continue
    if words and words[0] == 'vertices':
        vertices = int(words[1])
    result.append(line)
os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
open(out, 'w').write('\n'.join(result))
