"""``--set key=value`` overrides: the one parser behind every entry point.

An override is ``key=value``. The key is a dotted path (``dp``, ``wave.height``,
``flume.beach.slope``; in a scene file also ``gauges[2].x``). The value is converted one of two
ways, depending on what it overrides:

- a field of a builder object (the built-in cases of ``watersim run``, ``watersim bench``,
  the flume cases that ``watersim validate`` builds): the text is converted to the field's type
  hint (:meth:`Override.typed`), and :class:`Overrides` hands the values out to the case's
  objects, recording every key the case offers;
- a scene file (:mod:`watersim.scenefile`): the text is a TOML value (:meth:`Override.toml`)
  written into the parsed document (:func:`apply_to_document`), which is then checked like the
  file itself.

Every refusal is an :class:`OverrideError` whose message starts with the dotted key.
"""

from __future__ import annotations

import dataclasses
import re
import types
import typing
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, TypeVar

from ._compat import tomllib
from .errors import CliError

__all__ = [
    "NONE_WORDS",
    "Override",
    "OverrideError",
    "Overrides",
    "apply_to_document",
    "is_scalar",
    "parse",
]

T = TypeVar("T")

NONE_WORDS: tuple[str, ...] = ("none", "null", "auto")
"""Values that leave an optional field unset (it then takes its default)."""

MAX_KEY_PARTS = 16
"""The most names a ``--set`` key joins by dots (the deepest real key has four)."""
MAX_KEY_LENGTH = 256
"""The longest ``--set`` key [characters]."""


def _check_key_size(key: str) -> None:
    """Refuses a key longer than :data:`MAX_KEY_LENGTH` or of more than :data:`MAX_KEY_PARTS`
    parts, quoting only its start (every --set is checked so, whatever reads it).

    Raises:
        OverrideError: naming ``--set``.
    """
    if len(key) > MAX_KEY_LENGTH or key.count(".") >= MAX_KEY_PARTS:
        raise OverrideError(f"--set: key too long ({len(key)} characters, "
                            f"{key.count('.') + 1} parts; at most {MAX_KEY_LENGTH} and "
                            f"{MAX_KEY_PARTS}): {key[:60]!r}...")


_TOKEN = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)((?:\[\d+\])*)$")

Token = str | int
"""One step of a key's path: a field name or an array index."""


class OverrideError(CliError):
    """A bad ``key=value``: the message names the key (the command line prints it, exit 2)."""


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


@dataclass(frozen=True)
class Override:
    """One ``key=value`` item.

    Attributes:
        key: the dotted key, stripped.
        text: the value as given.
    """

    key: str
    text: str

    @classmethod
    def parse(cls, item: str) -> Override:
        """A ``key=value`` item as an override.

        Raises:
            OverrideError: an item without ``=`` or without a key.
        """
        key, sep, text = item.partition("=")
        key = key.strip()
        if not sep or not key:
            raise OverrideError(f"--set: expected key=value, got {item!r}")
        _check_key_size(key)
        return cls(key, text)

    def path(self) -> list[Token]:
        """The key as a path: ``gauges[2].x`` -> ``["gauges", 2, "x"]``.

        Raises:
            OverrideError: a key that is not names joined by dots with ``[i]`` indices.
        """
        _check_key_size(self.key)
        out: list[Token] = []
        for part in self.key.split("."):
            m = _TOKEN.match(part.strip())
            if m is None:
                raise OverrideError(f"--set: bad key {self.key!r} (expected names joined by "
                                    "dots, with [i] for array items)")
            out.append(m.group(1))
            out.extend(int(i) for i in re.findall(r"\[(\d+)\]", m.group(2)))
        return out

    def typed(self, hint: Any) -> Any:
        """The value converted to the type ``hint`` (float, int, bool, str, or optional of
        those; a word of :data:`NONE_WORDS` gives None for an optional one).

        Raises:
            OverrideError: ``"key: expected ..., got 'text'"`` when the text is not of that type.
        """
        hint, optional = _optional(hint)
        value = self.text.strip()
        if optional and value.lower() in NONE_WORDS:
            return None
        if hint is bool:
            if value.lower() in ("1", "true", "yes", "on"):
                return True
            if value.lower() in ("0", "false", "no", "off"):
                return False
            raise OverrideError(f"{self.key}: expected true or false, got {self.text!r}")
        if hint is float:
            try:
                return float(value)
            except ValueError:
                raise OverrideError(f"{self.key}: expected a number, got {self.text!r}") from None
        if hint is int:
            try:
                return int(value)
            except ValueError:
                raise OverrideError(
                    f"{self.key}: expected an integer, got {self.text!r}") from None
        return value

    def toml(self) -> Any:
        """The value as a TOML value (``0.02``, ``2``, ``true``, ``[1.0, 2.0]``, ``"name"``),
        else the text itself as a string (``--set wave.type=irregular``)."""
        try:
            return tomllib.loads(f"v = {self.text}")["v"]
        except (ValueError, RecursionError):  # not TOML, a 5000-digit integer, deep nesting
            return self.text.strip()

    def clears(self, hint: Any) -> bool:
        """Whether the value is a word of :data:`NONE_WORDS` that unsets a field of type
        ``hint`` (optional, and not a string, which would take the word itself)."""
        members = typing.get_args(hint) if _optional(hint)[1] else ()
        return (self.text.strip().lower() in NONE_WORDS and type(None) in members
                and str not in members)


def parse(items: Sequence[str]) -> list[Override]:
    """``key=value`` items as overrides, in order (:meth:`Override.parse`)."""
    return [Override.parse(item) for item in items]


