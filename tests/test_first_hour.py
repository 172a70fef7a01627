"""A coastal engineer's first hour: every gauge a scene declares is written and read back, the
analysis refuses windows too short and says what to run, a run does not mix its files with
another run's, headers carry units, figures carry targets, and the small things a new user meets
(did-you-mean, a steep slope, an interrupted run, ``watersim validate`` without scipy)."""

from __future__ import annotations

import csv
import importlib.util
import json
import math
import os
import re
import signal
import subprocess
import sys
import time
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import watersim as ws
from conftest import assert_clean_failure, run_cli
from watersim import cli, plotting
from watersim import scenefile as sf
from watersim.cli import builder_from_args
from watersim.flume import FlumeGauges, FlumeScene, analyse_flume
from watersim.flume.analyse import MIN_WINDOW_PERIODS, UNITS
from watersim.flume_cases import FLUME_CASES

ROOT = Path(__file__).resolve().parents[1]
GUIDE = ROOT / "docs" / "user-guide.md"

PROBED = """
type = "flume"
dp = 0.04
coefsound = 10.0
until = 0.3
sample_interval = 0.02

[flume]
length = 2.4
depth = 0.24
damping = false

[flume.beach]
type = "plane"
toe = 1.4
slope = 0.3

[wave]
type = "regular"
height = 0.04
period = 1.0

[[gauges]]
type = "elevation"
x = 1.0

[[gauges]]
type = "elevation"
x = 0.5

[[gauges]]
type = "velocity"
name = "u_mid"
points = [[0.5, 0.1], [0.5, 0.34]]  # the second point is above the water: dry

[[gauges]]
type = "window"
name = "piv"
min = [0.6, 0.04]
max = [1.0, 0.2]
n = [5, 3]
interval = 0.05

[runup]

[output]
snapshot_every = 0.1
"""


@pytest.fixture(scope="module")
def probed_run(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Any]:
    """A short `watersim run` of PROBED: (its folder, the completed process)."""
    folder = tmp_path_factory.mktemp("probed")
    scene = folder / "probed.toml"
    scene.write_text(PROBED)
    out = folder / "run"
    proc = run_cli("run", str(scene), "--out", str(out), "--no-progress")
    assert proc.returncode == 0, proc.stderr
    return out, proc


# ------------------------------------------------------------------------------------------------
# item 1: velocity probes and windows are written, plotted and loaded


def test_velocity_probes_and_windows_get_their_own_csv_files(probed_run: tuple[Path, Any]) -> None:
    out, _ = probed_run
    summary = json.loads((out / "summary.json").read_text())
    assert summary["velocity_csv"] == {"u_mid": "velocity_u_mid.csv", "piv": "velocity_piv.csv"}
    data = ws.load(out)
    for name, points in (("u_mid", 2), ("piv", 15)):
        with open(out / f"velocity_{name}.csv", newline="") as f:
            rows = list(csv.reader(f))
        header = rows[0]
        assert header[0] == "t_s" and len(header) == 1 + 3 * points  # u, w, kernel sum
        table = np.genfromtxt(out / f"velocity_{name}.csv", delimiter=",", names=True)
        assert list(table.dtype.names) == header  # NumPy keeps every name as written
        # the same records as watersim.load's, dry points blanked
        velocity = data[f"velocity_{name}"].values
        np.testing.assert_array_equal(table["t_s"], data[f"time_{name}"].values)
        ksum = data[f"kernel_sum_{name}"].values
        u = np.stack([table[h] for h in header if h.startswith("u_")], axis=1)
        wet = ksum >= 0.5
        np.testing.assert_array_equal(u[wet], velocity[..., 0][wet])
        assert np.all(np.isnan(u[~wet]))
    probe_header = (out / "velocity_u_mid.csv").read_text().splitlines()[0].split(",")
    assert probe_header == ["t_s", "u_x0p500_z0p100_m_per_s", "w_x0p500_z0p100_m_per_s",
                            "kernel_sum_x0p500_z0p100", "u_x0p500_z0p340_m_per_s",
                            "w_x0p500_z0p340_m_per_s", "kernel_sum_x0p500_z0p340"]
    dry_point = np.genfromtxt(out / "velocity_u_mid.csv", delimiter=",", names=True)
    assert np.all(np.isnan(dry_point["u_x0p500_z0p340_m_per_s"]))  # above the water
    assert np.all(np.isfinite(dry_point["u_x0p500_z0p100_m_per_s"]))


