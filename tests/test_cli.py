"""The ``watersim`` command: run, bench, refusal of bad input, thread-count determinism."""

from __future__ import annotations

import csv
import json
import sysconfig
from pathlib import Path

import pytest

from conftest import assert_clean_failure, run_cli

SUMMARY_KEYS = {
    "case",
    "dim",
    "n_particles",
    "n_fluid",
    "steps",
    "sim_time",
    "wall_s",
    "threads",
    "status",
    "state_sha256",
    "scene",
    "params",
}
BENCH_KEYS = {
    "case",
    "dim",
    "n_particles",
    "steps",
    "wall_s",
    "particle_steps_per_s",
    "us_per_particle_step",
    "fluid_pairs",
    "pairs_per_fluid_particle",
    "force_evaluations_per_step",
    "ns_per_pair",
    "bytes_per_particle",
    "threads",
    "kernel",
    "coefh",
    "viscosity",
    "diffusion",
}


def test_console_script_and_module_entry_points() -> None:
    scripts = Path(sysconfig.get_path("scripts"))
    assert (scripts / "watersim").exists() or (scripts / "watersim.exe").exists()
    proc = run_cli("--version")
    assert proc.returncode == 0 and proc.stdout.startswith("watersim ")


def test_unknown_set_key_is_refused_listing_valid_keys(tmp_path: Path) -> None:
    out = tmp_path / "unused"
    proc = run_cli("run", "dambreak2d", "--set", "bogus_key=1", "--out", str(out))
    assert_clean_failure(proc, "bogus_key", "valid keys", "dp", "tank_length")
    assert proc.returncode == 2
    assert not out.exists()


@pytest.mark.parametrize(
    ("setting", "field"),
    [
        ("dp=0", "dp"),
        ("dp=-0.02", "dp"),
        ("dp=nan", "dp"),
        ("dp=abc", "dp"),
        ("width=9", "width"),
        ("kernel=gaussian", "kernel"),
        ("viscosity=foo", "viscosity"),
        ("cfl=inf", "cfl"),
        ("dp", "key=value"),
    ],
)
def test_bad_set_values_are_refused_naming_the_field(
    setting: str, field: str, tmp_path: Path
) -> None:
    proc = run_cli("run", "dambreak2d", "--set", setting, "--out", str(tmp_path / "o"))
    assert_clean_failure(proc, field)
    assert proc.returncode == 2


def test_unknown_case_is_refused() -> None:
    proc = run_cli("run", "dambreak4d")
    assert_clean_failure(proc, "dambreak4d", "dambreak2d")


