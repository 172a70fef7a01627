"""Failing well (issue 5): every stability monitor fired through the Python API with its fields,
outputs written so far intact after a failure, the last good state saved and continued, and each
kind of bad input refused naming the field, through Python and the CLI."""

from __future__ import annotations

import csv
import json
import math
import re
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import watersim as ws
from conftest import assert_clean_failure, run_cli
from watersim import _core
from watersim.checkpoint import LastGood, load_checkpoint

SMALL = {"width": 0.6, "height": 0.9, "tank_length": 1.8, "tank_height": 1.2}


def _small_dambreak(**extra: Any) -> ws.DamBreak:
    return ws.DamBreak(dim=2, dp=0.1, **SMALL, **extra)


def _check_fields(err: ws.InstabilityError, kind: str, sim: ws.Simulation) -> None:
    """The error's fields are set, typed and consistent with its message."""
    assert err.kind == kind
    assert isinstance(err.step, int) and err.step >= 1
    assert isinstance(err.time, float) and err.time > 0.0
    assert isinstance(err.particle, int) and 0 <= err.particle < sim.n_particles
    assert len(err.position) == sim.dim
    message = str(err)
    assert err.message and err.message in message  # the monitor's own sentence
    assert message.startswith(f"{kind} at step {err.step} ")
    assert f"particle {err.particle}" in message
    # the core keeps the monitor's own sentence after the colon
    assert message.split(": ", 1)[1]


def _inject(sim: ws.Simulation, edit: Any) -> dict[str, Any]:
    """Restore ``sim`` from its own checkpoint after ``edit(state, fluid_slots)``."""
    state = sim.core.checkpoint()
    fluid = np.flatnonzero(state["kinds"] == 0)
    edit(state, fluid)
    sim.core.restore(state)
    return state


def test_non_finite_names_the_step_and_a_particle() -> None:
    sim = _small_dambreak().build()
    sim.step(2)

    def nan(state: dict, fluid: np.ndarray) -> None:
        state["velocities"][2 * fluid[3] + 1] = np.nan

    _inject(sim, nan)
    with pytest.raises(ws.InstabilityError) as info:
        sim.step(3)
    _check_fields(info.value, "non_finite", sim)
    assert info.value.step == 3
    assert "not finite" in str(info.value)
    # the state stays readable, and it is the failed one (NaN spread by the step)
    assert sim.steps == 3 and np.isnan(sim.velocities).any()


def test_density_out_of_band_reports_the_density() -> None:
    scene = _small_dambreak().to_scene()
    scene["density_band"] = 1e-4  # the hydrostatic column is 0.1 % denser at the floor
    sim = ws.Simulation(scene)
    with pytest.raises(ws.InstabilityError) as info:
        sim.step(5)
    _check_fields(info.value, "density_out_of_range", sim)
    assert info.value.step == 1
    assert re.search(
        r"density [0-9.]+ kg/m\^3 outside \[999\.900, 1000\.100\] \(rho0 -\+ 0\.01 %\)",
        str(info.value),
    )


def test_time_step_collapse_from_a_runaway_density() -> None:
    sim = _small_dambreak().build()
    sim.step(2)

    squeezed: dict[str, int] = {}

    def squeeze(state: dict, fluid: np.ndarray) -> None:
        state["densities"][fluid[3]] = 1e5  # pressure ~ B (100)^7: the step falls to ~1e-10 s
        squeezed["id"] = int(state["ids"][fluid[3]])

    _inject(sim, squeeze)
    with pytest.raises(ws.InstabilityError) as info:
        sim.step(2)
    _check_fields(info.value, "time_step_collapse", sim)
    # the error names the particle whose limit set the step: the squeezed one or a neighbour
    # it throws out
    ids = np.asarray(sim.ids)
    squeezed_at = np.asarray(sim.positions)[np.flatnonzero(ids == squeezed["id"])[0]]
    assert np.hypot(*(np.asarray(info.value.position) - squeezed_at)) < 4 * 0.1  # dp = 0.1
    # this monitor fires before the step is taken: step and time are those of the last good step
    assert info.value.step == 2 and sim.steps == 2
    assert "below the floor" in str(info.value)


