"""Checkpoint and restart: save a run's full state to a ``.npz`` file and continue it exactly.

A checkpoint holds the particle state in the solver's storage order, the integrator's history
(Verlet), the stability monitors' baselines and every gauge record; the paddle's motion law is a
function of time and needs nothing more. A run continued from a checkpoint reaches the same
``state_sha256`` as the run that never stopped (``crates/sph-core/tests/stability.rs``,
``tests/test_checkpoint.py``). The scene itself is stored too, as JSON, so that
:func:`load_checkpoint` can rebuild the simulation.

:class:`LastGood` keeps the last good state of a running simulation in memory, so that a run
stopped by a stability monitor can still save it: after an ``InstabilityError`` the core's state
is the failed one (the monitors run after the step that broke it), so the state to continue from
has to be taken before.
"""

from __future__ import annotations

import json
import math
import zipfile
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from ._core import SceneError
from ._files import atomic_write
from ._version import __version__
from .simulation import Simulation

__all__ = [
    "LastGood", "check_state", "load_checkpoint", "read_header", "save_checkpoint", "write_state",
]

_ARRAYS = (
    "positions", "velocities", "densities", "ids", "kinds", "velocities_prev", "densities_prev",
)
_SCALARS = ("time", "steps", "dt", "n_excluded")


def save_checkpoint(sim: Simulation, path: str | Path) -> Path:
    """Writes the state of ``sim`` to ``path`` (``.npz``); returns the path written."""
    return write_state(sim.core.checkpoint(), sim.scene, path)


def write_state(state: Mapping[str, Any], scene: Mapping[str, Any], path: str | Path,
                extras: Mapping[str, Any] | None = None) -> Path:
    """Writes a state taken with ``sim.core.checkpoint()`` of a simulation of ``scene`` to
    ``path`` (``.npz``, readable by :func:`load_checkpoint`); returns the path written.

    ``extras``: JSON-ready state of the Python side of the run (what its monitors found so
    far), read back with :func:`read_extras`. The file also records the package version.
    """
    data: dict[str, Any] = {key: state[key] for key in _ARRAYS}
    data["version"] = np.asarray(__version__)
    data["extras_json"] = np.asarray(json.dumps(dict(extras or {})))
    for key in _SCALARS:
        data[key] = np.asarray(state[key])
    data["energy0"] = np.asarray(state["energy0"], dtype=np.float64)
    data["scene_json"] = np.asarray(json.dumps(dict(scene)))
    correction = state.get("paddle_correction")
    if correction is not None:
        data["paddle_correction"] = np.asarray(correction, dtype=np.float64)
    data["n_gauges"] = np.asarray(len(state["gauges"]))
    for i, gauge in enumerate(state["gauges"]):
        data[f"gauge{i}_t"] = gauge["t"]
        data[f"gauge{i}_values"] = gauge["values"]
        data[f"gauge{i}_next_time"] = np.asarray(gauge["next_time"])
        if "crossings_past" in gauge:  # an overtopping gauge's particle sides
            data[f"gauge{i}_crossings_past"] = np.asarray(gauge["crossings_past"], dtype=np.uint8)
            data[f"gauge{i}_crossings_net"] = np.asarray(gauge["crossings_net"], dtype=np.int64)
    path = Path(path)
    # write then rename, so an interrupted save never leaves a truncated checkpoint behind
    with atomic_write(path, "wb") as f:
        np.savez(f, **data)
    return path


def read_header(path: str | Path) -> dict[str, Any]:
    """The scene, version, time, steps and extras of a checkpoint, without restoring it.

    Raises:
        SceneError: the file cannot be read as a WaterSim checkpoint (missing, truncated or
            not one), with the reason.
    """
    try:
        # our own handle: np.load leaves its file open when the archive is damaged
        with open(path, "rb") as handle, np.load(handle, allow_pickle=False) as f:
            missing = [k for k in ("scene_json", "time", "steps", *_ARRAYS) if k not in f]
            if missing:
                raise SceneError(f"checkpoint {path}: not a WaterSim checkpoint "
                                 f"(no {', '.join(missing)})")
            return {
                "scene": json.loads(str(f["scene_json"])),
                "version": str(f["version"]) if "version" in f else None,
                "time": float(f["time"]),
                "steps": int(f["steps"]),
                "extras": json.loads(str(f["extras_json"])) if "extras_json" in f else {},
            }
    except SceneError:
        raise
    except (OSError, ValueError, KeyError, zipfile.BadZipFile, EOFError) as exc:
        raise SceneError(f"checkpoint {path}: unreadable ({type(exc).__name__}: {exc})") from exc