class Overrides:
    """The overrides of one run, handed out to a case's objects by their dotted keys.

    Every key a case offers is recorded in :attr:`keys`, whether or not it was set, so that the
    same case function lists its keys (run once with no values) and applies them.

    Args:
        items: key -> value text (the last of repeated keys).
    """

    def __init__(self, items: Mapping[str, str]) -> None:
        self.items = dict(items)
        self.keys: list[str] = []

    def _typed(self, key: str, hint: Any) -> Any:
        return Override(key, self.items[key]).typed(hint)

    def apply(self, prefix: str, obj: T, skip: tuple[str, ...] = ()) -> T:
        """``obj`` (a dataclass) with its ``prefix.field`` values applied (checked again by its
        constructor); fields that are not scalars, not init fields or in ``skip`` are not
        offered."""
        hints = typing.get_type_hints(type(obj))
        changes: dict[str, Any] = {}
        for f in dataclasses.fields(obj):  # type: ignore[arg-type]
            if f.name in skip or not f.init or not is_scalar(hints[f.name]):
                continue
            key = f"{prefix}.{f.name}"
            self.keys.append(key)
            if key in self.items:
                changes[f.name] = self._typed(key, hints[f.name])
        return dataclasses.replace(obj, **changes) if changes else obj  # type: ignore[type-var]

    def apply_tagged(self, prefix: str, obj: T, classes: Sequence[type]) -> T:
        """:meth:`apply` for an object that one of several model classes may stand for
        (``classes``, each a dataclass with its scene-file tag ``TAG``): ``prefix.type=TAG``
        makes the object of that class from the fields the two share, then the ``prefix.field``
        values apply. A field only another class has is offered, and refused unless its type is
        chosen, so that no value is silently dropped.

        Raises:
            OverrideError: a ``prefix.type`` that is none of the tags (naming the allowed ones),
                or a field of another class than the one chosen.
        """
        key = f"{prefix}.type"
        self.keys.append(key)
        tags: dict[str, type] = {c.TAG: c for c in classes}  # type: ignore[attr-defined]
        if key in self.items:
            tag = str(Override(key, self.items[key]).toml())
            if tag not in tags:
                allowed = ", ".join(f'"{t}"' for t in tags)
                raise OverrideError(f"{key}: expected one of {allowed}, got {self.items[key]!r}")
            if tags[tag] is not type(obj):
                target = {f.name for f in dataclasses.fields(tags[tag]) if f.init}
                shared = {f.name: getattr(obj, f.name) for f in dataclasses.fields(obj)  # type: ignore[arg-type]
                          if f.init and f.name in target}
                obj = tags[tag](**shared)
        own = {f.name for f in dataclasses.fields(obj)}  # type: ignore[arg-type]
        for cls in classes:
            hints = typing.get_type_hints(cls)
            for f in dataclasses.fields(cls):
                if f.name in own or not f.init or not is_scalar(hints[f.name]):
                    continue
                other = f"{prefix}.{f.name}"
                self.keys.append(other)
                if other in self.items:
                    raise OverrideError(
                        f"{other}: a field of {prefix}.type={cls.TAG}, not of "  # type: ignore[attr-defined]
                        f"{type(obj).TAG} (set {key}={cls.TAG} too)")  # type: ignore[attr-defined]
        return self.apply(prefix, obj)

    def value(self, key: str, default: Any, hint: Any = float) -> Any:
        """A single parameter ``key`` of type ``hint`` (``default`` unless set)."""
        self.keys.append(key)
        if key not in self.items:
            return default
        return self._typed(key, hint)

    def fields(self, cls: type, names: Sequence[str], defaults: Mapping[str, Any]
               ) -> dict[str, Any]:
        """The fields ``names`` of ``cls``, keyed without a prefix: ``defaults`` with the values
        set applied."""
        hints = typing.get_type_hints(cls)
        out = dict(defaults)
        for name in names:
            self.keys.append(name)
            if name in self.items:
                out[name] = self._typed(name, hints[name])
        return out

    def was_set(self, key: str) -> bool:
        return key in self.items


def _where(tokens: Sequence[Token]) -> str:
    """A path back as a dotted key with ``[i]`` indices."""
    out = ""
    for tok in tokens:
        out = f"{out}[{tok}]" if isinstance(tok, int) else (tok if not out else f"{out}.{tok}")
    return out


def apply_to_document(data: dict[str, Any], override: Override,
                      hint_at: Callable[[Sequence[Token]], Any]) -> None:
    """Write ``override`` into a parsed TOML document, in place: tables missing on the way are
    created; a word of :data:`NONE_WORDS` removes an optional field (``hint_at(path)``: the type
    hint of the field at a path, None if unknown), so it takes its default.

    Raises:
        OverrideError: the path runs through an array item the document does not have, or
            through a value that is not a table.
    """
    key = override.key
    tokens = override.path()
    remove = override.clears(hint_at(tokens))
    node: Any = data
    for i, tok in enumerate(tokens[:-1]):
        where = _where(tokens[: i + 1])
        if isinstance(tok, int):
            if not isinstance(node, list) or tok >= len(node):
                size = len(node) if isinstance(node, list) else 0
                raise OverrideError(f"--set {key}: {where}: no such item ({size} in the file)")
            node = node[tok]
        else:
            if not isinstance(node, dict):
                raise OverrideError(f"--set {key}: {where}: not a table")
            nxt = tokens[i + 1]
            node = node.setdefault(tok, [] if isinstance(nxt, int) else {})
    last = tokens[-1]
    if isinstance(last, int):
        if not isinstance(node, list) or last >= len(node):
            raise OverrideError(f"--set {key}: no such item")
        node[last] = override.toml()
        return
    if not isinstance(node, dict):
        raise OverrideError(f"--set {key}: {_where(tokens[:-1])}: not a table")
    if remove:
        node.pop(last, None)
    else:
        node[last] = override.toml()
