"""Scene files: any case the Python builders can make, as a TOML file.

::

    watersim run examples/flume2d.toml --set wave.height=0.06
    watersim show-scene kimmoun2d > kimmoun2d.toml      # a built-in case, fully resolved
    python3 -m watersim.scenefile --reference            # docs/scene-reference.md

A scene file is the keyword arguments of a builder written as TOML: ``type`` chooses the builder
(``"scene"``: :class:`~watersim.Scene`, ``"dambreak"``: :class:`~watersim.DamBreak`,
``"tank"``: :class:`~watersim.Tank`, ``"flume"``: :class:`~watersim.FlumeScene`), the other
top-level keys are its fields (``[[fluid]]``, ``[[bodies]]`` and ``[[gauges]]`` tables of a
scene, each with its ``type``), and a
field holding an object is a table of that object's fields (``[flume]``, ``[flume.beach]``,
``[wave]``, ``[paddle]``, ``gauges = [{...}, ...]``, ``[runup]``, ``[viscosity]``). Where a
field takes one of several classes (beach, wave, paddle, each gauge, a numerical model) the table
names it with its own ``type`` key (:data:`TAGS`); a numerical model may also be given by its
name alone (``viscosity = "laminar"``: the core's parameters). An optional field left out takes
its default (``None``: automatic; for a numerical parameter, the core's). The
``[output]`` table (:class:`OutputOptions`) says what ``watersim run`` writes.

The file is read with :mod:`tomllib` and turned into builder objects field by field along the
builders' type hints: a key no builder has, or a value of the wrong TOML type, is refused here
with its dotted path (``wave.hieght: unknown key ...``, ``gauges[2].x: expected a number, got a
string``); every value check is the builders' own (their :class:`~watersim.SceneError` is
re-raised with the key's path in the file). :func:`scene_to_dict` writes a builder back, so a
file written by ``watersim show-scene`` gives the same scene (the same scene JSON for the core).
"""

from __future__ import annotations

import argparse
import collections.abc
import dataclasses
import inspect
import re
import stat
import sys
import types
import typing
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import tomli_w

from . import flume, overrides
from . import numerics as nm
from ._compat import tomllib
from ._core import SceneError
from .bodies import BODY_TYPES
from .bodies import Mesh as MeshBody
from .checks import _positive
from .errors import did_you_mean
from .flume import FlumeScene, MeshBeach
from .scenes import DamBreak, FillTo, FluidBlock, Scene, SceneBuilder, Tank

__all__ = [
    "SCENE_TYPES",
    "TAGS",
    "OutputOptions",
    "SceneFile",
    "SceneFileError",
    "apply_settings",
    "dumps",
    "is_scene_file",
    "load",
    "loads",
    "reference_markdown",
    "scene_from_dict",
    "scene_to_dict",
]

SCENE_TYPES: dict[str, type[SceneBuilder]] = {
    "scene": Scene,
    "dambreak": DamBreak,
    "tank": Tank,
    "flume": FlumeScene,
}
"""The top-level ``type`` of a scene file and the builder it makes."""

CHOICES: dict[tuple[type, str], tuple[str, ...]] = {
    **{(SceneBuilder, name): words for name, words in nm.CHOICES.items()},
    **{(SceneBuilder, name): tuple(c.TAG for c in classes)
       for name, classes in nm.OPTION_CLASSES.items() if classes[0].TAG},
    **flume.CHOICES,
}
"""Allowed values of string fields, for the reference (the builders check them; the flume
models' rows are each class's own ``CHOICES``)."""


class SceneFileError(SceneError):
    """A scene file refused: message ``FILE: key.path: reason`` (a :class:`~watersim.SceneError`,
    so the command line prints it and exits with code 2)."""


