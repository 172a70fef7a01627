"""The numerical options (``watersim.numerics``): one default per parameter, the core's; the
options' forms, checks and ``--set`` keys."""

from __future__ import annotations

import ast
import dataclasses
import json
import warnings
from pathlib import Path
from typing import Any

import pytest

import watersim as ws
from watersim import _core, cli
from watersim import numerics as nm
from watersim import scenefile as sf
from watersim.flume import FlumeScene
from watersim.overrides import OverrideError

PACKAGE = Path(__file__).resolve().parents[1] / "python" / "watersim"
EXAMPLES = Path(__file__).resolve().parents[1] / "examples"

PARAMETERS = {*ws.SceneBuilder.CORE_KEYS,
              *(p for ps in nm.SETTABLE_PARAMETERS.values() for p in ps)}
"""Every name of a core parameter a Python builder or option carries."""


def _dotted(tree: dict[str, Any], prefix: str = "") -> dict[str, Any]:
    """A nested dict as dotted keys (``{"viscosity.alpha": 0.01, ...}``)."""
    out: dict[str, Any] = {}
    for key, value in tree.items():
        if isinstance(value, dict):
            out.update(_dotted(value, f"{prefix}{key}."))
        else:
            out[f"{prefix}{key}"] = value
    return out


def _preset_pairs() -> set[tuple[str, Any]]:
    """Every (dotted key, value) a preset of ``watersim.numerics`` chooses."""
    presets = [nm.VERIFICATION, *nm.FLUME.values(), nm.FLUME_CASE, nm.WAVE_CARRYING, nm.WATER,
               nm.LOW_DISSIPATION]
    pairs: set[tuple[str, Any]] = set()
    for preset in presets:
        scene = ws.Tank(**preset).to_scene()  # the preset in the core's form
        pairs |= {(k, v) for k, v in _dotted(scene).items() if k.split(".")[0] in preset}
    return pairs


def _case_builder(case: str) -> ws.SceneBuilder:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # wave-validity warnings of some cases
        return cli.builder_from_args(case, [])


@pytest.mark.parametrize("case", cli.ALL_CASES)
def test_one_default_per_parameter(case: str) -> None:
    """What a built-in case sends the core differs from the core's default only where a preset
    of ``watersim.numerics`` chooses so; everything else it leaves to the core."""
    defaults = _dotted(_core.scene_defaults())
    sent = _dotted(_case_builder(case).to_scene())
    chosen = _preset_pairs()
    for key, value in sent.items():
        if key in defaults and value != defaults[key]:
            assert (key, value) in chosen, f"{case}: {key} = {value!r}, the core's is " \
                                           f"{defaults[key]!r}, and no preset chooses it"


@pytest.mark.parametrize("cls", [ws.DamBreak, ws.Tank, FlumeScene, *nm.TAGS, nm.Shifting,
                                 nm.TensileCorrection])
def test_python_declares_no_default_of_its_own(cls: type) -> None:
    """A core parameter's field defaults to None (the core decides) in every builder and
    option class."""
    for f in dataclasses.fields(cls):
        if f.name in PARAMETERS:
            assert f.default is None, f"{cls.__name__}.{f.name} defaults to {f.default!r}"


BUILDER_CALLS = {"DamBreak", "Tank", "FlumeScene", "scene", "simulation", "numerics", "replace",
                 "_finish", "_quiet_scene", *(cls.__name__ for cls in nm.TAGS), "Shifting"}
"""Calls whose keyword arguments are builder or option fields."""
UNAMBIGUOUS = PARAMETERS - {"gamma", "alpha", "kernel", "boundary", "coefficient", "shifting",
                            "surface_threshold"}
"""Core parameter names no other code uses for something else (JONSWAP's gamma, matplotlib's
alpha, ...): a dict entry with one of them is scene data."""


