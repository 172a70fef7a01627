"""The wave-flume builder: refusal of bad input, the scene JSON it produces, the paddle laws,
and the gauge records and analysis on synthetic data (no long runs here)."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import watersim as ws
from watersim import SceneError
from watersim import analysis as an
from watersim import wave_theory as wt
from watersim.flume import FlumeGauges, analyse_flume, flap_height_to_stroke_hinged

D, T, H = 0.3, 1.2, 0.04


def flat(**kw: Any) -> ws.Flume:
    return ws.Flume(**{"length": 4.0, "depth": D, **kw})


def regular(**kw: Any) -> ws.RegularWave:
    return ws.RegularWave(**{"height": H, "period": T, **kw})


def scene(flume: ws.Flume | None = None, wave: Any = None, **kw: Any) -> ws.FlumeScene:
    return (flume or flat()).scene(wave or regular(), **{"dp": 0.02, **kw})


# ------------------------------------------------------------------------------------------------
# refusal of bad input


@pytest.mark.parametrize(
    ("make", "field"),
    [
        (lambda: ws.Flume(length=4.0, depth=-0.3), "depth"),
        (lambda: ws.Flume(length=0.0, depth=0.3), "length"),
        (lambda: ws.Flume(length=4.0, depth=math.nan), "depth"),
        (lambda: ws.Flume(length=4.0, depth=0.3, width=-0.1), "width"),
        (lambda: ws.Flume(length=4.0, depth=0.3, height=0.2), "height"),
        (lambda: ws.Flume(length=17.0, depth=0.7, beach=ws.PlaneBeach(toe=20.0, slope=1 / 15)),
         "beach.toe"),
        (lambda: ws.PlaneBeach(toe=-1.0, slope=0.1), "beach.toe"),
        (lambda: ws.PlaneBeach(toe=4.0, slope=0.0), "beach.slope"),
        (lambda: ws.ProfileBeach(x=(1.0, 1.0), z=(0.0, 0.1)), "beach.x"),
        (lambda: ws.ProfileBeach(x=(1.0, 2.0), z=(0.0, -0.1)), "beach.z"),
        (lambda: ws.ProfileBeach(x=(1.0, 2.0, 3.0), z=(0.0, 0.1)), "beach.z"),
        (lambda: ws.Flume(length=4.0, depth=0.3, beach=ws.ProfileBeach(x=(1.0, 5.0),
                                                                       z=(0.0, 0.2))), "beach.x"),
        (lambda: ws.Flume(length=4.0, depth=0.3, damping=ws.DampingZone(length=5.0)),
         "damping.length"),
        (lambda: ws.DampingZone(strength=-1.0), "damping.strength"),
        (lambda: ws.RegularWave(height=-0.1, period=1.0), "wave.height"),
        (lambda: ws.RegularWave(height=0.1, period=math.nan), "wave.period"),
        (lambda: ws.IrregularWave(hs=0.1, tp=1.0, spectrum="foo"), "wave.spectrum"),
        (lambda: ws.IrregularWave(hs=0.1, tp=1.0, gamma=0.5), "wave.gamma"),
        (lambda: ws.SolitaryWave(height=0.0), "wave.height"),
        (lambda: ws.TabulatedMotion(t=(0.0, 1.0, 0.5), x=(0.0, 0.1, 0.0)), "wave.t"),
        (lambda: ws.TabulatedMotion(t=(0.0, 1.0), x=(0.0,)), "wave.x"),
        (lambda: ws.Piston(order=3), "paddle.order"),
        (lambda: ws.Piston(ramp="cosine"), "paddle.ramp"),
        (lambda: ws.Piston(ramp_periods=-1.0), "paddle.ramp_periods"),
        (lambda: ws.ElevationGauge(x=math.inf), "gauge.x"),
        (lambda: ws.ElevationGauge(x=1.0, method="sonar"), "gauge.method"),
        (lambda: ws.VelocityWindow(min=(1.0, 0.0), max=(0.5, 0.2), n=(3, 3)), "gauge.max"),
        (lambda: ws.RunupGauge(start=(1.0, 0.1)), "runup.end"),
    ],
)
def test_bad_objects_are_refused_naming_the_field(make: Any, field: str) -> None:
    with pytest.raises(SceneError, match=rf"^{field.replace('.', '[.]')}\b"):
        make()


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"gauges": [ws.ElevationGauge(20.0)]}, "gauges[0].x"),
        ({"gauges": [ws.ElevationGauge(1.0), ws.ElevationGauge(-0.5)]}, "gauges[1].x"),
        ({"gauges": [ws.ElevationGauge(1.0, y=0.05)]}, "gauges[0].y"),
        ({"gauges": [ws.VelocityProbe(points=[(1.0, 0.1), (1.0, 2.0)])]}, "gauges[0].points[1]"),
        ({"gauges": [ws.VelocityProbe(points=[(1.0, 0.0, 0.1)])]}, "gauges[0].points[0]"),
        ({"gauges": [ws.VelocityWindow(min=(1.0, 0.0), max=(9.0, 0.2), n=(3, 3))]},
         "gauges[0].max"),
        ({"gauges": [ws.ElevationGauge(1.0, name="a"), ws.ElevationGauge(2.0, name="a")]},
         "gauges[1].name"),
        ({"runup": True}, "runup"),
        ({"dp": 0.2}, "dp"),
        ({"dp": -0.02}, "dp"),
        ({"dim": 3}, "dim"),
        ({"kernel": "gaussian"}, "kernel"),
        ({"cfl": 2.0}, "cfl"),
        ({"until": 0.0}, "until"),
        ({"sample_interval": -1.0}, "sample_interval"),
        ({"paddle": ws.Flap(hinge_z=0.5)}, "paddle.hinge_z"),
        ({"paddle": "piston"}, "paddle"),
        # a 0.05 s wave is 3.9 mm long: fewer than 4 dp of 0.02 m
        ({"wave": ws.RegularWave(height=0.001, period=0.05)}, "wave.period"),
    ],
)
def test_bad_scenes_are_refused_naming_the_field(kwargs: dict[str, Any], field: str) -> None:
    with pytest.raises(SceneError) as info:
        scene(**kwargs)
    assert str(info.value).startswith(field + ":"), str(info.value)


def test_generation_combinations_the_theory_does_not_cover_are_refused() -> None:
    with pytest.raises(SceneError, match="^paddle.order"):
        scene(wave=ws.IrregularWave(hs=0.04, tp=1.2), paddle=ws.Flap(order=2))
    with pytest.raises(SceneError, match="^paddle.order"):
        scene(wave=ws.SolitaryWave(height=0.05), paddle=ws.Piston(order=2))
    with pytest.raises(SceneError, match="^paddle"):
        scene(wave=ws.SolitaryWave(height=0.05), paddle=ws.Flap())
    with pytest.raises(SceneError, match="^beach"):
        scene(flume=flat(beach=ws.PlaneBeach(toe=0.01, slope=0.1)))


def test_gauge_outside_the_3d_width_is_refused() -> None:
    with pytest.raises(SceneError, match=r"^gauges\[0\]\.y"):
        scene(flume=flat(width=0.1), gauges=[ws.ElevationGauge(1.0, y=0.2)], dp=0.025)


def test_wave_breaking_at_the_paddle_is_a_warning_not_an_error() -> None:
    with pytest.warns(wt.WaveValidityWarning) as record:
        built = scene(wave=regular(height=0.27, theory="linear"))
    messages = [str(w.message) for w in record]
    assert any("breaks at the paddle" in m for m in messages), messages
    assert built.to_scene()["paddle"]["law"]["components"][0][0] > 0


def test_wave_beyond_second_order_warns() -> None:
    with pytest.warns(wt.WaveValidityWarning) as record:
        ws.Flume(length=11.0, depth=0.34).scene(
            ws.RegularWave(height=0.105, period=2.42, theory="stokes2"),
            paddle=ws.Piston(order=2), dp=0.034
        )
    assert any("Ursell number H L^2/d^3 = 48.2 exceeds 8 pi^2/3 = 26.3" in str(w.message)
               for w in record)


def test_the_core_refuses_what_python_does_not_check() -> None:
    # a hand-edited scene still goes through the core's own checks
    sc = scene().to_scene()
    sc["gauges"][0:0] = [{"type": "elevation", "name": "x", "position": [99.0, 0.0],
                          "interval": 0.1}]
    with pytest.raises(SceneError, match=r"gauges\[0\]\.position"):
        ws.Simulation(sc)


# ------------------------------------------------------------------------------------------------
# the scene JSON


def test_piston_law_is_wave_theorys_stroke_and_madsen_term() -> None:
    sc = scene(paddle=ws.Piston(order=2, ramp_periods=3, ramp="tanh")).to_scene()
    law = sc["paddle"]["law"]
    theory = wt.regular_paddle_motion(H, T, D, "piston", 2)
    assert law["type"] == "harmonic" and law["ramp_shape"] == "tanh"
    assert law["ramp_duration"] == pytest.approx(3 * T)
    (a1, w1, p1), (a2, w2, p2) = law["components"]
    assert a1 == pytest.approx(0.5 * theory.stroke, rel=1e-12)
    assert a2 == pytest.approx(theory.second_order_amplitude, rel=1e-12) and a2 != 0.0
    assert (w1, w2) == (pytest.approx(2 * math.pi / T), pytest.approx(4 * math.pi / T))
    assert (p1, p2) == (0.0, 0.0)
    assert sc["paddle"]["kind"] == "piston" and sc["paddle"]["hinge_z"] is None
    # first order: one component, the Biesel stroke
    first = scene(paddle=ws.Piston(order=1)).to_scene()["paddle"]["law"]["components"]
    assert len(first) == 1
    assert first[0][0] == pytest.approx(0.5 * float(wt.piston_stroke(H, T, D)), rel=1e-12)


def test_the_law_reproduces_wave_theorys_motion() -> None:
    sc = scene(paddle=ws.Piston(order=2, ramp_periods=2))
    law = sc.law.law
    t = np.linspace(0.0, 5 * T, 301)
    ramp = np.minimum(t / law["ramp_duration"], 1.0)
    x = ramp * sum(a * np.sin(w * t + p) for a, w, p in law["components"])
    expected, _ = wt.piston_motion(t, H, T, D, order=2, ramp_periods=2)
    assert np.allclose(x, expected, rtol=0, atol=1e-12)


def test_tank_and_paddle_are_aligned_on_the_lattice() -> None:
    for dp in (0.02, 0.03, 0.3 / 17):  # dp must divide the depth (0.3 m): 15, 10, 17 layers
        sc = scene(dp=dp, paddle=ws.Piston(order=2))
        js = sc.to_scene()
        x_back = js["tank"]["min"][0]
        n = -x_back / dp
        assert n == pytest.approx(round(n), abs=1e-9), (dp, x_back)
        bound = sum(abs(c[0]) for c in js["paddle"]["law"]["components"])
        assert -x_back >= sc.layers * dp + bound
        assert js["paddle"]["x"] == 0.0 and js["fluid"][0]["min"][0] == 0.0
        assert js["fluid"][0]["max"] == [4.0, D]
        assert js["tank"]["max"][0] == 4.0 and js["tank"]["max"][1] > D
    sim = scene(dp=0.03, flume=flat(length=1.5, damping=False)).build()
    fluid = sim.fluid_positions()
    assert fluid[:, 0].min() == pytest.approx(0.015)  # first column dp/2 in front of the face
    assert fluid[:, 1].max() == pytest.approx(D - 0.015)
    assert sim.n_fluid == 50 * 10


def test_plane_beach_profile_and_damping_defaults() -> None:
    beach = ws.PlaneBeach(toe=4.0, slope=1 / 15)
    sc = ws.Flume(length=17.0, depth=0.705, beach=beach).scene(
        ws.RegularWave(height=0.114, period=1.275), dp=0.705 / 14
    )
    js = sc.to_scene()
    (obstacle,) = js["obstacles"]
    assert obstacle["shape"] == "profile"
    top = js["tank"]["max"][1]
    assert obstacle["x"][0] == 4.0 and obstacle["z"][0] == 0.0
    assert obstacle["z"][-1] == pytest.approx(min(top, 13.0 / 15.0))
    assert obstacle["x"][-1] == 17.0
    assert "damping" not in js  # a beach absorbs: no damping zone by default
    assert sc.shoreline == pytest.approx(4.0 + 0.705 * 15)
    assert sc.beach_slope == pytest.approx(1 / 15)
    assert float(sc.still_depth(10.0)) == pytest.approx(0.705 - 6.0 / 15)
    # flat flume: one wavelength of damping zone by default
    js = scene().to_scene()
    wl = float(wt.wavelength(T, D))
    assert js["damping"] == {"x_start": pytest.approx(4.0 - wl), "x_end": 4.0, "strength": 10.0}
    assert "damping" not in scene(flume=flat(damping=False)).to_scene()
    zone = scene(flume=flat(damping=ws.DampingZone(length=1.0, strength=5.0))).to_scene()
    assert zone["damping"] == {"x_start": 3.0, "x_end": 4.0, "strength": 5.0}


def test_plane_beach_reaching_the_walls_continues_flat() -> None:
    sc = ws.Flume(length=6.0, depth=0.3, height=0.45, beach=ws.PlaneBeach(toe=2.0, slope=0.2)) \
        .scene(regular(), dp=0.025)
    obstacle = sc.to_scene()["obstacles"][0]
    assert obstacle["x"] == [2.0, pytest.approx(2.0 + 0.45 / 0.2), 6.0]
    assert obstacle["z"] == [0.0, 0.45, 0.45]


def test_runup_gauge_is_laid_along_the_slope_above_the_bed() -> None:
    beach = ws.PlaneBeach(toe=2.0, slope=0.1)
    sc = ws.Flume(length=6.0, depth=0.3, beach=beach).scene(regular(), dp=0.02, runup=True)
    (spec,) = [g for g in sc.to_scene()["gauges"] if g["type"] == "runup"]
    (xs, zs), (xe, ze) = spec["start"], spec["end"]
    assert zs < 0.3 < ze <= sc.tank_height
    for x, z in ((xs, zs), (xe, ze)):
        # distance to the bed line z = 0.1 (x - 2), normal to it
        dist = (z - 0.1 * (x - 2.0)) / math.hypot(1.0, 0.1)
        assert dist == pytest.approx(1.5 * 0.02)
    assert zs <= 0.3 - 2 * H + 1e-9
    # automatic when the beach crosses the SWL, absent on a flat floor
    assert any(g["type"] == "runup" for g in
               ws.Flume(length=6.0, depth=0.3, beach=beach).scene(regular(), dp=0.02)
               .to_scene()["gauges"])
    assert all(g["type"] != "runup" for g in scene().to_scene()["gauges"])


def test_runup_gauge_takes_the_wet_front_method_and_refuses_an_unknown_one() -> None:
    beach = ws.PlaneBeach(toe=2.0, slope=0.1)
    flume = ws.Flume(length=6.0, depth=0.3, beach=beach)
    sc = flume.scene(regular(), dp=0.02, runup=ws.RunupGauge(method="wet_front"))
    (spec,) = [g for g in sc.to_scene()["gauges"] if g["type"] == "runup"]
    assert spec["method"] == "wet_front"
    with pytest.raises(SceneError, match="runup.method"):
        ws.RunupGauge(method="wetfront")


def test_gauges_without_a_method_take_the_cores_default() -> None:
    """The core's ``Defaults`` is the only default of a gauge's method: Python leaves an unset
    method out of the scene, and the core fills in ``scene_defaults()["gauges"]``'s."""
    from watersim import _core

    defaults = _core.scene_defaults()["gauges"]
    beach = ws.PlaneBeach(toe=2.0, slope=0.1)
    flume = ws.Flume(length=6.0, depth=0.3, beach=beach)
    sc = flume.scene(regular(), dp=0.02, gauges=[ws.ElevationGauge(1.0)], runup=ws.RunupGauge())
    core = sc.to_scene()["gauges"]
    assert all("method" not in g for g in core if g["type"] in ("elevation", "runup"))
    resolved = {g["type"]: g["method"] for g in sc.resolved_scene()["gauges"]
                if g["type"] in ("elevation", "runup")}
    assert resolved == {"elevation": defaults["elevation_method"],
                        "runup": defaults["runup_method"]}
    assert ws.ElevationGauge(1.0, method="particle").to_core(sc, "e", 0.1)["method"] == "particle"


