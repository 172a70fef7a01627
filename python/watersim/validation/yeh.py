"""Validation case yeh3d: the Yeh & Petroff 3D dam break against a tall square column.

Set-up as Raad & Bidoae (2005) and PySPH's ``dam_break/db_3d_yeh.py`` build it
(``watersim/data/SOURCES.md``): a tank 1.6 x 0.61 x 0.4 m, a water column 0.4 m long and 0.3 m
high across the whole width against the back wall, a thin sheet of water over the rest of the
floor (1 cm in the experiment: here one particle layer, so dp thick), and a square column 0.12 x
0.12 m centred at x = 0.96 m across the middle of the tank. The column is a
:class:`~watersim.Box` body of the scene's wall model; its force is the core's force gauge
(:class:`~watersim.ForceGauge`); the velocity probe stands at (0.814, centre, 0.026) m.

Errors:

- ``force_peak``: the largest simulated Fx on the column for t in [0.3, 0.6] s (the first
  impact) against the record's largest (33.1 N at 0.396 s), relative;
- ``force_impulse``: the integral of Fx over the same window against the record's (the
  momentum the first impact gives the column, whatever the sharpness of its peak: the simulated
  peak is a short acoustic spike of the weakly compressible water, as the Buchner cases' wall
  pressure);
- ``force_rms``: the RMS difference of Fx from the record at the record's times up to the run's
  end, over the record's peak;
- ``velocity_rms``: the RMS difference of the probe's horizontal velocity from the record, over
  the record's peak (2.2 m/s). The velocity record starts at 2.1 m/s at t = 0.009 s: its clock
  starts when the bore reaches the probe (the water needs about 0.2 s to get there from the
  gate; PySPH shifts its own series by a fixed 0.238 s), so the simulated series is compared
  from the time the water over the probe first stands :data:`BORE_DEPTH` deep (an elevation
  gauge on the probe's vertical): the sheet ahead of the bore, pushed along slowly, wets the
  probe earlier.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from ..bodies import Box
from ..flume.gauges import ElevationGauge, ForceGauge, VelocityProbe
from ..flume_cases import _load_csv
from ..scenes import FluidBlock, Scene
from .buchner import pressure_impulse
from .case import Case
from .running import _Clock, advance, make_record

YEH_TANK = (1.6, 0.61, 0.4)
"""The tank's inner length, width and height [m]."""
YEH_COLUMN_WATER = (0.4, 0.3)
"""Length and height of the water column [m]."""
YEH_OBSTACLE = ((0.9, 0.245, 0.0), (1.02, 0.365, 0.4))
"""The square column's corners [m]: 0.12 x 0.12 m centred at x = 0.96 m, across the middle,
up to the tank's top (PySPH's stands 0.75 m high above its 0.4 m tank; a body must lie in the
tank here, and the water does not climb the column that far in the time run)."""
YEH_PROBE = (0.814, 0.305, 0.026)
"""The velocity probe [m] (PySPH's (0.814, 0, 0.026) with y from the tank's side)."""
YEH_FILES = {"force": "yeh_petroff_force_on_column_pysph_digitised.csv",
             "velocity": "yeh_petroff_velocity_probe_pysph_digitised.csv"}
BORE_DEPTH = 0.05
"""Water depth over the probe [m] that marks the bore's arrival: above the sheet (one particle
layer reads at most about 0.035 m at the coarsest dp) and below the bore (about 0.09 m, Stoker's
wet-bed dam break for a sheet 0.08 of the column's height)."""
FIRST_IMPACT = (0.3, 0.6)
"""Window of the first impact's force peak [s]."""
SAMPLE = 0.005
"""Gauge sample interval [s]."""


def yeh_reference(name: str) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """The digitised record ``force`` (Fx [N]) or ``velocity`` (u [m/s]), sorted by t [s]."""
    t, v = _load_csv(YEH_FILES[name])
    order = np.argsort(t, kind="stable")
    return t[order], v[order]


