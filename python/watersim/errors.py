"""The command line's error type, in a module of its own so that every command's module
(:mod:`watersim.cli`, :mod:`watersim.stress`, :mod:`watersim.overrides`, ...) can raise it
without importing the command line."""

from __future__ import annotations

__all__ = ["CliError"]


class CliError(Exception):
    """Bad command-line input: printed as one line, exit code 2."""
