"""The gauges of a flume: surface elevation, velocity probes and windows, pressure, run-up,
force on a structure, overtopping."""

from __future__ import annotations

import math
import re
import typing
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
import numpy.typing as npt

from .._core import SceneError
from ..checks import _choice, _integer, _number, _positive
from .checks import _TOL, _finite_tuple, _optional_name, _set

if TYPE_CHECKING:
    from .records import FlumeGauges
    from .scene import FlumeScene

Series = tuple[str, npt.NDArray[np.float64], npt.NDArray[np.float64]]
"""A gauge's column of ``gauges.csv``: ``(column name, t [s], values)``."""

__all__ = [
    "GAUGE_TYPES",
    "RUNUP_METHODS",
    "SURFACE_METHODS",
    "ElevationGauge",
    "ForceGauge",
    "OvertoppingGauge",
    "PressureGauge",
    "RunupGauge",
    "VelocityProbe",
    "VelocityWindow",
    "elevation_gauges_between",
]
"""Exported as they are by :mod:`watersim.flume` and :mod:`watersim` (a new gauge class is
listed here, in its own file, and nowhere else)."""

Variables = tuple[dict[str, Any], dict[str, Any]]
"""A gauge kind's share of :func:`watersim.load`'s Dataset: ``(data variables, coordinates)``,
each ``name: (dims, values, attrs)``."""

_NOT_IN_A_NAME = re.compile(r"[^A-Za-z0-9_]")


def csv_column(name: str, unit: str = "") -> str:
    """The CSV column of a quantity ``name`` in ``unit`` (``"m"``, ``"s"``, ``"m_per_s"``; none
    for a pure number): a name NumPy's ``genfromtxt(names=True)`` and pandas read unchanged.

    genfromtxt deletes dots and most punctuation from column names, so a decimal point becomes
    ``p`` and a minus sign ``n`` (``eta_x1.000`` in m: ``eta_x1p000_m``); any other character
    outside letters, digits and ``_`` becomes ``_``.
    """
    text = name.replace(".", "p").replace("-", "n")
    text = _NOT_IN_A_NAME.sub("_", text)
    return f"{text}_{unit}" if unit else text

SURFACE_METHODS: tuple[str, ...] = ("kernel", "particle")
"""Free-surface methods of elevation and run-up gauges (DESIGN.md section 4): ``"kernel"``, the
highest point where the fluid's kernel volume sum fills half the space the walls leave free
(``S_fluid / (1 - S_wall) >= 0.5``: 0.5 away from walls, and right next to a side wall or bed
too); ``"particle"``, the highest fluid particle
near the gauge line (seed 001's method)."""


RUNUP_METHODS: tuple[str, ...] = SURFACE_METHODS + ("wet_front",)
"""Run-up methods: the surface methods along the gauge's segment, and ``"wet_front"``, the highest
fluid particle touching the bed (a fixed wall particle within 1.5 dp) within 3 dp of the
segment: water one particle thin counts, which a line above the bed cannot see."""


RUNUP_OFFSET_DP = 1.5
"""Distance of the automatic run-up gauge line above the beach surface, in dp (normal to it)."""

DRY_KERNEL_SUM = 0.5
"""A gauge point whose kernel volume sum is below this is out of the water (dry)."""


def point_labels(points: npt.NDArray[np.float64]) -> list[str]:
    """A CSV label for each of the points (p, dim) [m]: its position ``x4p000_z0p100`` (x, (y,)
    z to the millimetre), ``_k`` added to the k-th point at the place of an earlier one."""
    axes = ("x", "z") if points.shape[1] == 2 else ("x", "y", "z")
    labels: list[str] = []
    for k, point in enumerate(points):
        label = csv_column("_".join(f"{a}{c:.3f}" for a, c in zip(axes, point, strict=True)))
        labels.append(f"{label}_{k}" if label in labels else label)
    return labels


@dataclass(frozen=True)
class VelocityRecord:
    """A velocity probe or window record.

    Attributes:
        name: the gauge name.
        t: sample times (n,) [s].
        points: sampled points (p, dim) [m].
        velocity: (n, p, dim) [m/s]; for windows reshaped to ``(n, *reversed(shape), dim)``.
        kernel_sum: (n, p) kernel volume sum (about 1 in the water, 0 outside): mask samples
            with ``kernel_sum < 0.5`` as dry. Windows: ``(n, *reversed(shape))``.
        shape: the window's points per axis (x first), or None for probes.
    """

    name: str
    t: npt.NDArray[np.float64]
    points: npt.NDArray[np.float64]
    velocity: npt.NDArray[np.float64]
    kernel_sum: npt.NDArray[np.float64]
    shape: tuple[int, ...] | None

    @staticmethod
    def by_name(raws: list[dict[str, Any]], dim: int, window: bool) -> dict[str, VelocityRecord]:
        """The records ``raws`` (see :meth:`read`) by name."""
        return {str(r["name"]): VelocityRecord.read(r, dim, window) for r in raws}

    @staticmethod
    def read(raw: dict[str, Any], dim: int, window: bool) -> VelocityRecord:
        """The core's probe (or, ``window``, window) record ``raw`` of a ``dim``-D flume."""
        vel = np.asarray(raw["velocity"], dtype=np.float64)
        ksum = np.asarray(raw["kernel_sum"], dtype=np.float64)
        shape = tuple(int(v) for v in raw.get("shape") or ()) or None
        if window and shape is not None:
            grid = tuple(reversed(shape[:dim]))
            vel = vel.reshape((vel.shape[0], *grid, dim))
            ksum = ksum.reshape((ksum.shape[0], *grid))
        return VelocityRecord(
            name=str(raw["name"]),
            t=np.asarray(raw["t"], dtype=np.float64),
            points=np.asarray(raw["points"], dtype=np.float64),
            velocity=vel,
            kernel_sum=ksum,
            shape=shape if window else None,
        )


