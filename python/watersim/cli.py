"""The ``watersim`` command.

::

    watersim run CASE|FILE.toml [--set key=value ...] [--out DIR] [--overwrite]
                 [--sample-every S] [--snapshot-every S] [--progress|--no-progress] [--quiet]
    watersim show-scene CASE|FILE.toml [--set ...]     (or --reference)
    watersim plot DIR
    watersim bench [--case dambreak2d|dambreak3d|dsph-dambreak3d|dsph-dambreak2d|dsph-piston2d]
                   [--particles N] [--steps K] [--warmup W] [--repeat R] [--compare-threads A,B]
                   [--scaling N1,N2,...] [--set ...] [--json]
    watersim scene CASE [--set key=value ...]
    watersim stress [--quick] [--jobs N] [--json FILE] [--report DIR]   (watersim.stress)
    watersim validate [CASE ...] [--resolutions a,b,c] [--quick] [--json FILE] [--report DIR]

CASE is one of ``dambreak2d``, ``dambreak3d``, ``tank2d``, ``tank3d``; ``--set`` overrides any
field of the case's builder (:class:`~watersim.DamBreak` or :class:`~watersim.Tank`). Bad input
exits with code 2 and a one-line message naming the field; a run stopped by a stability monitor
writes what it has and exits with code 1.

The wave-flume cases ``flume2d``, ``kimmoun2d``, ``stansby2d``, ``bar2d``, ``solitary2d`` and
``flume3d`` (:mod:`watersim.flume_cases`) take the numerical parameters and dotted keys of their
objects (``--set wave.height=0.06 --set paddle.order=1 --set beach.slope=0.05``) and write
``summary.json``, ``gauges.csv`` and one ``velocity_NAME.csv`` per velocity probe or window
(rewritten as the run goes, so an unstable run keeps its records; headers with units,
:func:`watersim.flume.gauges.csv_column`) and ``analysis.json``, whose notes (what a too short
record left out, and the ``until`` it needs) are printed after the run.

A run writes into ``runs/NAME`` (a scene file NAME.toml) or ``runs/CASE-builtin`` (a built-in
case), or ``--out DIR``; a folder holding an earlier run's outputs is refused unless
``--overwrite`` (:func:`watersim.rundir.claim_folder`).

A scene file (``watersim run FILE.toml``, :mod:`watersim.scenefile`) describes any scene the
builders can make; ``watersim show-scene CASE`` prints a built-in case as one. Every run writes
``log.jsonl`` and, when asked (``--snapshot-every`` or the file's ``[output]`` table), particle
snapshots for ParaView; ``watersim plot DIR`` draws a finished run (:mod:`watersim.plotting`).
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import statistics
import sys
import time
import typing
import warnings
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, TextIO

from . import numerics as nm
from . import overrides, rundir
from ._core import InstabilityError, SceneError
from ._jsonio import json_ready as _jsonable
from ._jsonio import write_json_atomic
from ._version import __version__
from .bench_cases import DSPH_CASES, dsph_scene
from .bench_scaling import ScalingRun, fit_scaling
from .checkpoint import LastGood
from .cost import SpeedMeter
from .cost import estimate as estimate_cost
from .errors import CliError, did_you_mean
from .flume import FlumeScene, FlumeSimulation
from .flume.records import velocity_csv_name
from .flume_cases import (
    FLUME_CASES,
    case_extras,
    flume_builder,
    flume_settable_keys,
    headline,
)
from .measure import (
    MARTIN_MOYCE_DESCRIPTIONS,
    front_error,
    front_position,
    water_column_height,
)
from .numerics import FORCE_PRECISIONS
from .output import RunLog, RunOutputs
from .runrecord import RUN_FIELDS, error_record, rayon_threads, run_record, stop_status
from .scenefile import OutputOptions, SceneFile, is_scene_file, reference_markdown
from .scenefile import dumps as scene_dumps
from .scenefile import load as load_scene_file
from .scenes import DamBreak, SceneBuilder, Tank
from .simulation import Simulation
from .stress import add_parser as add_stress_parser
from .validation import sweep as _validation

__all__ = ["ALL_CASES", "CASES", "main"]

CASES: dict[str, tuple[type[SceneBuilder], dict[str, Any]]] = {
    "dambreak2d": (DamBreak, {"dim": 2}),
    "dambreak3d": (DamBreak, {"dim": 3}),
    "tank2d": (Tank, {"dim": 2}),
    "tank3d": (Tank, {"dim": 3}),
}
"""Built-in cases: builder class and the fields the case fixes."""

ALL_CASES: tuple[str, ...] = (*CASES, *FLUME_CASES)
DEFAULT_CHECKPOINTS = "wall:600"
"""A flume run writes a checkpoint every ten minutes of wall time unless told otherwise."""
"""Every case ``watersim run`` knows: the verification cases, then the wave-flume cases."""

BENCH_CASES: tuple[str, ...] = ("dambreak2d", "dambreak3d", *DSPH_CASES)


# ------------------------------------------------------------------------------------------------
# helpers


def settable_keys(case: str) -> list[str]:
    """Fields of ``case`` that ``--set`` may change (all but those the case fixes)."""
    if case in FLUME_CASES:
        return flume_settable_keys(case)
    cls, fixed = CASES[case]
    skip = set(fixed)
    if fixed.get("dim") == 2:
        skip.update(cls.THREE_D_ONLY)
    options = [key for name in nm.OPTION_CLASSES for key in nm.option_keys(name)]
    return sorted([name for name in cls.field_names()
                   if name not in skip and name not in nm.OPTION_CLASSES] + options)


def builder_from_args(case: str, settings: Sequence[str]) -> SceneBuilder:
    """The case's builder with ``key=value`` overrides applied (and checked).

    Raises:
        CliError: unknown case or key, or a value of the wrong type.
        SceneError: a value the builder refuses (a scene file's errors name the key's path).
    """
    if is_scene_file(case):
        return load_scene_file(case, settings).builder
    if case in FLUME_CASES:
        return flume_builder(case, {o.key: o.text for o in overrides.parse(settings)})
    if case not in CASES:
        raise CliError(f"case: unknown case {case!r}{did_you_mean(case, ALL_CASES)}; valid "
                       f"cases: {', '.join(ALL_CASES)} or a scene file FILE.toml")
    cls, fixed = CASES[case]
    valid = settable_keys(case)
    hints = typing.get_type_hints(cls)
    values: dict[str, Any] = {}
    option_items: dict[str, str] = {}
    for item in overrides.parse(settings):
        if item.key not in valid:
            why = (f"is fixed by the case {case}" if item.key in fixed
                   else f"is unknown for {case}{did_you_mean(item.key, valid)}")
            raise CliError(f"--set: key {item.key!r} {why}; valid keys: {', '.join(valid)}")
        if item.key.partition(".")[0] in nm.OPTION_CLASSES:
            option_items[item.key] = item.text
        else:
            values[item.key] = item.typed(hints[item.key])
    if option_items:
        case_builder = cls(**fixed)  # the case's own options, which the items change
        for name in nm.OPTION_CLASSES:
            values[name] = nm.from_settings(name, getattr(case_builder, name), option_items)
    return cls(**fixed, **values)


def _write_json(path: Path, data: dict[str, Any]) -> None:
    write_json_atomic(path, data, indent=2)


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

    A monitor stop (status: its kind), Ctrl-C (``"interrupted"``) or a core error (``"error"``)
    ends the run with its record; whatever happens, ``before_close`` runs, the log gets its
    ``end`` event and the outputs are closed, so what was written so far stays readable.
    """
    status = "ok"
    error: dict[str, Any] | None = None
    try:
        sim.run_schedule(until, schedule, progress=progress, **schedule_options)
    except InstabilityError as exc:
        status = stop_status(exc)
        error = error_record(exc)
    except KeyboardInterrupt as exc:
        status = "interrupted"
        error = error_record(exc)
    except RuntimeError as exc:
        status = "error"
        error = error_record(exc)
    finally:
        if before_close is not None:
            before_close()
        outputs.log.write("end", status=status, t=sim.time, steps=sim.steps, error=error)
        outputs.close()
    return status, error


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

    def __call__(self, sim: Simulation) -> None:
        if self.writer is not None and self.file is not None:
            pos = sim.fluid_positions()
            x_front = front_position(pos, self.dp)
            h_column = water_column_height(pos, self.dp)
            self.times.append(sim.time)
            self.fronts.append(x_front)
            self.writer.writerow([repr(sim.time), repr(x_front), repr(h_column)])
            self.file.flush()  # rows so far survive a crash or an instability
        if self.log is not None:
            self.log.sample(sim, **({"x_front": self.fronts[-1]} if self.fronts else {}))
        if sim.time >= self._next_report:
            front = f", front {self.fronts[-1]:.3f} m" if self.fronts else ""
            self.say(f"  t = {sim.time:.3f} s, {sim.steps} steps, dt = {sim.dt:.3g} s{front}")
            while self._next_report <= sim.time:
                self._next_report += self.until / 10.0


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


