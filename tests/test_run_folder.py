"""A run owns its folder (issue 33 items 1 and 2): a lock held for the run's life, a second run
into a folder being written refused, summary.json written first with the status ``running``,
``--overwrite`` clearing only the files a run writes; SIGTERM and SIGKILL during a run."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from watersim import cli, rundir

LONG_RUN = ["run", "dambreak2d", "--set", "dp=0.1", "--set", "until=100", "--quiet"]
"""A tiny dam break (482 particles) that runs for minutes unless stopped."""


def _start(out: Path, *extra: str) -> subprocess.Popen[str]:
    """A long run into ``out``, returned once it holds the folder and has sampled once."""
    proc = subprocess.Popen([sys.executable, "-m", "watersim", *LONG_RUN, "--out", str(out),
                             *extra], env={**os.environ, "RAYON_NUM_THREADS": "1"},
                            stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60.0
    log = out / "log.jsonl"
    while time.monotonic() < deadline and proc.poll() is None:
        if log.is_file() and log.read_text().count('"sample"') >= 2:
            return proc
        time.sleep(0.05)
    proc.kill()
    pytest.fail(f"the run did not start: {proc.communicate()[1]}")


def _summary(out: Path) -> dict:  # type: ignore[type-arg]
    return json.loads((out / "summary.json").read_text())


def test_a_second_run_into_a_folder_being_written_is_refused(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "shared"
    proc = _start(out)
    try:
        assert _summary(out)["status"] == "running"
        assert (out / rundir.LOCK_FILE).read_text().strip() == str(proc.pid)
        for extra in ([], ["--overwrite"]):
            assert cli.main([*LONG_RUN, "--out", str(out), *extra]) == 2
            err = capsys.readouterr().err
            assert "another run" in err and str(proc.pid) in err
            assert len(err.strip().splitlines()) == 1
        assert _summary(out)["status"] == "running"  # the running one's, untouched
    finally:
        proc.kill()
        proc.communicate()
    # killed: its summary says it never ended, its lock died with it, the folder is refused
    assert _summary(out)["status"] == "running"
    assert cli.main([*LONG_RUN, "--out", str(out)]) == 2
    assert "status running" in capsys.readouterr().err


def test_sigterm_ends_a_run_like_ctrl_c(tmp_path: Path) -> None:
    out = tmp_path / "term"
    proc = _start(out)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=30)
    assert proc.returncode == 128 + signal.SIGTERM, err
    assert "SIGTERM" in err and len(err.strip().splitlines()) == 1
    summary = _summary(out)
    assert summary["status"] == "terminated"
    assert summary["last_good"]["path"] == str(out / "last_good.npz")
    assert (out / "last_good.npz").is_file()
    events = [json.loads(line) for line in (out / "log.jsonl").read_text().splitlines()]
    assert events[-1]["event"] == "end" and events[-1]["status"] == "terminated"
    assert not (out / rundir.LOCK_FILE).exists()
    assert sorted(p.name for p in out.iterdir()) == ["front.csv", "last_good.npz", "log.jsonl",
                                                     "summary.json"]


def test_overwrite_clears_only_what_a_run_writes(tmp_path: Path) -> None:
    out = tmp_path / "run"
    (out / "snapshots").mkdir(parents=True)
    (out / "snapshots" / "particles_00007.vtu").write_text("old")
    (out / "snapshots" / "particles.pvd").write_text("old")
    (out / "snapshots" / "my_notes.txt").write_text("mine")
    (out / "checkpoints").mkdir()
    (out / "checkpoints" / "ckpt_000000000010.npz").write_text("old")
    (out / "front.csv").write_text("old")
    assert cli.main(["run", "tank2d", "--set", "dp=0.1", "--set", "until=0.01", "--quiet",
                     "--out", str(out), "--overwrite"]) == 0
    assert (out / "snapshots" / "my_notes.txt").read_text() == "mine"
    assert sorted(p.name for p in (out / "snapshots").iterdir()) == ["my_notes.txt"]
    assert not (out / "checkpoints").exists() and not (out / "front.csv").exists()
    assert _summary(out)["status"] == "ok"


def _in_namespace(script: str) -> subprocess.CompletedProcess[str]:
    """``script`` run by sh in a new user and mount namespace (where it may mount), or a skip
    when this machine does not allow one."""
    if subprocess.run(["unshare", "-rm", "true"], capture_output=True).returncode != 0:
        pytest.skip("cannot create a user and mount namespace here (unshare -rm) to mount in")
    return subprocess.run(["unshare", "-rm", "sh", "-c", script], capture_output=True, text=True,
                          env={**os.environ, "RAYON_NUM_THREADS": "1"}, timeout=120)


WATERSIM = f"{sys.executable} -m watersim"


def test_a_full_disk_names_the_file_and_leaves_no_temporary(tmp_path: Path) -> None:
    disk = tmp_path / "disk"
    disk.mkdir()
    proc = _in_namespace(
        f"mount -t tmpfs -o size=48k tmpfs {disk} && {WATERSIM} run dambreak2d --set dp=0.1 "
        f"--set until=3 --quiet --out {disk}/run; echo rc=$?; ls -a {disk}/run")
    assert "rc=2" in proc.stdout, proc.stderr
    err = proc.stderr.strip().splitlines()
    assert len(err) == 1 and "No space left on device" in err[0]
    assert f"{disk}/run/" in err[0]  # names the file
    assert ".tmp" not in proc.stdout and rundir.LOCK_FILE not in proc.stdout


def test_save_last_good_is_checked_before_the_run(tmp_path: Path,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "run"
    for target, expected in ((tmp_path, "a folder"), (Path("/dev/null"), "character device"),
                             (tmp_path / "missing" / "lg.npz", "does not exist")):
        assert cli.main(["run", "dambreak2d", "--set", "dp=0.1", "--quiet", "--out", str(out),
                         "--save-last-good", str(target)]) == 2
        assert expected in capsys.readouterr().err
        assert not out.exists()  # refused before the run
    read_only = tmp_path / "ro"
    read_only.mkdir()
    proc = _in_namespace(
        f"mount --bind {read_only} {read_only} && mount -o remount,bind,ro {read_only} && "
        f"{WATERSIM} run dambreak2d --set dp=0.1 --set until=0.05 --quiet --out {out} "
        f"--save-last-good {read_only}/lg.npz; echo rc=$?")
    assert "rc=2" in proc.stdout and "not writable" in proc.stderr and not out.exists()


def test_a_second_ctrl_c_after_the_run_still_leaves_the_summary(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
        capsys: pytest.CaptureFixture[str]) -> None:
    summary = cli._Run.summary

    def interrupted_summary(self: cli._Run, *args: object, **kwargs: object) -> dict:  # type: ignore[type-arg]
        os.kill(os.getpid(), signal.SIGINT)  # held back until the summary is written
        return summary(self, *args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(cli._Run, "summary", interrupted_summary)
    out = tmp_path / "run"
    assert cli.main(["run", "tank2d", "--set", "dp=0.1", "--set", "until=0.01", "--quiet",
                     "--out", str(out)]) == 128 + signal.SIGINT
    assert "interrupted" in capsys.readouterr().err
    assert _summary(out)["status"] == "ok"
    assert not (out / rundir.LOCK_FILE).exists()
