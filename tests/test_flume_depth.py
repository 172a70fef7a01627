"""The water is as deep (and, in 3D, as wide) as asked: the core fills the flume with whole
particle layers (crates/sph-core/src/geometry.rs: lattice points at (i + 1/2) dp, strictly inside
the fluid box), so a flume whose depth is not a whole number of dp is refused, and every dp the
package derives itself (the FlumeScene default, the built-in cases, the validation cases, the
DualSPHysics piston bench) divides the depth. Builds only, no stepping."""

from __future__ import annotations

import re
import warnings

import pytest

import watersim as ws
from watersim.bench_cases import dsph_scene
from watersim.flume import lattice_dp, lattice_layers
from watersim.flume_cases import FLUME_CASES, flume_builder
from watersim.validation.absorption import absorption_scene
from watersim.validation.cases import (
    CASES,
    _flume2d_items,
    secondorder_scene,
)
from watersim.validation.longflume import long_flume_scene


def _filled(sim: ws.Simulation, dp: float) -> tuple[float, float | None]:
    """(depth, width) of the water the core made [m]: the highest fluid particle within 3 dp of
    the paddle plus dp/2 (the bed is flat there), and in 3D the widest particle + dp/2."""
    pos = sim.fluid_positions()
    near = pos[:, 0] < 3.0 * dp
    up = pos.shape[1] - 1
    depth = float(pos[near, up].max()) + 0.5 * dp
    width = None if pos.shape[1] == 2 else float(pos[:, 1].max()) + 0.5 * dp
    return depth, width


def _case(name: str, items: dict[str, str]) -> ws.FlumeScene:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # stansby2d's wave is beyond second order: it says so
        return flume_builder(name, items)


def _quiet_build(scene: ws.FlumeScene) -> ws.Simulation:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # wave-validity warnings of the steep seed waves
        return scene.build()


def _flat(depth: float, dp: float, width: float | None = None) -> ws.FlumeScene:
    flume = ws.Flume(length=2.0, depth=depth, width=width, damping=True)
    return flume.scene(ws.RegularWave(period=1.0, height=0.03), dp=dp, until=0.1)


@pytest.mark.parametrize(("extent", "dp", "n"), [
    (0.705, 0.01, 70), (0.705, 0.05, 14), (0.34, 0.03, 11), (0.2, 0.03, 7), (0.2, 0.015, 13),
    (0.3, 0.025, 12), (0.3, 0.3 / 12, 12),
])
def test_lattice_layers_counts_what_the_core_fills(extent: float, dp: float, n: int) -> None:
    assert lattice_layers(extent, dp) == n


def test_a_depth_that_is_not_whole_layers_is_refused_with_two_that_are() -> None:
    with pytest.raises(ws.SceneError) as err:
        _flat(0.705, 0.01)
    msg = str(err.value)
    assert msg.startswith("dp: ") and "70.5 dp" in msg and "0.7 m deep" in msg
    found = re.search(r"use dp = ([0-9.e-]+) \(70 layers\) or ([0-9.e-]+) \(71 layers\)", msg)
    assert found, msg
    # both suggestions are accepted and give the depth asked for
    for text, n in zip(found.groups(), (70, 71), strict=True):
        dp = float(text)
        assert lattice_layers(0.705, dp) == n
        sim = _flat(0.705, dp).build()
        assert _filled(sim, dp)[0] == pytest.approx(0.705, abs=1e-6)


def test_the_irregular_run_that_lost_5_mm_of_water_is_refused() -> None:
    """dp = 0.015 in d = 0.2 m filled 0.195 m (an irregular-wave run of
    docs/irregular, since removed): now refused."""
    with pytest.raises(ws.SceneError, match=r"^dp: .*0\.195 m deep"):
        _flat(0.2, 0.015)


def test_a_3d_width_that_is_not_whole_columns_is_refused_naming_width() -> None:
    with pytest.raises(ws.SceneError) as err:
        _flat(0.2, 0.02, width=0.25)
    msg = str(err.value)
    assert msg.startswith("width: ") and "12.5 dp" in msg and "0.24 m wide" in msg
    assert "0.24 m (12 dp) or 0.26 m (13 dp)" in msg