def _run_options(args: argparse.Namespace, scene: SceneFile) -> tuple[Path, float | None, bool]:
    """Output folder, snapshot interval and progress bar of a run: the command line first,
    then the scene file's [output] table, then the defaults."""
    out = Path(args.out or scene.output.directory or default_folder(scene))
    if args.sample_every is None:
        args.sample_every = scene.output.sample_every
    _positive_option("--sample-every", args.sample_every)
    snapshot_every = _positive_option("--snapshot-every", args.snapshot_every)
    if snapshot_every is None:
        snapshot_every = scene.output.snapshot_every
    if args.progress is None:
        progress = sys.stderr.isatty() and not args.quiet
    else:
        progress = bool(args.progress)
    return out, snapshot_every, progress


def cmd_run(args: argparse.Namespace) -> int:
    """``watersim run``: run a case or a scene file, write summary.json, log.jsonl (and
    front.csv for dam breaks, snapshots when asked)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        scene = _run_input(args)
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
    name = scene.name
    if args.sample_every is None:
        args.sample_every = 0.01
    keeper = _last_good_keeper(args)
    sim = builder.build()  # the core's checks (memory, ...) come before the output folder
    rundir.claim_folder(out, args.overwrite)
    out.mkdir(parents=True, exist_ok=True)
    until = float(builder.until)  # type: ignore[arg-type]
    is_dambreak = isinstance(builder, DamBreak)
    threads = rayon_threads()
    say: Callable[[str], None] = (lambda _line: None) if args.quiet else print
    say(
        f"watersim {__version__}: {name}, {sim.n_particles} particles "
        f"({sim.n_fluid} fluid), dp = {builder.dp:g} m, until {until:g} s, {threads} threads"
    )
    say(estimate_cost(sim, until, threads).line())
    meter = SpeedMeter(sim, until, say)
    outputs = RunOutputs(out, snapshot_every)
    outputs.log.write("start", case=name, n_particles=sim.n_particles, dp=builder.dp,
                      until=until, threads=threads, version=__version__)

    t_start = time.perf_counter()
    front_file = open(out / "front.csv", "w", newline="", encoding="utf-8") if is_dambreak else None
    recorder = _Recorder(front_file, float(builder.dp), until,  # type: ignore[arg-type]
                         (lambda _line: None) if progress else say, outputs.log)

    def sample(s: Simulation) -> None:
        recorder(s)
        keeper(s)
        meter(s)

    status, error = _run_recorded(
        sim, until, [(args.sample_every, sample), *outputs.schedule()], progress, outputs,
        front_file.close if front_file is not None else None,
    )
    wall = time.perf_counter() - t_start

    summary: dict[str, Any] = {
        **run_record(RUN_FIELDS, sim, case=name, status=status, until=until, wall_s=wall,
                     threads=threads),
        **outputs.summary(),
        "builder": builder.as_dict(),
        "scene": sim.scene,
        "params": sim.params(),
    }
    if error is not None:
        summary["error"] = error
        summary["last_good"] = keeper.save_record(_last_good_path(args, out))
    if is_dambreak:
        assert isinstance(builder, DamBreak)
        summary["front_csv"] = "front.csv"
        summary["front_final"] = recorder.fronts[-1] if recorder.fronts else None
        summary["martin_moyce"] = _martin_moyce_summary(builder, recorder.times, recorder.fronts)
    elif isinstance(builder, Tank) and sim.n_fluid:
        summary["still_water"] = _still_water_checks(sim, builder)
    _write_json(out / "summary.json", summary)

    mm = summary.get("martin_moyce") or {}
    if mm.get("rms_rel_error") is not None:
        lead = mm.get("mean_lead_s")
        lead_text = "not reached" if lead is None else f"{lead:+.3f} s"
        reference = MARTIN_MOYCE_DESCRIPTIONS.get(mm["reference"], mm["reference"])
        say(
            f"  front vs Martin & Moyce 1952 ({reference}): RMS relative error "
            f"{100 * mm['rms_rel_error']:.1f} % over {mm['n_points']} points; "
            f"mean time lead of the simulation {lead_text}"
        )
    say(f"{status}: {sim.steps} steps to t = {sim.time:.4g} s in {wall:.1f} s; wrote {out}")
    if error is not None:
        print(f"watersim: run stopped: {_stop_message(error)}", file=sys.stderr)
        return 130 if status == "interrupted" else 1
    return 0


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
    builder = scene.builder
    assert isinstance(builder, FlumeScene)
    name = scene.name
    keeper = _last_good_keeper(args)
    checkpoint_every = rundir.CheckpointEvery.parse(args.checkpoint_every or DEFAULT_CHECKPOINTS)
    say: Callable[[str], None] = (lambda _line: None) if args.quiet else print
    until = float(builder.until)  # type: ignore[arg-type]
    every = args.sample_every if args.sample_every is not None else max(until / 20.0, 1e-6)
    # the core's checks (memory, ...) come before the output folder
    sim = builder.build() if resumed is None else resumed.sim
    assert isinstance(sim, FlumeSimulation)
    if resumed is None:
        rundir.claim_folder(out, args.overwrite)
    out.mkdir(parents=True, exist_ok=True)
    if resumed is None:
        rundir.write_scene(out, scene)
    checkpointer = rundir.Checkpointer(out, checkpoint_every, poll=every, scene=scene)
    threads = rayon_threads()
    start = "" if resumed is None else f", resumed at t = {resumed.time:.6g} s"
    say(
        f"watersim {__version__}: {name}, {sim.n_particles} particles "
        f"({sim.n_fluid} fluid), dp = {builder.dp:g} m, until {until:g} s{start}, "
        f"{threads} threads"
    )
    cost = estimate_cost(sim, until, threads)
    say(cost.line())
    meter = SpeedMeter(sim, until, say)
    outputs = RunOutputs(out, snapshot_every, None if resumed is None else resumed.time)
    outputs.log.write("start" if resumed is None else "resume", case=name,
                      n_particles=sim.n_particles, dp=builder.dp, until=until, threads=threads,
                      version=__version__, warnings=notes,
                      **({} if resumed is None else {"checkpoint": str(resumed.checkpoint),
                                                     "t": resumed.time, "steps": resumed.steps}))
    csv_path = out / "gauges.csv"
    t_start = time.perf_counter()
    next_report = [0.0]

    def write_records(s: FlumeSimulation) -> dict[str, Path]:
        s.write_gauges_csv(csv_path)
        return s.write_velocity_csvs(out)

    def on_sample(s: Simulation) -> None:
        assert isinstance(s, FlumeSimulation)
        write_records(s)  # records so far survive a crash or an instability
        outputs.log.sample(s)
        if not progress and s.time >= next_report[0]:
            say(f"  t = {s.time:.3f} s, {s.steps} steps, dt = {s.dt:.3g} s, "
                f"wall {time.perf_counter() - t_start:.1f} s")
            while next_report[0] <= s.time:
                next_report[0] += until / 10.0

    def sample_and_keep(s: Simulation) -> None:
        on_sample(s)
        keeper(s)
        meter(s)

    def finish() -> None:
        write_records(sim)
        if sim.time >= until:  # a finished run can be extended: resume --until
            checkpointer.save(sim)

    status, error = _run_recorded(
        sim, until, [(every, sample_and_keep), *outputs.schedule()], progress,
        outputs, finish, origin=0.0, initial=resumed is None, last=checkpointer.schedule(),
    )
    wall = time.perf_counter() - t_start

    analysis: dict[str, Any]
    try:
        analysis = sim.analyse()
        # reference comparisons belong to the built-in cases, not to a file of the same name
        extras_case = "" if scene.path is not None else name
        analysis.update(case_extras(extras_case, builder, analysis))
    except Exception as exc:  # noqa: BLE001 - the analysis must not lose the run's outputs
        analysis = {"error": error_record(exc)}
    analysis["case"] = name
    analysis["status"] = status
    _write_json(out / "analysis.json", analysis)

    summary: dict[str, Any] = {
        **run_record(RUN_FIELDS, sim, case=name, status=status, until=until, wall_s=wall,
                     threads=threads),
        **outputs.summary(),
        "gauges_csv": "gauges.csv",
        "velocity_csv": {name: velocity_csv_name(name)
                         for name in {**sim.gauges.velocity, **sim.gauges.windows}},
        "analysis_json": "analysis.json",
        "scene_toml": rundir.SCENE_FILE,
        "checkpoints": [str(p.relative_to(out)) for p in rundir.checkpoints(out)],
        **({} if resumed is None else {"resumed_from": {
            "checkpoint": str(resumed.checkpoint.relative_to(out)), "time": resumed.time,
            "steps": resumed.steps}}),
        "n_gauge_samples": int(sim.gauges.t.size),
        "warnings": notes,
        "builder": builder.as_dict(),
        "scene": sim.scene,
        "params": sim.params(),
    }
    if error is not None:
        summary["error"] = error
        summary["last_good"] = keeper.save_record(_last_good_path(args, out))
    _write_json(out / "summary.json", summary)
    for line in [*headline(name, analysis), *analysis_notes(analysis)]:
        say(line)
    say(f"{status}: {sim.steps} steps to t = {sim.time:.4g} s in {wall:.1f} s; wrote {out}")
    if error is not None:
        print(f"watersim: run stopped: {_stop_message(error)}", file=sys.stderr)
        return 130 if status == "interrupted" else 1
    return 0


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
    """Why a run stopped, never empty (a Ctrl-C carries no message of its own)."""
    if error.get("message"):
        return str(error["message"])
    if error.get("type") == "KeyboardInterrupt":
        return "interrupted (Ctrl-C); the outputs written so far are kept"
    return str(error.get("type") or "unknown error")


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
    sim = reopened.sim
    analysis = sim.analyse(t_start=args.t_start)
    name = reopened.scene.name
    # reference comparisons belong to the built-in cases, not to a file of the same name
    extras_case = "" if reopened.scene.path is not None else name
    analysis.update(case_extras(extras_case, reopened.scene.builder, analysis))
    analysis["case"] = name
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
# watersim bench


def _scaled_to(
    build: Callable[[float], Simulation], dp: float, dim: int, n_target: int
) -> Simulation:
    """``build(dp)`` with dp chosen so that the particle count is about ``n_target``."""
    sim = build(dp)
    for _ in range(6):
        n = sim.n_particles
        if abs(n - n_target) <= 0.03 * n_target:
            break
        dp *= (n / n_target) ** (1.0 / dim)
        # one simulation alive at a time: otherwise the process's peak resident memory, which
        # `watersim bench` reports next to the counted bytes, holds two of them
        del sim
        sim = build(dp)
    return sim


def _dsph_overrides(case: str, settings: list[str]) -> dict[str, str]:
    """The one override a DualSPHysics case takes: ``force_precision`` (the cases run f32 pair
    terms, as DualSPHysics forms its forces in float; WaterSim's own default is f64). Empty
    without ``--set``: the case's own scene then stands as it is."""
    chosen: dict[str, str] = {}
    for item in overrides.parse(settings):
        if item.key != "force_precision":
            raise CliError(
                f"--set: {case} reproduces DualSPHysics' settings exactly and takes no "
                f"override but force_precision, got {item.key!r} (use --particles N to scale it)"
            )
        precision = item.text.strip()
        if precision not in FORCE_PRECISIONS:
            raise CliError(
                f"--set: force_precision must be one of {', '.join(FORCE_PRECISIONS)}, "
                f"got {precision!r}"
            )
        chosen["force_precision"] = precision
    return chosen


def _bench_simulation(args: argparse.Namespace) -> Simulation:
    """The simulation ``watersim bench`` times: a built-in dam break or a DualSPHysics case."""
    if args.case in DSPH_CASES:
        chosen = _dsph_overrides(args.case, args.set or [])
        spec = DSPH_CASES[args.case]
        dim = int(dsph_scene(args.case)["dim"])

        def build(dp: float) -> Simulation:
            return Simulation({**dsph_scene(args.case, dp), **chosen})

        return _scaled_to(build, spec.dp, dim, args.particles) if args.particles else build(spec.dp)
    builder = builder_from_args(args.case, args.set or [])
    assert builder.dp is not None
    if not args.particles:
        return builder.build()

    def build_scaled(dp: float) -> Simulation:
        return builder.replace(dp=dp).build()

    return _scaled_to(build_scaled, builder.dp, builder.dim, args.particles)


def _peak_rss_bytes() -> int | None:
    """Peak resident memory of this process [bytes] (Linux ru_maxrss is in KiB)."""
    try:
        import resource

        return int(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss) * 1024
    except (ImportError, OSError):  # pragma: no cover - not on Linux
        return None


def _current_rss_bytes() -> int | None:
    """Resident memory of this process now [bytes] (``VmRSS`` of /proc/self/status)."""
    try:
        with open("/proc/self/status", encoding="ascii") as status:
            for line in status:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) * 1024
    except OSError:  # pragma: no cover - not on Linux
        pass
    return None  # pragma: no cover