_KERNEL_SUM_ATTRS = {"units": "1", "long_name": "kernel sum (< 0.5: dry)"}


def _velocity_variables(records: dict[str, VelocityRecord]) -> Variables:
    """``velocity_NAME`` (time_NAME, point_NAME, component) [m/s] and ``kernel_sum_NAME`` of
    velocity probes or windows, the points in ``points_NAME``."""
    data: dict[str, Any] = {}
    coords: dict[str, Any] = {}
    for name, record in records.items():
        tname, pname = f"time_{name}", f"point_{name}"
        points = np.asarray(record.points)
        n = record.t.size
        coords[tname] = (tname, record.t, {"units": "s"})
        coords[f"points_{name}"] = ((pname, "axis"), points, {"units": "m"})
        data[f"velocity_{name}"] = ((tname, pname, "component"),
                                    np.asarray(record.velocity).reshape(n, len(points), -1),
                                    {"units": "m/s"})
        data[f"kernel_sum_{name}"] = ((tname, pname),
                                      np.asarray(record.kernel_sum).reshape(n, len(points)),
                                      _KERNEL_SUM_ATTRS)
    return data, coords


class _Gauge:
    """What every gauge class declares besides its schema: how its core records become arrays
    of :class:`~watersim.flume.FlumeGauges`, and its columns of ``gauges.csv``."""

    TAG: ClassVar[str]
    CHOICES: ClassVar[dict[str, tuple[str, ...]]] = {}
    """The allowed values of the gauge's string fields."""

    name: str | None
    interval: float | None

    def _check_name_and_interval(self, prefix: str) -> None:
        """The record name and the sampling interval every gauge has (``prefix.name``, ...)."""
        _optional_name(f"{prefix}.name", self.name)
        if self.interval is not None:
            _set(self, "interval", _positive(f"{prefix}.interval", self.interval))

    def _check_choices(self, prefix: str) -> None:
        """The string fields of :attr:`CHOICES` that are set, each one of its words."""
        for field, words in self.CHOICES.items():
            if getattr(self, field) is not None:
                _choice(f"{prefix}.{field}", getattr(self, field), words)

    def _chosen(self) -> dict[str, str]:
        """The :attr:`CHOICES` fields that are set, for the core's gauge JSON (an unset one is
        left out: the core's default applies)."""
        return {f: getattr(self, f) for f in self.CHOICES if getattr(self, f) is not None}

    def default_name(self, scene: FlumeScene, index: int) -> str:
        """The name of the ``index``-th unnamed gauge of this kind: ``TAG{index}``."""
        return f"{self.TAG}{index}"

    @classmethod
    def read(cls, gauges: FlumeGauges, raws: list[dict[str, Any]]) -> None:
        """Turn this kind's core records ``raws`` into arrays on ``gauges``: by default each
        field of each record as an array in ``gauges.records[name]``."""
        for raw in raws:
            gauges.records[str(raw["name"])] = {
                key: np.asarray(value) for key, value in raw.items() if key not in ("type", "name")
            }

    @classmethod
    def _records_by_name(cls, gauges: FlumeGauges) -> Iterator[tuple[str, Any,
                                                                      dict[str, Any]]]:
        """Per gauge of this kind, in scene order: its name, ``t`` (n,) [s] and its record."""
        for spec in gauges.setup._gauge_specs():
            if spec["type"] == cls.TAG:
                record = gauges.records[spec["name"]]
                yield spec["name"], np.asarray(record["t"], dtype=np.float64), record

    @classmethod
    def dataset_variables(cls, gauges: FlumeGauges) -> Variables:
        """This kind's variables and coordinates in :func:`watersim.load` (none by default)."""
        return {}, {}

    @classmethod
    def csv_series(cls, gauges: FlumeGauges) -> list[Series]:
        """This kind's columns of ``gauges.csv`` (none by default)."""
        return []


class _VelocityGauge(_Gauge):
    """Velocity probes and windows: a :class:`VelocityRecord` per gauge in
    ``FlumeGauges.<RECORDS>`` (``velocity`` or ``windows``)."""

    RECORDS: ClassVar[str]

    @classmethod
    def read(cls, gauges: FlumeGauges, raws: list[dict[str, Any]]) -> None:
        records = VelocityRecord.by_name(raws, gauges.setup.dim,
                                         window=cls.RECORDS == "windows")
        setattr(gauges, cls.RECORDS, records)

    @classmethod
    def dataset_variables(cls, gauges: FlumeGauges) -> Variables:
        return _velocity_variables(getattr(gauges, cls.RECORDS))


