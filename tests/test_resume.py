"""A flume run's folder: scene.toml and checkpoints, ``watersim resume`` (bit-identical to an
uninterrupted run, also after kill -9), ``watersim analyse``, ``watersim.load`` and the
refusals of a folder that cannot be resumed."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import watersim as ws
from watersim import cli, rundir
from watersim import scenefile as sf

UNTIL = 1.2


@pytest.fixture(scope="module")
def scene_file(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A small flume with a moving piston, a beach, two elevation gauges, a velocity probe, a
    pressure gauge, an overtopping gauge on the beach (its particle sides go into the checkpoints)
    and a run-up gauge: about 600 particles, a few seconds to UNTIL."""
    flume = ws.Flume(length=2.4, depth=0.24, damping=False,
                     beach=ws.PlaneBeach(toe=1.4, slope=0.3))
    scene = flume.scene(ws.RegularWave(height=0.04, period=1.0), paddle=ws.Piston(ramp_periods=0.5),
                        dp=0.04, until=UNTIL, sample_interval=0.02,
                        gauges=[ws.ElevationGauge(0.5), ws.ElevationGauge(1.0),
                                ws.VelocityProbe(points=((0.5, 0.15),)),
                                ws.PressureGauge(points=((0.5, 0.06), (0.5, 0.3)), name="p"),
                                ws.OvertoppingGauge(x=1.6, name="q")],
                        runup=ws.RunupGauge())
    path = tmp_path_factory.mktemp("scene") / "small.toml"
    path.write_text(sf.dumps(scene))
    return path


def _run(argv: list[str]) -> int:
    return cli.main(argv)


def _summary(folder: Path) -> dict:  # type: ignore[type-arg]
    return json.loads((folder / "summary.json").read_text())


