"""Dam-break measurements and the Martin & Moyce (1952) reference.

Positions are (N, dim) arrays in metres whose first axis is x (along the tank) and last axis is
z (vertical). Particles represent cells of size dp centred on them, so a measured extent adds
dp/2 (the particle radius) to the outermost particle centre: at t = 0 the front equals the column
width and the column height equals its height exactly.

Reference data (``watersim/data``, see ``SOURCES.md`` there): Martin & Moyce (1952), surge front
of a collapsing column of width L1 (``a`` in the paper) and height 2 L1 (n^2 = 2), in the
dimensionless form ``tau = t sqrt(2 g / L1)``, ``delta = x / L1``. The experiment's gate took
time to open, so simulated fronts usually lead the data: :func:`front_error` reports that lead and
does not shift the data. The same paper tabulates the residual height of the column at the back
wall, ``eta = h / (n^2 a)`` against ``tau = t sqrt(g / a)`` (note: no factor n in this time),
shipped for n^2 = 2 as :func:`load_martin_moyce_height`.
"""

from __future__ import annotations

import csv
import math
import numbers
from dataclasses import asdict, dataclass
from importlib import resources
from typing import Any

import numpy as np
import numpy.typing as npt

__all__ = [
    "MARTIN_MOYCE_DESCRIPTIONS",
    "MARTIN_MOYCE_HEIGHT_FILE",
    "MARTIN_MOYCE_SETS",
    "FrontError",
    "MartinMoyce",
    "MartinMoyceHeight",
    "front_error",
    "front_position",
    "load_martin_moyce",
    "load_martin_moyce_height",
    "water_column_height",
]

MARTIN_MOYCE_SETS: dict[str, str] = {
    "lethe": "mm1952_front_n2-2_lethe.csv",
    "pysph_a2.25in": "mm1952_front_n2-2_a2.25in_pysph.csv",
    "pysph_a1.125in": "mm1952_front_n2-2_a1.125in_pysph.csv",
}
"""Martin & Moyce n^2 = 2 front sets shipped in ``watersim/data``; ``"lethe"`` is the primary."""

MARTIN_MOYCE_DESCRIPTIONS: dict[str, str] = {
    "lethe": "their n^2 = 2 table as transcribed by the Lethe project",
    "pysph_a2.25in": "digitised from their Fig. 3, a = 2.25 in, by PySPH",
    "pysph_a1.125in": "digitised from their Fig. 3, a = 1.125 in, by PySPH",
}
"""What each set of :data:`MARTIN_MOYCE_SETS` is, in words for the console and the figures
(``watersim/data/SOURCES.md`` gives the provenance)."""

MARTIN_MOYCE_HEIGHT_FILE = "mm1952_height_n2-2_ocellaris.csv"
"""Martin & Moyce (1952) residual column height for n^2 = 2, as transcribed in Ocellaris from the
paper's tables ("Table 2 and 6" there); provenance in ``watersim/data/SOURCES.md``."""


def _connected_extent(values: npt.NDArray[np.float64], max_gap: float) -> float:
    """Largest value reachable from the smallest one through steps of at most ``max_gap``.

    ``values`` must be non-empty. The walk starts at the smallest value (the bulk sits against
    the wall or the floor) and the first gap wider than ``max_gap`` ends it.
    """
    v = np.sort(values)
    gaps = np.diff(v)
    breaks = np.flatnonzero(gaps > max_gap)
    return float(v[breaks[0]] if breaks.size else v[-1])


