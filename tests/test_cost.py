"""The cost a run states before it starts (watersim.cost) and the speed it measures."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from watersim import _core, cli, cost
from watersim.scenes import DamBreak


def test_estimate_counts_steps_from_the_acoustic_bound_and_is_a_lower_bound() -> None:
    builder = DamBreak(dim=2, dp=0.05, until=0.2)
    sim = builder.build()
    estimate = cost.estimate(sim, 0.2, threads=2)
    params = sim.params()
    cfl = json.loads(_core.resolve_scene(json.dumps(sim.scene)))["cfl"]
    assert estimate.steps == pytest.approx(0.2 / (cfl * params["h"] / params["c0"]))
    assert estimate.cpu_s == pytest.approx(
        estimate.steps * sim.n_particles * cost.REFERENCE_US_PER_PARTICLE_STEP[2] * 1e-6)
    assert estimate.wall_s < estimate.cpu_s
    sim.run(0.2)
    assert sim.steps >= estimate.steps  # the step is the acoustic bound or shorter


def test_run_states_its_cost_and_the_measured_speed(tmp_path: Path,
                                                    capsys: pytest.CaptureFixture[str]) -> None:
    assert cli.main(["run", "dambreak2d", "--set", "dp=0.05", "--set", "until=0.1",
                     "--sample-every", "0.02", "--out", str(tmp_path), "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "cost:" in out and "particles x at least" in out and "of CPU" in out
    assert "measured:" in out and "us per particle-step" in out
