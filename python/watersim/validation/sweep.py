"""``watersim validate``: run validation cases at several resolutions, locally or on a Dask
cluster, keep every run's record in a JSON file (rewritten after each run, so a long sweep
keeps what it has) and write the report.

::

    watersim validate [CASE ...] [--resolutions a,b,c] [--quick] [--json FILE] [--report DIR]
                      [--jobs N] [--scheduler ADDRESS] [--from-json FILE] [--set KEY=VALUE ...]

Runs go to a :class:`concurrent.futures.ProcessPoolExecutor` with ``--jobs`` workers (1: in this
process, with a tqdm bar per run), or, with ``--scheduler``, to the Dask distributed scheduler
at ADDRESS (``Client(address).submit``), so the same sweep runs on a cluster unchanged. The
scheduler must be trusted: Dask sends the results back pickled, and unpickling runs code.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import importlib.util
import json
import math
import multiprocessing
import os
import platform
import sys
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path
from typing import Any

from .._jsonio import write_json_atomic
from ..errors import did_you_mean
from ..overrides import parse as parse_items
from .cases import CASES, run_case

__all__ = ["add_parser", "cmd_validate", "machine_info", "parse_resolutions", "plan",
           "run_sweep"]


class ValidateError(Exception):
    """Bad ``watersim validate`` input (the CLI prints it and exits with code 2)."""


def parse_resolutions(text: str) -> tuple[float, ...]:
    """``"10,20,40"`` -> (10.0, 20.0, 40.0); every value a positive finite number."""
    values = []
    for item in text.split(","):
        item = item.strip()
        try:
            v = float(item)
        except ValueError:
            raise ValidateError(f"--resolutions: expected numbers separated by commas, "
                                f"got {item!r}") from None
        if not (v > 0.0 and math.isfinite(v)):
            raise ValidateError(f"--resolutions: each resolution must be positive, got {item!r}")
        values.append(v)
    if not values:
        raise ValidateError("--resolutions: give at least one resolution")
    return tuple(values)


def plan(cases: Sequence[str], resolutions: Sequence[float] | None, quick: bool
         ) -> list[tuple[str, float]]:
    """The (case, resolution) runs of a sweep, in report order.

    Args:
        cases: case names (empty: all).
        resolutions: the same resolutions for every case; None: each case's own
            (``quick_resolutions`` with ``quick``).
    """
    names = list(cases) or list(CASES)
    for name in names:
        if name not in CASES:
            raise ValidateError(f"case: unknown validation case {name!r}"
                                f"{did_you_mean(name, CASES)}; valid cases: {', '.join(CASES)}")
    tasks = []
    for name in dict.fromkeys(names):
        case = CASES[name]
        res = resolutions if resolutions is not None else (
            case.quick_resolutions if quick else case.resolutions)
        tasks += [(name, float(r)) for r in res]
    return tasks


INSTALL_HINTS: dict[str, str] = {
    "scipy": "pip install scipy (or the package with its extra: pip install '.[validation]')",
    "distributed": "pip install 'dask[distributed]' (or pip install '.[dask]')",
}
"""How to install each optional package a sweep may need."""


def check_modules(tasks: Sequence[tuple[str, float]], scheduler: str | None) -> None:
    """Refuse, before anything runs, a sweep that needs a package that is not installed: a
    case's :attr:`Case.modules`, and Dask's ``distributed`` for ``--scheduler``.

    Raises:
        ValidateError: one line naming the package, what needs it and how to install it.
    """
    needs: dict[str, list[str]] = {}
    for name in dict.fromkeys(name for name, _ in tasks):
        for module in CASES[name].modules:
            needs.setdefault(module, []).append(name)
    if scheduler is not None:
        needs.setdefault("distributed", []).append("--scheduler")
    for module, users in needs.items():
        if importlib.util.find_spec(module) is None:
            cases = [u for u in users if u in CASES]
            without = f", or leave out {', '.join(cases)}" if cases else ""
            raise ValidateError(f"{' and '.join(users)}: needs {module}, which is not "
                                f"installed: {INSTALL_HINTS.get(module, f'pip install {module}')}"
                                f"{without}")


def machine_info() -> dict[str, Any]:
    """CPU model, logical CPUs, OS and Python version (no host name)."""
    cpu = platform.processor() or ""
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:  # pragma: no cover - not Linux
        pass
    return {"cpu": cpu, "cpus": os.cpu_count(), "system": platform.platform(terse=True),
            "python": platform.python_version()}


def _write_runs(path: Path, records: list[dict[str, Any]]) -> None:
    """Rewrite the JSON list of runs atomically (a crash leaves the previous version)."""
    write_json_atomic(path, records, indent=1)


def _stamp(record: dict[str, Any]) -> dict[str, Any]:
    record["finished_at"] = _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")
    return record


def _remote_run(name: str, resolution: float, quick: bool,
                settings: dict[str, str] | None = None) -> dict[str, Any]:
    """A run in a worker process: the record with the worker's machine and finish time."""
    record = run_case(name, resolution, quick, False, settings)
    record["machine"] = machine_info()
    return _stamp(record)