def front_position(
    positions_fluid: npt.ArrayLike,
    dp: float,
    wall_x: float = 0.0,
    *,
    floor_z: float = 0.0,
    band: float | None = None,
    max_gap: float = 2.0,
) -> float:
    """Surge front of a dam break [m], measured from the wall behind the column.

    Takes the fluid particles within ``band`` of the floor, sorts their x, and walks from the
    back wall towards the front; the first x-gap wider than ``max_gap * dp`` separates the bulk
    from droplets ahead of it, which are ignored. The front is the last connected particle plus
    dp/2 (its radius), so at t = 0 it equals the column width.

    Args:
        positions_fluid: (N, dim) fluid particle positions [m]; x first, z last.
        dp: particle spacing [m].
        wall_x: x of the wall behind the column [m].
        floor_z: z of the tank floor [m].
        band: height above the floor of the particles considered [m]; ``None`` means ``5 dp``
            (the surge tongue, not the splash above it).
        max_gap: largest x-gap between neighbours of the bulk, in units of dp.

    Returns:
        The front's distance from the wall [m]; NaN if no fluid particle is near the floor.
    """
    pos = np.asarray(positions_fluid, dtype=np.float64)
    if pos.ndim != 2 or pos.shape[1] not in (2, 3):
        raise ValueError(f"positions_fluid: expected shape (N, 2) or (N, 3), got {pos.shape}")
    if not dp > 0.0:
        raise ValueError(f"dp: must be positive, got {dp!r}")
    band_z = 5.0 * dp if band is None else band
    near_floor = pos[:, -1] - floor_z <= band_z
    x = pos[near_floor, 0]
    if x.size == 0:
        return math.nan
    front = _connected_extent(x, max_gap * dp)
    return front - wall_x + 0.5 * dp


def water_column_height(
    positions_fluid: npt.ArrayLike,
    dp: float,
    wall_x: float = 0.0,
    *,
    floor_z: float = 0.0,
    band: float | None = None,
    max_gap: float = 2.0,
) -> float:
    """Residual height of the collapsing column at the back wall [m].

    Takes the fluid particles within ``band`` of the wall, sorts their z, and walks up from the
    floor; the first z-gap wider than ``max_gap * dp`` separates the column from splashes above
    it. The height is the last connected particle plus dp/2, so at t = 0 it equals the column
    height.

    Args:
        positions_fluid: (N, dim) fluid particle positions [m]; x first, z last.
        dp: particle spacing [m].
        wall_x: x of the wall behind the column [m].
        floor_z: z of the tank floor [m].
        band: distance from the wall of the particles considered [m]; ``None`` means ``2 dp``.
        max_gap: largest z-gap between neighbours of the column, in units of dp.

    Returns:
        The height above the floor [m]; NaN if no fluid particle is near the wall.
    """
    pos = np.asarray(positions_fluid, dtype=np.float64)
    if pos.ndim != 2 or pos.shape[1] not in (2, 3):
        raise ValueError(f"positions_fluid: expected shape (N, 2) or (N, 3), got {pos.shape}")
    if not dp > 0.0:
        raise ValueError(f"dp: must be positive, got {dp!r}")
    band_x = 2.0 * dp if band is None else band
    near_wall = pos[:, 0] - wall_x <= band_x
    z = pos[near_wall, -1]
    if z.size == 0:
        return math.nan
    top = _connected_extent(z, max_gap * dp)
    return top - floor_z + 0.5 * dp


# ------------------------------------------------------------------------------------------------
# Martin & Moyce reference


@dataclass(frozen=True)
class MartinMoyce:
    """A Martin & Moyce front set in dimensionless form.

    Attributes:
        name: the set's key in :data:`MARTIN_MOYCE_SETS`.
        tau: ``t sqrt(2 g / L1)`` [-].
        delta: ``x / L1`` [-], front distance from the back wall over the column width.
    """

    name: str
    tau: npt.NDArray[np.float64]
    delta: npt.NDArray[np.float64]

    def dimensional(self, width: float, g: float = 9.81) -> tuple[np.ndarray, np.ndarray]:
        """(t [s], x [m]) for a column of width ``width`` [m] under gravity ``g`` [m/s^2]."""
        t = self.tau / math.sqrt(2.0 * g / width)
        return t, self.delta * width


