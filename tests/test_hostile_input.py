"""Hostile or careless input refused with a named error and exit 2, never a traceback or a hang
(issue 33 items 6, 8, 9, 10 and 13)."""

from __future__ import annotations

import copy
import json
import math
import os
from pathlib import Path

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

import watersim as ws
from watersim import cli, overrides, stress
from watersim import scenefile as sf
from watersim.checkpoint import check_state, load_checkpoint, save_checkpoint

DAMBREAK = Path(__file__).resolve().parents[1] / "examples" / "dambreak2d.toml"


def _scene_text(directory: str) -> str:
    """A tiny dam break's scene file writing into ``directory``."""
    return sf.dumps(ws.DamBreak(dim=2, dp=0.1, until=0.01), sf.OutputOptions(directory=directory))


def _refused(argv: list[str], capsys: pytest.CaptureFixture[str], *needles: str) -> str:
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1, err
    for needle in needles:
        assert needle in err, err
    return err


# item 8: nested TOML, huge integers, NUL bytes, --from-json, malformed meshes


@settings(max_examples=6, deadline=None)
@given(depth=st.integers(min_value=1000, max_value=5000), array=st.booleans())
def test_deeply_nested_toml_is_refused(depth: int, array: bool) -> None:
    value = "[" * depth + "]" * depth if array else "{a = " * depth + "1" + "}" * depth
    with pytest.raises(ws.SceneError, match="nested too deeply|not valid TOML"):
        sf.loads(f"v = {value}\n", source="deep.toml")


@settings(max_examples=6, deadline=None)
@given(digits=st.integers(min_value=4301, max_value=20000))
def test_huge_integers_are_refused_in_files_and_in_set(digits: int) -> None:
    with pytest.raises(ws.SceneError, match="not valid TOML") as info:
        sf.loads(f"dp = {'1' * digits}\n", source="big.toml")
    assert len(str(info.value)) < 300
    with pytest.raises(ws.SceneError):
        sf.load(DAMBREAK, [f"dp={'1' * digits}"])


def test_nul_bytes_in_paths_are_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                        monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ws.SceneError, match="NUL byte"):
        sf.load("a\0b.toml")
    _refused(["run", "tank2d", "--out", "a\0b"], capsys, "NUL byte")
    scene = tmp_path / "s.toml"
    scene.write_text(_scene_text("x\0y"))
    _refused(["run", str(scene)], capsys, "NUL byte")


def test_from_json_on_a_list_of_non_objects(tmp_path: Path,
                                            capsys: pytest.CaptureFixture[str]) -> None:
    runs = tmp_path / "runs.json"
    runs.write_text(json.dumps([{"case": "x"}, 3, "a"]))
    _refused(["validate", "--from-json", str(runs), "--report", str(tmp_path / "r")], capsys,
             "does not hold a list of runs")


def test_a_malformed_vtu_mesh_is_a_scene_error(tmp_path: Path) -> None:
    from watersim.meshbed import read_triangle_mesh

    for text in ("not a mesh", '<VTKFile type="UnstructuredGrid"><Piece/></VTKFile>'):
        mesh = tmp_path / "bed.vtu"
        mesh.write_text(text)
        with pytest.raises(ws.SceneError, match="cannot read"):
            read_triangle_mesh(mesh)


# item 9: special scene files, absurd thread counts, long --set keys


