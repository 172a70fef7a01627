"""``watersim stress`` machinery on a tiny matrix: the runner (fresh processes, one run failing
on purpose, one erroring), the record fields, the JSON and the report. The real matrices are run
by the command, not here."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from conftest import assert_clean_failure, run_cli
from watersim import stress
from watersim.stress import RunSpec

RECORD_KEYS = {
    "group", "name", "params", "status", "kind", "step", "time", "particle", "position",
    "message", "max_density_error", "energy_drift", "energy_growth_max", "wall_s",
    "n_particles", "n_fluid", "steps", "sim_time", "dp", "completed",
}

# A 2 m column at H/dp = 10 (200 particles): a few hundred steps to 0.1 s.
STABLE = RunSpec("stiffness", "cs20_cfl0.2", "dambreak",
                 {"dp": 0.2, "coefsound": 20.0, "cfl": 0.2}, 0.1, 0.01)
# CFL 1 with coefsound 80 at H/dp = 20: the energy monitor stops it within ~0.05 s (measured:
# energy_growth at t = 0.040 s, step 100).
FAILING = RunSpec("stiffness", "cs80_cfl1", "dambreak",
                  {"dp": 0.1, "coefsound": 80.0, "cfl": 1.0}, 0.7, 0.005)
# an unknown builder field: the builder raises TypeError inside the worker
BROKEN = RunSpec("violent", "broken", "dambreak", {"dp": 0.2, "no_such_field": 1.0}, 0.1, 0.01)


@pytest.fixture(scope="module")
def records() -> list[dict]:
    return stress.run_matrix([STABLE, FAILING, BROKEN], jobs=2, progress=False)


def test_runner_records_every_outcome_in_order(records: list[dict]) -> None:
    assert [r["name"] for r in records] == ["cs20_cfl0.2", "cs80_cfl1", "broken"]
    for r in records:
        assert RECORD_KEYS <= set(r), RECORD_KEYS - set(r)
    ok, bad, broken = records
    assert ok["status"] == "stable" and ok["completed"] and ok["sim_time"] >= 0.1
    assert ok["n_particles"] == 200 and ok["steps"] > 10 and ok["wall_s"] > 0
    assert 0 < ok["max_density_error"] < 0.05
    assert ok["energy_drift"] < 0.01  # a collapsing column loses energy, never gains much
    assert bad["status"] == "failed" and not bad["completed"]
    assert bad["kind"] == "energy_growth"
    assert 0 < bad["time"] < 0.7 and bad["step"] > 0 and bad["steps"] == bad["step"]
    assert len(bad["position"]) == 2 and isinstance(bad["particle"], int)
    assert "energy_growth" in bad["message"]
    assert broken["status"] == "error" and "no_such_field" in broken["message"]


def test_stable_region_and_report(records: list[dict], tmp_path: Path) -> None:
    region = stress.stable_region(records)
    assert region[20.0]["stable_up_to"] == 0.2
    assert region[80.0] == {"cfl_run": [1.0], "not_stable": [1.0], "stable_up_to": None,
                            "density_within_target": []}
    meta = {"command": "test", "version": "x"}
    readme = stress.write_report(records, tmp_path, meta)
    text = readme.read_text()
    assert "coefsound 20: stable for CFL <= 0.2" in text
    assert "coefsound 80: not stable at any CFL run (1)" in text
    assert "failed: energy_growth" in text and "error: TypeError" in text
    png = tmp_path / "stiffness_heatmap.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    path = stress.write_json(tmp_path / "stress.json", records, meta)
    data = json.loads(path.read_text())
    assert data["meta"] == meta
    assert [r["name"] for r in data["runs"]] == [r["name"] for r in records]


def test_wall_limit_gives_timeout_and_still_tank_measures() -> None:
    spec = RunSpec("long", "tank", "tank", {"dp": 0.1, "length": 1.0, "depth": 0.5,
                                            "height": 0.7}, 0.2, 0.05)
    record = stress.execute(spec)
    assert record["status"] == "stable"
    still = record["still_water"]
    assert abs(still["surface_drift_over_dp"]) < 0.5 and still["max_speed_over_sqrt_gd"] < 0.05
    assert abs(record["energy_drift"]) < 0.01
    limited = stress.execute({**spec.as_dict(), "max_wall_s": 0.0})
    assert limited["status"] == "timeout" and "wall-clock limit" in limited["message"]


def test_every_matrix_spec_builds() -> None:
    """Each spec of both matrices makes a valid scene (building only; nothing is run)."""
    for spec in [*stress.full_matrix(), *stress.quick_matrix()]:
        if spec.case == "finest_dambreak":
            continue
        sim, _ = stress._build(spec)
        assert sim.n_fluid > 0, spec.name
    groups = {s.group for s in stress.full_matrix()}
    assert groups == set(stress.GROUPS)


def test_cli_refuses_bad_options() -> None:
    assert_clean_failure(run_cli("stress", "--group", "bogus"), "--group", "bogus", "stiffness")
    assert_clean_failure(run_cli("stress", "--jobs", "0"), "--jobs")
