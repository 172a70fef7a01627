"""The ``watersim`` command.

::

    watersim run CASE|FILE.toml [--set key=value ...] [--out DIR] [--overwrite]
                 [--sample-every S] [--snapshot-every S] [--progress|--no-progress] [--quiet]
    watersim resume DIR [--until T]
    watersim analyse DIR [--t-start T]
    watersim show-scene CASE|FILE.toml [--set ...] [--json]     (or --reference)
    watersim plot DIR
    watersim bench [--case dambreak2d|dambreak3d|dsph-dambreak3d|dsph-dambreak2d|dsph-piston2d]
                   [--particles N] [--steps K] [--warmup W] [--repeat R] [--compare-threads A,B]
                   [--scaling N1,N2,...] [--set ...] [--json]   (watersim.bench_command)
    watersim bench --against DUALSPHYSICS --gencase GENCASE --xml CASE.xml ... [--interval S]
                   [--rounds R] [--cpu N[,M]] [--workdir DIR] [--json]   (watersim.bench_against)
    watersim stress [--quick] [--jobs N] [--json FILE] [--report DIR]   (watersim.stress)
    watersim validate [CASE ...] [--resolutions a,b,c] [--quick] [--json FILE] [--report DIR]

CASE is one of ``dambreak2d``, ``dambreak3d``, ``tank2d``, ``tank3d``; ``--set`` overrides any
field of the case's builder (:class:`~watersim.DamBreak` or :class:`~watersim.Tank`;
:mod:`watersim.builtin_cases`). Bad input
exits with code 2 and a one-line message naming the field; a run stopped by a stability monitor
writes what it has and exits with code 1.

The wave-flume cases ``flume2d``, ``kimmoun2d``, ``stansby2d``, ``bar2d``, ``solitary2d``,
``seawall2d``, ``flume3d`` and ``cylinder3d`` (:mod:`watersim.flume_cases`) take the numerical
parameters and dotted keys of their objects (``--set wave.height=0.06 --set paddle.order=1 --set
beach.slope=0.05``) and write
``summary.json``, ``gauges.csv`` and one ``velocity_NAME.csv`` per velocity probe or window
(rewritten as the run goes, so an unstable run keeps its records; headers with units,
:func:`watersim.flume.gauges.csv_column`) and ``analysis.json``, whose notes (what a too short
record left out, and the ``until`` it needs) are printed after the run.

A run writes into ``runs/NAME`` (a scene file NAME.toml) or ``runs/CASE-builtin`` (a built-in
case), or ``--out DIR``; a folder holding an earlier run's outputs is refused unless
``--overwrite`` (:func:`watersim.rundir.claim_folder`).

A scene file (``watersim run FILE.toml``, :mod:`watersim.scenefile`) describes any scene the
builders can make; ``watersim show-scene CASE`` prints a built-in case as one (``--json``: the
scene JSON the core receives; ``watersim scene CASE``, its old name, is a deprecated alias).
Every run writes ``log.jsonl`` and, when asked (``--snapshot-every`` or the file's ``[output]``
table), particle snapshots for ParaView; ``watersim plot DIR`` draws a finished run
(:mod:`watersim.plotting`).
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import json
import math
import signal
import sys
import threading
import time
import warnings
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TextIO

from . import rundir
from ._core import InstabilityError, SceneError
from ._files import OutputFileError, check_output_file, named_errors
from ._jsonio import json_ready as _jsonable
from ._jsonio import write_json_atomic
from ._version import __version__
from .bench_command import add_parser as add_bench_parser
from .builtin_cases import ALL_CASES, CASES, SET_HELP, builder_from_args, settable_keys
from .checkpoint import LastGood
from .cost import SpeedMeter
from .cost import estimate as estimate_cost
from .errors import CliError
from .flume import FlumeScene, FlumeSimulation
from .flume.records import velocity_csv_name
from .flume_cases import case_extras, headline
from .measure import (
    MARTIN_MOYCE_DESCRIPTIONS,
    front_error,
    front_position,
    water_column_height,
)
from .output import RunLog, RunOutputs
from .run_memory import estimate_run_memory
from .runrecord import RUN_FIELDS, error_record, rayon_threads, run_record, stop_status
from .scenefile import OutputOptions, SceneFile, is_scene_file, reference_markdown
from .scenefile import dumps as scene_dumps
from .scenefile import load as load_scene_file
from .scenes import DamBreak, SceneSimulation, Tank
from .simulation import Simulation, check_interval_resolved
from .stress import add_parser as add_stress_parser
from .validation import sweep as _validation

__all__ = ["ALL_CASES", "CASES", "build_parser", "builder_from_args", "main", "settable_keys"]

DEFAULT_CHECKPOINTS = "wall:600"
"""A flume run writes a checkpoint every ten minutes of wall time unless told otherwise."""

RECORD_EVERY_SAMPLES = 50
"""See :func:`record_every`."""


def record_every(until: float, sample_interval: float) -> float:
    """How often [s of simulated time] a flume run rewrites gauges.csv and velocity_NAME.csv,
    logs a sample and polls a wall-clock checkpoint, unless ``--sample-every`` says otherwise:
    every twentieth of the run, but at least every :data:`RECORD_EVERY_SAMPLES` gauge samples,
    so that a long run keeps its records (and its ten-minute checkpoints) as it goes."""
    return max(min(until / 20.0, RECORD_EVERY_SAMPLES * sample_interval), 1e-6)


# ------------------------------------------------------------------------------------------------
# helpers


def _write_json(path: Path, data: dict[str, Any]) -> None:
    write_json_atomic(path, data, indent=2)


class TerminatedError(KeyboardInterrupt):
    """SIGTERM (what ``timeout``, batch schedulers and ``docker stop`` send), raised in the main
    thread so that a run ends as after Ctrl-C: its summary, its last good state, its ``end``
    event."""


TERMINATED_MESSAGE = "terminated (SIGTERM); the outputs written so far are kept"


def _raise_terminated(_signum: int, _frame: Any) -> None:
    raise TerminatedError(TERMINATED_MESSAGE)


@contextlib.contextmanager
def _signals_deferred() -> Iterator[None]:
    """Ctrl-C and SIGTERM held back while the block writes a run's record (a second Ctrl-C
    during the post-run work must not lose the summary); raised when it ends."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list[int] = []
    previous = {sig: signal.signal(sig, lambda signum, _frame: caught.append(signum))
                for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
    if signal.SIGTERM in caught:
        raise TerminatedError(TERMINATED_MESSAGE)
    if caught:
        raise KeyboardInterrupt


# ------------------------------------------------------------------------------------------------
# watersim run


def _run_recorded(
    sim: Simulation,
    until: float,
    schedule: Sequence[tuple[float, Callable[[Simulation], Any]]],
    progress: bool,
    outputs: RunOutputs,
    before_close: Callable[[], Any] | None = None,
    **schedule_options: Any,
) -> tuple[str, dict[str, Any] | None]:
    """Run ``sim`` to ``until`` [s] with ``schedule`` (and the ``schedule_options`` of
    :meth:`Simulation.run_schedule`); return ``(status, error record)``.

    A monitor stop (status: its kind), Ctrl-C (``"interrupted"``), SIGTERM (``"terminated"``),
    a core error or a file that cannot be written (``"error"``) ends the run with its record;
    whatever happens, ``before_close`` runs (a failure there is the run's error if it had none),
    the log gets its ``end`` event and the outputs are closed, so what was written so far stays
    readable.
    """
    status = "ok"
    error: dict[str, Any] | None = None
    try:
        sim.run_schedule(until, schedule, progress=progress, **schedule_options)
    except (InstabilityError, KeyboardInterrupt, RuntimeError, OSError) as exc:
        status, error = _stopped(exc)
    try:
        if before_close is not None:
            before_close()
    except (KeyboardInterrupt, RuntimeError, OSError) as exc:
        if error is None:
            status, error = _stopped(exc)
    finally:
        with _signals_deferred():
            try:
                outputs.log.write("end", status=status, t=sim.time, steps=sim.steps, error=error)
                outputs.close()
            except OSError as exc:  # a full disk: the summary still gets its try
                with contextlib.suppress(OSError):
                    outputs.close()
                if error is None:
                    status, error = _stopped(exc)
    return status, error


def _stopped(exc: BaseException) -> tuple[str, dict[str, Any]]:
    """The status and error record of a run ``exc`` stopped."""
    if isinstance(exc, InstabilityError):
        status = stop_status(exc)
    elif isinstance(exc, TerminatedError):
        status = "terminated"
    elif isinstance(exc, KeyboardInterrupt):
        status = "interrupted"
    else:
        status = "error"
    return status, error_record(exc)


def _still_water_checks(sim: Simulation, builder: Tank) -> dict[str, Any]:
    """Largest fluid speed and free-surface level of a still tank, in SI and relative form."""
    import numpy as np

    assert builder.depth is not None and builder.length is not None and builder.dp is not None
    pos = sim.fluid_positions()
    speed = float(np.max(np.linalg.norm(sim.fluid_velocities(), axis=1))) if len(pos) else 0.0
    x = pos[:, 0]
    middle = np.abs(x - 0.5 * builder.length) <= 0.25 * builder.length
    surface = float(pos[middle, -1].max() + 0.5 * builder.dp) if np.any(middle) else math.nan
    return {
        "max_speed": speed,
        "max_speed_over_sqrt_gd": speed / math.sqrt(builder.g * builder.depth),
        "surface_z": surface,
        "surface_minus_depth_over_dp": (surface - builder.depth) / builder.dp,
    }


class _Recorder:
    """Run callback: writes front.csv rows (dam breaks) and a progress line every tenth of the run.

    Args:
        front_file: open CSV file for ``t_s, x_front_m, h_column_m`` rows, or ``None`` (no front).
        dp: particle spacing [m].
        until: end time of the run [s].
        say: where progress lines go (``print`` or a no-op).
        log: the run's log.jsonl, which gets a ``sample`` event per call.
    """

    def __init__(
        self, front_file: TextIO | None, dp: float, until: float, say: Callable[[str], None],
        log: RunLog | None = None,
    ) -> None:
        self.dp, self.until, self.say, self.log = dp, until, say, log
        self.file = front_file
        self.writer = csv.writer(front_file) if front_file is not None else None
        if self.writer is not None:
            self.writer.writerow(["t_s", "x_front_m", "h_column_m"])
        self.times: list[float] = []
        self.fronts: list[float] = []
        self._next_report = 0.0

    def close(self) -> None:
        """Closes front.csv (an error names it: a full disk fails here)."""
        if self.file is not None:
            with named_errors(self.file.name):
                self.file.close()

    def __call__(self, sim: Simulation) -> None:
        if self.writer is not None and self.file is not None:
            pos = sim.fluid_positions()
            x_front = front_position(pos, self.dp)
            h_column = water_column_height(pos, self.dp)
            self.times.append(sim.time)
            self.fronts.append(x_front)
            with named_errors(self.file.name):
                self.writer.writerow([repr(sim.time), repr(x_front), repr(h_column)])
                self.file.flush()  # rows so far survive a crash or an instability
        if self.log is not None:
            self.log.sample(sim, **({"x_front": self.fronts[-1]} if self.fronts else {}))
        if sim.time >= self._next_report:
            front = f", front {self.fronts[-1]:.3f} m" if self.fronts else ""
            self.say(f"  t = {sim.time:.3f} s, {sim.steps} steps, dt = {sim.dt:.3g} s{front}")
            self._next_report = next_report_time(sim.time, self.until)


def next_report_time(time: float, until: float) -> float:
    """The first tenth of ``until`` after ``time``: when a run next says how far it is. Found
    at once, never counted up to (an ``until`` of 1e-300 would take 1e297 additions)."""
    step = until / 10.0
    if not step > 0.0:
        return math.inf
    return max((math.floor(time / step) + 1.0) * step, math.nextafter(time, math.inf))


def _run_input(args: argparse.Namespace) -> SceneFile:
    """The scene of ``watersim run CASE|FILE.toml`` (a built-in case has no [output] table)."""
    if is_scene_file(args.case):
        return load_scene_file(args.case, args.set or [])
    builder = builder_from_args(args.case, args.set or [])
    return SceneFile(name=args.case, builder=builder, output=OutputOptions())


def _positive_option(name: str, value: float | None) -> float | None:
    if value is not None and not (value > 0.0 and math.isfinite(value)):
        raise CliError(f"{name}: must be a positive number, got {value!r}")
    return value


def default_folder(scene: SceneFile) -> Path:
    """Where a run writes without ``--out`` or ``[output] directory``: ``runs/NAME`` for a scene
    file NAME.toml, ``runs/CASE-builtin`` for a built-in case, so that a built-in case and a
    file of the same name (``examples/flume2d.toml``) never share a folder."""
    return Path("runs") / (scene.name if scene.path is not None else f"{scene.name}-builtin")


def _output_folder(given: str | None, scene: SceneFile) -> Path:
    """A run's folder: ``--out`` as given; else the scene file's ``[output] directory``, which
    must stay under the working directory (a shared scene file must not write, or clear, a
    folder elsewhere); else :func:`default_folder`.

    Raises:
        CliError: a NUL byte in the path, or a scene file's directory outside the working
            directory.
    """
    if given is not None:
        out = Path(given)
        source = "--out"
    elif scene.output.directory:
        out = Path(scene.output.directory)
        source = "[output] directory"
        if "\0" not in str(out):
            here = Path.cwd().resolve()
            if out.is_absolute() or not (here / out).resolve().is_relative_to(here):
                raise CliError(f"{source}: {str(out)!r} is outside the working directory "
                               f"{here}; a scene file writes under it, --out DIR writes elsewhere")
    else:
        return default_folder(scene)
    if "\0" in str(out):
        raise CliError(f"{source}: {str(out)!r}: a folder name cannot hold a NUL byte")
    return out


def _run_options(args: argparse.Namespace, scene: SceneFile) -> tuple[Path, float | None, bool]:
    """Output folder, snapshot interval and progress bar of a run: the command line first,
    then the scene file's [output] table, then the defaults."""
    out = _output_folder(args.out, scene)
    if args.sample_every is None:
        args.sample_every = scene.output.sample_every
    _positive_option("--sample-every", args.sample_every)
    snapshot_every = _positive_option("--snapshot-every", args.snapshot_every)
    if snapshot_every is None:
        snapshot_every = scene.output.snapshot_every
    until = float(scene.builder.until)  # type: ignore[arg-type]
    intervals = (("--sample-every", args.sample_every), ("--snapshot-every", snapshot_every))
    for name, every in intervals:
        if every is not None:
            _check_resolved(name, every, until)
    if args.save_last_good:  # checked now: the run must not end in a save that cannot be done
        check_output_file(args.save_last_good)
    if args.progress is None:
        progress = sys.stderr.isatty() and not args.quiet
    else:
        progress = bool(args.progress)
    return out, snapshot_every, progress


def _check_resolved(name: str, every: float, until: float) -> None:
    """:func:`check_interval_resolved` for a command-line interval (its default included: a
    dam break's 0.01 s samples are refused before a run to t = 1e9 s, not by its first stop).

    Raises:
        CliError: naming ``name``.
    """
    try:
        check_interval_resolved(name, every, until)
    except ValueError as e:
        raise CliError(str(e)) from None


def _say(args: argparse.Namespace) -> Callable[[str], None]:
    """Where a run's lines go: standard output, or nowhere with ``--quiet``."""
    return (lambda _line: None) if args.quiet else print


@dataclass
class _Run:
    """What a run of ``watersim run`` (or ``watersim resume``) holds from its start to its end:
    the pieces its summary and its last lines are made of."""

    args: argparse.Namespace
    scene: SceneFile
    out: Path
    sim: Simulation
    until: float
    threads: int
    say: Callable[[str], None]
    keeper: LastGood
    meter: SpeedMeter
    outputs: RunOutputs

    @classmethod
    def start(cls, args: argparse.Namespace, scene: SceneFile, out: Path, sim: Simulation,
              keeper: LastGood, outputs: Callable[[], RunOutputs],
              resumed_at: float | None = None) -> _Run:
        """Say what runs, where and what it should cost, write summary.json with the status
        ``running`` (replaced when the run ends: a killed run's summary says it never ended),
        then open the outputs (``outputs()``)."""
        until = float(scene.builder.until)  # type: ignore[arg-type]
        threads = rayon_threads()
        say = _say(args)
        start = "" if resumed_at is None else f", resumed at t = {resumed_at:.6g} s"
        say(
            f"watersim {__version__}: {scene.name}, {sim.n_particles} particles "
            f"({sim.n_fluid} fluid), dp = {scene.builder.dp:g} m, until {until:g} s{start}, "
            f"{threads} threads, into {out.resolve()}"
        )
        say(estimate_cost(sim, until, threads).line())
        meter = SpeedMeter(sim, until, say)
        _write_json(out / "summary.json", {
            **run_record(RUN_FIELDS, sim, case=scene.name, status="running", until=until,
                         threads=threads, state_sha256=None),
            "builder": scene.builder.as_dict(), "scene": sim.scene, "params": sim.params(),
        })
        return cls(args, scene, out, sim, until, threads, say, keeper, meter, outputs())

    def conclude(self, status: str, error: dict[str, Any] | None, wall: float,
                 extra: Callable[[], dict[str, Any]] = dict, **parts: Any) -> None:
        """Writes summary.json, with Ctrl-C and SIGTERM held back: the run record, the outputs,
        the command's own ``parts`` and ``extra()``, the scene; for a run that stopped, its error
        and then (a failure to save it cannot lose the summary) its last good state."""
        path = self.out / "summary.json"
        with _signals_deferred():
            summary = self.summary(status, error, wall, **parts)
            try:
                summary.update(extra())
            except Exception as exc:  # noqa: BLE001 - a comparison must not lose the summary
                summary["extra_error"] = error_record(exc)
            try:
                _write_json(path, summary)
            except OSError as exc:
                stopped = "" if error is None else f"; the run had stopped: {_stop_message(error)}"
                raise OutputFileError(f"{exc}{stopped}") from exc
            if error is None:
                return
            try:
                summary["last_good"] = self.keeper.save_record(
                    _last_good_path(self.args, self.out))
            except OSError as exc:
                summary["last_good"] = {"error": error_record(exc)}
            _write_json(path, summary)

    def summary(self, status: str, error: dict[str, Any] | None, wall: float,
                **parts: Any) -> dict[str, Any]:
        """summary.json: the run record, the outputs, the command's own ``parts``, the scene;
        for a run that stopped, its error."""
        summary: dict[str, Any] = {
            **run_record(RUN_FIELDS, self.sim, case=self.scene.name, status=status,
                         until=self.until, wall_s=wall, threads=self.threads),
            **self.outputs.summary(),
            **parts,
            "builder": self.scene.builder.as_dict(),
            "scene": self.sim.scene,
            "params": self.sim.params(),
        }
        if error is not None:
            summary["error"] = error
            summary["last_good"] = None
        return summary

    def finish(self, status: str, error: dict[str, Any] | None, wall: float) -> int:
        """The run's last line (and why it stopped, on stderr); its exit code."""
        self.say(f"{status}: {self.sim.steps} steps to t = {self.sim.time:.4g} s in "
                 f"{wall:.1f} s; wrote {self.out.resolve()}")
        if error is not None:
            print(f"watersim: run stopped: {_stop_message(error)}", file=sys.stderr)
            return STOP_CODES.get(status, 1)
        return 0


STOP_CODES = {"interrupted": 128 + signal.SIGINT, "terminated": 128 + signal.SIGTERM,
              "error": 2}
"""Exit codes of a stopped run (the shell's for a signal; 2 for a file that cannot be written or
a core error); a stability monitor's stop exits with 1."""


def cmd_run(args: argparse.Namespace) -> int:
    """``watersim run``: run a case or a scene file, write summary.json, log.jsonl (and
    front.csv for dam breaks, snapshots when asked)."""
    caught: list[warnings.WarningMessage] = []
    try:
        with warnings.catch_warnings(record=True) as caught:  # type: ignore[assignment]
            warnings.simplefilter("always")
            scene = _run_input(args)
    finally:  # a warning comes before the refusal it may explain (a beach at slope = 5)
        notes = [f"{w.category.__name__}: {w.message}" for w in caught]
        for note in notes:
            print(f"watersim: warning: {note}", file=sys.stderr)
    out, snapshot_every, progress = _run_options(args, scene)
    if isinstance(scene.builder, FlumeScene):
        return _run_flume(args, scene, notes, out, snapshot_every, progress)
    if args.checkpoint_every is not None:
        raise CliError("--checkpoint-every: only flume runs write checkpoints (a dam break or "
                       "tank run keeps its last good state: --save-last-good)")
    builder = scene.builder
    if args.sample_every is None:
        args.sample_every = 0.01
        _check_resolved("--sample-every", args.sample_every, float(builder.until))  # type: ignore[arg-type]
    keeper = _last_good_keeper(args)
    sim = builder.build()  # the core's checks (memory, ...) come before the output folder
    _check_run_memory(args, sim, scene, snapshot_every, flume=False)
    with rundir.RunFolder(out, args.overwrite):
        return _run_particles(args, scene, out, sim, keeper, snapshot_every, progress)


def _run_particles(args: argparse.Namespace, scene: SceneFile, out: Path, sim: Simulation,
                   keeper: LastGood, snapshot_every: float | None, progress: bool) -> int:
    """``watersim run`` of a dam break or a tank into its held folder ``out``."""
    builder = scene.builder
    run = _Run.start(args, scene, out, sim, keeper, lambda: RunOutputs(out, snapshot_every))
    run.outputs.log.write("start", case=scene.name, n_particles=sim.n_particles, dp=builder.dp,
                          until=run.until, threads=run.threads, version=__version__)
    is_dambreak = isinstance(builder, DamBreak)

    t_start = time.perf_counter()
    front_file = open(out / "front.csv", "w", newline="", encoding="utf-8") if is_dambreak else None
    recorder = _Recorder(front_file, float(builder.dp), run.until,  # type: ignore[arg-type]
                         (lambda _line: None) if progress else run.say, run.outputs.log)

    def sample(s: Simulation) -> None:
        recorder(s)
        keeper(s)
        run.meter(s)

    status, error = _run_recorded(
        sim, run.until, [(args.sample_every, sample), *run.outputs.schedule()], progress,
        run.outputs, recorder.close,
    )
    wall = time.perf_counter() - t_start

    def checks() -> dict[str, Any]:
        if isinstance(builder, DamBreak):
            return {"front_csv": "front.csv",
                    "front_final": recorder.fronts[-1] if recorder.fronts else None,
                    "martin_moyce": _martin_moyce_summary(builder, recorder.times,
                                                          recorder.fronts)}
        if isinstance(builder, Tank) and sim.n_fluid:
            return {"still_water": _still_water_checks(sim, builder)}
        return {}

    if isinstance(sim, SceneSimulation) and builder.gauges:  # type: ignore[attr-defined]
        sim.write_gauges_csv(out / "gauges.csv")
    run.conclude(status, error, wall, checks)
    if is_dambreak:
        assert isinstance(builder, DamBreak)
        _say_martin_moyce(run.say, _martin_moyce_summary(builder, recorder.times,
                                                         recorder.fronts))
    return run.finish(status, error, wall)


def _say_martin_moyce(say: Callable[[str], None], mm: dict[str, Any]) -> None:
    """The dam break's front against Martin & Moyce (1952), when it was computed."""
    if mm.get("rms_rel_error") is None:
        return
    lead = mm.get("mean_lead_s")
    lead_text = "not reached" if lead is None else f"{lead:+.3f} s"
    reference = MARTIN_MOYCE_DESCRIPTIONS.get(mm["reference"], mm["reference"])
    say(
        f"  front vs Martin & Moyce 1952 ({reference}): RMS relative error "
        f"{100 * mm['rms_rel_error']:.1f} % over {mm['n_points']} points; "
        f"mean time lead of the simulation {lead_text}"
    )


def _run_flume(
    args: argparse.Namespace,
    scene: SceneFile,
    notes: list[str],
    out: Path,
    snapshot_every: float | None,
    progress: bool,
    resumed: rundir.Reopened | None = None,
) -> int:
    """``watersim run`` for a wave flume: summary.json, gauges.csv, velocity_NAME.csv,
    analysis.json, log.jsonl, scene.toml and checkpoints/; with ``resumed``, ``watersim
    resume``: the run continues from its checkpoint into the same files."""
    settings = _FlumeSettings.parse(args, scene)
    # the core's checks (memory, ...) come before the output folder
    sim = scene.builder.build() if resumed is None else resumed.sim
    _check_run_memory(args, sim, scene, snapshot_every, flume=True)
    with rundir.RunFolder(out, getattr(args, "overwrite", False), claim=resumed is None):
        return _run_flume_held(args, scene, notes, out, sim, settings, snapshot_every, progress,
                               resumed)


def _check_run_memory(args: argparse.Namespace, sim: Simulation, scene: SceneFile,
                      snapshot_every: float | None, flume: bool) -> None:
    """Refuses, before the output folder is made, a run whose peak memory (the built state,
    the last good state, the gauge records to the end, a snapshot) would not fit
    (:mod:`watersim.run_memory`); says the estimate otherwise."""
    until = float(scene.builder.until)  # type: ignore[arg-type]
    estimate = estimate_run_memory(sim, until, snapshots=snapshot_every is not None,
                                   flume=flume)
    estimate.check()
    _say(args)(f"memory: about {estimate.total / 1024**3:.3g} GiB at the peak "
               f"({estimate.describe()})")


@dataclass(frozen=True)
class _FlumeSettings:
    """A flume run's options, checked before anything is built or written: the last-good
    keeper, the checkpoint interval and the interval at which gauges.csv is rewritten [s]."""

    keeper: LastGood
    checkpoint_every: rundir.CheckpointEvery
    record_every: float

    @classmethod
    def parse(cls, args: argparse.Namespace, scene: SceneFile) -> _FlumeSettings:
        builder = scene.builder
        assert isinstance(builder, FlumeScene)
        every = args.sample_every
        if every is None:
            every = record_every(float(builder.until),  # type: ignore[arg-type]
                                 float(builder.sample_interval))  # type: ignore[arg-type]
        return cls(_last_good_keeper(args),
                   rundir.CheckpointEvery.parse(args.checkpoint_every or DEFAULT_CHECKPOINTS),
                   every)


def _run_flume_held(
    args: argparse.Namespace, scene: SceneFile, notes: list[str], out: Path, sim: Simulation,
    settings: _FlumeSettings, snapshot_every: float | None, progress: bool,
    resumed: rundir.Reopened | None,
) -> int:
    """:func:`_run_flume` in its held folder ``out``."""
    run, checkpointer = _start_flume(args, scene, notes, out, sim, settings, snapshot_every,
                                     resumed)
    every = settings.record_every
    assert isinstance(sim, FlumeSimulation)
    t_start = time.perf_counter()
    status, error = _advance_flume(run, sim, checkpointer, every, progress, t_start, resumed)
    wall = time.perf_counter() - t_start
    run.conclude(status, error, wall, **_flume_records(run, sim, notes, resumed))
    analysis = _flume_analysis(scene, sim, status)
    _write_json(out / "analysis.json", analysis)
    for line in [*headline(scene.name, analysis), *analysis_notes(analysis)]:
        run.say(line)
    return run.finish(status, error, wall)


def _start_flume(
    args: argparse.Namespace, scene: SceneFile, notes: list[str], out: Path, sim: Simulation,
    settings: _FlumeSettings, snapshot_every: float | None, resumed: rundir.Reopened | None,
) -> tuple[_Run, rundir.Checkpointer]:
    """A flume run's set-up in its held folder: the scene.toml of a new run, the checkpoint
    schedule and the log's first event."""
    builder = scene.builder
    assert isinstance(builder, FlumeScene)
    until = float(builder.until)  # type: ignore[arg-type]
    if resumed is None:
        rundir.write_scene(out, scene)
    checkpointer = rundir.Checkpointer(out, settings.checkpoint_every,
                                       poll=settings.record_every, scene=scene)
    resumed_at = None if resumed is None else resumed.time
    run = _Run.start(args, scene, out, sim, settings.keeper,
                     lambda: RunOutputs(out, snapshot_every, resumed_at), resumed_at)
    run.outputs.log.write("start" if resumed is None else "resume", case=scene.name,
                          n_particles=sim.n_particles, dp=builder.dp, until=until,
                          threads=run.threads, version=__version__, warnings=notes,
                          **({} if resumed is None else {"checkpoint": str(resumed.checkpoint),
                                                         "t": resumed.time,
                                                         "steps": resumed.steps}))
    return run, checkpointer


def _advance_flume(
    run: _Run, sim: FlumeSimulation, checkpointer: rundir.Checkpointer, every: float,
    progress: bool, t_start: float, resumed: rundir.Reopened | None,
) -> tuple[str, dict[str, Any] | None]:
    """Run the flume to its end: every ``every`` seconds the records are rewritten (so that
    they survive a crash or an instability), the log sampled, the last good state kept; at the
    end the records are written once more and a finished run leaves a checkpoint."""
    csv_path = run.out / "gauges.csv"
    next_report = [0.0]

    def write_records(s: FlumeSimulation) -> dict[str, Path]:
        s.write_gauges_csv(csv_path)
        return s.write_velocity_csvs(run.out)

    def on_sample(s: Simulation) -> None:
        assert isinstance(s, FlumeSimulation)
        write_records(s)  # records so far survive a crash or an instability
        run.outputs.log.sample(s)
        if not progress and s.time >= next_report[0]:
            run.say(f"  t = {s.time:.3f} s, {s.steps} steps, dt = {s.dt:.3g} s, "
                    f"wall {time.perf_counter() - t_start:.1f} s")
            next_report[0] = next_report_time(s.time, run.until)

    def sample_and_keep(s: Simulation) -> None:
        on_sample(s)
        run.keeper(s)
        run.meter(s)

    def finish() -> None:
        write_records(sim)
        if sim.time >= run.until:  # a finished run can be extended: resume --until
            checkpointer.save(sim)

    return _run_recorded(
        sim, run.until, [(every, sample_and_keep), *run.outputs.schedule()], progress,
        run.outputs, finish, origin=0.0, initial=resumed is None, last=checkpointer.schedule(),
    )


def _case_analysis(scene: SceneFile, analysis: dict[str, Any]) -> dict[str, Any]:
    """``analysis`` with the case's reference comparisons, which belong to the built-in cases,
    not to a scene file of the same name."""
    extras_case = "" if scene.path is not None else scene.name
    analysis.update(case_extras(extras_case, scene.builder, analysis))
    analysis["case"] = scene.name
    return analysis


def _flume_analysis(scene: SceneFile, sim: FlumeSimulation, status: str) -> dict[str, Any]:
    """analysis.json of a flume run; an analysis that fails records its error instead of
    losing the run's outputs."""
    analysis: dict[str, Any]
    try:
        analysis = _case_analysis(scene, sim.analyse())
    except (Exception, KeyboardInterrupt) as exc:  # noqa: BLE001 - the run's outputs stay
        analysis = {"error": error_record(exc), "case": scene.name}
    analysis["status"] = status
    return analysis


def _flume_records(run: _Run, sim: FlumeSimulation, notes: list[str],
                   resumed: rundir.Reopened | None) -> dict[str, Any]:
    """The files a flume run wrote and what it started from, for summary.json."""
    return {
        "gauges_csv": "gauges.csv",
        "velocity_csv": {name: velocity_csv_name(name)
                         for name in {**sim.gauges.velocity, **sim.gauges.windows}},
        "analysis_json": "analysis.json",
        "scene_toml": rundir.SCENE_FILE,
        "checkpoints": [str(p.relative_to(run.out)) for p in rundir.checkpoints(run.out)],
        **({} if resumed is None else {"resumed_from": {
            "checkpoint": str(resumed.checkpoint.relative_to(run.out)), "time": resumed.time,
            "steps": resumed.steps}}),
        "n_gauge_samples": int(sim.gauges.t.size),
        "warnings": notes,
    }


MAX_NOTES = 8
"""Notes of the analysis printed after a run; the rest are in analysis.json."""


def analysis_notes(analysis: dict[str, Any]) -> list[str]:
    """The lines that tell the user what the analysis could not compute: its first notes and,
    when a part needs a longer record, the end time that makes every part computable."""
    notes = [str(n) for n in analysis.get("notes") or []]
    lines = [f"  note: {n}" for n in notes[:MAX_NOTES]]
    if len(notes) > MAX_NOTES:
        lines.append(f"  ... {len(notes) - MAX_NOTES} more notes in analysis.json")
    needs = [g.get("needs_until") for g in analysis.get("gauges") or []]
    needs.append((analysis.get("runup") or {}).get("needs_until"))
    needs += (analysis.get("envelopes") or {}).get("needs_until") or []
    needed = max((float(n) for n in needs if n is not None), default=None)
    if needed is not None:
        lines.append(f"  the analysis is incomplete: run with until >= "
                     f"{math.ceil(needed * 10) / 10:g} s (--set until=...) for every gauge")
    return lines


def _stop_message(error: dict[str, Any]) -> str:
    """Why a run stopped, never empty nor blank (a Ctrl-C carries no message of its own, and an
    exception's may be only white space): its message, else what the error says of itself."""
    message = str(error.get("message") or "").strip()
    if message:
        return message
    kind = str(error.get("type") or "").strip()
    if kind in ("KeyboardInterrupt", "TerminatedError"):
        return "interrupted (Ctrl-C); the outputs written so far are kept"
    if error.get("kind"):
        return f"{kind or 'instability'}: {error['kind']} at step {error.get('step')}"
    return f"{kind} (no message)" if kind else "unknown error (no message)"


def cmd_resume(args: argparse.Namespace) -> int:
    """``watersim resume DIR``: continue a flume run from its last checkpoint, to its end time
    or to ``--until``, into the same folder."""
    _positive_option("--until", args.until)
    resumed = rundir.reopen(args.directory, args.until)
    args.out = args.directory
    out, snapshot_every, progress = _run_options(args, resumed.scene)
    return _run_flume(args, resumed.scene, [], out, snapshot_every, progress, resumed)


def cmd_analyse(args: argparse.Namespace) -> int:
    """``watersim analyse DIR``: recompute analysis.json of a flume run from its records."""
    folder = Path(args.directory)
    reopened = rundir.reopen(folder)
    name = reopened.scene.name
    analysis = _case_analysis(reopened.scene, reopened.sim.analyse(t_start=args.t_start))
    analysis["status"] = "reanalysed"
    analysis["records_to"] = {"t": reopened.time, "steps": reopened.steps}
    target = Path(args.out) if args.out else folder / "analysis.json"
    _write_json(target, analysis)
    for line in [*headline(name, analysis), *analysis_notes(analysis)]:
        print(line)
    print(f"wrote {target}")
    return 0


def _last_good_keeper(args: argparse.Namespace) -> LastGood:
    """The rolling in-memory checkpoint of ``watersim run`` (``--last-good-every``)."""
    if args.last_good_every < 1:
        raise CliError(f"--last-good-every: must be at least 1, got {args.last_good_every}")
    return LastGood(args.last_good_every)


def _last_good_path(args: argparse.Namespace, out: Path) -> Path:
    """Where a failed run writes its last good state (``--save-last-good``)."""
    return Path(args.save_last_good) if args.save_last_good else out / "last_good.npz"


def _martin_moyce_summary(
    builder: DamBreak, times: list[float], fronts: list[float]
) -> dict[str, Any]:
    """Front error against Martin & Moyce n^2 = 2, or why it was not computed."""
    if abs(builder.height / builder.width - 2.0) > 0.01:
        return {"reference": "lethe", "note": "column height is not twice its width (n^2 != 2)"}
    try:
        err = front_error(times, fronts, builder.width, builder.g, x_max=builder.tank_length)
    except ValueError as exc:
        return {"reference": "lethe", "note": str(exc)}
    return err.as_dict()


# ------------------------------------------------------------------------------------------------
# watersim show-scene (watersim scene), watersim plot


def cmd_show_scene(args: argparse.Namespace) -> int:
    """``watersim show-scene``: a case's full, resolved scene as a scene file (TOML); with
    ``--json``, the scene JSON the core receives, checked by the core, with the parameters it
    derives and the particle count; with ``--reference``, the scene-file reference."""
    if args.reference:
        if args.case is not None or args.set or args.json:
            raise CliError("--reference: takes no CASE, --set or --json")
        sys.stdout.write(reference_markdown())
        return 0
    if args.case is None:
        raise CliError(f"CASE: required; a scene file FILE.toml or one of: {', '.join(ALL_CASES)}")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # wave-validity warnings: `watersim run` prints them
        scene = _run_input(args)
    if args.json:
        core_scene = scene.builder.to_scene()
        sim = Simulation(core_scene)
        shown = {"scene": core_scene, "params": sim.params(), "n_particles": sim.n_particles}
        print(json.dumps(_jsonable(shown), indent=2))
        return 0
    header = f"watersim show-scene {args.case}" + "".join(f" --set {s}" for s in args.set or [])
    header += f"\nwatersim {__version__}; run it with: watersim run FILE.toml"
    sys.stdout.write(scene_dumps(scene.builder, scene.output, header=header))
    return 0


SCENE_DEPRECATION = ("watersim: note: `watersim scene` is deprecated and will be removed; it is "
                     "`watersim show-scene --json`")
"""What ``watersim scene``, the old name of ``show-scene --json``, prints on stderr."""


def cmd_scene(args: argparse.Namespace) -> int:
    """``watersim scene``: deprecated alias of ``watersim show-scene --json``."""
    print(SCENE_DEPRECATION, file=sys.stderr)
    return cmd_show_scene(argparse.Namespace(**{**vars(args), "json": True, "reference": False}))


def cmd_plot(args: argparse.Namespace) -> int:
    """``watersim plot``: PNG figures of a finished run; prints the files written."""
    from .plotting import PlotError, plot_run

    try:
        written = plot_run(args.directory, args.out)
    except PlotError as exc:
        raise CliError(str(exc)) from None
    for path in written:
        print(path)
    return 0


# ------------------------------------------------------------------------------------------------


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``watersim`` command: one builder per sub-command."""
    parser = argparse.ArgumentParser(
        prog="watersim", description="WaterSim: weakly-compressible SPH wave flume."
    )
    parser.add_argument("--version", action="version", version=f"watersim {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    _add_run_parser(sub)
    _add_resume_parser(sub)
    _add_analyse_parser(sub)
    _add_show_scene_parser(sub)
    _add_plot_parser(sub)
    add_bench_parser(sub)
    _add_scene_parser(sub)
    add_stress_parser(sub)
    _validation.add_parser(sub)  # watersim validate (watersim.validation.sweep)
    return parser


CHECKPOINT_HELP = ("flume runs: write a checkpoint (DIR/checkpoints/, the last two kept) every "
                   "S simulated seconds (S or sim:S) or every S seconds of wall time (wall:S, "
                   "wall:10min, wall:2h); default wall:600. A finished run always writes one.")
PROGRESS_HELP = "show a progress bar on stderr (default: when stderr is a terminal)"
LAST_GOOD_EVERY_HELP = "take the in-memory last good state every K samples (default 1)"


def _add_run_parser(sub: Any) -> None:
    run = sub.add_parser("run", help="run a built-in case or a scene file (FILE.toml)")
    run.add_argument(
        "case", metavar="CASE", help=f"a scene file FILE.toml, or one of: {', '.join(ALL_CASES)}"
    )
    run.add_argument("--set", action="append", metavar="KEY=VALUE", help=SET_HELP)
    run.add_argument("--out", metavar="DIR", help="output folder (default: runs/NAME for a scene "
                     "file NAME.toml, runs/CASE-builtin for a built-in case)")
    run.add_argument("--overwrite", action="store_true",
                     help="delete an earlier run's outputs in the output folder first (without "
                     "it, a folder holding them is refused)")
    run.add_argument(
        "--sample-every",
        type=float,
        default=None,
        metavar="S",
        help="dam breaks: front sampling interval in simulated seconds (default 0.01); "
        "flume cases: how often gauges.csv is rewritten (default until/20)",
    )
    run.add_argument(
        "--snapshot-every",
        type=float,
        default=None,
        metavar="S",
        help="write particle snapshots (VTK .vtu + .pvd for ParaView) every S simulated seconds "
        "into DIR/snapshots (default: the scene file's [output] snapshot_every, else none)",
    )
    run.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                     help=PROGRESS_HELP)
    run.add_argument("--quiet", action="store_true", help="print nothing but errors")
    run.add_argument(
        "--save-last-good",
        metavar="FILE",
        help="where a run that stops early writes its last good state, a checkpoint to continue "
        "from (default OUT/last_good.npz)",
    )
    run.add_argument("--last-good-every", type=int, default=1, metavar="K",
                     help=LAST_GOOD_EVERY_HELP)
    run.add_argument("--checkpoint-every", metavar="SPEC", default=None, help=CHECKPOINT_HELP)
    run.set_defaults(func=cmd_run)


def _add_resume_parser(sub: Any) -> None:
    resume = sub.add_parser(
        "resume", help="continue a killed, stopped or finished flume run from its last checkpoint"
    )
    resume.add_argument("directory", metavar="DIR", help="the run's output folder")
    resume.add_argument("--until", type=float, default=None, metavar="T",
                        help="new end time [s] (default: the run's own)")
    resume.add_argument("--checkpoint-every", metavar="SPEC", default=None, help=CHECKPOINT_HELP)
    resume.add_argument("--sample-every", type=float, default=None, metavar="S",
                        help="how often gauges.csv is rewritten (default until/20)")
    resume.add_argument("--snapshot-every", type=float, default=None, metavar="S",
                        help="particle snapshots every S simulated seconds (default: the run's)")
    resume.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                        help=PROGRESS_HELP)
    resume.add_argument("--quiet", action="store_true", help="print nothing but errors")
    resume.add_argument("--save-last-good", metavar="FILE", help=argparse.SUPPRESS)
    resume.add_argument("--last-good-every", type=int, default=1, metavar="K",
                        help=LAST_GOOD_EVERY_HELP)
    resume.set_defaults(func=cmd_resume)


def _add_analyse_parser(sub: Any) -> None:
    analyse = sub.add_parser(
        "analyse", help="recompute analysis.json of a flume run from its stored records"
    )
    analyse.add_argument("directory", metavar="DIR", help="the run's output folder")
    analyse.add_argument("--t-start", type=float, default=None, metavar="T",
                         help="start every gauge's analysis window at T [s] (default: the wave's "
                         "arrival plus the ramp plus one period, per gauge)")
    analyse.add_argument("--out", metavar="FILE", help="where to write (default DIR/analysis.json)")
    analyse.set_defaults(func=cmd_analyse)


def _add_show_scene_parser(sub: Any) -> None:
    show = sub.add_parser(
        "show-scene", help="print a case's full scene as a scene file (TOML), its core JSON "
        "(--json), or the scene-file reference (--reference)"
    )
    show.add_argument("case", metavar="CASE", nargs="?",
                      help=f"a scene file FILE.toml, or one of: {', '.join(ALL_CASES)}")
    show.add_argument("--set", action="append", metavar="KEY=VALUE", help=SET_HELP)
    show.add_argument("--json", action="store_true",
                      help="print the scene JSON the core receives, checked by the core, with "
                      "the parameters it derives and the particle count")
    show.add_argument("--reference", action="store_true",
                      help="print the scene-file reference (docs/scene-reference.md) instead")
    show.set_defaults(func=cmd_show_scene)


def _add_scene_parser(sub: Any) -> None:
    scene = sub.add_parser("scene", help="deprecated: watersim show-scene --json")
    scene.add_argument("case", metavar="CASE",
                       help=f"a scene file FILE.toml, or one of: {', '.join(ALL_CASES)}")
    scene.add_argument("--set", action="append", metavar="KEY=VALUE", help=SET_HELP)
    scene.set_defaults(func=cmd_scene)


def _add_plot_parser(sub: Any) -> None:
    plot = sub.add_parser("plot", help="draw PNG figures of a finished run folder")
    plot.add_argument("directory", metavar="DIR", help="the run's output folder (--out)")
    plot.add_argument("--out", metavar="FIGDIR", help="where the PNGs go (default DIR/plots)")
    plot.set_defaults(func=cmd_plot)


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``watersim`` command; returns the exit code."""
    args = build_parser().parse_args(argv)
    args.argv = list(sys.argv[2:] if argv is None else argv[1:])  # for reports
    in_main_thread = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGTERM, _raise_terminated) if in_main_thread else None
    try:
        return int(args.func(args))
    except (CliError, SceneError, _validation.ValidateError, OSError) as exc:
        print(f"watersim: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt as exc:
        print(f"watersim: stopped: {str(exc) or 'interrupted (Ctrl-C)'}", file=sys.stderr)
        return 128 + (signal.SIGTERM if isinstance(exc, TerminatedError) else signal.SIGINT)
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
