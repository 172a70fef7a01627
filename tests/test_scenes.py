"""Scene builders: defaults, the JSON form, and refusal of bad input (Python and core)."""

from __future__ import annotations

import json
import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import watersim
from watersim import DamBreak, SceneError, Tank, _core
from watersim import numerics as nm

SCENE_KEYS = {
    "dim",
    "dp",
    "gravity",
    "rho0",
    "kernel",
    "coefh",
    "coefsound",
    "gamma",
    "h_swl",
    "cfl",
    "viscosity",
    "diffusion",
    "integrator",
    "shifting",
    "boundary",
    "force_precision",
    "tank",
    "obstacles",
    "fluid",
    "boundary_layers",
    "density_band",
    "lost_fraction_limit",
    "energy_growth_limit",
}


def test_scene_error_is_the_cores_and_a_value_error() -> None:
    assert watersim.SceneError is _core.SceneError
    assert issubclass(SceneError, ValueError)
    assert issubclass(watersim.InstabilityError, RuntimeError)


def test_force_precision_reaches_the_core_and_bad_values_are_named() -> None:
    assert "force_precision" not in Tank().to_scene()  # the core's default
    assert Tank().resolved_scene()["force_precision"] == "f64"
    sim = watersim.Simulation(Tank(dp=0.05, force_precision="f32").to_scene())
    assert sim.params()["force_precision"] == "f32"
    assert watersim.Simulation(Tank(dp=0.05).to_scene()).params()["force_precision"] == "f64"
    with pytest.raises(SceneError, match="^force_precision:"):
        Tank(force_precision="f16")
    # the SPS closure has no f32 loop: refused, not silently run in f64
    with pytest.raises(SceneError, match="^force_precision:"):
        Tank(force_precision="f32", viscosity="laminar_sps")
    scene = {**Tank(dp=0.05).to_scene(), "force_precision": "f32",
             "viscosity": {"model": "laminar_sps", "nu": 1e-6, "cs": 0.12, "ci": 0.0066}}
    with pytest.raises(SceneError, match="force_precision"):
        watersim.Simulation(scene)


def test_shifting_reaches_the_core_and_bad_values_are_named() -> None:
    assert "shifting" not in Tank().to_scene()
    assert Tank(shifting=2.0).to_scene()["shifting"] == {"coefficient": 2.0}
    shifting = nm.Shifting(coefficient=1.0, surface_threshold=2.5)
    assert Tank(dim=3, shifting=shifting).to_scene()["shifting"] == {
        "coefficient": 1.0, "surface_threshold": 2.5}
    assert Tank(shifting={}).resolved_scene()["shifting"] == {
        "model": nm.core_default("shifting.model"),
        "coefficient": nm.core_default("shifting.coefficient"), "surface_threshold": None}
    sim = watersim.Simulation(Tank(dp=0.05, shifting=2.0).to_scene())
    assert sim.params()["shifting"] == 2.0
    assert watersim.Simulation(Tank(dp=0.05).to_scene()).params()["shifting"] is None
    for kwargs, field in [({"shifting": 0.0}, "shifting.coefficient"),
                          ({"shifting": {"surface_threshold": 2.0}}, "shifting.surface_threshold"),
                          ({"shifting": {"threshold": 1.0}}, "shifting.threshold")]:
        with pytest.raises(SceneError, match=f"^{field}:"):
            Tank(**kwargs)


@pytest.mark.parametrize(
    "builder",
    [DamBreak(), DamBreak(dim=3), Tank(), Tank(dim=3)],
    ids=["dambreak2d", "dambreak3d", "tank2d", "tank3d"],
)
def test_defaults_give_the_core_json_form(builder: watersim.SceneBuilder) -> None:
    scene = builder.to_scene()
    assert set(scene) <= SCENE_KEYS
    assert set(builder.resolved_scene()) >= SCENE_KEYS
    assert len(scene["tank"]["min"]) == len(scene["tank"]["max"]) == builder.dim
    assert json.loads(json.dumps(scene)) == scene