def _timed_steps(sim: Simulation, steps: int, threads: int | None = None) -> float:
    """Wall time [s] of ``steps`` steps (on a pool of ``threads`` threads if given)."""
    t0 = time.perf_counter()
    sim.step(steps, threads=threads)
    return time.perf_counter() - t0


def _thread_counts(text: str) -> tuple[int, int]:
    """``--compare-threads A,B``: two different positive thread counts."""
    try:
        a, b = (int(part) for part in text.split(","))
    except ValueError:
        raise CliError(
            f"--compare-threads: two thread counts A,B, e.g. 1,2; got {text!r}") from None
    if a < 1 or b < 1 or a == b:
        raise CliError(f"--compare-threads: two different counts of at least 1, got {text!r}")
    return a, b


def _compare_threads(sim: Simulation, counts: tuple[int, int], steps: int,
                     rounds: int) -> dict[str, Any]:
    """Times ``rounds`` rounds of K steps on A threads and K steps on B threads, in turn on one
    simulation (the results do not depend on the thread count), each pool started and warmed by
    one untimed step first. On a shared host single runs scatter by 10-30 % from one minute to
    the next; the two runs of a round are adjacent in time, so their ratio drifts far less. The
    order alternates (A B, B A, ...) so that a steady drift favours neither. ``speedup`` is the
    median over rounds of time on A / time on B."""
    a, b = counts
    for t in counts:
        sim.step(1, threads=t)
    runs: dict[int, list[float]] = {a: [], b: []}
    ratios: list[float] = []
    for r in range(rounds):
        wall: dict[int, float] = {}
        for t in (a, b) if r % 2 == 0 else (b, a):
            wall[t] = _timed_steps(sim, steps, threads=t)
            runs[t].append(wall[t])
        ratios.append(wall[a] / wall[b])
    n = sim.n_particles
    return {
        "threads": [a, b],
        "rounds": rounds,
        "wall_s_runs": {str(t): runs[t] for t in counts},
        "us_per_particle_step": {
            str(t): 1e6 * statistics.median(runs[t]) / (n * steps) for t in counts},
        "speedup_runs": ratios,
        "speedup": statistics.median(ratios),
        # each count's least disturbed run: on a shared host the host's stalls only ever add
        # time, and a stall costs two threads more than one (each waits at every join for the
        # other), so the fastest rounds are the nearest to a quiet machine's ratio
        "speedup_fastest": min(runs[a]) / min(runs[b]),
    }


