"""The README as a new user reads it: every `watersim` command of its shell blocks is one the
command line takes (a run's case and --set keys build), the first flume run and its figures
work, its Python snippets run (shortened) and say what they write, and the example scripts
start from the installed package as their docstrings say (no PYTHONPATH, no path a user does
not have)."""

from __future__ import annotations

import contextlib
import io
import json
import re
import runpy
import shlex
import sys
import warnings
from pathlib import Path
from typing import Any

import pytest

from test_examples import _synthetic_records as shoaling_records
from watersim import cli
from watersim.flume import FlumeGauges, analyse_flume
from watersim.validation import sweep

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
EXAMPLES = ROOT / "examples"
PLACEHOLDERS = ("my_bed.stl", "tcp://host", "DualSPHysics5.4CPU")
"""Commands that name the user's own files or hosts: parsed, not built."""


def _blocks(language: str) -> list[str]:
    text = README.read_text(encoding="utf-8")
    return re.findall(rf"^```{language}\n(.*?)^```$", text, flags=re.S | re.M)


def _commands() -> list[list[str]]:
    """Every `watersim ...` command of the README's sh blocks, comments and continuations
    resolved, split as the shell would."""
    commands = []
    for block in _blocks("sh"):
        for line in block.replace("\\\n", " ").splitlines():
            for part in line.split("&&"):
                words = shlex.split(part, comments=True)
                if words[:1] == ["watersim"]:
                    commands.append(words[1:])
    return commands


