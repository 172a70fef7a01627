"""Property-based tests over scene parameters, absurd ones included: every scene either runs a
few steps or raises a Python exception with a message; never a crash, a hang or a Rust panic."""

from __future__ import annotations

import json
import math
import re
import warnings

import pytest
from hypothesis import HealthCheck, event, example, given, settings
from hypothesis import strategies as st

import watersim
from watersim import _core
from watersim.flume import SteepSlopeWarning

# any float, including NaN, infinities, zero, negatives and huge values
anything = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([0.0, -1.0, 1e-300, 1e300, 0.5, 2.0]),
)
plausible = st.floats(min_value=0.02, max_value=3.0)


def _mostly(draw: st.DrawFn, good: st.SearchStrategy, bad: st.SearchStrategy):
    """A value from ``good`` nine times in ten, else from ``bad``: most scenes are valid enough
    to run, and every field is sometimes absurd."""
    return draw(bad) if draw(st.integers(0, 9)) == 0 else draw(good)


@st.composite
def scenes(draw: st.DrawFn) -> dict:
    dim = _mostly(draw, st.sampled_from([2, 3]), st.sampled_from([1, 4, 0]))
    d = max(dim, 1)
    tank_max = [_mostly(draw, plausible, anything) for _ in range(d)]
    fluid_max = [
        _mostly(
            draw, st.floats(0.1, 1.0).map(lambda f, t=t: f * t if math.isfinite(t) else f), anything
        )
        for t in tank_max
    ]
    scene = {
        "dim": dim,
        "dp": _mostly(draw, st.floats(min_value=0.04, max_value=0.5), anything),
        "tank": {"min": [0.0] * d, "max": tank_max},
        "fluid": [{"min": [0.0] * d, "max": fluid_max}],
        # keeps a plausible-but-fine resolution from taking minutes: refused with the figure
        "memory_limit_bytes": 4_000_000,
    }
    ranges = {
        "gravity": (0.0, 20.0), "rho0": (500.0, 2000.0), "coefh": (0.8, 2.0),
        "coefsound": (5.0, 80.0),
        "gamma": (1.0, 7.0), "cfl": (0.05, 1.0), "density_band": (0.05, 1.0),
    }
    for key, (lo, hi) in ranges.items():
        if draw(st.booleans()):
            # (a tiny positive coefh used to panic in the core's CellGrid::new; the core now
            # counts the grid's cells in its memory check: test_tiny_coefh_is_refused_not_a_panic)
            scene[key] = _mostly(draw, st.floats(lo, hi), anything)
    if draw(st.booleans()):
        kernels = st.sampled_from(["wendland", "cubic_spline"])
        scene["kernel"] = _mostly(draw, kernels, st.sampled_from(["gauss", ""]))
    if draw(st.booleans()):
        models = st.sampled_from(["artificial", "laminar", "laminar_sps"])
        model = _mostly(draw, models, st.just("magic"))
        value = _mostly(draw, st.floats(0.0, 0.5), anything)
        scene["viscosity"] = {"model": model, "alpha" if model == "artificial" else "nu": value}
    if draw(st.booleans()):
        model = _mostly(draw, st.sampled_from(["none", "molteni", "fourtakas"]), st.just("x"))
        scene["diffusion"] = {"model": model}
        if model in ("molteni", "fourtakas"):
            scene["diffusion"]["delta"] = _mostly(draw, st.floats(0.0, 0.5), anything)
    if draw(st.booleans()):
        schemes = st.sampled_from(["symplectic", "verlet"])
        scene["integrator"] = {"scheme": _mostly(draw, schemes, st.just("rk4"))}
    if draw(st.integers(0, 9)) == 0:
        scene[draw(st.sampled_from(["bogus", "dpp", "Tank"]))] = 1
    return scene


def _to_json(scene: dict) -> str:
    # JSON has no NaN/inf: Python writes them as bare tokens, which the core must refuse cleanly
    return json.dumps(scene, allow_nan=True)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(scenes())
def test_any_scene_runs_or_raises_with_a_message(scene: dict) -> None:
    try:
        sim = _core.Simulation(_to_json(scene))
    except watersim.SceneError as err:
        assert str(err) and ":" in str(err)
        return
    try:
        sim.step(3)
    except watersim.InstabilityError as err:
        assert err.kind and str(err)
        return
    assert math.isfinite(sim.time) and sim.steps == 3


@settings(max_examples=60, deadline=None)
@given(
    dp=anything,
    width=st.one_of(anything, plausible),
    height=st.one_of(anything, plausible),
    alpha=st.one_of(anything, st.floats(0, 1)),
    cfl=st.one_of(anything, st.floats(0.01, 1)),
)
def test_dambreak_builder_refuses_or_builds(
    dp: float, width: float, height: float, alpha: float, cfl: float
) -> None:
    try:
        builder = watersim.DamBreak(dim=2, dp=dp, width=width, height=height, cfl=cfl,
                                    viscosity={"type": "artificial", "alpha": alpha})
        scene = builder.to_scene()
        scene["memory_limit_bytes"] = 4_000_000
        sim = watersim.Simulation(scene)
    except watersim.SceneError as err:
        assert str(err)
        return
    try:
        sim.step(2)
    except watersim.InstabilityError as err:
        assert err.kind


