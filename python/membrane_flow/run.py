"""Reading what a run of membrane-flow wrote into its output directory: the one reader of
statistics.txt, summary.json, run_info.json, parameters.prm, checkpoints' times, the timer
table of log.txt, the PVD series and its VTU files, used by the workflow, the studies, the
pictures, the benchmarks and the docs generators of the package.

Pure Python (numpy; VTK's Python module for the fields of a snapshot): it needs neither
the compiled part of membrane_flow nor MPI.

    run = membrane_flow.load_run('results/default')
    run.statistics['energy']        # columns of statistics.txt as numpy arrays
    run.summary['outcome']          # summary.json
    run.parameters['Material/Line tension']
    run.snapshots                   # [(t, path of the VTU), ...] from surface.pvd
    fields = run.snapshot(-1)       # points, cells and point data of the last snapshot
"""
import json
import os
import re
import xml.etree.ElementTree as ET

import numpy as np


def load_statistics(run_dir):
    """Columns of <run_dir>/statistics.txt as a dict of numpy arrays (in file order)."""
    return read_statistics(os.path.join(run_dir, 'statistics.txt'))


def read_statistics(path):
    """Columns of a statistics file (a '#' header of names, one row per step)."""
    with open(path) as f:
        names = f.readline().lstrip('#').split()
        data = np.loadtxt(f, ndmin=2)
    if data.size == 0:
        data = np.zeros((0, len(names)))
    return {n: data[:, i] for i, n in enumerate(names)}


class FileError(ValueError):
    """A file that cannot be read, or malformed JSON, with the file, line and column."""


def read_json(path, what=None):
    """A JSON file (summary.json, run_info.json, a sweep's case.json, a branch.json, ...).
    With `what` (e.g. 'sweep file'), a hand-written file: any problem is a FileError naming
    the file, and the line and column of a syntax error or a key given twice in one object."""
    if what is None:
        with open(path) as f:
            return json.load(f)
    try:
        with open(path) as f:
            text = f.read()
    except OSError as e:
        raise FileError(f'cannot read {what} {path}: {e.strerror}') from None

    def no_duplicates(pairs):
        seen = {}
        for key, value in pairs:
            if key in seen:
                raise FileError(f'{path}: malformed {what}: the key {key!r} appears twice in one object')
            seen[key] = value
        return seen
    try:
        return json.loads(text, object_pairs_hook=no_duplicates)
    except json.JSONDecodeError as e:
        raise FileError(f'{path}:{e.lineno}:{e.colno}: malformed JSON in {what}: {e.msg}') from None


def load_summary(run_dir):
    """summary.json as a dict."""
    return read_json(os.path.join(run_dir, 'summary.json'))


def load_run_info(run_dir):
    """run_info.json as a dict."""
    return read_json(os.path.join(run_dir, 'run_info.json'))


def checkpoint_time(path):
    """The time of a checkpoint file of membrane-flow (ValueError if it records none)."""
    with open(path) as f:
        for line in f:
            if line.startswith('time '):
                return float(line.split()[1])
            if line.startswith('parameters'):
                break
    raise ValueError(f'{path} is not a checkpoint of membrane-flow (no time)')


def read_timer_table(log):
    """({section: seconds of the slowest rank}, total wall seconds) from the last TimerOutput table
    in the text of a run's log (the table a run prints when it stops)."""
    table = log[log.rindex('Total wallclock time elapsed'):]
    sections = {}
    for line in table.splitlines():
        cells = [c.strip() for c in line.strip().strip('|').split('|')]
        if len(cells) == 5 and cells[1].isdigit():
            sections[cells[0]] = float(cells[4].split()[0].rstrip('s'))
    total = float(re.search(r'Total wallclock time elapsed\s*\|\s*([\d.e+-]+)s', table).group(1))
    return sections, total


def parse_prm(text):
    """The entries of a .prm text as {'Section/Entry': 'value'} (values as strings)."""
    entries, sections = {}, []
    for line in text.splitlines():
        line = line.split('#', 1)[0].strip()
        if not line:
            continue
        words = line.split(None, 1)
        if words[0] == 'subsection':
            sections.append(words[1].strip() if len(words) > 1 else '')
        elif words[0] == 'end':
            sections.pop()
        elif words[0] == 'set' and len(words) > 1:
            name, _, value = words[1].partition('=')
            entries['/'.join(sections + [name.strip()])] = value.strip()
    return entries


def load_parameters(run_dir):
    """parameters.prm (every parameter the run used) as {'Section/Entry': 'value'}."""
    with open(os.path.join(run_dir, 'parameters.prm')) as f:
        return parse_prm(f.read())


