"""Hostile and careless input to ``watersim run``, counted: every settable key of a dam break and
of a flume set to absurd values, absurd run options, and the files and scenes issue 33 lists.

    python3 scripts/hostile_sweep.py --jobs 2 --json hostile.json

Each input is one ``watersim run ...`` (``watersim.cli.main``, what ``python3 -m watersim``
runs) in a child forked from the sweep, which imported the package once (``--set until=...``
first, so that an accepted input runs briefly; a later ``--set until=`` of the input wins), one
thread, with a wall limit. Outcomes:

- ``refused``: exit 2 with one ``watersim: error: FIELD: reason`` line naming a field or option
  (the field is the text before the first ``:``), no traceback;
- ``ran``: exit 0, or 1 with ``summary.json`` holding a stability monitor's stop;
- ``crash``: anything else: a signal, a traceback, a Rust panic, another exit code, an exit 2
  whose message names nothing;
- ``slow``: past the wall limit, where the run's own cost line (particles x steps x the
  reference time per particle-step) promised more CPU time than the limit: an accepted input
  whose run is long (a time step made tiny by a huge sound speed, gravity or depth; Ctrl-C
  stops it); ``hang``: past the wall limit otherwise.

The counts go to stdout and, with ``--json``, every input with its outcome and message.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
VALUES = ["0", "-1", "1e-300", "1e300", "nan", "inf", "-inf", "1e9", "'text'", "[1, 2]",
          "99999999999999999999999", "true"]
"""What each settable key is set to."""
OPTIONS = {
    "--sample-every": ["0", "-1", "1e-300", "nan", "inf", "1e300"],
    "--snapshot-every": ["0", "-1", "1e-300", "nan", "inf"],
    "--last-good-every": ["0", "-1", "1e30", "x"],
    "--save-last-good": ["/dev/null", "/proc/version", "/nonexistent/dir/x.npz", "."],
    "--checkpoint-every": ["0", "-1", "nan", "x"],
}
"""Run options and their absurd values (``--checkpoint-every`` only where it applies)."""
CASES = {"dambreak2d": ["--set", "dp=0.1", "--set", "until=0.02"],
         "flume2d": ["--set", "dp=0.05", "--set", "until=0.05"]}
"""The cases swept and their brief-run settings."""
COST = re.compile(r"cost: ([\d,]+) particles x at least ([\d,]+) steps; .* at ([\d.]+) us per")
"""The run's own cost line (``watersim.cost``): particles, steps and the reference speed."""
NAMED = re.compile(r"^watersim(?: \w+)?: error: (?:argument )?([^\s:]+): \S")
"""A refusal's line: ``watersim: error: FIELD: reason`` (argparse: ``argument --OPTION: ...``)."""


def _specials(tmp: Path) -> list[tuple[str, list[str]]]:
    """The inputs of issue 33's text that are files or scenes rather than one value."""
    deep = tmp / "deep.toml"
    deep.write_text("v = " + "[" * 5000 + "]" * 5000 + "\n")
    big = tmp / "bigint.toml"
    big.write_text("type = \"dambreak\"\ndp = " + "1" * 5000 + "\n")
    fifo = tmp / "fifo.toml"
    if not fifo.exists():
        os.mkfifo(fifo)
    zero = tmp / "zero.toml"
    if not zero.exists():
        zero.symlink_to("/dev/zero")
    window = tmp / "window.toml"
    window.write_text("type = \"flume\"\ndp = 0.02\nuntil = 10.0\n[flume]\nlength = 6.0\n"
                      "depth = 0.3\n[wave]\ntype = \"regular\"\nheight = 0.04\nperiod = 1.2\n"
                      "[[gauges]]\ntype = \"window\"\nmin = [1.0, 0.05]\nmax = [3.0, 0.35]\n"
                      "n = [1000, 1000]\ninterval = 0.01\n")
    outside = tmp / "outside.toml"
    outside.write_text("type = \"dambreak\"\ndp = 0.1\nuntil = 0.01\n[output]\n"
                       "directory = \"../../x\"\n")
    return [
        ("deep TOML", [str(deep)]),
        ("5000-digit integer", [str(big)]),
        ("FIFO scene file", [str(fifo)]),
        ("/dev/zero scene file", [str(zero)]),
        ("1000 x 1000 window every 0.01 s", [str(window)]),
        ("output directory outside", [str(outside)]),
        ("NUL in --out", ["dambreak2d", "--out", "a\0b"]),
        ("unknown case", ["dambreak9d"]),
        ("20,000-level --set key", ["dambreak2d", "--set", ".".join(["a"] * 20000) + "=1"]),
    ]