def test_submerged_bar_profile_has_no_runup_and_keeps_its_shape() -> None:
    bar = ws.ProfileBeach(x=(6.0, 12.0, 14.0, 17.0), z=(0.0, 0.3, 0.3, 0.0))
    sc = ws.Flume(length=25.0, depth=0.4, beach=bar).scene(
        ws.RegularWave(height=0.02, period=2.02), dp=0.04
    )
    js = sc.to_scene()
    assert js["obstacles"] == [{"shape": "profile", "x": [6.0, 12.0, 14.0, 17.0],
                                "z": [0.0, 0.3, 0.3, 0.0]}]
    assert sc.runup_gauge is None and sc.shoreline is None
    assert float(sc.still_depth(13.0)) == pytest.approx(0.1)
    assert sc.beach_slope == pytest.approx(0.05)


def test_flap_law_uses_the_flap_transfer_function() -> None:
    sc = scene(paddle=ws.Flap(ramp_periods=1))
    js = sc.to_scene()["paddle"]
    assert js["kind"] == "flap" and js["hinge_z"] == 0.0 and js["swl_z"] == D
    (a1, _, _), = js["law"]["components"]
    assert a1 == pytest.approx(0.5 * float(wt.flap_stroke(H, T, D)), rel=1e-12)
    hinged = scene(paddle=ws.Flap(hinge_z=0.1)).to_scene()["paddle"]
    k = float(wt.wavenumber(T, D))
    ratio = float(flap_height_to_stroke_hinged(k, D, 0.1))
    assert hinged["hinge_z"] == 0.1
    assert hinged["law"]["components"][0][0] == pytest.approx(0.5 * H / ratio, rel=1e-12)