SCHEDULER_CONNECT_TIMEOUT_S = 30.0
"""How long ``--scheduler`` waits for the scheduler to answer before it gives up [s]."""


def parse_scheduler(address: str) -> str:
    """The Dask scheduler address ``--scheduler`` takes: ``tcp://HOST:PORT`` or ``HOST:PORT``
    (TCP). Refused with :class:`ValidateError` naming ``--scheduler``: an empty or malformed
    address, a port outside 1-65535, and the protocols the command line cannot serve
    (``tls://`` needs certificates it has no option for; ``inproc://`` is a scheduler inside
    this process, which there is not)."""
    text = address.strip()
    scheme, sep, rest = text.partition("://")
    if not sep:
        scheme, rest = "tcp", text
    if scheme != "tcp":
        raise ValidateError(f"--scheduler: the protocol {scheme}:// is not supported here "
                            f"(give tcp://HOST:PORT), got {address!r}")
    host, colon, port = rest.rpartition(":")
    if not colon or not host or "/" in rest or any(c.isspace() for c in rest):
        raise ValidateError(f"--scheduler: expected tcp://HOST:PORT, got {address!r}")
    if not (port.isdigit() and len(port) <= 5 and 1 <= int(port) <= 65535):
        raise ValidateError(f"--scheduler: the port must be a number from 1 to 65535, "
                            f"got {address!r}")
    return f"tcp://{host}:{int(port)}"


def check_scheduler_answers(address: str, timeout: float = SCHEDULER_CONNECT_TIMEOUT_S) -> None:
    """Ask the scheduler at ``address`` who it is, within ``timeout`` [s] for each of connect,
    send and answer: refused with :class:`ValidateError` naming ``--scheduler`` when nothing
    answers, or something that is not a Dask scheduler does (``Client()`` itself waits without
    end on a listener that accepts and stays silent)."""
    import asyncio

    from distributed.comm import connect

    async def identity() -> Any:
        comm = await asyncio.wait_for(connect(address, timeout=timeout), timeout)
        try:
            await asyncio.wait_for(comm.write({"op": "identity"}), timeout)
            return await asyncio.wait_for(comm.read(), timeout)
        finally:
            comm.abort()

    try:
        answer = asyncio.run(identity())
    except (OSError, TimeoutError) as exc:
        raise ValidateError(f"--scheduler: no Dask scheduler answered at {address} within "
                            f"{timeout:g} s ({type(exc).__name__}{': ' if str(exc) else ''}"
                            f"{exc})") from None
    if not (isinstance(answer, dict) and answer.get("type") == "Scheduler"):
        raise ValidateError(f"--scheduler: {address} answered, but not as a Dask scheduler")


def run_sweep(
    tasks: Sequence[tuple[str, float]],
    quick: bool = False,
    jobs: int = 1,
    scheduler: str | None = None,
    json_path: str | Path | None = None,
    progress: bool = False,
    on_record: Callable[[dict[str, Any]], None] | None = None,
    settings: dict[str, str] | None = None,
) -> list[dict[str, Any]]:
    """Run every (case, resolution) task and return the records in task order.

    Args:
        tasks: from :func:`plan`.
        quick: the cases' shortened durations.
        jobs: local worker processes (1: run here, one after the other).
        scheduler: a Dask distributed scheduler address; the runs are submitted there instead.
        json_path: rewrite this JSON list after every finished run.
        progress: tqdm bars (per run with one job here, else over the runs).
        on_record: called with each record as it arrives.
        settings: numerical ``--set`` items (key -> text) for every case (each must take them:
            :func:`check_settings`).
    """
    if jobs < 1:
        raise ValidateError(f"--jobs: must be at least 1, got {jobs}")
    path = Path(json_path) if json_path is not None else None
    slots: list[dict[str, Any] | None] = [None] * len(tasks)

    def done(i: int, record: dict[str, Any]) -> None:
        slots[i] = record
        if path is not None:
            _write_runs(path, [r for r in slots if r is not None])
        if on_record is not None:
            on_record(record)

    if scheduler is None and jobs == 1:
        machine = machine_info()
        for i, (name, res) in enumerate(tasks):
            record = run_case(name, res, quick, progress, settings)
            record["machine"] = machine
            done(i, _stamp(record))
        return [r for r in slots if r is not None]

    bar: Any = None
    if progress:
        from tqdm import tqdm  # type: ignore[import-untyped]

        bar = tqdm(total=len(tasks), desc="validation runs", unit="run")
    try:
        if scheduler is not None:
            try:
                from dask.distributed import Client
                from dask.distributed import as_completed as dask_completed
            except ImportError:
                raise ValidateError("--scheduler: needs dask.distributed "
                                    "(pip install 'watersim[dask]')") from None
            address = parse_scheduler(scheduler)
            check_scheduler_answers(address)
            with Client(address, timeout=SCHEDULER_CONNECT_TIMEOUT_S) as client:
                futures = {client.submit(_remote_run, name, res, quick, settings, pure=False): i
                           for i, (name, res) in enumerate(tasks)}
                for fut in dask_completed(futures):
                    done(futures[fut], fut.result())
                    if bar is not None:
                        bar.update()
        else:
            # spawn, not fork: a forked child inherits rayon's global thread pool without its
            # threads and blocks on the first parallel loop of the core
            context = multiprocessing.get_context("spawn")
            with ProcessPoolExecutor(max_workers=jobs, mp_context=context) as pool:
                pending = {pool.submit(_remote_run, name, res, quick, settings): i
                           for i, (name, res) in enumerate(tasks)}
                for fut in as_completed(pending):
                    done(pending[fut], fut.result())
                    if bar is not None:
                        bar.update()
    finally:
        if bar is not None:
            bar.close()
    return [r for r in slots if r is not None]