@dataclass(frozen=True)
class ElevationGauge(_Gauge):
    """Free-surface elevation on the vertical line through (x[, y]).

    Attributes:
        x: position along the flume [m].
        y: position across (3D only) [m]; ``None``: the flume's centre line.
        method: ``"kernel"`` or ``"particle"`` (see :data:`SURFACE_METHODS`); ``None``: the
            core's default (``scene_defaults()["gauges"]["elevation_method"]``).
        name: column name; default ``eta_x{x:.3f}`` (``_y{y:.3f}`` added in 3D).
        interval: sampling interval [s]; default the scene's ``sample_interval``.
    """

    x: float
    y: float | None = None
    method: str | None = None
    name: str | None = None
    interval: float | None = None

    TAG: ClassVar[str] = "elevation"
    """The core's gauge ``type`` (and the scene file's ``type`` of a gauge table)."""
    CHOICES: ClassVar[dict[str, tuple[str, ...]]] = {"method": SURFACE_METHODS}
    CORE_DEFAULTS: ClassVar[dict[str, str]] = {"method": "gauges.elevation_method"}
    """The core's defaults of the fields left ``None`` (keys of ``scene_defaults()``)."""

    def __post_init__(self) -> None:
        _set(self, "x", _number("gauge.x", self.x))
        if self.y is not None:
            _set(self, "y", _number("gauge.y", self.y))
        self._check_choices("gauge")
        self._check_name_and_interval("gauge")

    def y_in(self, scene: FlumeScene) -> float:
        """y of the gauge line in a 3D scene [m] (the centre line when not given)."""
        lo, hi = scene.extent(1)
        return 0.5 * (lo + hi) if self.y is None else self.y

    def default_name(self, scene: FlumeScene, index: int) -> str:
        """``eta_x{x:.3f}`` (``_y{y:.3f}`` added in 3D)."""
        base = f"eta_x{self.x:.3f}"
        if scene.dim == 3:
            base += f"_y{self.y_in(scene):.3f}"
        return base

    def along_x(self) -> list[float]:
        """Where along the flume the gauge reads the waves [m]."""
        return [self.x]

    def check_in(self, scene: FlumeScene, label: str) -> None:
        """Refuse a gauge line outside the flume (the tank), naming ``label`` (``gauges[i]``)."""
        x0, x1 = scene.extent(0)
        if not x0 - _TOL <= self.x <= x1 + _TOL:
            raise SceneError(
                f"{label}.x: x = {self.x:g} m lies outside the {scene.PLACE} [{x0:g}, {x1:g}] m"
            )
        if scene.dim == 2 and self.y is not None:
            raise SceneError(f"{label}.y: only used in 3D; leave it unset in 2D")
        if scene.dim == 3 and self.y is not None:
            y0, y1 = scene.extent(1)
            if not y0 - _TOL <= self.y <= y1 + _TOL:
                raise SceneError(
                    f"{label}.y: y = {self.y:g} m lies outside the {scene.PLACE} width "
                    f"[{y0:g}, {y1:g}] m"
                )

    def to_core(self, scene: FlumeScene, name: str, interval: float) -> dict[str, Any]:
        """The core's gauge JSON."""
        pos = [self.x, 0.0] if scene.dim == 2 else [self.x, self.y_in(scene), 0.0]
        return {"type": self.TAG, "name": name, "position": pos, **self._chosen(),
                "interval": interval}

    @classmethod
    def read(cls, gauges: FlumeGauges, raws: list[dict[str, Any]]) -> None:
        """``names``, ``x``, ``y``, ``still_depth``, ``t``, ``elevation_raw``, ``zero_offsets``
        and ``elevation``: every gauge on the first gauge's times."""
        setup = gauges.setup
        depth = setup.level
        specs = {s["name"]: s for s in setup._gauge_specs()}
        gauges.names = tuple(str(r["name"]) for r in raws)
        gauges.x = np.array([specs[n]["position"][0] for n in gauges.names], dtype=np.float64)
        gauges.y = (
            np.array([specs[n]["position"][1] for n in gauges.names], dtype=np.float64)
            if setup.dim == 3 else None
        )
        gauges.still_depth = np.asarray(setup.still_depth(gauges.x, gauges.y), dtype=np.float64)
        if raws:
            t = np.asarray(raws[0]["t"], dtype=np.float64)
            cols = []
            for r in raws:
                tr = np.asarray(r["t"], dtype=np.float64)
                zr = np.asarray(r["z"], dtype=np.float64) - depth
                if tr.shape != t.shape or not np.array_equal(tr, t):
                    zr = np.interp(t, tr, zr) if tr.size else np.full(t.shape, np.nan)
                cols.append(zr)
            gauges.t = t
            gauges.elevation_raw = np.stack(cols, axis=1)
        else:
            gauges.t = np.zeros(0)
            gauges.elevation_raw = np.zeros((0, 0))
        gauges.zero_offsets = cls._zero_offsets(gauges)
        gauges.elevation = gauges.elevation_raw - gauges.zero_offsets

    @staticmethod
    def _zero_offsets(gauges: FlumeGauges) -> npt.NDArray[np.float64]:
        """Each gauge's still-water reading (t = 0): what it reads above the SWL at rest.

        A surface gauge reads the still water a fraction of dp off the SWL (the kernel method
        finds where the kernel volume sum falls to 0.5, about 0.4 dp above the top particle
        row's nominal surface). Like a laboratory gauge zeroed in still water before the run,
        each gauge's reading at t = 0 is subtracted; gauges too shallow at rest (less than 3 dp
        of water, or dry) and gauges over water that does not stand at the SWL at rest (a
        ``fluid`` block of the scene: a reading more than dp off) take the median offset of the
        others (0 if none).
        """
        n = len(gauges.names)
        if n == 0 or gauges.t.size == 0 or abs(gauges.t[0]) > 1e-12:
            return np.zeros(n)
        first = gauges.elevation_raw[0]
        dp = float(gauges.setup.dp)  # type: ignore[arg-type]
        deep = (gauges.still_depth > 3.0 * dp) & (np.abs(np.nan_to_num(first, nan=np.inf)) <= dp)
        if not np.any(deep):
            return np.zeros(n)
        fallback = float(np.median(first[deep]))
        return np.where(deep, first, fallback)

    @classmethod
    def dataset_variables(cls, gauges: FlumeGauges) -> Variables:
        """``elevation`` (time, gauge) [m], NaN when dry; per gauge ``x`` (and ``y`` in 3D) and
        ``still_depth``."""
        coords: dict[str, Any] = {
            "time": ("time", gauges.t, {"units": "s"}),
            "gauge": ("gauge", list(gauges.names)),
            "x": ("gauge", gauges.x, {"units": "m", "long_name": "position along the flume"}),
            "still_depth": ("gauge", gauges.still_depth, {"units": "m"}),
        }
        if gauges.y is not None:
            coords["y"] = ("gauge", gauges.y, {"units": "m", "long_name": "position across"})
        attrs = {"units": "m", "long_name": "surface elevation above the still water"}
        data = {"elevation": (("time", "gauge"), gauges.elevation, attrs)}
        return data, coords

    @classmethod
    def csv_series(cls, gauges: FlumeGauges) -> list[Series]:
        """One column per gauge: eta above the SWL [m], ``nan`` when dry
        (``eta_x1.000``: ``eta_x1p000_m``)."""
        return [(csv_column(name, "m"), gauges.t, gauges.elevation[:, j])
                for j, name in enumerate(gauges.names)]