def test_hinged_flap_transfer_function_is_the_biesel_integral() -> None:
    """H/S = 4 sinh kd / (sinh 2kd + 2kd) * k int_0^d f(z) cosh kz dz, f the flap's shape."""
    d = 0.5
    for kd in (0.3, 1.0, 2.5):
        k = kd / d
        for hinge in (0.0, 0.1, 0.3):
            z = np.linspace(0.0, d, 200001)
            f = np.clip((z - hinge) / (d - hinge), 0.0, None)
            integral = np.trapezoid(f * np.cosh(k * z), z) if hasattr(np, "trapezoid") else \
                np.trapz(f * np.cosh(k * z), z)
            expected = 4 * math.sinh(kd) / (math.sinh(2 * kd) + 2 * kd) * k * integral
            assert float(flap_height_to_stroke_hinged(k, d, hinge)) == pytest.approx(
                expected, rel=1e-7)


def test_three_dimensional_flume() -> None:
    sc = flat(width=0.1).scene(
        regular(), dp=0.025, gauges=[ws.ElevationGauge(1.0), ws.ElevationGauge(1.0, y=0.025)]
    )
    js = sc.to_scene()
    assert sc.dim == 3 and js["dim"] == 3
    assert js["tank"]["min"][1:] == [0.0, 0.0] and js["tank"]["max"][1] == 0.1
    assert js["fluid"][0]["max"] == [4.0, 0.1, D]
    names = [g["name"] for g in js["gauges"]]
    assert names == ["eta_x1.000_y0.050", "eta_x1.000_y0.025"]
    assert js["gauges"][0]["position"] == [1.0, 0.05, 0.0]