def _literal_settings(tree: ast.AST) -> list[tuple[str, Any]]:
    """``(name, value node)`` of each literal given to a core parameter in ``tree``."""
    pairs: list[tuple[Any, Any]] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            func = node.func
            callee = func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")
            if callee in BUILDER_CALLS:
                pairs += [(k.arg, k.value) for k in node.keywords if k.arg in PARAMETERS]
        elif isinstance(node, ast.Dict):
            pairs += [(k.value, v) for k, v in zip(node.keys, node.values, strict=True)
                      if isinstance(k, ast.Constant) and k.value in UNAMBIGUOUS]
        elif isinstance(node, ast.ClassDef):
            for item in node.body:
                if (isinstance(item, ast.AnnAssign) and isinstance(item.target, ast.Name)
                        and item.target.id in UNAMBIGUOUS):
                    pairs.append((item.target.id, item.value))
    return [(name, v) for name, v in pairs
            if isinstance(v, ast.Constant) and v.value is not None]


def test_no_numbers_for_core_parameters_outside_the_numerics_module() -> None:
    """The grep: no builder call, scene dict or class field gives a core parameter a literal
    value anywhere in the package but ``numerics.py`` and ``bench_cases.py`` (which copies
    DualSPHysics' case files)."""
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        if path.name in ("numerics.py", "bench_cases.py"):
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        found += [f"{path.name}:{v.lineno} {name} = {v.value!r}"
                  for name, v in _literal_settings(tree)]
    assert not found, found


def test_defaults_of_the_core_are_read_not_kept() -> None:
    assert nm.core_default("viscosity.alpha") == _core.scene_defaults()["viscosity"]["alpha"]
    assert ws.DamBreak().core_value("coefh") == nm.core_default("coefh")
    assert ws.DamBreak(coefh=1.3).core_value("coefh") == 1.3


def test_an_option_takes_an_object_a_name_or_a_table() -> None:
    forms = [nm.Laminar(nu=2e-6), {"type": "laminar", "nu": 2e-6}]
    assert {ws.Tank(viscosity=f).viscosity for f in forms} == {nm.Laminar(nu=2e-6)}
    assert ws.Tank(viscosity="laminar").viscosity == nm.Laminar()
    assert ws.Tank(shifting=3.0).shifting == nm.Shifting(coefficient=3.0)
    assert nm.Verlet(euler_every=20).to_core() == {"scheme": "verlet", "euler_every": 20}
    assert nm.Laminar().to_core() == {"model": "laminar"}  # the core's nu


@pytest.mark.parametrize(("value", "key", "reason"), [
    ({"type": "laminar", "alpha": 0.1}, "viscosity.alpha", "not a parameter"),
    ({"type": "artificial", "alpha": -1.0}, "viscosity.alpha", "negative"),
    ({"type": "laminar", "wall_factor": -0.5}, "viscosity.wall_factor", "negative"),
    ({"alpha": 0.1}, "viscosity", "unknown value None"),
    ("lamniar", "viscosity", "did you mean"),
])
def test_bad_options_are_refused_naming_the_dotted_key(value: Any, key: str, reason: str) -> None:
    with pytest.raises(ws.SceneError, match=rf"^{key}: .*{reason}"):
        ws.DamBreak(viscosity=value)


def test_set_changes_one_parameter_of_a_case() -> None:
    b = cli.builder_from_args("dambreak2d", ["viscosity.alpha=0.05", "integrator=verlet",
                                             "integrator.euler_every=30"])
    assert b.viscosity == nm.Artificial(alpha=0.05)
    assert b.integrator == nm.Verlet(euler_every=30)
    # "none" names the model of that name, not the core's default (which is Fourtakas)
    assert cli.builder_from_args("dambreak2d", ["diffusion=none"]).diffusion == nm.NoDiffusion()
    assert cli.builder_from_args("dambreak2d", ["diffusion=auto"]).diffusion is None
    assert "viscosity.nu" in cli.settable_keys("dambreak2d")
    flume = _case_builder("flume2d")
    assert flume.viscosity == nm.Artificial(alpha=nm.FLUME2D_ALPHA)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        laminar = cli.builder_from_args("flume2d", ["viscosity=laminar",
                                                    "viscosity.nu=2e-6"])
    assert laminar.viscosity == nm.Laminar(nu=2e-6)
    with pytest.raises(OverrideError, match=r"^viscosity\.nu: not a parameter of the "
                                            r"viscosity model 'artificial'"):
        cli.builder_from_args("dambreak2d", ["viscosity.nu=2e-6"])
    with pytest.raises(OverrideError, match=r"^integrator\.euler_every: expected an integer"):
        cli.builder_from_args("dambreak2d", ["integrator=verlet", "integrator.euler_every=x"])