def cmd_bench(args: argparse.Namespace) -> int:
    """``watersim bench``: time K steps of a dam break scaled to about N particles."""
    if args.case not in BENCH_CASES:
        raise CliError(f"--case: unknown case {args.case!r}; valid: {', '.join(BENCH_CASES)}")
    if args.particles is not None and args.particles < 10:
        raise CliError(f"--particles: must be at least 10, got {args.particles}")
    if args.steps < 1 or args.warmup < 0:
        raise CliError("--steps: must be at least 1 (and --warmup not negative)")
    if args.repeat < 1:
        raise CliError(f"--repeat: must be at least 1, got {args.repeat}")
    compare = _thread_counts(args.compare_threads) if args.compare_threads is not None else None
    sizes = _scaling_sizes(args) if args.scaling is not None else None
    # what the process holds before the simulation exists (interpreter, NumPy, the module)
    baseline_rss = _current_rss_bytes()
    if sizes is not None:
        return _bench_scaling(args, sizes, baseline_rss)
    result = _bench_record(args, compare, baseline_rss)
    _print_bench(result, args.json)
    return 0 if "error" not in result else 1


def _print_bench(result: dict[str, Any], as_json: bool) -> None:
    if as_json:
        print(json.dumps(_jsonable(result), allow_nan=False))
    else:
        for key, value in result.items():
            print(f"{key:>22}: {value}")


