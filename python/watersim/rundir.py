"""A flume run's folder as something to come back to: the scene it ran, its checkpoints,
resuming it, re-analysing it and loading its records.

What ``watersim run`` writes for this, besides its records:

- ``scene.toml``: the run's whole scene as a scene file (the ``watersim show-scene`` format, every
  value written out), so that the run can be rebuilt exactly whatever the case or file it came
  from has become since;
- ``checkpoints/ckpt_STEPS.npz``: the last :data:`KEEP` checkpoints (:mod:`watersim.checkpoint`:
  the particle state, the integrator's history, the monitors' baselines, every gauge record and
  what the Python side's monitors found), one at the end of the run and, with
  ``--checkpoint-every``, periodic ones. Each is written to a temporary file and renamed, so a
  killed run never leaves a truncated one.

:func:`reopen` rebuilds a run from its folder and continues it from its last checkpoint
(``watersim resume``): the step never depends on where a run stops, so the resumed run reaches
the state an uninterrupted one reaches, bit for bit, and its gauge records are the same.
:func:`analyse` recomputes ``analysis.json`` from the stored records; :func:`load` returns them
as an :class:`xarray.Dataset`.
"""

from __future__ import annotations

import contextlib
import dataclasses
import fcntl
import json
import math
import os
import re
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from . import analysis as an
from ._core import SceneError
from ._files import write_text_atomic
from ._version import __version__
from .checkpoint import load_checkpoint, read_header, write_state
from .flume import GAUGE_TYPES, FlumeScene, FlumeSimulation
from .scenefile import SceneFile
from .scenefile import dumps as scene_dumps
from .scenefile import load as load_scene_file
from .simulation import Simulation

if TYPE_CHECKING:
    import xarray

__all__ = [
    "CHECKPOINTS", "KEEP", "LOCK_FILE", "RUN_FILES", "RUN_FOLDERS", "SCENE_FILE",
    "CheckpointEvery", "Checkpointer", "Reopened", "RunDirError", "RunFolder", "analyse",
    "checkpoints", "claim_folder",
    "earlier_outputs", "load", "reopen", "write_scene",
]

SCENE_FILE = "scene.toml"
CHECKPOINTS = "checkpoints"
KEEP = 2
"""Checkpoints kept: the newest and the one before, in case the newest is damaged after all."""

_CHECKPOINT_NAME = re.compile(r"^ckpt_(\d+)\.npz$")

RUN_FILES: tuple[str, ...] = (
    "summary.json", "log.jsonl", "gauges.csv", "velocity_*.csv", "analysis.json", "front.csv",
    SCENE_FILE, "last_good.npz",
)
"""The files (glob patterns) a run writes into its folder."""

RUN_FOLDERS: dict[str, tuple[str, ...]] = {
    CHECKPOINTS: ("ckpt_*.npz",),
    "snapshots": ("particles_*.vtu", "particles.pvd"),
    "plots": ("*.png",),
}
"""The folders a run (and ``watersim plot``) writes into its folder, with the files (glob
patterns) it writes there."""

LOCK_FILE = ".watersim.lock"
"""The file a run holds locked in its folder for as long as it writes there (:class:`RunFolder`)."""


class RunDirError(SceneError):
    """A run folder that cannot be resumed, re-analysed or loaded, with the reason (a
    :class:`~watersim.SceneError`: the command line prints it on one line and exits with 2)."""


@dataclasses.dataclass(frozen=True)
class CheckpointEvery:
    """How often a run writes a checkpoint: every ``seconds`` of simulated time, or of wall
    time when ``wall``."""

    seconds: float
    wall: bool = False

    @classmethod
    def parse(cls, text: str) -> CheckpointEvery:
        """``S`` or ``sim:S``: every S simulated seconds; ``wall:S``: every S seconds of wall
        time (``wall:10min``, ``wall:2h``: minutes and hours).

        Raises:
            RunDirError: naming ``--checkpoint-every`` and what was wrong.
        """
        kind, _, value = text.strip().rpartition(":")
        if kind not in ("", "sim", "wall"):
            raise RunDirError(f"--checkpoint-every: unknown clock {kind!r} in {text!r} "
                              "(sim:S or wall:S)")
        factor = 1.0
        for suffix, seconds in (("min", 60.0), ("h", 3600.0), ("s", 1.0)):
            if kind == "wall" and value.endswith(suffix):
                value, factor = value[: -len(suffix)], seconds
                break
        try:
            seconds = float(value) * factor
        except ValueError:
            raise RunDirError(f"--checkpoint-every: not a number of seconds: {text!r}") from None
        if not (seconds > 0.0 and math.isfinite(seconds)):
            raise RunDirError(f"--checkpoint-every: must be a positive interval, got {text!r}")
        return cls(seconds, wall=kind == "wall")


