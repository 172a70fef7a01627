"""A run's memory counted before it starts (issue 33 item 5): gauge records grow by their values
per sample times the samples, and a run that would not fit is refused naming the gauge, with
the estimate, before its folder is made; a real run's peak stays under its estimate."""

from __future__ import annotations

import dataclasses
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import watersim as ws
from conftest import run_cli
from watersim.run_memory import GIB, estimate_run_memory

WINDOW = """type = "flume"
dp = 0.05
until = {until}

[flume]
length = 6.0
depth = 0.3

[wave]
type = "regular"
height = 0.04
period = 1.2

[[gauges]]
type = "window"
min = [1.0, 0.05]
max = [3.0, 0.35]
n = [{nx}, {nz}]
interval = {interval}
"""


def _scene(tmp_path: Path, nx: int, nz: int, interval: float, until: float = 10.0) -> Path:
    path = tmp_path / "window.toml"
    path.write_text(WINDOW.format(nx=nx, nz=nz, interval=interval, until=until))
    return path


def test_a_megapoint_window_every_hundredth_second_is_refused_before_the_run(
        tmp_path: Path) -> None:
    out = tmp_path / "out"
    proc = run_cli("run", str(_scene(tmp_path, 1000, 1000, 0.01)), "--out", str(out))
    assert proc.returncode == 2, proc.stdout + proc.stderr
    assert "Traceback" not in proc.stderr
    message = proc.stderr.strip().splitlines()[-1]
    assert "gauges[0].interval" in message and "3000000 values a sample" in message, message
    assert "1002 samples" in message and re.search(r"\d+(\.\d+)? GiB of record", message)
    assert not out.exists()


@settings(max_examples=12, deadline=None)
@given(nx=st.integers(1, 400), nz=st.integers(1, 400),
       interval=st.sampled_from([0.005, 0.01, 0.05, 0.2]))
def test_records_are_counted_and_refused_past_the_limit(tmp_path_factory: pytest.TempPathFactory,
                                                        nx: int, nz: int,
                                                        interval: float) -> None:
    path = _scene(tmp_path_factory.mktemp("w"), nx, nz, interval)
    sim = ws.load_scene(path).builder.build()
    estimate = estimate_run_memory(sim, 10.0, flume=True)
    (record,) = estimate.gauges
    assert record.values_per_sample == 3 * nx * nz  # 2D velocity and kernel sum per point
    assert record.samples == int(10.0 / interval + 1e-9) + 2
    assert record.bytes == 8 * (3 * nx * nz + 1) * record.samples
    assert estimate.records == 7 * record.bytes  # core 3, decoded copies 2, last good 2
    tight = dataclasses.replace(estimate, limit=estimate.total * 0.999)
    with pytest.raises(ws.SceneError) as info:
        tight.check()
    blamed = "gauges[0].interval:" if estimate.records >= max(
        estimate.resident, estimate.mesh, estimate.last_good, estimate.passing) else "dp:"
    assert str(info.value).startswith(blamed), str(info.value)
    dataclasses.replace(estimate, limit=estimate.total * 1.001).check()


def test_a_run_peaks_under_its_estimate(tmp_path: Path) -> None:
    """The estimate the run prints against its peak resident set, read by a fresh parent whose
    only child is the run (``RUSAGE_CHILDREN``)."""
    run = [sys.executable, "-m", "watersim", "run", "dambreak2d", "--set", "dp=0.01",
           "--set", "until=0.02", "--snapshot-every", "0.01", "--out", str(tmp_path / "o")]
    parent = ("import resource, subprocess, sys; "
              f"p = subprocess.run({run!r}, capture_output=True, text=True); "
              "sys.stderr.write(p.stderr); print(p.stdout); print(p.returncode); "
              "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)")
    proc = subprocess.run([sys.executable, "-c", parent], capture_output=True, text=True,
                          timeout=900, env={**os.environ, "RAYON_NUM_THREADS": "1"})
    *lines, code, peak_kib = proc.stdout.strip().splitlines()
    assert code == "0", proc.stderr
    found = re.search(r"memory: about ([0-9.e+]+) GiB", "\n".join(lines))
    assert found, lines
    estimate = float(found.group(1)) * GIB
    peak = int(peak_kib) * 1024
    assert peak <= estimate, (peak, estimate)
