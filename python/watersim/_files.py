"""Writing output files safely: the one place where a file is replaced atomically.

Every file a run rewrites (summary.json, gauges.csv, checkpoints, scene.toml, snapshots, ...)
goes through :func:`atomic_path`: the new content is written to a temporary file of a unique
name in the target's folder and renamed over the target, so that a reader never sees half a
file and a killed run leaves the previous version. Targets that are not regular files (a
device such as ``/dev/null``, a folder, a FIFO) are refused rather than replaced, a failed write
removes its temporary file, and an error names the file it was writing (a full disk says which
file it could not write).
"""

from __future__ import annotations

import contextlib
import os
import stat
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import IO, Any

__all__ = ["OutputFileError", "atomic_path", "atomic_write", "check_output_file", "named_errors",
           "write_text_atomic"]


class OutputFileError(OSError):
    """A file that cannot be written, with its name and the reason (the command line prints it
    on one line and exits with 2)."""


_KINDS = ((stat.S_ISDIR, "a folder"), (stat.S_ISCHR, "a character device"),
          (stat.S_ISBLK, "a block device"), (stat.S_ISFIFO, "a FIFO"),
          (stat.S_ISSOCK, "a socket"))


def _kind(mode: int) -> str:
    return next((name for test, name in _KINDS if test(mode)), "not a regular file")


def _resolved(path: str | os.PathLike[str]) -> Path:
    """``path`` with a link followed (a link to a file keeps pointing at the rewritten file)."""
    target = Path(path)
    if "\0" in str(target):
        raise OutputFileError(f"{str(target)!r}: a file name cannot hold a NUL byte")
    return target.resolve() if target.is_symlink() else target


def check_output_file(path: str | os.PathLike[str]) -> Path:
    """``path``, checked as a file to write before any work is done: an existing folder for it,
    writable, and no existing non-regular file at its place.

    Raises:
        OutputFileError: naming the file and what is wrong.
    """
    target = _resolved(path)
    try:
        mode = os.stat(target).st_mode
    except FileNotFoundError:
        mode = None
    except OSError as exc:
        raise OutputFileError(f"{target}: cannot be written ({exc.strerror})") from None
    if mode is not None and not stat.S_ISREG(mode):
        raise OutputFileError(f"{target}: is {_kind(mode)}, not a regular file; give a file path")
    folder = target.parent
    if not folder.is_dir():
        raise OutputFileError(f"{target}: its folder {folder} does not exist")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise OutputFileError(f"{target}: its folder {folder} is not writable")
    return target


def _new_file_mode(target: Path) -> int:
    """The permissions the written file gets: the replaced file's, else the default of a new
    file under the process's umask (a temporary file is created private)."""
    try:
        return stat.S_IMODE(os.stat(target).st_mode)
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask


@contextlib.contextmanager
def named_errors(path: str | os.PathLike[str]) -> Iterator[None]:
    """Turns an :class:`OSError` of the block (a full disk, a read-only folder) into an
    :class:`OutputFileError` naming ``path``."""
    try:
        yield
    except OutputFileError:
        raise
    except OSError as exc:
        reason = exc.strerror or str(exc)
        raise OutputFileError(f"{path}: cannot be written ({reason})") from exc


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike[str], suffix: str = "") -> Iterator[Path]:
    """A temporary path to write the new content of ``path`` to; renamed over ``path`` when the
    block ends without an error, removed when it fails.

    ``suffix`` ends the temporary name (writers that choose a format by the name's ending:
    ``".vtu"``). Yields the temporary path (an empty file of a unique name in the target's
    folder).

    Raises:
        OutputFileError: the target is not a regular file, or writing it failed (naming it).
    """
    target = check_output_file(path)
    with named_errors(target):
        fd, name = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.",
                                    suffix=f".tmp{suffix}")
        os.close(fd)
        tmp = Path(name)
        try:
            yield tmp
            os.chmod(tmp, _new_file_mode(target))
            os.replace(tmp, target)
        except BaseException:
            tmp.unlink(missing_ok=True)
            raise


@contextlib.contextmanager
def atomic_write(path: str | os.PathLike[str], mode: str = "w",
                 **open_options: Any) -> Iterator[IO[Any]]:
    """An open file (``mode`` ``"w"`` or ``"wb"``, :func:`open`'s ``open_options``) whose
    content replaces ``path`` when the block ends without an error (:func:`atomic_path`)."""
    with atomic_path(path) as tmp, open(tmp, mode, **open_options) as f:
        yield f


def write_text_atomic(path: str | os.PathLike[str], text: str) -> None:
    """Replaces ``path`` with ``text`` (UTF-8) atomically (:func:`atomic_path`)."""
    with atomic_write(path, "w", encoding="utf-8") as f:
        f.write(text)