def test_gauge_names_and_intervals() -> None:
    sc = scene(
        gauges=[ws.ElevationGauge(1.0), ws.ElevationGauge(1.0), ws.ElevationGauge(2.0, name="g2"),
                ws.VelocityProbe(points=[(1.0, 0.1)]), ws.VelocityWindow(
                    min=(1.0, 0.05), max=(1.5, 0.25), n=(6, 5), interval=0.1)],
        sample_interval=0.05,
    )
    specs = sc.to_scene()["gauges"]
    assert [g["name"] for g in specs] == ["eta_x1.000", "eta_x1.000_2", "g2", "velocity0",
                                          "window0"]
    assert [g["interval"] for g in specs] == [0.05, 0.05, 0.05, 0.05, 0.1]
    assert specs[4]["n"] == [6, 5]
    lines = ws.elevation_gauges_between(1.0, 2.0, 0.25)
    assert [g.x for g in lines] == [1.0, 1.25, 1.5, 1.75, 2.0]


def test_defaults_follow_the_wave() -> None:
    sc = flat().scene(regular())
    assert sc.dp == pytest.approx(min(D / 15, H / 4), rel=1e-2)
    assert sc.sample_interval == pytest.approx(T / 40)
    ramp = 2 * T
    assert sc.until == pytest.approx(ramp + sc.arrival_time(0.75 * 4.0) + 10 * T)
    cg = float(wt.group_velocity(T, D))
    assert sc.arrival_time(2.0) == pytest.approx(2.0 / cg, rel=1e-3)
    assert sc.viscosity is None and sc.coefh == 1.5  # the core's viscosity
    assert sc.resolved_scene()["viscosity"] == {"model": "artificial", "alpha": 0.01,
                                                 "wall_factor": 1.0}


