"""Scene files (TOML): loading, refusals with the key's path, --set, show-scene round trip,
the examples and the generated reference."""

from __future__ import annotations

import dataclasses
import json
import warnings
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from watersim import cli
from watersim import scenefile as sf
from watersim.flume import FlumeScene, TabulatedMotion
from watersim.numerics import NoDiffusion
from watersim.scenes import DamBreak, Tank

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"

FLUME = """
type = "flume"
dp = 0.05
until = 1.0

[flume]
length = 4.0
depth = 0.3

[flume.beach]
type = "plane"
toe = 1.5
slope = 0.2

[wave]
type = "regular"
height = 0.05
period = 1.2

[paddle]
type = "piston"
order = 2

[[gauges]]
type = "elevation"
x = 1.0

[[gauges]]
type = "velocity"
points = [[1.0, 0.1], [1.0, 0.2]]

[output]
snapshot_every = 0.25
"""


def _scene_json(builder: object) -> str:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return json.dumps(builder.to_scene(), sort_keys=True)  # type: ignore[attr-defined]


def test_flume_file_gives_the_objects_it_describes() -> None:
    scene = sf.loads(FLUME, source="f.toml")
    b = scene.builder
    assert isinstance(b, FlumeScene)
    assert b.flume.length == 4.0 and b.flume.beach.slope == 0.2  # type: ignore[union-attr]
    assert b.paddle.order == 2 and b.wave.height == 0.05  # type: ignore[union-attr]
    assert b.gauges[1].points == ((1.0, 0.1), (1.0, 0.2))  # type: ignore[union-attr]
    assert scene.output == sf.OutputOptions(snapshot_every=0.25)
    # the same scene as the Python builders make
    import watersim as ws

    direct = ws.Flume(length=4.0, depth=0.3, beach=ws.PlaneBeach(toe=1.5, slope=0.2)).scene(
        ws.RegularWave(height=0.05, period=1.2), paddle=ws.Piston(order=2), dp=0.05, until=1.0,
        gauges=[ws.ElevationGauge(1.0), ws.VelocityProbe(((1.0, 0.1), (1.0, 0.2)))])
    assert _scene_json(b) == _scene_json(direct)


@pytest.mark.parametrize(
    ("old", "new", "path", "reason"),
    [
        ("height = 0.05", "hieght = 0.05", "wave.hieght", "unknown key"),
        ("x = 1.0", 'x = "1.0"', "gauges[0].x", "expected a number, got a string"),
        ("x = 1.0", "x = nan", "gauges[0].x", "finite"),
        ("x = 1.0", "x = 9.0", "gauges[0].x", "outside the flume"),
        ("dp = 0.05", "dp = true", "dp", "expected a number, got a boolean"),
        ("dp = 0.05", "dp = -0.05", "dp", "must be positive"),
        ("order = 2", "order = 2.0", "paddle.order", "expected an integer"),
        ("order = 2", "order = 3", "paddle.order", "must be 1 or 2"),
        ('type = "regular"', 'type = "regulr"', "wave.type", "unknown value 'regulr'"),
        ('type = "plane"\n', "", "flume.beach.type", "required"),
        ("toe = 1.5", "toe = 9.0", "flume.beach.toe", "beyond the flume"),
        ("slope = 0.2", "slope = [0.2]", "flume.beach.slope", "got an array"),
        ("length = 4.0", "", "flume.length", "required"),
        ("[flume]", "bogus = 1\n[flume]", "bogus", "unknown key for FlumeScene"),
        ("points = [[1.0, 0.1], [1.0, 0.2]]", 'points = [[1.0, 0.1], [1.0, "z"]]',
         "gauges[1].points[1][1]", "expected a number"),
        ("snapshot_every = 0.25", "snapshot_every = 0", "output.snapshot_every", "positive"),
        ("snapshot_every = 0.25", "snapshots = 1", "output.snapshots", "unknown key"),
        ('type = "flume"', 'type = "ship"', "type", "unknown value 'ship'"),
    ],
)
def test_bad_scene_files_name_the_key_path(old: str, new: str, path: str, reason: str) -> None:
    assert old in FLUME
    with pytest.raises(sf.SceneFileError) as info:
        sf.loads(FLUME.replace(old, new, 1), source="f.toml")
    message = str(info.value)
    assert message.startswith(f"f.toml: {path}: "), message
    assert reason in message, message


def test_dambreak_and_tank_files_refuse_like_their_builders() -> None:
    with pytest.raises(sf.SceneFileError, match=r"t.toml: tank_width: only used in 3D"):
        sf.loads('type = "dambreak"\ntank_width = 0.5\n', source="t.toml")
    with pytest.raises(sf.SceneFileError, match=r"t.toml: depth: wrong type: expected a number"):
        sf.loads('type = "tank"\ndepth = "deep"\n', source="t.toml")
    with pytest.raises(sf.SceneFileError, match=r"t.toml: not valid TOML"):
        sf.loads('type = "tank\n', source="t.toml")
    assert isinstance(sf.loads('type = "tank"\ndim = 3\n').builder, Tank)


