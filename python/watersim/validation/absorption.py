"""Validation case absorption2d: active absorption at the paddle. A regular wave (kd 1, H/d 0.1)
runs against the far wall; the share of the incident wave re-reflected by the paddle is measured
by Mansard & Funke's separation near the paddle, with the mean level, the still-water settling
and the residual of a solitary wave in a closed flume; piston and flap, absorption on and off."""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .. import analysis as an
from .. import numerics as nm
from .. import wave_theory as wt
from ..flume import (
    ElevationGauge,
    Flap,
    Flume,
    FlumeScene,
    FlumeSimulation,
    Piston,
    RegularWave,
    SolitaryWave,
    TabulatedMotion,
    lattice_dp,
)
from .running import _Clock, advance, make_record

if TYPE_CHECKING:
    from .case import Case



ABSORPTION_WAVE: dict[str, float] = {"depth": 0.4, "kd": 1.0, "height": 0.04}
"""The regular wave of absorption2d: d = 0.4 m, kd = 1 (T = 1.454 s, L = 2.51 m), H/d = 0.1."""

ABSORPTION_FLUME_WAVELENGTHS = 3.0
"""Length of the absorption2d flume [wavelengths]: a whole number of wavelengths is a natural
mode of the closed tank (an antinode at the paddle and at the wall), so without absorption the
re-reflected wave adds up in phase: the strongest build-up a closed tank gives, and the hardest
test for the absorber."""

ABSORPTION_PERIODS = (60, 20)
"""Simulated periods of absorption2d: (full, quick)."""

ABSORPTION_WINDOW_PERIODS = 5
"""Length of each window of the reflection analysis [periods]; the last two make the late
window."""

SOLITARY_CLOSED_FLUME: dict[str, float] = {"depth": 0.2, "height": 0.04, "length": 2.0}
"""The solitary wave of absorption2d (and of tests/test_absorption.py): H/d = 0.2 sent toward
the wall of a 2 m flume."""


def absorption_period(depth: float = ABSORPTION_WAVE["depth"], kd: float = ABSORPTION_WAVE["kd"],
                      g: float = 9.81) -> float:
    """The period [s] of the wave with ``k d = kd`` at ``depth`` (linear dispersion)."""
    k = kd / depth
    return 2.0 * math.pi / math.sqrt(g * k * math.tanh(kd))


def absorption_scene(paddle: Piston | Flap, dp: float, periods: float, still: bool = False
                     ) -> FlumeScene:
    """The absorption2d flume: :data:`ABSORPTION_WAVE` from ``paddle`` toward the vertical far
    wall :data:`ABSORPTION_FLUME_WAVELENGTHS` wavelengths away (a whole number of dp; no beach,
    no damping zone), three gauges near the paddle at 1.5 d, 1.5 d + L/10 and 1.5 d + L/4
    (Mansard & Funke's spacing), run for ``periods`` periods with flume2d's numerics.
    ``still``: the same flume with the paddle at rest (the still water's own settling)."""
    depth, height = ABSORPTION_WAVE["depth"], ABSORPTION_WAVE["height"]
    period = absorption_period()
    wl = float(wt.wavelength(period, depth))
    flume = Flume(length=dp * round(ABSORPTION_FLUME_WAVELENGTHS * wl / dp), depth=depth,
                  damping=False)
    first = 1.5 * depth  # beyond the paddle's evanescent near field (about one depth)
    gauges = [ElevationGauge(round(first + f * wl, 3), name=f"g{i + 1}")
              for i, f in enumerate((0.0, 0.1, 0.25))]
    wave = (TabulatedMotion(t=(0.0, 1.0), x=(0.0, 0.0)) if still
            else RegularWave(height=height, period=period))
    return flume.scene(wave, paddle=paddle, dp=dp,
                       gauges=gauges, until=round(periods * period, 3),
                       sample_interval=period / 40.0, **{**nm.FLUME_CASE, **nm.WAVE_CARRYING})


def _separated(t: np.ndarray, eta: np.ndarray, x: np.ndarray, depth: float, period: float,
               start: float, end: float) -> dict[str, Any]:
    """Incident and reflected first harmonics over the whole periods of [start, end]
    (Mansard & Funke, three gauges): complex incident amplitude at x = 0 and the mean level
    of the gauges."""
    sel = (t >= start) & (t < end)
    r = an.mansard_funke(eta[sel], t[sel], x, depth, period=period)
    a_i, a_r = float(r.incident_amplitudes[0]), float(r.reflected_amplitudes[0])
    return {"start": start, "end": end, "a_incident": a_i, "a_reflected": a_r,
            "incident": a_i * complex(math.cos(r.incident_phases[0]),
                                      math.sin(r.incident_phases[0])),
            "mean_level": float(np.mean(eta[sel]))}


