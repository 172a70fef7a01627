"""The command line's error type, in a module of its own so that every command's module
(:mod:`watersim.cli`, :mod:`watersim.stress`, :mod:`watersim.overrides`, ...) can raise it
without importing the command line; and the "did you mean" hint their messages share."""

from __future__ import annotations

import difflib
from collections.abc import Iterable

__all__ = ["CliError", "did_you_mean"]


class CliError(Exception):
    """Bad command-line input: printed as one line, exit code 2."""


def did_you_mean(word: str, choices: Iterable[str]) -> str:
    """``" (did you mean 'x'?)"`` for the choice closest to a mistyped ``word`` (difflib's
    ratio of at least 0.6, or a choice that differs only in case: ``Dp`` for ``dp``), or ``""``
    when none is close."""
    options = list(choices)
    close = difflib.get_close_matches(word, options, n=1)
    if not close:
        lowered = {option.lower(): option for option in reversed(options)}
        close = [lowered[c] for c in difflib.get_close_matches(word.lower(), list(lowered), n=1)]
    return f" (did you mean {close[0]!r}?)" if close else ""