@dataclass(frozen=True)
class _GaugeAtPoints(_Gauge):
    """A gauge at fixed points (x, z) or (x, y, z) [m]: their schema and checks.

    Attributes:
        points: the points, in flume coordinates (z from the floor).
        interval: sampling interval [s]; default the scene's ``sample_interval``.
    """

    points: tuple[tuple[float, ...], ...]
    name: str | None = None
    interval: float | None = None

    def __post_init__(self) -> None:
        try:
            rows = [tuple(p) for p in self.points]
        except TypeError:
            raise SceneError(f"gauge.points: expected a sequence of points, got "
                             f"{self.points!r}") from None
        if not rows:
            raise SceneError("gauge.points: needs at least one point")
        pts = tuple(_finite_tuple(f"gauge.points[{i}]", p, 2) for i, p in enumerate(rows))
        if len({len(p) for p in pts}) != 1 or len(pts[0]) not in (2, 3):
            raise SceneError("gauge.points: every point needs 2 (x, z) or 3 (x, y, z) coordinates")
        _set(self, "points", pts)
        self._check_name_and_interval("gauge")

    def along_x(self) -> list[float]:
        return [p[0] for p in self.points]

    def check_in(self, scene: FlumeScene, label: str) -> None:
        for j, p in enumerate(self.points):
            scene.check_point(f"{label}.points[{j}]", p)

    def to_core(self, scene: FlumeScene, name: str, interval: float) -> dict[str, Any]:
        return {"type": self.TAG, "name": name, "points": [list(p) for p in self.points],
                "interval": interval}


@dataclass(frozen=True)
class VelocityProbe(_VelocityGauge, _GaugeAtPoints):
    """Fluid velocity (Shepard-interpolated) at fixed points (x, z) or (x, y, z) [m].

    Attributes:
        name: record name; default ``velocity{i}``.
    """

    TAG: ClassVar[str] = "velocity"
    """The core's gauge ``type`` (and the scene file's ``type`` of a gauge table)."""

    RECORDS: ClassVar[str] = "velocity"


@dataclass(frozen=True)
class VelocityWindow(_VelocityGauge):
    """PIV-like window: velocity on a regular grid of ``n`` points per axis over ``[min, max]``.

    In 2D ``min``, ``max`` are (x, z) and ``n`` is (nx, nz); in 3D (x, y, z) and (nx, ny, nz)
    (one point along y gives a vertical plane). The record's velocity has shape
    ``(n_samples, *reversed(n), dim)``: z slowest, x fastest.

    Attributes:
        min, max: opposite corners [m], flume coordinates.
        n: points per axis (>= 1).
        name: record name; default ``window{i}``.
        interval: sampling interval [s]; default the scene's ``sample_interval``.
    """

    min: tuple[float, ...]
    max: tuple[float, ...]
    n: tuple[int, ...]
    name: str | None = None
    interval: float | None = None

    TAG: ClassVar[str] = "window"
    """The core's gauge ``type`` (and the scene file's ``type`` of a gauge table)."""

    def __post_init__(self) -> None:
        lo = _finite_tuple("gauge.min", self.min, 2)
        hi = _finite_tuple("gauge.max", self.max, 2)
        if len(lo) != len(hi) or len(lo) not in (2, 3):
            raise SceneError("gauge.max: min and max need 2 (x, z) or 3 (x, y, z) coordinates")
        if any(b < a for a, b in zip(lo, hi, strict=True)):
            raise SceneError(f"gauge.max: must not be below min on any axis ({lo} -> {hi})")
        counts = tuple(self.n) if not isinstance(self.n, (str, bytes)) else ()
        if len(counts) != len(lo):
            raise SceneError(f"gauge.n: needs {len(lo)} counts, got {self.n!r}")
        for i, c in enumerate(counts):
            _integer(f"gauge.n[{i}]", c, 1)
        _set(self, "min", lo)
        _set(self, "max", hi)
        _set(self, "n", tuple(int(c) for c in counts))
        self._check_name_and_interval("gauge")

    def along_x(self) -> list[float]:
        return []

    def check_in(self, scene: FlumeScene, label: str) -> None:
        scene.check_point(f"{label}.min", self.min)
        scene.check_point(f"{label}.max", self.max)

    def to_core(self, scene: FlumeScene, name: str, interval: float) -> dict[str, Any]:
        return {"type": self.TAG, "name": name, "min": list(self.min), "max": list(self.max),
                "n": list(self.n), "interval": interval}

    RECORDS: ClassVar[str] = "windows"