def test_cli_refuses_bad_files_with_exit_2_before_running(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    bad = tmp_path / "bad.toml"
    out = tmp_path / "out"
    for mutation, needles in [
        (("height = 0.05", "hieght = 0.05"), ("bad.toml: wave.hieght: unknown key", "valid keys")),
        (("x = 1.0", 'x = "one"'), ("bad.toml: gauges[0].x: wrong type", "got a string")),
    ]:
        bad.write_text(FLUME.replace(*mutation))
        assert cli.main(["run", str(bad), "--out", str(out)]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and all(n in err for n in needles), err
        assert not out.exists()
    assert cli.main(["run", str(tmp_path / "missing.toml")]) == 2
    assert "missing.toml: no such scene file" in capsys.readouterr().err


def test_set_overrides_a_scene_file() -> None:
    settings = [
        "wave.height=0.06",
        "gauges[0].x=1.2",
        "flume.beach.slope=0.25",
        "flume.damping.length=0.5",
        "h_swl=0.3",
        "output.sample_every=0.5",
        "paddle.ramp=tanh",
    ]
    scene = sf.loads(FLUME, settings, source="f.toml")
    b = scene.builder
    assert isinstance(b, FlumeScene)
    assert b.wave.height == 0.06 and b.gauges[0].x == 1.2  # type: ignore[union-attr]
    assert b.flume.beach.slope == 0.25 and b.flume.damping.length == 0.5  # type: ignore[union-attr]
    assert b.h_swl == 0.3 and b.paddle.ramp == "tanh"
    assert scene.output.sample_every == 0.5 and scene.output.snapshot_every == 0.25
    # `none` removes an optional field (its default again); a string field keeps the word
    assert sf.loads(FLUME, ["h_swl=0.3", "h_swl=none"]).builder.h_swl is None
    assert sf.loads(FLUME, ["diffusion=none"]).builder.diffusion == NoDiffusion()


def test_set_errors_name_the_key() -> None:
    with pytest.raises(sf.SceneFileError, match=r"wave\.hieght: unknown key"):
        sf.loads(FLUME, ["wave.hieght=1"], source="f.toml")
    with pytest.raises(sf.SceneFileError, match=r"gauges\[9\]: no such item \(2 in the file\)"):
        sf.loads(FLUME, ["gauges[9].x=1"], source="f.toml")
    with pytest.raises(sf.SceneFileError, match=r"dp: wrong type: expected a number, got a "
                                                r"string \('fine'\)"):
        sf.loads(FLUME, ["dp=fine"], source="f.toml")
    with pytest.raises(sf.SceneFileError, match=r"expected key=value"):
        sf.loads(FLUME, ["dp"], source="f.toml")


def test_switching_wave_type_with_set_is_checked() -> None:
    with pytest.raises(sf.SceneFileError, match=r"wave\.height: unknown key for IrregularWave"):
        sf.loads(FLUME, ["wave.type=irregular", "wave.hs=0.04", "wave.tp=1.2"])


@pytest.mark.parametrize("case", cli.ALL_CASES)
def test_show_scene_round_trip_gives_the_same_core_scene(
    case: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert cli.main(["show-scene", case]) == 0
    text = capsys.readouterr().out
    path = tmp_path / f"{case}.toml"
    path.write_text(text)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # stansby2d's wave is beyond Stokes 2nd order: warned
        assert cli.main(["show-scene", "--json", case]) == 0
        direct = json.loads(capsys.readouterr().out)
        assert cli.main(["show-scene", "--json", str(path)]) == 0
        from_file = json.loads(capsys.readouterr().out)
        # and the builder objects are equal field by field
        assert sf.load(path).builder == cli.builder_from_args(case, [])
    assert from_file == direct


def test_scene_is_a_deprecated_alias_of_show_scene_json(
    capsys: pytest.CaptureFixture[str]
) -> None:
    assert cli.main(["show-scene", "--json", "dambreak2d", "--set", "dp=0.04"]) == 0
    shown = capsys.readouterr()
    assert "deprecated" not in shown.err
    assert cli.main(["scene", "dambreak2d", "--set", "dp=0.04"]) == 0
    alias = capsys.readouterr()
    assert alias.out == shown.out and json.loads(alias.out)["scene"]["dp"] == 0.04
    assert "`watersim scene` is deprecated" in alias.err and "show-scene --json" in alias.err
    assert cli.main(["show-scene", "--reference", "--json"]) == 2
    assert "--reference: takes no CASE, --set or --json" in capsys.readouterr().err


def test_show_scene_applies_set_and_refuses_bad_input(capsys: pytest.CaptureFixture[str]) -> None:
    assert cli.main(["show-scene", "dambreak2d", "--set", "dp=0.04"]) == 0
    text = capsys.readouterr().out
    assert "dp = 0.04" in text and "# watersim show-scene dambreak2d --set dp=0.04" in text
    assert cli.main(["show-scene"]) == 2
    assert "CASE: required" in capsys.readouterr().err
    assert cli.main(["show-scene", "nosuchcase"]) == 2
    assert "unknown case" in capsys.readouterr().err


def test_written_files_keep_every_kind_of_object() -> None:
    import watersim as ws

    scene = ws.Flume(length=3.0, depth=0.3, width=0.3, damping=False,
                     beach=ws.ProfileBeach(x=(1.5, 3.0), z=(0.0, 0.45))).scene(
        ws.TabulatedMotion(t=(0.0, 1.0, 2.0), x=(0.0, 0.02, 0.0)), paddle=ws.Flap(hinge_z=0.05),
        dp=0.05, until=0.5,
        gauges=[ws.ElevationGauge(1.0, y=0.1, method="particle", name="g1", interval=0.05),
                ws.VelocityWindow(min=(0.5, 0.1, 0.05), max=(1.0, 0.1, 0.25), n=(3, 1, 2))],
        runup=ws.RunupGauge(method="particle"))
    back = sf.loads(sf.dumps(scene, sf.OutputOptions(directory="x", snapshot_every=0.1)))
    assert back.builder == scene
    assert back.output == sf.OutputOptions(directory="x", snapshot_every=0.1)
    assert isinstance(back.builder.wave, TabulatedMotion)  # type: ignore[union-attr]


@pytest.mark.parametrize("path", sorted(EXAMPLES.glob("*.toml")), ids=lambda p: p.name)
def test_example_files_load_and_make_a_core_scene(path: Path) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        scene = sf.load(path)
        sim = scene.builder.build()
    assert sim.n_fluid > 0
    assert scene.name == path.stem


def test_examples_cover_the_required_cases() -> None:
    names = {p.name for p in EXAMPLES.glob("*.toml")}
    assert {"flume2d.toml", "dambreak2d.toml", "kimmoun2d.toml"} <= names
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for case in ("kimmoun2d", "dambreak2d"):
            # as the core runs them: the file may write out a core default the case leaves out
            from_file = sf.load(EXAMPLES / f"{case}.toml").builder
            assert from_file.resolved_scene() == cli.builder_from_args(case, []).resolved_scene()
    assert isinstance(sf.load(EXAMPLES / "dambreak2d.toml").builder, DamBreak)


def test_committed_reference_matches_the_code() -> None:
    committed = (ROOT / "docs" / "scene-reference.md").read_text(encoding="utf-8")
    assert committed == sf.reference_markdown(), (
        "docs/scene-reference.md is out of date: regenerate it with "
        "`python3 -m watersim.scenefile --reference > docs/scene-reference.md`"
    )


def test_reference_lists_every_field_of_every_table() -> None:
    text = sf.reference_markdown()
    for _, _, cls, skip in sf._sections():
        for f in dataclasses.fields(cls):
            if f.init and f.name not in skip:
                assert f"| `{f.name}` |" in text, (cls.__name__, f.name)
    for tag in sf.TAGS.values():
        assert f'type = "{tag}"' in text


# any TOML value: scalars (absurd numbers included), arrays and tables
toml_values = st.recursive(
    st.one_of(
        st.booleans(),
        st.integers(-10**6, 10**6),
        st.floats(allow_nan=True, allow_infinity=True),
        st.sampled_from([0.0, -1.0, 1e-300, 1e300, 0.5, 2.0]),
        st.text(max_size=8),
        st.sampled_from(["regular", "plane", "piston", "elevation", "none", "velocity"]),
    ),
    lambda inner: st.one_of(st.lists(inner, max_size=3),
                            st.dictionaries(st.sampled_from(["type", "x", "height", "n", "bogus"]),
                                            inner, max_size=3)),
    max_leaves=6,
)


def _paths(node: object, prefix: tuple = ()) -> list[tuple]:
    """Every key path and array index of a parsed TOML document."""
    out = [prefix] if prefix else []
    if isinstance(node, dict):
        for k, v in node.items():
            out += _paths(v, (*prefix, k))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            out += _paths(v, (*prefix, i))
    return out


@settings(max_examples=150, deadline=None)
@given(data=st.data(), value=toml_values)
def test_any_value_anywhere_is_accepted_or_refused_with_its_path(data: st.DataObject,
                                                                   value: object) -> None:
    import tomllib

    doc = tomllib.loads(FLUME)
    path = data.draw(st.sampled_from(_paths(doc) + [("extra",), ("wave", "extra")]))
    node = doc
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value  # type: ignore[index]
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # a valid but steep wave warns
            scene = sf.scene_from_dict(doc, source="f.toml")
            scene.builder.to_scene()
    except sf.SceneFileError as exc:
        message = str(exc)
        assert message.startswith("f.toml: ") and ": " in message[len("f.toml: "):], message
        assert "\n" not in message