def check_settings(tasks: Sequence[tuple[str, float]], items: Sequence[str] | None
                   ) -> dict[str, str] | None:
    """The ``--set`` items as key -> text, refused before anything runs when a case of the sweep
    takes no settings (:attr:`Case.settable`) or a key or value is not one its scene takes
    (each case's scene is built once, at its first resolution)."""
    if not items:
        return None
    settings = {o.key: o.text for o in parse_items(items)}
    for name in dict.fromkeys(name for name, _ in tasks):
        if not CASES[name].settable:
            takers = ", ".join(c.name for c in CASES.values() if c.settable)
            raise ValidateError(f"--set: {name} takes no settings (cases that do: {takers})")
    from .._core import SceneError
    from ..flume_cases import FlumeCaseError

    for name in dict.fromkeys(name for name, _ in tasks):
        res = next(r for n, r in tasks if n == name)
        try:
            make = CASES[name].scene
            assert make is not None
            make(CASES[name].dp(res), settings)
        except (FlumeCaseError, SceneError) as exc:
            raise ValidateError(str(exc)) from None
    return settings


def _header(args: argparse.Namespace, records: Sequence[dict[str, Any]]) -> list[str]:
    """Report lines: the command, the dates, the machine."""
    shown: list[str] = []
    skip = False
    for item in args.argv or []:  # the notes are printed below, not in the command
        if skip:
            skip = False
        elif item == "--note":
            skip = True
        elif not item.startswith("--note="):
            shown.append(item)
    command = " ".join(["watersim validate", *shown])
    dates = sorted(r["finished_at"] for r in records if r.get("finished_at"))
    machine = next((r["machine"] for r in records if r.get("machine")), machine_info())
    threads = sorted({int(r["threads"]) for r in records if r.get("threads") is not None})
    lines = [f"- Command: `{command}`"]
    if dates:
        lines.append(f"- Runs finished between {dates[0]} and {dates[-1]} (UTC)")
    lines.append(f"- Machine: {machine.get('cpu')}, {machine.get('cpus')} logical CPUs, "
                 f"{machine.get('system')}, Python {machine.get('python')}; rayon threads per "
                 f"run: {', '.join(str(t) for t in threads)}")
    cpu = sum(float(r.get("cpu_s") or 0.0) for r in records)
    wall = sum(float(r.get("wall_s") or 0.0) for r in records)
    lines.append(f"- {len(records)} runs, {wall:.0f} s wall and {cpu:.0f} s CPU in all")
    lines += [f"- {note}" for note in args.note or []]
    return lines


