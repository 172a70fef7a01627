"""A thin Python wrapper around the core's ``Simulation``.

The core keeps particles in its own (cell-sorted) storage order, which changes every step, and
hands out read-only NumPy views of its arrays that are valid only until the next ``step``/``run``.
This wrapper adds what a user needs on top: copies of the fluid state, a state hash in particle-id
order (independent of the storage order), a ``run`` that calls back at regular sample times, and
:meth:`Simulation.snapshot`, a consistent copy of the state that another thread may take while one
steps.
"""

from __future__ import annotations

import hashlib
import json
import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from . import _core

__all__ = ["Simulation", "Snapshot"]

FLUID: int = 0
"""Particle kind code of fluid particles."""
FIXED_BOUNDARY: int = 1
"""Particle kind code of fixed wall particles."""
MOVING_BOUNDARY: int = 2
"""Particle kind code of moving wall particles."""


class Simulation:
    """A WCSPH simulation of one scene.

    Args:
        scene: the scene, as a dict in the core's JSON form (``SceneBuilder.to_scene()``) or as
            a JSON string.

    Raises:
        SceneError: the core refused the scene (message ``field.path: reason``).

    Attributes:
        scene: the scene as the core runs it, every default filled in by the core.

    Array properties (``positions``, ``velocities``, ``densities``, ``pressures``, ``kinds``,
    ``ids``) are read-only views in the solver's storage order, valid until the next
    :meth:`step` or :meth:`run`: copy what you keep. They alias the solver's own arrays, which
    a step writes with the GIL released: a view read on one thread while another thread steps
    the simulation sees a torn mixture of two states. From another thread, read
    :meth:`snapshot` instead (the properties themselves raise ``RuntimeError`` while a step
    runs on another thread).
    """

    def __init__(self, scene: Mapping[str, Any] | str) -> None:
        scene_json = scene if isinstance(scene, str) else json.dumps(dict(scene))
        self._sim = _core.Simulation(scene_json)
        self.scene: dict[str, Any] = json.loads(_core.resolve_scene(scene_json))

    # -- pass-through ---------------------------------------------------------------------------

    @property
    def core(self) -> _core.Simulation:
        """The underlying ``watersim._core.Simulation``."""
        return self._sim

    @property
    def dim(self) -> int:
        """Number of space dimensions (2 or 3)."""
        return self._sim.dim

    @property
    def n_particles(self) -> int:
        """Number of particles, fluid and boundary."""
        return self._sim.n_particles

    @property
    def n_fluid(self) -> int:
        """Number of fluid particles."""
        return self._sim.n_fluid

    @property
    def n_boundary(self) -> int:
        """Number of boundary (wall) particles."""
        return self._sim.n_boundary

    @property
    def time(self) -> float:
        """Simulated time [s]."""
        return self._sim.time

    @property
    def steps(self) -> int:
        """Number of time steps taken."""
        return self._sim.steps

    @property
    def dt(self) -> float:
        """Last time step [s]."""
        return self._sim.dt

    @property
    def positions(self) -> npt.NDArray[np.float64]:
        """(N, dim) positions [m], read-only view in storage order."""
        return self._sim.positions

    @property
    def velocities(self) -> npt.NDArray[np.float64]:
        """(N, dim) velocities [m/s], read-only view in storage order."""
        return self._sim.velocities

    @property
    def densities(self) -> npt.NDArray[np.float64]:
        """(N,) densities [kg/m^3], read-only view in storage order."""
        return self._sim.densities

    @property
    def pressures(self) -> npt.NDArray[np.float64]:
        """(N,) pressures [Pa], storage order: the equation of state of ``densities``,
        computed on each access (the core does not store pressure), read-only like the views."""
        pressures = self._sim.pressures
        pressures.flags.writeable = False
        return pressures

    @property
    def kinds(self) -> npt.NDArray[np.uint8]:
        """(N,) particle kinds: 0 fluid, 1 fixed boundary, 2 moving boundary."""
        return self._sim.kinds

    @property
    def ids(self) -> npt.NDArray[np.uint32]:
        """(N,) original particle id of each storage slot."""
        return self._sim.ids

    def snapshot(self) -> Snapshot:
        """Copies of the state at one instant, safe to take from any thread.

        While another thread is in :meth:`step` or :meth:`run`, the stepping thread makes the
        copies between two steps (the caller waits at most about one step, with the GIL
        released); otherwise they are made at once. Every array of one snapshot belongs to the
        same step as its ``time`` and ``steps``.
        """
        s = self._sim.snapshot()
        return Snapshot(**s)

    def step(self, n: int = 1, threads: int | None = None) -> None:
        """Advance ``n`` time steps.

        Args:
            n: steps to take.
            threads: run them on a pool of this many threads (built on first use, then kept)
                instead of the global pool (``RAYON_NUM_THREADS``). The results do not depend
                on it: for timing thread counts against each other in one process.

        Raises:
            InstabilityError: a stability monitor stopped the run.
            ValueError: ``threads`` is not a positive integer.
        """
        positive = isinstance(threads, int) and not isinstance(threads, bool) and threads >= 1
        if threads is not None and not positive:
            raise ValueError(f"threads: must be a positive integer, got {threads!r}")
        self._sim.step(n, threads)

    def memory_bytes(self) -> int:
        """Bytes of the solver's own particle and cell arrays (capacity-based)."""
        return self._sim.memory_bytes()

    def fluid_pairs(self) -> int:
        """Pairs one fluid force evaluation sums over at the present positions: each fluid
        particle with every other particle closer than the kernel support.

        A step costs about this many pair terms times :meth:`force_evaluations_per_step`; per
        particle the count depends on how much of the scene lies near a wall or the free
        surface. A diagnostic (it sorts a copy of the positions, about 9 bytes per particle
        plus the positions while it runs), not for every step."""
        return int(self._sim.fluid_pairs())

    def force_evaluations_per_step(self) -> int:
        """Fluid force evaluations per time step: 2 with Symplectic, 1 with Verlet."""
        return int(self._sim.force_evaluations_per_step())

    def params(self) -> dict[str, Any]:
        """Derived parameters: ``h``, ``c0``, ``mass``, ``b_tait``, ``rho0``, ``dp``, ..."""
        return self._sim.params()

    def interpolate(self, points: npt.ArrayLike) -> dict[str, npt.NDArray[np.float64]]:
        """Shepard-normalised SPH interpolation of the fluid at ``points`` (M, dim) [m].

        Returns a dict with ``"pressure"`` (M,) [Pa], ``"density"`` (M,) [kg/m^3],
        ``"velocity"`` (M, dim) [m/s] and ``"kernel_sum"`` (M,) (sum of V_b W_b: about 1 inside
        the fluid, 0 outside).
        """
        pts = np.ascontiguousarray(points, dtype=np.float64)
        if pts.ndim == 1:
            pts = pts.reshape(1, -1)
        if pts.ndim != 2 or pts.shape[1] != self.dim:
            raise ValueError(f"points: expected shape (M, {self.dim}), got {pts.shape}")
        return self._sim.interpolate(pts)

    # -- additions ------------------------------------------------------------------------------

    def fluid_mask(self) -> npt.NDArray[np.bool_]:
        """(N,) True for fluid particles, in the current storage order."""
        return np.asarray(self._sim.kinds) == FLUID

    def fluid_positions(self) -> npt.NDArray[np.float64]:
        """(n_fluid, dim) copy of the fluid positions [m], in storage order."""
        return np.array(self._sim.positions[self.fluid_mask()], dtype=np.float64)

    def fluid_velocities(self) -> npt.NDArray[np.float64]:
        """(n_fluid, dim) copy of the fluid velocities [m/s], in storage order."""
        return np.array(self._sim.velocities[self.fluid_mask()], dtype=np.float64)

    def state_sha256(self) -> str:
        """SHA-256 (hex) of the state in particle-id order.

        The digest covers the positions, then the velocities, then the densities of all
        particles, each sorted by particle id and written as little-endian float64 bytes
        (row-major for the (N, dim) arrays), concatenated in that order. It does not depend on
        the solver's storage order, so two runs agree exactly when their states are bit-identical.
        """
        order = np.argsort(np.asarray(self._sim.ids), kind="stable")
        digest = hashlib.sha256()
        for array in (self._sim.positions, self._sim.velocities, self._sim.densities):
            sorted_le = np.ascontiguousarray(np.asarray(array)[order], dtype="<f8")
            digest.update(sorted_le.tobytes())
        return digest.hexdigest()

    def __repr__(self) -> str:
        return (
            f"{type(self).__name__}(dim={self.dim}, particles={self.n_particles} "
            f"({self.n_fluid} fluid), time={self.time:.6g} s, steps={self.steps}, "
            f"dt={self.dt:.3g} s)"
        )

    def run(
        self,
        until: float,
        callback_every: float | None = None,
        callback: Callable[[Simulation], None] | None = None,
        progress: bool = False,
    ) -> None:
        """Advance until ``time >= until`` [s], optionally calling back at sample times.

        With ``callback``, it is called once at the current time before stepping, then each time
        the simulation reaches ``t0 + k * callback_every`` (k = 1, 2, ...) and finally at
        ``until``. The call sees the state at the first step that reaches the sample time, so
        ``sim.time`` may be past it by less than one ``dt``: record ``sim.time``.

        Args:
            until: end time [s].
            callback_every: interval between callbacks [s] (required with ``callback``).
            callback: called with this simulation at each sample time.
            progress: show a progress bar on stderr (tqdm): simulated time [s] as its position,
                the last time step and particle-steps per wall second as its postfix. The core
                never shortens a step to land on a stopping time, so the bar's intermediate
                stops do not change the results (the state hash is the same without it).

        Raises:
            InstabilityError: a stability monitor stopped the run; samples taken before it were
                passed to ``callback``, and the last good state stays readable.
        """
        if callback is None:
            self.run_schedule(until, (), progress=progress)
            return
        if callback_every is None or not (callback_every > 0.0 and math.isfinite(callback_every)):
            raise ValueError(f"callback_every: must be a positive number, got {callback_every!r}")
        self.run_schedule(until, ((callback_every, callback),), progress=progress)

    def run_schedule(
        self,
        until: float,
        schedule: Sequence[tuple[float, Callable[[Simulation], Any]]],
        progress: bool = False,
        *,
        origin: float | None = None,
        initial: bool = True,
        last: Sequence[tuple[float, Callable[[Simulation], Any]]] = (),
    ) -> None:
        """Advance until ``time >= until`` [s], calling several callbacks at their own intervals.

        Each ``(every, callback)`` of ``schedule`` is called as :meth:`run` calls its callback:
        once at the current time, at the first step reaching each ``t0 + k * every`` (once per
        stop, even if a step passes several of its sample times) and at ``until``. Callbacks due
        at the same stop are called in ``schedule`` order, then the simulation's own monitors,
        then ``last``. A sample closer than ``1e-9 * every`` to ``until`` is merged with the
        final one. Where the run stops between steps never changes a step.

        Args:
            until: end time [s].
            schedule: ``(interval [s], callback)`` pairs.
            progress: show a progress bar (see :meth:`run`).
            origin: ``t0`` of the sample times (default: the current time). A resumed run passes
                its first run's start, so that it stops where the first run would have: the
                first sample time of each callback is then the first ``origin + k * every``
                after the current time.
            initial: call every callback once at the current time (a resumed run does not: its
                checkpoint was taken after they ran at that time).
            last: callbacks called after every other one due at a stop (a checkpoint, which
                must hold what the others did).

        Raises:
            ValueError: ``until`` not finite, or an interval not a positive number.
            InstabilityError: a stability monitor stopped the run.
        """
        if not math.isfinite(until):
            raise ValueError(f"until: must be finite, got {until!r}")
        schedule = (*schedule, *self._monitors(), *last)
        for every, _ in schedule:
            if not (every > 0.0 and math.isfinite(every)):
                raise ValueError(f"callback_every: must be a positive number, got {every!r}")
            check_interval_resolved("callback_every", every, until)
        bar = _Progress(self, until) if progress else None
        try:
            t0 = self._sim.time if origin is None else float(origin)
            if initial:
                for _, callback in schedule:
                    callback(self)
            ks = [max(1, math.floor((self._sim.time - t0) / every) + 1) for every, _ in schedule]
            for i, (every, _) in enumerate(schedule):  # the first k with t0 + k every > time
                while ks[i] > 1 and t0 + (ks[i] - 1) * every > self._sim.time:
                    ks[i] -= 1
                while t0 + ks[i] * every <= self._sim.time:
                    ks[i] += 1

            def due(i: int) -> float | None:
                every = schedule[i][0]
                target = t0 + ks[i] * every
                return target if target < until - 1e-9 * every else None

            while True:
                targets = [t for t in (due(i) for i in range(len(schedule))) if t is not None]
                if not targets:
                    break
                target = min(targets)
                self._advance(target, bar)
                for i, (every, callback) in enumerate(schedule):
                    t_i = due(i)
                    if t_i is None or self._sim.time < t_i:
                        continue
                    callback(self)
                    ks[i] = _next_stop(ks[i], t0, every, self._sim.time)
            if self._sim.time < until:
                self._advance(until, bar)
                for _, callback in schedule:
                    callback(self)
        finally:
            if bar is not None:
                bar.close()

    def _monitors(self) -> list[tuple[float, Callable[[Simulation], Any]]]:
        """``(interval [s], callback)`` pairs the simulation runs for itself after the caller's
        (see :meth:`run_schedule`); none here, subclasses add their own."""
        return []

    def _advance(self, target: float, bar: _Progress | None) -> None:
        """Run the core to ``target`` [s], in pieces that update the progress bar if any."""
        if bar is None:
            self._sim.run(target)
            return
        while self._sim.time < target:
            self._sim.run(min(target, self._sim.time + bar.chunk))
            bar.update()