@pytest.mark.parametrize("kind", ["fifo", "zero_link", "folder"])
def test_a_scene_file_that_is_not_a_regular_file(kind: str, tmp_path: Path,
                                                 capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "s.toml"
    if kind == "fifo":
        os.mkfifo(path)
    elif kind == "zero_link":
        path.symlink_to("/dev/zero")
    else:
        path.mkdir()
    _refused(["run", str(path), "--out", str(tmp_path / "o")], capsys, "not a regular file")


def test_absurd_thread_counts_are_refused(capsys: pytest.CaptureFixture[str]) -> None:
    _refused(["bench", "--compare-threads", "1,100000"], capsys, "--compare-threads", "at most")


@settings(max_examples=5, deadline=2000)
@given(levels=st.integers(min_value=17, max_value=20000))
def test_long_set_keys_are_refused_at_once(levels: int) -> None:
    key = ".".join(["a"] * levels)
    with pytest.raises(overrides.OverrideError, match="key too long"):
        overrides.Override.parse(f"{key}=1").path()
    with pytest.raises(ws.SceneError, match="key too long"):
        sf.load(DAMBREAK, [f"{key}=1"])


# item 6: a scene file's output folder stays under the working directory


@pytest.mark.parametrize("directory", ["../elsewhere", "/tmp/elsewhere", "a/../../b"])
def test_a_scene_files_output_folder_stays_under_the_working_directory(
        directory: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
        capsys: pytest.CaptureFixture[str]) -> None:
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    scene = work / "s.toml"
    scene.write_text(_scene_text(directory))
    _refused(["run", str(scene)], capsys,
             "outside the working directory", "--out")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["work"]
    # --out, given on the command line, writes anywhere
    out = tmp_path / "elsewhere"
    assert cli.main(["run", str(scene), "--out", str(out)]) == 0
    assert str(out.resolve()) in capsys.readouterr().out


# item 10: inconsistent checkpoints


def _state_and_sim() -> tuple[dict, ws.Simulation]:  # type: ignore[type-arg]
    sim = ws.DamBreak(dim=2, dp=0.1).build()
    sim.step(2)
    return sim.core.checkpoint(), ws.DamBreak(dim=2, dp=0.1).build()


@pytest.mark.parametrize(("change", "needle"), [
    (lambda s: s["ids"].__setitem__(1, s["ids"][0]), "duplicate particle ids"),
    (lambda s: s["kinds"].__setitem__(0, 9), "unknown particle kinds"),
    (lambda s: s.__setitem__("time", float("nan")), "time"),
    (lambda s: s.__setitem__("dt", float("inf")), "dt"),
    (lambda s: s.__setitem__("n_excluded", 10**6), "n_excluded"),
    (lambda s: s.__setitem__("energy0", (float("nan"), 1.0)), "energy0"),
])
def test_inconsistent_states_are_refused(change, needle: str) -> None:  # type: ignore[no-untyped-def]
    state, sim = _state_and_sim()
    check_state(state, sim)
    bad = copy.deepcopy(state)
    change(bad)
    with pytest.raises(ws.SceneError, match=f"inconsistent state: .*{needle}"):
        check_state(bad, sim)


def test_gauge_records_with_fewer_values_than_times_are_refused() -> None:
    state, sim = _state_and_sim()
    gauge = {"t": np.arange(3.0), "values": np.arange(2.0), "next_time": 1.0}
    with pytest.raises(ws.SceneError, match="gauge 0 has 2 values for 3 times"):
        check_state({**state, "gauges": [gauge]}, sim)
    with pytest.raises(ws.SceneError, match="next_time"):
        check_state({**state, "gauges": [{**gauge, "values": np.arange(3.0),
                                          "next_time": -np.inf}]}, sim)


@pytest.mark.parametrize("content", [b"", b"not a zip", None])
def test_files_that_are_not_checkpoints_raise_scene_error(content: bytes | None,
                                                          tmp_path: Path) -> None:
    path = tmp_path / "c.npz"
    if content is None:  # an archive without the checkpoint's arrays
        np.savez(path, scene_json=np.asarray("{}"))
    else:
        path.write_bytes(content)
    with pytest.raises(ws.SceneError, match="checkpoint"):
        load_checkpoint(path)


def test_a_saved_checkpoint_still_loads(tmp_path: Path) -> None:
    sim = ws.DamBreak(dim=2, dp=0.1).build()
    sim.step(3)
    save_checkpoint(sim, tmp_path / "c.npz")
    assert load_checkpoint(tmp_path / "c.npz").steps == 3


# item 13


def test_stress_exits_1_when_a_run_times_out(monkeypatch: pytest.MonkeyPatch,
                                             tmp_path: Path) -> None:
    spec = stress.quick_matrix()[0]

    def timed_out(specs, jobs, progress, on_record):  # type: ignore[no-untyped-def]
        record = stress._base_record(spec)
        record.update(status="timeout", wall_s=1.0)
        return [record]

    monkeypatch.setattr(stress, "run_matrix", timed_out)
    assert cli.main(["stress", "--quick", "--quiet", "--group", spec.group]) == 1


def test_an_absurd_coefsound_is_warned_about(capsys: pytest.CaptureFixture[str],
                                             tmp_path: Path) -> None:
    with pytest.warns(UserWarning, match="coefsound = 1e\\+10"):
        ws.DamBreak(dim=2, dp=0.1, coefsound=1e10)
    assert cli.main(["show-scene", "dambreak2d", "--set", "coefsound=1e10"]) == 0


@settings(max_examples=30, deadline=None)
@given(until=st.floats(min_value=1e-300, max_value=1e6),
       time=st.floats(min_value=0.0, max_value=1e6))
def test_the_next_progress_report_is_found_at_once(until: float, time: float) -> None:
    """A run says how far it is every tenth of its end time; the next report time comes from
    a division, not a count (an until of 1e-300 took 1e297 additions: the sweep's one hang)."""
    following = cli.next_report_time(time, until)
    assert following > time
    assert following <= time + until / 10.0 * (1 + 1e-9) or following == math.nextafter(
        time, math.inf)


def test_a_tiny_until_runs_and_ends(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    code = cli.main(["run", "dambreak2d", "--set", "dp=0.1", "--set", "until=1e-300", "--quiet",
                     "--out", str(tmp_path / "o")])
    assert code == 0, capsys.readouterr().err


@settings(max_examples=5, deadline=None)
@given(levels=st.integers(min_value=17, max_value=20000))
def test_any_long_set_key_is_refused_quoting_its_start(levels: int) -> None:
    from watersim.builtin_cases import builder_from_args
    from watersim.errors import CliError

    key = ".".join(["a"] * levels)
    for case in ("dambreak2d", "flume2d"):
        with pytest.raises(CliError, match="--set: key too long") as info:
            builder_from_args(case, [f"{key}=1"])
        assert len(str(info.value)) < 300


@settings(max_examples=50, deadline=None)
@given(k=st.integers(0, 10**6), every=st.floats(1e-6, 10.0),
       time=st.floats(0.0, 1e300, allow_subnormal=False))
@example(k=0, every=4.5, time=3.982928839205582e16)  # the quotient rounds up past the stop
def test_the_next_sample_stop_is_found_at_once(k: int, every: float, time: float) -> None:
    """The run's next stop after a step far past its sample times (gravity = 1e-300 gave one
    step of 1e147 s: 1e149 additions) is the first ``t0 + k every`` beyond the time."""
    from watersim.simulation import _next_stop

    nxt = _next_stop(k, 0.0, every, time)
    assert nxt > k and nxt * every > time
    if nxt > k + 1 and (nxt - 1) * every != nxt * every:  # the minimal one, where resolved
        assert (nxt - 1) * every <= time


def test_one_step_far_past_the_end_ends_the_run(tmp_path: Path,
                                               capsys: pytest.CaptureFixture[str]) -> None:
    code = cli.main(["run", "dambreak2d", "--set", "dp=0.1", "--set", "gravity=1e-300",
                     "--set", "until=0.02", "--quiet", "--out", str(tmp_path / "o")])
    assert code == 0, capsys.readouterr().err