def test_the_viscous_wall_factor_is_a_parameter_of_every_viscosity_model() -> None:
    """``wall_factor`` (DualSPHysics' ViscoBoundFactor) reaches the core's scene for each
    model, ``--set`` changes it alone (the case's alpha stays), and the core's default is 1."""
    for cls in nm.VISCOSITIES:
        assert cls(wall_factor=0).to_core()["wall_factor"] == 0.0
        assert "wall_factor" not in cls().to_core()
    assert nm.core_default("viscosity.wall_factor") == 1.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        flume = cli.builder_from_args("flume2d", ["viscosity.wall_factor=0"])
    assert flume.viscosity == nm.Artificial(alpha=nm.FLUME2D_ALPHA, wall_factor=0.0)
    sim = ws.DamBreak(dp=0.05, viscosity=nm.Laminar(wall_factor=0.25)).build()
    assert sim.scene["viscosity"] == {"model": "laminar", "nu": 1e-6, "wall_factor": 0.25}


def test_delta_plus_shifting_is_a_model_of_the_shifting_option() -> None:
    """``shifting.model``: the core's law of that name, its own checks, reached by ``--set``,
    a scene-file table and the builders; left out, the core's (Lind)."""
    assert nm.Shifting().to_core() == {}
    assert nm.core_default("shifting.model") == "lind"
    dp = nm.Shifting(model="delta_plus", coefficient=4.0)
    assert dp.to_core() == {"model": "delta_plus", "coefficient": 4.0}
    sim = ws.Tank(shifting=dp, until=0.01).build()
    assert sim.params()["shifting_model"] == "delta_plus"
    assert sim.scene["shifting"]["model"] == "delta_plus"
    assert ws.Tank(until=0.01).build().params()["shifting_model"] is None
    b = cli.builder_from_args("dambreak2d", ["shifting.model=delta_plus"])
    assert b.shifting == nm.Shifting(model="delta_plus")
    table = sf.loads('type = "tank"\nshifting = { model = "delta_plus" }\n', source="f.toml")
    assert table.builder.shifting == nm.Shifting(model="delta_plus")
    with pytest.raises(ws.SceneError, match=r"^shifting\.model: unknown value 'lnd'.*did you"):
        nm.Shifting(model="lnd")
    with pytest.raises(ws.SceneError, match=r"^shifting\.surface_threshold: belongs to"):
        nm.Shifting(model="delta_plus", surface_threshold=1.5)
    with pytest.raises(ws.SceneError, match=r"^shifting\.surface_threshold: belongs to"):
        _core.Simulation(json.dumps(ws.Tank(until=0.01).to_scene() | {
            "shifting": {"model": "delta_plus", "surface_threshold": 1.5}}))


def _scene_file_round_trip(text: str) -> Any:
    """The builder a scene file's ``text`` loads to, after checking that writing it back and
    loading that gives the same builder."""
    loaded = sf.loads(text, source="f.toml").builder
    assert sf.loads(sf.dumps(loaded), source="g.toml").builder == loaded
    return loaded


