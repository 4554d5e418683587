#!/usr/bin/python3
"""Write the parameter manual (Markdown): `python3 -m membrane_flow parameter-manual` under the
name that docs/parameters.md gives as its generator.
Usage: make_parameter_manual.py <membrane-flow executable> <output.md>"""
import os
import sys

if len(sys.argv) != 3:
    sys.exit(__doc__)
python = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'python')
env = dict(os.environ, PYTHONPATH=os.pathsep.join([python] + [p for p in [os.environ.get('PYTHONPATH')] if p]))
os.execve(sys.executable, [sys.executable, '-m', 'membrane_flow', 'parameter-manual', sys.argv[2],
                           '--exe', sys.argv[1]], env)
