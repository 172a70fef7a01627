"""The gauge records of a flume run as NumPy arrays, and their CSV file."""
from __future__ import annotations

import csv
import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

if TYPE_CHECKING:
    from .scene import FlumeScene


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
    """

    def __init__(self, setup: FlumeScene, records: list[dict[str, Any]]) -> None:
        depth = setup.flume.depth
        self.setup = setup
        elevation = [r for r in records if r["type"] == "elevation"]
        specs = {s["name"]: s for s in setup._gauge_specs()}
        self.names: tuple[str, ...] = tuple(str(r["name"]) for r in elevation)
        self.x = np.array([specs[n]["position"][0] for n in self.names], dtype=np.float64)
        self.y = (
            np.array([specs[n]["position"][1] for n in self.names], dtype=np.float64)
            if setup.dim == 3 else None
        )
        self.still_depth = np.asarray(setup.still_depth(self.x, self.y), dtype=np.float64)
        if elevation:
            t = np.asarray(elevation[0]["t"], dtype=np.float64)
            cols = []
            for r in elevation:
                tr = np.asarray(r["t"], dtype=np.float64)
                zr = np.asarray(r["z"], dtype=np.float64) - depth
                if tr.shape != t.shape or not np.array_equal(tr, t):
                    zr = np.interp(t, tr, zr) if tr.size else np.full(t.shape, np.nan)
                cols.append(zr)
            self.t = t
            self.elevation_raw = np.stack(cols, axis=1)
        else:
            self.t = np.zeros(0)
            self.elevation_raw = np.zeros((0, 0))
        self.zero_offsets = self._zero_offsets(setup)
        self.elevation = self.elevation_raw - self.zero_offsets
        runup = [r for r in records if r["type"] == "runup"]
        self.runup_offset = 0.0
        if runup:
            self.runup_name: str | None = str(runup[0]["name"])
            self.runup_t: npt.NDArray[np.float64] | None = np.asarray(runup[0]["t"], dtype=float)
            raw = np.asarray(runup[0]["z"], dtype=np.float64) - depth
            if self.runup_t.size and abs(self.runup_t[0]) <= 1e-12 and np.isfinite(raw[0]):
                self.runup_offset = float(raw[0])
            self.runup_raw: npt.NDArray[np.float64] | None = raw
            self.runup: npt.NDArray[np.float64] | None = raw - self.runup_offset
        else:
            self.runup_name, self.runup_t, self.runup, self.runup_raw = None, None, None, None
        self.velocity: dict[str, VelocityRecord] = {}
        self.windows: dict[str, VelocityRecord] = {}
        for r in records:
            if r["type"] not in ("velocity", "window"):
                continue
            vel = np.asarray(r["velocity"], dtype=np.float64)
            ksum = np.asarray(r["kernel_sum"], dtype=np.float64)
            shape = tuple(int(v) for v in r.get("shape") or ()) or None
            if r["type"] == "window" and shape is not None:
                grid = tuple(reversed(shape[: setup.dim]))
                vel = vel.reshape((vel.shape[0], *grid, setup.dim))
                ksum = ksum.reshape((ksum.shape[0], *grid))
            rec = VelocityRecord(
                name=str(r["name"]),
                t=np.asarray(r["t"], dtype=np.float64),
                points=np.asarray(r["points"], dtype=np.float64),
                velocity=vel,
                kernel_sum=ksum,
                shape=shape if r["type"] == "window" else None,
            )
            (self.windows if r["type"] == "window" else self.velocity)[rec.name] = rec

    def _zero_offsets(self, setup: FlumeScene) -> npt.NDArray[np.float64]:
        """Each gauge's still-water reading (t = 0): what it reads above the SWL at rest.

        A surface gauge reads the still water a fraction of dp off the SWL (the kernel method
        finds where the kernel volume sum falls to 0.5, about 0.4 dp above the top particle
        row's nominal surface). Like a laboratory gauge zeroed in still water before the run,
        each gauge's reading at t = 0 is subtracted; gauges too shallow at rest (less than 3 dp
        of water, or dry) take the median offset of the others (0 if none).
        """
        n = len(self.names)
        if n == 0 or self.t.size == 0 or abs(self.t[0]) > 1e-12:
            return np.zeros(n)
        first = self.elevation_raw[0]
        deep = (self.still_depth > 3.0 * float(setup.dp)) & np.isfinite(first)  # type: ignore[arg-type]
        if not np.any(deep):
            return np.zeros(n)
        fallback = float(np.median(first[deep]))
        return np.where(deep, first, fallback)

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

    def columns(self) -> list[str]:
        """Column names of :meth:`to_csv`: ``t``, the elevation gauges, the run-up gauge."""
        cols = ["t", *self.names]
        if self.runup_name is not None:
            cols.append(self.runup_name)
        return cols

    def to_csv(self, path: str | os.PathLike[str]) -> Path:
        """Write ``t``, one column per elevation gauge (eta above the SWL [m], ``nan`` when dry)
        and the run-up (elevation above the SWL [m]) on the elevation gauges' times.

        Written to a temporary file first and renamed, so a reader never sees half a file.
        """
        out = Path(path)
        tmp = out.with_name(out.name + ".tmp")
        runup = self.runup_on(self.t) if self.t.size else None
        with open(tmp, "w", newline="", encoding="utf-8") as f:
            writer = csv.writer(f)
            writer.writerow(self.columns())
            if self.t.size == 0 and self.runup is not None and self.runup_t is not None:
                for tk, rk in zip(self.runup_t, self.runup, strict=True):
                    writer.writerow([repr(float(tk)), repr(float(rk))])
            for i, tk in enumerate(self.t):
                row = [repr(float(tk))] + [repr(float(v)) for v in self.elevation[i]]
                if runup is not None:
                    row.append(repr(float(runup[i])))
                writer.writerow(row)
        tmp.replace(out)
        return out