# ------------------------------------------------------------------------------------------------
# other laws


def test_solitary_wave_law_is_gorings_motion_as_a_table() -> None:
    wave = ws.SolitaryWave(height=0.09, delay=0.5, samples=401)
    sc = ws.Flume(length=12.0, depth=0.3, beach=ws.PlaneBeach(toe=4.0, slope=1 / 19.85)) \
        .scene(wave, dp=0.03)
    law = sc.to_scene()["paddle"]["law"]
    t = np.asarray(law["t"])
    x = np.asarray(law["x"])
    assert law["type"] == "table" and t.size == 401 and np.all(np.diff(t) > 0)
    assert t[0] == 0.5
    expected, _ = wt.solitary_piston_motion(t - 0.5, 0.09, 0.3)
    assert np.allclose(x, expected, atol=1e-12)
    assert x[0] == 0.0 and np.all(np.diff(x) >= -1e-15)
    assert x[-1] == pytest.approx(float(wt.solitary_piston_stroke(0.09, 0.3)) * math.tanh(
        math.acosh(1 / math.sqrt(0.002))), rel=1e-6)
    assert t[-1] - 0.5 == pytest.approx(float(wt.solitary_piston_duration(0.09, 0.3)))
    assert sc.back_x <= -sc.layers * sc.dp  # nothing moves backwards