@dataclass(frozen=True)
class OutputOptions:
    """The ``[output]`` table: what ``watersim run`` writes besides summary.json and log.jsonl.

    Attributes:
        directory: output folder (relative paths from the current directory); default
            ``runs/NAME`` for a scene file NAME.toml. ``--out`` overrides it.
        snapshot_every: interval between particle snapshots [s] of simulated time
            (``snapshots/particles_NNNNN.vtu`` and ``snapshots/particles.pvd`` for ParaView);
            none when left out. ``--snapshot-every`` overrides it.
        sample_every: dam breaks: surge front sampling interval for front.csv [s] (default
            0.01); flumes: how often gauges.csv is rewritten during the run [s] (default
            ``until / 20`` or 50 sample intervals, the shorter; the gauges themselves sample at
            the scene's ``sample_interval``).
            ``--sample-every`` overrides it.
    """

    directory: str | None = None
    snapshot_every: float | None = None
    sample_every: float | None = None

    def __post_init__(self) -> None:
        if self.directory is not None and not str(self.directory).strip():
            raise SceneError("output.directory: must not be empty")
        for name in ("snapshot_every", "sample_every"):
            value = getattr(self, name)
            if value is not None:
                object.__setattr__(self, name, _positive(f"output.{name}", value))


@dataclass(frozen=True)
class SceneFile:
    """A scene read from a file.

    Attributes:
        name: the file's stem (the default output folder ``runs/NAME``).
        builder: the builder (:class:`~watersim.DamBreak`, :class:`~watersim.Tank` or
            :class:`~watersim.FlumeScene`), checked.
        output: the ``[output]`` table.
        path: the file, or None for a string.
    """

    name: str
    builder: SceneBuilder
    output: OutputOptions
    path: Path | None = None


def is_scene_file(arg: str) -> bool:
    """Whether a ``watersim run`` argument names a scene file (by its ``.toml`` suffix)."""
    return arg.lower().endswith(".toml")


def scene_files_near(arg: str, limit: int = 200) -> list[str]:
    """The scene files in the folder a mistyped case argument points into, spelt as the user
    would type them (``examples/flume2d.toml`` for ``examples/flume2d.tom``): the candidates of
    a "did you mean" hint (at most ``limit``, so that a huge folder costs nothing)."""
    folder = Path(arg).parent
    try:
        names = sorted(p.name for _, p in zip(range(limit), folder.glob("*.toml"), strict=False))
    except OSError:
        return []
    return [str(folder / name) for name in names]


# ------------------------------------------------------------------------------------------------
# type hints


def _union_args(hint: Any) -> tuple[Any, ...] | None:
    """The members of a union hint (``A | B``, ``Optional[A]``), or None if not a union."""
    if isinstance(hint, types.UnionType) or typing.get_origin(hint) is typing.Union:
        return typing.get_args(hint)
    return None


def _is_sequence(hint: Any) -> bool:
    origin = typing.get_origin(hint)
    return origin in (tuple, list, collections.abc.Sequence)


def _item_hint(hint: Any, index: int) -> Any:
    """The hint of item ``index`` of a sequence hint (``tuple[float, ...]``, ``Sequence[X]``,
    ``tuple[float, float]``)."""
    args = typing.get_args(hint)
    if not args:
        return Any
    if typing.get_origin(hint) is tuple and not (len(args) == 2 and args[1] is Ellipsis):
        return args[index] if index < len(args) else args[-1]
    return args[0]


def _dataclasses_in(hint: Any) -> list[type]:
    members = _union_args(hint) or (hint,)
    return [m for m in members if isinstance(m, type) and dataclasses.is_dataclass(m)]


def _init_fields(cls: type) -> dict[str, dataclasses.Field[Any]]:
    return {f.name: f for f in dataclasses.fields(cls) if f.init}


def _hints(cls: type) -> dict[str, Any]:
    return typing.get_type_hints(cls)


def _required(f: dataclasses.Field[Any]) -> bool:
    return f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING


def _object_fields(cls: type) -> Iterator[tuple[str, Any, bool]]:
    """``(name, hint, in_sequence)`` of each init field of ``cls`` that holds objects: the hint
    of the object (of an item, for a sequence of them)."""
    hints = _hints(cls)
    for name in _init_fields(cls):
        hint = hints[name]
        in_sequence = _is_sequence(hint)
        if in_sequence:
            hint = _item_hint(hint, 0)
        if _dataclasses_in(hint):
            yield name, hint, in_sequence


TAGS: dict[type, str] = {**flume.TAGS, **nm.TAGS,
                         **{c: c.TAG for c in (*BODY_TYPES, FluidBlock, FillTo)}}
"""The ``type`` key of a table whose field takes one of several classes (a beach, a wave, a
paddle, a gauge, a numerical model): each model class's own ``TAG``."""


# ------------------------------------------------------------------------------------------------
# reading