def _scaling_sizes(args: argparse.Namespace) -> list[int]:
    """``--scaling N1,N2,...``: two or more particle counts of at least 10, in ascending order
    (the process's peak memory then belongs to the last, largest run)."""
    if args.particles is not None or args.compare_threads is not None:
        raise CliError("--scaling: sets the particle counts itself; drop --particles and "
                       "--compare-threads")
    try:
        sizes = [int(part) for part in args.scaling.split(",")]
    except ValueError:
        raise CliError(f"--scaling: particle counts N1,N2,..., e.g. 20000,200000,2000000; "
                       f"got {args.scaling!r}") from None
    if len(sizes) < 2 or min(sizes) < 10 or len(set(sizes)) != len(sizes):
        raise CliError(f"--scaling: two or more different counts of at least 10, got "
                       f"{args.scaling!r}")
    return sorted(sizes)


def _bench_scaling(args: argparse.Namespace, sizes: list[int], baseline_rss: int | None) -> int:
    """``watersim bench --scaling``: the case at each size in turn (one simulation alive at a
    time), each timed as a plain bench run, then the spreads and the fit of
    :func:`watersim.bench_scaling.fit_scaling`."""
    records = []
    for n in sizes:
        record = _bench_record(argparse.Namespace(**{**vars(args), "particles": n}), None,
                               baseline_rss)
        records.append(record)
        if "error" in record:
            break
    result: dict[str, Any] = {"case": args.case, "threads": rayon_threads(),
                              "steps": args.steps, "warmup_steps": args.warmup,
                              "repeat": args.repeat, "runs": records}
    failed = any("error" in r for r in records)
    if not failed:
        result["scaling"] = fit_scaling([
            ScalingRun(n_particles=r["n_particles"], n_fluid=r["n_fluid"], wall_s=r["wall_s"],
                       steps=r["steps"], fluid_pairs=r["fluid_pairs"],
                       force_evaluations_per_step=r["force_evaluations_per_step"])
            for r in records])
    if args.json:
        _print_bench(result, True)
    else:
        print(_scaling_table(result))
    return 1 if failed else 0


