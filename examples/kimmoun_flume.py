"""Seed 001 (Roselli et al.; Kimmoun & Branger 2007): regular waves plunging on a 1:15 beach,
with the figures of seed 001 Figs. 4, 5, 8, 9 and 10. At the default dp (H/dp 6.8, 33,052
particles, 20 periods) the run is about 94,000 steps, some 20-30 CPU-minutes (10-17 minutes on
two cores); the script prints its estimate before it starts and the speed it measures once it
runs, and rewrites gauges.csv as it goes, so a stopped run keeps its records.

    RAYON_NUM_THREADS=2 python3 examples/kimmoun_flume.py --out runs/kimmoun
    python3 examples/kimmoun_flume.py --dp 0.020142857 --periods 40 --out runs/kimmoun-fine
    python3 examples/kimmoun_flume.py --out runs/kimmoun --replot   # figures only
    # the whole experiment (128 waves of spin-up, the last 128 analysed) from the built-in case:
    watersim run kimmoun2d --set until=350 --out runs/kimmoun350 --checkpoint-every wall:10min
    python3 examples/kimmoun_flume.py --from-run runs/kimmoun350 --t-start 186.8 \
        --out runs/kimmoun350/figures

The flume is the built-in case ``kimmoun2d`` written out with the public API, plus velocity
probes at two sections of the breaking zone: 17 m long, d = 0.705 m, a plane 1:15 beach from
x = 4 m (shoreline at 14.575 m), T = 1.275 s, H = 2 a = 0.114 m (a = 5.70 cm observed before
the slope), second-order piston with a two-period ramp. Gauges take seed 001's free surface,
the highest particle.

Writes to ``--out``: gauges.csv, analysis.json, records.npz, summary.json and
fig4_toe.png, fig5_breaking_gauges.png, fig8_envelopes.png, fig9_runup.png,
fig10_phase_averages.png. Seed values drawn as references are quoted from the text of seed
001 (Roselli et al., the project's reference sheet of the experiment; python/watersim/data/
SOURCES.md), never from its plotted curves, which are not available as data.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

import watersim as ws
from watersim import analysis as an
from watersim import wave_theory as wt

sys.path.insert(0, str(Path(__file__).resolve().parent))
from flume_example import (  # noqa: E402 - the shared module sits next to this script
    Records,
    note,
    parse_args,
    phase_averaged,
    plot_envelopes,
    plot_phase_averaged_gauges,
    pyplot,
    run_flume,
    save,
    steady_start,
)

DEPTH = 0.705
"""Still-water depth at the paddle [m] (seed 001)."""
TOE = 4.0
"""Toe of the 1:15 beach, from the paddle [m]."""
SLOPE = 1.0 / 15.0
PERIOD = 1.275
"""Wave period T [s]."""
HEIGHT = 0.114
"""Wave height 2 a [m], a = 5.70 cm observed before the slope (seed 001, section 2)."""
SHORE = TOE + DEPTH / SLOPE
"""Shoreline x [m] (14.575 m)."""
FIG5_DISTANCES = (2.48, 1.42, 0.42)
"""Seed 001 Fig. 5's gauges [m before the shoreline]: incipient breaking, plunging/splash-up,
roller."""
SECTIONS = (SHORE - 4.0, SHORE - 2.48)
"""x [m] of the velocity probes: 4 m before the shoreline (shoaling) and at the incipient
breaking gauge (2.48 m before it)."""
PHASES_DEG = (35.0, 106.0, 176.0, 247.0, 318.0)
"""Phases of seed 001 Figs. 10 and 11 [deg]."""

# values quoted from seed 001's text
SEED_H_BREAKING = 0.14
"""Wave height at breaking H_B = 14.00 cm (seed 001, section 2)."""
SEED_BREAKING_FROM_SHORE = 2.50
"""'The waves broke initially at about x = 250 cm from the shoreline' (seed 001, section 4)."""
SEED_RUNUP_MEAN, SEED_RUNUP_STD = 0.0753, 0.0103
"""R/H = 7.53 % with standard deviation 1.03 % (seed 001 Fig. 9, SPH over 128 waves)."""
SEED_TABLE3 = {"Eq. 1 (Hunt)": 0.1562, "Eq. 3 (Schuttrumpf)": 0.1378, "Eq. 4 (Chue)": 0.0987,
               "Eq. 6 (Hughes)": 0.1234}
"""Run-up R/H of the empirical formulas as printed in seed 001 Table 3."""
SEED_CELERITY = {"crest, SPH": 1.05, "crest, experiment": 1.20, "trough": -0.40}
"""Phase-averaged horizontal velocity / sqrt(g D) quoted in seed 001 section 4 (Fig. 11)."""


def make(dp: float, periods: float) -> tuple[ws.Flume, dict[str, Any]]:
    """The flume and the arguments of :meth:`watersim.Flume.simulation` at spacing ``dp`` [m]
    for ``periods`` wave periods."""
    flume = ws.Flume(length=17.0, depth=DEPTH, beach=ws.PlaneBeach(toe=TOE, slope=SLOPE))
    wl = float(wt.wavelength(PERIOD, DEPTH))
    xs = [4.0, *(round(SHORE - d, 3) for d in FIG5_DISTANCES)]
    xs += [g.x for g in ws.elevation_gauges_between(8.0, 14.5, 0.5)]
    xs += [round(1.5 + f * wl, 3) for f in (0.0, 0.1, 0.25)]  # Mansard & Funke triplet
    unique: list[float] = []
    for x in xs:
        if all(abs(x - u) > 1e-3 for u in unique):
            unique.append(x)
    gauges: list[Any] = [ws.ElevationGauge(x, method="particle") for x in unique]
    for x in SECTIONS:
        # a vertical line of points from just above the bed to above the highest crest
        bed = (x - TOE) * SLOPE
        zs = np.linspace(bed + 0.5 * dp, DEPTH + HEIGHT, 12)
        gauges.append(ws.VelocityProbe(points=tuple((x, float(z)) for z in zs), name=f"u_x{x:.3f}"))
    return flume, {
        "wave": ws.RegularWave(height=HEIGHT, period=PERIOD),
        "paddle": ws.Piston(order=2, ramp_periods=2.0),
        "dp": dp,
        "coefsound": 10.0,
        # as the built-in kimmoun2d: water's viscosity, not alpha = 0.01, whose viscosity
        # against the bed damps the wave on the slope at coarse dp (docs/wave-flume.md)
        **ws.numerics.WATER,
        "integrator": "verlet",
        "gauges": gauges,
        "runup": True,
        "until": round(periods * PERIOD, 3),
    }


# ------------------------------------------------------------------------------------------------
# figures


def fig4_toe(scene: ws.FlumeScene, records: Records, analysis: dict[str, Any],
             path: Path) -> Path:
    """Seed 001 Fig. 4: elevation at the toe (x = 4 m) against time, with the target wave
    (Stokes second order, first-harmonic phase fitted to the steady part)."""
    plt = pyplot()
    j = records.column(4.0)
    t, eta = records.t, records.eta[:, j]
    fig, ax = plt.subplots(figsize=(10, 3.8))
    ax.plot(t, eta, color="tab:blue", lw=1.0, label="WaterSim (highest particle)")
    t0 = steady_start(analysis, records.names[j], math.inf)
    sel = t >= t0
    title = "x = 4.0 m (toe of the beach)"
    if t[-1] - t0 >= PERIOD and np.count_nonzero(sel) >= 8:
        harm = an.harmonic_analysis(eta[sel], t[sel], PERIOD, 1)
        k = float(wt.wavenumber(PERIOD, DEPTH))
        phase = float(harm.phases[0]) + k * 4.0
        target = wt.stokes2_elevation(4.0, t[sel], HEIGHT, PERIOD, DEPTH, phase=phase)
        ax.plot(t[sel], target, "k--", lw=1.0,
                label=f"target: Stokes 2nd order, H = {HEIGHT} m (phase fitted)")
        rms = float(np.sqrt(np.mean((eta[sel] - target) ** 2)))
        ax.axvspan(t0, t[-1], color="0.93", zorder=0, label="steady part (analysed)")
        title += (f": RMS difference from the target {rms * 1000:.1f} mm = "
                  f"{100 * rms / HEIGHT:.0f} % of H")
    else:
        note(ax, f"the record ends before the steady part (t >= {t0:.1f} s): run longer")
    for s in (1, -1):
        ax.axhline(s * HEIGHT / 2, color="tab:red", lw=0.7, ls=":",
                   label="seed 001: observed amplitude a = 5.70 cm" if s > 0 else None)
    ax.set_title(title + "\nseed 001 Fig. 4: SPH within 3 % RMS of the measurement", fontsize=9)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("eta [m]")
    ax.legend(fontsize=7, loc="lower left", ncols=2)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return save(fig, path)


def fig5_gauges(records: Records, analysis: dict[str, Any], path: Path) -> Path:
    """Seed 001 Fig. 5: the three gauges 248, 142 and 42 cm before the shoreline."""
    labels = ("incipient breaking", "plunging, splash-up", "roller")
    gauges = [(round(SHORE - d, 3), f"{100 * d:.0f} cm before the shoreline "
               f"(x = {SHORE - d:.3f} m), seed: {lab}")
              for d, lab in zip(FIG5_DISTANCES, labels, strict=True)]
    notes = {
        gauges[1][0]: "seed 001: SPH vs measurement, max errors crest 4 %, trough 7 % here",
        gauges[2][0]: "seed 001: SPH vs measurement, max errors crest 8 %, trough 12 % here",
    }
    return plot_phase_averaged_gauges(records, analysis, PERIOD, gauges, path,
                                      "seed 001 Fig. 5-like: gauges in the breaking zone", notes)


def _fig8_references(ax1: Any, ax2: Any) -> None:
    xb = SHORE - SEED_BREAKING_FROM_SHORE
    for ax in (ax1, ax2):
        ax.axvline(xb, color="k", lw=1.0, ls="-.",
                   label="seed 001: breaking about 250 cm before the shoreline")
        ax.axvline(SHORE, color="0.4", lw=0.8, ls=":", label="shoreline at rest")
    ax2.plot([xb], [SEED_H_BREAKING], "k*", ms=11, label="seed 001: H_B = 14 cm at breaking")


def fig9_runup(records: Records, analysis: dict[str, Any], path: Path) -> Path:
    """Seed 001 Fig. 9: run-up record and the distribution of R/H per wave, against the seed's
    SPH result and the empirical formulas (seed 001 Eqs. 1, 3, 4, 6)."""
    plt = pyplot()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4), gridspec_kw={"width_ratios": [3, 2]})
    info = analysis.get("runup") or {}
    values = np.asarray(info.get("values") or [], dtype=float)
    if records.runup is not None:
        ax1.plot(records.t, records.runup, color="tab:red", lw=0.8)
    window = info.get("window")
    if window and values.size and records.runup is not None:
        ax1.axvspan(window[0], window[1], color="0.92", zorder=0, label="analysed part")
        per = an.runup_per_wave(records.runup[records.t >= window[0]],
                                records.t[records.t >= window[0]], PERIOD)
        ax1.plot(per.window_starts + 0.5 * PERIOD, per.values, "kv", ms=5,
                 label="highest run-up of each wave")
        ax1.legend(fontsize=7)
    ax1.set_xlabel("t [s]")
    ax1.set_ylabel("run-up above SWL [m]")
    ax1.set_title("run-up on the 1:15 slope", fontsize=9)
    ax1.grid(alpha=0.3)
    # R/H of every wave
    l0 = float(wt.deep_water_wavelength(PERIOD))
    xi = float(wt.iribarren(SLOPE, HEIGHT, l0))
    formulas = {
        "Hunt (Eq. 1)": float(wt.hunt_runup(xi)),
        "Schuttrumpf (Eq. 3)": float(wt.schuttrumpf_runup(xi)),
        "Chue (Eq. 4)": float(wt.chue_runup(HEIGHT, l0, SLOPE)),
        "Hughes (Eq. 6)": float(wt.hughes_runup(
            SLOPE, wt.linear_momentum_flux_parameter(HEIGHT, PERIOD, DEPTH))),
    }
    if values.size:
        rh = 100 * values / HEIGHT
        ax2.hist(rh, bins=max(5, min(20, rh.size)), color="tab:red", alpha=0.7,
                 label=f"WaterSim, {rh.size} waves: {rh.mean():.1f} +- {rh.std():.1f} %")
        ax2.axvline(rh.mean(), color="tab:red", lw=1.5)
    else:
        note(ax2, "no whole wave reached the shoreline: run longer")
    ax2.axvspan(100 * (SEED_RUNUP_MEAN - SEED_RUNUP_STD), 100 * (SEED_RUNUP_MEAN + SEED_RUNUP_STD),
                color="k", alpha=0.15, label="seed 001 SPH: 7.53 +- 1.03 %")
    for (name, value), c in zip(formulas.items(), ("C0", "C2", "C4", "C5"), strict=True):
        ax2.axvline(100 * value, color=c, lw=1.2, ls="--",
                    label=f"{name}: {100 * value:.1f} % (watersim.wave_theory)")
    for name, value in SEED_TABLE3.items():
        ax2.plot([100 * value], [0], "|", color="0.3", ms=14)
        ax2.annotate(name.split()[0] + " " + name.split()[1], (100 * value, 0), fontsize=5,
                     rotation=90, xytext=(2, 8), textcoords="offset points", color="0.3")
    ax2.plot([], [], "|", color="0.3", ms=10, label="seed 001 Table 3 as printed")
    ax2.set_xlabel(f"R / H [%]  (H = {HEIGHT} m, xi = {xi:.2f})")
    ax2.set_ylabel("waves")
    ax2.set_ylim(bottom=-0.5)
    ax2.legend(fontsize=6, loc="upper right")
    fig.tight_layout()
    return save(fig, path)


def _phase_index(phases: np.ndarray, deg: float) -> int:
    return int(np.argmin(np.abs(np.angle(np.exp(1j * (phases - math.radians(deg)))))))


def fig10_phase_averages(scene: ws.FlumeScene, records: Records, analysis: dict[str, Any],
                         path: Path) -> Path:
    """Seed 001 Figs. 10 (phase-averaged free surface along the beach) and 11 (phase-averaged
    horizontal velocity / sqrt(g D)), at the seed's five phases, phase 0 at the paddle start."""
    plt = pyplot()
    n = len(PHASES_DEG)
    fig, axes = plt.subplots(n, 2, figsize=(12, 1.6 + 1.8 * n),
                             gridspec_kw={"width_ratios": [3, 2]}, squeeze=False)
    order = np.argsort(records.x)
    cols = [int(j) for j in order if records.x[j] >= 8.0]
    t0 = max((steady_start(analysis, records.names[j], math.inf) for j in cols), default=math.inf)
    pa = phase_averaged(records, cols, t0, PERIOD) if cols else None
    x_bed, z_bed = scene.bed_profile
    # velocity: each probe phase-averaged over the whole periods after its section's steady start
    prof: dict[str, Any] = {}
    for name, (pt, pts, u, _ks) in records.probes.items():
        x = float(pts[0, 0])
        j = int(np.argmin(np.abs(records.x - x)))
        ts = steady_start(analysis, records.names[j], math.inf)
        sel = pt >= ts
        if np.count_nonzero(sel) >= 4 and pt[-1] - ts >= PERIOD:
            # points above the trough are dry in part of the waves: average over the wet
            # waves only (u * wet / wet), and only where wet in at least half of them
            ux = u[sel, :, 0]
            wet = np.isfinite(ux).astype(float)
            pu = an.phase_average(np.nan_to_num(ux) * wet, pt[sel], PERIOD)
            pw = an.phase_average(wet, pt[sel], PERIOD)
            with np.errstate(invalid="ignore", divide="ignore"):
                mean = np.where(pw.mean >= 0.5, pu.mean / pw.mean, np.nan)
            prof[name] = (x, pts[:, 1] - DEPTH, pu.phases, mean, pu.n_waves)
    for row, deg in enumerate(PHASES_DEG):
        ax, axv = axes[row]
        ax.fill_between(x_bed, np.asarray(z_bed) - DEPTH, -0.3, color="0.8")
        ax.axhline(0.0, color="k", lw=0.5, ls="--")
        if pa is not None:
            i = _phase_index(pa.phases, deg)
            xs = records.x[cols]
            ax.plot(xs, pa.mean[i], "o-", ms=3, color="tab:blue",
                    label=f"phase average over {pa.n_waves} waves")
            ax.fill_between(xs, pa.mean[i] - pa.std[i], pa.mean[i] + pa.std[i], color="tab:blue",
                            alpha=0.2)
        elif row == 0:
            note(ax, "no whole wave after the steady start at every gauge: run longer")
        ax.axvline(SHORE - SEED_BREAKING_FROM_SHORE, color="k", lw=0.8, ls="-.",
                   label="seed 001: breaking ~250 cm before the shoreline")
        ax.set_xlim(8.0, 15.2)
        ax.set_ylim(-0.25, 0.15)
        ax.set_ylabel(f"phi = {deg:.0f} deg\neta [m]", fontsize=8)
        ax.grid(alpha=0.3)
        for x, z, phases, mean, n_w in prof.values():
            i = _phase_index(phases, deg)
            depth_here = float(scene.still_depth(x))
            axv.plot(mean[i] / math.sqrt(wt.G * depth_here), z, "o-", ms=3,
                     label=f"x = {x:.2f} m ({SHORE - x:.2f} m before the shoreline), "
                           f"{n_w} waves (wet ones)")
            ax.axvline(x, color="0.5", lw=0.6)
        for lab, v in SEED_CELERITY.items():
            axv.axvline(v, color="0.4", lw=0.7, ls=":")
            if row == 0:
                axv.text(v, 1.02, lab, transform=axv.get_xaxis_transform(), fontsize=6,
                         rotation=30, ha="left")
        axv.axhline(0.0, color="k", lw=0.5, ls="--")
        axv.set_xlim(-1.0, 1.6)
        axv.set_ylim(-DEPTH + (SECTIONS[0] - TOE) * SLOPE - 0.02, 0.15)
        axv.set_ylabel("z - SWL [m]", fontsize=8)
        axv.grid(alpha=0.3)
        if not prof and row == 0:
            note(axv, "no whole wave at the velocity sections after their steady start")
    axes[0, 0].legend(fontsize=6, loc="lower left")
    if prof:
        axes[-1, 1].legend(fontsize=6, loc="lower right")
    axes[-1, 0].set_xlabel("x [m] from the paddle (gauges: highest particle)")
    axes[-1, 1].set_xlabel("phase-averaged u / sqrt(g D) [-] (dotted: seed 001 sec. 4 values)")
    fig.suptitle("seed 001 Figs. 10-11-like: phase averages (Eq. 18), phase 0 at the paddle "
                 "start (the seed's origin is not given)", fontsize=10)
    fig.tight_layout()
    return save(fig, path)


def figures(scene: ws.FlumeScene, records: Records, analysis: dict[str, Any],
            out: Path) -> list[Path]:
    """All five figures into ``out``; returns their paths."""
    return [
        fig4_toe(scene, records, analysis, out / "fig4_toe.png"),
        fig5_gauges(records, analysis, out / "fig5_breaking_gauges.png"),
        plot_envelopes(scene, analysis, out / "fig8_envelopes.png",
                       "seed 001 Fig. 8-like: water-level envelopes on the 1:15 beach",
                       _fig8_references),
        fig9_runup(records, analysis, out / "fig9_runup.png"),
        fig10_phase_averages(scene, records, analysis, out / "fig10_phase_averages.png"),
    ]


def main(argv: Sequence[str] | None = None) -> list[Path]:
    """Run the example (see the module docstring); returns the figures written."""
    args = parse_args(argv, __doc__.splitlines()[0], dp=0.0168, periods=20.0, out="runs/kimmoun",
                      depth=DEPTH)
    return run_flume(args, make, figures)


if __name__ == "__main__":
    main()