def _toml_type(value: Any) -> str:
    """How a TOML value's type reads in a message."""
    if isinstance(value, bool):
        return "a boolean"
    if isinstance(value, int):
        return "an integer"
    if isinstance(value, float):
        return "a number"
    if isinstance(value, str):
        return "a string"
    if isinstance(value, list):
        return "an array"
    if isinstance(value, dict):
        return "a table"
    return f"a {type(value).__name__}"


def _expected(hint: Any) -> str:
    """What a hint expects, for a message."""
    members = _union_args(hint)
    if members is not None:
        parts = [_expected(m) for m in members if m is not type(None)]
        return " or ".join(dict.fromkeys(parts))
    if hint is float:
        return "a number"
    if hint is int:
        return "an integer"
    if hint is bool:
        return "true or false"
    if hint is str:
        return "a string"
    if _is_sequence(hint):
        return "an array"
    if isinstance(hint, type) and dataclasses.is_dataclass(hint):
        return f"a table ({hint.__name__})"
    return str(hint)


def _join(path: str, key: str) -> str:
    return key if not path else f"{path}.{key}"


class _Reader:
    """Turns TOML values into builder objects along the type hints (one file)."""

    def __init__(self, source: str, base: Path | None = None) -> None:
        self.source = source
        self.base = base

    def fail(self, path: str, reason: str) -> SceneFileError:
        where = f"{path}: " if path else ""
        return SceneFileError(f"{self.source}: {where}{reason}")

    def value(self, raw: Any, hint: Any, path: str) -> Any:
        members = _union_args(hint)
        if members is not None:
            return self._union(raw, members, hint, path)
        if hint is Any:
            return raw
        if hint is float:
            if isinstance(raw, bool) or not isinstance(raw, (int, float)):
                raise self._wrong(raw, hint, path)
            return float(raw)
        if hint is int:
            if isinstance(raw, bool) or not isinstance(raw, int):
                raise self._wrong(raw, hint, path)
            return raw
        if hint is bool or hint is str:
            if not isinstance(raw, hint):
                raise self._wrong(raw, hint, path)
            return raw
        if _is_sequence(hint):
            if not isinstance(raw, list):
                raise self._wrong(raw, hint, path)
            return tuple(
                self.value(item, _item_hint(hint, i), f"{path}[{i}]") for i, item in enumerate(raw)
            )
        if isinstance(hint, type) and dataclasses.is_dataclass(hint):
            if not isinstance(raw, dict):
                raise self._wrong(raw, hint, path)
            return self.table(raw, hint, path, tagged=False)
        raise self.fail(path, f"cannot read a value of type {hint}")  # pragma: no cover

    def _wrong(self, raw: Any, hint: Any, path: str) -> SceneFileError:
        shown = repr(raw) if not isinstance(raw, (dict, list)) else ""
        got = _toml_type(raw) + (f" ({shown})" if shown else "")
        return self.fail(path, f"wrong type: expected {_expected(hint)}, got {got}")

    def _union(self, raw: Any, members: tuple[Any, ...], hint: Any, path: str) -> Any:
        classes = [m for m in members if isinstance(m, type) and dataclasses.is_dataclass(m)]
        if isinstance(raw, dict) and classes:
            if len(classes) == 1:
                return self.table(raw, classes[0], path, tagged=False)
            tags = {TAGS[c]: c for c in classes}
            tag = raw.get("type")
            if tag is None:
                raise self.fail(_join(path, "type"), f"required; one of {_quoted(tags)}")
            if not isinstance(tag, str) or tag not in tags:
                hint = did_you_mean(tag, tags) if isinstance(tag, str) else ""
                raise self.fail(_join(path, "type"),
                                f"unknown value {tag!r}{hint}; one of {_quoted(tags)}")
            return self.table(raw, tags[tag], path, tagged=True)
        for m in members:
            if m is bool and isinstance(raw, bool):
                return raw
            if m in (float, int) and isinstance(raw, (int, float)) and not isinstance(raw, bool):
                return self.value(raw, m, path)
            if m is str and isinstance(raw, str):
                return raw
            if _is_sequence(m) and isinstance(raw, list):
                return self.value(raw, m, path)
        raise self._wrong(raw, hint, path)

    def table(self, raw: Mapping[str, Any], cls: type, path: str, tagged: bool) -> Any:
        """Build ``cls`` from a TOML table (``type`` skipped when ``tagged``)."""
        fields = _init_fields(cls)
        hints = _hints(cls)
        kwargs: dict[str, Any] = {}
        for key, item in raw.items():
            if tagged and key == "type":
                continue
            if key not in fields:
                valid = ", ".join(fields)
                raise self.fail(_join(path, key), f"unknown key for {cls.__name__}"
                                f"{did_you_mean(key, fields)}; valid keys: "
                                f"{'type, ' if tagged else ''}{valid}")
            kwargs[key] = self.value(item, hints[key], _join(path, key))
        for name, f in fields.items():
            if _required(f) and name not in kwargs:
                raise self.fail(_join(path, name), f"required ({cls.__name__} has no default)")
        if (cls in (MeshBeach, MeshBody) and isinstance(kwargs.get("path"), str)
                and self.base is not None):
            # a mesh file named in a scene file is found next to it, wherever the run starts
            kwargs["path"] = str(self.base / Path(kwargs["path"]).expanduser())
        try:
            return cls(**kwargs)
        except SceneFileError:
            raise
        except SceneError as exc:
            raise self.relocate(exc, path, cls) from None

    def relocate(self, exc: SceneError, path: str, cls: type) -> SceneFileError:
        """A builder's ``name: reason`` message with ``name`` as its path in the file.

        The builders name a nested object's field by their own prefix (an ElevationGauge says
        ``gauge.x``, a FlumeScene says ``beach.z`` for the flume's beach): the prefix is
        replaced by the table's path from the first component that is a field of ``cls``.
        """
        message = str(exc)
        name, sep, reason = message.partition(": ")
        if not sep or " " in name:
            return self.fail(path, message)
        parts = name.split(".")
        fields = _init_fields(cls)
        for i, part in enumerate(parts):
            if re.sub(r"\[\d+\]$", "", part) in fields:
                return self.fail(_join(path, ".".join(parts[i:])), reason)
        if cls is FlumeScene and parts[0] in ("beach", "damping", "depth", "length", "width"):
            return self.fail(_join(path, "flume." + name), reason)
        return self.fail(path, message)