def load_martin_moyce(name: str = "lethe") -> MartinMoyce:
    """Load a Martin & Moyce (1952) n^2 = 2 surge-front set shipped with the package.

    Args:
        name: one of :data:`MARTIN_MOYCE_SETS` (``"lethe"``, the primary set, is the
            n^2 = 2 table as given by Lethe; the PySPH sets are digitised from the paper's
            Fig. 3 for a = 2.25 in and 1.125 in).
    """
    if name not in MARTIN_MOYCE_SETS:
        allowed = ", ".join(repr(k) for k in MARTIN_MOYCE_SETS)
        raise ValueError(f"reference: unknown Martin & Moyce set {name!r}; allowed: {allowed}")
    text = resources.files("watersim.data").joinpath(MARTIN_MOYCE_SETS[name]).read_text("utf-8")
    rows = list(csv.reader(text.splitlines()))
    data = np.array([[float(a), float(b)] for a, b in rows[1:] if a.strip()], dtype=np.float64)
    return MartinMoyce(name=name, tau=data[:, 0], delta=data[:, 1])


@dataclass(frozen=True)
class MartinMoyceHeight:
    """The Martin & Moyce residual column height in their dimensionless form.

    Attributes:
        tau: ``t sqrt(g / a)`` [-] (a: the column width; unlike the front's time, no factor n).
        eta: ``h / (n^2 a)`` [-], the water height at the back wall over the initial height.
        n2: the column's height over its width, n^2 [-].
    """

    tau: npt.NDArray[np.float64]
    eta: npt.NDArray[np.float64]
    n2: float = 2.0

    def dimensional(self, width: float, g: float = 9.81) -> tuple[np.ndarray, np.ndarray]:
        """(t [s], h [m]) for a column of width ``width`` [m] (height ``n2 * width``)."""
        return self.tau / math.sqrt(g / width), self.eta * self.n2 * width


def load_martin_moyce_height() -> MartinMoyceHeight:
    """Load the Martin & Moyce (1952) residual column height for n^2 = 2 shipped with the package
    (17 points, tau = 0.56 to 7.40, eta on steps of 1/18: readings at fixed marks)."""
    text = resources.files("watersim.data").joinpath(MARTIN_MOYCE_HEIGHT_FILE).read_text("utf-8")
    rows = list(csv.reader(text.splitlines()))
    data = np.array([[float(a), float(b)] for a, b in rows[1:] if a.strip()], dtype=np.float64)
    return MartinMoyceHeight(tau=data[:, 0], eta=data[:, 1], n2=2.0)