class Checkpointer:
    """Writes a run's checkpoints into ``DIRECTORY/checkpoints`` and keeps the last :data:`KEEP`.

    Args:
        directory: the run's folder.
        every: the periodic interval, or None for none (:meth:`save` still writes one).
        poll: how often [s of simulated time] a wall-clock interval is checked.
        scene: the run's scene (its name goes into the checkpoints).
    """

    def __init__(self, directory: str | Path, every: CheckpointEvery | None,
                 poll: float, scene: SceneFile) -> None:
        self.directory = Path(directory) / CHECKPOINTS
        self.every = every
        self.poll = poll
        # which case this is: a built-in case's reference comparisons go with it
        self.run_info = {"case": scene.name, "builtin": scene.path is None}
        self._last_wall = time.perf_counter()
        self.written = 0

    def schedule(self) -> list[tuple[float, Callable[[Simulation], Any]]]:
        """The ``last`` callbacks of :meth:`Simulation.run_schedule` (a checkpoint is taken after
        every other callback of its stop, so that it holds what they did)."""
        if self.every is None:
            return []
        if self.every.wall:
            return [(self.poll, self._if_due)]
        return [(self.every.seconds, self.save)]

    def _if_due(self, sim: Simulation) -> None:
        assert self.every is not None
        if time.perf_counter() - self._last_wall >= self.every.seconds:
            self.save(sim)

    def save(self, sim: Simulation) -> Path:
        """Writes a checkpoint of ``sim`` now and removes all but the last :data:`KEEP`."""
        self.directory.mkdir(parents=True, exist_ok=True)
        path = self.directory / f"ckpt_{sim.steps:012d}.npz"
        extras = {**self.run_info, **_monitor_state(sim)}
        write_state(sim.core.checkpoint(), sim.scene, path, extras=extras)
        self._last_wall = time.perf_counter()
        self.written += 1
        for old in checkpoints(self.directory.parent)[:-KEEP]:
            old.unlink(missing_ok=True)
        return path


def _monitor_state(sim: Simulation) -> dict[str, Any]:
    """What the Python side's monitors of ``sim`` found so far, JSON-ready."""
    if not isinstance(sim, FlumeSimulation):
        return {}
    return {
        "overturns": [[t, dataclasses.asdict(o)] for t, o in sim.overturns],
        "overturn_checks": sim.overturn_checks,
    }


def _restore_monitor_state(sim: Simulation, state: dict[str, Any]) -> None:
    if isinstance(sim, FlumeSimulation):
        sim.overturns = [(float(t), an.Overturn(**o)) for t, o in state.get("overturns", [])]
        sim.overturn_checks = int(state.get("overturn_checks", 0))


def checkpoints(directory: str | Path) -> list[Path]:
    """A run folder's checkpoints, oldest first."""
    folder = Path(directory) / CHECKPOINTS
    if not folder.is_dir():
        return []
    found = [(int(m.group(1)), p) for p in folder.iterdir()
             if (m := _CHECKPOINT_NAME.match(p.name))]
    return [p for _, p in sorted(found)]


def earlier_outputs(directory: str | Path) -> list[Path]:
    """What earlier runs left in ``directory``: the files of :data:`RUN_FILES` and those of
    :data:`RUN_FOLDERS` in their folders (nothing else it holds)."""
    folder = Path(directory)
    if not folder.is_dir():
        return []
    found = {p for pattern in RUN_FILES for p in folder.glob(pattern) if p.is_file()}
    for name, patterns in RUN_FOLDERS.items():
        found.update(p for pattern in patterns for p in (folder / name).glob(pattern)
                     if p.is_file())
    return sorted(found)