def inputs(tmp: Path) -> list[tuple[str, list[str]]]:
    """Every input: a label and the arguments after ``watersim run``."""
    from watersim.builtin_cases import settable_keys

    out = []
    for case, brief in CASES.items():
        for key in settable_keys(case):
            for value in VALUES:
                out.append((f"{case} {key}={value}", [case, *brief, "--set", f"{key}={value}"]))
        for option, values in OPTIONS.items():
            if option == "--checkpoint-every" and not case.startswith("flume"):
                continue
            out += [(f"{case} {option} {v}", [case, *brief, option, v]) for v in values]
    return out + _specials(tmp)


def classify(proc: subprocess.CompletedProcess[str] | None, out: Path, limit: float
             ) -> tuple[str, str]:
    """The outcome of one input (see the module's description) and its last stderr line."""
    summary = out / "summary.json"
    if proc is None:
        stdout = out.parent / "stdout"
        cost = COST.search(stdout.read_text(errors="replace")) if stdout.exists() else None
        if cost:
            particles, steps, us = (float(g.replace(",", "")) for g in cost.groups())
            seconds = particles * steps * us * 1e-6
            if seconds > limit:
                return "slow", f"its cost line promised {seconds:.3g} s of CPU ({steps:.3g} steps)"
        return "hang", "at the wall limit, its cost line promising less"
    err = proc.stderr.strip()
    last = err.splitlines()[-1] if err else ""
    broken = any(s in err for s in ("Traceback", "panicked", "RUST_BACKTRACE"))
    if proc.returncode == 2 and not broken:
        named = NAMED.match(last)
        if named:
            return "refused", last
        return "crash", f"exit 2 naming nothing: {last}"
    if proc.returncode in (0, 1) and not broken and summary.is_file():
        return "ran", last
    return "crash", f"exit {proc.returncode}: {last or proc.stdout.strip()[-200:]}"


def _child(argv: list[str], tmp: Path, stdout: Path, stderr: Path) -> None:
    """The forked child: ``watersim.cli.main(argv)`` (what ``python3 -m watersim`` runs), its
    output into files; exits with its code (a traceback is printed and exits 1)."""
    code = 70
    try:
        os.chdir(tmp)
        os.dup2(os.open(stdout, os.O_WRONLY | os.O_CREAT), 1)
        os.dup2(os.open(stderr, os.O_WRONLY | os.O_CREAT), 2)
        os.dup2(os.open(os.devnull, os.O_RDONLY), 0)
        from watersim.cli import main as cli_main

        code = cli_main(argv)
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else 1
    except BaseException:  # noqa: BLE001 - a traceback is an outcome here
        import traceback

        traceback.print_exc()
        code = 1
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)


def run_one(label: str, args: list[str], tmp: Path, limit: float) -> dict[str, object]:
    """``watersim run ARGS`` in a child forked from this process (the package is imported
    once, here), killed past ``limit`` seconds."""
    out = Path(tempfile.mkdtemp(dir=tmp))
    argv = ["run", *args] + ([] if "--out" in args else ["--out", str(out / "run")])
    stdout, stderr = out / "stdout", out / "stderr"
    pid = os.fork()
    if pid == 0:
        _child(argv, tmp, stdout, stderr)
    deadline = time.monotonic() + limit
    proc: subprocess.CompletedProcess[str] | None = None
    while True:
        done, status = os.waitpid(pid, os.WNOHANG)
        if done:
            proc = subprocess.CompletedProcess(
                argv, os.waitstatus_to_exitcode(status),
                stdout.read_text(errors="replace") if stdout.exists() else "",
                stderr.read_text(errors="replace") if stderr.exists() else "")
            break
        if time.monotonic() > deadline:
            os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
            break
        time.sleep(0.05)
    outcome, message = classify(proc, out / "run", limit)
    return {"input": label, "outcome": outcome, "message": message}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--limit", type=float, default=120.0, help="wall limit per input [s]")
    parser.add_argument("--json", type=Path)
    parser.add_argument("--only", metavar="REGEX", help="the inputs whose label matches")
    args = parser.parse_args()
    os.environ.update(RAYON_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    sys.path.insert(0, str(ROOT / "python"))
    import watersim.cli  # noqa: F401 - imported once, before the children are forked
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        cases = [c for c in inputs(tmp) if args.only is None or re.search(args.only, c[0])]
        with ThreadPoolExecutor(args.jobs) as pool:
            records = list(pool.map(lambda c: run_one(c[0], c[1], tmp, args.limit), cases))
    counts: dict[str, int] = {}
    for r in records:
        counts[str(r["outcome"])] = counts.get(str(r["outcome"]), 0) + 1
    tally = ", ".join(f"{k} {v}" for k, v in sorted(counts.items()))
    print(f"inputs tried {len(records)}: {tally}")
    for r in records:
        if r["outcome"] in ("crash", "hang", "slow"):
            print(f"  {r['outcome']}: {r['input']}: {r['message']}")
    if args.json:
        args.json.write_text(json.dumps({"counts": counts, "inputs": records}, indent=1))
    return 1 if counts.get("crash") or counts.get("hang") else 0


if __name__ == "__main__":
    sys.exit(main())