def test_irregular_law_is_the_seeded_spectral_synthesis() -> None:
    wave = ws.IrregularWave(hs=0.04, tp=1.2, spectrum="pm", seed=7, repeat_period=60.0)
    law = scene(wave=wave, paddle=ws.Piston(ramp_periods=3)).to_scene()["paddle"]["law"]
    motion = wt.irregular_paddle_motion(0.04, 1.2, D, "pierson-moskowitz", seed=7,
                                        repeat_period=60.0)
    comps = np.asarray(law["components"])
    assert comps.shape == (motion.frequencies.size, 3)
    assert np.allclose(comps[:, 0], motion.stroke_amplitudes, rtol=1e-12)
    assert np.allclose(comps[:, 1], 2 * np.pi * motion.frequencies, rtol=1e-12)
    assert np.allclose(comps[:, 2], motion.phases, rtol=0, atol=0)
    assert law["ramp_duration"] == pytest.approx(3 * 1.2)
    # reproducible, and another seed changes the phases only
    again = scene(wave=wave).to_scene()["paddle"]["law"]["components"]
    assert again == law["components"]
    other = np.asarray(scene(wave=ws.IrregularWave(hs=0.04, tp=1.2, spectrum="pm", seed=8,
                                                   repeat_period=60.0))
                       .to_scene()["paddle"]["law"]["components"])
    assert np.allclose(other[:, :2], comps[:, :2]) and not np.allclose(other[:, 2], comps[:, 2])
    # the target spectrum's Hm0 (components' energy)
    hm0 = 4 * math.sqrt(0.5 * float(np.sum(motion.wave_amplitudes ** 2)))
    assert hm0 == pytest.approx(0.04, rel=0.02)
    # the core accepts it: room behind the paddle for its bound, the sum of the amplitudes
    sim = scene(wave=wave, flume=flat(length=3.0), dp=0.05).build()
    assert sim.n_fluid == 60 * 6
    assert -sim.scene["tank"]["min"][0] >= float(np.sum(np.abs(comps[:, 0])))