@dataclass(frozen=True)
class PressureGauge(_GaugeAtPoints):
    """Fluid pressure at fixed points (x, z) or (x, y, z) [m]: the Shepard-normalised kernel
    interpolation of the particles' pressures (their Tait law), as DualSPHysics measures pressure
    at a point; in still water, the hydrostatic ``rho0 g (depth - z)``.

    With ``on_wall=True`` the points are pressure sensors on a wall or a body: each must lie
    within dp of the tank's floor or sides or of a body's surface (the build refuses it
    otherwise, naming ``gauges[i].points[j]``), and is read at the point moved along that
    surface's normal to dp/2 inside the fluid (the first fluid layer; the pressure a wall
    particle's own equation of state gives is noisier, and Adami's walls have none of their
    own); the record's points are those read.

    Its record is ``FlumeGauges.records[name]``: ``t`` (n,) [s], ``points`` (p, dim) [m],
    ``pressure`` (n, p) [Pa] and ``kernel_sum`` (n, p) (below :data:`DRY_KERNEL_SUM` the point
    is out of the water and its pressure means nothing).

    Attributes:
        name: record name; default ``pressure{i}``.
        on_wall: the points are sensors on a wall or body (see above).
    """

    on_wall: bool = False

    TAG: ClassVar[str] = "pressure"
    """The core's gauge ``type`` (and the scene file's ``type`` of a gauge table)."""

    def __post_init__(self) -> None:
        super().__post_init__()
        if not isinstance(self.on_wall, bool):
            raise SceneError(f"gauge.on_wall: expected True or False, got {self.on_wall!r}")

    def to_core(self, scene: FlumeScene, name: str, interval: float) -> dict[str, Any]:
        spec = super().to_core(scene, name, interval)
        if self.on_wall:
            spec["on_wall"] = True
        return spec

    @classmethod
    def dataset_variables(cls, gauges: FlumeGauges) -> Variables:
        """Per gauge ``pressure_NAME`` (time_NAME, point_NAME) [Pa], NaN where dry, and
        ``kernel_sum_NAME``; the points in ``points_NAME``."""
        data: dict[str, Any] = {}
        coords: dict[str, Any] = {}
        for name, t, points, pressure, kernel_sum in cls._records(gauges):
            tname, pname = f"time_{name}", f"point_{name}"
            coords[tname] = (tname, t, {"units": "s"})
            coords[f"points_{name}"] = ((pname, "axis"), points, {"units": "m"})
            data[f"pressure_{name}"] = ((tname, pname), pressure,
                                        {"units": "Pa", "long_name": "fluid pressure"})
            data[f"kernel_sum_{name}"] = ((tname, pname), kernel_sum, _KERNEL_SUM_ATTRS)
        return data, coords

    @classmethod
    def _records(cls, gauges: FlumeGauges) -> Iterator[tuple[str, Any, Any, Any, Any]]:
        """Per pressure gauge: its name, ``t`` (n,), ``points`` (p, dim), the pressure (n, p)
        with NaN where dry, and the kernel sum (n, p)."""
        for name, t, record in cls._records_by_name(gauges):
            kernel_sum = np.asarray(record["kernel_sum"], dtype=np.float64).reshape(t.size, -1)
            pressure = np.asarray(record["pressure"], dtype=np.float64).reshape(t.size, -1)
            yield (name, t, np.asarray(record["points"], dtype=np.float64),
                   np.where(kernel_sum < DRY_KERNEL_SUM, np.nan, pressure), kernel_sum)

    @classmethod
    def csv_series(cls, gauges: FlumeGauges) -> list[Series]:
        """One column per point of each pressure gauge: its pressure [Pa], ``nan`` where the
        point is dry (gauge ``p0``, point (4, 0.1): ``p0_x4p000_z0p100_Pa``)."""
        series: list[Series] = []
        for name, t, points, pressure, _ in cls._records(gauges):
            for k, label in enumerate(point_labels(points)):
                series.append((csv_column(f"{name}_{label}", "Pa"), t, pressure[:, k]))
        return series


