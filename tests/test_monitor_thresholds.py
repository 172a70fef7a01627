"""Stability monitor thresholds (``density_band``, ``lost_fraction_limit``,
``energy_growth_limit``) as builder fields: checked, passed to the core, settable with ``--set``
and scene files, and acting on the run (docs/stability.md)."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import watersim as ws
from conftest import assert_clean_failure, run_cli
from watersim import scenefile as sf
from watersim.flume_cases import flume_builder, flume_settable_keys

MONITORS = ("density_band", "lost_fraction_limit", "energy_growth_limit")
SMALL = {"dim": 2, "dp": 0.1, "width": 0.6, "height": 0.9, "tank_length": 1.8,
         "tank_height": 1.2}


def _inject(sim: ws.Simulation, edit: Any) -> None:
    """Restore ``sim`` from its own checkpoint after ``edit(state, fluid_slots)``."""
    state = sim.core.checkpoint()
    edit(state, np.flatnonzero(state["kinds"] == 0))
    sim.core.restore(state)


def test_defaults_are_the_core_defaults_and_reach_the_scene() -> None:
    builder = ws.DamBreak(dim=2, dp=0.1)
    assert not set(MONITORS) & set(builder.to_scene())  # unset: the core decides
    scene = builder.resolved_scene()
    assert {k: scene[k] for k in MONITORS} == {
        "density_band": 0.5, "lost_fraction_limit": 0.01, "energy_growth_limit": 0.05}
    scene = ws.Tank(dim=3, density_band=0.2, lost_fraction_limit=0.0,
                    energy_growth_limit=1.0).to_scene()
    assert {k: scene[k] for k in MONITORS} == {
        "density_band": 0.2, "lost_fraction_limit": 0.0, "energy_growth_limit": 1.0}


@pytest.mark.parametrize(
    ("field", "value", "reason"),
    [
        ("density_band", 0.0, "must be positive"),
        ("density_band", 1.5, "must be at most 1"),
        ("density_band", math.nan, "finite"),
        ("density_band", "wide", "expected a number"),
        ("lost_fraction_limit", -0.01, "must not be negative"),
        ("lost_fraction_limit", 1.01, "must be at most 1"),
        ("lost_fraction_limit", math.inf, "finite"),
        ("energy_growth_limit", 0.0, "must be positive"),
        ("energy_growth_limit", 2.0, "must be at most 1"),
        ("energy_growth_limit", "fast", "expected a number"),
    ],
)
def test_bad_thresholds_are_refused_naming_the_field(field: str, value: Any, reason: str) -> None:
    with pytest.raises(ws.SceneError, match=rf"^{field}: .*{reason}"):
        ws.DamBreak(**SMALL, **{field: value})
    with pytest.raises(ws.SceneError, match=rf"^{field}: .*{reason}"):
        ws.Tank(dim=2).replace(**{field: value})


def test_flume_takes_the_density_and_domain_limits_but_refuses_the_energy_limit() -> None:
    # every flume has a paddle, and the core's energy monitor skips such scenes: a value there
    # would be accepted and ignored
    scene = flume_builder("flume2d", {"density_band": "0.3", "lost_fraction_limit": "0.02"})
    core = scene.to_scene()
    assert core["density_band"] == 0.3 and core["lost_fraction_limit"] == 0.02
    assert "energy_growth_limit" not in core
    assert scene.energy_growth_limit is None
    with pytest.raises(ws.SceneError, match=r"^energy_growth_limit: .*paddle"):
        scene.replace(energy_growth_limit=0.05)
    keys = flume_settable_keys("flume2d")
    assert "density_band" in keys and "lost_fraction_limit" in keys
    assert "energy_growth_limit" not in keys


def test_lost_fraction_limit_of_the_builder_is_the_core_s() -> None:
    def outside(state: dict[str, Any], fluid: np.ndarray) -> None:
        state["positions"][2 * fluid[-1]] = 9.0  # far beyond the 1.8 m tank: 1 of 54 fluid

    loose = ws.DamBreak(**SMALL, lost_fraction_limit=0.05).build()
    _inject(loose, outside)
    loose.step(3)
    assert loose.core.n_excluded == 1
    strict = ws.DamBreak(**SMALL, lost_fraction_limit=0.0).build()
    _inject(strict, outside)
    with pytest.raises(ws.InstabilityError) as info:
        strict.step(3)
    assert info.value.kind == "out_of_domain"


def test_energy_growth_limit_of_the_builder_is_the_core_s() -> None:
    def kick(state: dict[str, Any], fluid: np.ndarray) -> None:
        # all the water thrown upwards at 0.6 m/s: kinetic energy 0.18 J/kg against the initial
        # potential energy g d / 2 = 1.47 J/kg, a growth of about 12 %
        state["velocities"][2 * fluid + 1] = 0.6

    tank = {"dim": 2, "dp": 0.05, "length": 0.6, "depth": 0.3, "height": 0.5}
    loose = ws.Tank(**tank, energy_growth_limit=0.5).build()
    _inject(loose, kick)
    loose.step(60)  # past the check at step 50
    strict = ws.Tank(**tank, energy_growth_limit=0.05).build()
    _inject(strict, kick)
    with pytest.raises(ws.InstabilityError) as info:
        strict.step(60)
    assert info.value.kind == "energy_growth" and info.value.step == 50


def test_cli_density_band_stops_the_run_at_once(tmp_path: Path) -> None:
    # the hydrostatic column is already about 0.3 % denser at the floor than rho0
    proc = run_cli("run", "dambreak2d", "--set", "density_band=0.001", "--set", "dp=0.1",
                   "--quiet", "--out", str(tmp_path))
    assert proc.returncode == 1, proc.stdout + proc.stderr
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["status"] == "density_out_of_range"
    assert summary["steps"] <= 2
    assert summary["scene"]["density_band"] == 0.001


@pytest.mark.parametrize(
    "setting",
    ["density_band=0", "density_band=3", "lost_fraction_limit=2", "energy_growth_limit=-1",
     "energy_growth_limit=nan"],
)
def test_cli_bad_threshold_is_refused_naming_the_field(setting: str, tmp_path: Path) -> None:
    out = tmp_path / "o"
    proc = run_cli("run", "dambreak2d", "--set", setting, "--out", str(out))
    assert_clean_failure(proc, setting.split("=")[0])
    assert proc.returncode == 2 and not out.exists()


def test_scene_file_round_trips_the_thresholds(tmp_path: Path) -> None:
    builder = ws.Tank(dim=2, density_band=0.25, lost_fraction_limit=0.1, energy_growth_limit=0.2)
    text = sf.dumps(builder)
    for line in ("density_band = 0.25", "lost_fraction_limit = 0.1", "energy_growth_limit = 0.2"):
        assert line in text
    path = tmp_path / "tank.toml"
    path.write_text(text)
    loaded = sf.load(path).builder
    assert loaded == builder and loaded.to_scene() == builder.to_scene()
    # --set on a file, and a bad value named by its key
    assert sf.load(path, ["density_band=0.4"]).builder.density_band == 0.4
    with pytest.raises(sf.SceneFileError, match=r"tank\.toml: lost_fraction_limit: .*at most 1"):
        sf.load(path, ["lost_fraction_limit=1.5"])


def test_flume_scene_file_refuses_the_energy_limit(tmp_path: Path) -> None:
    path = tmp_path / "flume.toml"
    path.write_text("energy_growth_limit = 0.1\n" + sf.dumps(flume_builder("flume2d", {})))
    with pytest.raises(sf.SceneFileError, match=r"flume\.toml: energy_growth_limit: .*paddle"):
        sf.load(path)
