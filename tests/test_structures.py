"""Structures in the flume and the force gauge on them: a submerged box in still water feels its
buoyancy, the records reach the CSV, ``watersim.load`` and the analysis, a scene file builds the
same core scene as Python, and bad structures are refused with the field named."""

from __future__ import annotations

import csv
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

import watersim as ws
from watersim import _core, scenefile
from watersim.analysis import load_statistics
from watersim.flume.gauges import ForceGauge

DEPTH = 0.4
BOX = ((0.3, 0.12), (0.5, 0.24))
"""A box 10 x 6 dp at dp = 0.02, 8 dp under the surface and 6 dp over the floor: no kernel
support reaches from it to the floor or the surface."""

STILL = ws.TabulatedMotion(t=(0.0, 1.0), x=(0.0, 0.0))
"""A paddle that never moves: still water."""


def _still_flume(**kwargs: object) -> ws.FlumeScene:
    args: dict[str, object] = {
        "bodies": [ws.BoxStructure("block", *BOX)],
        "gauges": [ws.ForceGauge(structure="block", point=(0.4, 0.18), interval=0.01)],
    }
    args.update(kwargs)
    return ws.Flume(length=0.8, depth=DEPTH).scene(
        STILL, dp=0.02, until=0.1, sample_interval=0.01, **args)


def test_a_submerged_box_in_still_water_feels_its_buoyancy(tmp_path: Path) -> None:
    sim = _still_flume().build()
    sim.run()
    record = sim.gauges.records["block"]
    t, force, moment = record["t"], record["force"], record["moment"]
    assert force.shape == (t.size, 2) and t.size >= 8
    (lo_x, lo_z), (hi_x, hi_z) = BOX
    scene = sim.setup
    buoyancy = scene.core_value("rho0") * scene.g * (hi_x - lo_x) * (hi_z - lo_z)
    settled = t >= 0.02
    fx, fz = force[settled, 0].mean(), force[settled, 1].mean()
    print(f"\nFz / rho g V = {fz / buoyancy:.4f}, Fx = {fx:.3g} N/m, "
          f"My = {moment[settled].mean():.3g} N m/m")
    assert abs(fz / buoyancy - 1.0) < 0.02
    assert abs(fx) < 0.01 * buoyancy

    columns = sim.gauges.columns()
    assert columns == ["t_s", "block_Fx_N_per_m", "block_Fz_N_per_m", "block_My_N_m_per_m"]
    with open(sim.gauges.to_csv(tmp_path / "gauges.csv"), encoding="utf-8") as f:
        rows = list(csv.reader(f))
    assert rows[0] == columns
    np.testing.assert_allclose([float(v) for v in rows[-1][1:3]], force[-1])

    data, coords = ForceGauge.dataset_variables(sim.gauges)
    assert data["force_block"][2]["units"] == "N/m"
    np.testing.assert_array_equal(data["force_block"][1], force)
    assert coords["time_block"][1].shape == t.shape

    analysis = ws.analyse_flume(scene, sim.gauges)
    (entry,) = analysis["forces"]
    assert entry["name"] == "block" and entry["structure"] == "block"
    assert entry["Fz_max"] >= entry["Fz_mean"] >= entry["Fz_min"]
    json.dumps(analysis)


def test_load_statistics_of_a_sine() -> None:
    """Fx = m + A sin(2 pi t / T): every wave's maximum is m + A, the largest event's impulse
    the integral of A sin over half a period, A T / pi."""
    period, amplitude, mean = 2.0, 3.0, 1.5
    t = np.linspace(0.0, 10.0 * period, 20001)
    fx = mean + amplitude * np.sin(2.0 * math.pi * t / period)
    stats = load_statistics(t, fx, np.full_like(t, -4.0))
    assert stats["Fx_significant"] == pytest.approx(mean + amplitude, rel=1e-6)
    assert stats["impulse"] == pytest.approx(amplitude * period / math.pi, rel=1e-4)
    assert stats["Fx_mean"] == pytest.approx(mean, abs=1e-3)
    assert stats["Fz_max"] == stats["Fz_min"] == -4.0
    assert stats["n_waves"] in (9, 10)