def test_tensile_correction_round_trips_and_is_off_by_default() -> None:
    """Monaghan's (2000) tensile correction (``tensile_correction``): off unless set, the
    cubic spline only; through the core, ``--set`` and a scene file and back; an unknown key, a
    bad value and a Wendland kernel refused, naming the key, in Python and in the core."""
    assert nm.TensileCorrection().to_core() == {}
    assert [nm.core_default(f"tensile_correction.{k}")
            for k in ("model", "epsilon_pos", "epsilon_neg")] == ["monaghan", 0.01, 0.2]
    b = ws.Tank(kernel="cubic_spline", tensile_correction=nm.TensileCorrection(epsilon_neg=0.3),
                until=0.01)
    assert b.to_scene()["tensile_correction"] == {"epsilon_neg": 0.3}  # unset values left out
    assert b.resolved_scene()["tensile_correction"] == {
        "model": "monaghan", "epsilon_pos": 0.01, "epsilon_neg": 0.3}
    sim = b.build()
    assert sim.params()["tensile_correction"] == "monaghan"
    assert sim.scene["tensile_correction"]["epsilon_neg"] == 0.3
    plain = ws.Tank(kernel="cubic_spline", until=0.01)
    assert "tensile_correction" not in plain.to_scene()
    assert "tensile_correction" not in plain.resolved_scene()
    assert plain.build().params()["tensile_correction"] is None
    # its forms: the law's name, a table, --set, a scene file (written and read back)
    on = nm.TensileCorrection(model="monaghan")
    assert ws.Tank(kernel="cubic_spline", tensile_correction="monaghan").tensile_correction == on
    assert ws.Tank(kernel="cubic_spline",
                   tensile_correction={"model": "monaghan"}).tensile_correction == on
    on_by_set = cli.builder_from_args("dambreak2d",
                                      ["kernel=cubic_spline", "tensile_correction=monaghan"])
    assert on_by_set.tensile_correction == on
    set_one = cli.builder_from_args("dambreak2d", ["kernel=cubic_spline",
                                                   "tensile_correction.epsilon_neg=0.25"])
    assert set_one.tensile_correction == nm.TensileCorrection(epsilon_neg=0.25)
    assert "tensile_correction.epsilon_pos" in cli.settable_keys("dambreak2d")
    text = ('type = "tank"\nkernel = "cubic_spline"\n'
            'tensile_correction = { model = "monaghan", epsilon_pos = 0.02 }\n')
    loaded = _scene_file_round_trip(text)
    assert loaded.tensile_correction == nm.TensileCorrection(model="monaghan", epsilon_pos=0.02)
    # refusals
    with pytest.raises(ws.SceneError, match=r"^tensile_correction\.eps: not a parameter"):
        ws.Tank(kernel="cubic_spline", tensile_correction={"eps": 0.2})
    with pytest.raises(ws.SceneError, match=r"^tensile_correction: .*cubic_spline"):
        ws.Tank(tensile_correction="monaghan")  # the core's default kernel, Wendland
    with pytest.raises(ws.SceneError, match=r"^tensile_correction\.epsilon_neg: "):
        nm.TensileCorrection(epsilon_neg=-0.2)
    with pytest.raises(ws.SceneError, match=r"^tensile_correction\.model: unknown value"):
        nm.TensileCorrection(model="gray")
    tank = ws.Tank(until=0.01).to_scene()
    for kernel, table, key in (("wendland", {"model": "monaghan"}, "tensile_correction: "),
                               ("cubic_spline", {"eps": 0.2}, "tensile_correction"),
                               ("cubic_spline", {"epsilon_pos": -1.0},
                                "tensile_correction.epsilon_pos")):
        with pytest.raises(ws.SceneError, match=key):
            _core.Simulation(json.dumps(tank | {"kernel": kernel, "tensile_correction": table}))


RIEMANN_COMPANIONS = {"viscosity": "laminar", "diffusion": "none", "integrator": "symplectic"}