def test_dambreak_default_is_martin_moyce_geometry() -> None:
    b = DamBreak()
    assert (b.dim, b.width, b.height, b.tank_length) == (2, 1.0, 2.0, 4.0)
    assert b.height / b.width == 2.0  # n^2 = 2
    assert b.core_value("kernel") == "wendland" and b.integrator is None
    assert b.viscosity == nm.VERIFICATION["viscosity"] and b.diffusion is None
    scene = b.to_scene()
    assert scene["fluid"] == [{"min": [0.0, 0.0], "max": [1.0, 2.0]}]
    assert scene["viscosity"] == {"model": "artificial", "alpha": 0.02}
    d3 = DamBreak(dim=3)
    assert d3.tank_width is not None
    assert d3.to_scene()["fluid"][0]["max"] == [1.0, d3.tank_width, 2.0]  # spans the width


def test_models_map_to_the_scene() -> None:
    b = DamBreak(viscosity=nm.LaminarSps(nu=2e-6), diffusion="none",
                 integrator={"type": "verlet", "euler_every": 50})
    s = b.to_scene()
    assert s["viscosity"] == {"model": "laminar_sps", "nu": 2e-6}
    assert s["diffusion"] == {"model": "none"}
    assert s["integrator"] == {"scheme": "verlet", "euler_every": 50}
    assert b.resolved_scene()["viscosity"] == {"model": "laminar_sps", "nu": 2e-6, "cs": 0.12,
                                               "ci": 0.0066, "wall_factor": 1.0}
    assert DamBreak(viscosity="laminar").resolved_scene()["viscosity"] == {
        "model": "laminar", "nu": 1e-6, "wall_factor": 1.0}
    assert DamBreak(diffusion="molteni").resolved_scene()["diffusion"] == {
        "model": "molteni", "delta": 0.1}


BAD_DAMBREAK = [
    ({"dp": 0.0}, "dp", "positive"),
    ({"dp": -0.02}, "dp", "positive"),
    ({"dp": math.nan}, "dp", "finite"),
    ({"dp": math.inf}, "dp", "finite"),
    ({"dp": "0.02"}, "dp", "number"),
    ({"dp": 0.8}, "dp", "fewer than 2 particles"),
    ({"width": 5.0}, "width", "tank length"),
    ({"height": 3.0}, "height", "tank_height"),
    ({"width": -1.0}, "width", "positive"),
    ({"tank_length": math.nan}, "tank_length", "finite"),
    ({"kernel": "gaussian"}, "kernel", "'wendland', 'wendland_c4', 'cubic_spline'"),
    ({"viscosity": "sph"}, "viscosity", "'artificial', 'laminar', 'laminar_sps'"),
    ({"diffusion": "ddt"}, "diffusion", "'none', 'molteni', 'fourtakas'"),
    ({"integrator": "rk4"}, "integrator", "'symplectic', 'verlet'"),
    ({"cfl": 1.5}, "cfl", "at most 1"),
    ({"viscosity": {"type": "artificial", "alpha": -0.1}}, "viscosity.alpha", "negative"),
    ({"viscosity": {"type": "laminar", "alpha": 0.1}}, "viscosity.alpha",
     "not a parameter of viscosity model 'laminar'"),
    ({"viscosity": 0.1}, "viscosity", "expected Artificial"),
    ({"coefsound": 0.0}, "coefsound", "positive"),
    ({"integrator": {"type": "verlet", "euler_every": 0}}, "integrator.euler_every",
     "at least 1"),
    ({"integrator": {"type": "verlet", "euler_every": 2.5}}, "integrator.euler_every",
     "integer"),
    ({"gravity": math.nan}, "gravity", "finite"),
    ({"until": -1.0}, "until", "positive"),
    ({"boundary_layers": 0}, "boundary_layers", "at least 1"),
    ({"h_swl": -2.0}, "h_swl", "positive"),
    ({"dim": 4}, "dim", "2 or 3"),
    ({"tank_width": 0.5}, "tank_width", "3D"),
]


