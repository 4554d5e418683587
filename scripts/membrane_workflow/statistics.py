"""Reading a run's statistics.txt and summary.json."""
import json
import os

import numpy as np


def load_statistics(run_dir):
    """Columns of statistics.txt as a dict of numpy arrays."""
    with open(os.path.join(run_dir, 'statistics.txt')) as f:
        names = f.readline().lstrip('#').split()
        data = np.atleast_2d(np.loadtxt(f))
    return {n: data[:, i] for i, n in enumerate(names)}


def load_summary(run_dir):
    with open(os.path.join(run_dir, 'summary.json')) as f:
        return json.load(f)