def load_checkpoint(path: str | Path, sim: Simulation | None = None) -> Simulation:
    """Continues a run from ``path``: into ``sim`` when given (it must be built from the same
    scene), else into a new simulation built from the scene stored in the checkpoint.

    Raises:
        SceneError: the file is not a WaterSim checkpoint (missing, damaged, or another kind of
            file), its state is inconsistent (:func:`check_state`), or it belongs to another
            scene.
    """
    try:
        with open(path, "rb") as handle, np.load(handle, allow_pickle=False) as f:
            if "scene_json" not in f:
                raise SceneError(f"checkpoint {path}: not a WaterSim checkpoint (no scene_json)")
            if sim is None:
                try:
                    sim = Simulation(str(f["scene_json"]))
                except SceneError as exc:
                    raise SceneError(f"checkpoint {path}: its scene is refused: {exc}") from exc
            state = _read_state(f)
    except SceneError:
        raise
    except (OSError, ValueError, KeyError, TypeError, IndexError, zipfile.BadZipFile,
            EOFError) as exc:
        raise SceneError(f"checkpoint {path}: unreadable ({type(exc).__name__}: {exc})") from exc
    check_state(state, sim, f"checkpoint {path}")
    sim.core.restore(state)
    return sim


def _read_state(f: Any) -> dict[str, Any]:
    """The state stored in an opened checkpoint archive ``f``, as ``core.restore`` takes it."""
    state: dict[str, Any] = {key: np.asarray(f[key]) for key in _ARRAYS}
    state["time"] = float(f["time"])
    state["steps"] = int(f["steps"])
    state["dt"] = float(f["dt"])
    state["n_excluded"] = int(f["n_excluded"])
    state["energy0"] = tuple(float(v) for v in f["energy0"])
    if "paddle_correction" in f:
        state["paddle_correction"] = tuple(float(v) for v in f["paddle_correction"])
    state["gauges"] = []
    for i in range(int(f["n_gauges"])):
        gauge = {
            "t": np.asarray(f[f"gauge{i}_t"]),
            "values": np.asarray(f[f"gauge{i}_values"]),
            "next_time": float(f[f"gauge{i}_next_time"]),
        }
        if f"gauge{i}_crossings_past" in f:
            gauge["crossings_past"] = np.asarray(f[f"gauge{i}_crossings_past"])
            gauge["crossings_net"] = int(f[f"gauge{i}_crossings_net"])
        state["gauges"].append(gauge)
    return state


KINDS = (0, 1, 2, 3)
"""Particle kinds: fluid, fixed wall, moving wall, excluded."""


def check_state(state: Mapping[str, Any], sim: Simulation, source: str = "checkpoint") -> None:
    """Refuses a state that ``sim`` cannot continue from (the core checks the arrays' lengths):
    duplicate ids, unknown kinds, a time, step or baseline energy that is not finite, more
    excluded particles than particles, gauge records with fewer values than times.

    Raises:
        SceneError: ``"SOURCE: inconsistent state: ..."`` naming what is wrong.
    """
    def refuse(reason: str) -> None:
        raise SceneError(f"{source}: inconsistent state: {reason}")

    n = sim.n_particles
    ids = np.asarray(state["ids"]).reshape(-1)
    kinds = np.asarray(state["kinds"]).reshape(-1)
    if np.unique(ids).size != ids.size:
        refuse("duplicate particle ids")
    if not np.isin(kinds, KINDS).all():
        refuse(f"unknown particle kinds {sorted(set(kinds.tolist()) - set(KINDS))[:5]}")
    for key in ("time", "dt"):
        if not math.isfinite(state[key]) or state[key] < 0.0:
            refuse(f"{key} = {state[key]!r}, not a finite non-negative number")
    if not 0 <= int(state["n_excluded"]) <= n:
        refuse(f"n_excluded = {state['n_excluded']}, above the {n} particles")
    if not all(math.isfinite(v) for v in state["energy0"]):
        refuse(f"energy0 = {tuple(state['energy0'])!r}, not finite")
    for i, gauge in enumerate(state["gauges"]):
        times, values = np.asarray(gauge["t"]).size, np.asarray(gauge["values"]).size
        if values < times or (times and values % times):
            refuse(f"gauge {i} has {values} values for {times} times")
        if math.isnan(gauge["next_time"]) or gauge["next_time"] == -math.inf:
            refuse(f"gauge {i}: next_time = {gauge['next_time']!r}")