def absorption_measure(sim: FlumeSimulation, scene: FlumeScene) -> dict[str, Any]:
    """What absorption2d measures in one run, from the three gauges near the paddle.

    ``early``: the incident wave before any reflection reaches the gauges (from the ramp's end
    plus the arrival at the farthest gauge plus one period, to the arrival there of the wall's
    reflection, at the group velocity): the paddle's own wave. ``windows``: consecutive
    windows of :data:`ABSORPTION_WINDOW_PERIODS` periods from the end of ``early`` to the end
    of the run; ``late``: the last two. ``rereflected``: ``|A_I(late) - A_I(early)| /
    |A_I(early)|`` with A_I the complex incident amplitude: whatever the paddle sends into the
    flume on top of its own wave, i.e. the re-reflected wave's share of the incident height,
    whatever its phase. ``incident_growth``: ``|A_I(late)| / |A_I(early)| - 1``.
    ``mean_level_over_H``: the gauges' mean level over ``late`` (zeroed at t = 0) over H.
    """
    t, eta, _ = sim.gauges.uniform()
    x = np.asarray(sim.gauges.x, dtype=float)
    period = scene.period
    assert period is not None
    depth, height = scene.flume.depth, ABSORPTION_WAVE["height"]
    cg = float(wt.group_velocity(period, depth, scene.g))
    start = scene.law.ramp_duration + x[-1] / cg + period
    wall_return = (2.0 * scene.flume.length - x[-1]) / cg
    early = _separated(t, eta, x, depth, period, start,
                       start + period * math.floor((wall_return - start) / period))
    span = ABSORPTION_WINDOW_PERIODS * period
    n = math.floor((float(t[-1]) - early["end"]) / span + 1e-6)
    windows = [_separated(t, eta, x, depth, period, early["end"] + i * span,
                          early["end"] + (i + 1) * span + 1e-9) for i in range(n)]
    late = _separated(t, eta, x, depth, period, windows[-2]["start"], windows[-1]["end"])
    a0 = early["incident"]
    return {
        "early": {k: v for k, v in early.items() if k != "incident"},
        "late": {k: v for k, v in late.items() if k != "incident"},
        "windows": [{k: v for k, v in w.items() if k != "incident"} for w in windows],
        "rereflected": abs(late["incident"] - a0) / abs(a0),
        "rereflected_windows": [abs(w["incident"] - a0) / abs(a0) for w in windows],
        "incident_growth": abs(late["incident"]) / abs(a0) - 1.0,
        "incident_over_target": late["a_incident"] / (0.5 * height),
        "mean_level_over_H": late["mean_level"] / height,
    }