@dataclass(frozen=True)
class Snapshot:
    """A consistent copy of a simulation's state between two steps (:meth:`Simulation.snapshot`),
    arrays in the solver's storage order of that step (``ids`` maps them to particles)."""

    time: float
    """Simulated time [s]."""
    steps: int
    dt: float
    """Last time step [s]."""
    n_excluded: int
    positions: npt.NDArray[np.float64]
    """(N, dim) [m]."""
    velocities: npt.NDArray[np.float64]
    """(N, dim) [m/s]."""
    densities: npt.NDArray[np.float64]
    """(N,) [kg/m^3]."""
    kinds: npt.NDArray[np.uint8]
    ids: npt.NDArray[np.uint32]


def _next_stop(k: int, t0: float, every: float, time: float) -> int:
    """The first ``k' > k`` with ``t0 + k' every > time`` (as computed in floating point):
    bracketed from the quotient ``(time - t0) / every`` and found by bisection, which the
    monotonic rounding of ``t0 + k' every`` allows; never counted up to (one step of 1e147 s
    past 0.01 s samples would be 1e149 additions)."""

    def past(j: int) -> bool:
        return t0 + j * every > time

    lo = k + 1
    if past(lo):
        return lo
    guess = max(lo, math.floor((time - t0) / every))
    if not past(guess):
        lo = guess
    step, hi = 1, guess
    while not past(hi):
        hi, step = guess + step, 2 * step
    while hi - lo > 1:  # lo is not past the time, hi is
        mid = (lo + hi) // 2
        lo, hi = (lo, mid) if past(mid) else (mid, hi)
    return hi


