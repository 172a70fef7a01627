"""Every built-in case and every ``examples/*.toml`` builds the same core scene as recorded in
``tests/data/scene_golden.json`` (recorded from main at 1b66fb8, before the "one home per model"
refactor): the refactor moves code, not numbers.

Scenes are compared as the core resolves them (``watersim._core.resolve_scene``: every default
filled in by the core), so a key the Python side stops sending because the core's default is the
same value compares equal, and a changed default anywhere does not.

Numbers are compared to 1e-12 relative: the wave laws' coefficients come from numpy and scipy
(root finding, FFTs), whose builds differ in the last bit from one install to the next; that is not
a change of case. Everything else (keys, models, integers, strings) compares exactly.

Rewrite the record (only for an intended change of a case, said in the commit):
``python3 tests/test_scene_golden.py --write``.
"""

from __future__ import annotations

import json
import math
import sys
import warnings
from pathlib import Path
from typing import Any

import pytest

from watersim import _core
from watersim.bench_cases import DSPH_CASES, dsph_scene
from watersim.cli import ALL_CASES, builder_from_args

ROOT = Path(__file__).resolve().parents[1]
GOLDEN = ROOT / "tests" / "data" / "scene_golden.json"
EXAMPLES = sorted((ROOT / "examples").glob("*.toml"))
BARE_SCENE: dict[str, Any] = {"dim": 2, "dp": 0.1, "tank": {"min": [0, 0], "max": [2, 1]},
                              "fluid": [{"min": [0, 0], "max": [1, 0.5]}]}
"""The keys a scene must have; the core fills in the rest."""


def _case_names() -> list[str]:
    return [*ALL_CASES, *DSPH_CASES, *(f"examples/{p.name}" for p in EXAMPLES)]


def core_scene(name: str) -> dict[str, Any]:
    """The core's resolved scene of a built-in case, a DualSPHysics bench case or a scene file."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # wave-validity warnings of some cases
        if name in DSPH_CASES:
            scene = dsph_scene(name)
        elif name.startswith("examples/"):
            scene = builder_from_args(str(ROOT / name), []).to_scene()
        else:
            scene = builder_from_args(name, []).to_scene()
    return json.loads(_core.resolve_scene(json.dumps(scene)))


REL_TOL = 1e-12
"""Relative tolerance on floats: library builds move the last bit (see the module docstring)."""


def differences(got: Any, want: Any, path: str = "") -> list[str]:
    """Paths where ``got`` differs from ``want``: floats beyond ``REL_TOL``, anything else at
    all."""
    if isinstance(got, dict) and isinstance(want, dict):
        out = [f"{path}/{k}: missing" for k in sorted(set(want) - set(got))]
        out += [f"{path}/{k}: not recorded" for k in sorted(set(got) - set(want))]
        for k in sorted(set(got) & set(want)):
            out += differences(got[k], want[k], f"{path}/{k}")
        return out
    if isinstance(got, list) and isinstance(want, list):
        if len(got) != len(want):
            return [f"{path}: {len(got)} items, recorded {len(want)}"]
        pairs = enumerate(zip(got, want, strict=True))
        return [d for i, (g, w) in pairs for d in differences(g, w, f"{path}[{i}]")]
    if (isinstance(got, float) and isinstance(want, (int, float)) and not isinstance(want, bool)
            and math.isclose(got, want, rel_tol=REL_TOL, abs_tol=1e-300)):
        return []
    return [] if got == want and type(got) is type(want) else [f"{path}: {got!r} != {want!r}"]


def test_differences_compares_floats_to_the_tolerance_only() -> None:
    assert differences({"a": [1.0, "x"]}, {"a": [1.0 + 1e-15, "x"]}) == []
    assert differences({"a": 1.0}, {"a": 1.0 + 1e-9}) == ["/a: 1.0 != 1.000000001"]
    assert differences({"a": 1}, {"a": 2}) == ["/a: 1 != 2"]
    assert differences({"a": True}, {"a": 1}) == ["/a: True != 1"]
    assert differences({"a": [1]}, {"a": [1, 2]}) == ["/a: 1 items, recorded 2"]
    assert differences({"b": 1}, {"a": 1}) == ["/a: missing", "/b: not recorded"]


@pytest.fixture(scope="module")
def golden() -> dict[str, Any]:
    return json.loads(GOLDEN.read_text())


def test_every_case_is_recorded(golden: dict[str, Any]) -> None:
    assert sorted(golden) == sorted(_case_names())


@pytest.mark.parametrize("name", _case_names())
def test_case_builds_the_recorded_core_scene(name: str, golden: dict[str, Any]) -> None:
    diffs = differences(core_scene(name), golden[name])
    assert not diffs, f"{len(diffs)} differences: " + "; ".join(diffs[:10])


def test_resolution_fills_the_cores_defaults() -> None:
    """The comparison above is only as strict as the resolution: a bare scene gets every
    default, and the defaults are the ones the core runs with."""
    bare = BARE_SCENE
    resolved = json.loads(_core.resolve_scene(json.dumps(bare)))
    assert resolved["viscosity"] == {"model": "artificial", "alpha": 0.01, "wall_factor": 1.0}
    assert resolved["diffusion"] == {"model": "fourtakas", "delta": 0.1}
    assert resolved["cfl"] == 0.2
    with pytest.raises(_core.SceneError, match="dp"):
        _core.resolve_scene(json.dumps({**bare, "dp": -1.0}))


def test_scene_defaults_are_what_the_core_fills_in() -> None:
    """``scene_defaults()`` is the core's own table: a bare scene resolves to it, key by key,
    and a model named by its tag alone takes its parameters from it."""
    defaults = _core.scene_defaults()
    bare = BARE_SCENE
    resolved = json.loads(_core.resolve_scene(json.dumps(bare)))
    for key, value in defaults.items():
        if not isinstance(value, dict):
            assert resolved[key] == value, key
    assert resolved["boundary"] == {"model": defaults["boundary"]["model"]}
    assert resolved["viscosity"] == {"model": defaults["viscosity"]["model"], **{
        k: defaults["viscosity"][k] for k in ("alpha", "wall_factor")}}
    sps = json.loads(_core.resolve_scene(json.dumps(
        {**bare, "viscosity": {"model": "laminar_sps"}, "integrator": {"scheme": "verlet"}})))
    assert sps["viscosity"] == {"model": "laminar_sps", **{
        k: defaults["viscosity"][k] for k in ("nu", "cs", "ci", "wall_factor")}}
    assert sps["integrator"]["euler_every"] == defaults["integrator"]["euler_every"]


def test_params_come_from_the_cores_params() -> None:
    bare = BARE_SCENE
    params = _core.Simulation(json.dumps(bare)).params()
    assert params["kernel"] == "wendland" and params["shifting"] is None
    assert params["boundary_layers"] == 3 and isinstance(params["n_cells"], int)
    assert params["h"] == 0.1 * 2 ** 0.5


if __name__ == "__main__" and sys.argv[1:] == ["--write"]:
    rows = [f"{json.dumps(n)}: {json.dumps(core_scene(n), sort_keys=True)}"
            for n in sorted(_case_names())]
    GOLDEN.write_text("{\n" + ",\n".join(rows) + "\n}\n")  # one case a line: diffs name the case
    print(f"written: {GOLDEN}")
