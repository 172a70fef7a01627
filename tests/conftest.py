"""Shared helpers. Every test runs against the real compiled extension ``watersim._core``."""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Mapping
from pathlib import Path

import pytest
from hypothesis import settings

import watersim._core  # noqa: F401  (fail loudly, not skip, when the extension is missing)

# No example database: nothing written into the work tree, and every run draws afresh.
settings.register_profile("watersim", database=None, deadline=None)
settings.load_profile("watersim")


def run_cli(
    *args: str, env: Mapping[str, str] | None = None, cwd: Path | None = None, timeout: float = 900
) -> subprocess.CompletedProcess[str]:
    """Run ``python -m watersim ARGS`` in a subprocess and capture its output."""
    full_env = dict(os.environ)
    full_env.update(env or {})
    return subprocess.run(
        [sys.executable, "-m", "watersim", *args],
        capture_output=True,
        text=True,
        env=full_env,
        cwd=cwd,
        timeout=timeout,
        check=False,
    )


def assert_clean_failure(proc: subprocess.CompletedProcess[str], *needles: str) -> None:
    """A refused input: non-zero exit, a one-line message naming ``needles``, no traceback."""
    assert proc.returncode != 0, proc.stdout + proc.stderr
    for needle in needles:
        assert needle in proc.stderr, proc.stderr
    for forbidden in ("Traceback", "panicked", "RUST_BACKTRACE"):
        assert forbidden not in proc.stderr + proc.stdout


@pytest.fixture()
def cli():
    """The :func:`run_cli` helper as a fixture."""
    return run_cli