STOP_RESOLUTION = 1e-9
"""The shortest interval between a run's stops, as a fraction of its end time (see
:func:`check_interval_resolved`)."""


def check_interval_resolved(name: str, every: float, until: float) -> None:
    """Refuses an interval between a run's stops (callbacks, samples, snapshots) shorter than
    :data:`STOP_RESOLUTION` times the run's end time ``until``: t has 16 significant digits, so
    the sample times ``t0 + k * every`` stay 7 digits apart, and a run stops at most 1e9 times
    (an interval below the resolution of t, 1e-300, would make :meth:`Simulation.run_schedule`
    count its stops one by one for ever).

    Raises:
        ValueError: the message names ``name``.
    """
    floor = STOP_RESOLUTION * abs(until)
    if every < floor:
        raise ValueError(f"{name}: {every:g} s is below {floor:g} s, {STOP_RESOLUTION:g} of the "
                         f"run's end time {until:g} s")


class _Progress:
    """A tqdm bar over simulated time, with dt and particle-steps per second as its postfix.

    The core is run in pieces of 1/500 of the run's simulated time between updates (cheap:
    each piece is many steps, and stopping never changes a step).
    """

    def __init__(self, sim: Simulation, until: float) -> None:
        from tqdm import tqdm

        self.sim = sim
        self.t0 = sim.time
        self.total = max(until - self.t0, 0.0)
        self.chunk = max(self.total / 500.0, 1e-12)
        self.steps0 = sim.steps
        self.wall0 = time.perf_counter()
        self.bar = tqdm(
            total=self.total,
            unit="s",
            desc="t",
            bar_format="{desc} {n:.4g}/{total:.4g} s |{bar}| {percentage:3.0f}% "
            "[{elapsed}<{remaining}{postfix}]",
            dynamic_ncols=True,
            leave=True,
        )

    def update(self) -> None:
        """Move the bar to the simulation's time and refresh the postfix."""
        sim = self.sim
        wall = time.perf_counter() - self.wall0
        rate = sim.n_particles * (sim.steps - self.steps0) / wall if wall > 0.0 else 0.0
        self.bar.set_postfix_str(f"dt={sim.dt:.3g} s, {rate:.3g} particle-steps/s",
                                 refresh=False)
        # update() redraws at most every tqdm mininterval (0.1 s), unlike refresh()
        self.bar.update(min(sim.time - self.t0, self.total) - self.bar.n)

    def close(self) -> None:
        self.update()
        self.bar.close()
