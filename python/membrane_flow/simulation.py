"""A run of membrane-flow driven from Python: the same time loop as the program."""
import os

from . import _core
from .run import parse_prm

Error = _core.Error


def _entry_value(value):
    """A Python value as the text of a parameter entry."""
    if isinstance(value, bool):
        return 'true' if value else 'false'
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, (int, str)):
        return str(value)
    if isinstance(value, (list, tuple)):
        return ', '.join(_entry_value(v) for v in value)
    raise TypeError(f"parameter value {value!r} of type {type(value).__name__}: "
                    "give a number, a bool, a string or a list of them")


class Simulation:
    """A run: its mesh, state and output directory.

    Simulation(input=None, parameters=None, output_directory=None, overwrite=False, quiet=True)

    input             a .prm file (optional; entries left out take their defaults)
    parameters        {'Section/Entry': value} overriding the file, as --set does
    output_directory  Output/Directory (else the one of the file or the dict)
    overwrite         delete the output files of an earlier run there first (--overwrite)
    quiet             no progress lines and no timing table (--quiet)

    The constructor sets up the mesh and the initial state (t = 0) and writes the first
    statistics row and snapshot. Bad input raises membrane_flow.Error with the message the
    program prints. finish() (or leaving a `with` block, or run()) writes summary.json.
    """

    def __init__(self, input=None, parameters=None, output_directory=None, overwrite=False, quiet=True):
        if input is not None and not isinstance(input, (str, os.PathLike)):
            raise TypeError("input is the path of a .prm file; give entries as parameters={...}")
        entries = [(str(k), _entry_value(v)) for k, v in (parameters or {}).items()]
        if output_directory is not None:
            entries.append(('Output/Directory', os.fspath(output_directory)))
        self._sim = _core.Simulation(os.fspath(input) if input is not None else '', entries, bool(overwrite),
                                     bool(quiet))

    # -- the time loop ---------------------------------------------------------------
    def step(self):
        """One accepted time step (rejected trial steps are retried with a smaller tau).
        Returns False, doing nothing, once the run has stopped (see result)."""
        return self._sim.step()

    def advance(self, n):
        """Up to n accepted steps; returns how many were taken."""
        return self._sim.advance(int(n))

    def run_until(self, t):
        """Accepted steps until the time reaches t (the last step may pass it; the step
        size is the run's own) or the run stops; returns the number of steps."""
        return self._sim.run_until(float(t))

    def run(self):
        """Steps until the run stops (end time, maximum steps, a stop rule), then finish()."""
        return self._sim.run()

    def finish(self):
        """Writes the last snapshot, statistics.txt and summary.json; returns result.
        The state stays readable; no further steps are taken."""
        return self._sim.finish()

    def close(self):
        """finish() and free the simulator; the object cannot be used afterwards."""
        self._sim.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    # -- where the run is ------------------------------------------------------------
    @property
    def time(self):
        return self._sim.time()

    @property
    def steps(self):
        """Accepted steps so far."""
        return self._sim.steps()

    @property
    def tau(self):
        """The time step the next trial step will try."""
        return self._sim.tau()

    @property
    def stopped(self):
        return self._sim.stopped()

    @property
    def result(self):
        """{'stop_reason', 'failed', 'outcome'}; stop_reason is '' while the run goes on,
        outcome is set by finish()."""
        return self._sim.result()

    @property
    def energies(self):
        """The free energy and its terms at the current step, named as in statistics.txt."""
        return self._sim.energies()

    @property
    def energy(self):
        return self._sim.energies()['energy']

    def statistics(self):
        """Every statistics row so far (the columns of statistics.txt) as {name: numpy array}."""
        return self._sim.statistics()

    def statistics_frame(self):
        """statistics() as a pandas DataFrame (needs pandas)."""
        import pandas
        return pandas.DataFrame(self.statistics())

    @property
    def output_directory(self):
        return self._sim.output_directory()

    @property
    def parameter_text(self):
        """Every parameter the run uses, as written to parameters.prm."""
        return self._sim.parameter_text()

    @property
    def parameters(self):
        """Every parameter the run uses as {'Section/Entry': 'value'}."""
        return parse_prm(self._sim.parameter_text())

    # -- the state as numpy arrays (copies), one row per vertex ----------------------
    @property
    def positions(self):
        """Vertex positions X = X_ref + D (n_vertices x 3). On the periodic patch the
        vertices on the edges u = 1 are the periodic copies of those on u = 0."""
        return self._sim.positions()

    @property
    def cells(self):
        """Vertex indices of each cell (n_cells x 4), counter-clockwise (VTK_QUAD order)."""
        return self._sim.cells()

    def field(self, name):
        """A vertex field by name: phi, Y, gamma, H, K, vertex_area (n_vertices),
        normal, displacement (n_vertices x 3)."""
        return self._sim.field(name)

    @property
    def phi(self):
        """The order parameter (+1 phase A, -1 phase B)."""
        return self._sim.field('phi')

    @property
    def Y(self):
        """The chemical potential of the Cahn-Hilliard step."""
        return self._sim.field('Y')

    @property
    def gamma(self):
        """The surface pressure of the shape step (the Lagrange multiplier of the local
        area constraint; 'gamma' in the VTU files and statistics)."""
        return self._sim.field('gamma')

    @property
    def H(self):
        """Mean curvature (sum of the principal curvatures)."""
        return self._sim.field('H')

    @property
    def K(self):
        """Gaussian curvature."""
        return self._sim.field('K')

    @property
    def normals(self):
        return self._sim.field('normal')

    @property
    def displacement(self):
        return self._sim.field('displacement')

    @property
    def vertex_areas(self):
        """The area a_i carried by each vertex: integral phi ds = sum(phi * vertex_areas).
        Periodic copies and hanging vertices carry 0 (their share is in their master)."""
        return self._sim.field('vertex_area')

    def __repr__(self):
        if not self._sim.is_open():
            return "Simulation(closed)"
        return (f"Simulation({self.output_directory!r}, step {self.steps}, t = {self.time:.6g}, "
                f"energy {self.energy:.6g})")