def test_particle_outside_stops_the_run_past_the_lost_fraction() -> None:
    placed: dict[str, int] = {}

    def outside(state: dict, fluid: np.ndarray) -> None:
        placed["id"] = int(state["ids"][fluid[-1]])
        state["positions"][2 * fluid[-1]] = 9.0  # far beyond the 1.8 m tank and its walls

    strict_scene = _small_dambreak().to_scene()
    strict_scene["lost_fraction_limit"] = 0.0
    strict = ws.Simulation(strict_scene)
    _inject(strict, outside)
    with pytest.raises(ws.InstabilityError) as info:
        strict.step(2)
    _check_fields(info.value, "out_of_domain", strict)
    assert info.value.particle == placed["id"] and info.value.position[0] == 9.0
    assert "left the domain" in str(info.value)


def test_lost_fraction_within_the_limit_freezes_the_particle() -> None:
    scene = _small_dambreak().to_scene()
    scene["lost_fraction_limit"] = 0.05
    sim = ws.Simulation(scene)

    def outside(state: dict, fluid: np.ndarray) -> None:
        state["positions"][2 * fluid[-1]] = 9.0

    _inject(sim, outside)
    sim.step(3)
    assert sim.core.n_excluded == 1
    assert (np.asarray(sim.kinds) == 3).sum() == 1


def test_energy_growth_without_forcing() -> None:
    sim = ws.Tank(dim=2, dp=0.05, length=0.6, depth=0.3, height=0.5).build()

    def kick(state: dict, fluid: np.ndarray) -> None:
        state["velocities"][2 * fluid + 1] = 0.6  # all the water thrown upwards at 0.6 m/s

    _inject(sim, kick)
    with pytest.raises(ws.InstabilityError) as info:
        sim.step(60)
    _check_fields(info.value, "energy_growth", sim)
    assert info.value.step == 50  # the energy is checked every 50 steps
    # it names the fastest fluid particle
    speed = np.linalg.norm(np.asarray(sim.velocities), axis=1)
    fluid_slots = np.flatnonzero(np.asarray(sim.kinds) == 0)
    fastest = fluid_slots[np.argmax(speed[fluid_slots])]
    assert info.value.particle == int(np.asarray(sim.ids)[fastest])
    assert "exceeds its initial" in str(info.value)


def test_cfl_far_too_large() -> None:
    with pytest.raises(ws.SceneError, match=r"^cfl: must be at most 1"):
        ws.DamBreak(dim=2, cfl=2.0)
    scene = ws.DamBreak(dim=2, dp=0.1).to_scene()
    scene["cfl"] = 5.0
    with pytest.raises(ws.SceneError, match=r"^cfl: must be <= 1"):
        ws.Simulation(scene)
    # the largest CFL accepted, with a stiff sound speed: the run blows up within 0.1 s
    # (measured: energy_growth at t = 0.040 s, step 100, in `watersim stress`)
    sim = ws.DamBreak(dim=2, dp=0.1, cfl=1.0, coefsound=80.0).build()
    with pytest.raises(ws.InstabilityError) as info:
        sim.run(0.7)
    _check_fields(info.value, "energy_growth", sim)
    assert info.value.time < 0.1


# ------------------------------------------------------------------------------------------------
# outputs written so far, last good state


