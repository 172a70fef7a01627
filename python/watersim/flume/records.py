"""The gauge records of a flume run as NumPy arrays, and their CSV files."""

from __future__ import annotations

import csv
import math
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from .._files import atomic_write
from .gauges import DRY_KERNEL_SUM, GAUGE_TYPES, Series, VelocityRecord, csv_column, point_labels

if TYPE_CHECKING:
    from .scene import FlumeScene

__all__ = ["DRY_KERNEL_SUM", "FlumeGauges", "VelocityRecord", "velocity_csv_name"]

_COMPONENTS = {2: ("u", "w"), 3: ("u", "v", "w")}
"""Velocity components along x (u), y (v) and z (w), the axes of the flume."""


def velocity_csv_name(name: str) -> str:
    """The file a velocity probe or window ``name`` is written to: ``velocity_NAME.csv``."""
    return f"velocity_{csv_column(name)}.csv"


class FlumeGauges:
    """Gauge records of a flume run as NumPy arrays (a snapshot taken when created).

    Attributes:
        names: elevation gauge names, in scene order.
        x: (g,) gauge positions along the flume [m]; y: (g,) across (3D) or None.
        still_depth: (g,) still-water depth at each gauge [m] (<= 0 on a dry beach).
        t: (n,) sample times of the elevation gauges [s].
        elevation: (n, g) surface elevation above the SWL [m], each gauge zeroed on its
            still-water reading at t = 0 (see :attr:`zero_offsets`); NaN when no water was found.
        elevation_raw: (n, g) the core's surface height minus the depth [m], not zeroed.
        zero_offsets: (g,) the still-water readings subtracted [m] (a fraction of dp).
        runup_t, runup: run-up record [s], [m above the SWL], zeroed on its reading at rest
            (``runup_offset``; ``runup_raw`` is not zeroed); None without a run-up gauge.
        runup_name: the run-up gauge's name, or None.
        velocity: velocity probes by name (:class:`VelocityRecord`).
        windows: velocity windows by name (:class:`VelocityRecord`).
        records: by name, the records of gauge kinds that declare no arrays of their own
            (each field of the core's record as an array).

    Each gauge class in :data:`~watersim.flume.gauges.GAUGE_TYPES` turns its kind's records
    into these arrays (its ``read``) and names its columns of :meth:`to_csv` (its
    ``csv_series``).
    """

    names: tuple[str, ...]
    x: npt.NDArray[np.float64]
    y: npt.NDArray[np.float64] | None
    still_depth: npt.NDArray[np.float64]
    t: npt.NDArray[np.float64]
    elevation_raw: npt.NDArray[np.float64]
    zero_offsets: npt.NDArray[np.float64]
    elevation: npt.NDArray[np.float64]
    runup_name: str | None
    runup_t: npt.NDArray[np.float64] | None
    runup_raw: npt.NDArray[np.float64] | None
    runup_offset: float
    runup: npt.NDArray[np.float64] | None
    velocity: dict[str, VelocityRecord]
    windows: dict[str, VelocityRecord]

    def __init__(self, setup: FlumeScene, records: list[dict[str, Any]]) -> None:
        self.setup = setup
        self.records: dict[str, dict[str, npt.NDArray[Any]]] = {}
        for tag, cls in GAUGE_TYPES.items():
            cls.read(self, [r for r in records if r["type"] == tag])

    @property
    def bed_elevation(self) -> npt.NDArray[np.float64]:
        """(g,) bed level at each gauge relative to the SWL [m] (``-still_depth``)."""
        return -self.still_depth

    @property
    def elevation_filled(self) -> npt.NDArray[np.float64]:
        """:attr:`elevation` with dry samples (NaN) replaced by the bed level: what a gauge
        standing on the beach reads (the convention of envelopes and set-up)."""
        if self.elevation.size == 0:
            return self.elevation.copy()
        bed = np.broadcast_to(self.bed_elevation, self.elevation.shape)
        return np.where(np.isnan(self.elevation), bed, self.elevation)

    def runup_on(self, t: npt.ArrayLike) -> npt.NDArray[np.float64] | None:
        """The run-up record interpolated on times ``t`` [s] (None without run-up gauge)."""
        if self.runup is None or self.runup_t is None:
            return None
        tt = np.asarray(t, dtype=np.float64)
        if self.runup_t.shape == tt.shape and np.array_equal(self.runup_t, tt):
            return self.runup.copy()
        return np.interp(tt, self.runup_t, self.runup) if self.runup_t.size else None

    def uniform(
        self, dt: float | None = None
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64] | None]:
        """``(t, elevation_filled, runup)`` linearly resampled on a uniform time grid.

        The core samples at the first step past each sample time, so recorded times jitter by
        less than one time step; spectral analysis wants them uniform. ``dt`` defaults to the
        scene's ``sample_interval``.
        """
        step = float(self.setup.sample_interval if dt is None else dt)  # type: ignore[arg-type]
        if self.t.size < 2:
            return self.t.copy(), self.elevation_filled, self.runup_on(self.t)
        n = math.floor((self.t[-1] - self.t[0]) / step + 1e-9) + 1
        grid = self.t[0] + step * np.arange(n)
        filled = self.elevation_filled
        eta = np.stack([np.interp(grid, self.t, filled[:, j]) for j in range(filled.shape[1])],
                       axis=1) if filled.shape[1] else np.zeros((n, 0))
        runup = None
        if self.runup is not None and self.runup_t is not None and self.runup_t.size >= 2:
            r = self.runup
            start_level = self._runup_start_level() - self.runup_offset
            r = np.where(np.isnan(r), start_level, r)
            runup = np.interp(grid, self.runup_t, r)
        return grid, eta, runup

    def _runup_start_level(self) -> float:
        gauge = self.setup.runup_gauge
        if gauge is None or gauge.start is None:
            return 0.0
        return float(gauge.start[-1]) - self.setup.flume.depth

    def _csv_series(self) -> list[Series]:
        return [s for cls in GAUGE_TYPES.values() for s in cls.csv_series(self)]

    def columns(self) -> list[str]:
        """Column names of :meth:`to_csv`, each with its unit: ``t_s``, the elevation gauges
        (``eta_x1p000_m``), the run-up gauge (``runup_m``) and the columns of any other gauge
        kind that declares some (see :func:`~watersim.flume.gauges.csv_column`)."""
        return ["t_s", *(name for name, _, _ in self._csv_series())]

    def to_csv(self, path: str | os.PathLike[str]) -> Path:
        """Write ``t_s``, one column per elevation gauge (eta above the SWL [m], ``nan`` when
        dry) and the run-up (elevation above the SWL [m]) on the elevation gauges' times (on the
        first column's own times when the elevation gauges have none yet).

        Written to a temporary file first and renamed, so a reader never sees half a file.
        """
        series = self._csv_series()
        base = self.t if self.t.size else next((ts for _, ts, _ in series if ts.size), self.t)
        cols = [c for c in (_on(base, ts, values) for _, ts, values in series) if c is not None]
        return _write_table(Path(path), self.columns(), [base, *cols])

    def velocity_columns(self, name: str) -> tuple[list[str], list[npt.NDArray[np.float64]]]:
        """Header and columns of the velocity probe or window ``name``'s CSV file: ``t_s``,
        then per point (``x4p000_z0p100``: its position x, (y,) z [m]) the velocity components
        ``u``, (``v``,) ``w`` along x, (y,) z [m/s], ``nan`` where the point is dry (kernel sum
        below :data:`DRY_KERNEL_SUM`), and the point's ``kernel_sum`` [-]."""
        record = {**self.velocity, **self.windows}[name]
        points = np.asarray(record.points, dtype=np.float64)
        n = record.t.size
        velocity = np.asarray(record.velocity, dtype=np.float64).reshape(n, len(points), -1)
        ksum = np.asarray(record.kernel_sum, dtype=np.float64).reshape(n, len(points))
        header, cols = ["t_s"], [record.t]
        for k, label in enumerate(point_labels(points)):
            dry = ksum[:, k] < DRY_KERNEL_SUM
            for c, component in enumerate(_COMPONENTS[velocity.shape[2]]):
                header.append(f"{component}_{label}_m_per_s")
                cols.append(np.where(dry, np.nan, velocity[:, k, c]))
            header.append(f"kernel_sum_{label}")
            cols.append(ksum[:, k])
        return header, cols

    def velocity_to_csv(self, directory: str | os.PathLike[str]) -> dict[str, Path]:
        """Write each velocity probe and window to ``DIRECTORY/velocity_NAME.csv`` (see
        :meth:`velocity_columns`), on its own sampling times; returns the files by gauge name."""
        folder = Path(directory)
        return {name: _write_table(folder / velocity_csv_name(name), *self.velocity_columns(name))
                for name in {**self.velocity, **self.windows}}


def _write_table(path: Path, header: list[str],
                 columns: list[npt.NDArray[np.float64]]) -> Path:
    """Write a CSV table of float ``columns`` (the first one's length) under ``header``
    atomically (:func:`watersim._files.atomic_write`), so a reader never sees half a file."""
    with atomic_write(path, "w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f)
        writer.writerow(header)
        for i in range(len(columns[0])):
            writer.writerow([repr(float(c[i])) for c in columns])
    return path


def _on(t: npt.NDArray[np.float64], ts: npt.NDArray[np.float64],
        values: npt.NDArray[np.float64]) -> npt.NDArray[np.float64] | None:
    """``values`` sampled at ``ts`` [s], interpolated on ``t`` (as they are on the same
    times), None without samples."""
    if ts.shape == t.shape and np.array_equal(ts, t):
        return values
    return np.interp(t, ts, values) if ts.size else None
