"""``watersim bench --scaling``: the cost per particle-step across sizes, and its fit to fluid
and wall particles (watersim.bench_scaling)."""

from __future__ import annotations

import json

import pytest

from conftest import run_cli
from watersim.bench_scaling import SPREAD_LIMIT, ScalingRun, fit_scaling


def _run(n: int, n_fluid: int, a: float, b: float, pairs_per_fluid: float = 150.0) -> ScalingRun:
    """A run whose ten steps cost exactly a per fluid and b per wall particle [s]."""
    return ScalingRun(n_particles=n, n_fluid=n_fluid, wall_s=10 * (a * n_fluid + b * (n - n_fluid)),
                      steps=10, fluid_pairs=int(pairs_per_fluid * n_fluid),
                      force_evaluations_per_step=1)


def test_a_linear_cost_is_recovered_and_the_counted_spread_comes_from_the_walls() -> None:
    a, b = 1.0e-6, 0.1e-6
    # the walls' share falls from 42 % to 12 %, as in the 3D dam break from 20k to 2M
    runs = [_run(20_000, 11_600, a, b), _run(200_000, 152_000, a, b),
            _run(2_000_000, 1_760_000, a, b)]
    result = fit_scaling(runs)
    assert result["fit"]["us_per_fluid_particle_step"] == pytest.approx(1.0, rel=1e-9)
    assert result["fit"]["us_per_wall_particle_step"] == pytest.approx(0.1, rel=1e-6)
    assert result["fit"]["max_abs_relative_residual"] < 1e-9
    counted = [(a * r.n_fluid + b * r.n_walls) / r.n_particles * 1e6 for r in runs]
    assert result["us_per_particle_step"] == pytest.approx(counted)
    assert result["spread"]["counted"] == pytest.approx(max(counted) / min(counted) - 1)
    # per fluid particle the walls still add a little: (a Nf + b Nw) / Nf
    per_fluid = [1e6 * (a + b * r.n_walls / r.n_fluid) for r in runs]
    assert result["spread"]["per_fluid_particle"] == pytest.approx(
        max(per_fluid) / min(per_fluid) - 1)
    assert result["within_limit"] == {"counted": False, "per_fluid_particle": True,
                                      "per_pair": True}
    assert result["spread_limit"] == SPREAD_LIMIT
    assert result["wall_share"][0] == pytest.approx(0.42)


def test_a_cost_that_grows_faster_than_n_shows_in_the_residuals() -> None:
    # t = a N log N: not linear in either kind of particle
    import math

    runs = [ScalingRun(n, int(0.8 * n), 1e-7 * n * math.log(n), 1, int(100 * n), 1)
            for n in (10_000, 100_000, 1_000_000)]
    result = fit_scaling(runs)
    assert result["fit"]["max_abs_relative_residual"] > 0.05
    assert result["spread"]["per_fluid_particle"] > SPREAD_LIMIT


def test_bad_runs_are_refused_naming_the_field() -> None:
    with pytest.raises(ValueError, match="runs: a scaling fit needs two sizes"):
        fit_scaling([_run(100, 50, 1e-6, 1e-7)])
    with pytest.raises(ValueError, match=r"runs\[1\]"):
        fit_scaling([_run(100, 50, 1e-6, 1e-7), ScalingRun(100, 0, 1.0, 1, 0, 1)])


def test_bench_scaling_times_each_size_and_fits_them() -> None:
    proc = run_cli("bench", "--case", "dsph-dambreak3d", "--scaling", "8000,3000,5000",
                   "--steps", "1", "--warmup", "0", "--json", env={"RAYON_NUM_THREADS": "1"})
    assert proc.returncode == 0, proc.stderr
    result = json.loads(proc.stdout)
    runs = result["runs"]
    counts = [r["n_particles"] for r in runs]
    assert counts == sorted(counts) and len(runs) == 3
    for target, n in zip((3000, 5000, 8000), counts, strict=True):
        assert abs(n - target) <= 0.05 * target
    scaling = result["scaling"]
    assert scaling["sizes"] == counts
    assert scaling["us_per_particle_step"] == pytest.approx(
        [r["us_per_particle_step"] for r in runs])
    assert scaling["wall_share"] == pytest.approx(
        [1 - r["n_fluid"] / r["n_particles"] for r in runs])
    assert len(scaling["fit"]["relative_residuals"]) == 3
    assert set(scaling["within_limit"]) == {"counted", "per_fluid_particle", "per_pair"}


@pytest.mark.parametrize("extra", [("--scaling", "3000"), ("--scaling", "3000,x"),
                                   ("--scaling", "3000,3000"), ("--scaling", "5,3000"),
                                   ("--scaling", "3000,5000", "--particles", "4000"),
                                   ("--scaling", "3000,5000", "--compare-threads", "1,2")])
def test_bench_scaling_refuses_bad_sizes(extra: tuple[str, ...]) -> None:
    proc = run_cli("bench", "--case", "dsph-dambreak3d", *extra)
    assert proc.returncode == 2 and "--scaling" in proc.stderr, proc.stderr


def test_bench_scaling_prints_a_table_without_json() -> None:
    proc = run_cli("bench", "--case", "dambreak2d", "--scaling", "1000,2000", "--steps", "1",
                   "--warmup", "0", env={"RAYON_NUM_THREADS": "1"})
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    assert lines[0].startswith("dambreak2d on 1 thread(s)")
    assert len([line for line in lines if line.split()[0].isdigit()]) == 2
    assert any(line.startswith("spread counted:") for line in lines)
    assert lines[-1].startswith("fit: ") and "us per wall particle-step" in lines[-1]