def test_failed_dambreak_keeps_front_csv_and_last_good(tmp_path: Path) -> None:
    out = tmp_path / "run"
    proc = run_cli("run", "dambreak2d", "--set", "dp=0.1", "--set", "coefsound=1", "--quiet",
                   "--out", str(out))
    assert proc.returncode == 1, proc.stderr
    assert "Traceback" not in proc.stderr and "run stopped" in proc.stderr
    summary = json.loads((out / "summary.json").read_text())
    error = summary["error"]
    assert summary["status"] == error["kind"] != "ok"
    with open(out / "front.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) >= 5 and all(math.isfinite(float(r["x_front_m"])) for r in rows)
    last = summary["last_good"]
    assert last["path"] == str(out / "last_good.npz")
    # the last good state is one of the samples front.csv was written from: the last one, or
    # an earlier one when the energy (checked by the core every 50 steps only) had already
    # grown past the limit at the last sample
    assert last["time"] in [float(r["t_s"]) for r in rows] and last["time"] < error["time"]
    resumed = load_checkpoint(out / "last_good.npz")
    assert resumed.time == last["time"] and resumed.steps == last["steps"]
    assert np.isfinite(resumed.densities).all()
    # it continues, exactly as the run did, to the same failure
    with pytest.raises(ws.InstabilityError) as again:
        resumed.run(0.7)
    assert (again.value.kind, again.value.step) == (error["kind"], error["step"])
    assert again.value.step > last["steps"]


def test_failed_flume_keeps_gauges_csv(tmp_path: Path) -> None:
    out = tmp_path / "flume"
    custom = tmp_path / "elsewhere" / "good.npz"
    custom.parent.mkdir()
    proc = run_cli("run", "flume2d", "--set", "dp=0.05", "--set", "coefsound=1", "--set",
                   "until=1", "--set", "sample_interval=0.002", "--sample-every", "0.01", "--quiet",
                   "--out", str(out),
                   "--save-last-good", str(custom))
    assert proc.returncode == 1, proc.stderr
    summary = json.loads((out / "summary.json").read_text())
    assert summary["status"] == summary["error"]["kind"] == "density_out_of_range"
    assert summary["last_good"]["path"] == str(custom) and custom.exists()
    assert not (out / "last_good.npz").exists()
    with open(out / "gauges.csv", newline="") as f:
        rows = list(csv.reader(f))
    header, data = rows[0], rows[1:]
    assert header[0].startswith("t") and len(data) == summary["n_gauge_samples"] >= 2
    assert all(float(r[0]) <= summary["error"]["time"] for r in data)
    analysis = json.loads((out / "analysis.json").read_text())
    assert analysis["status"] == "density_out_of_range"
    # the paddle's motion is a function of time: the saved state continues with it
    resumed = load_checkpoint(custom)
    assert resumed.time == summary["last_good"]["time"]


def test_last_good_every_is_checked() -> None:
    proc = run_cli("run", "dambreak2d", "--last-good-every", "0")
    assert_clean_failure(proc, "--last-good-every")
    with pytest.raises(ValueError, match="every"):
        LastGood(0)


def test_last_good_restores_into_a_relaxed_scene_and_runs_on(tmp_path: Path) -> None:
    """A too-strict monitor stops the run; the last good state continues with it relaxed to
    the same end as the run that never stopped."""
    strict = _small_dambreak().to_scene()
    strict["density_band"] = 0.004
    sim = ws.Simulation(strict)
    keeper = LastGood(every=2)
    with pytest.raises(ws.InstabilityError) as info:
        sim.run(0.5, callback_every=0.01, callback=keeper)
    assert keeper.time is not None and keeper.time < info.value.time
    assert keeper.calls >= 2
    path = keeper.save(tmp_path / "last_good.npz")
    assert path is not None
    relaxed = ws.Simulation({**strict, "density_band": 0.5})
    load_checkpoint(path, relaxed)
    assert relaxed.time == keeper.time and relaxed.steps == keeper.steps
    relaxed.run(0.5)
    assert relaxed.time >= 0.5
    # and restoring into the strict scene reproduces the failure exactly
    again = load_checkpoint(path)
    with pytest.raises(ws.InstabilityError) as second:
        again.run(0.5)
    assert (second.value.step, second.value.particle) == (info.value.step, info.value.particle)


def test_checkpoint_cost_is_small() -> None:
    """The rolling checkpoint is a copy of the arrays: far cheaper than a step."""
    import time

    sim = ws.DamBreak(dim=2, dp=0.05).build()
    sim.step(2)
    t0 = time.perf_counter()
    sim.step(10)
    per_step = (time.perf_counter() - t0) / 10
    t0 = time.perf_counter()
    for _ in range(10):
        sim.core.checkpoint()
    per_checkpoint = (time.perf_counter() - t0) / 10
    print(f"\n{sim.n_particles} particles: step {1e3 * per_step:.3f} ms, "
          f"checkpoint {1e3 * per_checkpoint:.3f} ms")
    assert per_checkpoint < per_step


# ------------------------------------------------------------------------------------------------
# input checks: each refused naming the field and the reason, before anything runs

TANK2 = {"min": [0.0, 0.0], "max": [2.0, 1.0]}


def _raw(**extra: Any) -> dict[str, Any]:
    scene: dict[str, Any] = {"dim": 2, "dp": 0.1, "tank": TANK2,
                             "fluid": [{"min": [0.0, 0.0], "max": [0.9, 0.5]}]}
    scene.update(extra)
    return scene


RAW_SCENES = [
    (_raw(dp=-0.1), "dp", "must be > 0"),
    (_raw(coefsound=0.0), "coefsound", "must be > 0"),
    (_raw(gravity=-9.81), "gravity", ">= 0"),
    (_raw(fluid=[{"min": [0.0, 0.0], "max": [0.9, 0.0]}]), "fluid[0]", "greater than"),
    (_raw(obstacles=[{"shape": "box", "min": [0.0, 0.0], "max": [1.0, 1.0]}]), "fluid",
     "leaves no fluid"),
    (_raw(fluid=[{"min": [-0.5, 0.0], "max": [0.9, 0.5]}]), "fluid[0]", "does not fit"),
    (_raw(gauges=[{"type": "elevation", "name": "g", "position": [5.0, 0.0],
                   "interval": 0.01}]), "gauges[0].position", "outside the domain"),
    (_raw(paddle={"kind": "piston", "x": 5.0, "law": {"type": "table", "t": [0, 1],
                                                      "x": [0, 0.1]}}), "paddle.x", "inside"),
    (_raw(dp=1e-5), "dp", "GiB"),
    (_raw(bogus=1), "bogus", "unknown field"),
    (_raw(viscosity={"model": "artificial", "alpha": 0.1, "beta": 1}), "viscosity", "unknown"),
]


@pytest.mark.parametrize(("scene", "field", "reason"), RAW_SCENES)
def test_core_refuses_raw_scenes(scene: dict, field: str, reason: str) -> None:
    with pytest.raises(ws.SceneError) as info:
        _core.Simulation(json.dumps(scene))
    message = str(info.value)
    assert message.startswith(f"{field}:") or message.startswith(f"{field} "), message
    assert reason in message


def _flume(**kw: Any) -> ws.FlumeScene:
    flume = kw.pop("flume", ws.Flume(length=3.0, depth=0.3))
    wave = kw.pop("wave", ws.RegularWave(height=0.05, period=1.2))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ws.wave_theory.WaveValidityWarning)
        return flume.scene(wave, dp=0.05, **kw)