def _scaling_table(result: dict[str, Any]) -> str:
    """``watersim bench --scaling`` without ``--json``: one line per size, then the spreads and
    the fit."""
    lines = [f"{result['case']} on {result['threads']} thread(s), {result['steps']} steps "
             f"after {result['warmup_steps']}, median of {result['repeat']}",
             f"{'particles':>10} {'fluid':>10} {'walls':>6} {'us/particle-step':>17} "
             f"{'us/fluid particle':>18} {'ns/pair':>8} {'bytes/particle':>15}"]
    for r in result["runs"]:
        if "error" in r:
            lines.append(f"{r['n_particles']:>10} stopped: {r['error']}")
            continue
        walls = 1 - r["n_fluid"] / r["n_particles"]
        per_fluid = r["us_per_particle_step"] * r["n_particles"] / r["n_fluid"]
        pair = f"{r['ns_per_pair']:8.2f}" if r["ns_per_pair"] else f"{'-':>8}"
        lines.append(f"{r['n_particles']:>10} {r['n_fluid']:>10} {walls:6.0%} "
                     f"{r['us_per_particle_step']:17.3f} {per_fluid:18.3f} {pair} "
                     f"{r['bytes_per_particle']:15.1f}")
    scaling = result.get("scaling")
    if scaling is not None:
        limit = scaling["spread_limit"]
        for key, spread in scaling["spread"].items():
            verdict = "within" if scaling["within_limit"][key] else "beyond"
            lines.append(f"spread {key.replace('_', ' ')}: {spread:.1%} ({verdict} {limit:.0%})")
        fit = scaling["fit"]
        lines.append(f"fit: {fit['us_per_fluid_particle_step']:.3f} us per fluid particle-step, "
                     f"{fit['us_per_wall_particle_step']:.3f} us per wall particle-step, largest "
                     f"residual {fit['max_abs_relative_residual']:.1%}")
    return "\n".join(lines)