def test_tabulated_motion_is_passed_through() -> None:
    t = np.linspace(0.0, 2.0, 11)
    x = 0.02 * np.sin(np.pi * t)
    js = scene(wave=ws.TabulatedMotion(t=t, x=x)).to_scene()
    assert js["paddle"]["law"] == {"type": "table", "t": t.tolist(), "x": x.tolist()}
    sc = scene(wave=ws.TabulatedMotion(t=t, x=x))
    assert -sc.back_x >= sc.layers * sc.dp + 0.02


# ------------------------------------------------------------------------------------------------
# gauge records and analysis on synthetic data


def _records(sc: ws.FlumeScene, t: np.ndarray, eta: dict[str, np.ndarray],
             runup: np.ndarray | None = None) -> list[dict[str, Any]]:
    """Fake core gauge records: elevations in the core's form (z of the surface)."""
    depth = sc.flume.depth
    recs: list[dict[str, Any]] = []
    for spec in sc.to_scene()["gauges"]:
        if spec["type"] == "elevation":
            recs.append({"name": spec["name"], "type": "elevation", "t": t,
                         "z": depth + eta[spec["name"]]})
        elif spec["type"] == "runup":
            assert runup is not None
            recs.append({"name": spec["name"], "type": "runup", "t": t, "z": depth + runup})
    return recs


def test_gauges_are_zeroed_on_their_still_water_reading_and_written_as_csv(
    tmp_path: Path,
) -> None:
    sc = scene(gauges=[ws.ElevationGauge(1.0), ws.ElevationGauge(2.0)])
    t = np.arange(0.0, 3.0, 0.03)
    offset = 0.007
    eta = {"eta_x1.000": offset + 0.01 * np.sin(t), "eta_x2.000": np.where(t > 1, np.nan,
                                                                            offset)}
    gauges = FlumeGauges(sc, _records(sc, t, eta))
    assert gauges.names == ("eta_x1.000", "eta_x2.000")
    assert np.allclose(gauges.zero_offsets, offset)
    assert np.allclose(gauges.elevation[:, 0], 0.01 * np.sin(t))
    assert np.isnan(gauges.elevation[-1, 1])
    assert gauges.elevation_filled[-1, 1] == pytest.approx(-D)  # a dry gauge reads the bed
    path = gauges.to_csv(tmp_path / "gauges.csv")
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    assert rows[0] == ["t_s", "eta_x1p000_m", "eta_x2p000_m"]
    assert len(rows) == t.size + 1 and float(rows[1][0]) == 0.0
    assert rows[-1][2] == "nan"


def test_analysis_of_a_synthetic_regular_wave() -> None:
    """A known Stokes-like record at four flat gauges: height, period, harmonics, reflection."""
    sc = scene(flume=flat(length=8.0), gauges=[ws.ElevationGauge(x) for x in
                                               (1.0, 1.18, 1.44, 3.0)], sample_interval=0.02)
    k = 2 * math.pi / float(wt.wavelength(T, D))
    w = 2 * math.pi / T
    t = np.arange(0.0, 30.0 + 1e-9, 0.02)
    ramp = np.minimum(t / (2 * T), 1.0)  # still water at t = 0, as in a run
    kr = 0.2
    eta = {}
    for name, x in zip(("eta_x1.000", "eta_x1.180", "eta_x1.440", "eta_x3.000"),
                       (1.0, 1.18, 1.44, 3.0), strict=True):
        eta[name] = ramp * (0.5 * H * np.cos(w * t - k * x) + kr * 0.5 * H * np.cos(w * t + k * x)
                            + 0.002 * np.cos(2 * (w * t - k * x)))
    result = analyse_flume(sc, FlumeGauges(sc, _records(sc, t, eta)))
    json.dumps(result, allow_nan=False)
    g0 = result["gauges"][0]
    assert g0["T_mean"] == pytest.approx(T, rel=1e-3)
    assert g0["harmonics"][0] == pytest.approx(0.5 * H * abs(1 + kr * np.exp(2j * k * 1.0)),
                                               rel=1e-3)
    assert g0["harmonics"][1] == pytest.approx(0.002, rel=1e-2)
    refl = result["reflection"]
    assert refl["method"] == "mansard-funke" and len(refl["gauges"]) == 3
    assert refl["coefficient"] == pytest.approx(kr, abs=0.01)
    assert refl["incident_amplitude"] == pytest.approx(0.5 * H, rel=0.02)
    assert {"wave", "gauges", "envelopes", "notes"} <= set(result)
    assert "breaking" not in result and "runup" not in result