BUILDERS = [
    (lambda: ws.DamBreak(dp=0.0), "dp", "positive"),
    (lambda: ws.DamBreak(viscosity=ws.numerics.Artificial(alpha=math.nan)), "viscosity.alpha",
     "finite"),
    (lambda: ws.DamBreak(width=5.0), "width", "wider than the tank"),
    (lambda: ws.Tank(depth=1.0, height=0.7), "depth", "deeper than the tank"),
    (lambda: ws.DamBreak(dp=1e-4).build(), "dp", "GiB"),
    (lambda: ws.Flume(length=-3.0, depth=0.3), "length", "positive"),
    (lambda: ws.Flume(length=3.0, depth=math.inf), "depth", "finite"),
    (lambda: _flume(wave=ws.RegularWave(height=-0.1, period=1.0)), "wave.height", "positive"),
    (lambda: _flume(wave=ws.RegularWave(height=0.05, period=0.0)), "wave.period", "positive"),
    (lambda: _flume(wave=ws.SolitaryWave(height=0.3)), "wave.height",
     "highest solitary wave"),
    (lambda: ws.Flume(length=3.0, depth=0.3, beach=ws.PlaneBeach(toe=1.0, slope=-0.1)),
     "beach.slope", "positive"),
    (lambda: ws.Flume(length=3.0, depth=0.3, beach=ws.PlaneBeach(toe=4.0, slope=0.1)),
     "beach.toe", "beyond the flume"),
    (lambda: _flume(gauges=[ws.ElevationGauge(7.0)]), "gauges[0].x", "outside the flume"),
    (lambda: _flume(gauges=[ws.VelocityProbe(points=((1.0, 2.0),))]), "gauges[0].points[0]",
     "outside the flume height"),
    (lambda: _flume(paddle=ws.Flap(hinge_z=0.5)), "paddle.hinge_z", "below the still-water"),
    (lambda: _flume(flume=ws.Flume(length=0.6, depth=0.1, damping=False),
                    wave=ws.RegularWave(height=0.15, period=10.0, theory="linear")), "paddle",
     "reaches the far wall"),
    (lambda: _flume(wave=ws.RegularWave(height=1e300, period=1.2, theory="linear")), "paddle",
     "reaches the far wall"),
    (lambda: _flume(wave=ws.RegularWave(height=1e300, period=1.2)), "wave.height",
     "no steady wave"),
    (lambda: _flume(wave=ws.RegularWave(height=0.05, period=1.2, theory="stokes2")),
     "wave.theory", "paddle.order = 1"),
    (lambda: _flume(wave=ws.RegularWave(height=0.05, period=1.2, theory="stream_function"),
                    paddle=ws.Flap()), "wave.theory", "Piston"),
    (lambda: ws.RegularWave(height=0.05, period=1.2, stroke_gain=0.0), "wave.stroke_gain",
     "must be positive"),
    (lambda: ws.RegularWave(height=0.05, period=1.2, theory="fenton"), "wave.theory",
     "cnoidal"),
    (lambda: _flume(wave=ws.RegularWave(height=1e300, period=1.2, theory="cnoidal")),
     "wave.height", "no steady wave"),
    (lambda: ws.Flume(length=3.0, depth=0.3).scene(ws.SolitaryWave(height=1e-300)), "dp",
     "fluid particles"),
]


