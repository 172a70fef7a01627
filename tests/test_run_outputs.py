"""`watersim run` outputs end to end (scene file -> run -> VTK snapshots read back -> `watersim
plot`), progress bars, the run schedule and the readable reprs."""

from __future__ import annotations

import json
import os
import warnings
import xml.etree.ElementTree as ET
from pathlib import Path

import meshio
import numpy as np
import pytest

import watersim as ws
from conftest import assert_clean_failure, run_cli
from watersim import cli
from watersim.plotting import plot_run

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"

TINY_FLUME = """
type = "flume"
dp = 0.04
coefsound = 10.0
until = 0.3
sample_interval = 0.02

[flume]
length = 2.5
depth = 0.2

[flume.beach]
type = "plane"
toe = 1.0
slope = 0.25

[wave]
type = "regular"
height = 0.04
period = 1.0

[[gauges]]
type = "elevation"
x = 0.5

[[gauges]]
type = "elevation"
x = 1.2

[output]
snapshot_every = 0.1
sample_every = 0.1
"""

SMALL_DAMBREAK = ["--set", "dp=0.1", "--set", "width=0.6", "--set", "height=1.2",
                  "--set", "tank_length=1.8", "--set", "tank_height=1.5", "--set", "until=0.1"]


def _pngs(lines: str) -> list[Path]:
    paths = [Path(line) for line in lines.splitlines() if line.strip()]
    for p in paths:
        assert p.suffix == ".png" and p.read_bytes()[:8] == PNG_MAGIC, p
        assert p.stat().st_size > 5000, p  # a drawn figure, not an empty canvas
    return paths


def test_scene_file_run_writes_snapshots_gauges_log_and_plots(tmp_path: Path) -> None:
    scene = tmp_path / "tiny.toml"
    scene.write_text(TINY_FLUME)
    out = tmp_path / "run"
    proc = run_cli("run", str(scene), "--out", str(out), "--no-progress",
                   env={"RAYON_NUM_THREADS": "2"})
    assert proc.returncode == 0, proc.stderr
    assert "particle-steps/s" not in proc.stderr  # no bar when asked not to
    summary = json.loads((out / "summary.json").read_text())
    assert summary["case"] == "tiny" and summary["status"] == "ok"
    n, n_fluid = summary["n_particles"], summary["n_fluid"]

    # snapshots at t = 0, 0.1, 0.2, 0.3 s: the .pvd lists them, meshio reads each back
    snaps = summary["snapshots"]
    assert snaps["count"] == 4 and snaps["every"] == 0.1
    pvd = out / snaps["pvd"]
    sets = ET.parse(pvd).getroot().find("Collection").findall("DataSet")  # type: ignore[union-attr]
    times = [float(d.get("timestep")) for d in sets]  # type: ignore[arg-type]
    assert times[0] == 0.0 and np.all(np.diff(times) > 0.09)
    assert times[-1] == pytest.approx(summary["sim_time"])
    for d in sets:
        mesh = meshio.read(pvd.parent / d.get("file"))  # type: ignore[operator]
        assert mesh.points.shape == (n, 3)
        for field, shape in (("velocity", (n, 3)), ("density", (n,)), ("pressure", (n,)),
                             ("kind", (n,))):
            assert mesh.point_data[field].shape == shape, field
        assert int((mesh.point_data["kind"] == 0).sum()) == n_fluid
        assert np.all(np.isfinite(mesh.point_data["density"]))
    last = meshio.read(pvd.parent / sets[-1].get("file"))  # type: ignore[operator]
    assert np.max(np.linalg.norm(last.point_data["velocity"], axis=1)) > 0.0  # the paddle moved

    # gauges.csv, the JSON log
    header = (out / "gauges.csv").read_text().splitlines()[0].split(",")
    assert header == ["t_s", "eta_x0p500_m", "eta_x1p200_m", "runup_m"]
    events = [json.loads(line) for line in (out / "log.jsonl").read_text().splitlines()]
    assert events[0]["event"] == "start" and events[-1]["event"] == "end"
    assert events[-1]["status"] == "ok"
    assert sum(e["event"] == "snapshot" for e in events) == 4
    assert sum(e["event"] == "sample" for e in events) >= 4

    # plots
    proc = run_cli("plot", str(out))
    assert proc.returncode == 0, proc.stderr
    names = {p.name for p in _pngs(proc.stdout)}
    assert names == {"gauges.png", "envelopes.png", "runup.png", "snapshot.png"}