SCENE_FILE = """
type = "flume"
dp = 0.02
until = 0.1
sample_interval = 0.01

[flume]
length = 0.8
depth = 0.4

[wave]
type = "tabulated"
t = [0.0, 1.0]
x = [0.0, 0.0]

[[bodies]]
type = "box"
name = "block"
min = [0.3, 0.12]
max = [0.5, 0.24]

[[bodies]]
type = "profile_structure"
name = "seawall"
x = [0.6, 0.7, 0.75]
z = [0.0, 0.5, 0.5]

[[gauges]]
type = "force"
structure = "block"
point = [0.4, 0.18]
interval = 0.01

[[gauges]]
type = "force"
structure = "seawall"
point = [0.7, 0.0]
"""


def test_a_scene_file_builds_the_same_core_scene_as_python() -> None:
    builder = scenefile.loads(SCENE_FILE).builder
    python = _still_flume(
        bodies=[ws.BoxStructure("block", *BOX),
                    ws.ProfileStructure("seawall", x=(0.6, 0.7, 0.75), z=(0.0, 0.5, 0.5))],
        gauges=[ws.ForceGauge(structure="block", point=(0.4, 0.18), interval=0.01),
                ws.ForceGauge(structure="seawall", point=(0.7, 0.0))])
    assert builder == python
    from_file = _core.resolve_scene(json.dumps(builder.to_scene()))
    from_python = _core.resolve_scene(json.dumps(python.to_scene()))
    assert from_file == from_python
    scene = json.loads(from_file)
    assert [o["shape"] for o in scene["obstacles"]] == ["box", "profile"]
    assert [g["obstacle"] for g in scene["gauges"]] == [0, 1]


def test_the_obstacle_index_counts_the_beach() -> None:
    flume = ws.Flume(length=3.0, depth=0.3, beach=ws.PlaneBeach(toe=2.0, slope=0.1))
    scene = flume.scene(STILL, dp=0.02, bodies=[ws.BoxStructure("b", (1.0, 0.0),
                                                                    (1.2, 0.4))],
                        gauges=[ws.ForceGauge(structure="b", point=(1.0, 0.0))])
    core = scene.to_scene()
    assert [o["shape"] for o in core["obstacles"]] == ["profile", "box"]
    assert core["gauges"][0]["obstacle"] == 1


@pytest.mark.parametrize(("kwargs", "field"), [
    ({"bodies": [ws.BoxStructure("b", (0.6, 0.1), (0.9, 0.2))]}, r"bodies\[0\]\.max"),
    ({"bodies": [ws.BoxStructure("b", (0.3, -0.1), (0.5, 0.2))]}, r"bodies\[0\]\.min"),
    ({"bodies": [ws.BoxStructure("b", (0.01, 0.1), (0.2, 0.2))]}, r"bodies\[0\]\.min"),
    ({"bodies": [ws.BoxStructure("b", (0.3, 0.1), (0.5, 0.13))]},
     r"bodies\[0\]\.max\[1\]"),
    ({"bodies": [ws.BoxStructure("b", (0.3, 0.1, 0.1), (0.5, 0.2, 0.2))]},
     r"bodies\[0\]\.min"),
    ({"bodies": [ws.ProfileStructure("w", (0.5, 0.52), (0.0, 0.3))]}, r"bodies\[0\]\.x"),
    ({"bodies": [ws.BoxStructure("b", *BOX), ws.BoxStructure("b", (0.6, 0.1), (0.7, 0.2))]},
     r"bodies\[1\]\.name"),
    ({"gauges": [ws.ForceGauge(structure="pile", point=(0.4, 0.1))]},
     r"gauges\[0\]\.structure"),
    ({"gauges": [ws.ForceGauge(structure="block", point=(0.4, 0.1, 0.1))]},
     r"gauges\[0\]\.point"),
])
def test_bad_structures_are_refused_naming_the_field(kwargs: dict[str, object],
                                                     field: str) -> None:
    with pytest.raises(ws.SceneError, match=rf"^{field}: "):
        _still_flume(**kwargs)


@pytest.mark.parametrize(("make", "field"), [
    (lambda: ws.BoxStructure("b", (0.3, 0.1), (0.2, 0.2)), "body.max"),
    (lambda: ws.BoxStructure("", (0.3, 0.1), (0.4, 0.2)), "body.name"),
    (lambda: ws.ProfileStructure("w", (0.5, 0.4), (0.0, 0.3)), "body.x"),
    (lambda: ws.ProfileStructure("w", (0.4, 0.5), (0.0, -0.3)), "body.z"),
    (lambda: ws.ForceGauge(structure="b", point=(0.4,)), "gauge.point"),
])
def test_bad_models_name_the_field(make: object, field: str) -> None:
    with pytest.raises(ws.SceneError, match=rf"^{re.escape(field)}: "):
        make()  # type: ignore[operator]