def test_memory_estimate_refuses_with_the_figure() -> None:
    scene = watersim.DamBreak(dim=2, dp=0.05).to_scene()
    scene["memory_limit_bytes"] = 4_000_000
    _core.Simulation(json.dumps(scene))  # ~2k particles: fits
    scene["dp"] = 0.001
    try:
        _core.Simulation(json.dumps(scene))
    except watersim.SceneError as err:
        assert str(err).startswith("dp:") and "GiB" in str(err) and "particles" in str(err)
    else:  # pragma: no cover
        raise AssertionError("a 1 mm dam break in 4 MB must be refused")


# ------------------------------------------------------------------------------------------------
# the wave flume: absurd wave heights, periods, beaches, gauges and paddles


def _rarely_bad(draw: st.DrawFn, good: st.SearchStrategy, bad: st.SearchStrategy):
    """A value from ``bad`` one time in twenty: a flume has a dozen fields, and a fair share of
    the examples should get past the checks and run."""
    return draw(bad) if draw(st.integers(0, 19)) == 0 else draw(good)


@st.composite
def flume_setups(draw: st.DrawFn) -> dict:
    """Keyword arguments of the flume objects, mostly plausible, every one sometimes absurd."""
    length = _rarely_bad(draw, st.floats(3.0, 6.0), anything)
    depth = _rarely_bad(draw, st.floats(0.1, 0.4), anything)
    kind = draw(st.sampled_from(["regular", "regular", "solitary", "irregular"]))
    wave: dict = {"kind": kind, "height": _rarely_bad(draw, st.floats(0.005, 0.15), anything)}
    if kind != "solitary":
        wave["period"] = _rarely_bad(draw, st.floats(0.5, 1.5), anything)
    beach = draw(st.sampled_from([None, "plane", "profile"]))
    beach_args: dict = {}
    if beach == "plane":
        beach_args = {"toe": _rarely_bad(draw, st.floats(0.5, 3.0), anything),
                      "slope": _rarely_bad(draw, st.floats(0.02, 0.5), anything)}
    elif beach == "profile":
        beach_args = {"x": (_rarely_bad(draw, st.floats(0.5, 1.5), anything),
                            _rarely_bad(draw, st.floats(1.6, 2.8), anything)),
                      "z": (0.0, _rarely_bad(draw, st.floats(0.0, 0.3), anything))}
    paddle = draw(st.sampled_from(["piston1", "piston2", "flap"]))
    hinge = _rarely_bad(draw, st.one_of(st.none(), st.floats(0.0, 0.1)), anything)
    gauges = draw(st.lists(gauge_x, max_size=3))
    probe = draw(st.booleans())
    probe_point = (_rarely_bad(draw, st.floats(0.2, 1.0), anything),
                   _rarely_bad(draw, st.floats(0.02, 0.1), anything))
    # a dp that fills the depth with whole layers (else the lattice check refuses it), so that
    # most examples get as far as stepping
    layers = st.integers(3, 8).map(lambda n: depth / n) if isinstance(depth, float) and \
        0.1 <= depth <= 0.4 else st.floats(0.03, 0.06)
    numerics = {"dp": _rarely_bad(draw, layers, anything)}
    for key, (lo, hi) in {"coefsound": (5.0, 40.0), "cfl": (0.05, 0.5),
                          "sample_interval": (0.01, 0.1)}.items():
        if draw(st.booleans()):
            numerics[key] = _rarely_bad(draw, st.floats(lo, hi), anything)
    return {"length": length, "depth": depth, "wave": wave, "beach": beach,
            "beach_args": beach_args, "paddle": paddle, "hinge": hinge, "gauges": gauges,
            "probe": probe, "probe_point": probe_point, "numerics": numerics}


gauge_x = st.one_of(st.floats(0.0, 1.0), anything, st.sampled_from([-1.0, 50.0]))
"""Gauge positions: inside most flumes, absurd, or outside (behind the paddle, past the end)."""


def _make_flume(a: dict) -> watersim.FlumeScene:
    beach = None
    if a["beach"] == "plane":
        beach = watersim.PlaneBeach(**a["beach_args"])
    elif a["beach"] == "profile":
        beach = watersim.ProfileBeach(**a["beach_args"])
    flume = watersim.Flume(length=a["length"], depth=a["depth"], beach=beach)
    w = a["wave"]
    if w["kind"] == "regular":
        wave = watersim.RegularWave(height=w["height"], period=w["period"])
    elif w["kind"] == "solitary":
        wave = watersim.SolitaryWave(height=w["height"])
    else:
        wave = watersim.IrregularWave(hs=w["height"], tp=w["period"])
    if a["paddle"] == "flap":
        paddle = watersim.Flap(hinge_z=a["hinge"])
    else:
        paddle = watersim.Piston(order=2 if a["paddle"] == "piston2" else 1)
    gauges: list = [watersim.ElevationGauge(x) for x in a["gauges"]]
    if a["probe"]:
        gauges.append(watersim.VelocityProbe(points=(a["probe_point"],)))
    return flume.scene(wave, paddle=paddle, gauges=gauges, until=0.05, **a["numerics"])


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(flume_setups())
# found by hypothesis: an absorbing flap's extra room summed the squares of a 1e154 amplitude
# (a numpy overflow warning) before the excursion was refused
@example(a={"length": 3.0, "depth": 0.25,
            "wave": {"kind": "regular", "height": 1.0036766131521608e154, "period": 1.5},
            "beach": "plane", "beach_args": {"toe": 0.0, "slope": 0.5}, "paddle": "flap",
            "hinge": 0.0, "gauges": [], "probe": False, "probe_point": (1.0, 0.0625),
            "numerics": {"dp": 0.25 / 3}})