def _quoted(names: Mapping[str, Any] | Sequence[str]) -> str:
    return ", ".join(repr(n) for n in names)


def scene_from_dict(data: Mapping[str, Any], source: str = "scene", name: str = "scene",
                    base: Path | None = None) -> SceneFile:
    """A scene from the parsed TOML document ``data`` (``source`` names it in messages;
    relative mesh file paths are taken from the folder ``base``, default the current one).

    Raises:
        SceneFileError: an unknown key, a value of the wrong type, or a value a builder refuses.
    """
    reader = _Reader(source, base)
    doc = dict(data)
    kind = doc.pop("type", None)
    if kind is None:
        raise reader.fail("type", f"required; one of {_quoted(SCENE_TYPES)}")
    if not isinstance(kind, str) or kind not in SCENE_TYPES:
        raise reader.fail("type", f"unknown value {kind!r}; one of {_quoted(SCENE_TYPES)}")
    raw_output = doc.pop("output", {})
    if not isinstance(raw_output, dict):
        raise reader._wrong(raw_output, OutputOptions, "output")
    output = reader.table(raw_output, OutputOptions, "output", tagged=False)
    builder = reader.table(doc, SCENE_TYPES[kind], "", tagged=False)
    return SceneFile(name=name, builder=builder, output=output)


def loads(text: str, settings: Sequence[str] = (), source: str = "scene", name: str = "scene",
          base: Path | None = None) -> SceneFile:
    """A scene from TOML text, with ``key=value`` overrides (see :func:`apply_settings`);
    relative mesh file paths are from the folder ``base`` (default: the current one)."""
    try:
        data = tomllib.loads(text)
    except RecursionError:
        raise SceneFileError(f"{source}: not a scene: arrays or tables nested too deeply") from None
    except ValueError as exc:  # TOMLDecodeError, or an integer of more than 4300 digits
        raise SceneFileError(f"{source}: not valid TOML: {_short(str(exc))}") from None
    if settings:
        apply_settings(data, settings, source)
    try:
        return scene_from_dict(data, source, name, base)
    except RecursionError:
        raise SceneFileError(f"{source}: not a scene: values nested too deeply") from None