def test_every_readme_command_is_taken(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(ROOT)  # the README's paths are the repository's
    commands = _commands()
    assert {c[0] for c in commands} >= {"run", "plot", "bench", "validate"}
    parser = cli.build_parser()
    built = 0
    for command in commands:
        args = parser.parse_args(command)  # argparse exits (2) on an option it does not take
        if any(p in " ".join(command) for p in PLACEHOLDERS):
            continue
        if command[0] == "run":
            cli.builder_from_args(args.case, args.set or [])
            built += 1
        elif command[0] == "validate" and not args.from_json:
            assert sweep.plan(args.cases, None, args.quick), command
    assert built >= 8


def test_the_first_flume_run_and_its_figures(tmp_path: Path,
                                             monkeypatch: pytest.MonkeyPatch) -> None:
    """"First flume run", shortened to 0.05 s: the run folder and the figures it names."""
    block = next(b for b in _blocks("sh") if "examples/flume2d.toml" in b)
    commands = [shlex.split(line, comments=True)[1:] for line in block.splitlines()]
    assert [c[0] for c in commands] == ["run", "plot"]
    text = " ".join(README.read_text(encoding="utf-8").split())
    assert "runs/flume2d/plots/gauges.png" in text
    (tmp_path / "examples").mkdir()
    (tmp_path / "examples" / "flume2d.toml").write_text(
        (EXAMPLES / "flume2d.toml").read_text())
    monkeypatch.chdir(tmp_path)
    assert cli.main([*commands[0], "--set", "until=0.05", "--quiet"]) == 0
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert cli.main(commands[1]) == 0
    assert "runs/flume2d/plots/gauges.png" in out.getvalue()
    assert (tmp_path / "runs/flume2d/plots/gauges.png").is_file()


def test_the_wave_flume_snippet_runs_and_gives_what_it_promises(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Run shortened: the gauges.csv columns its comment names. Analysed on a synthetic record
    to its own 25.5 s that shoals and breaks: every analysis its comment lists is there."""
    (code,) = [b for b in _blocks("python") if "ws.Flume(" in b]
    assert "sim.run(until=25.5, progress=True)" in code
    columns = re.search(r'write_gauges_csv\("gauges.csv"\)\s*#\s*(.*)', code)
    assert columns is not None
    monkeypatch.chdir(tmp_path)
    space: dict[str, Any] = {}
    exec(compile(code.replace("sim.run(until=25.5, progress=True)", "sim.run(until=0.05)"),
                 "README.md", "exec"), space)
    header = (tmp_path / "gauges.csv").read_text().splitlines()[0].split(",")
    named = [c.strip() for c in columns.group(1).split(",")]
    cut = named.index("...") if "..." in named else len(named)
    assert header[:cut] == named[:cut] and header[len(header) - len(named) + cut + 1:] == \
        named[cut + 1:]
    sim = space["sim"]
    assert space["eta"].shape[1] == 5  # the five elevation gauges
    scene = sim.setup.replace(until=25.5)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # the synthetic record's dry gauges
        report = analyse_flume(scene, FlumeGauges(scene, shoaling_records(scene, 0.114, 1.275)))
    assert all(g.get("H_mean") is not None for g in report["gauges"]), report["notes"]
    assert all(g.get("harmonics") for g in report["gauges"]), report["notes"]
    assert report["breaking"]["position"] is not None, report["notes"]
    assert report["runup"].get("values"), report["notes"]
    assert report["reflection"] is not None, report["notes"]
    assert all(v is not None for v in report["envelopes"]["maximum"])


def test_the_python_dam_break_snippet_runs(capsys: pytest.CaptureFixture[str]) -> None:
    (code,) = [b for b in _blocks("python") if "DamBreak(" in b]
    assert "DamBreak(dp=0.04, until=0.7)" in code
    exec(compile(code.replace("DamBreak(dp=0.04, until=0.7)", "DamBreak(dp=0.1, until=0.1)"),
                 "README.md", "exec"), {})
    printed = capsys.readouterr().out
    assert "RMS relative front error" in printed and re.search(r"^[0-9a-f]{64}$", printed, re.M)


@pytest.mark.parametrize("script", sorted(p.name for p in EXAMPLES.glob("*.py")
                                          if "__main__" in p.read_text()))
def test_example_scripts_start_as_documented(script: str, monkeypatch: pytest.MonkeyPatch,
                                             capsys: pytest.CaptureFixture[str]) -> None:
    """Each script's --help from the package as installed (a script imports only watersim and
    its sibling modules), and its docstring's commands name the script as the user runs it."""
    text = (EXAMPLES / script).read_text()
    for bad in ("PYTHONPATH", "/work/", "../shared"):
        assert bad not in text, (script, bad)
    monkeypatch.setattr(sys, "argv", [script, "--help"])
    with pytest.raises(SystemExit) as done:
        runpy.run_path(str(EXAMPLES / script), run_name="__main__")
    assert done.value.code == 0 and "usage:" in capsys.readouterr().out
    documented = re.findall(r"python3? (examples/\S+\.py)", text)
    assert all(name == f"examples/{script}" or (ROOT / name).is_file() for name in documented)


def test_the_readme_and_guide_ask_for_no_pythonpath() -> None:
    for doc in (README, ROOT / "docs" / "user-guide.md"):
        assert "PYTHONPATH=python" not in doc.read_text(), doc


def test_the_readme_states_the_rust_version_of_the_workspace() -> None:
    version = re.search(r'^rust-version = "([0-9.]+)"', (ROOT / "Cargo.toml").read_text(), re.M)
    assert version is not None
    assert f"Rust {version.group(1)} or newer" in README.read_text()
    assert "pip install -v ." in README.read_text()  # the build's progress


def test_summary_of_the_first_command_names_its_files(tmp_path: Path,
                                                      monkeypatch: pytest.MonkeyPatch) -> None:
    """The Quick start's dam break (shortened) writes the files the README names, where it
    says."""
    (first,) = [c for c in _commands() if c[:2] == ["run", "dambreak2d"] and len(c) == 2]
    monkeypatch.chdir(tmp_path)
    assert cli.main([*first, "--set", "dp=0.1", "--set", "until=0.1", "--quiet"]) == 0
    text = README.read_text()
    for name in ("runs/dambreak2d-builtin/summary.json", "runs/dambreak2d-builtin/front.csv"):
        assert name in text and (tmp_path / name).is_file()
    header = (tmp_path / "runs/dambreak2d-builtin/front.csv").read_text().splitlines()[0]
    assert "t_s" in header and "x_front_m" in header
    summary = json.loads((tmp_path / "runs/dambreak2d-builtin/summary.json").read_text())
    assert "Martin & Moyce 1952" in text and "rms_rel_error" in summary["martin_moyce"]