@dataclass(frozen=True)
class RunupGauge(_Gauge):
    """Run-up: the highest wet point along a segment laid just above the beach (``end`` uphill);
    records its vertical position.

    Attributes:
        start, end: the segment's ends [m], flume coordinates; ``None`` (both): laid automatically
            along the beach, ``1.5 dp`` above its surface, from below the lowest run-down up to
            the top of the slope.
        method: ``"kernel"``, ``"particle"`` or ``"wet_front"`` (see :data:`RUNUP_METHODS`);
            ``None``: the core's default (``scene_defaults()["gauges"]["runup_method"]``).
        name: record name (default ``"runup"``).
        interval: sampling interval [s]; default the scene's ``sample_interval``.
    """

    start: tuple[float, ...] | None = None
    end: tuple[float, ...] | None = None
    method: str | None = None
    name: str = "runup"
    interval: float | None = None

    TAG: ClassVar[str] = "runup"
    """The core's gauge ``type`` (and the scene file's ``type`` of a gauge table)."""
    CHOICES: ClassVar[dict[str, tuple[str, ...]]] = {"method": RUNUP_METHODS}
    CORE_DEFAULTS: ClassVar[dict[str, str]] = {"method": "gauges.runup_method"}
    """The core's defaults of the fields left ``None`` (keys of ``scene_defaults()``)."""

    def __post_init__(self) -> None:
        if (self.start is None) != (self.end is None):
            raise SceneError("runup.end: give both start and end, or neither (automatic)")
        if self.start is not None and self.end is not None:
            a = _finite_tuple("runup.start", self.start, 2)
            b = _finite_tuple("runup.end", self.end, 2)
            if len(a) != len(b) or len(a) not in (2, 3):
                raise SceneError("runup.end: start and end need 2 (x, z) or 3 (x, y, z) values")
            if a == b:
                raise SceneError("runup.end: must differ from start")
            if b[-1] <= a[-1]:
                raise SceneError("runup.end: must be uphill of start (higher z)")
            _set(self, "start", a)
            _set(self, "end", b)
        self._check_choices("runup")
        self._check_name_and_interval("runup")

    def to_core(self, scene: FlumeScene, name: str, interval: float) -> dict[str, Any]:
        """The core's gauge JSON (the segment resolved: see :attr:`FlumeScene.runup_gauge`)."""
        assert self.start is not None and self.end is not None
        return {"type": self.TAG, "name": name, "start": list(self.start),
                "end": list(self.end), **self._chosen(), "interval": interval}

    @classmethod
    def read(cls, gauges: FlumeGauges, raws: list[dict[str, Any]]) -> None:
        """``runup_name``, ``runup_t``, ``runup_raw``, ``runup_offset`` and ``runup`` (zeroed on
        the reading at rest), None without a run-up gauge."""
        gauges.runup_offset = 0.0
        if not raws:
            gauges.runup_name, gauges.runup_t, gauges.runup, gauges.runup_raw = (
                None, None, None, None)
            return
        depth = gauges.setup.flume.depth
        gauges.runup_name = str(raws[0]["name"])
        gauges.runup_t = np.asarray(raws[0]["t"], dtype=float)
        raw = np.asarray(raws[0]["z"], dtype=np.float64) - depth
        if gauges.runup_t.size and abs(gauges.runup_t[0]) <= 1e-12 and np.isfinite(raw[0]):
            gauges.runup_offset = float(raw[0])
        gauges.runup_raw = raw
        gauges.runup = raw - gauges.runup_offset

    @classmethod
    def dataset_variables(cls, gauges: FlumeGauges) -> Variables:
        """``runup`` (time_runup) [m] above the still water."""
        if gauges.runup is None or gauges.runup_t is None:
            return {}, {}
        return ({"runup": ("time_runup", gauges.runup,
                           {"units": "m", "long_name": "run-up above the still water"})},
                {"time_runup": ("time_runup", gauges.runup_t, {"units": "s"})})

    @classmethod
    def csv_series(cls, gauges: FlumeGauges) -> list[Series]:
        """The run-up: elevation above the SWL [m] (``runup_m``)."""
        if gauges.runup_name is None or gauges.runup is None or gauges.runup_t is None:
            return []
        return [(csv_column(gauges.runup_name, "m"), gauges.runup_t, gauges.runup)]


