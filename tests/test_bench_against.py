"""``watersim bench --against``: the side-by-side harness, tested without DualSPHysics.

Fake GenCase and DualSPHysics scripts write what the real ones write (GenCase: the case's
``.xml`` and ``.bi4``; DualSPHysics: ``Run.out`` with ``JSph::ShowResume``'s lines, thousands
separators included), so that the command line, the parsing, the alternation and the ratio
arithmetic run for real; WaterSim's side is the real solver over a few steps.
"""

from __future__ import annotations

import json
import os
import stat
import sys
from pathlib import Path

import pytest

from conftest import assert_clean_failure, run_cli
from watersim.bench_against import (
    RunTiming,
    case_summary,
    core_ticks,
    xml_cases,
)
from watersim.bench_cases import DSPH_CASES
from watersim.errors import CliError

FAKE_GENCASE = """\
import sys
from pathlib import Path
out = Path(sys.argv[2])
Path(sys.argv[1] + ".xml").read_text()  # GenCase reads CASE.xml given CASE
out.with_suffix(".xml").write_text('<case><particles np="21001" nb="1001"/></case>')
out.with_suffix(".bi4").write_bytes(b"bi4")
"""

FAKE_DUALSPHYSICS = """\
import os, sys, time
from pathlib import Path
case, out = Path(sys.argv[1]), Path(sys.argv[2])
opts = dict(a.lstrip("-").split(":", 1) if ":" in a else (a.lstrip("-"), "") for a in sys.argv[3:])
assert case.with_suffix(".bi4").is_file(), case
assert opts["ompthreads"] == os.environ["OMP_NUM_THREADS"] and "cpu" in opts, opts
assert opts["sv"] == "none", opts
with open(os.environ["FAKE_DSPH_LOG"], "a") as log:
    log.write(f"dualsphysics {time.monotonic()} {os.sched_getaffinity(0)} {opts['tmax']} "
              f"{opts['ompthreads']}\\n")
if os.environ.get("FAKE_DSPH_FAIL") == "exit":
    sys.exit(3)
tmax = float(opts["tmax"])
runtime = float(os.environ.get("FAKE_DSPH_RUNTIME", "2.5"))
out.mkdir(parents=True)
state = "INTERRUPTED" if os.environ.get("FAKE_DSPH_FAIL") == "interrupt" else "finished"
(out / "Run.out").write_text(f'''
[Simulation {state}  06-12-2026 03:00:00]
Particles of simulation (initial): 21,001
DTs adjusted to DtMin............: 0
Excluded particles...............: 0
Total Runtime....................: {runtime + 0.4:f} sec.
Simulation Runtime...............: {runtime:f} sec.
Runtime per physical second......: {runtime / tmax:f} sec.
Steps per second.................: {1234 / runtime:f}
Steps of simulation..............: 1,234
PART files.......................: 2
''')
"""


def _script(path: Path, body: str) -> Path:
    path.write_text(f"#!{sys.executable}\n{body}", encoding="utf-8")
    path.chmod(path.stat().st_mode | stat.S_IXUSR)
    return path


@pytest.fixture()
def fakes(tmp_path: Path) -> dict[str, Path]:
    xml = tmp_path / "xml" / DSPH_CASES["dsph-dambreak2d"].xml
    xml.parent.mkdir()
    xml.write_text("<case/>", encoding="utf-8")
    return {"gencase": _script(tmp_path / "GenCase_linux64", FAKE_GENCASE),
            "dsph": _script(tmp_path / "DualSPHysics5.4CPU_linux64", FAKE_DUALSPHYSICS),
            "xml": xml, "log": tmp_path / "dsph.log", "work": tmp_path / "work"}


def _against(fakes: dict[str, Path], *extra: str, env: dict[str, str] | None = None):
    cpu = str(min(os.sched_getaffinity(0)))
    return run_cli("bench", "--against", str(fakes["dsph"]), "--gencase", str(fakes["gencase"]),
                   "--xml", str(fakes["xml"]), "--cpu", cpu, *extra,
                   env={"FAKE_DSPH_LOG": str(fakes["log"]), **(env or {})})