def test_analysis_on_a_beach_finds_breaking_and_runup_per_wave() -> None:
    beach = ws.PlaneBeach(toe=2.0, slope=0.1)
    sc = ws.Flume(length=6.0, depth=0.3, beach=beach).scene(
        regular(height=0.06), dp=0.02, gauges=[ws.ElevationGauge(x) for x in (1.0, 3.0, 4.0)],
        sample_interval=0.02)
    t = np.arange(0.0, 30.0, 0.02)
    w = 2 * math.pi / T
    ramp = np.minimum(t / (2 * T), 1.0)
    # heights: 0.06 at x = 1 (d = 0.3), 0.12 at x = 3 (d = 0.2, H/d = 0.6), 0.09 at x = 4
    # (d = 0.1, H/d = 0.9: breaking)
    eta = {"eta_x1.000": 0.03 * ramp * np.sin(w * t), "eta_x3.000": 0.06 * ramp * np.sin(w * t - 1),
           "eta_x4.000": 0.045 * ramp * np.sin(w * t - 2)}
    runup = 0.05 + 0.04 * ramp * np.sin(w * t - 3)  # reads 0.05 at rest: zeroed to 0
    result = analyse_flume(sc, FlumeGauges(sc, _records(sc, t, eta, runup)))
    br = result["breaking"]
    assert br["position"] == 4.0 and br["criterion"] == "H/d > 0.78"
    assert br["wave_height"] == pytest.approx(0.09, rel=1e-2)
    assert br["max_height_position"] == 3.0
    assert br["breaker_type"] in ("spilling", "plunging", "collapsing/surging")
    ru = result["runup"]
    assert ru["mean"] == pytest.approx(0.04, rel=1e-2)  # zeroed on its reading at t = 0
    assert ru["std"] < 1e-3 and ru["n_waves"] >= 15
    assert ru["mean_over_H"] == pytest.approx(0.04 / 0.06, rel=1e-2)
    # no overturn search made: no overturn keys
    assert "overturn" not in br and "breaker_type_observed" not in br
    # with the snapshots the run searched (FlumeSimulation.overturns): the first and the extent
    jets = [(12.0, an.Overturn(3.9, 4.0, 0.31, 0.37, 5, 6)),
            (12.1, an.Overturn(4.1, 4.3, 0.30, 0.33, 8, 9))]
    seen = analyse_flume(sc, FlumeGauges(sc, _records(sc, t, eta, runup)), overturns=jets,
                         overturn_checks=50)["breaking"]
    assert seen["breaker_type_observed"] == "plunging"
    assert seen["overturn"] == {
        "checks": 50, "seen": 2, "x_min": 3.9, "x_max": 4.3, "columns": 8,
        "first": {"time": 12.0, "x_min": 3.9, "x_max": 4.0, "gap": pytest.approx(0.06)}}
    quiet = analyse_flume(sc, FlumeGauges(sc, _records(sc, t, eta, runup)), overturn_checks=50)
    assert quiet["breaking"]["breaker_type_observed"] is None
    assert quiet["breaking"]["overturn"] == {"checks": 50, "seen": 0}
    assert any("no overturned surface" in n for n in quiet["notes"])