@dataclass(frozen=True)
class ForceGauge(_Gauge):
    """Force and moment of the fluid on a body (one of the ``bodies`` of a
    :class:`~watersim.Scene` or a preset, a flume too, by name): the sum over the body's wall
    particles of the opposites of their fluid neighbours' pair forces (pressure and viscosity),
    and its moment about ``point``. In 2D per unit width: N/m and N m/m, the moment about the
    y axis (``M_y = r_z F_x - r_x F_z``); in 3D N and N m about x, y and z.

    Its record is ``FlumeGauges.records[name]``: ``t`` (n,) [s], ``force`` (n, dim) and
    ``moment`` (n,) in 2D or (n, 3) in 3D.

    Attributes:
        structure: the name of the body (structure) measured.
        point: the point the moment is taken about [m], (x, z) or (x, y, z).
        name: record name; default the structure's name.
        interval: sampling interval [s]; default the scene's ``sample_interval``.
    """

    structure: str
    point: tuple[float, ...]
    name: str | None = None
    interval: float | None = None

    TAG: ClassVar[str] = "force"
    """The core's gauge ``type`` (and the scene file's ``type`` of a gauge table)."""

    def __post_init__(self) -> None:
        _optional_name("gauge.structure", self.structure)
        if self.structure is None:
            raise SceneError("gauge.structure: a force gauge needs the name of its structure")
        point = _finite_tuple("gauge.point", self.point, 2)
        if len(point) not in (2, 3):
            raise SceneError("gauge.point: needs 2 (x, z) or 3 (x, y, z) coordinates")
        _set(self, "point", point)
        self._check_name_and_interval("gauge")

    def default_name(self, scene: FlumeScene, index: int) -> str:
        """The structure's name."""
        return self.structure

    def along_x(self) -> list[float]:
        return []

    def check_in(self, scene: FlumeScene, label: str) -> None:
        """Refuse a structure the scene does not have, or a point of the wrong dimension."""
        if scene.obstacle_index(self.structure) is None:
            known = ", ".join(repr(n) for n in scene.body_names()) or "none"
            raise SceneError(f"{label}.structure: no body named {self.structure!r} in the "
                             f"scene's {scene.BODIES} ({known})")
        if len(self.point) != scene.dim:
            raise SceneError(f"{label}.point: needs {scene.dim} coordinates in {scene.dim}D, "
                             f"got {len(self.point)}")

    def to_core(self, scene: FlumeScene, name: str, interval: float) -> dict[str, Any]:
        return {"type": self.TAG, "name": name, "obstacle": scene.obstacle_index(self.structure),
                "point": list(self.point), "interval": interval}

    @classmethod
    def records_of(cls, gauges: FlumeGauges) -> Iterator[tuple[str, Any, Any, Any]]:
        """Per force gauge: its name, ``t`` (n,), ``force`` (n, dim) and ``moment`` (n, 1) in
        2D, (n, 3) in 3D."""
        for name, t, record in cls._records_by_name(gauges):
            force = np.asarray(record["force"], dtype=np.float64).reshape(t.size, -1)
            moment = np.asarray(record["moment"], dtype=np.float64).reshape(t.size, -1)
            yield name, t, force, moment

    @staticmethod
    def units(dim: int) -> tuple[str, str]:
        """The force's and the moment's units (per unit width in 2D)."""
        return ("N/m", "N m/m") if dim == 2 else ("N", "N m")

    @classmethod
    def dataset_variables(cls, gauges: FlumeGauges) -> Variables:
        """Per gauge ``force_NAME`` (time_NAME, component) [N, N/m in 2D] and ``moment_NAME``
        (time_NAME, moment_axis) [N m, N m/m in 2D]."""
        dim = gauges.setup.dim
        force_unit, moment_unit = cls.units(dim)
        axes = ["y"] if dim == 2 else ["x", "y", "z"]
        data: dict[str, Any] = {}
        coords: dict[str, Any] = {}
        for name, t, force, moment in cls.records_of(gauges):
            tname = f"time_{name}"
            coords[tname] = (tname, t, {"units": "s"})
            data[f"force_{name}"] = ((tname, "component"), force,
                                     {"units": force_unit, "long_name": "fluid force"})
            coords[f"moment_axis_{name}"] = (f"moment_axis_{name}", axes)
            data[f"moment_{name}"] = ((tname, f"moment_axis_{name}"), moment,
                                      {"units": moment_unit, "long_name": "fluid moment"})
        return data, coords

    @classmethod
    def csv_series(cls, gauges: FlumeGauges) -> list[Series]:
        """Per force gauge its force components and moment (gauge ``box`` in 2D:
        ``box_Fx_N_per_m``, ``box_Fz_N_per_m``, ``box_My_N_m_per_m``)."""
        dim = gauges.setup.dim
        force_unit, moment_unit = (u.replace("/", "_per_").replace(" ", "_")
                                   for u in cls.units(dim))
        axes = ("x", "z") if dim == 2 else ("x", "y", "z")
        moment_axes = ("y",) if dim == 2 else ("x", "y", "z")
        series: list[Series] = []
        for name, t, force, moment in cls.records_of(gauges):
            series += [(csv_column(f"{name}_F{a}", force_unit), t, force[:, k])
                       for k, a in enumerate(axes)]
            series += [(csv_column(f"{name}_M{a}", moment_unit), t, moment[:, k])
                       for k, a in enumerate(moment_axes)]
        return series


