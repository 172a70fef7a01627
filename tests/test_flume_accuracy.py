"""Issue 3's flume measurements: the mean-water-level drift and local second-harmonic spread
metrics on synthetic records with known answers, and examples/flume_accuracy.py on synthetic
run records (tables and both figures; no simulation)."""

from __future__ import annotations

import importlib.util
import json
import math
import sys
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest

from watersim import wave_theory as wt
from watersim.numerics import Artificial, Verlet
from watersim.validation import CASES, metrics

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _example() -> ModuleType:
    spec = importlib.util.spec_from_file_location("flume_accuracy",
                                                  EXAMPLES / "flume_accuracy.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["flume_accuracy"] = module
    spec.loader.exec_module(module)
    return module


def test_mean_level_drift_of_a_wave_on_a_rising_level() -> None:
    period, dt = 1.2, 1.2 / 40
    t = 5.0 + dt * np.arange(40 * 6)
    eta = 0.05 * np.cos(2 * math.pi * t / period) + 1e-3 * (t - t[0])  # 1 mm/s rise
    slope, change = metrics.mean_level_drift(eta, t, period)
    assert slope == pytest.approx(1e-3, rel=1e-6)
    assert change == pytest.approx(1e-3 * 6 * period, rel=1e-6)
    level, none = metrics.mean_level_drift(0.05 * np.cos(2 * math.pi * t / period), t, period)
    assert abs(level) < 1e-12 and abs(none) < 1e-12
    with pytest.raises(ValueError, match="fewer than 2 periods"):
        metrics.mean_level_drift(eta[:50], t[:50], period)


def test_local_spread_ignores_decay_but_sees_a_free_harmonic() -> None:
    k, depth = 2 * math.pi / 1.83, 0.2
    x = np.linspace(0.9, 4.6, 9)
    a1 = 0.0225 * 0.95 ** (x / 1.83)  # 5 % height lost per wavelength
    bound = np.asarray(wt.stokes2_second_harmonic_amplitude(2 * a1, k, depth))
    assert metrics.harmonic_spread_local_bound(a1, bound, k, depth) == pytest.approx(0.0,
                                                                                     abs=1e-12)
    assert metrics.harmonic_spread(bound, float(bound[0])) > 0.1  # the raw spread counts decay
    beat = 1.0 + 0.4 * np.cos(2 * math.pi * x / 3.4)  # a free harmonic beating with the bound
    assert metrics.harmonic_spread_local_bound(a1, bound * beat, k, depth) == pytest.approx(
        (beat.max() - beat.min()) / beat.mean())
    with pytest.raises(ValueError, match="at least 2"):
        metrics.harmonic_spread_local_bound([0.01], [0.001], k, depth)


def test_case_targets_follow_the_issue() -> None:
    flume, second = CASES["flume2d"], CASES["secondorder2d"]
    assert flume.dp(10.0) == pytest.approx(0.01) and flume.target == 0.05
    assert second.primary == "local_spread_ratio" and second.target == 0.5


def _records() -> list[dict[str, Any]]:
    wl, target = 1.77, 0.1
    xs = [1.0, 1.5, 1.6, 1.75, 2.0, 3.0]
    gauges = [{"name": f"g{i}", "x": n * wl, "H_mean": target * (1 - 0.01 * n)}
              for i, n in enumerate(xs)]
    flume = {"case": "flume2d", "resolution": 10.0, "dp": 0.01, "status": "ok",
             "n_particles": 30000, "steps": 47000, "wall_s": 1500.0, "cpu_s": 1400.0,
             "errors": {}, "details": {
                 "H_target": target, "wavelength_linear": wl, "gauges": gauges,
                 "H_1L": 0.099, "H_2L": 0.098, "H_3L": 0.097,
                 "height_loss_per_wavelength": 0.01, "wavelength_measured": wl * 1.02,
                 "wavelength_stokes3": wl * 1.042,
                 "mwl": {"g0": {"mean": 1e-3, "change": -2e-4}}}}
    k, depth = 2 * math.pi / 1.83, 0.2
    a1 = [0.0225] * 3
    b = float(wt.stokes2_second_harmonic_amplitude(0.045, k, depth))
    second = {"case": "secondorder2d", "resolution": 3.0, "dp": 0.015, "status": "ok",
              "n_particles": 7000, "steps": 50000, "wall_s": 600.0, "cpu_s": 500.0,
              "errors": {"a2_local_spread_order1": 0.6, "a2_local_spread_order2": 0.2,
                         "local_spread_ratio": 1 / 3},
              "details": {"wavelength": 1.83, "wave": {"depth": depth},
                          **{f"x_order{o}": [1.0, 2.0, 3.0] for o in (1, 2)},
                          **{f"a1_order{o}": a1 for o in (1, 2)},
                          "a2_order1": [b * 0.7, b * 1.3, b], "a2_order2": [b, b * 1.1, b]}}
    return [flume, second]


def test_flume_accuracy_example_writes_tables_and_figures(tmp_path: Path) -> None:
    mod = _example()
    runs = tmp_path / "runs.json"
    runs.write_text(json.dumps(_records()))
    assert mod.main([str(runs), "--out", str(tmp_path / "out")]) == 0
    table = (tmp_path / "out" / "results.md").read_text()
    assert "| 10 | 0.01 | 30,000 |" in table and "-1.0 %" in table and "-3.0 %" in table
    assert "+2.0 %" in table  # wavelength against linear
    assert "0.333" in table  # the spread ratio
    assert (tmp_path / "out" / "flume2d_height.png").stat().st_size > 1000
    assert (tmp_path / "out" / "secondorder2d.png").stat().st_size > 1000
    data = json.loads((tmp_path / "out" / "results.json").read_text())
    assert data["flume2d"][0]["H_3L"] == pytest.approx(-0.03)
    assert mod.main([str(tmp_path / "missing.json"), "--out", str(tmp_path / "x")]) == 2


def test_secondorder_wave_is_the_documented_one() -> None:
    """SECOND_ORDER_WAVE's docstring: kd 0.69, Madsen 2.0 mm on a 66 mm stroke, bound harmonic
    5.4 mm below H/8, beat length 1.86 L; flume2d's H = 0.1 m wave is 4.2 % longer by Stokes 3."""
    from watersim.validation.cases import FLUME2D_HEIGHT, SECOND_ORDER_WAVE, secondorder_scene

    first, second = secondorder_scene(0.025, 1), secondorder_scene(0.025, 2)  # 8 layers
    assert first.law.second_order_amplitude == 0.0
    assert second.law.second_order_amplitude == pytest.approx(0.0020, abs=5e-5)
    assert second.law.stroke == pytest.approx(0.066, abs=5e-4)
    d, period, h = (SECOND_ORDER_WAVE[k] for k in ("depth", "period", "height"))
    k = float(wt.wavenumber(period, d))
    assert k * d == pytest.approx(0.69, abs=0.005)
    bound = float(wt.stokes2_second_harmonic_amplitude(h, k, d))
    assert bound == pytest.approx(0.0054, abs=5e-5) and bound < h / 8
    k2 = float(wt.wavenumber_from_omega(4 * math.pi / period, d))
    assert 2 * math.pi / (k2 - 2 * k) * k / (2 * math.pi) == pytest.approx(1.86, abs=0.005)
    assert metrics.stokes3_wavelength(1.2, 0.3, FLUME2D_HEIGHT) / float(
        wt.wavelength(1.2, 0.3)) == pytest.approx(1.042, abs=0.0005)


def test_numerics_study_table_and_bad_input(capsys: pytest.CaptureFixture[str]) -> None:
    spec = importlib.util.spec_from_file_location("flume_numerics_study",
                                                  EXAMPLES / "flume_numerics_study.py")
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    committed = EXAMPLES.parent / "docs" / "wave-flume" / "numerics-study.json"
    assert mod.main(["--table", "--json", str(committed)]) == 0
    out = capsys.readouterr().out
    assert "| base | flume defaults |" in out and "| alpha0 | alpha 0 |" in out
    assert mod.main(["nonsense"]) == 2 and "unknown variant" in capsys.readouterr().err
    assert mod.main(["--table"]) == 2
    scene, wl = mod.scene(**mod.VARIANTS["verlet_alpha0.003"])
    assert scene.integrator == Verlet() and scene.viscosity == Artificial(alpha=0.003)
    assert scene.flume.length == pytest.approx(3.25 * wl, abs=1e-3)
