"""``watersim bench --against DUALSPHYSICS``: WaterSim and DualSPHysics side by side.

For each DualSPHysics case XML the user names (``--xml``, recognised by its file name:
:data:`watersim.bench_cases.DSPH_CASES`' ``xml`` fields), the harness

1. runs GenCase (``--gencase``) on it once, into a work folder;
2. runs, ``--rounds`` times and alternating which goes first, DualSPHysics' CPU binary on the
   generated case and WaterSim on the matching bench case, each from t = 0 over the same
   simulated interval (``--interval``), each as its own process pinned by ``taskset`` to the
   cores named (``--cpu 0``, or ``--cpu 0,1`` for two), one thread per core
   (``-ompthreads:N``; ``RAYON_NUM_THREADS=N``);
3. reads the pinned cores' busy time from ``/proc/stat`` before and after each run and takes
   the run's own CPU time (the child's rusage) off it: what is left is other processes' load on
   those cores (``foreign``, a share of the cores' time over the run), reported beside the
   hypervisor's ``steal`` share;
4. prints per case both codes' particles, steps and run times and, over the rounds, the
   median and range of two ratios, DualSPHysics' time over WaterSim's: per particle-step and
   per simulated second (the second counts the steps each code takes, the first does not).

The run time compared is each code's own time loop, set-up excluded: DualSPHysics' "Simulation
Runtime" in its ``Run.out`` (wall time after its initialisation; the simulated time reached is
that runtime over its "Runtime per physical second") and the wall time of WaterSim's
``Simulation.run`` after the scene is built. Neither writes particle files (DualSPHysics runs
with ``-sv:none`` and one output interval as long as the run).
"""

from __future__ import annotations

import json
import math
import os
import platform
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from .bench_cases import DSPH_CASES
from .errors import CliError

__all__ = ["CoreTicks", "RunTiming", "core_ticks", "cores_ticks", "parse_cpus",
           "parse_run_out", "ratio_summary", "run_against", "xml_cases"]

DSPH_FIELDS = {
    "particles": r"Particles of simulation \(initial\)\.*:\s*([\d,.]+)",
    "runtime_s": r"Simulation Runtime\.*:\s*([-+\d.eE]+)\s*sec",
    "runtime_per_sim_s": r"Runtime per physical second\.*:\s*([-+\d.eE]+)\s*sec",
    "steps": r"Steps of simulation\.*:\s*([\d,.]+)",
}
"""What the harness reads from DualSPHysics' ``Run.out`` (``JSph::ShowResume``)."""


@dataclass(frozen=True)
class RunTiming:
    """One timed run of one code.

    Attributes:
        code: ``"watersim"`` or ``"dualsphysics"``.
        particles: particles at the start.
        steps: time steps taken.
        sim_time_s: simulated time reached [s].
        runtime_s: wall time of the code's time loop [s] (set-up excluded).
        process_wall_s: wall time of the whole process [s].
        process_cpu_s: user + system CPU time of the whole process [s].
        foreign: other processes' busy time on the pinned cores over the cores' time (their
            number times the process's wall time).
        steal: the hypervisor's steal time on those cores over the cores' time.
    """

    code: str
    particles: int
    steps: int
    sim_time_s: float
    runtime_s: float
    process_wall_s: float
    process_cpu_s: float
    foreign: float
    steal: float

    @property
    def us_per_particle_step(self) -> float:
        return 1e6 * self.runtime_s / (self.particles * self.steps)

    @property
    def s_per_sim_s(self) -> float:
        """Run time per simulated second."""
        return self.runtime_s / self.sim_time_s


def _integer(text: str) -> int:
    """An integer DualSPHysics printed with thousands separators (``171,496``)."""
    return int(re.sub(r"[,.]", "", text))


def parse_run_out(text: str, source: str = "Run.out") -> dict[str, float]:
    """Particles, steps, run time and simulated time of a finished DualSPHysics run, from its
    ``Run.out``. Raises :class:`RuntimeError` naming what is missing, or an interrupted run."""
    if "[Simulation INTERRUPTED" in text:
        raise RuntimeError(f"{source}: DualSPHysics reports the simulation INTERRUPTED")
    found: dict[str, float] = {}
    for key, pattern in DSPH_FIELDS.items():
        match = re.search(pattern, text)
        if match is None:
            raise RuntimeError(f"{source}: no {pattern.split(chr(92))[0]!r} line (did the run "
                               "finish?)")
        found[key] = _integer(match[1]) if key in ("particles", "steps") else float(match[1])
    if not (found["runtime_s"] > 0 and found["runtime_per_sim_s"] > 0 and found["steps"] > 0):
        raise RuntimeError(f"{source}: runtime, runtime per physical second and steps must be "
                           f"positive, got {found}")
    found["sim_time_s"] = found["runtime_s"] / found["runtime_per_sim_s"]
    return found


