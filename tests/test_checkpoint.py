"""Checkpoint/restart through the Python API: same state_sha256 as the uninterrupted run."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import watersim
from watersim.checkpoint import load_checkpoint, save_checkpoint


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("integrator", ["symplectic", "verlet"])
def test_restart_reaches_the_same_state(tmp_path: Path, dim: int, integrator: str) -> None:
    builder = watersim.DamBreak(
        dim=dim, dp=0.1 if dim == 2 else 0.15, integrator=integrator, width=0.6, height=0.9,
        tank_length=1.8, tank_height=1.2, **({"tank_width": 0.45} if dim == 3 else {}),
    )
    whole = builder.build()
    whole.step(30)
    first = builder.build()
    first.step(12)
    path = save_checkpoint(first, tmp_path / "run.npz")
    del first
    resumed = load_checkpoint(path)
    assert resumed.steps == 12
    resumed.step(18)
    assert resumed.time == whole.time
    assert resumed.state_sha256() == whole.state_sha256()


def test_checkpoint_of_another_scene_is_refused(tmp_path: Path) -> None:
    a = watersim.DamBreak(dim=2, dp=0.1, width=0.6, height=0.9, tank_length=1.8, tank_height=1.2)
    b = watersim.DamBreak(dim=2, dp=0.05, width=0.6, height=0.9, tank_length=1.8, tank_height=1.2)
    path = save_checkpoint(a.build(), tmp_path / "a.npz")
    with pytest.raises(watersim.SceneError, match=r"checkpoint\.positions"):
        load_checkpoint(path, b.build())
    np.savez(tmp_path / "junk.npz", x=np.zeros(3))
    with pytest.raises(watersim.SceneError, match="not a WaterSim checkpoint"):
        load_checkpoint(tmp_path / "junk.npz")


def test_injected_nan_raises_a_structured_error() -> None:
    sim = watersim.DamBreak(
        dim=2, dp=0.1, width=0.6, height=0.9, tank_length=1.8, tank_height=1.2
    ).build()
    sim.step(2)
    state = sim.core.checkpoint()
    fluid = np.flatnonzero(state["kinds"] == 0)
    state["velocities"][2 * fluid[3]] = np.nan
    sim.core.restore(state)
    with pytest.raises(watersim.InstabilityError) as info:
        sim.step(3)
    err = info.value
    assert err.kind == "non_finite"
    assert err.step == 3
    assert err.time > 0
    assert isinstance(err.particle, int)
    assert len(err.position) == 2
    assert "non_finite" in str(err)


@pytest.mark.parametrize("dim", [2, 3])
def test_flume_with_moving_paddle_restarts_exactly(tmp_path: Path, dim: int) -> None:
    """The paddle's motion is a function of time: a restart continues it, and the gauge records,
    bit for bit."""
    flume = watersim.Flume(length=1.6, depth=0.16, width=0.12 if dim == 3 else None)
    setup = flume.scene(
        watersim.RegularWave(height=0.03, period=0.8), paddle=watersim.Piston(ramp_periods=0.5),
        dp=0.04, gauges=[watersim.ElevationGauge(0.8)], sample_interval=0.005,
    )
    whole = setup.build()
    whole.step(40)
    first = setup.build()
    first.step(15)
    path = save_checkpoint(first, tmp_path / "flume.npz")
    del first
    resumed = load_checkpoint(path)
    resumed.step(25)
    assert resumed.time == whole.time
    assert resumed.state_sha256() == whole.state_sha256()
    # the paddle moved between the halves, and the gauges sampled across the restart
    paddle = np.asarray(whole.kinds) == 2
    assert np.ptp(np.asarray(whole.velocities)[paddle][:, 0]) == 0.0
    assert np.max(np.abs(np.asarray(whole.velocities)[paddle][:, 0])) > 0.0
    for a, b in zip(resumed.core.gauges(), whole.core.gauges(), strict=True):
        assert a["t"].size > 3
        np.testing.assert_array_equal(a["t"], b["t"])
        np.testing.assert_array_equal(a["z"], b["z"])