def read_pvd(path):
    """The snapshots a PVD file lists, [(t, path of the VTU), ...] in order of time; the paths
    are those of the PVD joined with its directory."""
    root = ET.parse(path).getroot()
    series = [(float(d.get('timestep')), os.path.join(os.path.dirname(path), d.get('file')))
              for d in root.iter('DataSet')]
    return sorted(series, key=lambda s: s[0])


def load_snapshots(run_dir, pvd='surface.pvd'):
    """The snapshots listed in the PVD file as [(t, absolute path of the VTU), ...]."""
    return read_pvd(os.path.join(os.path.abspath(run_dir), pvd))


def read_grid(path):
    """The VTK unstructured grid of a .vtu or .pvtu file (FileNotFoundError, or ValueError
    when VTK reads no cells from it)."""
    from vtkmodules.vtkIOXML import vtkXMLPUnstructuredGridReader, vtkXMLUnstructuredGridReader

    if not os.path.isfile(path):
        raise FileNotFoundError(f"no snapshot file <{path}>")
    reader = vtkXMLPUnstructuredGridReader() if path.endswith('.pvtu') else vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if grid is None or grid.GetNumberOfPoints() == 0 or grid.GetNumberOfCells() == 0:
        raise ValueError(f"<{path}> holds no unstructured grid that VTK can read")
    return grid


def grid_time(grid, fallback=None):
    """The TIME field data of a grid (written by the simulator, single precision), else `fallback`."""
    array = grid.GetFieldData().GetArray('TIME')
    return float(array.GetTuple1(0)) if array is not None and array.GetNumberOfTuples() else fallback


def read_vtu(path):
    """Points, cells and point data of a VTU (or PVTU) file, read with VTK.

    Returns a dict: 'points' (n x 3), 'cells' (n_cells x vertices per cell, indices into
    points), 'point_data' {name: array}, 'cell_data' {name: array}, and 'time' if the file
    records one (VTK field data TIME, single precision in deal.II's files)."""
    from vtkmodules.util.numpy_support import vtk_to_numpy

    grid = read_grid(path)
    points = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
    n_cells = grid.GetNumberOfCells()
    connectivity = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).astype(np.int64)
    offsets = vtk_to_numpy(grid.GetCells().GetOffsetsArray()).astype(np.int64)
    sizes = np.diff(offsets)
    if n_cells and np.all(sizes == sizes[0]):
        cells = connectivity.reshape(n_cells, sizes[0])
    else:
        cells = [connectivity[offsets[i]:offsets[i + 1]] for i in range(n_cells)]

    def arrays(data):
        return {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i)).copy()
                for i in range(data.GetNumberOfArrays()) if data.GetArray(i) is not None}

    result = {'points': points, 'cells': cells, 'point_data': arrays(grid.GetPointData()),
              'cell_data': arrays(grid.GetCellData())}
    time = grid_time(grid)
    if time is not None:
        result['time'] = time
    return result


class Run:
    """A finished (or running) run's output directory. Each file is read on first use."""

    def __init__(self, directory):
        if not os.path.isdir(directory):
            raise FileNotFoundError(f"no run directory <{directory}>")
        self.directory = directory
        self._cache = {}

    def _get(self, key, load):
        if key not in self._cache:
            self._cache[key] = load(self.directory)
        return self._cache[key]

    @property
    def statistics(self):
        """statistics.txt: {column: numpy array}, one entry per accepted step (and t = 0)."""
        return self._get('statistics', load_statistics)

    @property
    def summary(self):
        return self._get('summary', load_summary)

    @property
    def run_info(self):
        return self._get('run_info', load_run_info)

    @property
    def parameters(self):
        """parameters.prm: {'Section/Entry': 'value'}, every entry the run used."""
        return self._get('parameters', load_parameters)

    @property
    def snapshots(self):
        """[(t, path), ...] of the snapshots in surface.pvd."""
        return self._get('snapshots', load_snapshots)

    @property
    def times(self):
        return np.array([t for t, _ in self.snapshots])

    def snapshot(self, index=-1):
        """The fields of a snapshot (see read_vtu): by position in the series
        (an int, negative from the end) or the one closest to a time (a float)."""
        series = self.snapshots
        if not series:
            raise ValueError(f"<{self.directory}> lists no snapshots")
        if isinstance(index, float):
            index = int(np.argmin([abs(t - index) for t, _ in series]))
        fields = read_vtu(series[index][1])
        fields['time'], fields['file'] = series[index]  # the PVD's time (the VTU's is single precision)
        return fields

    def __repr__(self):
        return f"Run({self.directory!r})"


def load_run(directory):
    """A run's output directory (see Run)."""
    return Run(directory)
