"""Checks of single builder fields, shared by every builder and model class: each returns the
value as its type or raises :class:`~watersim.SceneError` naming the field (``"field: reason"``)."""

from __future__ import annotations

import math
from typing import Any

from ._core import SceneError


def _number(name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise SceneError(f"{name}: expected a number, got {value!r}")
    v = float(value)
    if not math.isfinite(v):
        raise SceneError(f"{name}: must be a finite number, got {value!r}")
    return v


def _positive(name: str, value: Any) -> float:
    v = _number(name, value)
    if v <= 0.0:
        raise SceneError(f"{name}: must be positive, got {value!r}")
    return v


def _non_negative(name: str, value: Any) -> float:
    v = _number(name, value)
    if v < 0.0:
        raise SceneError(f"{name}: must not be negative, got {value!r}")
    return v


def _integer(name: str, value: Any, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise SceneError(f"{name}: expected an integer, got {value!r}")
    if value < minimum:
        raise SceneError(f"{name}: must be at least {minimum}, got {value!r}")
    return value


def _choice(name: str, value: Any, allowed: tuple[str, ...]) -> str:
    if not isinstance(value, str) or value not in allowed:
        options = ", ".join(repr(a) for a in allowed)
        raise SceneError(f"{name}: unknown value {value!r}; allowed: {options}")
    return value