@dataclass(frozen=True)
class CoreTicks:
    """Cumulative time of one CPU from ``/proc/stat`` [s]: busy (user, nice, system, irq,
    softirq) and stolen by the hypervisor."""

    busy_s: float
    steal_s: float


def core_ticks(cpu: int, stat_text: str | None = None) -> CoreTicks:
    """The ``cpuN`` line of ``/proc/stat`` (or of ``stat_text``) in seconds."""
    if stat_text is None:
        stat_text = Path("/proc/stat").read_text(encoding="ascii")
    hz = os.sysconf("SC_CLK_TCK")
    for line in stat_text.splitlines():
        fields = line.split()
        if fields and fields[0] == f"cpu{cpu}":
            user, nice, system, _idle, _iowait, irq, softirq, steal = (
                int(v) for v in fields[1:9])
            return CoreTicks((user + nice + system + irq + softirq) / hz, steal / hz)
    raise RuntimeError(f"/proc/stat: no line for cpu{cpu}")


def cores_ticks(cpus: list[int], stat_text: str | None = None) -> CoreTicks:
    """The summed ``cpuN`` lines of ``cpus``, read from one snapshot of ``/proc/stat``."""
    if stat_text is None:
        stat_text = Path("/proc/stat").read_text(encoding="ascii")
    ticks = [core_ticks(cpu, stat_text) for cpu in cpus]
    return CoreTicks(sum(t.busy_s for t in ticks), sum(t.steal_s for t in ticks))


def _timed_process(cmd: list[str], env: dict[str, str], cpus: list[int],
                   log: Path) -> tuple[float, float, float, float, str]:
    """Runs ``cmd`` pinned to ``cpus``; its wall and CPU time, the foreign and steal shares of
    those cores over the run, and its standard output. Its output goes to ``log`` too."""
    before_core = cores_ticks(cpus)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run(["taskset", "-c", ",".join(map(str, cpus)), *cmd], env=env,
                          capture_output=True, text=True, check=False)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    after_core = cores_ticks(cpus)
    log.write_text(proc.stdout + proc.stderr, encoding="utf-8")
    if proc.returncode != 0:
        raise RuntimeError(f"{cmd[0]} exited with code {proc.returncode} (output: {log}):\n"
                           + "\n".join((proc.stdout + proc.stderr).splitlines()[-8:]))
    own = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    capacity = wall * len(cpus)
    foreign = max(0.0, after_core.busy_s - before_core.busy_s - own) / capacity
    steal = (after_core.steal_s - before_core.steal_s) / capacity
    return wall, own, min(foreign, 1.0), steal, proc.stdout


def _run_dualsphysics(binary: Path, case_path: Path, out: Path, interval: float,
                      cpus: list[int]) -> RunTiming:
    if out.exists():
        shutil.rmtree(out)
    threads = len(cpus)
    cmd = [str(binary), str(case_path), str(out), "-cpu", f"-ompthreads:{threads}",
           f"-tmax:{interval}", f"-tout:{interval}", "-sv:none"]
    env = {**os.environ, "OMP_NUM_THREADS": str(threads)}
    wall, cpu_s, foreign, steal, _ = _timed_process(cmd, env, cpus, out.with_suffix(".log"))
    run_out = out / "Run.out"
    if not run_out.is_file():
        raise RuntimeError(f"{binary}: wrote no {run_out}")
    got = parse_run_out(run_out.read_text(encoding="utf-8", errors="replace"), str(run_out))
    return RunTiming("dualsphysics", int(got["particles"]), int(got["steps"]), got["sim_time_s"],
                     got["runtime_s"], wall, cpu_s, foreign, steal)


def _run_watersim(case: str, interval: float, cpus: list[int], log: Path) -> RunTiming:
    cmd = [sys.executable, "-m", "watersim.bench_against", "worker", case, repr(interval)]
    env = {**os.environ, "RAYON_NUM_THREADS": str(len(cpus))}
    wall, cpu_s, foreign, steal, out = _timed_process(cmd, env, cpus, log)
    got = json.loads(out.strip().splitlines()[-1])
    return RunTiming("watersim", got["particles"], got["steps"], got["sim_time_s"],
                     got["runtime_s"], wall, cpu_s, foreign, steal)


def worker(case: str, interval: float) -> dict[str, Any]:
    """The WaterSim side of a round (run in its own pinned process): builds ``case``, then
    times ``Simulation.run(interval)`` from t = 0."""
    from .bench_cases import dsph_scene
    from .runrecord import rayon_threads
    from .simulation import Simulation

    sim = Simulation(dsph_scene(case))
    steps0 = sim.steps
    t0 = time.perf_counter()
    sim.run(interval)
    runtime = time.perf_counter() - t0
    return {"particles": sim.n_particles, "steps": sim.steps - steps0, "sim_time_s": sim.time,
            "runtime_s": runtime, "threads": rayon_threads()}