def test_run_writes_summary_and_front(tmp_path: Path) -> None:
    out = tmp_path / "tmp"
    proc = run_cli("run", "dambreak2d", "--set", "until=0.05", "--out", str(out))
    assert proc.returncode == 0, proc.stderr
    summary = json.loads((out / "summary.json").read_text())
    assert SUMMARY_KEYS <= set(summary)
    assert summary["case"] == "dambreak2d" and summary["status"] == "ok"
    assert summary["dim"] == 2 and summary["sim_time"] >= 0.05
    assert summary["n_fluid"] == 40 * 80  # default dp = 0.025 m, 1 m x 2 m column
    assert len(summary["state_sha256"]) == 64
    assert summary["scene"]["dp"] == summary["params"]["dp"] == 0.025
    assert "martin_moyce" in summary  # no measured point before 0.05 s: a note says so
    with open(out / "front.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert {"t_s", "x_front_m", "h_column_m"} <= set(rows[0])
    assert float(rows[0]["t_s"]) == 0.0 and float(rows[0]["x_front_m"]) == pytest.approx(1.0)
    assert len(rows) == 6 and float(rows[-1]["t_s"]) >= 0.05


def test_still_tank_run_reports_still_water(tmp_path: Path) -> None:
    args = "run tank2d --set until=0.05 --set dp=0.05 --quiet --out".split()
    proc = run_cli(*args, str(tmp_path))
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout == ""
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["status"] == "ok" and not (tmp_path / "front.csv").exists()
    assert summary["still_water"]["max_speed_over_sqrt_gd"] < 0.05


def test_thread_count_does_not_change_the_state(tmp_path: Path) -> None:
    hashes = {}
    for threads in ("1", "2"):
        out = tmp_path / f"t{threads}"
        args = "run dambreak2d --set dp=0.05 --set until=0.2 --quiet --out".split()
        proc = run_cli(*args, str(out), env={"RAYON_NUM_THREADS": threads})
        assert proc.returncode == 0, proc.stderr
        summary = json.loads((out / "summary.json").read_text())
        assert summary["threads"] == int(threads)
        assert summary["steps"] > 100
        hashes[threads] = summary["state_sha256"]
    assert hashes["1"] == hashes["2"]


def _bench(*extra: str) -> dict:
    proc = run_cli("bench", "--case", "dambreak2d", "--steps", "3", "--json", *extra)
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


def test_bench_repeat_reports_the_median_run() -> None:
    result = _bench("--particles", "2000", "--repeat", "3")
    assert result["repeat"] == 3 and len(result["wall_s_runs"]) == 3
    assert result["wall_s"] == sorted(result["wall_s_runs"])[1]
    assert result["us_per_particle_step"] == pytest.approx(
        1e6 * result["wall_s"] / (result["n_particles"] * result["steps"]))
    proc = run_cli("bench", "--case", "dambreak2d", "--repeat", "0")
    assert proc.returncode == 2 and "--repeat" in proc.stderr


def test_bench_compare_threads_times_both_counts_in_turn() -> None:
    result = _bench("--particles", "2000", "--repeat", "3", "--compare-threads", "1,2")
    comparison = result["thread_comparison"]
    assert comparison["threads"] == [1, 2] and comparison["rounds"] == 3
    runs = comparison["wall_s_runs"]
    assert len(runs["1"]) == len(runs["2"]) == 3
    assert comparison["speedup_runs"] == pytest.approx(
        [a / b for a, b in zip(runs["1"], runs["2"], strict=True)])
    assert comparison["speedup"] == sorted(comparison["speedup_runs"])[1]
    assert comparison["speedup_fastest"] == pytest.approx(min(runs["1"]) / min(runs["2"]))
    for t in ("1", "2"):
        assert comparison["us_per_particle_step"][t] == pytest.approx(
            1e6 * sorted(runs[t])[1] / (result["n_particles"] * result["steps"]))
    for bad in ("2", "1,1", "0,2", "one,two"):
        proc = run_cli("bench", "--case", "dambreak2d", "--compare-threads", bad)
        assert proc.returncode == 2 and "--compare-threads" in proc.stderr, bad


def test_bench_prints_one_json_object() -> None:
    result = _bench("--particles", "4000")
    assert BENCH_KEYS <= set(result)
    assert abs(result["n_particles"] - 4000) <= 0.1 * 4000
    assert result["steps"] == 3 and result["wall_s"] > 0
    assert result["particle_steps_per_s"] == pytest.approx(
        result["n_particles"] * 3 / result["wall_s"], rel=1e-6
    )


def test_artificial_viscosity_uses_fewer_bytes_than_sps() -> None:
    artificial = _bench("--set", "dp=0.05", "--set", "viscosity=artificial")
    sps = _bench("--set", "dp=0.05", "--set", "viscosity=laminar_sps")
    assert artificial["n_particles"] == sps["n_particles"]
    print(
        f"\nbytes/particle: artificial {artificial['bytes_per_particle']:.1f}, "
        f"laminar_sps {sps['bytes_per_particle']:.1f}"
    )
    assert artificial["bytes_per_particle"] < sps["bytes_per_particle"]


def test_unstable_run_keeps_its_output_and_exits_1(tmp_path: Path) -> None:
    # c0 = sqrt(g H) (coefsound 1) lets the collapsing column compress past the density band
    # part-way through the run.
    args = "run dambreak2d --set dp=0.1 --set coefsound=1 --quiet --out".split()
    proc = run_cli(*args, str(tmp_path))
    assert proc.returncode == 1, proc.stdout + proc.stderr
    assert "Traceback" not in proc.stderr and "panicked" not in proc.stderr
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["status"] not in ("ok", "error")
    error = summary["error"]
    assert {"kind", "step", "time", "particle", "position", "message"} <= set(error)
    assert error["kind"] == summary["status"] and len(error["position"]) == 2
    assert 0 < error["time"] < 0.7
    with open(tmp_path / "front.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) > 5 and float(rows[0]["x_front_m"]) == pytest.approx(1.0)
    assert float(rows[-1]["t_s"]) <= error["time"]