@dataclass(frozen=True)
class OvertoppingGauge(_Gauge):
    """Overtopping: the volume of water that has crossed the vertical section at ``x`` towards
    the far end since the start, net of what came back (each particle's side of the section is
    tracked by the core), and the discharge over each sampling interval. Per unit width in 2D:
    m^3/m and m^3/s/m; in 3D m^3 and m^3/s over the whole width.

    Its record is ``FlumeGauges.records[name]``: ``t`` (n,) [s], ``volume`` (n,) and
    ``discharge`` (n,) (0 at the first sample).

    Attributes:
        x: the section, e.g. a seawall's crest [m].
        name: record name; default ``overtopping{i}``.
        interval: sampling interval [s]; default the scene's ``sample_interval``.
    """

    x: float
    name: str | None = None
    interval: float | None = None

    TAG: ClassVar[str] = "overtopping"
    """The core's gauge ``type`` (and the scene file's ``type`` of a gauge table)."""

    def __post_init__(self) -> None:
        _set(self, "x", _number("gauge.x", self.x))
        self._check_name_and_interval("gauge")

    def along_x(self) -> list[float]:
        return [self.x]

    def check_in(self, scene: FlumeScene, label: str) -> None:
        """Refuse a section outside the flume (the tank)."""
        x0, x1 = scene.extent(0)
        if not x0 < self.x < x1:
            raise SceneError(f"{label}.x: x = {self.x:g} m lies outside the {scene.PLACE} "
                             f"({x0:g}, {x1:g}) m")

    def to_core(self, scene: FlumeScene, name: str, interval: float) -> dict[str, Any]:
        return {"type": self.TAG, "name": name, "x": self.x, "interval": interval}

    @classmethod
    def records_of(cls, gauges: FlumeGauges) -> Iterator[tuple[str, Any, Any, Any]]:
        """Per overtopping gauge: its name, ``t``, ``volume`` and ``discharge`` (each (n,))."""
        for name, t, record in cls._records_by_name(gauges):
            yield (name, t, np.asarray(record["volume"], dtype=np.float64).reshape(-1),
                   np.asarray(record["discharge"], dtype=np.float64).reshape(-1))

    @staticmethod
    def units(dim: int) -> tuple[str, str]:
        """The volume's and the discharge's units (per unit width in 2D)."""
        return ("m^3/m", "m^3/s/m") if dim == 2 else ("m^3", "m^3/s")

    @classmethod
    def dataset_variables(cls, gauges: FlumeGauges) -> Variables:
        """Per gauge ``overtopping_volume_NAME`` and ``overtopping_discharge_NAME``
        (time_NAME)."""
        volume_unit, discharge_unit = cls.units(gauges.setup.dim)
        data: dict[str, Any] = {}
        coords: dict[str, Any] = {}
        for name, t, volume, discharge in cls.records_of(gauges):
            tname = f"time_{name}"
            coords[tname] = (tname, t, {"units": "s"})
            data[f"overtopping_volume_{name}"] = (tname, volume, {
                "units": volume_unit, "long_name": "volume crossed since the start, net"})
            data[f"overtopping_discharge_{name}"] = (tname, discharge, {
                "units": discharge_unit, "long_name": "discharge over the last interval"})
        return data, coords

    @classmethod
    def csv_series(cls, gauges: FlumeGauges) -> list[Series]:
        """Per gauge its volume and discharge (gauge ``q`` in 2D: ``q_volume_m3_per_m``,
        ``q_discharge_m3_per_s_per_m``)."""
        volume_unit, discharge_unit = (u.replace("^", "").replace("/", "_per_")
                                       for u in cls.units(gauges.setup.dim))
        series: list[Series] = []
        for name, t, volume, discharge in cls.records_of(gauges):
            series.append((csv_column(f"{name}_volume", volume_unit), t, volume))
            series.append((csv_column(f"{name}_discharge", discharge_unit), t, discharge))
        return series


Gauge = (ElevationGauge | VelocityProbe | VelocityWindow | PressureGauge | ForceGauge
         | OvertoppingGauge)
"""The gauges a :class:`FlumeScene` takes in its ``gauges`` (the run-up gauge is apart)."""

SCENE_GAUGE_TYPES: tuple[type[_Gauge], ...] = typing.get_args(Gauge)

GAUGE_TYPES: dict[str, type[_Gauge]] = {
    cls.TAG: cls for cls in typing.get_args(Gauge | RunupGauge)
}
"""Every gauge class by its ``TAG`` (the core's gauge ``type``)."""


def gauge_names(scene: FlumeScene, gauges: Sequence[_Gauge]) -> list[str]:
    """Names of ``gauges`` (defaults by position or index, deduplicated with ``_2``...)."""
    names: list[str] = []
    taken = {g.name for g in gauges if g.name is not None}
    counters: dict[type, int] = {}
    for g in gauges:
        if g.name is not None:
            names.append(g.name)
            continue
        index = counters.get(type(g), 0)
        counters[type(g)] = index + 1
        base = g.default_name(scene, index)
        name, k = base, 2
        while name in taken:
            name, k = f"{base}_{k}", k + 1
        taken.add(name)
        names.append(name)
    return names


def check_gauges(scene: FlumeScene, gauges: Sequence[_Gauge]) -> set[str]:
    """Each gauge checked in ``scene`` (``gauges[i]`` named), names unique; returns the names."""
    names: set[str] = set()
    for i, (g, name) in enumerate(zip(gauges, gauge_names(scene, gauges), strict=True)):
        g.check_in(scene, f"gauges[{i}]")  # type: ignore[attr-defined]
        if name in names:
            raise SceneError(f"gauges[{i}].name: duplicate gauge name {name!r}")
        names.add(name)
    return names


def gauge_specs(scene: FlumeScene, gauges: Sequence[_Gauge], default_interval: float
                ) -> list[dict[str, Any]]:
    """The core's JSON of ``gauges`` (``default_interval`` [s] where a gauge gives none)."""
    return [g.to_core(scene, name, default_interval if g.interval is None  # type: ignore[attr-defined]
                      else g.interval)
            for g, name in zip(gauges, gauge_names(scene, gauges), strict=True)]


def elevation_gauges_between(
    x_start: float, x_end: float, spacing: float, method: str | None = None
) -> list[ElevationGauge]:
    """Elevation gauges every ``spacing`` metres from ``x_start`` to ``x_end`` (both included
    when they fall on the spacing): a line of gauges for envelopes and breaking position
    (``method`` as :class:`ElevationGauge`'s)."""
    a = _number("x_start", x_start)
    b = _number("x_end", x_end)
    s = _positive("spacing", spacing)
    if b < a:
        raise SceneError(f"x_end: must not be before x_start ({a:g} -> {b:g})")
    n = math.floor((b - a) / s + 1e-9)
    return [ElevationGauge(round(a + i * s, 9), method=method) for i in range(n + 1)]