def test_plot_draws_the_velocity_files(probed_run: tuple[Path, Any], tmp_path: Path) -> None:
    out, _ = probed_run
    written = {p.name for p in plotting.plot_run(out, tmp_path)}
    assert {"velocity_u_mid.png", "velocity_piv.png", "gauges.png", "runup.png"} <= written


def test_the_irregular_example_writes_its_probe_and_window(tmp_path: Path) -> None:
    out = tmp_path / "irregular"
    proc = run_cli("run", str(ROOT / "examples" / "irregular2d.toml"), "--set", "until=0.06",
                   "--out", str(out), "--quiet")
    assert proc.returncode == 0, proc.stderr
    assert (out / "velocity_u_toe.csv").is_file() and (out / "velocity_piv.csv").is_file()
    header = (out / "velocity_piv.csv").read_text().splitlines()[0].split(",")
    assert len(header) == 1 + 3 * 11 * 5


# ------------------------------------------------------------------------------------------------
# item 2: too short a window is refused, said on the console, and not drawn


def test_a_short_run_says_what_it_needs_and_computes_nothing_partial(
    probed_run: tuple[Path, Any]
) -> None:
    out, proc = probed_run
    analysis = json.loads((out / "analysis.json").read_text())
    needs = [g["needs_until"] for g in analysis["gauges"]]
    assert all(n > 0.3 for n in needs)
    assert not any("H_mean" in g for g in analysis["gauges"])
    assert analysis["envelopes"]["maximum"] == [None, None]  # not the partial record's maxima
    assert analysis["runup"]["needs_until"] > 0.3 and "max" not in analysis["runup"]
    needed = max([*needs, analysis["runup"]["needs_until"]])
    assert f"run with until >= {math.ceil(needed * 10) / 10:g} s" in proc.stdout
    assert "wave statistics: not computed" in proc.stdout


def _scene(text: str, until: float | None = None) -> FlumeScene:
    scene = sf.loads(text, [] if until is None else [f"until={until!r}"]).builder
    assert isinstance(scene, FlumeScene)
    return scene


def _synthetic_records(scene: FlumeScene, amplitude: float = 0.02) -> list[dict[str, Any]]:
    """The records a run of ``scene`` to its ``until`` would give, for a regular wave of the
    scene's period at every elevation and run-up gauge (the analysis's windows depend on the
    times only)."""
    assert scene.until is not None and scene.sample_interval is not None
    t = np.arange(0.0, scene.until + 1e-9, scene.sample_interval)
    period = scene.law.period
    assert period is not None
    z = scene.flume.depth + amplitude * np.sin(2.0 * np.pi * t / period)
    records = [{"type": spec["type"], "name": spec["name"], "t": t.tolist(), "z": z.tolist()}
               for spec in scene._gauge_specs() if spec["type"] in ("elevation", "runup")]
    # a force gauge's record: an inline force in phase with the wave, no moment
    dim = scene.flume.dim
    force = np.zeros((t.size, dim))
    force[:, 0] = 10.0 * np.sin(2.0 * np.pi * t / period)
    moment = np.zeros((t.size,) if dim == 2 else (t.size, 3))
    records += [{"type": "force", "name": spec["name"], "t": t.tolist(),
                 "force": force.tolist(), "moment": moment.tolist()}
                for spec in scene._gauge_specs() if spec["type"] == "force"]
    return records


def _analysis(scene: FlumeScene) -> dict[str, Any]:
    return analyse_flume(scene, FlumeGauges(scene, _synthetic_records(scene)))