def test_riemann_solver_round_trips_and_refuses_what_it_replaces() -> None:
    """The Riemann solver (``riemann``, ``physics/riemann.rs``): off unless set; through the
    core, ``--set`` and a scene file and back; with the artificial viscosity, a density
    diffusion, the Verlet integrator or f32 pair terms refused naming that field, in Python and
    in the core (the defaults of viscosity and diffusion are refused too)."""
    assert [nm.core_default(f"riemann.{k}") for k in ("model", "limiter")] == ["acoustic", 3.0]
    b = ws.Tank(riemann=nm.RiemannSolver(limiter=2.0), until=0.01, **RIEMANN_COMPANIONS)
    assert b.to_scene()["riemann"] == {"limiter": 2.0}
    assert b.resolved_scene()["riemann"] == {"model": "acoustic", "limiter": 2.0}
    sim = b.build()
    assert sim.params()["riemann"] == "acoustic"
    plain = ws.Tank(until=0.01)
    assert "riemann" not in plain.resolved_scene()
    assert plain.build().params()["riemann"] is None
    on = nm.RiemannSolver(model="acoustic")
    assert ws.Tank(riemann="acoustic", **RIEMANN_COMPANIONS).riemann == on
    by_set = cli.builder_from_args("dambreak2d", ["riemann=acoustic", "viscosity=laminar",
                                                  "diffusion=none", "integrator=symplectic"])
    assert by_set.riemann == on
    assert "riemann.limiter" in cli.settable_keys("dambreak2d")
    text = ('type = "tank"\nriemann = { model = "acoustic", limiter = 1.5 }\n'
            'viscosity = "laminar"\ndiffusion = "none"\n')
    loaded = _scene_file_round_trip(text)
    assert loaded.riemann == nm.RiemannSolver(model="acoustic", limiter=1.5)
    # refusals, each naming its field
    with pytest.raises(ws.SceneError, match=r"^viscosity: the Riemann solver"):
        ws.Tank(riemann="acoustic")  # the core's default viscosity is artificial
    with pytest.raises(ws.SceneError, match=r"^diffusion: the Riemann solver"):
        ws.Tank(riemann="acoustic", viscosity="laminar")  # the core's default: fourtakas
    with pytest.raises(ws.SceneError, match=r"^integrator: the Verlet"):
        ws.Tank(riemann="acoustic", viscosity="laminar", diffusion="none", integrator="verlet")
    with pytest.raises(ws.SceneError, match=r"^force_precision: "):
        ws.Tank(riemann="acoustic", force_precision="f32", **RIEMANN_COMPANIONS)
    with pytest.raises(ws.SceneError, match=r"^riemann\.limiter: "):
        nm.RiemannSolver(limiter=-1.0)
    with pytest.raises(ws.SceneError, match=r"^riemann\.model: unknown value"):
        nm.RiemannSolver(model="hllc")
    tank = ws.Tank(until=0.01).to_scene()
    companions = {"viscosity": {"model": "laminar"}, "diffusion": {"model": "none"}}
    for extra, key in (({}, "viscosity: "),
                       ({"viscosity": {"model": "laminar"}}, "diffusion: "),
                       (companions | {"integrator": {"scheme": "verlet"}}, "integrator: "),
                       (companions | {"riemann": {"limiter": -1.0}}, "riemann.limiter"),
                       (companions | {"riemann": {"eta": 3}}, "riemann")):
        with pytest.raises(ws.SceneError, match=key):
            _core.Simulation(json.dumps(tank | {"riemann": {}} | extra))


def test_kernel_correction_round_trips_and_refuses_what_it_cannot_run_with() -> None:
    """The kernel gradient correction (``kernel_correction``, ``physics/kgc.rs``): off unless
    set; through the core, ``--set`` and a scene file; bad values and the options it is not
    combined with refused naming the field, in Python and in the core."""
    assert nm.core_default("kernel_correction.min_eigenvalue") == 0.75
    b = ws.Tank(kernel_correction=nm.KernelCorrection(), until=0.01)
    assert b.to_scene()["kernel_correction"] == {}
    assert b.resolved_scene()["kernel_correction"] == {"min_eigenvalue": 0.75}
    assert b.build().params()["kernel_correction"] == 0.75
    assert ws.Tank(until=0.01).build().params()["kernel_correction"] is None
    by_set = cli.builder_from_args("dambreak2d", ["kernel_correction.min_eigenvalue=0.8"])
    assert by_set.kernel_correction == nm.KernelCorrection(min_eigenvalue=0.8)
    loaded = _scene_file_round_trip('type = "tank"\nkernel_correction = { min_eigenvalue = 0.9 }\n')
    assert loaded.kernel_correction == nm.KernelCorrection(min_eigenvalue=0.9)
    for bad in (0.0, 1.5):
        with pytest.raises(ws.SceneError, match=r"^kernel_correction\.min_eigenvalue: "):
            nm.KernelCorrection(min_eigenvalue=bad)
    with pytest.raises(ws.SceneError, match=r"^force_precision: is not combined"):
        ws.Tank(kernel_correction=nm.KernelCorrection(), force_precision="f32")
    tank = ws.Tank(until=0.01).to_scene()
    for extra, key in (({"kernel_correction": {"min_eigenvalue": 2.0}},
                        "kernel_correction.min_eigenvalue"),
                       ({"kernel_correction": {"lambda": 0.5}}, "kernel_correction"),
                       ({"kernel_correction": {}, "force_precision": "f32"}, "force_precision")):
        with pytest.raises(ws.SceneError, match=key):
            _core.Simulation(json.dumps(tank | extra))