@pytest.mark.parametrize(("changes", "field", "reason"), BAD_DAMBREAK)
def test_bad_dambreak_is_refused_naming_the_field(changes: dict, field: str, reason: str) -> None:
    with pytest.raises(SceneError) as info:
        DamBreak(**changes)
    message = str(info.value)
    assert message.startswith(f"{field}:"), message
    assert reason in message, message


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        ({"depth": 1.0, "height": 0.7}, "depth"),
        ({"length": 0.0}, "length"),
        ({"dim": 3, "width": math.nan}, "width"),
        ({"width": 0.3}, "width"),
        ({"dp": -1.0}, "dp"),
    ],
)
def test_bad_tank_is_refused_naming_the_field(changes: dict, field: str) -> None:
    with pytest.raises(SceneError, match=f"^{field}:"):
        Tank(**changes)


def test_replace_checks_again() -> None:
    b = DamBreak(dp=0.1)
    assert b.replace(dp=0.05).dp == 0.05
    with pytest.raises(SceneError, match="^dp:"):
        b.replace(dp=-1.0)


@settings(max_examples=60, deadline=None)
@given(
    field=st.sampled_from(
        [
            "dp",
            "width",
            "height",
            "tank_length",
            "tank_height",
            "coefh",
            "coefsound",
            "gamma",
            "cfl",
            "rho0",
            "gravity",
            "until",
        ]
    ),
    value=st.sampled_from([0.0, -1.0, -1e-300, math.nan, math.inf, -math.inf]),
)
def test_any_non_positive_or_non_finite_number_is_refused(field: str, value: float) -> None:
    with pytest.raises(SceneError) as info:
        DamBreak(**{field: value})
    assert str(info.value).split(":")[0] == field


def _core_scene(**changes: object) -> str:
    scene = DamBreak(dp=0.1).to_scene()
    scene.update(changes)
    return json.dumps(scene)


def test_core_refuses_unknown_key_naming_it() -> None:
    with pytest.raises(SceneError, match="bogus"):
        _core.Simulation(_core_scene(bogus=1))


def test_core_refuses_bad_values_naming_the_field() -> None:
    with pytest.raises(SceneError, match="kernel"):
        _core.Simulation(_core_scene(kernel="gaussian"))
    with pytest.raises(SceneError, match="dp"):
        _core.Simulation(_core_scene(dp=-0.1))
    with pytest.raises(SceneError, match="viscosity"):
        _core.Simulation(_core_scene(viscosity={"model": "magic"}))
    with pytest.raises(SceneError):
        _core.Simulation("{not json")


@pytest.mark.parametrize("dim", [2, 3])
def test_build_lattice_counts_and_derived_params(dim: int) -> None:
    b = DamBreak(dim=dim, dp=0.1, tank_width=0.3 if dim == 3 else None)
    sim = b.build()
    across = 3 if dim == 3 else 1
    assert sim.dim == dim
    assert sim.n_fluid == 10 * 20 * across
    assert sim.n_particles == sim.n_fluid + sim.n_boundary
    p = sim.params()
    assert p["h"] == pytest.approx(math.sqrt(dim) * 0.1)
    assert p["c0"] == pytest.approx(20.0 * math.sqrt(9.81 * 2.0))
    assert p["rho0"] == pytest.approx(1000.0)
    assert p["dp"] == pytest.approx(0.1)
    fluid = sim.fluid_positions()
    assert fluid[:, 0].min() == pytest.approx(0.05) and fluid[:, 0].max() == pytest.approx(0.95)
    assert watersim.front_position(fluid, 0.1) == pytest.approx(1.0)
    assert watersim.water_column_height(fluid, 0.1) == pytest.approx(2.0)


def test_tank_builds_still_water() -> None:
    sim = Tank(dp=0.05).build()
    assert sim.n_fluid == 20 * 10
    assert float(abs(sim.velocities).max()) == 0.0