def test_statistics_need_three_periods_of_window() -> None:
    scene = _scene(PROBED)
    short = _analysis(scene.replace(until=4.0))
    needed = short["gauges"][0]["needs_until"]
    start = short["gauges"][0]["window"][0]
    assert needed == pytest.approx(start + MIN_WINDOW_PERIODS * 1.0)
    enough = _analysis(scene.replace(until=math.ceil(needed * 10) / 10))
    assert "needs_until" not in enough["gauges"][0] and enough["gauges"][0]["n_waves"] >= 2
    assert enough["envelopes"]["needs_until"][1] is None


def _guide_toml() -> str:
    text = GUIDE.read_text(encoding="utf-8")
    return re.findall(r"^```toml\n(.*?)^```$", text, flags=re.S | re.M)[0]


@pytest.mark.parametrize("tutorial", ["examples/flume2d.toml", "user guide beach.toml"])
def test_tutorials_run_long_enough_for_what_they_promise(tutorial: str) -> None:
    """examples/flume2d.toml promises statistics at its four gauges and the incident/reflected
    separation; the user guide's beach case wave heights, run-up and reflection."""
    if tutorial.startswith("examples/"):
        scene = sf.load(ROOT / tutorial).builder
    else:
        scene = _scene(_guide_toml())
    assert isinstance(scene, FlumeScene)
    analysis = _analysis(scene)
    assert all(g.get("H_mean") is not None for g in analysis["gauges"]), analysis["notes"]
    assert all(v is not None for v in analysis["envelopes"]["maximum"])
    assert analysis["reflection"] is not None, analysis["notes"]
    if scene.runup_gauge is not None:
        assert analysis["runup"].get("mean") is not None, analysis["notes"]
    assert not [n for n in analysis["notes"] if "not computed" in n]


@pytest.mark.parametrize("case", [c for c in FLUME_CASES
                                  if c not in ("solitary2d", "seawall2d")])
def test_built_in_wave_cases_run_long_enough_for_every_gauge(case: str) -> None:
    """Each built-in regular-wave case's default ``until`` gives every gauge its steady window
    (ramp, arrival, one period to settle, then MIN_WINDOW_PERIODS periods)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # wave-validity warnings of some cases
        scene = builder_from_args(case, [])
    analysis = _analysis(scene)
    assert all(g.get("H_mean") is not None for g in analysis["gauges"]), analysis["notes"]


# ------------------------------------------------------------------------------------------------
# item 3: one run per folder


def test_a_folder_of_another_run_is_refused_then_overwritten(
    probed_run: tuple[Path, Any], tmp_path: Path
) -> None:
    out = tmp_path / "shared"
    out.mkdir()
    for name in ("summary.json", "gauges.csv", "velocity_old.csv", "log.jsonl"):
        (out / name).write_text("{}")
    (out / "snapshots").mkdir()
    (out / "snapshots" / "particles_00099.vtu").write_text("old")
    (out / "notes.txt").write_text("mine")
    before = sorted(p.name for p in out.rglob("*"))
    scene = tmp_path / "probed.toml"
    scene.write_text(PROBED)
    proc = run_cli("run", str(scene), "--out", str(out), "--set", "until=0.02")
    assert_clean_failure(proc, str(out), "earlier run", "summary.json", "--overwrite")
    assert proc.returncode == 2 and sorted(p.name for p in out.rglob("*")) == before
    proc = run_cli("run", str(scene), "--out", str(out), "--set", "until=0.02", "--overwrite",
                   "--quiet")
    assert proc.returncode == 0, proc.stderr
    assert not (out / "velocity_old.csv").exists()
    assert not (out / "snapshots" / "particles_00099.vtu").exists()
    assert (out / "notes.txt").read_text() == "mine"  # not a run's: left alone
    assert json.loads((out / "summary.json").read_text())["case"] == "probed"
    # a dam break likewise
    proc = run_cli("run", "tank2d", "--set", "dp=0.1", "--set", "until=0.01", "--out", str(out))
    assert_clean_failure(proc, "case probed, status ok")


def test_a_builtin_case_and_the_file_of_its_name_write_to_different_folders() -> None:
    builtin = cli._run_input(cli.build_parser().parse_args(["run", "flume2d"]))
    from_file = sf.load(ROOT / "examples" / "flume2d.toml")
    assert cli.default_folder(builtin) == Path("runs/flume2d-builtin")
    assert cli.default_folder(from_file) == Path("runs/flume2d")


# ------------------------------------------------------------------------------------------------
# item 7: watersim validate without scipy


def test_validate_without_scipy_says_what_to_install_before_running(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name == "scipy" else real(name, *a))
    started = time.perf_counter()
    assert cli.main(["validate", "tank2d", "standing2d"]) == 2
    err = capsys.readouterr().err
    assert time.perf_counter() - started < 5.0  # refused before any case ran
    assert err.count("\n") == 1 and "standing2d: needs scipy" in err and "pip install scipy" in err
    assert cli.main(["validate", "tank2d", "--quick", "--from-json", "x"]) == 2  # other checks


def test_validate_help_says_what_it_needs_and_how_long_it_takes() -> None:
    proc = run_cli("validate", "--help")
    text = " ".join(proc.stdout.split())
    assert "scipy" in text and "two hours" in text and "--quick" in text


# ------------------------------------------------------------------------------------------------
# item 8: figures


def _figures(run: Path, monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> dict[str, Any]:
    """plot_run's figures by file name, kept open to look at."""
    figures: dict[str, Any] = {}

    def keep(fig: Any, path: Path) -> Path:
        figures[path.name] = fig
        fig.savefig(path, dpi=30)
        return path

    monkeypatch.setattr(plotting, "_save", keep)
    plotting.plot_run(run, tmp_path / "figs")
    return figures


