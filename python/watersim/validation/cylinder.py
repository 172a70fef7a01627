"""Validation case cylinder3d: the inline force of a regular wave on a vertical cylinder, Chen et
al. (2014), against their records as REEF3D's tutorial ships them (``watersim/data/SOURCES.md``).

The scene is the built-in flume case ``cylinder3d`` (:func:`watersim.flume_cases.case_cylinder3d`:
half the tank by symmetry, the paddle 4 m before the cylinder). Both records are on the
experiment's clock, the simulation's on its own: the amplitudes are compared as they are, the
phase as the force's phase relative to the elevation at the gauge (which does not depend on the
clock), and the whole force record after the simulation's clock is set on the gauge's phase.

Errors:

- ``force_amplitude``: half the mean zero-up-crossing height of the pile's Fx (twice the half
  cylinder's) over the analysis window (from two periods after the wave front reaches the
  cylinder to the run's end) against the record's (over all of it), relative;
- ``height_wg5``: the mean zero-up-crossing height at the gauge (x = 5 m in the tutorial's frame)
  against the record's: the wave that reaches the pile, so a force error can be told from the
  wave-maker's and the crossing's;
- ``phase``: the first harmonic's phase of Fx relative to the gauge's elevation against the
  record's, as a fraction of the period (signed: positive when the simulated force leads);
- ``force_rms``: the RMS difference of Fx from the record at the record's times, the
  simulation's clock shifted so that its first harmonic at the gauge has the record's phase, over
  the record's first-harmonic force amplitude.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from .. import analysis as an
from ..flume import FlumeScene
from ..flume_cases import CHEN_CYLINDER, CHEN_OFFSET, CHEN_WAVE, _load_csv
from .case import Case
from .running import _Clock, flume_run, make_record, numerical_case_scene

CHEN_FILES = {"force": "chen2014_expt_data_force_reef3d.csv",
              "elevation": "chen2014_expt_data_wsf_reef3d.csv"}
PERIODS_ANALYSED = 6.0
"""Periods of force record analysed (the run goes on that long after the analysis window opens,
two periods after the front reaches the cylinder)."""
QUICK_PERIODS = 3.0
"""The same with ``--quick``."""
SERIES_STEP = 0.02
"""Sample interval [s] of the series kept in a run's details for the figure."""

Series = tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]


def chen_reference(name: str) -> Series:
    """The record ``force`` (Fx [N]) or ``elevation`` (eta [m] at x = 5 m) against t [s], sorted
    by time, the values at a repeated time averaged (the digitised records repeat some)."""
    t, v = _load_csv(CHEN_FILES[name])
    times, index = np.unique(t, return_inverse=True)
    values = np.bincount(index, weights=v) / np.bincount(index)
    return times, values


def first_harmonic(t: npt.NDArray[np.float64], v: npt.NDArray[np.float64], period: float
                   ) -> tuple[float, float]:
    """Amplitude and phase [rad] of the least-squares fit ``c + A cos(w t - phi)``, w = 2 pi /
    ``period``, to samples at any times (the records' steps are irregular)."""
    w = 2.0 * math.pi / period
    basis = np.column_stack([np.ones_like(t), np.cos(w * t), np.sin(w * t)])
    (_, a, b), *_ = np.linalg.lstsq(basis, v, rcond=None)
    return float(math.hypot(a, b)), float(math.atan2(b, a))


def half_height(t: npt.NDArray[np.float64], v: npt.NDArray[np.float64]) -> float:
    """Half the mean zero-up-crossing height of a record (its mean as the level)."""
    return 0.5 * an.zero_crossing_waves(v, t, kind="up").mean_height


def _wrap(angle: float) -> float:
    """``angle`` [rad] into (-pi, pi]."""
    return math.pi - (math.pi - angle) % (2.0 * math.pi)


