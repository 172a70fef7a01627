"""``--set key=value`` parsing shared by the command line (:mod:`watersim.cli`) and the built-in
flume cases (:mod:`watersim.flume_cases`); scene files parse their values as TOML instead
(:func:`watersim.scenefile.apply_settings`)."""

from __future__ import annotations

import types
import typing
from typing import Any

NONE_WORDS: tuple[str, ...] = ("none", "null", "auto")
"""Values that leave an optional field unset (it then takes its default)."""


def split_setting(item: str) -> tuple[str, str] | None:
    """``"key=value"`` as ``(key, value)`` (key stripped, value as given); None without ``=`` or
    without a key."""
    key, sep, text = item.partition("=")
    key = key.strip()
    if not sep or not key:
        return None
    return key, text


def _optional(hint: Any) -> tuple[Any, bool]:
    """``(X, True)`` for a hint ``X | None`` (the first member other than None), else
    ``(hint, False)``."""
    if isinstance(hint, types.UnionType) or typing.get_origin(hint) is typing.Union:
        args = [a for a in typing.get_args(hint) if a is not type(None)]
        return args[0], len(args) < len(typing.get_args(hint))
    return hint, False


def is_scalar(hint: Any) -> bool:
    """Whether a field of this type can be set from one ``--set`` value."""
    if isinstance(hint, types.UnionType) or typing.get_origin(hint) is typing.Union:
        args = [a for a in typing.get_args(hint) if a is not type(None)]
        return len(args) == 1 and is_scalar(args[0])
    return hint in (float, int, bool, str)


def parse_setting(hint: Any, key: str, text: str, error: type[Exception]) -> Any:
    """``text`` converted to the type ``hint`` (float, int, bool, str, or optional of those).

    Raises:
        error: ``"key: expected ..., got 'text'"`` when ``text`` is not of that type.
    """
    hint, optional = _optional(hint)
    value = text.strip()
    if optional and value.lower() in NONE_WORDS:
        return None
    if hint is bool:
        if value.lower() in ("1", "true", "yes", "on"):
            return True
        if value.lower() in ("0", "false", "no", "off"):
            return False
        raise error(f"{key}: expected true or false, got {text!r}")
    if hint is float:
        try:
            return float(value)
        except ValueError:
            raise error(f"{key}: expected a number, got {text!r}") from None
    if hint is int:
        try:
            return int(value)
        except ValueError:
            raise error(f"{key}: expected an integer, got {text!r}") from None
    return value