# found by hypothesis: a flap's transfer function underflowed to 0 for a 4e7 s wave (a
# ZeroDivisionError instead of the refusal of its infinite stroke)
@example(a={"length": 3.0, "depth": 0.25,
            "wave": {"kind": "regular", "height": 0.125, "period": 42572118.0},
            "beach": None, "beach_args": {}, "paddle": "flap", "hinge": 0.125, "gauges": [],
            "probe": False, "probe_point": (0.0, 0.0), "numerics": {"dp": 0.25 / 3}})
# found by hypothesis: a 0.03 s wave (1.5 mm long) overflowed the wave-maker theory's cosh when
# the absorbing piston's near field was computed; it is refused as unresolved now
@example(a={"length": 3.0, "depth": 0.25,
            "wave": {"kind": "regular", "height": 0.125, "period": 0.03125},
            "beach": "plane", "beach_args": {"toe": 1.0, "slope": 0.5}, "paddle": "piston1",
            "hinge": 0.0, "gauges": [], "probe": False, "probe_point": (0.0, 0.0),
            "numerics": {"dp": 0.25 / 3}})
# found by hypothesis: periods of 5e-214 s and 7e161 s overflowed the dispersion relation of
# that check (numpy warnings instead of a refusal)
@example(a={"length": 3.0, "depth": 0.25,
            "wave": {"kind": "regular", "height": 0.125, "period": 4.782392385153945e-214},
            "beach": None, "beach_args": {}, "paddle": "piston1", "hinge": 0.0, "gauges": [],
            "probe": False, "probe_point": (0.0, 0.0625), "numerics": {"dp": 0.25 / 3}})
@example(a={"length": 3.0, "depth": 0.25,
            "wave": {"kind": "regular", "height": 0.125, "period": 6.572062360961943e161},
            "beach": None, "beach_args": {}, "paddle": "piston1", "hinge": 0.0, "gauges": [],
            "probe": False, "probe_point": (0.0, 0.0625), "numerics": {"dp": 0.25 / 3}})
def test_any_flume_builds_and_steps_or_raises_with_a_message(a: dict) -> None:
    """Flume objects with absurd values: refused with ``field: reason`` (a SceneError), or built
    and stepped. Anything else (a TypeError, an overflow warning, a pyo3 PanicException, which
    is a BaseException) fails the test."""
    try:
        with warnings.catch_warnings():
            # a wave beyond the theory's validity, a beach steeper than 1:1 and a very stiff
            # fluid are warnings by design (wave_theory.py, flume/bed.py, scenes.py)
            warnings.simplefilter("ignore", watersim.wave_theory.WaveValidityWarning)
            warnings.simplefilter("ignore", SteepSlopeWarning)
            warnings.simplefilter("ignore", watersim.StiffFluidWarning)
            setup = _make_flume(a)
            scene = setup.to_scene()
        scene["memory_limit_bytes"] = 4_000_000
        sim = watersim.Simulation(scene)
    except watersim.SceneError as err:
        assert re.match(r"^[A-Za-z_][\w.\[\]]*: \S", str(err)), str(err)
        event(f"refused: {str(err).split(':')[0]}")
        return
    try:
        sim.step(2)
    except watersim.InstabilityError as err:
        assert err.kind and str(err)
        event(f"unstable: {err.kind}")
        return
    event("ran")
    assert sim.steps == 2 and math.isfinite(sim.time)


def test_tiny_coefh_is_refused_not_a_panic() -> None:
    scene = {"dim": 3, "dp": 0.07, "coefh": 1e-6, "memory_limit_bytes": 4_000_000,
             "tank": {"min": [0.0, 0.0, 0.0], "max": [2.0, 0.3, 1.9]},
             "fluid": [{"min": [0.0, 0.0, 0.0], "max": [0.45, 0.07, 0.47]}]}
    try:
        _core.Simulation(json.dumps(scene))
    except watersim.SceneError as err:
        assert str(err).startswith(("coefh:", "dp:"))
    else:  # pragma: no cover
        raise AssertionError("a 1e-6 coefh must be refused")


def test_builders_refuse_a_tiny_coefh() -> None:
    with pytest.raises(watersim.SceneError, match=r"^coefh: must be at least 0\.5"):
        watersim.DamBreak(dim=3, coefh=1e-6)