def cylinder_metrics(t_force: npt.NDArray[np.float64], fx: npt.NDArray[np.float64],
                     t_eta: npt.NDArray[np.float64], eta: npt.NDArray[np.float64],
                     start: float, period: float) -> tuple[dict[str, float | None], dict[str, Any]]:
    """Errors and details from the pile's inline force and the gauge's elevation of a run,
    analysed from ``start`` [s] (both on the run's clock)."""
    errors: dict[str, float | None] = {"force_amplitude": None, "height_wg5": None,
                                       "phase": None, "force_rms": None}
    details: dict[str, Any] = {"analysis_start": start}
    tf, ff = chen_reference("force")
    te, ee = chen_reference("elevation")
    f_amp_rec, f_phase_rec = first_harmonic(tf, ff, period)
    e_amp_rec, e_phase_rec = first_harmonic(te, ee, period)
    details.update(force_amplitude_recorded=half_height(tf, ff),
                   force_first_harmonic_recorded=f_amp_rec,
                   height_wg5_recorded=2.0 * half_height(te, ee))
    sel_f = (t_force >= start) & np.isfinite(fx)
    sel_e = (t_eta >= start) & np.isfinite(eta)
    if np.count_nonzero(sel_f) < 8 or np.count_nonzero(sel_e) < 8 \
            or t_force[-1] - start < 1.5 * period:
        return errors, details
    tfs, ffs, tes, ees = t_force[sel_f], fx[sel_f], t_eta[sel_e], eta[sel_e]
    try:
        amplitude = half_height(tfs, ffs)
        height = 2.0 * half_height(tes, ees)
    except ValueError:  # no complete wave in the window
        return errors, details
    f_amp, f_phase = first_harmonic(tfs, ffs, period)
    e_amp, e_phase = first_harmonic(tes, ees, period)
    errors["force_amplitude"] = amplitude / details["force_amplitude_recorded"] - 1.0
    errors["height_wg5"] = height / details["height_wg5_recorded"] - 1.0
    # phase of the force after the elevation's, simulated against recorded
    lag = _wrap((f_phase - e_phase) - (f_phase_rec - e_phase_rec))
    errors["phase"] = -lag / (2.0 * math.pi)
    details.update(force_amplitude=amplitude, force_first_harmonic=f_amp, height_wg5=height,
                   first_harmonic_wg5=e_amp, first_harmonic_wg5_recorded=e_amp_rec,
                   phase_error_deg=math.degrees(-lag))
    # the run's clock on the record's: the gauge's first harmonics in phase, the whole periods
    # chosen so that the analysed window falls on the force record's middle
    w = 2.0 * math.pi / period
    shift = (e_phase_rec - e_phase) / w
    shift += period * round((0.5 * (tf[0] + tf[-1]) - 0.5 * (start + t_force[-1]) - shift) / period)
    inside = (tf - shift >= start) & (tf - shift <= t_force[-1])
    if np.count_nonzero(inside) >= 8:
        diff = np.interp(tf[inside] - shift, tfs, ffs) - ff[inside]
        errors["force_rms"] = float(np.sqrt(np.mean(diff ** 2))) / f_amp_rec
    details["clock_shift"] = shift
    keep = t_force >= start - 2.0 * period
    step = max(1, int(round(SERIES_STEP / float(np.median(np.diff(t_force))))))
    details.update(series_t=[round(float(v) + shift, 4) for v in t_force[keep][::step]],
                   series_fx=[round(float(v), 3) for v in fx[keep][::step]])
    return errors, details


def cylinder_scene(dp: float, settings: Mapping[str, str] | None = None, quick: bool = False
                   ) -> tuple[FlumeScene, list[str]]:
    """cylinder3d at ``dp`` with ``--set``-style numerical ``settings``, run to two periods
    after the front reaches the cylinder plus :data:`PERIODS_ANALYSED` (:data:`QUICK_PERIODS`
    with ``quick``), and the warnings its build gave."""
    periods = QUICK_PERIODS if quick else PERIODS_ANALYSED

    def until(s: FlumeScene) -> float:
        return analysis_start(s) + periods * CHEN_WAVE["period"] + 0.05

    return numerical_case_scene("cylinder3d", dp, settings, until)


