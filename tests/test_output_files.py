"""Atomic output files (:mod:`watersim._files`): unique temporary names in the target's folder,
special files refused rather than replaced, no temporary file left after a failure, errors that
name the file."""

from __future__ import annotations

import os
import stat
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from watersim._files import (
    OutputFileError,
    atomic_path,
    atomic_write,
    check_output_file,
    write_text_atomic,
)


def test_replaces_a_file_and_leaves_nothing_else(tmp_path: Path) -> None:
    target = tmp_path / "summary.json"
    target.write_text("old")
    target.chmod(0o640)
    write_text_atomic(target, "new")
    assert target.read_text() == "new"
    assert stat.S_IMODE(target.stat().st_mode) == 0o640  # the replaced file's permissions
    assert sorted(p.name for p in tmp_path.iterdir()) == ["summary.json"]


def test_a_new_file_gets_the_umask_default_permissions(tmp_path: Path) -> None:
    umask = os.umask(0o022)
    try:
        write_text_atomic(tmp_path / "a.csv", "x")
    finally:
        os.umask(umask)
    assert stat.S_IMODE((tmp_path / "a.csv").stat().st_mode) == 0o644


@pytest.mark.parametrize("kind", ["device", "folder", "fifo"])
def test_special_files_are_refused_and_left_alone(kind: str, tmp_path: Path) -> None:
    if kind == "device":
        target = Path("/dev/null")
        expected = "character device"
    elif kind == "folder":
        target = tmp_path / "out"
        target.mkdir()
        expected = "a folder"
    else:
        target = tmp_path / "pipe"
        os.mkfifo(target)
        expected = "a FIFO"
    before = os.stat(target)
    with pytest.raises(OutputFileError, match=expected) as info:
        write_text_atomic(target, "x")
    assert str(target) in str(info.value)
    after = os.stat(target)
    assert (after.st_ino, after.st_mode, after.st_rdev) == (before.st_ino, before.st_mode,
                                                           before.st_rdev)
    if kind != "device":
        assert sorted(p.name for p in tmp_path.iterdir()) == [target.name]


def test_a_failed_write_removes_its_temporary_file_and_keeps_the_old(tmp_path: Path) -> None:
    target = tmp_path / "gauges.csv"
    target.write_text("old")
    with pytest.raises(ZeroDivisionError), atomic_write(target) as f:
        f.write("half")
        _ = 1 / 0
    assert target.read_text() == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["gauges.csv"]


def test_temporary_names_are_unique_and_in_the_target_folder(tmp_path: Path) -> None:
    target = tmp_path / "ckpt.npz"
    with atomic_path(target) as first, atomic_path(target, suffix=".vtu") as second:
        assert first != second and first.parent == second.parent == tmp_path
        assert second.name.endswith(".vtu") and first.name != "ckpt.npz.tmp"
        first.write_text("1")
        second.write_text("2")
    assert target.read_text() == "1"  # the last one renamed wins, whole


def test_a_link_to_a_file_stays_a_link(tmp_path: Path) -> None:
    real = tmp_path / "real.json"
    real.write_text("old")
    link = tmp_path / "link.json"
    link.symlink_to(real)
    write_text_atomic(link, "new")
    assert link.is_symlink() and real.read_text() == "new"


def test_check_names_what_is_wrong(tmp_path: Path) -> None:
    with pytest.raises(OutputFileError, match="does not exist"):
        check_output_file(tmp_path / "missing" / "x.npz")
    with pytest.raises(OutputFileError, match="NUL byte"):
        check_output_file(str(tmp_path / "a\0b"))
    assert check_output_file(tmp_path / "x.npz") == tmp_path / "x.npz"


@settings(max_examples=30, deadline=None)
@given(name=st.text(st.characters(blacklist_categories=("Cs", "Cc"), blacklist_characters="/"),
                    min_size=1, max_size=40).filter(lambda s: s not in (".", "..")),
       text=st.text(max_size=200))
def test_any_file_name_round_trips_and_leaves_only_the_target(
        name: str, text: str, tmp_path_factory: pytest.TempPathFactory) -> None:
    folder = tmp_path_factory.mktemp("names")
    try:
        write_text_atomic(folder / name, text)
    except OutputFileError as exc:  # a name too long for the file system, named
        assert "File name too long" in str(exc)
        return
    assert (folder / name).read_bytes().decode("utf-8") == text
    assert [p.name for p in folder.iterdir()] == [name]