def cmd_validate(args: argparse.Namespace) -> int:
    """``watersim validate``: run the sweep (or load it with ``--from-json``) and report.

    Returns 0 when every run finished, 1 when a run was stopped or failed.
    """
    from .report import write_report

    if args.note and args.report is None:
        raise ValidateError("--note: only used with --report")
    if args.from_json is not None:
        used = [flag for flag, given in (("--resolutions", args.resolutions is not None),
                                         ("--quick", args.quick), ("--jobs", args.jobs != 1),
                                         ("--scheduler", args.scheduler is not None),
                                         ("--json", args.json is not None),
                                         ("--set", bool(args.set))) if given]
        if used:
            raise ValidateError(f"{used[0]}: not used with --from-json (it runs nothing)")
        if args.report is None:
            raise ValidateError("--from-json: give --report DIR (there is nothing else to do)")
        try:
            records = json.loads(Path(args.from_json).read_text("utf-8"))
        except (OSError, json.JSONDecodeError) as exc:
            raise ValidateError(f"--from-json: cannot read {args.from_json}: {exc}") from None
        if not isinstance(records, list) or not all(isinstance(r, dict) for r in records):
            raise ValidateError(f"--from-json: {args.from_json} does not hold a list of runs "
                                "(JSON objects, as --json writes them)")
        if args.cases:
            plan(args.cases, None, False)  # checks the names
            records = [r for r in records if r.get("case") in args.cases]
    else:
        resolutions = parse_resolutions(args.resolutions) if args.resolutions else None
        tasks = plan(args.cases, resolutions, args.quick)
        if args.jobs < 1:
            raise ValidateError(f"--jobs: must be at least 1, got {args.jobs}")
        if args.scheduler is not None and args.jobs != 1:
            raise ValidateError("--jobs: not used with --scheduler (the cluster's workers run "
                                "the sweep)")
        if args.scheduler is not None:
            parse_scheduler(args.scheduler)
        check_modules(tasks, args.scheduler)
        settings = check_settings(tasks, args.set)
        if args.json is not None:
            Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        progress = sys.stderr.isatty()

        def say(r: dict[str, Any]) -> None:
            errs = ", ".join(f"{k} {v:.3g}" for k, v in r["errors"].items() if v is not None)
            print(f"{r['case']} resolution {r['resolution']:g} (dp {r['dp']:.4g} m, "
                  f"{r['n_particles']} particles): {r['status']} in {r['wall_s']:.1f} s; "
                  f"{errs or 'no errors measured'}", flush=True)
            if r["status"] != "ok":
                print(f"  {r.get('message')}", flush=True)

        records = run_sweep(tasks, args.quick, args.jobs, args.scheduler, args.json, progress,
                            say, settings)
    if args.report is not None:
        readme = write_report(records, args.report, header=_header(args, records))
        print(f"wrote {readme}")
    if args.json is not None:
        print(f"wrote {args.json}")
    return 0 if all(r.get("status") == "ok" for r in records) else 1


def add_parser(sub: Any) -> argparse.ArgumentParser:
    """Register ``validate`` on the ``watersim`` sub-command parsers."""
    p = sub.add_parser(
        "validate", help="run validation cases at several resolutions and report error against "
        "run time",
        description="Run validation cases at several resolutions and report error against run "
        "time. Without CASE and --quick it runs every case at its own resolutions, about two "
        "hours on two cores (the committed report, docs/validation/README.md: 30 runs, 6,800 s "
        "of wall time one after another, the longest, kimmoun2d, 40 minutes; absorption2d, added "
        "later, takes 8 minutes of CPU at H/dp 1 and about three times that at 1.5); --quick "
        "runs every case once, coarse and short, in a few minutes (absorption2d: 2.5 minutes "
        "of CPU). standing2d needs scipy (pip install "
        "scipy, or pip install '.[validation]'); --scheduler needs dask[distributed]; both are "
        "checked before anything runs.")
    p.add_argument("cases", nargs="*", metavar="CASE", help=f"any of: {', '.join(CASES)} "
                   "(default: all)")
    p.add_argument("--resolutions", metavar="A,B,C", help="resolutions for every case given "
                   "(particles per the case's characteristic length; default: each case's own)")
    p.add_argument("--quick", action="store_true", help="coarse resolutions, short durations")
    p.add_argument("--json", metavar="FILE", help="write the runs here (rewritten after each)")
    p.add_argument("--report", metavar="DIR", help="write DIR/README.md and PNG plots")
    p.add_argument("--jobs", type=int, default=1, metavar="N", help="local worker processes (1)")
    p.add_argument("--scheduler", metavar="ADDRESS", help="run on this Dask distributed "
                   "scheduler (tcp://host:8786); it must be trusted: the results it sends are "
                   "unpickled here")
    p.add_argument("--from-json", metavar="FILE", help="report on the runs in FILE instead of "
                   "running")
    settable = ", ".join(c.name for c in CASES.values() if c.settable)
    p.add_argument("--set", action="append", metavar="KEY=VALUE", help="a numerical setting "
                   f"of the cases that take them ({settable}), e.g. --set "
                   "shifting.model=delta_plus (repeatable; recorded in each run's "
                   "details.settings)")
    p.add_argument("--note", action="append", metavar="TEXT", help="a line for the report's "
                   "header, e.g. what else ran on the machine (repeatable)")
    p.set_defaults(func=cmd_validate)
    return p
