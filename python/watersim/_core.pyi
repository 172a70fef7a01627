"""Type stub of the compiled extension ``watersim._core`` (crates/sph-py).

Units are SI throughout: metres, seconds, kg/m^3, pascals.
"""

from typing import Any

import numpy as np
import numpy.typing as npt

class SceneError(ValueError):
    """A scene refused before anything runs; the message reads ``field.path: reason``."""

class InstabilityError(RuntimeError):
    """A run stopped by a stability monitor (NaN/inf, runaway density, ...)."""

    kind: str
    """Which monitor fired, e.g. ``"non_finite"`` or ``"density_out_of_range"``."""
    step: int
    time: float
    """Simulated time [s]."""
    particle: int
    """Original id of the offending particle."""
    position: list[float]
    """Where the particle was [m]."""

def resolve_scene(scene_json: str) -> str:
    """The scene as the core runs it: checked (``SceneError`` naming the field) and returned as
    JSON with every default filled in."""

def scene_defaults() -> dict[str, Any]:
    """The core's default of every optional scene key, as nested dicts laid out as the scene:
    ``scene_defaults()["viscosity"]["nu"]`` is the default of ``viscosity.nu``. A table holds
    its default model and the parameters of every model; ``shifting`` and ``damping``, off by
    default, hold their parameters' defaults for when they are on. (``Defaults`` in
    ``crates/sph-core/src/scene/defaults.rs``.)"""

class Simulation:
    """A WCSPH simulation built from a scene in its JSON form.

    ``step`` and ``run`` release the GIL. While one thread steps, every other call from another
    thread raises ``RuntimeError`` at once, except ``snapshot()``; NumPy views taken before
    (``positions``, ``velocities``, ``densities``, ``kinds``, ``ids``) alias the arrays the step
    writes, so reading them then gives a torn mixture of two states: use ``snapshot()``.
    """
    def __init__(self, scene_json: str) -> None: ...
    @property
    def dim(self) -> int: ...
    @property
    def n_particles(self) -> int: ...
    @property
    def n_fluid(self) -> int: ...
    @property
    def n_boundary(self) -> int: ...
    @property
    def time(self) -> float:
        """Simulated time [s]."""
    @property
    def steps(self) -> int: ...
    @property
    def dt(self) -> float:
        """Last time step [s]."""
    def step(self, n: int = 1, threads: int | None = None) -> None: ...
    def run(self, until: float) -> None: ...
    def snapshot(self) -> dict[str, Any]:
        """Copies of the state at one instant: ``time``, ``steps``, ``dt``, ``n_excluded`` and
        arrays ``positions``, ``velocities`` (N, dim), ``densities``, ``kinds``, ``ids`` (N,) in
        storage order. Callable from any thread: while another thread steps, the stepping
        thread copies the state between two steps (the caller waits with the GIL released)."""
    @property
    def positions(self) -> npt.NDArray[np.float64]:
        """(N, dim) [m], read-only view in storage order, valid until the next step/run; it
        aliases the solver's array, which a step on another thread writes while it is read."""
    @property
    def velocities(self) -> npt.NDArray[np.float64]:
        """(N, dim) [m/s], read-only view in storage order (aliases as ``positions``)."""
    @property
    def densities(self) -> npt.NDArray[np.float64]:
        """(N,) [kg/m^3], read-only view in storage order (aliases as ``positions``)."""
    @property
    def pressures(self) -> npt.NDArray[np.float64]:
        """(N,) [Pa] in storage order, computed from the densities on each access (a copy)."""
    @property
    def kinds(self) -> npt.NDArray[np.uint8]:
        """(N,) 0 fluid, 1 fixed boundary, 2 moving boundary (a view, aliases as ``positions``)."""
    @property
    def ids(self) -> npt.NDArray[np.uint32]:
        """(N,) original particle id of each storage slot (a view, aliases as ``positions``)."""
    def memory_bytes(self) -> int: ...
    def fluid_pairs(self) -> int: ...
    def force_evaluations_per_step(self) -> int: ...
    def params(self) -> dict[str, Any]: ...
    def interpolate(
        self, points: npt.NDArray[np.float64]
    ) -> dict[str, npt.NDArray[np.float64]]: ...
    def gauges(self) -> list[dict[str, Any]]:
        """Gauge records in the scene's order: dicts with ``name``, ``type``, ``t`` (n,) [s] and
        one array per quantity the core's gauge records (its ``columns``): (n,) for a gauge on a
        line (elevation and run-up: ``z`` [m, NaN when dry]), (n, points) for a gauge at points,
        with ``points`` (points, dim) [m] (velocity probes and windows: ``velocity``
        (n, points, dim) [m/s] and ``kernel_sum`` (n, points)); a quantity of several components
        gains a last axis. Windows add ``shape``, the counts per axis, x fastest."""
    @property
    def n_excluded(self) -> int:
        """Fluid particles excluded after leaving the domain."""
    def checkpoint(self) -> dict[str, Any]:
        """The full state needed to continue this run exactly: NumPy arrays (``positions``,
        ``velocities``, ``densities``, ``ids``, ``kinds``, ``velocities_prev``,
        ``densities_prev``), scalars (``time``, ``steps``, ``dt``, ``n_excluded``), ``energy0``
        and ``gauges`` (dicts of ``t``, ``values``, ``next_time``)."""
    def restore(self, checkpoint: dict[str, Any]) -> None:
        """Continues from ``checkpoint()`` of a run of the same scene; raises SceneError naming
        the entry that is missing or does not fit."""