@pytest.mark.parametrize(("make", "field", "reason"), BUILDERS)
def test_builders_refuse_naming_the_field(make: Any, field: str, reason: str) -> None:
    with pytest.raises(ws.SceneError) as info:
        make()
    message = str(info.value)
    assert message.startswith(f"{field}:"), message
    assert reason in message, message


CLI_REFUSALS = [
    (["run", "dambreak2d", "--set", "dp=-1"], ["dp", "positive"]),
    (["run", "dambreak2d", "--set", "gravity=inf"], ["gravity", "finite"]),
    (["run", "dambreak2d", "--set", "dp=0.0001"], ["dp", "GiB"]),
    (["run", "tank2d", "--set", "depth=5"], ["depth", "deeper"]),
    (["run", "flume2d", "--set", "wave.height=0"], ["wave.height", "positive"]),
    (["run", "flume2d", "--set", "flume.length=3"], ["gauges[", "outside the flume"]),
    (["run", "solitary2d", "--set", "wave.height=0.5"], ["wave.height", "solitary"]),
    (["run", "kimmoun2d", "--set", "beach.toe=30"], ["beach.toe", "beyond the flume"]),
    (["run", "dambreak2d", "--bogus-option"], ["unrecognized arguments", "--bogus-option"]),
    (["run", "flume2d", "--set", "wave.colour=3"], ["wave.colour", "valid keys"]),
]


@pytest.mark.parametrize(("args", "needles"), CLI_REFUSALS)
def test_cli_refuses_naming_the_field(args: list[str], needles: list[str], tmp_path: Path) -> None:
    out = tmp_path / "never"
    proc = run_cli(*args, "--out", str(out))
    assert_clean_failure(proc, *needles)
    assert proc.returncode == 2
    assert not out.exists()