def _bench_record(args: argparse.Namespace, compare: tuple[int, int] | None,
                  baseline_rss: int | None) -> dict[str, Any]:
    """One bench run of ``args``' case: its timings, work, memory and settings."""
    sim = _bench_simulation(args)
    params = sim.params()
    threads = rayon_threads()
    status = "ok"
    error: dict[str, Any] | None = None
    wall = math.nan
    comparison: dict[str, Any] | None = None
    # one wall time per run of K steps: on a shared host single runs scatter by 10-30 %
    walls: list[float] = []
    try:
        if args.warmup:
            sim.step(args.warmup)
        walls = [_timed_steps(sim, args.steps) for _ in range(args.repeat)]
        wall = statistics.median(walls)
        if compare is not None:
            comparison = _compare_threads(sim, compare, args.steps, args.repeat)
    except InstabilityError as exc:
        status, error = str(getattr(exc, "kind", "unstable")), error_record(exc)
    n = sim.n_particles
    # before the pair count, whose sorted copy of the positions is not the simulation's
    peak_rss = _peak_rss_bytes()
    # the work of the timed steps: the pairs at their end (the flow changes little over them)
    pairs = sim.fluid_pairs()
    evaluations = sim.force_evaluations_per_step()
    pair_terms = pairs * evaluations * args.steps
    result: dict[str, Any] = {
        "case": args.case,
        "status": status,
        "dim": sim.dim,
        "n_particles": n,
        "n_fluid": sim.n_fluid,
        "steps": args.steps,
        "warmup_steps": args.warmup,
        "repeat": args.repeat,
        # the median of the runs' wall times; every figure per step below is from it
        "wall_s": wall,
        "wall_s_runs": walls,
        "particle_steps_per_s": n * args.steps / wall if wall > 0 else None,
        "us_per_particle_step": 1e6 * wall / (n * args.steps) if wall > 0 else None,
        # O(N) in the neighbour work: the pairs per fluid particle grow with the share of the
        # fluid a support away from every wall and from the surface, the time per pair not
        "fluid_pairs": pairs,
        "pairs_per_fluid_particle": pairs / sim.n_fluid if sim.n_fluid else None,
        "force_evaluations_per_step": evaluations,
        "ns_per_pair": 1e9 * wall / pair_terms if wall > 0 and pair_terms else None,
        "bytes_per_particle": sim.memory_bytes() / n,
        "memory_bytes": sim.memory_bytes(),
        "threads": threads,
        "dp": params.get("dp", sim.scene["dp"]),
        "h": params.get("h"),
        "kernel": sim.scene["kernel"],
        "coefh": sim.scene["coefh"],
        "viscosity": sim.scene["viscosity"]["model"],
        "diffusion": sim.scene["diffusion"]["model"],
        "integrator": sim.scene["integrator"]["scheme"],
        "force_precision": sim.scene.get("force_precision", "f64"),
        "sim_time": sim.time,
        "peak_rss_bytes": peak_rss,
        "baseline_rss_bytes": baseline_rss,
        # the simulation's share of the peak, to set against bytes_per_particle
        "peak_rss_above_baseline_per_particle": (
            (peak_rss - baseline_rss) / n if peak_rss is not None and baseline_rss is not None
            else None),
        "version": __version__,
    }
    if args.case in DSPH_CASES:
        spec = DSPH_CASES[args.case]
        result["dsph_particles"] = spec.particles
        result["dsph_us_per_particle_step"] = {"1": spec.dsph_us[0], "2": spec.dsph_us[1]}
        result["target_us_per_particle_step"] = {"1": spec.target_us[0], "2": spec.target_us[1]}
        us = result["us_per_particle_step"]
        if threads in (1, 2) and us:
            result["speedup_vs_dsph"] = spec.dsph_us[threads - 1] / us
            result["meets_target"] = us <= spec.target_us[threads - 1]
    if comparison is not None:
        result["thread_comparison"] = comparison
    if error is not None:
        result["error"] = error
    return result


# ------------------------------------------------------------------------------------------------
# watersim scene


def cmd_scene(args: argparse.Namespace) -> int:
    """``watersim scene``: print the scene JSON of a case, checked by Python and by the core."""
    builder = builder_from_args(args.case, args.set or [])
    scene = builder.to_scene()
    sim = Simulation(scene)
    shown = {"scene": scene, "params": sim.params(), "n_particles": sim.n_particles}
    print(json.dumps(_jsonable(shown), indent=2))
    return 0


# ------------------------------------------------------------------------------------------------
# watersim show-scene, watersim plot