def _short(text: str, limit: int = 200) -> str:
    """``text`` cut to ``limit`` characters (a message quoting a hostile value stays a line)."""
    return text if len(text) <= limit else text[: limit - 3] + "..."


MAX_SCENE_FILE_BYTES = 16 * 2**20
"""The largest scene file read (a scene is a few kilobytes; meshes are files of their own)."""


def load(path: str | Path, settings: Sequence[str] = ()) -> SceneFile:
    """A scene file, with ``key=value`` overrides (``--set``).

    Raises:
        SceneFileError: the file is missing, not TOML, or refused (key path and reason).
    """
    p = Path(path)
    if "\0" in str(p):
        raise SceneFileError(f"{str(p)!r}: a file name cannot hold a NUL byte")
    try:
        mode = p.stat().st_mode  # a link is followed: a link to /dev/zero is a device
        if not stat.S_ISREG(mode):
            # a FIFO would block and a device never end: read regular files only
            raise SceneFileError(f"{p}: not a regular file (a scene file is a TOML file)")
        if p.stat().st_size > MAX_SCENE_FILE_BYTES:
            raise SceneFileError(f"{p}: {p.stat().st_size} bytes; a scene file is at most "
                                 f"{MAX_SCENE_FILE_BYTES} bytes")
        text = p.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise SceneFileError(f"{p}: no such scene file") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise SceneFileError(f"{p}: cannot read the scene file: {exc}") from None
    scene = loads(text, settings, source=str(p), name=p.stem, base=p.resolve().parent)
    return dataclasses.replace(scene, path=p)


# ------------------------------------------------------------------------------------------------
# --set on a scene file


def _hint_at(data: Mapping[str, Any], tokens: Sequence[str | int]) -> Any:
    """The type hint of the field at ``tokens`` in the document, or None if unknown there."""
    kind = data.get("type")
    if kind not in SCENE_TYPES:
        return None
    if tokens and tokens[0] == "output":
        hint: Any = OutputOptions
        node: Any = data.get("output", {})
        rest = tokens[1:]
    else:
        hint, node, rest = SCENE_TYPES[str(kind)], data, tokens
    for tok in rest:
        if isinstance(tok, int):
            if not _is_sequence(hint):
                return None
            hint = _item_hint(hint, tok)
            node = node[tok] if isinstance(node, list) and tok < len(node) else None
            continue
        classes = _dataclasses_in(hint)
        if len(classes) > 1:
            tag = node.get("type") if isinstance(node, dict) else None
            classes = [c for c in classes if TAGS.get(c) == tag]
        if len(classes) != 1:
            return None
        if tok == "type" and TAGS.get(classes[0]):
            return str
        fields = _hints(classes[0])
        if tok not in fields:
            return None
        hint = fields[tok]
        node = node.get(tok) if isinstance(node, dict) else None
    return hint


def apply_settings(data: dict[str, Any], settings: Sequence[str], source: str = "scene") -> None:
    """Apply ``key=value`` overrides to a parsed scene file, in place.

    Keys are dotted paths (``dp``, ``wave.height``, ``flume.beach.slope``, ``gauges[0].x``,
    ``output.snapshot_every``); missing tables on the way are created. Values are TOML values;
    a bare word is a string. ``none`` (or ``null``, ``auto``) removes an optional field, so it
    takes its default (:func:`watersim.overrides.apply_to_document`). The result is checked
    like the file itself.
    """
    try:
        for item in settings:
            overrides.apply_to_document(data, overrides.Override.parse(item),
                                        lambda tokens: _hint_at(data, tokens))
    except overrides.OverrideError as exc:
        raise SceneFileError(f"{source}: {exc}") from None


# ------------------------------------------------------------------------------------------------
# writing