class LastGood:
    """A rolling in-memory checkpoint of a run, to save when the run fails.

    Call it from the run's sample callback (``sim.run(until, callback_every, callback)``): every
    ``every``-th call it takes ``sim.core.checkpoint()``, a copy of the state that has passed
    every monitor (they run after each step, and a sample is taken between steps). When the run
    then stops with an ``InstabilityError``, :meth:`save` writes that state; it is at most
    ``every`` sample intervals older than the failure.

    One monitor is not checked after every step: the energy growth (scenes without a paddle),
    evaluated every 50 steps. A sample between two evaluations may already be past its limit, so
    the state is kept only if its energy, computed here as the core does (``m sum(|v|^2/2 + g z)``
    over the fluid, against ``energy0`` and the scene's ``energy_growth_limit``), is within the
    limit; otherwise the older state stays (:attr:`skipped` counts these).

    The copy costs about as much as one pass over the particle arrays, far less than a step
    (docs/stability.md gives the figures), so taking it at every sample is cheap.

    Args:
        every: take the checkpoint every this many calls (>= 1).
    """

    def __init__(self, every: int = 1) -> None:
        if isinstance(every, bool) or not isinstance(every, int) or every < 1:
            raise ValueError(f"every: must be an integer >= 1, got {every!r}")
        self.every = every
        self.calls = 0
        self.state: dict[str, Any] | None = None
        self.scene: dict[str, Any] | None = None
        self.skipped = 0
        self._mass: float | None = None

    def __call__(self, sim: Simulation) -> None:
        if self.calls % self.every == 0:
            state = sim.core.checkpoint()
            if self._energy_within_limit(sim, state):
                self.state = state
                self.scene = sim.scene
            else:
                self.skipped += 1
        self.calls += 1

    def _energy_within_limit(self, sim: Simulation, state: Mapping[str, Any]) -> bool:
        """The energy-growth test of the core's monitor (``check_energy`` in
        crates/sph-core/src/diagnostics.rs), on a checkpoint."""
        scene = sim.scene
        if scene.get("paddle") is not None:
            return True  # the monitor is off: a paddle does work on the fluid
        if self._mass is None:
            self._mass = float(sim.params()["mass"])
        gravity = float(scene.get("gravity", 9.81))
        limit = float(scene.get("energy_growth_limit", 0.05))
        e0, pot0 = (float(v) for v in state["energy0"])
        fluid = np.asarray(state["kinds"]) == 0
        pos = np.asarray(state["positions"]).reshape(-1, sim.dim)[fluid]
        vel = np.asarray(state["velocities"]).reshape(-1, sim.dim)[fluid]
        energy = self._mass * float(np.sum(0.5 * np.sum(vel * vel, axis=1) + gravity * pos[:, -1]))
        return energy <= e0 + limit * max(abs(pot0), np.finfo(np.float64).tiny)

    @property
    def time(self) -> float | None:
        """Simulated time of the state kept [s], or None before the first call."""
        return None if self.state is None else float(self.state["time"])

    @property
    def steps(self) -> int | None:
        """Step count of the state kept, or None before the first call."""
        return None if self.state is None else int(self.state["steps"])

    def save(self, path: str | Path) -> Path | None:
        """Writes the state kept to ``path`` (``.npz``); None (nothing written) if no state was
        taken yet."""
        if self.state is None or self.scene is None:
            return None
        return write_state(self.state, self.scene, path)

    def save_record(self, path: str | Path) -> dict[str, Any] | None:
        """:meth:`save`, and what summary.json says about it: ``path``, ``time`` [s], ``steps``
        (None if nothing was kept)."""
        written = self.save(path)
        if written is None:
            return None
        return {"path": str(written), "time": self.time, "steps": self.steps}