def yeh_scene(dp: float, until: float) -> Scene:
    """The Yeh & Petroff dam break at ``dp`` to ``until`` [s], with the force gauge
    ``column`` and the velocity probe ``probe``."""
    length, width, height = YEH_TANK
    water_length, water_height = YEH_COLUMN_WATER
    return Scene(
        tank=YEH_TANK, dp=dp, until=until,
        fluid=[FluidBlock((0.0, 0.0, 0.0), (water_length, width, water_height)),
               # the 1 cm sheet as one particle layer (its centre at dp/2)
               FluidBlock((water_length, 0.0, 0.0), (length, width, dp))],
        bodies=[Box(*YEH_OBSTACLE, name="column")],
        gauges=[ForceGauge("column", point=(0.96, 0.305, 0.0), interval=SAMPLE),
                VelocityProbe(points=(YEH_PROBE,), name="probe", interval=SAMPLE),
                ElevationGauge(YEH_PROBE[0], YEH_PROBE[1], name="h_probe", interval=SAMPLE)],
    )


def first_reaching(t: npt.NDArray[np.float64], value: npt.NDArray[np.float64], level: float
                   ) -> float | None:
    """The first time ``value`` reaches ``level`` (linearly interpolated; NaN never does), or
    None."""
    reached = np.flatnonzero(np.nan_to_num(value, nan=-np.inf) >= level)
    if reached.size == 0:
        return None
    i = int(reached[0])
    if i == 0 or not np.isfinite(value[i - 1]):
        return float(t[i])
    a, b = value[i - 1], value[i]
    return float(t[i - 1] + (level - a) / (b - a) * (t[i] - t[i - 1]))


def yeh_metrics(t_force: npt.NDArray[np.float64], fx: npt.NDArray[np.float64],
                t_probe: npt.NDArray[np.float64], u: npt.NDArray[np.float64],
                kernel_sum: npt.NDArray[np.float64], depth: npt.NDArray[np.float64]
                ) -> tuple[dict[str, float | None], dict[str, Any]]:
    """Errors and details from the column's Fx, the probe's u and kernel sum and the water
    depth over the probe (on the probe's times)."""
    tf, ff = yeh_reference("force")
    tv, uv = yeh_reference("velocity")
    errors: dict[str, float | None] = {"force_peak": None, "force_impulse": None,
                                       "force_rms": None, "velocity_rms": None}
    details: dict[str, Any] = {}
    f_peak = float(np.max(ff))
    impact = (t_force >= FIRST_IMPACT[0]) & (t_force <= FIRST_IMPACT[1])
    if np.any(impact):
        i = int(np.argmax(np.where(impact, fx, -np.inf)))
        details.update(force_peak=float(fx[i]), t_force_peak=float(t_force[i]),
                       force_peak_recorded=f_peak,
                       t_force_peak_recorded=float(tf[int(np.argmax(ff))]))
        errors["force_peak"] = float(fx[i]) / f_peak - 1.0
    if t_force.size and t_force[-1] >= FIRST_IMPACT[1]:
        impulse = pressure_impulse(t_force, fx, *FIRST_IMPACT)
        recorded = pressure_impulse(tf, ff, *FIRST_IMPACT)
        details.update(force_impulse=impulse, force_impulse_recorded=recorded)
        errors["force_impulse"] = impulse / recorded - 1.0
    inside = (tf >= t_force[0]) & (tf <= t_force[-1]) if t_force.size else np.zeros(0, bool)
    if np.count_nonzero(inside) >= 2:
        diff = np.interp(tf[inside], t_force, fx) - ff[inside]
        errors["force_rms"] = float(np.sqrt(np.mean(diff ** 2))) / f_peak
    t_wet = first_reaching(t_probe, depth, BORE_DEPTH) if t_probe.size else None
    details["t_bore_at_probe"] = t_wet
    if t_wet is not None:
        rel = t_probe - t_wet
        u_wet = np.where(kernel_sum >= 0.5, u, 0.0)
        inside_v = (tv >= 0.0) & (tv <= rel[-1])
        if np.count_nonzero(inside_v) >= 2:
            diff = np.interp(tv[inside_v], rel, u_wet) - uv[inside_v]
            errors["velocity_rms"] = float(np.sqrt(np.mean(diff ** 2))) / float(np.max(uv))
    step = max(1, int(round(0.01 / SAMPLE)))
    details.update(force_t=[round(float(v), 4) for v in t_force[::step]],
                   force_x=[round(float(v), 3) for v in fx[::step]],
                   probe_t=[round(float(v), 4) for v in t_probe[::step]],
                   probe_u=[round(float(v), 4) if math.isfinite(v) else None
                            for v in np.where(kernel_sum >= 0.5, u, np.nan)[::step]])
    return errors, details


