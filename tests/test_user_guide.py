"""The code of docs/user-guide.md runs, and its scene file is its Python case."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

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
    assert json.dumps(from_file.builder.to_scene(), sort_keys=True) == json.dumps(
        sim.scene, sort_keys=True)  # type: ignore[attr-defined]

    # the NumPy reading example works on these files
    summary = {"n_particles": sim.n_particles}  # type: ignore[attr-defined]
    (run / "summary.json").write_text(json.dumps(summary))
    reading = python[1].replace("runs/beach", str(run)).replace("particles_00012",
                                                                "particles_00001")
    ns: dict[str, object] = {}
    exec(compile(reading, "user-guide.md", "exec"), ns)
    assert ns["t"].shape == ns["eta_1m"].shape  # type: ignore[attr-defined]
    assert ns["xz"].shape == (sim.n_fluid, 2)  # type: ignore[attr-defined]
