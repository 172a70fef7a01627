"""Pressure gauge: hydrostatic pressure in still water, its CSV columns, its scene-file table,
and bad input refused with the field named (by the Python class and by the core)."""

from __future__ import annotations

import csv
import json
import re
from pathlib import Path

import numpy as np
import pytest

import watersim as ws
from watersim import scenefile

DEPTH = 0.3
DEPTHS_BELOW_SWL = (0.24, 0.18, 0.12)
"""Probe depths [m]: at least 6 dp (several kernel supports) from the floor and the surface."""

STILL = ws.TabulatedMotion(t=(0.0, 1.0), x=(0.0, 0.0))
"""A paddle that never moves: still water."""


def _still_flume(gauges: list[ws.PressureGauge]) -> ws.FlumeScene:
    return ws.Flume(length=0.8, depth=DEPTH).scene(
        STILL, dp=0.02, until=0.3, sample_interval=0.05, gauges=gauges)


def test_still_water_reads_the_hydrostatic_pressure(tmp_path: Path) -> None:
    points = [(0.4, DEPTH - d) for d in DEPTHS_BELOW_SWL]
    sim = _still_flume([ws.PressureGauge(points=points, name="p")]).build()
    sim.run()
    record = sim.gauges.records["p"]
    scene = sim.setup
    expected = scene.core_value("rho0") * scene.g * np.array(DEPTHS_BELOW_SWL)
    pressure = record["pressure"]
    assert pressure.shape == (record["t"].size, len(points)) and record["t"].size >= 6
    np.testing.assert_allclose(record["points"], points)
    assert np.all(record["kernel_sum"] > 0.9)
    print(f"\nmean / hydrostatic: {pressure.mean(axis=0) / expected}")
    np.testing.assert_allclose(pressure, np.broadcast_to(expected, pressure.shape), rtol=0.03)

    columns = sim.gauges.columns()
    assert columns == ["t_s", "p_x0p400_z0p060_Pa", "p_x0p400_z0p120_Pa", "p_x0p400_z0p180_Pa"]
    with open(sim.gauges.to_csv(tmp_path / "gauges.csv"), encoding="utf-8") as f:
        rows = list(csv.reader(f))
    assert rows[0] == columns
    np.testing.assert_allclose([float(v) for v in rows[-1][1:]], pressure[-1])


def test_a_scene_file_pressure_gauge_is_the_class() -> None:
    text = """
type = "flume"
dp = 0.02
until = 0.3

[flume]
length = 0.8
depth = 0.3

[wave]
type = "tabulated"
t = [0.0, 1.0]
x = [0.0, 0.0]

[[gauges]]
type = "pressure"
points = [[0.4, 0.1], [0.5, 0.1]]
interval = 0.1
"""
    builder = scenefile.loads(text).builder
    assert isinstance(builder, ws.FlumeScene)
    assert builder.gauges == (ws.PressureGauge(points=((0.4, 0.1), (0.5, 0.1)), interval=0.1),)
    (spec,) = builder.to_scene()["gauges"]
    assert spec == {"type": "pressure", "name": "pressure0",
                    "points": [[0.4, 0.1], [0.5, 0.1]], "interval": 0.1}


@pytest.mark.parametrize(("gauge", "field"), [
    (lambda: ws.PressureGauge(points=()), "gauge.points"),
    (lambda: ws.PressureGauge(points=((0.4, float("nan")),)), "gauge.points[0]"),
    (lambda: ws.PressureGauge(points=((0.4, 0.1),), interval=0.0), "gauge.interval"),
])
def test_bad_pressure_gauges_name_the_field(gauge: object, field: str) -> None:
    with pytest.raises(ws.SceneError, match=rf"^{re.escape(field)}: "):
        gauge()  # type: ignore[operator]


def test_a_pressure_point_outside_the_flume_is_refused_by_the_scene_and_the_core() -> None:
    outside = [ws.PressureGauge(points=((0.4, 0.1), (0.4, 5.0)))]
    with pytest.raises(ws.SceneError, match=r"^gauges\[0\]\.points\[1\]: z = 5"):
        _still_flume(outside)
    scene = _still_flume([ws.PressureGauge(points=((0.4, 0.1),))]).to_scene()
    scene["gauges"][0]["points"].append([0.4, 5.0])
    with pytest.raises(ws.SceneError, match=r"^gauges\[0\]\.points\[1\]"):
        ws.Simulation(json.dumps(scene))
    scene["gauges"][0]["points"] = []
    with pytest.raises(ws.SceneError, match=r"^gauges\[0\]\.points: needs at least one point"):
        ws.Simulation(json.dumps(scene))
