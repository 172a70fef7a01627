"""Small input checks shared by the flume's models (each raises SceneError naming the field)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from .._core import SceneError

_TOL = 1e-9


def _finite_tuple(name: str, values: Any, min_len: int = 1) -> tuple[float, ...]:
    """``values`` as a tuple of finite floats with at least ``min_len`` entries."""
    if isinstance(values, (str, bytes)):
        raise SceneError(f"{name}: expected a sequence of numbers, got {values!r}")
    try:
        arr = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise SceneError(f"{name}: expected a sequence of numbers, got {values!r}") from None
    if arr.ndim != 1:
        raise SceneError(f"{name}: expected a 1-D sequence of numbers, got shape {arr.shape}")
    if arr.size < min_len:
        raise SceneError(f"{name}: needs at least {min_len} values, got {arr.size}")
    if not np.all(np.isfinite(arr)):
        raise SceneError(f"{name}: values must be finite, got {arr.tolist()}")
    return tuple(float(v) for v in arr)


def _strictly_increasing(name: str, values: Sequence[float]) -> None:
    """SceneError ``name: must increase strictly (v[i] >= v[i + 1])``, ``v`` the last part of
    ``name``, at the first pair that does not increase."""
    symbol = name.rsplit(".", 1)[-1]
    for i in range(len(values) - 1):
        if not values[i + 1] > values[i]:
            raise SceneError(f"{name}: must increase strictly ({symbol}[{i}] >= {symbol}[{i + 1}])")


def _optional_name(name: str, value: Any) -> None:
    if value is None:
        return
    if not isinstance(value, str) or not value.strip():
        raise SceneError(f"{name}: must be a non-empty string, got {value!r}")
    if "," in value or "\n" in value:
        raise SceneError(f"{name}: must not contain commas or line breaks, got {value!r}")


def _set(obj: Any, name: str, value: Any) -> None:
    object.__setattr__(obj, name, value)


def expected(classes: Sequence[type]) -> str:
    """``an A, B or C``: what a refusal says it expected."""
    names = [c.__name__ for c in classes]
    article = "an" if names[0][0] in "AEIOU" else "a"
    return f"{article} {', '.join(names[:-1])} or {names[-1]}"


def _models_of(obj: Any, field: str, classes: tuple[type, ...]) -> tuple[Any, ...]:
    """The models of ``obj.field`` (one of them, or a sequence) as a tuple, each one of
    ``classes``; set on ``obj`` and returned."""
    value = getattr(obj, field)
    if isinstance(value, classes):
        value = (value,)
    try:
        models = tuple(value)
    except TypeError:
        raise SceneError(f"{field}: expected a sequence of {field}, got {value!r}") from None
    for i, model in enumerate(models):
        if not isinstance(model, classes):
            raise SceneError(f"{field}[{i}]: expected {expected(classes)}, got {model!r}")
    _set(obj, field, models)
    return models
