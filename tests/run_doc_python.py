#!/usr/bin/python3
"""Run the ```python blocks of a Markdown page in order, in one namespace, as a notebook
would, from a scratch directory in which `experiments/` is the repository's.
Usage: run_doc_python.py <page.md> <scratch directory>
Fails (exit 1) if the page has no python block or any block raises."""
import os
import re
import shutil
import sys
import traceback

page, scratch = os.path.abspath(sys.argv[1]), sys.argv[2]
repository = os.path.dirname(os.path.dirname(page))
with open(page) as f:
    blocks = re.findall(r'^```python\n(.*?)^```', f.read(), flags=re.S | re.M)
if not blocks:
    sys.exit(f"{page}: no ```python blocks")

shutil.rmtree(scratch, ignore_errors=True)  # a fresh start, as for a new user
os.makedirs(scratch)
os.chdir(scratch)
link = 'experiments'
if not os.path.islink(link):
    os.symlink(os.path.join(repository, 'experiments'), link)
os.environ.setdefault('MPLBACKEND', 'Agg')

namespace = {'__name__': '__main__'}
for number, code in enumerate(blocks, 1):
    print(f"--- block {number} of {len(blocks)} ---\n{code}", flush=True)
    try:
        exec(compile(code, f"{os.path.basename(page)} block {number}", 'exec'), namespace)
    except Exception:
        traceback.print_exc()
        sys.exit(f"block {number} of {page} failed")
print(f"OK: {len(blocks)} blocks of {page} ran")