def test_an_overtopping_gauge_counts_the_water_past_its_section(tmp_path: Path) -> None:
    """A solitary wave over a low seawall: the gauge behind the crest records the volume of the
    particles that end past it (the core tracks each particle's side)."""
    flume = ws.Flume(length=3.0, depth=0.2, height=0.5)
    scene = flume.scene(
        ws.SolitaryWave(height=0.1), dp=0.02, until=2.5,
        bodies=[ws.ProfileStructure("wall", x=(2.0, 2.2, 2.3), z=(0.0, 0.22, 0.22))],
        gauges=[ws.OvertoppingGauge(x=2.3, name="q", interval=0.02)])
    sim = scene.build()

    def past() -> int:  # fluid particles (excluded ones too) past the section
        fluid = np.isin(sim.kinds, (0, 3))
        return int(np.count_nonzero(fluid & (sim.positions[:, 0] > 2.3)))

    behind_at_rest = past()
    sim.run()
    record = sim.gauges.records["q"]
    volume, discharge = record["volume"], record["discharge"]
    print(f"\ncrossed {volume[-1]:.5f} m^2/m, peak discharge {discharge.max():.4f} m^2/s")
    assert volume[-1] == pytest.approx((past() - behind_at_rest) * 0.02**2, abs=1e-12)
    assert volume[-1] > 0.0
    assert sim.gauges.columns()[-2:] == ["q_volume_m3_per_m", "q_discharge_m3_per_s_per_m"]
    analysis = ws.analyse_flume(scene, sim.gauges)
    (entry,) = analysis["overtopping"]
    assert entry["total"] == pytest.approx(volume[-1]) and entry["x"] == 2.3


def test_a_flume_is_a_preset_of_the_general_scene() -> None:
    """A flume takes what any scene takes: bodies, gauges and more water. A basin behind a
    seawall, filled above the still water and below the crest, stands at rest; the gauge over
    it reads its level above the SWL (its reading is not zeroed away); the core holds the
    flume's still water and the basin as two fluid boxes. The flume makes its own tank."""
    wall = ws.ProfileStructure("wall", x=(0.8, 0.84, 0.9, 0.94), z=(0.0, 0.3, 0.3, 0.0))
    basin = ws.FluidBlock((0.88, 0.0), (1.4, 0.26))  # up to the wall's sloping back face
    flume = ws.Flume(length=1.4, depth=0.2, height=0.4)
    scene = flume.scene(STILL, dp=0.02, until=0.3, sample_interval=0.05, bodies=[wall],
                        fluid=[basin], gauges=[ws.ElevationGauge(0.4, name="sea"),
                                               ws.ElevationGauge(1.2, name="basin")])
    assert isinstance(scene, ws.Scene)
    assert scene.to_scene()["fluid"] == [{"min": [0.0, 0.0], "max": [1.4, 0.2]},
                                         {"min": [0.88, 0.0], "max": [1.4, 0.26]}]
    sim = scene.build()
    behind = sim.fluid_positions()[:, 0] > 0.9
    # the basin: 0.46 x 0.26 m behind the wall and 0.0045 m^2 under its back face
    assert np.count_nonzero(behind) * 0.02**2 == pytest.approx(0.1241, rel=0.03)
    sim.run()
    gauges = sim.gauges
    sea, level = gauges.elevation[:, 0], gauges.elevation[:, 1]
    assert np.max(np.abs(sea)) < 0.005  # the sea stays at the SWL
    assert np.allclose(level, 0.06, atol=0.012)  # the basin 6 cm above it
    assert np.max(np.abs(sim.fluid_velocities()[behind])) < 0.05
    with pytest.raises(ws.SceneError, match=r"^tank: a flume makes its own tank"):
        flume.scene(STILL, dp=0.02, tank=(1.4, 0.4))
    with pytest.raises(ws.SceneError, match=r"^fluid\[0\]\.max: the water spans"):
        flume.scene(STILL, dp=0.02, fluid=[ws.FluidBlock((1.0, 0.0), (1.6, 0.26))])
    with pytest.raises(ws.SceneError, match=r"^fluid\[0\]"):
        flume.scene(STILL, dp=0.02, fluid=[ws.FillTo(0.3)])