def analysis_start(scene: FlumeScene) -> float:
    """When the analysis window opens [s]: two periods after the wave front (linear group
    velocity, after the ramp) reaches the cylinder's axis."""
    x = CHEN_CYLINDER["x"] - CHEN_OFFSET
    return scene.law.ramp_duration + scene.arrival_time(x) + 2.0 * CHEN_WAVE["period"]


def run_cylinder(case: Any, res: float, quick: bool, progress: bool,
                 settings: Mapping[str, str] | None = None) -> dict[str, Any]:
    """cylinder3d at ``res`` = H / dp (the runner of :mod:`.cases`)."""
    dp = case.dp(res)
    scene, notes = cylinder_scene(dp, settings, quick)
    clock = _Clock()
    sim, status, message, result = flume_run(case, scene, res, progress, f"{case.name} {res:g}")
    gauges = sim.gauges
    force = gauges.records["half_pile"]
    t_force = np.asarray(force["t"], dtype=np.float64)
    # the tank is half of one mirrored through y = 0: the gauge reads half the pile's force
    fx = 2.0 * np.asarray(force["force"], dtype=np.float64).reshape(t_force.size, -1)[:, 0]
    eta = gauges.elevation[:, list(gauges.names).index("WG5")]
    errors, details = cylinder_metrics(t_force, fx, gauges.t, eta, analysis_start(scene),
                                       CHEN_WAVE["period"])
    details.update(until=scene.until, width=scene.flume.width, settings=dict(settings or {}),
                   notes=notes, analysis_notes=result.get("notes", []))
    return make_record(case.name, res, dp, sim, clock.wall(), clock.cpu(), status, message,
                       errors, details)


def plot_cylinder(runs: Sequence[Mapping[str, Any]], path: Path) -> None:
    """The pile's inline force of each run, on the record's clock, over the record."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 3.8))
    tf, ff = chen_reference("force")
    ax.plot(tf, ff, "o", ms=2.5, mfc="none", color="k", label="Chen et al. (2014)")
    for run in sorted(runs, key=lambda r: r["resolution"]):
        d = run.get("details", {})
        if d.get("series_t"):
            ax.plot(d["series_t"], d["series_fx"], lw=0.9, label=f"H/dp = {run['resolution']:g}")
    ax.set_xlabel("t [s] (the record's clock; a run's set on its phase at the gauge)")
    ax.set_ylabel("inline force Fx [N]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


CYLINDER_CASE = Case(
    "cylinder3d", "Chen et al. (2014): inline force of a regular wave on a vertical cylinder (3D)",
    "Chen et al. (2014) records of the inline force and of the elevation at x = 5 m (REEF3D's "
    "tutorial copy)",
    "wave height / dp", CHEN_WAVE["height"], (1.2, 1.4, 1.7), (1.2,), "force_amplitude", 0.10,
    "inline force amplitude within 10 % of the record's", run_cylinder,
    "The built-in cylinder3d (`watersim/validation/cylinder.py`): H = 0.07 m, T = 1.22 s, d = "
    "0.505 m, a 0.25 m pile 4 m from the piston (at the tutorial's x = 7.5 m), half the "
    "tutorial's 3 m wide tank by symmetry (the free-slip side wall y = 0 a plane of symmetry "
    "through the pile's axis, `symmetry_y_min`, the force doubled), the low-dissipation "
    "numerics. `force_amplitude`: half the mean zero-up-crossing height of Fx over six periods "
    "from two periods after the front reaches the pile (three with --quick), against the "
    "record's; `height_wg5`: the mean height at the gauge (x = 5 m) against the record's, the "
    "wave the pile meets; `phase`: the force's first-harmonic phase relative to the gauge's "
    "against the record's, in periods; `force_rms`: the RMS difference of Fx from the record "
    "with the run's clock set on the gauge's phase, over the record's first-harmonic amplitude "
    "(30.5 N).",
    report_details=("force_amplitude", "force_amplitude_recorded", "height_wg5",
                    "phase_error_deg"),
    depth=CHEN_WAVE["depth"], figure=plot_cylinder, scene=cylinder_scene,
)
"""The ``watersim validate`` entry of cylinder3d."""