def _earlier_run(folder: Path) -> dict[str, Any]:
    """The summary.json of the run that wrote ``folder``, or ``{}``."""
    try:
        summary = json.loads((folder / "summary.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    return summary if isinstance(summary, dict) else {}


def claim_folder(directory: str | Path, overwrite: bool) -> None:
    """Make ``directory`` ready for a new run's outputs.

    A folder that holds an earlier run's outputs (:func:`earlier_outputs`) is refused, so that no
    run mixes its files with another's (old snapshots, checkpoints or velocity files of another
    scene would stay next to the new ones); with ``overwrite`` those outputs are deleted first,
    and the run's sub-folders when nothing else is left in them. Other files in the folder are
    left alone either way.

    Raises:
        RunDirError: the folder holds an earlier run's outputs and ``overwrite`` is false.
    """
    folder = Path(directory)
    found = earlier_outputs(folder)
    if found and not overwrite:
        names = ", ".join(str(p.relative_to(folder)) for p in found[:6])
        more = f" and {len(found) - 6} more" if len(found) > 6 else ""
        earlier = _earlier_run(folder)
        case = (f" (case {earlier.get('case')}, status {earlier.get('status')})"
                if earlier else "")
        hint = (f"; `watersim resume {folder}` continues it"
                if checkpoints(folder) and earlier.get("status", "running") == "running" else "")
        raise RunDirError(
            f"{folder}: holds the outputs of an earlier run{case}: {names}"
            f"{more}; --overwrite deletes them first, --out DIR writes elsewhere{hint}")
    for path in found:
        path.unlink()
    for name in RUN_FOLDERS:
        with contextlib.suppress(OSError):  # missing, or holding the user's own files
            (folder / name).rmdir()


class RunFolder:
    """A run's hold on its output folder, for as long as the run writes there (a context
    manager): the folder is created, :data:`LOCK_FILE` in it is locked (``flock``: the kernel
    releases it when the process ends, however it ends) and, for a new run, the folder is
    claimed (:func:`claim_folder`). The lock file is removed when the run lets go.

    Args:
        directory: the run's folder.
        overwrite: delete an earlier run's outputs (a new run).
        claim: refuse or clear an earlier run's outputs; False for a run continuing its own
            folder (``watersim resume``), which must exist.

    Raises:
        RunDirError: another process holds the folder, or :func:`claim_folder` refuses it.
    """

    def __init__(self, directory: str | Path, overwrite: bool = False, claim: bool = True) -> None:
        self.directory = Path(directory)
        self.overwrite = overwrite
        self.claim = claim
        self._fd: int | None = None

    @property
    def lock_path(self) -> Path:
        return self.directory / LOCK_FILE

    def __enter__(self) -> RunFolder:
        if self.claim:
            self.directory.mkdir(parents=True, exist_ok=True)
        elif not self.directory.is_dir():
            raise RunDirError(f"{self.directory}: no such folder")
        self._fd = self._lock()
        try:
            if self.claim:
                claim_folder(self.directory, self.overwrite)
        except BaseException:
            self.release()
            raise
        return self

    def _lock(self) -> int:
        while True:
            fd = os.open(self.lock_path, os.O_RDWR | os.O_CREAT, 0o644)
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                holder = os.read(fd, 64).decode("ascii", "replace").strip() or "?"
                os.close(fd)
                raise RunDirError(
                    f"{self.directory}: another run (process {holder}) is writing into this "
                    "folder; wait for it to end or give --out DIR") from None
            try:
                same = os.fstat(fd).st_ino == os.stat(self.lock_path).st_ino
            except FileNotFoundError:
                same = False
            if same:  # not a lock file its last holder removed between our open and flock
                os.ftruncate(fd, 0)
                os.write(fd, f"{os.getpid()}\n".encode("ascii"))
                return fd
            os.close(fd)

    def release(self) -> None:
        """Lets go of the folder: removes the lock file (while still holding it, so that no
        other run locks a file about to disappear) and closes it."""
        if self._fd is None:
            return
        with contextlib.suppress(OSError):
            self.lock_path.unlink()
        os.close(self._fd)
        self._fd = None

    def __exit__(self, *exc_info: object) -> None:
        self.release()


def write_scene(directory: str | Path, scene: SceneFile) -> Path:
    """Writes ``DIRECTORY/scene.toml``: the run's scene, every value written out."""
    path = Path(directory) / SCENE_FILE
    header = (f"The scene of this run, written by watersim {__version__}; "
              "watersim resume and watersim analyse rebuild the run from it.")
    write_text_atomic(path, scene_dumps(scene.builder, scene.output, header=header))
    return path


@dataclasses.dataclass
class Reopened:
    """A run rebuilt from its folder at its last checkpoint (:func:`reopen`)."""

    scene: SceneFile
    sim: FlumeSimulation
    checkpoint: Path
    time: float
    steps: int


def reopen(directory: str | Path, until: float | None = None) -> Reopened:
    """Rebuilds the flume run of ``directory`` from its ``scene.toml`` and restores its last
    checkpoint; ``until`` [s] replaces the scene's end time. Reads only: nothing on disk changes.

    Raises:
        RunDirError: no scene.toml, no checkpoint, an unreadable checkpoint, one written by
            another version or of another scene, not a flume run, or ``until`` not after the
            checkpoint.
    """
    folder = Path(directory)
    scene_path = folder / SCENE_FILE
    if not folder.is_dir():
        raise RunDirError(f"{folder}: no such run folder")
    if not scene_path.is_file():
        raise RunDirError(f"{folder}: not a watersim run folder (no {SCENE_FILE}; runs of "
                          "watersim before checkpoints cannot be resumed)")
    found = checkpoints(folder)
    if not found:
        raise RunDirError(f"{folder}: no checkpoint in {CHECKPOINTS}/ to continue from")
    path = found[-1]
    header = read_header(path)
    if header["version"] != __version__:
        raise RunDirError(f"checkpoint {path}: written by watersim {header['version']}, this is "
                          f"{__version__}; a run continues only with the version that started it")
    settings = [] if until is None else [f"until={float(until)!r}"]
    loaded = load_scene_file(scene_path, settings)
    extras = header["extras"]
    scene = SceneFile(name=str(extras.get("case", folder.name)), builder=loaded.builder,
                      output=loaded.output,
                      path=None if extras.get("builtin", False) else scene_path)
    if not isinstance(scene.builder, FlumeScene):
        raise RunDirError(f"{folder}: resume and analyse take flume runs; this run is a "
                          f"{type(scene.builder).__name__}")
    sim = scene.builder.build()
    assert isinstance(sim, FlumeSimulation)
    if header["scene"] != sim.scene:
        raise RunDirError(f"checkpoint {path}: of another scene than {scene_path} (was the "
                          "scene file edited?)")
    if until is not None and not float(until) > header["time"]:
        raise RunDirError(f"--until: must be after the checkpoint's time {header['time']:.6g} s, "
                          f"got {until!r}")
    try:
        load_checkpoint(path, sim)
    except (SceneError, ValueError, KeyError, OSError, RuntimeError) as exc:
        raise RunDirError(f"checkpoint {path}: cannot be restored ({exc})") from exc
    _restore_monitor_state(sim, extras)
    return Reopened(scene=scene, sim=sim, checkpoint=path, time=header["time"],
                    steps=header["steps"])


def analyse(directory: str | Path, t_start: float | None = None) -> dict[str, Any]:
    """The wave analysis of a finished or stopped flume run from its last checkpoint (its
    records up to then), as ``watersim run`` writes it to analysis.json; ``t_start`` [s]
    overrides the start of every gauge's window."""
    return reopen(directory).sim.analyse(t_start=t_start)


def load(directory: str | Path) -> xarray.Dataset:
    """A flume run's gauge records as a labelled :class:`xarray.Dataset`, from its last
    checkpoint (every record up to it).

    Variables (units in each one's ``units`` attribute, SI):

    - ``elevation`` (time, gauge): surface elevation above the still-water level [m], NaN when
      dry; coordinates ``x`` (and ``y`` in 3D) and ``still_depth`` per gauge;
    - ``runup`` (time_runup): run-up, elevation of the wet tip above the still water [m];
    - ``velocity_NAME`` (time_NAME, point, component) for each velocity probe and window [m/s],
      with the points' coordinates, and ``kernel_sum_NAME`` (below 0.5: the point is dry);
    - ``pressure_NAME`` (time_NAME, point_NAME) for each pressure gauge [Pa], NaN where dry.
    - ``force_NAME`` (time_NAME, component) and ``moment_NAME`` (time_NAME, moment_axis_NAME)
      for each force gauge [N, N m; per unit width in 2D, N/m and N m/m].

    Each gauge class gives its own variables (``dataset_variables``).

    The attributes carry the case's scene (``scene_toml``) and the run's time and steps.
    """
    import xarray as xr

    reopened = reopen(directory)
    data: dict[str, Any] = {}
    coords: dict[str, Any] = {}
    for kind in GAUGE_TYPES.values():
        kind_data, kind_coords = kind.dataset_variables(reopened.sim.gauges)
        data.update(kind_data)
        coords.update(kind_coords)
    scene_text = (Path(directory) / SCENE_FILE).read_text(encoding="utf-8")
    return xr.Dataset(data, coords=coords, attrs={
        "scene_toml": scene_text, "t_end": reopened.time, "steps": reopened.steps,
        "checkpoint": str(reopened.checkpoint), "watersim_version": __version__,
    })