def _plain(value: Any, hint: Any) -> Any:
    """A builder value as a TOML value (tables for objects, arrays for sequences)."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        tagged = len(_dataclasses_in(hint)) > 1
        return _table(value, tagged)
    if isinstance(value, (tuple, list)):
        return [_plain(v, _item_hint(hint, i)) for i, v in enumerate(value)]
    if hasattr(value, "item") and not isinstance(value, (str, bytes)):
        value = value.item()  # a NumPy scalar
    if isinstance(value, bool | int | float | str):
        return value
    raise TypeError(f"cannot write {value!r} to a scene file")  # pragma: no cover


def _table(obj: Any, tagged: bool) -> dict[str, Any]:
    hints = _hints(type(obj))
    out: dict[str, Any] = {}
    if tagged:
        out["type"] = TAGS[type(obj)]
    for name in _init_fields(type(obj)):
        value = getattr(obj, name)
        if value is None:
            continue  # left out: the field's default (None) when read back
        out[name] = _plain(value, hints[name])
    return out


def scene_to_dict(builder: SceneBuilder, output: OutputOptions | None = None) -> dict[str, Any]:
    """A builder (and output options) as a scene-file document; :func:`scene_from_dict` of it
    gives an equal builder."""
    kinds = {cls: name for name, cls in SCENE_TYPES.items()}
    kind = kinds.get(type(builder))
    if kind is None:
        raise TypeError(f"no scene file type for {type(builder).__name__}")
    doc: dict[str, Any] = {"type": kind, **_table(builder, tagged=False)}
    if output is not None:
        table = _table(output, tagged=False)
        if table:
            doc["output"] = table
    return doc


def dumps(builder: SceneBuilder, output: OutputOptions | None = None, header: str = "") -> str:
    """A builder as scene-file text (``header`` lines are written first as comments)."""
    comments = "".join(f"# {line}".rstrip() + "\n" for line in header.splitlines())
    return comments + tomli_w.dumps(scene_to_dict(builder, output))


# ------------------------------------------------------------------------------------------------
# reference


def _attribute_docs(cls: type) -> dict[str, str]:
    """Field descriptions from the ``Attributes:`` sections of ``cls`` and its bases."""
    docs: dict[str, str] = {}
    for klass in reversed(cls.__mro__):
        doc = inspect.cleandoc(klass.__doc__ or "") if "__doc__" in vars(klass) else ""
        lines = doc.splitlines()
        try:
            start = lines.index("Attributes:") + 1
        except ValueError:
            continue
        current: list[str] = []
        text: list[str] = []
        for line in lines[start:]:
            if line and not line.startswith(" "):
                break
            m = re.match(r"^    ([a-z_][a-z0-9_]*(?:, [a-z_][a-z0-9_]*)*): (.*)$", line)
            if m:
                for name in current:
                    docs[name] = " ".join(text)
                current = m.group(1).split(", ")
                text = [m.group(2).strip()]
            elif line.strip() and current:
                text.append(line.strip())
        for name in current:
            docs[name] = " ".join(text)
    return docs


def _markdown(text: str) -> str:
    """reStructuredText inline markup of the docstrings as Markdown."""
    text = re.sub(r":[a-z]+:`~(?:[\w.]+\.)?(\w+)`", r"`\1`", text)  # ~a.b.C shows as C
    text = re.sub(r":[a-z]+:`([\w.]+)`", r"`\1`", text)
    return re.sub(r"``(.+?)``", r"`\1`", text)


def _description(cls: type) -> str:
    """The paragraphs of a class docstring before its ``Attributes:``, each on one line."""
    doc = inspect.cleandoc(cls.__doc__ or "").split("\nAttributes:")[0]
    paragraphs = [" ".join(p.split()) for p in doc.split("\n\n") if p.strip()]
    return _markdown("\n\n".join(paragraphs))


def _type_name(hint: Any) -> str:
    members = _union_args(hint)
    if members is not None:
        tagged = [m for m in members if m in TAGS]
        parts = [_type_name(m) for m in members if m is not type(None) and m not in TAGS]
        if tagged:
            kinds = ", ".join(f'"{TAGS[m]}"' for m in tagged)
            parts.insert(0, f"table with type = {kinds}")
        return " or ".join(dict.fromkeys(parts))
    if hint is float:
        return "number"
    if hint is int:
        return "integer"
    if hint is bool:
        return "boolean"
    if hint is str:
        return "string"
    if _is_sequence(hint):
        args = typing.get_args(hint)
        if typing.get_origin(hint) is tuple and args and args[-1] is not Ellipsis:
            return f"array of {len(args)} {_type_name(args[0])}s"
        return f"array of {_type_name(_item_hint(hint, 0))}"
    if isinstance(hint, type) and dataclasses.is_dataclass(hint):
        tag = TAGS.get(hint)
        return f"table ({hint.__name__})" if tag is None else f'table with type = "{tag}"'
    return str(hint)


def _core_default_text(cls: type, name: str) -> str | None:
    """The core's default of a builder field or an option's parameter, if it has one."""
    if issubclass(cls, nm.Option):
        key = f"{cls.FIELD}.{name}"
    elif issubclass(cls, SceneBuilder) and name in SceneBuilder.CORE_KEYS:
        key = name
    elif name in getattr(cls, "CORE_DEFAULTS", {}):  # a gauge's
        key = cls.CORE_DEFAULTS[name]  # type: ignore[attr-defined]
    else:
        return None
    try:
        value = nm.core_default(key)
    except KeyError:  # derived by the core (h_swl, boundary_layers): see the meaning
        return None
    if isinstance(value, dict):  # an option: its model, whose parameters are listed below
        tag = value.get("model", value.get("scheme"))
        # an option without tagged classes (shifting) is off by default: its model is a parameter
        tagged = name not in nm.OPTION_CLASSES or bool(nm.OPTION_CLASSES[name][0].TAG)
        return f'the core\'s: `"{tag}"`' if tag and tagged else None
    return f"the core's: {_toml_literal(value)}"


def _default_text(cls: type, f: dataclasses.Field[Any]) -> str:
    dim_defaults = getattr(cls, "_DIM_DEFAULTS", {})
    hint = _hints(cls)[f.name]
    per_dim = [f"{d}D: {_toml_literal(v[f.name], hint)}" for d, v in sorted(dim_defaults.items())
               if f.name in v]
    if per_dim:
        return ", ".join(per_dim)
    if f.default_factory is not dataclasses.MISSING:
        value = f.default_factory()
        tag = TAGS.get(type(value))
        return f'`{{ type = "{tag}" }}`' if tag else repr(value)
    if f.default is dataclasses.MISSING:
        return "**required**"
    if f.default is None:
        return _core_default_text(cls, f.name) or "automatic"
    return _toml_literal(f.default)


def _toml_literal(value: Any, hint: Any = Any) -> str:
    if isinstance(value, (tuple, list)):  # on one line (tomli-w writes one item per line)
        return "`[" + ", ".join(_toml_literal(v).strip("`") for v in value) + "]`"
    text = tomli_w.dumps({"v": _plain(value, hint)}).strip()
    if text.startswith("[v]"):  # a table: inline
        pairs = [line.strip() for line in text.splitlines()[1:] if line.strip()]
        return "`{ " + ", ".join(pairs) + " }`"
    return "`" + text[len("v = "):] + "`"


def _class_rows(cls: type, skip: tuple[str, ...] = ()) -> list[str]:
    docs = _attribute_docs(cls)
    hints = _hints(cls)
    rows = ["| key | type | default | meaning |", "| --- | --- | --- | --- |"]
    if cls in TAGS:
        rows.append(f'| `type` | string | **required** | `"{TAGS[cls]}"` |')
    for name, f in _init_fields(cls).items():
        if name in skip:
            continue
        meaning = _markdown(docs.get(name, "")).replace("|", "\\|")
        choices = next((c for (k, n), c in CHOICES.items() if n == name and issubclass(cls, k)),
                       None)
        if choices:
            meaning += " Allowed: " + ", ".join(f'`"{c}"`' for c in choices) + "."
        rows.append(f"| `{name}` | {_type_name(hints[name])} | {_default_text(cls, f)} | "
                    f"{meaning} |")
    return rows


def _sections() -> Iterator[tuple[str, str, type, tuple[str, ...]]]:
    """(heading, note, class, fields to skip) of each table of the reference."""
    base = tuple(SceneBuilder.field_names())
    yield ('`type = "scene"` (top level)',
           "A general scene: a tank, fluid blocks, bodies and gauges (`watersim.Scene`); the "
           "numerical fields are those of the dam break below.",
           Scene, base)
    yield from _object_sections(Scene, "", skip=tuple(nm.OPTION_CLASSES))
    own = ("tank", "fluid")  # the presets make them from their own fields
    yield ('`type = "dambreak"` (top level)',
           "A preset of the general scene: `bodies`, `gauges` and `sample_interval` as there.",
           DamBreak, own)
    yield from _object_sections(SceneBuilder, "")
    yield ('`type = "tank"` (top level)', "A preset of the general scene, as the dam break.",
           Tank, own)
    yield ('`type = "flume"` (top level)',
           "A preset of the general scene: the flume makes the tank and the still water; "
           "`bodies`, `gauges`, `sample_interval` and more `fluid` as there. "
           "The numerical fields are those of the dam break above, with the defaults below, "
           "except `energy_growth_limit`: the core's energy monitor does not run in a scene "
           "with a paddle, so a flume refuses it.",
           FlumeScene, tuple(n for n in base if n not in ("dim", "coefh", "boundary", "dp",
                                                          "until")) + ("energy_growth_limit",
                                                                       "tank"))
    yield from _object_sections(FlumeScene, "", skip=tuple(nm.OPTION_CLASSES))
    yield ("`[output]`", "", OutputOptions, ())


def _object_sections(cls: type, path: str, skip: tuple[str, ...] = ()
                     ) -> Iterator[tuple[str, str, type, tuple[str, ...]]]:
    """The sections of the objects within ``cls`` (at ``path`` in the file; fields ``skip``
    left out), each followed by those of the objects within it: one per class a field takes."""
    for name, hint, in_sequence in _object_fields(cls):
        if name in skip:
            continue
        key = _join(path, name)
        members = _dataclasses_in(hint)
        note = f"Or `{name} = true` / `false`." if bool in (_union_args(hint) or ()) else ""
        for member in members:
            heading = f"`{key}` item" if in_sequence else f"`[{key}]`"
            if len(members) > 1:
                heading += f' with `type = "{TAGS[member]}"`'
            yield heading, note, member, ()
            yield from _object_sections(member, key)


def _python_name(cls: type) -> str:
    """``watersim.NAME`` for a class the package exports, else its full name."""
    # the package is loaded before any of its modules: read it, do not import it (the package
    # imports this module)
    package = sys.modules[__name__.partition(".")[0]]
    if getattr(package, cls.__name__, None) is cls:
        return f"watersim.{cls.__name__}"
    return f"{cls.__module__}.{cls.__qualname__}"


def reference_markdown() -> str:
    """The scene-file reference (docs/scene-reference.md), generated from the builders."""
    out = [
        "# Scene file reference",
        "",
        "<!-- Generated from the builder classes by `python3 -m watersim.scenefile "
        "--reference > docs/scene-reference.md`; do not edit by hand (a test compares). -->",
        "",
        _module_intro(),
        "",
        "Units are SI (metres, seconds, kilograms). *automatic* means the field is left out "
        "(it is `None` in Python) and the builder chooses (see its meaning).",
        "",
    ]
    for heading, note, cls, skip in _sections():
        out += [f"## {heading}", "", f"Python: `{_python_name(cls)}`. {_description(cls)}", ""]
        if note:
            out += [note, ""]
        out += _class_rows(cls, skip)
        out.append("")
    return "\n".join(out)


def _module_intro() -> str:
    """The module docstring's paragraphs on the file format (after the usage example)."""
    doc = inspect.cleandoc(__doc__ or "")
    paragraphs = doc.split("\n\n")
    return _markdown("\n\n".join(" ".join(p.split()) for p in paragraphs[3:5]))


def main(argv: Sequence[str] | None = None) -> int:
    """``python3 -m watersim.scenefile --reference``: print the scene-file reference."""
    parser = argparse.ArgumentParser(prog="python3 -m watersim.scenefile")
    parser.add_argument("--reference", action="store_true",
                        help="print the scene-file reference (Markdown)")
    parser.add_argument("--check", metavar="FILE", nargs="*", default=[],
                        help="load these scene files and report errors")
    args = parser.parse_args(argv)
    if args.reference:
        sys.stdout.write(reference_markdown())
    status = 0
    for name in args.check:
        try:
            load(name)
            print(f"{name}: ok")
        except SceneError as exc:
            print(f"error: {exc}", file=sys.stderr)
            status = 2
    if not args.reference and not args.check:
        parser.print_usage()
        return 2
    return status


if __name__ == "__main__":  # pragma: no cover
    # run the imported module's main, not this __main__ copy, so class names and identities are
    # those of watersim.scenefile
    from watersim.scenefile import main as _main

    sys.exit(_main())
