"""Validation package: metrics on synthetic inputs with known errors, convergence/Pareto/cheapest
on synthetic records, the ``watersim validate`` CLI on a tiny case, and the Dask executor."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from watersim import wave_theory as wt
from watersim.cli import main
from watersim.measure import (
    MartinMoyceHeight,
    front_error,
    load_martin_moyce,
    load_martin_moyce_height,
)
from watersim.validation import CASES, StandingWaveTank, metrics, run_case
from watersim.validation.report import (
    cheapest_meeting,
    convergence_order,
    pareto_front,
    self_convergence,
    settings_label,
    write_report,
)
from watersim.validation.sweep import (
    ValidateError,
    check_scheduler_answers,
    parse_resolutions,
    parse_scheduler,
    plan,
    run_sweep,
)

G = 9.81


# ------------------------------------------------------------------------------------------------
# metrics


def test_hydrostatic_error_of_a_constant_offset() -> None:
    z = np.linspace(0.0, 0.5, 21)
    exact = 1000.0 * G * (0.5 - z)
    assert metrics.hydrostatic_pressure_error(z, exact, 0.5, 1000.0, G) == (0.0, 0.0)
    rms, worst = metrics.hydrostatic_pressure_error(z, exact + 0.01 * 1000.0 * G * 0.5, 0.5,
                                                    1000.0, G)
    assert rms == pytest.approx(0.01) and worst == pytest.approx(0.01)
    # a 10 % error in the slope: |err| = 0.1 (d - z)/d, max at the floor
    rms, worst = metrics.hydrostatic_pressure_error(z, 1.1 * exact, 0.5, 1000.0, G)
    assert worst == pytest.approx(0.1)
    assert rms == pytest.approx(0.1 * np.sqrt(np.mean(((0.5 - z) / 0.5) ** 2)))


def test_spurious_velocity() -> None:
    v = np.zeros((10, 2))
    v[3] = [0.0, -0.1 * math.sqrt(G * 0.5)]
    assert metrics.spurious_velocity(v, 0.5, G) == pytest.approx(0.1)


def test_front_error_of_a_scaled_martin_moyce_curve() -> None:
    ref = load_martin_moyce("lethe")
    t_ref, x_ref = ref.dimensional(1.0, G)
    t = np.union1d(np.linspace(0.0, t_ref[-1], 400), t_ref)  # samples at the measured times
    exact = np.interp(t, t_ref, x_ref)
    assert front_error(t, exact, 1.0, G).rms_rel_error == pytest.approx(0.0, abs=1e-12)
    # a front 10 % ahead everywhere: the error is 10 % at every point
    err = front_error(t, 1.1 * exact, 1.0, G)
    assert err.rms_rel_error == pytest.approx(0.1) and err.mean_rel_error == pytest.approx(0.1)


def test_best_shift_recovers_a_time_lead() -> None:
    ref = load_martin_moyce("lethe")
    t_ref, x_ref = ref.dimensional(1.0, G)
    lead = 0.05
    t = np.linspace(0.0, t_ref[-1], 700)
    x = np.interp(t + lead, t_ref, x_ref)  # the simulated front leads the data by 0.05 s
    raw = front_error(t, x, 1.0, G)
    assert raw.rms_rel_error > 0.05  # the lead shows as a large raw error ...
    shifted = metrics.front_error_best_shift(t, x, 1.0, G)
    assert shifted.shift_s == pytest.approx(lead, abs=1e-3)  # ... which the shift removes
    assert shifted.rms_rel_error < 5e-3


def _height_curve(width: float) -> tuple[np.ndarray, np.ndarray]:
    """The Martin & Moyce height itself, sampled every 0.01 s and at the tabulated times."""
    t_ref, h_ref = load_martin_moyce_height().dimensional(width, G)
    t = np.union1d(np.arange(0.0, 0.7001, 0.01), t_ref[t_ref <= 0.7])
    h = np.interp(t, np.concatenate([[0.0], t_ref]), np.concatenate([[2.0 * width], h_ref]))
    return t, h


def test_column_height_error_of_a_scaled_martin_moyce_curve() -> None:
    t, exact = _height_curve(1.0)
    err = metrics.column_height_error(t, exact, 1.0, G)
    assert err.rms_rel_error == pytest.approx(0.0, abs=1e-12)
    assert err.n_points == 9  # tau = 0.56 ... 2.00 lie within 0.7 s for a = 1 m
    assert err.t_max_s == pytest.approx(2.00 / math.sqrt(G))
    # a column 10 % too high everywhere: 10 % at every point, signed positive
    high = metrics.column_height_error(t, 1.1 * exact, 1.0, G)
    assert high.rms_rel_error == pytest.approx(0.1) and high.max_rel_error == pytest.approx(0.1)
    assert high.mean_rel_error == pytest.approx(0.1)
    # a known error at one point only: 18 % at the last of 9 points -> RMS 0.18 / 3
    bumped = exact.copy()
    last = np.argmin(np.abs(t - 2.00 / math.sqrt(G)))
    bumped[last] *= 1.18
    one = metrics.column_height_error(t, bumped, 1.0, G)
    assert one.rms_rel_error == pytest.approx(0.18 / 3.0)
    assert one.max_rel_error == pytest.approx(0.18)
    # the shift is added to the simulated times: a run 0.05 s late is matched by shift -0.05
    late = np.interp(t - 0.05, t, exact)
    assert metrics.column_height_error(t, late, 1.0, G).rms_rel_error > 0.03
    assert metrics.column_height_error(t + 0.05, exact, 1.0, G, shift=-0.05).rms_rel_error \
        == pytest.approx(0.0, abs=1e-12)


def test_column_height_error_against_a_wrong_reference_fails() -> None:
    t, exact = _height_curve(1.0)
    ref = load_martin_moyce_height()
    # the front's time scaling t sqrt(2 g / a) (a factor sqrt 2 in time) instead of t sqrt(g / a)
    wrong_time = MartinMoyceHeight(tau=ref.tau * math.sqrt(2.0), eta=ref.eta, n2=ref.n2)
    assert metrics.column_height_error(t, exact, 1.0, G, wrong_time).rms_rel_error > 0.10
    # heights over a instead of over n^2 a
    wrong_scale = MartinMoyceHeight(tau=ref.tau, eta=ref.eta, n2=1.0)
    assert metrics.column_height_error(t, exact, 1.0, G, wrong_scale).rms_rel_error > 0.9
    with pytest.raises(ValueError, match="holds no tabulated height"):
        metrics.column_height_error([0.0, 0.1], [2.0, 2.0], 1.0, G)
    with pytest.raises(ValueError, match="increasing"):
        metrics.column_height_error([0.0, 0.5, 0.5], [2.0, 1.5, 1.4], 1.0, G)
    with pytest.raises(ValueError, match="width"):
        metrics.column_height_error(t, exact, 0.0, G)


def test_standing_wave_period_deep_water_limit() -> None:
    length = 1.0
    deep = metrics.standing_wave_period(length, 20.0, G)
    assert deep == pytest.approx(2.0 * math.pi / math.sqrt(G * math.pi / length), rel=1e-12)
    shallow = metrics.standing_wave_period(length, 0.01, G)  # c = sqrt(g d), T = 2 l / c
    assert shallow == pytest.approx(2.0 * length / math.sqrt(G * 0.01), rel=1e-3)


def test_surface_profile_and_mode_amplitude_of_a_cosine_lattice() -> None:
    dp, length, depth, a = 0.01, 1.0, 0.3, 0.04
    xs = (np.arange(100) + 0.5) * dp
    pts = []
    for x in xs:
        top = depth + a * math.cos(math.pi * x / length)
        zs = np.arange(0.5 * dp, top - 0.5 * dp + 1e-12, dp)
        zs = zs - zs[-1] + top - 0.5 * dp  # the top particle sits dp/2 below the surface
        pts += [(x, z) for z in zs]
    x, top = metrics.surface_profile(np.array(pts), dp, 0.0, length)
    assert np.allclose(top, depth + a * np.cos(math.pi * x / length))
    assert metrics.standing_wave_mode_amplitude(x, top, length) == pytest.approx(a, rel=1e-9)
    assert metrics.standing_wave_mode_amplitude(x, top, length, mode=2) == pytest.approx(
        0.0, abs=1e-12)


def test_damped_oscillation_fit_recovers_known_parameters() -> None:
    t = np.linspace(0.0, 3.0, 120)
    y = 0.04 * np.exp(-0.3 * t) * np.cos(5.0 * t + 0.2) + 0.01
    fit = metrics.damped_oscillation_fit(t, y, 4.5)
    assert fit.omega == pytest.approx(5.0, rel=1e-6)
    assert fit.decay == pytest.approx(0.3, rel=1e-5)
    assert fit.amplitude == pytest.approx(0.04, rel=1e-6)
    assert fit.phase == pytest.approx(0.2, abs=1e-6)
    assert fit.log_decrement == pytest.approx(0.3 * 2 * math.pi / 5.0, rel=1e-5)


def test_stokes3_wavelength() -> None:
    T, d = 1.2, 0.3
    linear = float(wt.wavelength(T, d))
    assert metrics.stokes3_wavelength(T, d, 1e-6) == pytest.approx(linear, rel=1e-9)
    longer = metrics.stokes3_wavelength(T, d, 0.05)
    assert longer > linear
    # deep water: omega^2 = g k (1 + (k a)^2)
    k = 2 * math.pi / metrics.stokes3_wavelength(0.8, 50.0, 0.05)
    assert (2 * math.pi / 0.8) ** 2 == pytest.approx(G * k * (1 + (k * 0.025) ** 2), rel=1e-9)


def test_wavelength_from_wrapped_phases() -> None:
    k = 2 * math.pi / 1.77
    x = np.array([1.77, 2.655, 2.832, 3.0975, 3.54, 5.31])
    phase = np.angle(np.exp(1j * (0.7 - k * x)))  # wrapped into (-pi, pi]
    assert metrics.wavelength_from_phases(x, phase, 0.8 * k) == pytest.approx(1.77, rel=1e-9)


def test_height_loss_per_wavelength() -> None:
    wl = 1.5
    x = np.array([1.0, 2.0, 3.0]) * wl
    h = 0.05 * 0.9 ** (x / wl)  # 10 % lost per wavelength
    assert metrics.height_loss_per_wavelength(x, h, wl) == pytest.approx(0.1)
    assert metrics.height_loss_per_wavelength(x, np.full(3, 0.05), wl) == pytest.approx(0.0)


def test_harmonic_spread_and_amplitude_errors() -> None:
    assert metrics.harmonic_spread([0.002, 0.003, 0.0025], 0.004) == pytest.approx(0.25)
    sim = np.array([[0.011, 0.002, 0.0], [0.009, 0.002, 0.0]])
    ref = np.array([[0.010, 0.001, 0.0], [0.010, 0.003, 0.0]])
    err = metrics.harmonic_amplitude_errors(sim, ref, 0.01)
    assert np.allclose(err, [0.1, 0.1, 0.0])


def test_relative_phase_error_ignores_a_clock_offset() -> None:
    meas = np.array([0.3, -2.0, 3.0, 1.0])
    assert metrics.relative_phase_error(meas + 1.234, meas) == pytest.approx(0.0, abs=1e-12)
    off = np.array([0.1, -0.1, 0.1, -0.1])
    assert metrics.relative_phase_error(meas + 2.0 + off, meas) == pytest.approx(0.1)


def test_a_wrong_synolakis_coefficient_gives_a_large_error() -> None:
    runup = float(wt.synolakis_runup(0.045, 0.3, 1 / 3)) * 0.3  # a "simulation" that obeys it
    law = float(wt.synolakis_runup(0.045, 0.3, 1 / 3)) * 0.3
    assert metrics.relative_error(runup, law) == pytest.approx(0.0)
    wrong = 2.0 * math.sqrt(3.0) * 0.15**1.25 * 0.3  # coefficient 2.0 instead of 2.831
    assert metrics.relative_error(runup, wrong) == pytest.approx(2.831 / 2.0 - 1.0)
    assert metrics.relative_error(runup, wrong) > CASES["solitary2d"].target


# ------------------------------------------------------------------------------------------------
# report functions on synthetic records


def _rec(res: float, dp: float, wall: float, err: float | None, status: str = "ok") -> dict:
    return {"case": "tank2d", "resolution": res, "dp": dp, "n_particles": 100, "steps": 10,
            "sim_time": 1.0, "wall_s": wall, "cpu_s": wall, "threads": 1,
            "errors": {"pressure_rms": err, "spurious_velocity": 0.001}, "status": status,
            "message": None}


def test_convergence_order_of_synthetic_errors() -> None:
    dp = np.array([0.1, 0.05, 0.025, 0.0125])
    assert convergence_order(dp, 3.0 * dp**2).order == pytest.approx(2.0)
    order = convergence_order(dp, 0.2 * dp**-0.5)
    assert order.order == pytest.approx(-0.5) and order.falls is False
    assert order.falls_every_step is False
    assert convergence_order(dp, 3.0 * dp**2).falls_every_step is True
    # the dam break's column height: a slow fall at every step (p = 0.17) ...
    slow = convergence_order(dp, [0.0433, 0.0409, 0.0353, 0.0311])
    assert 0.1 < slow.order < 0.2 and slow.falls and slow.falls_every_step
    # ... is not a fall with one step back up
    assert convergence_order(dp, [0.0433, 0.0409, 0.0420, 0.0311]).falls_every_step is False
    assert math.isnan(convergence_order([0.1], [0.2]).order)


def test_pareto_front_and_cheapest_run() -> None:
    runs = [_rec(10, 0.05, 1.0, 0.05), _rec(20, 0.025, 8.0, 0.02), _rec(30, 0.0167, 30.0, 0.03),
            _rec(40, 0.0125, 60.0, 0.008), _rec(50, 0.01, 2.0, None, status="non_finite")]
    front = pareto_front(runs, "pressure_rms")
    assert [r["resolution"] for r in front] == [10, 20, 40]
    assert cheapest_meeting(runs, "pressure_rms", 0.025)["resolution"] == 20
    assert cheapest_meeting(runs, "pressure_rms", 0.001) is None
    # a signed error counts by its size: -0.39 does not meet 0.10, -0.02 beats +0.05
    signed = [_rec(1, 0.05, 1.0, -0.39), _rec(2, 0.04, 2.0, 0.05), _rec(3, 0.03, 4.0, -0.02)]
    assert cheapest_meeting(signed, "pressure_rms", 0.10)["resolution"] == 2
    assert [r["resolution"] for r in pareto_front(signed, "pressure_rms")] == [1, 2, 3]
    assert cheapest_meeting(signed, "pressure_rms", 0.03)["resolution"] == 3


def test_self_convergence_of_synthetic_fronts(tmp_path) -> None:
    t = np.linspace(0.0, 0.7, 71)
    exact = 1.0 + 4.0 * t**2

    def run(dp: float) -> dict:
        r = _rec(1.0 / dp, dp, 1.0, 0.1)
        r["details"] = {"front_t": list(t), "front_x": list(exact * (1.0 + 3.0 * dp**2))}
        return r

    out = self_convergence([run(0.1), run(0.05), run(0.0125)])
    assert [r["dp"] for r, _ in out] == [0.1, 0.05]
    ref = exact * (1.0 + 3.0 * 0.0125**2)
    for r, diff in out:
        rel = exact * (1.0 + 3.0 * r["dp"] ** 2) / ref - 1.0
        assert diff == pytest.approx(np.sqrt(np.mean(rel**2)))
    # a second series under its own key (the column height): the runs without it are left out
    with_height = [run(0.1), run(0.05), run(0.025), run(0.0125)]
    for r in with_height[1:]:
        r["details"]["height_h"] = list(2.0 - t * (1.0 + r["dp"]))
    height = self_convergence(with_height, "front_t", "height_h")
    assert [r["dp"] for r, _ in height] == [0.05, 0.025]
    for r, diff in height:
        rel = (2.0 - t * (1.0 + r["dp"])) / (2.0 - t * 1.0125) - 1.0
        assert diff == pytest.approx(np.sqrt(np.mean(rel**2)))
    text = write_report(with_height, tmp_path).read_text()
    assert "difference of the column height to the finest run's" in text


def test_report_writes_readme_and_plots(tmp_path) -> None:
    runs = [_rec(10, 0.05, 1.0, 0.05), _rec(20, 0.025, 8.0, 0.012), _rec(40, 0.0125, 60.0, 0.004)]
    readme = write_report(runs, tmp_path, header=["- test header"])
    text = readme.read_text()
    assert "the cheapest run that meets" in text and "resolution 40" in text
    slope = np.polyfit(np.log([0.05, 0.025, 0.0125]), np.log([0.05, 0.012, 0.004]), 1)[0]
    assert f"`pressure_rms`: p = {slope:.2f} over 3 runs; the error falls" in text
    assert (tmp_path / "tank2d.png").stat().st_size > 1000


def test_report_compares_the_settings_of_a_case(tmp_path) -> None:
    """Runs of one case with different ``--set`` items: one row per run with its setting, the
    Pareto front over CPU time across settings, each setting's order, and the cheapest run
    that meets the target whatever its setting."""

    def with_settings(rec: dict, settings: dict | None, cpu: float) -> dict:
        return {**rec, "cpu_s": cpu, "details": {} if settings is None else {"settings": settings}}

    default = [with_settings(_rec(10, 0.05, 1.0, 0.05), None, 1.0),
               with_settings(_rec(20, 0.025, 8.0, 0.02), {}, 8.0)]
    option = [with_settings(_rec(10, 0.05, 2.0, 0.008), {"viscosity": "laminar", "b": "1"}, 2.0),
              with_settings(_rec(20, 0.025, 16.0, 0.004, ), {"viscosity": "laminar", "b": "1"},
                            16.0),
              with_settings(_rec(20, 0.025, 3.0, None, "density_out_of_range"),
                            {"kernel": "wendland_c4"}, 3.0)]
    assert settings_label(default[0]) == settings_label(default[1]) == "default"
    assert settings_label(option[0]) == "b=1, viscosity=laminar"
    assert [r["resolution"] for r in pareto_front(default + option, "pressure_rms", "cpu_s")] \
        == [10, 10, 20]
    text = write_report(default + option, tmp_path).read_text()
    assert "| setting | resolution |" in text
    assert "| b=1, viscosity=laminar | 20 | 100 | 10 | 16 | ok | 0.004 |" in text
    assert "| kernel=wendland_c4 | 20 | 100 | 10 | 3 | **density_out_of_range** |" in text
    assert "Pareto front (`pressure_rms` against CPU time): default at resolution 10 (1 s, " \
        "0.05), b=1, viscosity=laminar at resolution 10 (2 s, 0.008)" in text
    assert "- b=1, viscosity=laminar: p = 1.00 over 2 runs; the error falls" in text
    # tank2d's target is 1 %: met first by the option at resolution 10 (2 s CPU)
    assert "the cheapest run that meets" in text and "b=1, viscosity=laminar at resolution 10" \
        in text
    assert (tmp_path / "tank2d.png").stat().st_size > 1000
    # one setting only: the usual section, without a settings column
    assert "| setting |" not in write_report(default, tmp_path / "one").read_text()


# ------------------------------------------------------------------------------------------------
# cases, sweep and CLI


def test_standing_wave_tank_surface_is_a_cosine_staircase() -> None:
    b = StandingWaveTank(dp=0.025, amplitude=0.05, until=1.0)
    sim = b.build()
    x, top = metrics.surface_profile(sim.fluid_positions(), 0.025, 0.0, 1.0)
    assert x.size == 40
    design = 0.5 + 0.05 * np.cos(math.pi * x)
    assert np.max(np.abs(top - design)) <= 0.5 * 0.025 + 1e-9
    amp = metrics.standing_wave_mode_amplitude(x, top, 1.0)
    assert amp == pytest.approx(0.05, abs=0.25 * 0.025)


def test_bad_input_is_refused_before_running() -> None:
    with pytest.raises(ValidateError, match="unknown validation case 'nope'"):
        plan(["nope"], None, False)
    with pytest.raises(ValidateError, match="--resolutions: each resolution must be positive"):
        parse_resolutions("10,-2")
    with pytest.raises(ValidateError, match="--resolutions: expected numbers"):
        parse_resolutions("10,x")
    assert plan(["tank2d"], None, True) == [("tank2d", 10.0)]
    with pytest.raises(ValueError, match="resolution: must be positive"):
        run_case("tank2d", 0.0)
    assert main(["validate", "nope"]) == 2
    assert main(["validate", "--from-json", "x.json", "--quick", "--report", "r"]) == 2
    assert main(["validate", "tank2d", "--jobs", "2", "--scheduler", "tcp://x:1"]) == 2
    assert main(["validate", "tank2d", "--jobs", "0"]) == 2
    assert main(["validate", "tank2d", "--note", "n"]) == 2  # a note needs --report


def test_run_case_reports_a_scene_it_cannot_build() -> None:
    record = run_case("tank2d", 1.0, quick=True)  # dp = depth: fewer than 2 particles deep
    assert record["status"] == "error" and "dp" in record["message"]


FIELDS = {"case", "resolution", "dp", "n_particles", "steps", "sim_time", "wall_s", "threads",
          "errors", "status"}


def test_cli_validate_tiny_case(tmp_path, capsys) -> None:
    out_json = tmp_path / "runs.json"
    report = tmp_path / "report"
    code = main(["validate", "tank2d", "--quick", "--resolutions", "4,6", "--json",
                 str(out_json), "--report", str(report)])
    assert code == 0
    runs = json.loads(out_json.read_text())
    assert [r["resolution"] for r in runs] == [4.0, 6.0]
    for r in runs:
        assert FIELDS <= set(r)
        assert r["status"] == "ok" and r["steps"] > 0 and r["sim_time"] >= 0.5
        assert r["dp"] == pytest.approx(0.5 / r["resolution"])
        assert set(r["errors"]) == {"pressure_rms", "pressure_max", "spurious_velocity"}
    text = (report / "README.md").read_text()
    assert "watersim validate tank2d --quick" in text and "![tank2d](tank2d.png)" in text
    assert (report / "tank2d.png").exists()
    # the report again from the JSON, without running
    again = tmp_path / "again"
    assert main(["validate", "--from-json", str(out_json), "--report", str(again)]) == 0
    assert (again / "README.md").exists()


def test_dambreak2d_records_front_and_column_height() -> None:
    r = run_case("dambreak2d", 6.0, quick=True)  # dp = 1/6 m, to 0.4 s: about a second
    assert r["status"] == "ok"
    assert {"front_rms", "front_max", "front_rms_shifted", "height_rms", "height_max"} <= set(
        r["errors"])
    d = r["details"]
    assert d["height_n_points"] == 4  # tau = 0.56 ... 1.08 lie within 0.4 s for a = 1 m
    assert len(d["height_h"]) == len(d["front_t"]) and d["height_h"][0] <= 2.0 + 1e-9
    # the recorded metric is the one of the recorded samples
    again = metrics.column_height_error(d["front_t"], d["height_h"], 1.0, G)
    assert r["errors"]["height_rms"] == pytest.approx(again.rms_rel_error)
    assert 0.0 < r["errors"]["height_rms"] < 0.3
    assert d["front_rms_pysph_a2.25in"] is not None
    three = run_case("dambreak3d", 3.0, quick=True)  # the 3D case keeps the front only
    assert "height_rms" not in three["errors"] and "height_h" not in three["details"]


def test_process_pool_executor() -> None:
    runs = run_sweep([("tank2d", 4.0), ("tank2d", 5.0)], quick=True, jobs=2)
    assert [r["resolution"] for r in runs] == [4.0, 5.0]
    assert all(r["status"] == "ok" for r in runs)


def test_dask_local_cluster_executor(tmp_path) -> None:
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        runs = run_sweep([("tank2d", 4.0)], quick=True, scheduler=cluster.scheduler_address,
                         json_path=tmp_path / "runs.json")
    assert runs[0]["status"] == "ok" and runs[0]["steps"] > 0
    assert json.loads((tmp_path / "runs.json").read_text())[0]["case"] == "tank2d"


@pytest.mark.parametrize(("address", "reason"), [
    ("", "expected tcp://HOST:PORT"), ("   ", "expected tcp://HOST:PORT"),
    ("tcp://", "expected tcp://HOST:PORT"), ("host", "expected tcp://HOST:PORT"),
    ("tcp://host:port", "port must be a number"), ("tcp://h:0", "port must be a number"),
    ("h:70000", "port must be a number"), ("tcp://h:1/x", "expected tcp://HOST:PORT"),
    ("tls://h:8786", "tls:// is not supported"), ("inproc://x", "inproc:// is not supported"),
])
def test_a_bad_scheduler_address_is_refused_naming_the_option(address: str, reason: str) -> None:
    with pytest.raises(ValidateError, match=rf"^--scheduler: .*{reason}"):
        parse_scheduler(address)
    assert main(["validate", "tank2d", "--scheduler", address]) == 2


def test_scheduler_addresses_that_are_accepted() -> None:
    assert parse_scheduler("tcp://10.0.0.1:8786") == "tcp://10.0.0.1:8786"
    assert parse_scheduler("host.example:8786") == "tcp://host.example:8786"
    assert parse_scheduler("tcp://[::1]:8786") == "tcp://[::1]:8786"


def test_a_silent_listener_is_refused_within_the_timeout() -> None:
    """A port that accepts and never answers (not a scheduler): refused, not a hang."""
    import socket
    import threading
    import time

    pytest.importorskip("dask.distributed")
    accepted: list[socket.socket] = []
    with socket.socket() as server:
        server.bind(("127.0.0.1", 0))
        server.listen()
        threading.Thread(target=lambda: accepted.append(server.accept()[0]), daemon=True).start()
        start = time.monotonic()
        with pytest.raises(ValidateError, match="--scheduler: no Dask scheduler answered"):
            check_scheduler_answers(f"tcp://127.0.0.1:{server.getsockname()[1]}", timeout=1.0)
        assert time.monotonic() - start < 5.0
    for conn in accepted:
        conn.close()


def test_standing_wave_tank_keeps_the_tank_numerics() -> None:
    """StandingWaveTank replaces Tank's per-dimension defaults (its geometry): it must carry
    the same numerics preset, or the standing2d figures move with a default elsewhere."""
    from watersim import _core
    from watersim.scenes import Tank
    from watersim.validation.cases import StandingWaveTank

    def numerics(builder: Tank) -> dict[str, object]:
        scene = json.loads(_core.resolve_scene(json.dumps(builder.to_scene())))
        return {k: scene[k] for k in ("viscosity", "diffusion", "integrator", "coefh",
                                      "coefsound", "cfl", "boundary")}

    assert numerics(StandingWaveTank(dp=0.05)) == numerics(Tank(dim=2, dp=0.05))


def test_stansby2d_case_plumbing() -> None:
    """stansby2d's scene, run length and metrics, without running it: the verticals stand at
    seed 002 Table 3's gauges (13 and 14 left out), the run leaves the steady periods it says at
    the last gauge, and each metric of a synthetic analysis.json is the one its note defines."""
    import warnings

    from watersim.flume import VelocityProbe
    from watersim.flume_cases import STANSBY_GAUGES, flume_builder
    from watersim.validation.stansby import (
        STANSBY_STEADY_PERIODS,
        stansby_metrics,
        stansby_undertow_table,
        stansby_until,
    )

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        scene = flume_builder("stansby2d", {})
    verticals = {g.name: g for g in scene.gauges if isinstance(g, VelocityProbe)}
    gauges = [8, 10, 11, 12, 15, 17, 18, 19, 21, 23]
    assert sorted(verticals) == sorted(f"u_gauge{n}" for n in gauges)
    for n in gauges:
        points = verticals[f"u_gauge{n}"].points
        x = STANSBY_GAUGES[n - 1]
        assert len(points) == 12 and all(p[0] == x for p in points)
        assert points[0][1] == pytest.approx((x - 2.0) / 20.0 + 0.5 * scene.dp, abs=1e-4)
        assert points[-1][1] == pytest.approx(0.34 + 0.105)
    for quick in (False, True):
        steady = stansby_until(scene, quick) - (
            scene.law.ramp_duration + scene.arrival_time(7.6) + scene.period)
        assert steady == pytest.approx(STANSBY_STEADY_PERIODS[quick] * 2.42)
    table = stansby_undertow_table()
    assert sorted(table) == [8, 10, 11, 12, 13, 14, 15, 17, 18, 19, 21, 23]
    assert table[8] == 0.022 and table[23] == 0.021

    wet_x = [5.3, 5.54, 5.6, 5.74]
    result = {
        "gauges": [{"x": 0.8, "still_depth": 0.34, "H_mean": 0.100},
                   {"x": 1.1, "still_depth": 0.34, "H_mean": 0.103},
                   {"x": 1.8, "still_depth": 0.34, "H_mean": 0.103},
                   *({"x": x, "still_depth": 0.34 - (x - 2.0) / 20.0, "H_mean": None}
                     for x in wet_x)],
        "breaking": {"phase_averaged": {"position": 5.3, "wave_height": 0.14, "n_waves": 4}},
        # + shoreward in analysis.json; gauge 13's vertical (none in the case) is not compared
        "velocity_verticals": [{"name": "u_gauge8", "undertow": -0.032,
                                "crest_velocity_over_sqrt_gD": 0.75},
                               {"name": "u_gauge10", "undertow": -0.008},
                               {"name": "u_gauge13", "undertow": -1.0},
                               {"name": "u_gauge11", "undertow": None}],
        # midpoints of the wet gauges 5.3 | 5.54 | 5.6 | 5.74: the first is before gauge 8
        "crest_celerity": {"x": [5.42, 5.57, 5.67], "ratio": [0.1, 0.9, 0.6]},
    }
    errors, details = stansby_metrics(result)
    assert "incident_first_harmonic" not in details  # no reflection analysis
    assert details["H_flat"] == pytest.approx(0.102)
    assert errors["H_flat"] == pytest.approx(0.003 / 0.105)
    assert errors["breaking_x_m"] == pytest.approx(0.24)  # 5.3 m: 0.24 m before 5.54 m
    assert details["undertow_gauges"] == [8, 10]
    assert details["crest_velocity_over_sqrt_gD"] == {"8": 0.75}
    assert details["undertow_seaward"] == [0.032, 0.008]
    # differences +0.01 and -0.01 m/s against a Table 3 mean of 0.02 m/s
    assert errors["undertow_rms"] == pytest.approx(0.5)
    assert errors["undertow_mean"] == pytest.approx(0.0, abs=1e-12)
    # pairs 0.06 m (0.9) and 0.14 m (0.6) apart: weighted mean 0.69, 0.01 below 0.70
    assert details["celerity_surf_x"] == [5.57, 5.67]
    assert details["celerity_ratio_surf"] == pytest.approx((0.06 * 0.9 + 0.14 * 0.6) / 0.2)
    assert errors["celerity"] == pytest.approx(0.01)
    result["breaking"]["phase_averaged"]["position"] = 5.6
    assert stansby_metrics(result)[0]["breaking_x_m"] == 0.0
    # the incident first harmonic against the target wave's (the Fourier wave's, or H/2)
    result.update(still_water_depth=0.34,
                  wave={"height": 0.105, "period": 2.42, "theory": "stream_function"},
                  reflection={"incident_amplitude": 0.0441, "coefficient": 0.03})
    details = stansby_metrics(result)[1]
    first = float(wt.stream_function_wave(0.105, 2.42, 0.34).elevation_coefficients[1])
    assert details["target_first_harmonic"] == pytest.approx(first)
    assert details["incident_first_harmonic_error"] == pytest.approx(0.0441 / first - 1.0)
    assert details["reflection_coefficient"] == 0.03
    result["wave"]["theory"] = "stokes2"
    assert stansby_metrics(result)[1]["target_first_harmonic"] == pytest.approx(0.0525)
    empty_errors, _ = stansby_metrics({"gauges": []})
    assert set(empty_errors) == set(errors) and all(v is None for v in empty_errors.values())
    # the crests' flux and what the undertow returns of it, at gauge 8 (5.54 m, d = 0.163 m)
    depth = 0.34 - (5.54 - 2.0) / 20.0
    linear = 9.81 * 0.12**2 / (8.0 * math.sqrt(9.81 * depth))
    flux = {"gauges": [{"x": 5.54, "still_depth": depth, "H_mean": 0.12}],
            "velocity_verticals": [{"name": "u_gauge8", "x": 5.54, "still_depth": depth,
                                    "flux_above_trough": 0.5 * linear,
                                    "flux_below_trough": -0.4 * linear},
                                   {"name": "u_gauge13", "x": 7.2, "still_depth": 0.08,
                                    "flux_above_trough": 1.0, "flux_below_trough": 0.0}]}
    details = stansby_metrics(flux)[1]
    assert details["crest_flux_return"] == pytest.approx(0.8)
    assert details["crest_flux_over_linear"] == pytest.approx(0.5)
    assert list(details["crest_flux_return_by_gauge"]) == ["8"]


def test_long_flume_scene_and_its_settings() -> None:
    """flume2d-long: gauges every wavelength to 10 L, the damping zone past them, the record
    long enough for the statistics at 10 L; ``--set`` reaches its numerics and nothing else."""
    from watersim import numerics as nm
    from watersim.validation.longflume import long_flume_scene

    case = CASES["flume2d-long"]
    scene, _ = long_flume_scene(case.dp(5.0))
    wl = scene.wavelength
    assert wl is not None and scene.period is not None
    xs = [g.x for g in scene.gauges]
    assert xs == pytest.approx([n * wl for n in range(1, 11)], abs=1e-3)
    assert scene.flume.length == pytest.approx(12.0 * wl, abs=1e-3)
    start = scene.law.ramp_duration + scene.arrival_time(10 * wl) + scene.period
    assert scene.until >= start + 3.0 * scene.period  # the analysis' three periods at 10 L
    assert scene.shifting is None
    shifted, _ = long_flume_scene(case.dp(5.0), {"shifting.coefficient": "4"})
    assert shifted.shifting == nm.Shifting(coefficient=4.0)
    from watersim.validation.sweep import check_settings

    with pytest.raises(ValidateError, match="--set: key 'wave.height'"):
        check_settings([("flume2d-long", 5.0)], ["wave.height=0.2"])
    with pytest.raises(ValidateError, match="--set: tank2d takes no settings"):
        check_settings([("tank2d", 10.0)], ["shifting.model=delta_plus"])
    with pytest.raises(ValidateError, match="viscosity.alpha"):
        check_settings([("flume2d-long", 5.0)], ["viscosity.alpha=-1"])
    assert main(["validate", "tank2d", "--set", "alpha=0.1"]) == 2


def test_solitary_scene_reads_the_wet_front_and_takes_wall_settings() -> None:
    """solitary2d: the run-up gauge reads the wet front; ``--set`` reaches the wall model and
    nothing that would change the wave or the beach."""
    from watersim.validation.cases import solitary_scene
    from watersim.validation.sweep import check_settings

    dp = CASES["solitary2d"].dp(2.0)
    scene, _ = solitary_scene(dp)
    core = scene.to_scene()
    (runup,) = [g for g in core["gauges"] if g["type"] == "runup"]
    assert runup["method"] == "wet_front"
    slip, _ = solitary_scene(dp, {"boundary": "mdbc", "boundary.slip": "free_slip"})
    assert slip.to_scene()["boundary"] == {"model": "mdbc", "slip": "free_slip"}
    assert slip.until == scene.until
    with pytest.raises(ValidateError, match="--set: key 'beach.slope'"):
        check_settings([("solitary2d", 2.0)], ["beach.slope=0.1"])


def test_kimmoun_and_stansby_scenes_take_numerical_settings_only() -> None:
    """kimmoun2d: ``--set`` reaches the numerics (the viscous wall factor, say) and keeps the
    case's own (water's viscosity); the wave, the beach and dp are refused."""
    from watersim import numerics as nm
    from watersim.validation.cases import kimmoun_scene
    from watersim.validation.sweep import check_settings

    dp = CASES["kimmoun2d"].dp(1.2)
    scene, _ = kimmoun_scene(dp)
    free, _ = kimmoun_scene(dp, {"viscosity.wall_factor": "0"})
    assert scene.viscosity == nm.WATER["viscosity"]
    assert free.viscosity == nm.Laminar(wall_factor=0.0)
    assert free.until == scene.until and free.dp == scene.dp
    assert kimmoun_scene(dp, quick=True)[0].until < scene.until
    for item in ("wave.height=0.1", "dp=0.01", "beach.slope=0.1"):
        with pytest.raises(ValidateError, match=f"--set: key '{item.split('=')[0]}'"):
            check_settings([("kimmoun2d", 1.2)], [item])
    # stansby2d the same way (its own numerics, the flume defaults, kept)
    from watersim.validation.cases import stansby_scene

    plain, _ = stansby_scene(CASES["stansby2d"].dp(2.5))
    free, _ = stansby_scene(CASES["stansby2d"].dp(2.5), {"viscosity.wall_factor": "0"})
    assert plain.viscosity is None and free.viscosity == nm.Artificial(wall_factor=0.0)
    assert free.until == plain.until
    with pytest.raises(ValidateError, match="--set: key 'until'"):
        check_settings([("stansby2d", 2.5)], ["until=3"])


def test_seawall2d_case_plumbing() -> None:
    """seawall2d: the gauges stand at Hsiao & Lin's positions less the offset, the seawall's
    crest 0.056 m above the still water, the run long enough for the records; the metrics read
    a simulation that reproduces the records as (nearly) exact and one a tenth too high as
    about a tenth off at its peaks."""
    import warnings

    from watersim.flume import ElevationGauge, OvertoppingGauge
    from watersim.flume_cases import HSIAO_LIN_GAUGES, HSIAO_LIN_OFFSET, flume_builder
    from watersim.validation import seawall as sw

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        scene = flume_builder("seawall2d", {})
    gauges = {g.name: g.x for g in scene.gauges if isinstance(g, ElevationGauge)}
    assert gauges == {n: pytest.approx(x - HSIAO_LIN_OFFSET) for n, x in HSIAO_LIN_GAUGES.items()}
    crest = [g for g in scene.gauges if isinstance(g, OvertoppingGauge)]
    assert [g.x for g in crest] == [pytest.approx(13.948 - HSIAO_LIN_OFFSET)]
    bx, bz = scene.flume.beach.profile_in(scene.flume, scene.tank_height)
    crest_z = np.interp(13.92 - HSIAO_LIN_OFFSET, bx, bz)
    assert crest_z - scene.flume.depth == pytest.approx(0.056)
    beds = {n: float(np.interp(x, bx, bz, left=0.0)) for n, x in gauges.items()}
    assert beds["WG22"] < 0.2 < beds["WG28"]  # wet at rest before the wall, dry on it
    quick, _ = sw.seawall_scene(float(scene.dp), quick=True)
    full, _ = sw.seawall_scene(float(scene.dp))
    assert full.until - quick.until == pytest.approx(12.0 - sw.QUICK_SPAN, abs=2e-3)

    # a simulation sampled every 0.02 s that is the records themselves, crest at WG1 at 3 s
    t = np.arange(0.0, 16.0, 0.02)
    series = {}
    for name in HSIAO_LIN_GAUGES:
        td, vd = sw.seawall_reference(name)
        value = np.interp(t - 3.0, td, vd)
        if name in sw.INUNDATION_GAUGES:  # depth above the ground -> elevation, dry = NaN
            value = np.where(value > 0.0, value + beds[name] - 0.2, np.nan)
        series[name] = value
    errors, details = sw.seawall_metrics(t, series, beds, np.linspace(0.0, 0.01, t.size))
    assert details["t_crest_wg1"] == pytest.approx(3.0, abs=0.02)
    assert errors["gauge_rms"] < 0.03 and errors["peak"] < 0.03
    assert details["overtopped_volume"] == pytest.approx(0.01)
    assert set(details["series"]) == set(HSIAO_LIN_GAUGES)
    high = {n: v * 1.1 if n not in sw.INUNDATION_GAUGES else v for n, v in series.items()}
    errors_high, details_high = sw.seawall_metrics(t, high, beds)
    assert details_high["peak_simulated"]["WG3"] == pytest.approx(
        1.1 * details["peak_simulated"]["WG3"], rel=1e-6)
    assert errors_high["gauge_rms"] > errors["gauge_rms"] + 0.005
    # a gauge that stays dry records the ground (elevation) or no water (inundation)
    dry = np.full(3, np.nan)
    assert list(sw.gauge_series(dry, 0.21, 0.2, True)) == [0.0, 0.0, 0.0]
    assert sw.gauge_series(dry, 0.17, 0.2, False) == pytest.approx([-0.03] * 3)
    assert sw.seawall_metrics(t, {}, beds)[0] == {"gauge_rms": None, "peak": None}


def test_yeh3d_case_plumbing() -> None:
    """yeh3d: the scene holds the column, the water and the sheet as the set-up says; the
    metrics read a simulation that is the records themselves (the velocity put on the bore's
    arrival over the probe) as (nearly) exact, and one with twice the force as 100 % off."""
    from watersim.validation import yeh

    scene = yeh.yeh_scene(0.02, 0.6)
    assert scene.tank == yeh.YEH_TANK
    blocks = [(b.min, b.max) for b in scene.fluid]
    assert blocks[0] == ((0.0, 0.0, 0.0), (0.4, 0.61, 0.3))
    assert blocks[1] == ((0.4, 0.0, 0.0), (1.6, 0.61, 0.02))  # the sheet: one layer
    (column,) = scene.bodies
    assert (column.min, column.max) == yeh.YEH_OBSTACLE and column.name == "column"

    t = np.arange(0.0, 1.5, yeh.SAMPLE)
    tf, ff = yeh.yeh_reference("force")
    tv, uv = yeh.yeh_reference("velocity")
    fx = np.interp(t, tf, ff)
    arrival = 0.2412
    depth = np.clip(0.05 + (t - arrival), 0.03, 0.09)  # the sheet, then the bore
    u = np.interp(t - arrival, tv, uv)
    kernel_sum = np.ones_like(t)
    errors, details = yeh.yeh_metrics(t, fx, t, u, kernel_sum, depth)
    assert details["t_bore_at_probe"] == pytest.approx(arrival, abs=1e-9)
    assert abs(errors["force_peak"]) < 0.02 and abs(errors["force_impulse"]) < 0.01
    # the digitised points scatter: resampling them leaves a few per cent
    assert errors["force_rms"] < 0.06 and errors["velocity_rms"] < 0.06
    double, _ = yeh.yeh_metrics(t, 2.0 * fx, t, u, kernel_sum, depth)
    assert double["force_peak"] == pytest.approx(1.0, abs=0.04)
    assert double["force_impulse"] == pytest.approx(1.0, abs=0.02)
    # a probe the bore never reaches: no velocity error, the force still measured
    never, details = yeh.yeh_metrics(t, fx, t, u, kernel_sum, np.full(t.size, np.nan))
    assert never["velocity_rms"] is None and details["t_bore_at_probe"] is None
    assert never["force_peak"] is not None


def test_cylinder3d_case_plumbing() -> None:
    """cylinder3d: half of the tutorial's tank, the wall y = 0 a plane of symmetry through the
    pile's axis, the gauge and the pile at the tutorial's x less the offset;
    the metrics read a simulation that is the records themselves on another clock as (nearly)
    exact, one with a fifth more force as 20 % off, and one whose force comes a tenth of a
    period late as that much out of phase."""
    import warnings

    from watersim.flume import ElevationGauge, ForceGauge
    from watersim.flume_cases import CHEN_CYLINDER, CHEN_OFFSET, flume_builder
    from watersim.validation import cylinder as cy

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        scene = flume_builder("cylinder3d", {})
    dp = float(scene.dp)
    assert scene.flume.width == pytest.approx(round(1.5 / dp) * dp)
    (pile,) = scene.bodies
    radius = 0.5 * CHEN_CYLINDER["diameter"]
    lo, hi = pile.bounds()
    x_pile = CHEN_CYLINDER["x"] - CHEN_OFFSET
    assert lo == pytest.approx((x_pile - radius, -radius, 0.0))
    assert hi == pytest.approx((x_pile + radius, radius, 0.8))
    assert scene.symmetry_y_min is True
    assert scene.to_scene()["symmetry_y_min"] is True
    (wg5,) = [g for g in scene.gauges if isinstance(g, ElevationGauge)]
    assert (wg5.name, wg5.x) == ("WG5", pytest.approx(CHEN_CYLINDER["gauge_x"] - CHEN_OFFSET))
    (force,) = [g for g in scene.gauges if isinstance(g, ForceGauge)]
    assert force.structure == pile.name == "half_pile"
    quick, _ = cy.cylinder_scene(dp, quick=True)
    assert scene.until - quick.until == pytest.approx(
        (cy.PERIODS_ANALYSED - cy.QUICK_PERIODS) * 1.22, abs=0.06)

    # the records on a clock 7.3 s behind theirs, sampled every 0.03 s
    period = 1.22
    t = np.arange(9.0, 24.0, 0.03)
    tf, ff = cy.chen_reference("force")
    te, ee = cy.chen_reference("elevation")
    fx, eta = np.interp(t + 7.3, tf, ff), np.interp(t + 7.3, te, ee)
    start = 12.2
    errors, details = cy.cylinder_metrics(t, fx, t, eta, start, period)
    assert details["clock_shift"] == pytest.approx(7.3, abs=0.02)
    assert abs(errors["force_amplitude"]) < 0.03 and abs(errors["height_wg5"]) < 0.03
    assert abs(errors["phase"]) < 0.005 and errors["force_rms"] < 0.05
    more, _ = cy.cylinder_metrics(t, 1.2 * fx, t, eta, start, period)
    assert more["force_amplitude"] == pytest.approx(1.2 * (1.0 + errors["force_amplitude"]) - 1.0)
    assert more["force_rms"] > 0.12
    late, details_late = cy.cylinder_metrics(t, np.interp(t + 7.3 - 0.122, tf, ff), t, eta,
                                             start, period)
    assert late["phase"] == pytest.approx(-0.1, abs=0.01)
    assert details_late["phase_error_deg"] == pytest.approx(-36.0, abs=3.0)
    # a run that stopped before the window holds a wave: no errors
    short = t < start + 1.0
    none, _ = cy.cylinder_metrics(t[short], fx[short], t[short], eta[short], start, period)
    assert all(v is None for v in none.values())
