"""Refusals blame the field that causes them and stay readable (issue 33 item 11): a huge
``coefh`` or ``boundary_layers`` is refused naming it, not ``dp``; extreme numbers are written
short (a dp of 1e-300 is not 300 characters); a stopped run's "run stopped:" line always says
why."""

from __future__ import annotations

import json
import re
from typing import Any

from hypothesis import given, settings
from hypothesis import strategies as st

import watersim as ws
from conftest import run_cli
from watersim import _core
from watersim.cli import _stop_message

GIB = 1024**3


def _scene(**extra: Any) -> str:
    scene: dict[str, Any] = {"dim": 2, "dp": 0.05, "tank": {"min": [0, 0], "max": [4, 3]},
                             "fluid": [{"min": [0, 0], "max": [1, 2]}],
                             "memory_limit_bytes": 4 * GIB}
    scene.update(extra)
    return json.dumps(scene)


def _refusal(scene: str) -> str:
    try:
        _core.Simulation(scene)
    except ws.SceneError as exc:
        return str(exc)
    raise AssertionError("accepted")


def _longest_number(text: str) -> int:
    return max((len(m) for m in re.findall(r"[0-9.]+", text)), default=0)


@settings(max_examples=30, deadline=None)
@given(st.floats(min_value=2e3, max_value=1e12))
def test_a_huge_coefh_is_blamed_for_its_walls(coefh: float) -> None:
    message = _refusal(_scene(coefh=coefh))
    assert message.startswith("coefh:"), message
    assert "GiB" in message and "wall layers" in message


@settings(max_examples=30, deadline=None)
@given(st.integers(min_value=10**5, max_value=10**15))
def test_huge_boundary_layers_are_blamed(layers: int) -> None:
    message = _refusal(_scene(boundary_layers=layers))
    assert message.startswith("boundary_layers:"), message
    assert "the support needs" in message


@settings(max_examples=30, deadline=None)
@given(st.floats(min_value=1e-300, max_value=1e-5))
def test_a_tiny_dp_is_blamed_and_written_short(dp: float) -> None:
    message = _refusal(_scene(dp=dp))
    assert message.startswith("dp:"), message
    assert _longest_number(message) <= 24 and len(message) < 400, message


@settings(max_examples=40, deadline=None)
@given(st.sampled_from(["coefsound", "gravity", "rho0", "cfl", "coefh", "density_band",
                        "h_swl", "energy_growth_limit"]),
       st.sampled_from([1e-300, -1e-300, 1e300, -1e300, 5e-324]))
def test_extreme_values_are_written_short(field: str, value: float) -> None:
    try:
        _core.Simulation(_scene(**{field: value}))
    except ws.SceneError as exc:
        message = str(exc)
        assert _longest_number(message) <= 24 and len(message) < 400, message
    except ws.InstabilityError:
        pass


def test_cli_names_coefh_and_boundary_layers_not_dp(tmp_path: Any) -> None:
    for setting, field in (("coefh=1e6", "coefh"), ("boundary_layers=100000000",
                                                    "boundary_layers")):
        proc = run_cli("run", "dambreak2d", "--set", setting, "--out", str(tmp_path / field))
        assert proc.returncode == 2, proc.stderr
        assert f"error: {field}:" in proc.stderr, proc.stderr
    proc = run_cli("run", "dambreak2d", "--set", "dp=1e-300", "--out", str(tmp_path / "dp"))
    assert proc.returncode == 2 and "dp" in proc.stderr
    assert len(proc.stderr) < 400 and _longest_number(proc.stderr) <= 24, proc.stderr


@given(st.fixed_dictionaries({}, optional={
    "type": st.one_of(st.none(), st.text(max_size=20),
                      st.sampled_from(["KeyboardInterrupt", "TerminatedError", "OSError"])),
    "message": st.one_of(st.none(), st.text(max_size=20)),
    "kind": st.one_of(st.none(), st.sampled_from(["non_finite", "energy_growth"])),
    "step": st.integers(0, 10**6),
}))
def test_run_stopped_always_says_why(error: dict[str, Any]) -> None:
    assert _stop_message(error).strip()