def test_dambreak_snapshots_from_the_command_line_and_front_plot(tmp_path: Path) -> None:
    out = tmp_path / "db"
    assert cli.main(["run", "dambreak2d", *SMALL_DAMBREAK, "--snapshot-every", "0.05",
                     "--out", str(out), "--quiet", "--no-progress"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["snapshots"]["count"] == 3  # t = 0, 0.05, 0.1 s
    files = sorted((out / "snapshots").glob("particles_*.vtu"))
    assert len(files) == 3
    mesh = meshio.read(files[-1])
    assert mesh.points.shape == (summary["n_particles"], 3)
    assert set(mesh.point_data) >= {"velocity", "density", "pressure", "kind"}
    written = _pngs("\n".join(str(p) for p in plot_run(out, tmp_path / "figs")))
    assert {p.name for p in written} == {"front.png", "snapshot.png"}
    assert all(p.parent == tmp_path / "figs" for p in written)


def test_nothing_but_summary_and_log_unless_asked(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "tank"
    tank = ["run", "tank2d", "--set", "dp=0.1", "--set", "until=0.05", "--out", str(out)]
    assert cli.main(tank) == 0
    assert sorted(p.name for p in out.iterdir()) == ["log.jsonl", "summary.json"]
    assert "snapshots" not in json.loads((out / "summary.json").read_text())
    # stderr is not a terminal here: no bar by default, one with --progress
    assert "particle-steps/s" not in capfd.readouterr().err
    assert cli.main([*tank, "--progress", "--quiet", "--overwrite"]) == 0
    captured = capfd.readouterr()
    assert "particle-steps/s" in captured.err and captured.out == ""


def test_bad_snapshot_interval_is_refused(tmp_path: Path,
                                          capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "o"
    assert cli.main(["run", "dambreak2d", "--snapshot-every", "0", "--out", str(out)]) == 2
    assert "--snapshot-every: must be a positive number" in capsys.readouterr().err
    assert not out.exists()


def test_plot_refuses_a_missing_or_empty_folder(tmp_path: Path) -> None:
    proc = run_cli("plot", str(tmp_path / "nowhere"))
    assert_clean_failure(proc, "nowhere", "no such run folder")
    assert proc.returncode == 2
    (tmp_path / "empty").mkdir()
    proc = run_cli("plot", str(tmp_path / "empty"))
    assert_clean_failure(proc, "no run results to plot")
    assert proc.returncode == 2
    assert not (tmp_path / "empty" / "plots").exists()


def _small_dambreak() -> ws.DamBreak:
    return ws.DamBreak(dp=0.1, width=0.6, height=1.2, tank_length=1.8, tank_height=1.5,
                       until=0.1)


def test_progress_bar_runs_cleanly_and_changes_nothing(capfd: pytest.CaptureFixture[str]) -> None:
    plain = _small_dambreak().build()
    plain.run(0.1)
    shown = _small_dambreak().build()
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no warning of any kind (tqdm's included)
        shown.run(0.1, progress=True)
    err = capfd.readouterr().err
    assert "particle-steps/s" in err and "dt=" in err and "100%" in err
    assert shown.state_sha256() == plain.state_sha256()
    assert shown.steps == plain.steps


def test_flume_simulation_run_takes_progress(capfd: pytest.CaptureFixture[str]) -> None:
    flume = ws.Flume(length=2.0, depth=0.2)
    sim = flume.simulation(ws.RegularWave(height=0.03, period=1.0), dp=0.05, until=0.05,
                           gauges=[ws.ElevationGauge(0.5)])
    sim.run(progress=True)
    assert sim.time >= 0.05
    assert "particle-steps/s" in capfd.readouterr().err
    assert sim.gauges.t.size >= 2


def test_run_schedule_calls_each_callback_at_its_own_interval() -> None:
    sim = _small_dambreak().build()
    fast: list[float] = []
    slow: list[float] = []
    sim.run_schedule(0.1, [(0.01, lambda s: fast.append(s.time)),
                           (0.04, lambda s: slow.append(s.time))])
    assert fast[0] == slow[0] == 0.0
    assert fast[-1] == slow[-1] == sim.time >= 0.1
    assert len(fast) == 11 and len(slow) == 4  # 0, 0.04, 0.08, end
    for k, t in enumerate(slow[1:-1], start=1):
        assert 0.04 * k <= t < 0.04 * k + 2 * sim.dt
    with pytest.raises(ValueError, match="callback_every"):
        sim.run_schedule(0.2, [(0.0, lambda s: None)])


def test_readable_reprs() -> None:
    sim = _small_dambreak().build()
    text = repr(sim)
    # the dam break is a preset of the general scene: its simulation names its own class
    assert text.startswith(f"{type(sim).__name__}(dim=2, particles=")
    assert isinstance(sim, ws.Simulation) and f"{sim.n_fluid} fluid" in text
    assert "time=0 s" in text and "dt=" in text
    flume = ws.Flume(length=2.0, depth=0.2).simulation(
        ws.RegularWave(height=0.03, period=1.0), dp=0.05, gauges=[ws.ElevationGauge(0.5)])
    text = repr(flume)
    assert text.startswith("FlumeSimulation(dim=2, particles=")
    assert "2 m long, 0.2 m deep" in text and "RegularWave" in text and "1 gauges" in text


@pytest.mark.skipif(os.environ.get("WATERSIM_TEST_INSTALLED") != "1",
                    reason="only under scripts/test-wheel.sh")
def test_the_installed_package_is_under_test() -> None:
    # scripts/test-wheel.sh sets WATERSIM_TEST_INSTALLED=1: the tests must then import the
    # installed wheel, not the source tree's python/ folder
    source = Path(__file__).resolve().parents[1] / "python"
    assert source not in Path(ws.__file__).resolve().parents, ws.__file__