def test_side_by_side_parses_times_and_alternates(fakes: dict[str, Path]) -> None:
    interval = 0.0015
    proc = _against(fakes, "--interval", str(interval), "--rounds", "3", "--workdir",
                    str(fakes["work"]), "--json")
    assert proc.returncode == 0, proc.stderr
    result = json.loads(proc.stdout)
    case = result["cases"]["dsph-dambreak2d"]
    # the order alternates round by round, DualSPHysics first in the first round
    assert case["order"] == ["dualsphysics", "watersim", "dualsphysics"]
    dsph, ws = case["dualsphysics"], case["watersim"]
    assert (dsph["particles"], dsph["steps"]) == (21_001, 1_234)
    assert [r["runtime_s"] for r in dsph["runs"]] == [2.5] * 3
    assert dsph["sim_time_s"] == pytest.approx(interval, rel=1e-5)
    assert ws["particles"] == pytest.approx(21_001, rel=0.012) and ws["steps"] >= 1
    assert all(r["sim_time_s"] >= interval for r in ws["runs"])
    # the ratios, round by round, from the runs' own figures
    for r, (d, w) in enumerate(zip(dsph["runs"], ws["runs"], strict=True)):
        per_step = (d["runtime_s"] / (d["particles"] * d["steps"])) / (
            w["runtime_s"] / (w["particles"] * w["steps"]))
        per_sim_s = (d["runtime_s"] / d["sim_time_s"]) / (w["runtime_s"] / w["sim_time_s"])
        assert case["ratio_per_particle_step"]["rounds"][r] == pytest.approx(per_step)
        assert case["ratio_per_sim_second"]["rounds"][r] == pytest.approx(per_sim_s)
        for run in (d, w):
            assert 0.0 <= run["foreign"] <= 1.0 and run["steal"] >= 0.0
            assert run["process_wall_s"] > 0 and run["process_cpu_s"] > 0
    summary = case["ratio_per_sim_second"]
    assert summary["min"] <= summary["median"] <= summary["max"]
    # DualSPHysics ran pinned to the one core named, over the interval
    calls = fakes["log"].read_text().splitlines()
    assert len(calls) == 3
    assert all(f"{{{min(os.sched_getaffinity(0))}}} {interval} 1" in c for c in calls)
    assert (fakes["work"] / "dsph-dambreak2d" / "out0" / "Run.out").is_file()
    assert result["threads"] == 1 and result["host"] and result["date_utc"]


@pytest.mark.skipif(len(os.sched_getaffinity(0)) < 2, reason="needs two cores")
def test_two_cores_run_both_codes_on_two_threads(fakes: dict[str, Path]) -> None:
    cpus = sorted(os.sched_getaffinity(0))[:2]
    proc = run_cli("bench", "--against", str(fakes["dsph"]), "--gencase", str(fakes["gencase"]),
                   "--xml", str(fakes["xml"]), "--cpu", f"{cpus[0]},{cpus[1]}", "--interval",
                   "0.0005", "--rounds", "1", "--workdir", str(fakes["work"]), "--json",
                   env={"FAKE_DSPH_LOG": str(fakes["log"])})
    assert proc.returncode == 0, proc.stderr
    result = json.loads(proc.stdout)
    assert result["threads"] == 2 and result["cpus"] == cpus
    # DualSPHysics on both cores with two OpenMP threads
    (call,) = fakes["log"].read_text().splitlines()
    assert call.endswith(" 2") and f"{{{cpus[0]}, {cpus[1]}}}" in call
    # WaterSim's worker process on two rayon threads
    log = (fakes["work"] / "dsph-dambreak2d" / "watersim0.log").read_text()
    assert json.loads(log.strip().splitlines()[-1])["threads"] == 2


def test_side_by_side_prints_a_table_and_its_progress(fakes: dict[str, Path]) -> None:
    proc = _against(fakes, "--interval", "0.0005", "--rounds", "1")
    assert proc.returncode == 0, proc.stderr
    assert "ratio (DualSPHysics / WaterSim): per particle-step" in proc.stdout
    assert "DualSPHysics" in proc.stdout and "21,001" in proc.stdout
    assert "[dsph-dambreak2d round 1/1:" in proc.stderr


@pytest.mark.parametrize(("failure", "needle"), [("exit", "exited with code 3"),
                                                  ("interrupt", "INTERRUPTED")])
