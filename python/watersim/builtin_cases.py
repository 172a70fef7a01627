"""The built-in cases of the ``watersim`` command and their ``--set`` overrides.

The verification cases (:data:`CASES`: a dam break and a still tank, 2D and 3D) take any field
of their builder (:class:`~watersim.DamBreak` or :class:`~watersim.Tank`) but those the case
fixes; the wave-flume cases (:data:`watersim.flume_cases.FLUME_CASES`) take their numerical
parameters and the dotted keys of their objects. A scene file (``FILE.toml``) takes any dotted
key of the file. Every ``key=value`` is read by :mod:`watersim.overrides`.
"""

from __future__ import annotations

import typing
from collections.abc import Sequence
from typing import Any

from . import numerics as nm
from . import overrides
from .errors import CliError, did_you_mean
from .flume_cases import FLUME_CASES, flume_builder, flume_settable_keys
from .scenefile import is_scene_file, scene_files_near
from .scenefile import load as load_scene_file
from .scenes import DamBreak, SceneBuilder, Tank

__all__ = ["ALL_CASES", "CASES", "SET_HELP", "builder_from_args", "settable_keys"]

CASES: dict[str, tuple[type[SceneBuilder], dict[str, Any]]] = {
    "dambreak2d": (DamBreak, {"dim": 2}),
    "dambreak3d": (DamBreak, {"dim": 3}),
    "tank2d": (Tank, {"dim": 2}),
    "tank3d": (Tank, {"dim": 3}),
}
"""Built-in cases: builder class and the fields the case fixes."""

ALL_CASES: tuple[str, ...] = (*CASES, *FLUME_CASES)
"""Every case ``watersim run`` knows: the verification cases, then the wave-flume cases."""

SET_HELP = "override a case parameter (repeatable), e.g. --set dp=0.04"
"""The help of every command's ``--set``."""


def settable_keys(case: str) -> list[str]:
    """Fields of ``case`` that ``--set`` may change (all but those the case fixes)."""
    if case in FLUME_CASES:
        return flume_settable_keys(case)
    cls, fixed = CASES[case]
    skip = set(fixed)
    if fixed.get("dim") == 2:
        skip.update(cls.THREE_D_ONLY)
    options = [key for name in nm.OPTION_CLASSES for key in nm.option_keys(name)]
    return sorted([name for name in cls.field_names()
                   if name not in skip and name not in nm.OPTION_CLASSES] + options)


def builder_from_args(case: str, settings: Sequence[str]) -> SceneBuilder:
    """The case's builder with ``key=value`` overrides applied (and checked).

    Raises:
        CliError: unknown case or key, or a value of the wrong type.
        SceneError: a value the builder refuses (a scene file's errors name the key's path).
    """
    if is_scene_file(case):
        return load_scene_file(case, settings).builder
    if case in FLUME_CASES:
        return flume_builder(case, {o.key: o.text for o in overrides.parse(settings)})
    if case not in CASES:
        hint = did_you_mean(case, [*ALL_CASES, *scene_files_near(case)])
        raise CliError(f"case: unknown case {case!r}{hint}; valid cases: {', '.join(ALL_CASES)} "
                       "or a scene file FILE.toml")
    cls, fixed = CASES[case]
    valid = settable_keys(case)
    hints = typing.get_type_hints(cls)
    values: dict[str, Any] = {}
    option_items: dict[str, str] = {}
    for item in overrides.parse(settings):
        if item.key not in valid:
            why = (f"is fixed by the case {case}" if item.key in fixed
                   else f"is unknown for {case}{did_you_mean(item.key, valid)}")
            raise CliError(f"--set: key {item.key!r} {why}; valid keys: {', '.join(valid)}")
        if item.key.partition(".")[0] in nm.OPTION_CLASSES:
            option_items[item.key] = item.text
        else:
            values[item.key] = item.typed(hints[item.key])
    if option_items:
        case_builder = cls(**fixed)  # the case's own options, which the items change
        for name in nm.OPTION_CLASSES:
            values[name] = nm.from_settings(name, getattr(case_builder, name), option_items)
    return cls(**fixed, **values)