def run_yeh(case: Any, res: float, quick: bool, progress: bool) -> dict[str, Any]:
    """yeh3d at ``res`` = column width (0.12 m) / dp (the runner of :mod:`.cases`): to 1.5 s
    (0.6 s quick: the first impact)."""
    dp = case.dp(res)
    until = 0.6 if quick else 1.5
    scene = yeh_scene(dp, until)
    clock = _Clock()
    sim = scene.build()
    status, message = advance(sim, until, until / 30.0, None, progress, f"{case.name} {res:g}")
    gauges = sim.gauges
    force = gauges.records["column"]
    t_force = np.asarray(force["t"], dtype=np.float64)
    fx = np.asarray(force["force"], dtype=np.float64).reshape(t_force.size, -1)[:, 0]
    probe = gauges.velocity["probe"]
    depth = np.interp(probe.t, gauges.t, gauges.elevation[:, 0])
    errors, details = yeh_metrics(t_force, fx, probe.t, probe.velocity[:, 0, 0],
                                  probe.kernel_sum[:, 0], depth)
    details.update(until=until, sheet_thickness=dp)
    return make_record(case.name, res, dp, sim, clock.wall(), clock.cpu(), status, message,
                       errors, details)


def plot_yeh(runs: Sequence[Mapping[str, Any]], path: Path) -> None:
    """The column's force and the probe's velocity of each run over the records."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_f, ax_u) = plt.subplots(2, 1, figsize=(8, 7))
    tf, ff = yeh_reference("force")
    tv, uv = yeh_reference("velocity")
    ax_f.plot(tf, ff, "o", ms=2.5, mfc="none", color="k", label="Yeh & Petroff (digitised)")
    ax_u.plot(tv, uv, "o", ms=2.5, mfc="none", color="k", label="Yeh & Petroff (digitised)")
    for run in sorted(runs, key=lambda r: r["resolution"]):
        d = run.get("details", {})
        label = f"column/dp = {run['resolution']:g}"
        if d.get("force_t"):
            ax_f.plot(d["force_t"], d["force_x"], lw=0.9, label=label)
        if d.get("probe_t") and d.get("t_bore_at_probe") is not None:
            t = np.asarray(d["probe_t"], dtype=np.float64) - d["t_bore_at_probe"]
            u = np.array([np.nan if v is None else v for v in d["probe_u"]], dtype=np.float64)
            ax_u.plot(t, u, lw=0.9, label=label)
    ax_f.set_xlabel("t [s] from the release")
    ax_f.set_ylabel("Fx on the column [N]")
    ax_u.set_xlabel("t [s] from the bore's arrival at the probe")
    ax_u.set_ylabel("u at the probe [m/s]")
    for ax in (ax_f, ax_u):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    ax_u.set_xlim(-0.1, 1.4)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


YEH_CASE = Case(
    "yeh3d", "Yeh & Petroff 3D dam break against a square column: force, velocity",
    "Yeh & Petroff's records as digitised by Raad & Bidoae (2005) (PySPH's copy)",
    "column width / dp", 0.12, (5.0, 6.0, 8.0), (5.0,), "force_peak", 0.15,
    "first-impact force on the column within 15 % of the record's 33.1 N", run_yeh,
    "Tank 1.6 x 0.61 x 0.4 m, water 0.4 m long and 0.3 m high against the back wall, "
    "the record's 1 cm sheet over the rest of the floor as one particle layer (dp "
    "thick), a 0.12 m square column at x = 0.96 m (`watersim/validation/yeh.py`), "
    "DBC walls and the general scene's numerics, to 1.5 s (0.6 s with --quick). "
    "`force_peak`: the largest Fx for t in [0.3, 0.6] s against the record's (the "
    "simulated peak is a short acoustic spike, as in the Buchner cases); "
    "`force_impulse`: the integral of Fx over that window against the record's; "
    "`force_rms`: the RMS difference of Fx from the record up to the run's end, over "
    "its peak; `velocity_rms`: the same for u at (0.814, 0.305, 0.026) m over its "
    "peak (2.2 m/s), the simulated series put on the record's clock, which starts "
    "when the bore reaches the probe (here: when the water over the probe first "
    "stands 5 cm deep, above the sheet).",
    report_details=("force_peak", "t_force_peak", "force_impulse", "t_bore_at_probe"),
    figure=plot_yeh,
)
"""The ``watersim validate`` entry of yeh3d."""