@pytest.fixture(scope="module")
def straight(scene_file: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The uninterrupted run to UNTIL."""
    out = tmp_path_factory.mktemp("straight")
    assert _run(["run", str(scene_file), "--out", str(out), "--quiet",
                 "--checkpoint-every", "0.25"]) == 0
    return out


def test_run_writes_its_scene_and_keeps_the_last_two_checkpoints(straight: Path,
                                                                 scene_file: Path) -> None:
    assert sf.load(straight / "scene.toml").builder == sf.load(scene_file).builder
    found = rundir.checkpoints(straight)
    assert len(found) == rundir.KEEP
    summary = _summary(straight)
    assert summary["checkpoints"] == [str(p.relative_to(straight)) for p in found]
    # the last is the run's end
    header = ws.checkpoint.read_header(found[-1])
    assert header["time"] >= UNTIL and header["steps"] == summary["steps"]


def test_resume_of_a_finished_run_extends_it_bit_for_bit(scene_file: Path, straight: Path,
                                                        tmp_path: Path) -> None:
    """Run to UNTIL/2, then resume --until UNTIL: the state and the gauge records are those of
    the straight run."""
    out = tmp_path / "two_legs"
    assert _run(["run", str(scene_file), "--out", str(out), "--quiet",
                 "--set", f"until={UNTIL / 2}"]) == 0
    assert _run(["resume", str(out), "--until", str(UNTIL), "--quiet"]) == 0
    summary = _summary(out)
    assert summary["state_sha256"] == _summary(straight)["state_sha256"]
    assert summary["resumed_from"]["time"] >= UNTIL / 2
    assert (out / "gauges.csv").read_bytes() == (straight / "gauges.csv").read_bytes()
    velocity = sorted(p.name for p in straight.glob("velocity_*.csv"))
    assert len(velocity) == 1
    assert (out / velocity[0]).read_bytes() == (straight / velocity[0]).read_bytes()
    events = [json.loads(line)["event"] for line in (out / "log.jsonl").read_text().splitlines()]
    assert events[0] == "start" and "resume" in events and events[-1] == "end"


def test_kill_minus_nine_then_resume_is_bit_identical(scene_file: Path, straight: Path,
                                                      tmp_path: Path) -> None:
    out = tmp_path / "killed"
    proc = subprocess.Popen(
        [sys.executable, "-m", "watersim", "run", str(scene_file), "--out", str(out), "--quiet",
         "--checkpoint-every", "0.1"],
        env={**os.environ, "RAYON_NUM_THREADS": "1"},
    )
    try:
        deadline = time.monotonic() + 120.0
        while time.monotonic() < deadline and proc.poll() is None:
            found = rundir.checkpoints(out)
            if found and ws.checkpoint.read_header(found[-1])["time"] >= 0.3:
                break
            time.sleep(0.05)
        if proc.poll() is not None:
            pytest.skip("the run finished before it could be killed (a very fast machine)")
        os.kill(proc.pid, signal.SIGKILL)
    finally:
        proc.wait()
    assert _summary(out)["status"] == "running"  # the killed run's summary says it never ended
    assert _run(["resume", str(out), "--quiet"]) == 0  # its lock died with it
    assert not (out / rundir.LOCK_FILE).exists()
    assert _summary(out)["state_sha256"] == _summary(straight)["state_sha256"]
    assert (out / "gauges.csv").read_bytes() == (straight / "gauges.csv").read_bytes()


def test_analyse_recomputes_analysis_json(straight: Path, tmp_path: Path) -> None:
    target = tmp_path / "analysis.json"
    assert _run(["analyse", str(straight), "--out", str(target)]) == 0
    again = json.loads(target.read_text())
    first = json.loads((straight / "analysis.json").read_text())
    assert again["gauges"] == first["gauges"]
    assert again["status"] == "reanalysed"
    assert _run(["analyse", str(straight), "--out", str(target), "--t-start", "0.6"]) == 0
    assert all(g["window"][0] == pytest.approx(0.6, abs=0.05)
               for g in json.loads(target.read_text())["gauges"] if g.get("window"))


def test_load_gives_labelled_records(straight: Path) -> None:
    data = ws.load(straight)
    assert data["elevation"].dims == ("time", "gauge")
    assert data["elevation"].attrs["units"] == "m"
    assert list(data["x"].values) == pytest.approx([0.5, 1.0])
    assert data["time"].values[-1] == pytest.approx(UNTIL, abs=0.03)
    assert "runup" in data and data["runup"].attrs["units"] == "m"
    velocity = [name for name in data.data_vars if name.startswith("velocity_")]
    assert len(velocity) == 1 and data[velocity[0]].attrs["units"] == "m/s"
    pressure = data["pressure_p"]
    assert pressure.dims == ("time_p", "point_p") and pressure.attrs["units"] == "Pa"
    assert data["points_p"].values.tolist() == [[0.5, 0.06], [0.5, 0.3]]
    # the upper point is above the water (NaN, a low kernel sum), the lower one under it
    assert np.all(np.isnan(pressure.values[:, 1]))
    assert np.all(data["kernel_sum_p"].values[:, 1] < 0.5)
    assert np.nanmean(pressure.values[:, 0]) > 0.5 * 1000.0 * 9.81 * (0.24 - 0.06)
    csv = np.genfromtxt(straight / "gauges.csv", delimiter=",", names=True)
    assert np.array_equal(csv["t_s"], data["time"].values)
    assert np.array_equal(csv["p_x0p500_z0p060_Pa"], pressure.values[:, 0])
    assert data["overtopping_volume_q"].attrs["units"] == "m^3/m"
    assert data["overtopping_volume_q"].values[0] == 0.0


def _snapshot(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in folder.rglob("*") if p.is_file()}


@pytest.mark.parametrize("damage", ["no_checkpoint", "corrupt", "other_scene", "other_version",
                                    "no_scene"])
def test_a_folder_that_cannot_be_resumed_is_refused_and_left_alone(
        damage: str, straight: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    import shutil

    out = tmp_path / "run"
    shutil.copytree(straight, out)
    last = rundir.checkpoints(out)[-1]
    if damage == "no_checkpoint":
        shutil.rmtree(out / rundir.CHECKPOINTS)
        expected = "no checkpoint"
    elif damage == "corrupt":
        last.write_bytes(last.read_bytes()[:1000])
        expected = "unreadable"
    elif damage == "other_scene":
        text = "coefsound = 15.0\n" + (out / "scene.toml").read_text()
        (out / "scene.toml").write_text(text)
        expected = "of another scene"
    elif damage == "other_version":
        with np.load(last) as f:
            arrays = {k: f[k] for k in f.files}
        arrays["version"] = np.asarray("0.0.1")
        np.savez(last, **arrays)
        expected = "written by watersim 0.0.1"
    else:
        (out / "scene.toml").unlink()
        expected = "not a watersim run folder"
    before = _snapshot(out)
    assert _run(["resume", str(out), "--until", str(2 * UNTIL), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert expected in err and len(err.strip().splitlines()) == 1
    assert _snapshot(out) == before


def test_bad_checkpoint_intervals_are_refused(scene_file: Path,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    for spec in ("0", "wall:-1", "cpu:5", "soon"):
        assert _run(["run", str(scene_file), "--checkpoint-every", spec, "--quiet"]) == 2
        assert "--checkpoint-every" in capsys.readouterr().err
    assert _run(["run", "dambreak2d", "--checkpoint-every", "1", "--quiet"]) == 2
    assert "only flume runs" in capsys.readouterr().err
    assert rundir.CheckpointEvery.parse("wall:10min") == rundir.CheckpointEvery(600.0, wall=True)
    assert rundir.CheckpointEvery.parse("sim:2.5") == rundir.CheckpointEvery(2.5)


def test_long_runs_write_their_records_as_they_go() -> None:
    """A short run rewrites its records every twentieth of the run; a long one at least every
    50 gauge samples (the 350 s kimmoun2d run: every 1.6 s, not every 17.5 s)."""
    from watersim.cli import record_every

    assert record_every(10.0, 0.03) == pytest.approx(0.5)
    assert record_every(350.0, 0.031875) == pytest.approx(50 * 0.031875)
