#!/usr/bin/python3
"""Write a copy of a checkpoint of the periodic patch in which every vertex on the periodic edges
(u_1 = 0 or u_2 = 0) is written as its image on the opposite edge (u_k = 1), as a checkpoint reads
when the other copy of those vertices carried the dofs at the time it was written (after a mesh
that refined and coarsened). Resuming from it must continue exactly as from the original.
Usage: make_periodic_image_checkpoint.py <checkpoint.txt> <out.txt>"""
import os
import sys

source, out = sys.argv[1], sys.argv[2]
lines = open(source).read().split('\n')
assert lines[0].startswith('membrane-checkpoint'), f'{source} is not a checkpoint'
result, vertices, moved = [], 0, 0
for line in lines:
    words = line.split()
    if vertices:
        vertices -= 1
        x, y = float(words[0]), float(words[1])
        if x == 0 or y == 0:
            words[0], words[1] = ('1' if x == 0 else words[0]), ('1' if y == 0 else words[1])
            moved += 1
        result.append(' '.join(words))
        continue
    if words and words[0] == 'vertices':
        vertices = int(words[1])
    result.append(line)
assert moved > 0, 'no vertex on the periodic edges'
os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
open(out, 'w').write('\n'.join(result))
print(f'{moved} vertices written as their periodic images')