def ratio_summary(values: list[float]) -> dict[str, Any]:
    """Median and range of per-round ratios."""
    return {"median": statistics.median(values), "min": min(values), "max": max(values),
            "rounds": values}


def case_summary(rounds: list[dict[str, Any]]) -> dict[str, Any]:
    """Both codes' runs and the ratios (DualSPHysics' time over WaterSim's) over ``rounds``."""
    per_step = [r["dualsphysics"].us_per_particle_step / r["watersim"].us_per_particle_step
                for r in rounds]
    per_sim_s = [r["dualsphysics"].s_per_sim_s / r["watersim"].s_per_sim_s for r in rounds]
    codes: dict[str, Any] = {}
    for code in ("watersim", "dualsphysics"):
        runs = [r[code] for r in rounds]
        codes[code] = {
            "particles": runs[0].particles,
            "steps": statistics.median(r.steps for r in runs),
            "sim_time_s": statistics.median(r.sim_time_s for r in runs),
            "us_per_particle_step": ratio_summary([r.us_per_particle_step for r in runs]),
            "s_per_sim_s": ratio_summary([r.s_per_sim_s for r in runs]),
            "foreign": ratio_summary([r.foreign for r in runs]),
            "steal": ratio_summary([r.steal for r in runs]),
            "runs": [{**asdict(r), "us_per_particle_step": r.us_per_particle_step,
                      "s_per_sim_s": r.s_per_sim_s} for r in runs],
        }
    return {**codes, "ratio_per_particle_step": ratio_summary(per_step),
            "ratio_per_sim_second": ratio_summary(per_sim_s),
            "order": [r["first"] for r in rounds]}


def parse_cpus(text: str) -> list[int]:
    """The cores of ``--cpu``: ``"0"`` or ``"0,1"``, each one this process may run on, none
    twice; one thread per core."""
    allowed = sorted(os.sched_getaffinity(0))
    try:
        cpus = [int(part) for part in str(text).split(",")]
    except ValueError:
        raise CliError(f"--cpu: a core number or a comma-separated list of them, got {text!r}"
                       ) from None
    if len(set(cpus)) != len(cpus):
        raise CliError(f"--cpu: a core named twice in {text!r}")
    for cpu in cpus:
        if cpu not in allowed:
            raise CliError(f"--cpu: CPU {cpu} is not one this process may run on ({allowed})")
    return cpus


def xml_cases(paths: list[str]) -> dict[str, Path]:
    """The bench case of each ``--xml`` path, recognised by its file name."""
    by_name = {spec.xml: case for case, spec in DSPH_CASES.items()}
    cases: dict[str, Path] = {}
    for text in paths:
        path = Path(text)
        case = by_name.get(path.name)
        if case is None:
            raise CliError(f"--xml: {path.name!r} is not a known DualSPHysics case XML; known: "
                           f"{', '.join(sorted(by_name))}")
        if case in cases:
            raise CliError(f"--xml: {path.name} given twice")
        if not path.is_file():
            raise CliError(f"--xml: {text!r} is not a file")
        cases[case] = path.resolve()
    return cases


def _executable(option: str, text: str) -> Path:
    path = Path(text)
    if not (path.is_file() and os.access(path, os.X_OK)):
        raise CliError(f"{option}: {text!r} is not an executable file")
    return path.resolve()


def _generate(gencase: Path, xml: Path, work: Path) -> Path:
    """GenCase on ``xml`` into ``work``; the generated case's path (without extension)."""
    work.mkdir(parents=True, exist_ok=True)
    out = work / xml.stem
    proc = subprocess.run([str(gencase), str(xml.with_suffix("")), str(out)], capture_output=True,
                          text=True, check=False)
    (work / "gencase.log").write_text(proc.stdout + proc.stderr, encoding="utf-8")
    if proc.returncode != 0 or not out.with_suffix(".xml").is_file() \
            or not out.with_suffix(".bi4").is_file():
        raise RuntimeError(f"{gencase}: failed on {xml} (exit {proc.returncode}, log "
                           f"{work / 'gencase.log'})")
    return out


def _host() -> dict[str, Any]:
    model = ""
    try:
        for line in Path("/proc/cpuinfo").read_text(encoding="utf-8").splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:  # pragma: no cover - not on Linux
        pass
    return {"host": platform.node(), "cpu_model": model, "cpus": os.cpu_count(),
            "date_utc": time.strftime("%Y-%m-%d %H:%M", time.gmtime())}