def test_a_whole_dp_builds_with_the_depth_and_width_asked() -> None:
    sim = _flat(0.2, 0.025, width=0.1).build()
    depth, width = _filled(sim, 0.025)
    assert depth == pytest.approx(0.2, abs=1e-9) and width == pytest.approx(0.1, abs=1e-9)


def test_the_default_dp_divides_the_depth_and_the_width() -> None:
    scene = ws.Flume(length=17.0, depth=0.705).scene(ws.RegularWave(period=1.275, height=0.114))
    assert scene.dp == pytest.approx(0.705 / 25)  # min(d / 15, H / 4) = 0.0285 -> 25 layers
    scene3 = ws.Flume(length=2.0, depth=0.2, width=0.24, damping=True).scene(
        ws.RegularWave(period=1.0, height=0.05))
    dp = float(scene3.dp)  # type: ignore[arg-type]
    assert lattice_layers(0.2, dp) * dp == pytest.approx(0.2)
    assert lattice_layers(0.24, dp) * dp == pytest.approx(0.24)


def test_lattice_dp_keeps_a_dp_that_already_divides_the_depth() -> None:
    assert lattice_dp(0.3, 0.025) == 0.025
    assert lattice_dp(0.705, 0.05) == 0.705 / 14
    assert lattice_dp(0.34, 0.03) == 0.34 / 11


@pytest.mark.parametrize("case", list(FLUME_CASES))
def test_every_built_in_case_fills_its_depth_at_its_default_dp(case: str) -> None:
    scene = _case(case, {})
    dp = float(scene.dp)  # type: ignore[arg-type]
    depth, width = _filled(_quiet_build(scene), dp)
    assert depth == pytest.approx(scene.flume.depth, abs=1e-9)
    if scene.flume.width is not None:
        assert width == pytest.approx(scene.flume.width, abs=1e-9)


def test_a_case_dp_set_by_hand_must_divide_the_depth() -> None:
    with pytest.raises(ws.SceneError, match=r"^dp: .*14\.1 dp"):
        _case("kimmoun2d", {"dp": "0.05"})
    # the default follows a depth set by hand
    scene = _case("stansby2d", {"flume.depth": "0.35"})
    assert scene.dp == pytest.approx(0.35 / 12)  # 11.7 layers at the nominal 0.03 m


def _validation_scene(name: str, dp: float) -> ws.FlumeScene:
    """The validation case's scene at dp, built the way its runner builds it (flume2d,
    secondorder2d and absorption2d by their helpers; bar2d, solitary2d and kimmoun2d are the
    built-in cases with dp set, at the case's depth; flume2d-long by its scene function)."""
    if name == "absorption2d":
        return absorption_scene(ws.Flap(absorption=True), dp, periods=1)
    if name == "flume2d":
        return _flume2d_items(dp, 2)[0]
    if name == "secondorder2d":
        return secondorder_scene(dp, 2)
    if name == "flume2d-long":
        return long_flume_scene(dp)[0]
    return _case(name, {"dp": repr(dp), "until": "0.1"})


@pytest.mark.parametrize("name", [n for n, c in CASES.items() if c.depth is not None])
def test_validation_flume_cases_fill_their_depth_at_every_resolution(name: str) -> None:
    case = CASES[name]
    assert case.depth is not None
    for res in sorted(set(case.resolutions + case.quick_resolutions)):
        dp = case.dp(res)
        nominal = case.length / res
        assert abs(dp - nominal) <= 0.5 * dp * nominal / case.depth + 1e-12  # half a layer
        scene = _validation_scene(name, dp)
        assert scene.flume.depth == case.depth
        n = lattice_layers(case.depth, dp)
        assert n * dp == pytest.approx(case.depth, abs=1e-9)
        depth, _ = _filled(_quiet_build(scene), dp)
        assert depth == pytest.approx(case.depth, abs=1e-9)


def test_the_piston_bench_keeps_dualsphysics_dp_and_water() -> None:
    # WallRegAwas2's GenCase output at dp = 6 mm: 43 rows of fluid (z = 0.008 to 0.260 m, one dp
    # above the floor's particles), 499 columns
    scene = dsph_scene("dsph-piston2d")
    dp = scene["dp"]
    assert dp == 0.006
    assert scene["fluid"][0]["max"] == pytest.approx([499 * 0.006, 43 * 0.006], abs=1e-12)
