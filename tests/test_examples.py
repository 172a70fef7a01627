"""The flume examples (examples/kimmoun_flume.py, examples/stansby_flume.py) keep working: each
makes every one of its figures, from a synthetic gauge record with waves that shoal and break
(through the real analysis, :func:`watersim.flume.analyse_flume`), and the Kimmoun script runs
end to end (a very short, very coarse run, then ``--replot``)."""

from __future__ import annotations

import importlib.util
import json
import math
import sys
import warnings
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest

import watersim as ws
from watersim import wave_theory as wt
from watersim.flume import FlumeGauges, analyse_flume, lattice_dp

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _load(name: str) -> ModuleType:
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / f"{name}.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


def _synthetic_records(scene: ws.FlumeScene, height: float, period: float) -> list[dict[str, Any]]:
    """Core-like gauge records: a regular wave arriving after the ramp, shoaling by Green's law
    and limited to 0.85 d (so it 'breaks', H/d > 0.78, near the shoreline), dry above the beach;
    run-up and probe velocities in phase with it."""
    depth = scene.flume.depth
    t = np.arange(0.0, float(scene.until), float(scene.sample_interval))
    w = 2.0 * math.pi / period
    k = float(wt.wavenumber(period, depth))
    ramp = np.clip(t / (2.0 * period), 0.0, 1.0)
    records: list[dict[str, Any]] = []
    for spec in scene._gauge_specs():
        if spec["type"] == "elevation":
            x = spec["position"][0]
            d = float(scene.still_depth(x))
            if d <= 0.0:
                z = np.full(t.shape, np.nan)
            else:
                h = min(height * (depth / d) ** 0.25, 0.85 * d)
                z = depth + 0.5 * h * ramp * np.cos(w * t - k * x)
            records.append({"type": "elevation", "name": spec["name"], "t": t, "z": z})
        elif spec["type"] == "runup":
            z = depth + 0.01 * ramp * np.cos(w * t)
            records.append({"type": "runup", "name": spec["name"], "t": t, "z": z})
        elif spec["type"] == "velocity":
            pts = np.asarray(spec["points"], dtype=float)
            phase = np.cos(w * t[:, None] - k * pts[None, :, 0])
            vel = np.zeros((t.size, len(pts), 2))
            vel[:, :, 0] = 0.3 * ramp[:, None] * phase
            ksum = (pts[None, :, 1] <= depth + 0.03 * phase).astype(float)
            records.append({"type": "velocity", "name": spec["name"], "t": t,
                            "points": pts, "velocity": vel, "kernel_sum": ksum})
    return records


@pytest.mark.parametrize("name", ["kimmoun_flume", "stansby_flume"])
def test_example_figures_from_a_synthetic_record(name: str, tmp_path: Path) -> None:
    mod = _load(name)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", wt.WaveValidityWarning)
        flume, kwargs = mod.make(lattice_dp(mod.DEPTH, 0.05), 30.0)  # whole layers
        scene = flume.scene(**kwargs)
    gauges = FlumeGauges(scene, _synthetic_records(scene, mod.HEIGHT, mod.PERIOD))
    analysis = analyse_flume(scene, gauges)
    # the figures get data to draw: a breaking point, run-up per wave, whole steady waves
    assert analysis["breaking"]["position"] is not None
    assert len(analysis["runup"]["values"]) >= 5
    records = mod.Records.from_gauges(gauges)
    written = mod.figures(scene, records, analysis, tmp_path)
    assert len(written) == (5 if name == "kimmoun_flume" else 2)
    for path in written:
        assert path.parent == tmp_path and path.suffix == ".png"
        assert path.stat().st_size > 10_000, f"{path.name} looks empty"
    # the records round-trip through records.npz
    again = mod.Records.load(records.save(tmp_path / "records.npz"))
    np.testing.assert_array_equal(again.eta, records.eta)
    assert again.names == records.names and set(again.probes) == set(records.probes)


def test_kimmoun_script_runs_end_to_end_and_replots(tmp_path: Path) -> None:
    """A one-period run at dp = 0.141 m (0.705 / 5): every figure is written even
    though no wave reaches the beach (they say so), and ``--replot`` redraws them."""
    mod = _load("kimmoun_flume")
    out = tmp_path / "run"
    written = mod.main(["--dp", "0.141", "--periods", "1.0", "--out", str(out)])
    names = {p.name for p in written}
    assert names == {"fig4_toe.png", "fig5_breaking_gauges.png", "fig8_envelopes.png",
                     "fig9_runup.png", "fig10_phase_averages.png"}
    for f in ("gauges.csv", "analysis.json", "records.npz", "summary.json", *names):
        assert (out / f).is_file(), f
    for p in written:
        p.unlink()
    again = mod.main(["--dp", "0.141", "--periods", "1.0", "--out", str(out), "--replot"])
    assert all(p.is_file() for p in again) and len(again) == 5


def test_kimmoun_script_draws_a_watersim_run_folder(tmp_path: Path) -> None:
    """``--from-run``: the built-in kimmoun2d run by ``watersim run`` (a very coarse, one-period
    run here) is reopened from its last checkpoint, analysed from ``--t-start`` and drawn."""
    from watersim.cli import main as cli_main

    run = tmp_path / "builtin"
    assert cli_main(["run", "kimmoun2d", "--set", "dp=0.141", "--set", "until=1.3",
                     "--out", str(run), "--no-progress", "--quiet"]) == 0
    mod = _load("kimmoun_flume")
    out = tmp_path / "figures"
    written = mod.main(["--from-run", str(run), "--t-start", "0.5", "--out", str(out)])
    assert len(written) == 5 and all(p.is_file() for p in written)
    analysis = json.loads((out / "analysis.json").read_text())
    assert all(g["window"][0] == 0.5 for g in analysis["gauges"])
    with pytest.raises(SystemExit) as exc:
        mod.main(["--from-run", str(tmp_path / "missing"), "--out", str(out)])
    assert "--from-run" in str(exc.value)
    with pytest.raises(SystemExit) as exc:
        mod.main(["--t-start", "3", "--out", str(out)])
    assert exc.value.code == 2


def test_bad_options_are_refused(capsys: pytest.CaptureFixture[str]) -> None:
    mod = _load("stansby_flume")
    with pytest.raises(SystemExit) as exc:
        mod.main(["--dp", "-1"])
    assert exc.value.code == 2
    assert "--dp" in capsys.readouterr().err
    # a dp that does not divide the depth (0.34 m is 11.3 dp of 0.03 m) is refused with two
    with pytest.raises(SystemExit) as exc:
        mod.main(["--dp", "0.03"])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "--dp: the depth 0.34 m is 11.33 dp" in err and "0.030909091 (11 layers)" in err
