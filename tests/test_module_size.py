"""Size limits of python/watersim: no module above 1,100 lines but the two pure libraries, no
function above 100 lines.

A module that outgrows the limit holds more than one responsibility (split it, as the command
line's ``bench`` went to :mod:`watersim.bench_command`); a function that outgrows it does several
things in a row (split it into its steps, as ``watersim run`` for a flume: set-up, run,
analysis, summary). The two pure libraries, the wave theories and the signal analysis, are
collections of independent functions and may be longer.
"""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "python" / "watersim"

MAX_MODULE_LINES = 1100
MAX_FUNCTION_LINES = 100
LONG_LIBRARIES = {"wave_theory.py", "analysis.py"}
"""Modules of independent pure functions, exempt from the module limit (not the function one)."""


def _modules() -> list[Path]:
    return sorted(PACKAGE.rglob("*.py"))


def _name(path: Path) -> str:
    return str(path.relative_to(PACKAGE.parent))


def test_the_package_is_seen() -> None:
    names = {_name(p) for p in _modules()}
    assert "watersim/cli.py" in names and "watersim/flume/scene.py" in names


def test_no_module_above_the_limit() -> None:
    long = {_name(p): n for p in _modules() if p.name not in LONG_LIBRARIES
            and (n := len(p.read_text(encoding="utf-8").splitlines())) > MAX_MODULE_LINES}
    assert not long, f"modules above {MAX_MODULE_LINES} lines: {long}"


def test_no_function_above_the_limit() -> None:
    """Every function and method, nested ones included, from its ``def`` (decorators left out)
    to its last line."""
    long: dict[str, int] = {}
    for path in _modules():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                assert node.end_lineno is not None
                lines = node.end_lineno - node.lineno + 1
                if lines > MAX_FUNCTION_LINES:
                    long[f"{_name(path)}:{node.lineno} {node.name}"] = lines
    assert not long, f"functions above {MAX_FUNCTION_LINES} lines: {long}"