@dataclass(frozen=True)
class FrontError:
    """Simulated surge front against a Martin & Moyce set.

    Attributes:
        reference: the reference set's name.
        rms_rel_error: RMS over the compared points of ``(x_sim(t_i) - x_i) / x_i`` [-].
        max_rel_error: largest ``|x_sim(t_i) - x_i| / x_i`` [-].
        mean_rel_error: mean signed relative error [-] (positive: the simulation is ahead).
        mean_lead_s: mean of ``t_i - t_sim(x_i)`` [s] over the points the simulated front has
            reached: how much earlier the simulation gets to each measured position (positive:
            the simulation leads). NaN if none was reached.
        n_points: number of reference points compared.
        t_max_s: last reference time compared [s].
    """

    reference: str
    rms_rel_error: float
    max_rel_error: float
    mean_rel_error: float
    mean_lead_s: float
    n_points: int
    t_max_s: float

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready dict (NaN becomes None)."""
        return {
            k: (None if isinstance(v, float) and math.isnan(v) else v)
            for k, v in asdict(self).items()
        }


def checked_series(
    t: npt.ArrayLike, values: npt.ArrayLike, name: str, width: float, shift: float = 0.0
) -> tuple[np.ndarray, np.ndarray]:
    """A simulated dam-break record ready to compare: times (plus ``shift`` [s]) and values as
    1-D float arrays without the non-finite samples.

    Raises:
        ValueError: arrays of different lengths or fewer than 2 samples (naming ``t`` and
            ``name``), times that are not strictly increasing, a non-positive ``width`` [m].
    """
    ts = np.asarray(t, dtype=np.float64).ravel() + float(shift)
    vs = np.asarray(values, dtype=np.float64).ravel()
    if ts.shape != vs.shape or ts.size < 2:
        raise ValueError(f"t, {name}: need two 1-D arrays of the same length, at least 2 samples")
    keep = np.isfinite(ts) & np.isfinite(vs)
    ts, vs = ts[keep], vs[keep]
    if ts.size < 2 or np.any(np.diff(ts) <= 0.0):
        raise ValueError("t: sample times must be finite and strictly increasing")
    if not width > 0.0:
        raise ValueError(f"width: must be positive, got {width!r}")
    return ts, vs


def front_error(
    t: npt.ArrayLike,
    x_front: npt.ArrayLike,
    width: float,
    g: float = 9.81,
    reference: str | MartinMoyce = "lethe",
    x_max: float | None = None,
) -> FrontError:
    """Compare a simulated surge front with Martin & Moyce (1952), without shifting either.

    The reference points compared are those measured after t = 0 (the initial point
    ``delta = 1`` of a set is the initial condition, not a measurement), at most at the last
    simulated time and, with ``x_max``, at most ``x_max`` from the back wall. At each such time
    t_i the simulated front is linearly interpolated and its relative error
    ``(x_sim - x_i) / x_i`` taken; the RMS over the points is returned. The time lead is
    ``t_i - t_sim(x_i)``, with ``t_sim(x)`` the first time the simulated front (made monotone
    by a running maximum) reaches x.

    Args:
        t: (K,) sample times [s], increasing.
        x_front: (K,) front distance from the back wall [m] (:func:`front_position`).
        width: column width L1 [m].
        g: gravitational acceleration [m/s^2].
        reference: a :data:`MARTIN_MOYCE_SETS` key or a loaded :class:`MartinMoyce`.
        x_max: compare only reference points at most this far from the back wall [m] (e.g.
            the tank length: a front cannot go past the far wall).

    Raises:
        ValueError: inputs of different lengths, non-increasing times, a ``g`` that is not a
            positive number, or no reference point in the simulated time range.
    """
    ts, xs = checked_series(t, x_front, "x_front", width)
    if isinstance(g, bool) or not isinstance(g, numbers.Real) or not 0.0 < g < math.inf:
        raise ValueError(f"g: must be a positive number [m/s^2], got {g!r} (a builder's "
                         "resolved value is its .g)")
    ref = load_martin_moyce(reference) if isinstance(reference, str) else reference
    t_ref, x_ref = ref.dimensional(width, g)
    measured = (t_ref > 0.0) & (t_ref <= ts[-1] * (1.0 + 1e-12)) & (t_ref >= ts[0])
    if x_max is not None:
        measured &= x_ref <= x_max
    if not np.any(measured):
        raise ValueError(
            f"t: the simulated range {ts[0]:g}-{ts[-1]:g} s holds no measured point of "
            f"'{ref.name}' (first at {t_ref[t_ref > 0].min():g} s)"
        )
    t_i, x_i = t_ref[measured], x_ref[measured]
    x_sim = np.interp(t_i, ts, xs)
    rel = (x_sim - x_i) / x_i

    # Time lead: first time the (monotone) simulated front reaches each measured position.
    envelope = np.maximum.accumulate(xs)
    leads = []
    for tk, xk in zip(t_i, x_i, strict=True):
        j = int(np.searchsorted(envelope, xk, side="left"))
        if j >= envelope.size:
            continue  # not reached in the simulated time
        if j == 0:
            t_reach = ts[0]
        else:
            x0, x1 = envelope[j - 1], envelope[j]
            frac = (xk - x0) / (x1 - x0) if x1 > x0 else 1.0
            t_reach = ts[j - 1] + frac * (ts[j] - ts[j - 1])
        leads.append(tk - t_reach)
    return FrontError(
        reference=ref.name,
        rms_rel_error=float(np.sqrt(np.mean(rel**2))),
        max_rel_error=float(np.max(np.abs(rel))),
        mean_rel_error=float(np.mean(rel)),
        mean_lead_s=float(np.mean(leads)) if leads else math.nan,
        n_points=int(t_i.size),
        t_max_s=float(t_i[-1]),
    )