def solitary_closed_flume(absorption: bool, dp: float) -> tuple[FlumeScene, float, float]:
    """:data:`SOLITARY_CLOSED_FLUME`'s solitary wave sent toward the vertical far wall, two
    gauges (0.3 m and mid-flume). Returns ``(scene, back, until)``: the time the reflected wave
    is back at the paddle, and that plus one crossing of the flume."""
    depth, height, length = (SOLITARY_CLOSED_FLUME[k] for k in ("depth", "height", "length"))
    flume = Flume(length=length, depth=depth, damping=False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # sizing only
        probe = flume.scene(SolitaryWave(height=height), paddle=Piston(absorption=absorption),
                            dp=dp)
    c = float(wt.solitary_celerity(height, depth))
    assert probe.law.duration is not None
    back = probe.law.duration + 2.0 * length / c
    until = back + length / c
    scene = flume.scene(SolitaryWave(height=height), paddle=Piston(absorption=absorption), dp=dp,
                        until=round(until, 3), sample_interval=0.02, **nm.FLUME_CASE,
                        gauges=[ElevationGauge(0.3, name="near"),
                                ElevationGauge(0.5 * length, name="middle")])
    return scene, back, until


def solitary_residual(sim: FlumeSimulation, back: float) -> float:
    """The largest |elevation| [m] at the gauges from 0.3 s after the reflected solitary wave
    is back at the paddle: what the paddle left in the tank."""
    late = sim.gauges.t > back + 0.3
    return float(np.nanmax(np.abs(sim.gauges.elevation[late])))


def _plot_absorption(runs: Sequence[Mapping[str, Any]], path: Path) -> None:
    """The finest finished run of absorption2d: the incident amplitude near the paddle (over
    the paddle's own wave) and the mean level (over H) per window, against time in periods,
    for the piston and the flap with absorption on and off."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    done = [r for r in runs if r.get("status") == "ok" and "piston_on" in (r.get("details") or {})]
    if not done:
        return
    run = min(done, key=lambda r: float(r["dp"]))
    details = run["details"]
    period = float(details["period"])
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for i, label in enumerate(("piston_on", "piston_off", "flap_on", "flap_off")):
        measured = details.get(label)
        if measured is None:
            continue
        windows = [measured["early"], *measured["windows"]]
        t = [0.5 * (w["start"] + w["end"]) / period for w in windows]
        style = {"color": f"C{i // 2}", "ls": "-" if label.endswith("on") else "--",
                 "marker": "o", "label": label.replace("_", ", absorption ")}
        a0 = measured["early"]["a_incident"]
        ax1.plot(t, [w["a_incident"] / a0 for w in windows], **style)
        ax2.plot(t, [w["mean_level"] / ABSORPTION_WAVE["height"] for w in windows], **style)
    still = details.get("mean_level_over_H_still")
    if still is not None:
        ax2.axhline(still, color="0.4", lw=1, label="still water, late window")
    ax1.axhspan(0.9, 1.1, color="0.85", label="+-10 % of the paddle's own wave")
    ax2.axhspan(-0.02, 0.02, color="0.85", label="+-2 % of H")
    ax1.set_ylabel("incident amplitude / paddle's own wave [-]")
    ax2.set_ylabel("mean level / H [-]")
    for ax in (ax1, ax2):
        ax.set_xlabel("t / T (window centres)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, framealpha=0.5)
    fig.suptitle(f"absorption2d at H/dp {float(run['resolution']):g} (dp {float(run['dp']):.4g} "
                 "m): three gauges near the paddle", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _run_absorption(case: Case, res: float, quick: bool, progress: bool) -> dict[str, Any]:
    """absorption2d: :func:`absorption_scene` with a piston and a flap, each with absorption on
    and off, for 60 periods (20 quick), measured by :func:`absorption_measure`; and the
    solitary wave of :func:`solitary_closed_flume`, with and without absorption, at the same
    H/dp (its dp snapped to whole layers of its depth)."""
    dp = case.dp(res)
    periods = ABSORPTION_PERIODS[1 if quick else 0]
    clock = _Clock()
    errors: dict[str, float | None] = {}
    details: dict[str, Any] = {"wave": dict(ABSORPTION_WAVE), "period": absorption_period(),
                               "periods": periods}
    status, message = "ok", None
    n_particles = steps = 0
    sim: FlumeSimulation | None = None
    # the still water's own level at the gauges: the particles settle on the floor and the
    # level at the gauges rises by about 0.1 dp whatever the paddle does (0.10 H at H/dp 1,
    # 0.06 H at 1.5, more than the 2 % limit), so the mean level is measured against it
    still = absorption_scene(Piston(absorption=False), dp, periods, still=True)
    sim_still = still.build()
    st, msg = advance(sim_still, float(still.until), 1.0, None, progress,  # type: ignore[arg-type]
                      f"{case.name} {res:g} still water")
    steps += sim_still.steps
    if st != "ok":
        status, message = st, f"still water: {msg}"
    t_still, eta_still, _ = sim_still.gauges.uniform()
    runs = [(kind, on) for kind in ("piston", "flap") for on in (True, False)]
    for kind, on in runs:
        paddle = Piston(absorption=on) if kind == "piston" else Flap(absorption=on)
        label = f"{kind}_{'on' if on else 'off'}"
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            scene = absorption_scene(paddle, dp, periods)
        sim = scene.build()
        st, msg = advance(sim, float(scene.until), 1.0, None, progress,  # type: ignore[arg-type]
                          f"{case.name} {res:g} {label}")
        n_particles = max(n_particles, sim.n_particles)
        steps += sim.steps
        if st != "ok":
            status, message = (st, f"{label}: {msg}") if status == "ok" else (status, message)
            continue
        measured = absorption_measure(sim, scene)
        measured["notes"] = [f"{w.category.__name__}: {w.message}" for w in caught]
        late = measured["late"]
        sel = (t_still >= late["start"]) & (t_still < late["end"])
        still_level = float(np.mean(eta_still[sel])) / ABSORPTION_WAVE["height"]
        measured["mean_level_over_H_still"] = still_level
        measured["mean_level_over_still_H"] = measured["mean_level_over_H"] - still_level
        details[label] = measured
        details["flume_length"] = scene.flume.length
        details["gauges_x"] = [float(v) for v in sim.gauges.x]
        details["mean_level_over_H_still"] = still_level
        for key in ("rereflected", "incident_growth", "mean_level_over_H",
                    "mean_level_over_still_H"):
            details[f"{key}_{label}"] = measured[key]
        if on:
            errors[f"rereflected_{kind}"] = measured["rereflected"]
            errors[f"mean_level_{kind}"] = abs(measured["mean_level_over_still_H"])
    on_errors = [errors.get(f"rereflected_{k}") for k in ("piston", "flap")]
    errors["rereflected"] = (max(on_errors) if None not in on_errors  # type: ignore[type-var]
                             else None)
    sol_dp = lattice_dp(SOLITARY_CLOSED_FLUME["depth"], SOLITARY_CLOSED_FLUME["height"] / res)
    details["solitary_dp"] = sol_dp
    for on in (True, False):
        scene, back, until = solitary_closed_flume(on, sol_dp)
        sol = scene.build()
        st, msg = advance(sol, until, 0.1, None, progress, f"{case.name} {res:g} solitary")
        steps += sol.steps
        if st != "ok":
            status, message = (st, f"solitary: {msg}") if status == "ok" else (status, message)
            continue
        residual = solitary_residual(sol, back) / SOLITARY_CLOSED_FLUME["height"]
        details[f"solitary_residual_{'on' if on else 'off'}"] = residual
        if on:
            errors["solitary_residual"] = residual
    errors = {"rereflected": errors.pop("rereflected"), **errors}
    return make_record(case.name, res, dp, sim, clock.wall(), clock.cpu(), status, message,
                       errors, details, n_sims=len(runs) + 3, particles_total=n_particles,
                       steps_total=steps)