def test_a_failed_dualsphysics_run_is_reported(fakes: dict[str, Path], failure: str,
                                               needle: str) -> None:
    proc = _against(fakes, "--interval", "0.0005", "--rounds", "1",
                    env={"FAKE_DSPH_FAIL": failure})
    assert proc.returncode == 1 and needle in proc.stderr, proc.stderr
    assert "Traceback" not in proc.stderr


@pytest.mark.parametrize(("args", "needle"), [
    (("--against", "/nonexistent/DualSPHysics"), "--against"),
    (("--xml", "/tmp/NotACase.xml"), "--xml"),
    (("--interval", "-1"), "--interval"),
    (("--rounds", "0"), "--rounds"),
    (("--cpu", "4096"), "--cpu"),
    (("--cpu", "0,0"), "--cpu"),
    (("--cpu", "one"), "--cpu"),
    (("--particles", "3000"), "--particles"),
    (("--steps", "5"), "--steps"),
])
def test_bad_side_by_side_input_is_refused(fakes: dict[str, Path], args: tuple[str, ...],
                                           needle: str) -> None:
    base = {"--against": str(fakes["dsph"]), "--gencase": str(fakes["gencase"]),
            "--xml": str(fakes["xml"])}
    extra = list(args)
    for option in list(base):
        if option in extra:
            base.pop(option)
    argv = [x for kv in base.items() for x in kv]
    proc = run_cli("bench", *argv, *extra, env={"FAKE_DSPH_LOG": str(fakes["log"])})
    assert proc.returncode == 2
    assert_clean_failure(proc, needle)
    assert not fakes["log"].exists()


def test_side_by_side_options_need_against() -> None:
    proc = run_cli("bench", "--rounds", "3")
    assert proc.returncode == 2
    assert_clean_failure(proc, "--rounds", "--against")


def test_xml_names_map_to_the_bench_cases(tmp_path: Path) -> None:
    paths = []
    for spec in DSPH_CASES.values():
        (tmp_path / spec.xml).write_text("<case/>", encoding="utf-8")
        paths.append(str(tmp_path / spec.xml))
    assert set(xml_cases(paths)) == set(DSPH_CASES)
    with pytest.raises(CliError, match="twice"):
        xml_cases([paths[0], paths[0]])


def test_ratios_by_hand() -> None:
    def timing(code: str, particles: int, steps: int, runtime: float) -> RunTiming:
        return RunTiming(code, particles, steps, 0.1, runtime, runtime + 1, runtime, 0.1, 0.0)

    rounds = [
        {"first": "dualsphysics", "dualsphysics": timing("dualsphysics", 1000, 100, 10.0),
         "watersim": timing("watersim", 2000, 200, 2.0)},
        {"first": "watersim", "dualsphysics": timing("dualsphysics", 1000, 100, 12.0),
         "watersim": timing("watersim", 2000, 200, 2.0)},
        {"first": "dualsphysics", "dualsphysics": timing("dualsphysics", 1000, 100, 8.0),
         "watersim": timing("watersim", 2000, 200, 2.0)},
    ]
    s = case_summary(rounds)
    # DualSPHysics 100, 120, 80 us per particle-step against WaterSim's 5
    assert s["ratio_per_particle_step"] == {"median": 20.0, "min": 16.0, "max": 24.0,
                                            "rounds": [20.0, 24.0, 16.0]}
    # the same simulated 0.1 s: 10, 12, 8 s against 2 s
    assert s["ratio_per_sim_second"]["rounds"] == [5.0, 6.0, 4.0]
    assert s["dualsphysics"]["us_per_particle_step"]["median"] == pytest.approx(100.0)


def test_foreign_load_is_read_per_core() -> None:
    hz = os.sysconf("SC_CLK_TCK")
    text = ("cpu  10 0 10 100 0 0 0 0 0 0\n"
            f"cpu0 {hz} {hz} {hz} 500 7 {hz} {hz} {3 * hz} 0 0\n"
            "cpu1 1 1 1 1 1 1 1 1 0 0\n")
    ticks = core_ticks(0, text)
    assert ticks.busy_s == pytest.approx(5.0) and ticks.steal_s == pytest.approx(3.0)
    with pytest.raises(RuntimeError, match="cpu7"):
        core_ticks(7, text)
