"""The code and commands of docs/user-guide.md run, and its scene file is its Python case."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from conftest import run_cli
from watersim import scenefile as sf

GUIDE = Path(__file__).resolve().parents[1] / "docs" / "user-guide.md"


def _blocks(language: str) -> list[str]:
    text = GUIDE.read_text(encoding="utf-8")
    return re.findall(rf"^```{language}\n(.*?)^```$", text, flags=re.S | re.M)


def _shortened(code: str, run: Path) -> str:
    # a fraction of a second instead of the guide's 6 s, and files under tmp_path
    assert "until=11.0" in code and "runs/beach" in code
    return code.replace("until=11.0", "until=0.3").replace("runs/beach", str(run))


def test_python_example_runs_and_matches_the_scene_file(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    python = _blocks("python")
    toml = _blocks("toml")
    assert len(python) == 2 and len(toml) == 1
    run = tmp_path / "beach"
    (run / "snapshots").mkdir(parents=True)
    space: dict[str, object] = {}
    exec(compile(_shortened(python[0], run), "user-guide.md", "exec"), space)
    sim = space["sim"]
    assert sim.time >= 0.3  # type: ignore[attr-defined]
    assert space["eta"].shape[1] == 3  # type: ignore[attr-defined]
    assert "particle-steps/s" in capfd.readouterr().err  # the progress bar was shown
    assert (run / "gauges.csv").is_file()
    assert sorted(p.name for p in (run / "snapshots").glob("*.vtu")) == [
        "particles_00000.vtu", "particles_00001.vtu"]

    # the scene file of section 2 is the same case
    from_file = sf.loads(toml[0].replace("until = 11.0", "until = 0.3"), source="beach.toml")
    assert from_file.output.snapshot_every == 0.5
    assert from_file.builder.resolved_scene() == sim.scene  # type: ignore[attr-defined]

    # the NumPy reading example works on these files
    summary = {"n_particles": sim.n_particles}  # type: ignore[attr-defined]
    (run / "summary.json").write_text(json.dumps(summary))
    reading = python[1].replace("runs/beach", str(run)).replace("particles_00012",
                                                                "particles_00001")
    ns: dict[str, object] = {}
    exec(compile(reading, "user-guide.md", "exec"), ns)
    assert ns["t"].shape == ns["eta_1m"].shape  # type: ignore[attr-defined]
    assert ns["xz"].shape == (sim.n_fluid, 2)  # type: ignore[attr-defined]


def test_command_line_walk_through(tmp_path: Path) -> None:
    """The guide's `watersim` commands in order, in a fresh folder, each run shortened to 0.3 s
    (resume to 0.5 s); running the first command again is refused (its folder holds a run)."""
    (tmp_path / "beach.toml").write_text(_blocks("toml")[0])
    shell = _blocks("sh")
    commands = [line.split("#")[0].split() for block in (shell[0], shell[2])
                for line in block.splitlines() if line.strip()]
    assert [c[:2] for c in commands] == [["watersim", "run"], ["watersim", "run"],
                                         ["watersim", "plot"], ["watersim", "resume"],
                                         ["watersim", "resume"], ["watersim", "analyse"]]
    shortened = {"run": ["--set", "until=0.3", "--quiet"], "resume": ["--quiet"]}
    for command in commands:
        args = command[1:]
        if args[0] == "resume" and "--until" in args:
            args[args.index("--until") + 1] = "0.5"
        if args[0] == "analyse":
            args[args.index("--t-start") + 1] = "0.1"
        if args[0] == "resume" and "--until" not in args:
            continue  # the run finished: nothing to go on with
        proc = run_cli(*args, *shortened.get(args[0], []), cwd=tmp_path)
        assert proc.returncode == 0, (args, proc.stderr)
        if args[0] == "plot":
            assert "runs/beach/plots/gauges.png" in proc.stdout
    assert json.loads((tmp_path / "runs/beach/summary.json").read_text())["sim_time"] >= 0.5
    assert (tmp_path / "runs/beach-h5/gauges.csv").is_file()
    again = run_cli(*commands[0][1:], "--set", "until=0.3", cwd=tmp_path)
    assert again.returncode == 2 and "--overwrite" in again.stderr


def test_the_general_scene_example_runs_and_its_scene_file_reads(tmp_path: Path,
                                                                  monkeypatch: pytest.MonkeyPatch
                                                                  ) -> None:
    """Section 2's dam break against a box (at dp 0.08 m for 0.02 s) and its scene file."""
    (python,) = _blocks("python scene")
    (toml,) = _blocks("toml scene")
    assert "dp=0.02, until=1.0" in python
    monkeypatch.chdir(tmp_path)
    space: dict[str, object] = {}
    code = python.replace("dp=0.02, until=1.0", "dp=0.08, until=0.02")
    exec(compile(code, "user-guide.md", "exec"), space)
    assert space["force"].shape[1] == 3  # type: ignore[attr-defined]
    assert (tmp_path / "gauges.csv").is_file()
    scene = sf.loads(toml, source="scene.toml").builder
    assert scene.to_scene()["obstacles"] == [
        {"shape": "sphere", "centre": [0.4, 0.2], "radius": 0.1}]
