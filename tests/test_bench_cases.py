"""The DualSPHysics reference cases of ``watersim bench``: same particle counts and settings."""

from __future__ import annotations

import json

import numpy as np
import pytest

from conftest import run_cli
from watersim import Simulation, _core
from watersim.bench_cases import DSPH_CASES, dsph_scene


@pytest.mark.parametrize("case", sorted(DSPH_CASES))
def test_particle_count_matches_dualsphysics(case: str) -> None:
    sim = Simulation(dsph_scene(case))
    spec = DSPH_CASES[case]
    # the lattice conventions differ at the walls by at most a row of particles
    assert sim.n_particles == pytest.approx(spec.particles, rel=0.012)
    assert sim.params()["boundary_layers"] == 1


@pytest.mark.parametrize("case", sorted(DSPH_CASES))
def test_walls_are_dualsphysics_dbc(case: str) -> None:
    # every reference case runs DualSPHysics' dynamic boundary condition, whatever the
    # builder's own default (the flume's is Adami's walls)
    assert dsph_scene(case).get("boundary", {"model": "dbc"}) == {"model": "dbc"}


def test_settings_are_dualsphysics_own() -> None:
    s3 = dsph_scene("dsph-dambreak3d")
    settings = (s3["kernel"], s3["coefh"], s3["cfl"], s3["coefsound"])
    assert settings == ("cubic_spline", 1.0, 0.2, 20.0)
    assert s3["viscosity"] == {"model": "artificial", "alpha": 0.1}
    assert s3["diffusion"] == {"model": "fourtakas", "delta": 0.1}
    assert s3["integrator"] == {"scheme": "verlet", "euler_every": 40}
    s2 = dsph_scene("dsph-dambreak2d")
    assert (s2["kernel"], s2["viscosity"]["alpha"], s2["integrator"]["scheme"]) == (
        "wendland", 0.02, "verlet")
    piston = dsph_scene("dsph-piston2d")
    assert (piston["kernel"], piston["coefh"], piston["diffusion"]["model"]) == (
        "wendland", 1.2, "none")
    assert piston["integrator"]["scheme"] == "symplectic" and piston["paddle"]["kind"] == "piston"


def test_the_piston_case_is_wallregawas2s_fluid_and_walls() -> None:
    """GenCase's WallRegAwas2 at dp = 6 mm (commit cedbb95b): 21,457 fluid particles in 499
    columns from x = 0.008 m and 43 rows one dp above the floor; a flat tank with a far wall, 0.6
    m high; a piston with its AWAS. (The paddle is one layer thick here, four there.)"""
    scene = dsph_scene("dsph-piston2d")
    sim = _core.Simulation(json.dumps(scene))
    assert sim.n_fluid == 21_457
    assert scene["obstacles"] == [] and scene["tank"]["max"][1] == pytest.approx(0.6)
    assert scene["tank"]["min"][0] == pytest.approx(-34 * 0.006)
    assert "absorption" in scene["paddle"] and scene.get("damping") is None
    x = np.asarray(sim.positions)[np.asarray(sim.kinds) == 0]
    assert x.min(axis=0) == pytest.approx([0.5 * 0.006, 0.5 * 0.006])


def test_the_cubic_spline_case_runs_dualsphysics_tensile_correction() -> None:
    # DualSPHysics applies Monaghan's (2000) correction to every cubic-spline pair
    assert dsph_scene("dsph-dambreak3d")["tensile_correction"] == {"model": "monaghan"}
    assert all("tensile_correction" not in dsph_scene(c)
               for c in ("dsph-dambreak2d", "dsph-piston2d"))
    for law, expected in (("none", None), ("monaghan", "monaghan")):
        proc = run_cli("bench", "--case", "dsph-dambreak3d", "--particles", "3000", "--steps",
                       "1", "--set", f"tensile_correction={law}", "--json",
                       env={"RAYON_NUM_THREADS": "1"})
        assert proc.returncode == 0, proc.stderr
        assert json.loads(proc.stdout)["tensile_correction"] == expected
    proc = run_cli("bench", "--case", "dsph-dambreak3d", "--set", "tensile_correction=gray")
    assert proc.returncode == 2 and "tensile_correction" in proc.stderr


def test_bench_prints_no_ratio_it_did_not_measure() -> None:
    proc = run_cli("bench", "--case", "dsph-dambreak2d", "--particles", "3000", "--steps", "2",
                   "--json", env={"RAYON_NUM_THREADS": "1"})
    assert proc.returncode == 0, proc.stderr
    result = json.loads(proc.stdout)
    assert abs(result["n_particles"] - 3000) <= 0.05 * 3000
    # a ratio to DualSPHysics comes only from `watersim bench --against` (side by side)
    assert not {k for k in result if "speedup" in k or "target" in k or k.startswith("dsph_us")}
    assert result["dsph_particles"] == 21_001 and result["peak_rss_bytes"] > 0
    # Verlet: one force evaluation per step; a full 2D support at coefh 1 holds some 24 pairs
    assert result["force_evaluations_per_step"] == 1
    assert 10 < result["pairs_per_fluid_particle"] < 25
    assert result["ns_per_pair"] == pytest.approx(
        1e9 * result["wall_s"] / (result["fluid_pairs"] * result["steps"]))
    assert 0 < result["baseline_rss_bytes"] < result["peak_rss_bytes"]
    assert result["peak_rss_above_baseline_per_particle"] == pytest.approx(
        (result["peak_rss_bytes"] - result["baseline_rss_bytes"]) / result["n_particles"])


def test_bench_refuses_overrides_of_a_reference_case() -> None:
    proc = run_cli("bench", "--case", "dsph-piston2d", "--set", "dp=0.01")
    assert proc.returncode == 2 and "--set" in proc.stderr


@pytest.mark.parametrize("case", sorted(DSPH_CASES))
def test_pair_terms_are_dualsphysics_float(case: str) -> None:
    # DualSPHysics' CPU solver forms its pair terms in float; WaterSim's default is f64
    assert dsph_scene(case)["force_precision"] == "f32"
    assert Simulation(dsph_scene(case)).scene["force_precision"] == "f32"


def test_a_reference_case_takes_the_force_precision() -> None:
    for precision in ("f32", "f64"):
        proc = run_cli("bench", "--case", "dsph-dambreak2d", "--particles", "3000", "--steps",
                       "2", "--set", f"force_precision={precision}", "--json",
                       env={"RAYON_NUM_THREADS": "1"})
        assert proc.returncode == 0, proc.stderr
        assert json.loads(proc.stdout)["force_precision"] == precision
    proc = run_cli("bench", "--case", "dsph-dambreak2d", "--particles", "3000", "--steps", "2",
                   "--json", env={"RAYON_NUM_THREADS": "1"})
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["force_precision"] == "f32"
    proc = run_cli("bench", "--case", "dsph-piston2d", "--set", "force_precision=f16")
    assert proc.returncode == 2 and "force_precision" in proc.stderr