def cmd_show_scene(args: argparse.Namespace) -> int:
    """``watersim show-scene``: a case's full, resolved scene as a scene file (TOML)."""
    if args.reference:
        if args.case is not None or args.set:
            raise CliError("--reference: takes no CASE or --set")
        sys.stdout.write(reference_markdown())
        return 0
    if args.case is None:
        raise CliError(f"CASE: required; a scene file FILE.toml or one of: {', '.join(ALL_CASES)}")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # wave-validity warnings: `watersim run` prints them
        scene = _run_input(args)
    header = f"watersim show-scene {args.case}" + "".join(f" --set {s}" for s in args.set or [])
    header += f"\nwatersim {__version__}; run it with: watersim run FILE.toml"
    sys.stdout.write(scene_dumps(scene.builder, scene.output, header=header))
    return 0


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
    """The argument parser of the ``watersim`` command."""
    parser = argparse.ArgumentParser(
        prog="watersim", description="WaterSim: weakly-compressible SPH wave flume."
    )
    parser.add_argument("--version", action="version", version=f"watersim {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    set_help = "override a case parameter (repeatable), e.g. --set dp=0.04"
    run = sub.add_parser("run", help="run a built-in case or a scene file (FILE.toml)")
    run.add_argument(
        "case", metavar="CASE", help=f"a scene file FILE.toml, or one of: {', '.join(ALL_CASES)}"
    )
    run.add_argument("--set", action="append", metavar="KEY=VALUE", help=set_help)
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
    run.add_argument(
        "--progress",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="show a progress bar on stderr (default: when stderr is a terminal)",
    )
    run.add_argument("--quiet", action="store_true", help="print nothing but errors")
    run.add_argument(
        "--save-last-good",
        metavar="FILE",
        help="where a run that stops early writes its last good state, a checkpoint to continue "
        "from (default OUT/last_good.npz)",
    )
    run.add_argument(
        "--last-good-every",
        type=int,
        default=1,
        metavar="K",
        help="take the in-memory last good state every K samples (default 1)",
    )
    checkpoint_help = ("flume runs: write a checkpoint (DIR/checkpoints/, the last two kept) every "
                       "S simulated seconds (S or sim:S) or every S seconds of wall time (wall:S, "
                       "wall:10min, wall:2h); default wall:600. A finished run always writes one.")
    run.add_argument("--checkpoint-every", metavar="SPEC", default=None, help=checkpoint_help)
    run.set_defaults(func=cmd_run)

    resume = sub.add_parser(
        "resume", help="continue a killed, stopped or finished flume run from its last checkpoint"
    )
    resume.add_argument("directory", metavar="DIR", help="the run's output folder")
    resume.add_argument("--until", type=float, default=None, metavar="T",
                        help="new end time [s] (default: the run's own)")
    resume.add_argument("--checkpoint-every", metavar="SPEC", default=None, help=checkpoint_help)
    resume.add_argument("--sample-every", type=float, default=None, metavar="S",
                        help="how often gauges.csv is rewritten (default until/20)")
    resume.add_argument("--snapshot-every", type=float, default=None, metavar="S",
                        help="particle snapshots every S simulated seconds (default: the run's)")
    resume.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                        help="show a progress bar on stderr (default: when stderr is a terminal)")
    resume.add_argument("--quiet", action="store_true", help="print nothing but errors")
    resume.add_argument("--save-last-good", metavar="FILE", help=argparse.SUPPRESS)
    resume.add_argument("--last-good-every", type=int, default=1, metavar="K",
                        help="take the in-memory last good state every K samples (default 1)")
    resume.set_defaults(func=cmd_resume)

    analyse = sub.add_parser(
        "analyse", help="recompute analysis.json of a flume run from its stored records"
    )
    analyse.add_argument("directory", metavar="DIR", help="the run's output folder")
    analyse.add_argument("--t-start", type=float, default=None, metavar="T",
                         help="start every gauge's analysis window at T [s] (default: the wave's "
                         "arrival plus the ramp plus one period, per gauge)")
    analyse.add_argument("--out", metavar="FILE", help="where to write (default DIR/analysis.json)")
    analyse.set_defaults(func=cmd_analyse)

    show = sub.add_parser(
        "show-scene", help="print a case's full scene as a scene file (TOML), or --reference"
    )
    show.add_argument("case", metavar="CASE", nargs="?",
                      help=f"a scene file FILE.toml, or one of: {', '.join(ALL_CASES)}")
    show.add_argument("--set", action="append", metavar="KEY=VALUE", help=set_help)
    show.add_argument("--reference", action="store_true",
                      help="print the scene-file reference (docs/scene-reference.md) instead")
    show.set_defaults(func=cmd_show_scene)

    plot = sub.add_parser("plot", help="draw PNG figures of a finished run folder")
    plot.add_argument("directory", metavar="DIR", help="the run's output folder (--out)")
    plot.add_argument("--out", metavar="FIGDIR", help="where the PNGs go (default DIR/plots)")
    plot.set_defaults(func=cmd_plot)

    bench = sub.add_parser(
        "bench", help="time the solver on a dam break or a DualSPHysics reference case"
    )
    bench.add_argument("--case", default="dambreak2d", help=f"one of: {', '.join(BENCH_CASES)}")
    bench.add_argument(
        "--particles",
        type=int,
        default=None,
        metavar="N",
        help="about this many particles (default: the case's own dp)",
    )
    bench.add_argument("--steps", type=int, default=20, metavar="K", help="timed steps (20)")
    bench.add_argument("--warmup", type=int, default=3, metavar="W", help="untimed steps (3)")
    bench.add_argument("--repeat", type=int, default=1, metavar="R",
                       help="time R runs of K steps in a row and report their median (1)")
    bench.add_argument("--compare-threads", metavar="A,B", default=None,
                       help="then R rounds of K steps on A threads and K on B threads in turn, "
                            "and the median ratio of their times (thread_comparison)")
    bench.add_argument("--scaling", metavar="N1,N2,...", default=None,
                       help="time the case at each of these particle counts in turn and fit "
                            "the time per step to fluid and wall particles (scaling)")
    bench.add_argument("--set", action="append", metavar="KEY=VALUE", help=set_help)
    bench.add_argument("--json", action="store_true", help="print one JSON object")
    bench.set_defaults(func=cmd_bench)

    scene = sub.add_parser("scene", help="print a case's scene JSON and derived parameters")
    scene.add_argument("case", metavar="CASE", help=f"one of: {', '.join(ALL_CASES)}")
    scene.add_argument("--set", action="append", metavar="KEY=VALUE", help=set_help)
    scene.set_defaults(func=cmd_scene)

    add_stress_parser(sub)
    _validation.add_parser(sub)  # watersim validate (watersim.validation.sweep)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``watersim`` command; returns the exit code."""
    args = build_parser().parse_args(argv)
    args.argv = list(sys.argv[2:] if argv is None else argv[1:])  # for reports
    try:
        return int(args.func(args))
    except (CliError, SceneError, _validation.ValidateError) as exc:
        print(f"watersim: error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:
        print(f"watersim: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
