"""``watersim bench``: the solver's speed on a dam break or a DualSPHysics reference case, or
(``--against``) side by side with DualSPHysics (:mod:`watersim.bench_against`).

One record per run: the median wall time of K steps after W untimed ones, the work (fluid pairs,
force evaluations per step), the memory (counted bytes and the process's resident set) and the
settings; ``--compare-threads A,B`` adds the ratio of two thread counts timed in turn,
``--scaling N1,N2,...`` the fit of :func:`watersim.bench_scaling.fit_scaling` over several sizes.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import time
from collections.abc import Callable
from typing import Any

from . import overrides
from ._core import InstabilityError
from ._jsonio import json_ready as _jsonable
from ._version import __version__
from .bench_against import cmd_against
from .bench_cases import DSPH_CASES, dsph_scene
from .bench_scaling import ScalingRun, fit_scaling
from .builtin_cases import SET_HELP, builder_from_args
from .errors import CliError, did_you_mean
from .numerics import FORCE_PRECISIONS, TensileCorrection
from .runrecord import error_record, rayon_threads
from .scenefile import is_scene_file, scene_files_near
from .simulation import Simulation

__all__ = ["BENCH_CASES", "add_parser", "cmd_bench"]

BENCH_CASES: tuple[str, ...] = ("dambreak2d", "dambreak3d", *DSPH_CASES)
"""The cases ``watersim bench`` times: the built-in dam breaks and the DualSPHysics cases."""


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


def _dsph_overrides(case: str, settings: list[str]) -> dict[str, Any]:
    """The two overrides a DualSPHysics case takes, to time what they cost:
    ``force_precision`` (the cases run f32 pair terms, as DualSPHysics forms its forces in
    float; WaterSim's own default is f64) and ``tensile_correction`` (``none``, or
    ``monaghan`` for a cubic-spline case: ``dsph-dambreak3d`` runs it, as DualSPHysics does).
    Empty without ``--set``: the case's own scene then stands as it is."""
    chosen: dict[str, Any] = {}
    for item in overrides.parse(settings):
        if item.key == "tensile_correction":
            law = item.text.strip().lower()
            if law not in ("none", *TensileCorrection.MODELS):
                raise CliError(f"--set: tensile_correction must be none or one of "
                               f"{', '.join(TensileCorrection.MODELS)}, got {item.text!r}")
            chosen["tensile_correction"] = None if law == "none" else {"model": law}
            continue
        if item.key != "force_precision":
            raise CliError(
                f"--set: {case} reproduces DualSPHysics' settings exactly and takes no "
                f"override but force_precision and tensile_correction, got {item.key!r} (use "
                "--particles N to scale it)"
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
    most = max_threads()
    if max(a, b) > most:
        raise CliError(f"--compare-threads: at most {most} threads (8 per CPU of this machine), "
                       f"got {text!r}")
    return a, b


def max_threads() -> int:
    """The most threads ``--compare-threads`` starts: 8 per CPU, at least 64 (oversubscription
    is worth measuring; tens of thousands of threads only exhaust the machine)."""
    return max(64, 8 * (os.cpu_count() or 1))


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
    """``watersim bench``: time K steps of a dam break scaled to about N particles, or
    (``--against``) WaterSim and DualSPHysics side by side."""
    if args.against is not None:
        _refuse_with_against(args)
        return cmd_against(args)
    for option in ("gencase", "xml", "interval", "rounds", "cpu", "workdir"):
        if getattr(args, option) is not None:
            raise CliError(f"--{option}: only with --against (the side-by-side comparison)")
    for option, value in PLAIN_DEFAULTS.items():
        if getattr(args, option) is None:
            setattr(args, option, value)
    if args.case not in BENCH_CASES and not is_scene_file(args.case):
        raise CliError(f"--case: unknown case {args.case!r}"
                       f"{did_you_mean(args.case, [*BENCH_CASES, *scene_files_near(args.case)])}; "
                       f"valid: {', '.join(BENCH_CASES)} or a scene file FILE.toml")
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


def _refuse_with_against(args: argparse.Namespace) -> None:
    """``--against`` takes its cases from ``--xml`` and times whole intervals: the options of a
    plain bench run are refused with it, not ignored. Its own options get their defaults."""
    for option in (*PLAIN_DEFAULTS, "particles", "compare_threads", "scaling", "set"):
        if getattr(args, option) is not None:
            raise CliError(f"--{option.replace('_', '-')}: not with --against (its cases are "
                           "the --xml files, each run over --interval from t = 0)")
    for option, value in AGAINST_DEFAULTS.items():
        if getattr(args, option) is None:
            setattr(args, option, value)


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
        "tensile_correction": (sim.scene.get("tensile_correction") or {}).get("model"),
        "riemann": (sim.scene.get("riemann") or {}).get("model"),
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
        # GenCase's count for the case; a speed ratio to DualSPHysics is only what
        # `watersim bench --against` measures side by side (watersim.bench_against)
        result["dsph_particles"] = DSPH_CASES[args.case].particles
    if comparison is not None:
        result["thread_comparison"] = comparison
    if error is not None:
        result["error"] = error
    return result


def add_parser(sub: Any) -> argparse.ArgumentParser:
    """Register ``bench`` on the ``watersim`` sub-command parsers."""
    bench = sub.add_parser(
        "bench", help="time the solver on a dam break or a DualSPHysics reference case"
    )
    bench.add_argument("--case", default=None,
                       help=f"one of: {', '.join(BENCH_CASES)}, or a scene file FILE.toml "
                       "(default dambreak2d)")
    bench.add_argument(
        "--particles",
        type=int,
        default=None,
        metavar="N",
        help="about this many particles (default: the case's own dp)",
    )
    bench.add_argument("--steps", type=int, default=None, metavar="K", help="timed steps (20)")
    bench.add_argument("--warmup", type=int, default=None, metavar="W", help="untimed steps (3)")
    bench.add_argument("--repeat", type=int, default=None, metavar="R",
                       help="time R runs of K steps in a row and report their median (1)")
    bench.add_argument("--compare-threads", metavar="A,B", default=None,
                       help="then R rounds of K steps on A threads and K on B threads in turn, "
                            "and the median ratio of their times (thread_comparison)")
    bench.add_argument("--scaling", metavar="N1,N2,...", default=None,
                       help="time the case at each of these particle counts in turn and fit "
                            "the time per step to fluid and wall particles (scaling)")
    bench.add_argument("--set", action="append", metavar="KEY=VALUE", help=SET_HELP)
    bench.add_argument("--json", action="store_true", help="print one JSON object")
    _add_against_arguments(bench)
    bench.set_defaults(func=cmd_bench)
    return bench


PLAIN_DEFAULTS: dict[str, Any] = {"case": "dambreak2d", "steps": 20, "warmup": 3, "repeat": 1}
"""The defaults of a plain bench run's options (refused with ``--against``)."""

AGAINST_DEFAULTS: dict[str, Any] = {"interval": 0.2, "rounds": 3, "cpu": "0"}
"""The defaults of ``--against``'s own options (refused without ``--against``)."""


def _add_against_arguments(bench: argparse.ArgumentParser) -> None:
    """The side-by-side comparison's options (:mod:`watersim.bench_against`)."""
    group = bench.add_argument_group(
        "side by side with DualSPHysics",
        "--against runs DualSPHysics' CPU binary on the GenCase output of each --xml and "
        "WaterSim on the matching dsph-* case, alternately, pinned to the cores of --cpu with "
        "one thread per core, and prints the ratios of their times with the other processes' "
        "load on those cores")
    group.add_argument("--against", metavar="DUALSPHYSICS", default=None,
                       help="DualSPHysics' CPU binary (e.g. DualSPHysics5.4CPU_linux64)")
    group.add_argument("--gencase", metavar="GENCASE", default=None,
                       help="DualSPHysics' GenCase binary (GenCase_linux64)")
    group.add_argument("--xml", metavar="CASE.xml", action="append", default=None,
                       help="a DualSPHysics case XML, repeatable: " + ", ".join(
                           f"{spec.xml} ({case})" for case, spec in DSPH_CASES.items()))
    group.add_argument("--interval", type=float, default=None, metavar="S",
                       help=f"simulated seconds from t = 0 ({AGAINST_DEFAULTS['interval']})")
    group.add_argument("--rounds", type=int, default=None, metavar="R",
                       help=f"rounds per case, the order alternating "
                            f"({AGAINST_DEFAULTS['rounds']})")
    group.add_argument("--cpu", default=None, metavar="N[,M...]",
                       help="the cores both codes are pinned to, one thread each: 0 for one "
                            f"thread, 0,1 for two ({AGAINST_DEFAULTS['cpu']})")
    group.add_argument("--workdir", metavar="DIR", default=None,
                       help="keep GenCase's output and both codes' logs here (default: a "
                            "temporary folder, removed)")