def test_scene_files_take_option_tables_and_set_their_parameters() -> None:
    scene = sf.load(EXAMPLES / "dambreak2d.toml", ["viscosity.alpha=0.03"])
    assert scene.builder.viscosity == nm.Artificial(alpha=0.03)
    with pytest.raises(sf.SceneFileError,
                       match=r"f\.toml: viscosity\.alpha: unknown key for Laminar"):
        sf.loads('type = "tank"\nviscosity = { type = "laminar", alpha = 0.1 }\n',
                 source="f.toml")
    text = sf.dumps(ws.Tank(viscosity=nm.Laminar(nu=2e-6)))
    assert sf.loads(text).builder.viscosity == nm.Laminar(nu=2e-6)


def test_wall_models_are_options_of_their_own() -> None:
    """``boundary`` takes a model's name, object or table like the other options; modified
    DBC's slip mode is sent only when set, and the core fills in its own."""
    assert ws.Tank(boundary="mdbc").boundary == nm.Mdbc()
    assert ws.Tank(boundary={"type": "mdbc", "slip": "no_slip"}).boundary == \
        nm.Mdbc(slip="no_slip")
    assert ws.Tank(boundary="adami").to_scene()["boundary"] == {"model": "adami"}
    assert nm.Mdbc().to_core() == {"model": "mdbc"}
    assert nm.Mdbc(slip="free_slip").to_core() == {"model": "mdbc", "slip": "free_slip"}
    resolved = ws.Tank(boundary="mdbc").resolved_scene()["boundary"]
    assert resolved == {"model": "mdbc", "slip": nm.core_default("boundary.slip")}
    assert nm.core_default("boundary.model") == "dbc"
    with pytest.raises(ws.SceneError, match=r"^boundary\.slip: unknown value 'sticky'"):
        ws.Tank(boundary=nm.Mdbc(slip="sticky"))
    with pytest.raises(ws.SceneError, match=r"^boundary: unknown value 'mirror'"):
        ws.Tank(boundary="mirror")
    b = cli.builder_from_args("dambreak2d", ["boundary=mdbc", "boundary.slip=no_slip"])
    assert b.boundary == nm.Mdbc(slip="no_slip")
    with pytest.raises(OverrideError, match=r"^boundary\.slip: not a parameter of the "
                                            r"boundary model 'dbc'"):
        cli.builder_from_args("dambreak2d", ["boundary.slip=no_slip"])
    assert sf.loads(sf.dumps(ws.Tank(boundary=nm.Mdbc(slip="no_slip")))).builder.boundary == \
        nm.Mdbc(slip="no_slip")


def test_the_low_dissipation_preset_reaches_the_core() -> None:
    """``LOW_DISSIPATION`` (Wendland C4, water's viscosity with free-slip walls, delta 0.05,
    Verlet) is what a flume built with it sends the core."""
    flume = ws.Flume(length=3.0, depth=0.3)
    scene = flume.simulation(ws.RegularWave(height=0.03, period=1.0), dp=0.03, until=0.1,
                             **nm.LOW_DISSIPATION).scene
    resolved = json.loads(_core.resolve_scene(json.dumps(scene)))
    assert resolved["kernel"] == "wendland_c4"
    assert resolved["viscosity"]["model"] == "laminar"
    assert resolved["viscosity"]["wall_factor"] == 0.0
    assert resolved["diffusion"] == {"model": "fourtakas", "delta": 0.05}
    assert resolved["integrator"]["scheme"] == "verlet"