def run_against(args: Any) -> dict[str, Any]:
    """The side-by-side comparison of ``watersim bench --against``; progress and the time left
    on stderr."""
    binary = _executable("--against", args.against)
    if args.gencase is None:
        raise CliError("--gencase: required with --against (DualSPHysics' GenCase binary)")
    gencase = _executable("--gencase", args.gencase)
    if not args.xml:
        raise CliError("--xml: name at least one DualSPHysics case XML with --against")
    cases = xml_cases(args.xml)
    interval, rounds = args.interval, args.rounds
    if not (math.isfinite(interval) and interval > 0):
        raise CliError(f"--interval: a positive number of simulated seconds, got {interval}")
    if rounds < 1:
        raise CliError(f"--rounds: must be at least 1, got {rounds}")
    cpus = parse_cpus(args.cpu)
    if shutil.which("taskset") is None:
        raise CliError("--against: needs taskset (util-linux) to pin each run to one core")
    keep = args.workdir is not None
    work = Path(args.workdir or tempfile.mkdtemp(prefix="watersim-against-"))
    started = time.perf_counter()
    result: dict[str, Any] = {**_host(), "cpus": cpus, "threads": len(cpus),
                              "interval_s": interval,
                              "rounds": rounds, "binary": str(binary), "gencase": str(gencase),
                              "cases": {}}
    try:
        for index, (case, xml) in enumerate(cases.items()):
            generated = _generate(gencase, xml, work / case)
            done: list[dict[str, Any]] = []
            for r in range(rounds):
                t_round = time.perf_counter()
                order = ("dualsphysics", "watersim") if r % 2 == 0 else (
                    "watersim", "dualsphysics")
                timings: dict[str, Any] = {"first": order[0]}
                for code in order:
                    timings[code] = (
                        _run_dualsphysics(binary, generated, work / case / f"out{r}", interval,
                                          cpus) if code == "dualsphysics" else
                        _run_watersim(case, interval, cpus, work / case / f"watersim{r}.log"))
                done.append(timings)
                took = time.perf_counter() - t_round
                left = took * (rounds - r - 1)
                later = len(cases) - index - 1
                print(f"[{case} round {r + 1}/{rounds}: {took:.0f} s; this case about "
                      f"{left:.0f} s more"
                      + (f", then {later} more case(s) of their own length]" if later else "]"),
                      file=sys.stderr, flush=True)
            result["cases"][case] = case_summary(done)
    finally:
        if not keep:
            shutil.rmtree(work, ignore_errors=True)
    result["harness_wall_s"] = time.perf_counter() - started
    return result


def _range(s: dict[str, Any], fmt: str) -> str:
    return f"{s['median']:{fmt}} ({s['min']:{fmt}}-{s['max']:{fmt}})"


def against_table(result: dict[str, Any]) -> str:
    """The side-by-side result as text: one block per case."""
    lines = [f"WaterSim against DualSPHysics, side by side: {result['rounds']} round(s) "
             f"alternated, {result['interval_s']:g} s simulated from t = 0, "
             f"{result['threads']} thread(s) pinned to CPU(s) "
             f"{','.join(map(str, result['cpus']))}; {result['host']} ({result['cpu_model']}), "
             f"{result['date_utc']} UTC, {result['harness_wall_s']:.0f} s in all",
             f"{'case':<16} {'code':<13} {'particles':>9} {'steps':>7} {'us/particle-step':>22}"
             f" {'s per sim. s':>22} {'foreign load':>18}"]
    for case, s in result["cases"].items():
        for code, name in (("watersim", "WaterSim"), ("dualsphysics", "DualSPHysics")):
            c = s[code]
            lines.append(f"{case if code == 'watersim' else '':<16} {name:<13} "
                         f"{c['particles']:>9,} {c['steps']:>7.0f} "
                         f"{_range(c['us_per_particle_step'], '.3f'):>22} "
                         f"{_range(c['s_per_sim_s'], '.1f'):>22} "
                         f"{_range(c['foreign'], '.0%'):>18}")
        lines.append(f"{'':<16} ratio (DualSPHysics / WaterSim): per particle-step "
                     f"{_range(s['ratio_per_particle_step'], '.2f')}, per simulated second "
                     f"{_range(s['ratio_per_sim_second'], '.2f')}")
    return "\n".join(lines)


def cmd_against(args: Any) -> int:
    """``watersim bench --against``: runs the comparison and prints it (``--json``: one JSON
    object). Exit 1 when a code fails to run."""
    try:
        result = run_against(args)
    except RuntimeError as exc:
        print(f"watersim: bench --against failed: {exc}", file=sys.stderr)
        return 1
    print(json.dumps(result) if args.json else against_table(result))
    return 0


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "worker":
        print(json.dumps(worker(sys.argv[2], float(sys.argv[3]))))
    else:
        sys.exit("usage: python -m watersim.bench_against worker CASE INTERVAL_S")