def test_figures_order_gauges_along_the_flume_with_targets_windows_and_units(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A synthetic run long enough to analyse (gauges declared at x = 1.0 then 0.5)."""
    scene = _scene(PROBED, until=8.0)
    gauges = FlumeGauges(scene, _synthetic_records(scene))
    run = tmp_path / "run"
    run.mkdir()
    gauges.to_csv(run / "gauges.csv")
    analysis = analyse_flume(scene, gauges)
    (run / "analysis.json").write_text(json.dumps({**analysis, "case": "probed"}))
    (run / "summary.json").write_text(json.dumps(
        {"builder": scene.as_dict(), "scene": scene.to_scene()}, default=float))
    figures = _figures(run, monkeypatch, tmp_path)

    axes = figures["gauges.png"].axes
    titles = [ax.get_title(loc="left") for ax in axes]
    assert titles[0].startswith("x = 0.500 m") and titles[1].startswith("x = 1.000 m")
    assert "target 0.04 m" in titles[0] and "H = " in titles[0]  # measured against target
    assert axes[0].get_ylabel() == "eta above SWL [m]"
    assert axes[-1].get_ylabel() == "run-up above SWL [m]"
    window = analysis["gauges"][1]["window"]  # x = 0.5 m, second in scene order
    spans = [p.get_x() for p in axes[0].patches]
    assert spans and spans[0] == pytest.approx(window[0])  # the analysed window shaded
    targets = [line.get_ydata()[0] for line in axes[0].lines[1:]]
    assert sorted(targets) == pytest.approx([-0.02, 0.02])  # target crest and trough

    levels, heights = figures["envelopes.png"].axes
    labels = [line.get_label() for line in heights.lines]
    assert any("measured" in label for label in labels)
    assert any("linear theory" in label for label in labels)
    assert heights.get_ylabel() == "wave height [m]" and "[m]" in levels.get_ylabel()
    theory = max(float(np.nanmax(line.get_ydata())) for line in heights.lines
                 if "theory" in line.get_label())
    assert heights.get_ylim()[1] >= 1.1 * theory  # not on the axes' top edge
    assert figures["runup.png"].axes[0].get_ylabel() == "run-up above SWL [m]"


def test_envelopes_do_not_draw_a_partial_window(
    probed_run: tuple[Path, Any], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    out, _ = probed_run
    levels = _figures(out, monkeypatch, tmp_path)["envelopes.png"].axes[0]
    drawn = {line.get_label(): line.get_ydata() for line in levels.lines}
    assert np.all(np.isnan(np.asarray(drawn["highest level"], dtype=float)))
    assert "window too short: no envelope" in drawn


# ------------------------------------------------------------------------------------------------
# item 9: headers with units that NumPy and pandas read unchanged


def test_gauges_csv_reads_unchanged_in_numpy_and_pandas(probed_run: tuple[Path, Any]) -> None:
    out, _ = probed_run
    header = (out / "gauges.csv").read_text().splitlines()[0].split(",")
    assert header == ["t_s", "eta_x1p000_m", "eta_x0p500_m", "runup_m"]
    table = np.genfromtxt(out / "gauges.csv", delimiter=",", names=True)
    assert list(table.dtype.names) == header
    pandas = pytest.importorskip("pandas")
    assert list(pandas.read_csv(out / "gauges.csv").columns) == header
    analysis = json.loads((out / "analysis.json").read_text())
    assert analysis["units"] == UNITS and analysis["units"]["needs_until"] == "s"
    keys = {k for g in analysis["gauges"] for k in g if k not in ("name",)}
    assert keys <= set(UNITS) | {"n_samples", "n_waves"}


# ------------------------------------------------------------------------------------------------
# item 10: small things


def test_help_texts_cite_no_issue_numbers() -> None:
    for command in ("run", "resume", "analyse", "plot", "bench", "scene", "stress", "validate",
                    "show-scene"):
        proc = run_cli(command, "--help")
        assert proc.returncode == 0 and "issue" not in proc.stdout.lower(), command
    assert "issue" not in run_cli("--help").stdout.lower()


def test_did_you_mean_on_a_mistyped_case_or_key(tmp_path: Path) -> None:
    proc = run_cli("run", "flume2dd")
    assert_clean_failure(proc, "did you mean 'flume2d'?")
    proc = run_cli("run", "flume2d", "--set", "wave.heigth=0.1")
    assert_clean_failure(proc, "did you mean 'wave.height'?")
    proc = run_cli("run", "dambreak2d", "--set", "widht=1")
    assert_clean_failure(proc, "did you mean 'width'?")
    scene = tmp_path / "s.toml"
    scene.write_text(PROBED)
    proc = run_cli("run", str(scene), "--set", "wave.hieght=0.1")
    assert_clean_failure(proc, "wave.hieght", "did you mean 'height'?")
    proc = run_cli("run", "flume2d", "--set", "qqq=1")
    assert "did you mean" not in proc.stderr  # nothing close: no guess


@pytest.mark.parametrize(("argv", "needle"), [
    (["validate", "flume2dd"], "did you mean 'flume2d'?"),
    (["bench", "--case", "dambreak2"], "did you mean 'dambreak2d'?"),
    (["run", "examples/flume2d.tom"], "did you mean 'examples/flume2d.toml'?"),
    (["show-scene", "flume2d", "--set", "Dp=0.02"], "did you mean 'dp'?"),
    (["resume", "runs/no-such-run"], "runs/no-such-run: no such run folder"),
])
def test_did_you_mean_on_validate_bench_paths_and_case(
    argv: list[str], needle: str, capsys: pytest.CaptureFixture[str],
    monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(ROOT)
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and needle in err, err


def test_a_steep_slope_on_a_built_in_case_is_warned_of_and_builds(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    """``--set beach.slope=5`` (meaning 1:5) on kimmoun2d: the warning says what slope means;
    the case's velocity verticals stand on the floor before the toe, not 11 m under it."""
    with pytest.warns(ws.flume.SteepSlopeWarning):
        scene = cli.builder_from_args("kimmoun2d", ["beach.slope=5"])
    assert isinstance(scene, FlumeScene)
    probes = [g for g in scene.gauges if isinstance(g, ws.VelocityProbe)]
    assert probes and min(z for g in probes for _, z in g.points) > 0.0
    # a warning is printed before a refusal it may explain
    assert cli.main(["run", "kimmoun2d", "--set", "beach.slope=5", "--set", "until=-1",
                     "--out", str(tmp_path / "k")]) == 2
    err = capsys.readouterr().err.splitlines()
    assert "SteepSlopeWarning" in err[0] and "until" in err[-1], err


def test_paddle_type_switches_the_law_of_a_built_in_flume_case() -> None:
    piston = cli.builder_from_args("flume2d", [])
    flap = cli.builder_from_args("flume2d", ["paddle.type=flap", "paddle.hinge_z=0.1"])
    assert isinstance(piston.paddle, ws.Piston) and isinstance(flap.paddle, ws.Flap)
    # the settings the two laws share carry over; the scene's paddle is the flap's
    assert (flap.paddle.order, flap.paddle.ramp_periods) == (2, 2.0) and flap.paddle.hinge == 0.1
    paddle = flap.to_scene()["paddle"]
    assert paddle["kind"] == "flap" and paddle["hinge_z"] == 0.1
    # a built-in case written as a scene file keeps the switch
    assert sf.loads(sf.dumps(flap)).builder == flap
    assert "paddle.type" in cli.settable_keys("kimmoun2d")


@pytest.mark.parametrize(("setting", "needles"), [
    ("paddle.type=wedge", ("paddle.type", '"piston", "flap"', "'wedge'")),
    ("paddle.hinge_z=0.1", ("paddle.hinge_z", "paddle.type=flap")),
    ("wave.type=irregular", ("wave.type", "fixed type", "watersim show-scene flume2d")),
])
def test_paddle_type_refusals_name_the_key_and_the_choices(
    setting: str, needles: tuple[str, ...], capsys: pytest.CaptureFixture[str]
) -> None:
    assert cli.main(["show-scene", "flume2d", "--set", setting]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and all(n in err for n in needles), err


def test_a_beach_steeper_than_one_to_one_is_warned_about() -> None:
    with pytest.warns(ws.flume.SteepSlopeWarning, match=r"79 degrees.*slope = 0\.2"):
        ws.PlaneBeach(toe=1.0, slope=5)
    ws.PlaneBeach(toe=1.0, slope=0.2)  # no warning (warnings are errors in this suite)


def test_an_interrupted_run_says_so(tmp_path: Path) -> None:
    out = tmp_path / "tank"
    proc = subprocess.Popen(
        [sys.executable, "-m", "watersim", "run", "tank2d", "--set", "dp=0.05", "--set",
         "until=100", "--sample-every", "0.01", "--out", str(out), "--quiet"],
        stderr=subprocess.PIPE, text=True, env={**os.environ, "RAYON_NUM_THREADS": "1"})
    try:
        deadline = time.monotonic() + 60.0
        while time.monotonic() < deadline:
            log = out / "log.jsonl"
            if log.is_file() and '"sample"' in log.read_text():
                break
            time.sleep(0.05)
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=60)
    finally:
        proc.kill()
    assert proc.returncode == 130, err
    assert "run stopped: interrupted (Ctrl-C)" in err
    assert json.loads((out / "summary.json").read_text())["status"] == "interrupted"


def test_the_dam_break_reference_is_explained(tmp_path: Path) -> None:
    out = tmp_path / "db"
    proc = run_cli("run", "dambreak2d", "--set", "dp=0.1", "--set", "until=0.3", "--out",
                   str(out))
    assert proc.returncode == 0, proc.stderr
    assert "(lethe)" not in proc.stdout
    assert "Martin & Moyce 1952 (their n^2 = 2 table as transcribed by the Lethe project)" \
        in proc.stdout
