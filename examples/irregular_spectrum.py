"""Does the irregular-wave paddle reproduce its target spectrum? (project issue 3)

A flat 2D flume with a damping zone at the far end; a piston makes JONSWAP (gamma = 3.3) waves;
two elevation gauges record them for at least 100 peak periods after the ramp and the arrival of
the waves. Hm0 = 4 sqrt(m0) and Tp (peak of the Welch spectrum,
:func:`watersim.analysis.wave_spectrum`) at each gauge are compared with the requested Hs and Tp.

The paddle motion is synthesised through the first-order Biesel transfer function of the piston
(:func:`watersim.wave_theory.irregular_paddle_motion`), so the target spectrum of the propagating
wave anywhere on the flat floor is the requested one (linear theory, no dissipation).

Gauge positions: the near gauge is 1.5 depths from the paddle. The paddle also makes evanescent
(locally standing) modes that decay like exp(-k_n x) with k_1 d between pi/2 and pi; at the peak
frequency here k_1 d = 2.8, so at x = 1.5 d they are down to exp(-4.2) = 1.5 % of their amplitude
at the paddle, and the gauge is still as close to the paddle as possible so that numerical
damping over the distance travelled is small. The far gauge (about 3.5 depths further) shows
how much the coarse SPH resolution damps the waves as they travel.

Run (about 10 minutes on one core at the default dp):

    RAYON_NUM_THREADS=1 PYTHONPATH=python python3 examples/irregular_spectrum.py

writes ``docs/irregular/{results.json,spectrum.png,records.npz}``; ``--replot`` redoes the
analysis and the figure from ``records.npz`` without running. Units: metres, seconds.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

import watersim as ws
from watersim import analysis as an
from watersim import wave_theory as wt

FloatArray = npt.NDArray[np.float64]

DEPTH = 0.2
"""Still-water depth [m]: shallow enough for a short flume, kp d = 1.2 at the peak."""
HS = 0.04
"""Requested significant wave height Hm0 [m] (Hs / d = 0.2, Hmax ~ 1.8 Hs far from breaking)."""
TP = 0.9
"""Requested peak period [s]; Lp = 1.09 m at d = 0.2 m."""
GAMMA = 3.3
SEED = 3
GAUGE_X = (1.5 * DEPTH, 5.0 * DEPTH)
"""Gauge positions [m]: 1.5 d (past the evanescent modes, see the module docstring) and 5 d."""
TOLERANCE = 0.05
"""Acceptance: |Hm0 / Hs - 1| and |Tp / Tp_target - 1| below 5 % (issue 3)."""
SEGMENT_PERIODS = 8.0
"""Welch segment length in peak periods: frequency resolution fp / 8, and a 100 Tp record gives
24 half-overlapping segments. On 20 seeds of the linear target record (105 Tp) this estimator
gives Tp -1.0 % +- 0.7 % and Hm0 -0.3 % +- 3.0 % (the Hm0 scatter is the record's own sampling
variability); 16 Tp segments scatter Tp by +- 1.9 %."""
BANDS = ((0.5, 0.8), (0.8, 1.2), (1.2, 2.0), (2.0, 3.0))
"""Frequency bands [f / fp] of the measured / target variance ratios in the results."""


def flume(dp: float) -> tuple[ws.Flume, dict[str, Any]]:
    """The flume and the keyword arguments of :meth:`watersim.Flume.scene` (without ``until``).

    Flume 3.2 m: the gauges, then a 1.8 m damping zone (1.65 Lp; the zone's damping rate rises
    as s^2, so a longer zone reflects less of the long components but costs particles).
    """
    fl = ws.Flume(length=3.2, depth=DEPTH, damping=ws.DampingZone(length=1.8))
    kwargs: dict[str, Any] = {
        # 128 Tp: the signal does not repeat within the run, and half the components of the
        # default 256 Tp keep the paddle's travel bound (the sum of the amplitudes) modest.
        "wave": ws.IrregularWave(hs=HS, tp=TP, spectrum="jonswap", gamma=GAMMA, seed=SEED,
                                 repeat_period=128.0 * TP),
        "paddle": ws.Piston(ramp_periods=2.0),
        "gauges": [ws.ElevationGauge(x) for x in GAUGE_X],
        "dp": dp,
        "coefsound": 10.0,
    }
    return fl, kwargs


def record_start(scene: ws.FlumeScene) -> float:
    """First time [s] analysed: the ramp, then the group-velocity arrival at the far gauge."""
    return scene.law.ramp_duration + scene.arrival_time(max(GAUGE_X))


def spectrum_check(
    t: npt.ArrayLike, eta: npt.ArrayLike, hs: float, tp: float, gamma: float = GAMMA,
    segment_duration: float | None = None,
) -> dict[str, Any]:
    """Hm0 and Tp of a record against the requested JONSWAP spectrum.

    Args:
        t: uniform times [s]; eta: elevation [m] (mean removed per Welch segment).
        hs, tp, gamma: requested Hm0 [m], peak period [s], peak enhancement.
        segment_duration: Welch segment [s]; default :data:`SEGMENT_PERIODS` ``tp``.

    Returns:
        ``hm0``, ``tp`` (measured), their relative errors ``hm0_error``, ``tp_error``
        (signed, e.g. -0.03 = 3 % low), ``within_tolerance``, the spectrum ``frequencies``
        [Hz], ``density`` [m^2/Hz] and the ``target`` density at the same frequencies.
    """
    seg = SEGMENT_PERIODS * tp if segment_duration is None else segment_duration
    spec = an.wave_spectrum(eta, t, segment_duration=seg)
    target = wt.jonswap_spectrum(spec.frequencies, hs, tp, gamma)
    hm0_err = spec.hm0 / hs - 1.0
    tp_err = spec.tp / tp - 1.0
    return {
        "hm0": spec.hm0,
        "tp": spec.tp,
        "hm0_error": hm0_err,
        "tp_error": tp_err,
        "within_tolerance": bool(abs(hm0_err) < TOLERANCE and abs(tp_err) < TOLERANCE),
        "frequencies": spec.frequencies.tolist(),
        "density": spec.density.tolist(),
        "target": np.asarray(target).tolist(),
    }


def analyse(scene: ws.FlumeScene, t: FloatArray, eta: FloatArray) -> dict[str, Any]:
    """:func:`spectrum_check` of every gauge from :func:`record_start`, and the same check of
    the linear target record the paddle was synthesised for (its own components at the gauge):
    that separates the estimator's scatter from the flume's error."""
    t0 = record_start(scene)
    keep = t >= t0
    motion = wt.irregular_paddle_motion(HS, TP, DEPTH, "jonswap", GAMMA, SEED,
                                        repeat_period=128.0 * TP)
    # energy of the synthesised components (the band 0.5-3 fp only): the best the paddle can do
    m0_synth = float(np.sum(motion.wave_amplitudes**2) / 2.0)
    out: dict[str, Any] = {
        "hs_target": HS, "tp_target": TP, "gamma": GAMMA, "seed": SEED,
        "hm0_synthesised": 4.0 * math.sqrt(m0_synth),
        "t_start": float(t0), "t_end": float(t[-1]),
        "periods_analysed": float((t[-1] - t0) / TP),
        "segment_duration": SEGMENT_PERIODS * TP, "tolerance": TOLERANCE, "gauges": {},
    }
    for j, x in enumerate(GAUGE_X):
        measured = spectrum_check(t[keep], eta[keep, j], HS, TP)
        linear = spectrum_check(t[keep], motion.target_elevation(t[keep], x), HS, TP)
        f = np.asarray(measured["frequencies"]) * TP
        s_meas, s_lin = np.asarray(measured["density"]), np.asarray(linear["density"])
        # where the energy goes missing: measured / linear-target variance in bands of f / fp
        bands = {}
        for lo, hi in BANDS:
            sel = (f >= lo) & (f < hi)
            bands[f"{lo:g}-{hi:g}"] = float(np.sum(s_meas[sel]) / np.sum(s_lin[sel]))
        out["gauges"][f"x{x:.2f}"] = {
            "x": x, "x_over_depth": x / DEPTH, "measured": measured,
            "linear_target_record": {k: linear[k] for k in ("hm0", "tp", "hm0_error",
                                                             "tp_error", "density")},
            "variance_ratio_by_band": bands,
        }
    return out


def figure(result: dict[str, Any], path: Path) -> Path:
    """Measured vs target spectrum at each gauge (PNG)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    gauges = result["gauges"]
    fig, axes = plt.subplots(1, len(gauges), figsize=(5 * len(gauges), 3.8), sharey=True)
    for ax, g in zip(np.atleast_1d(axes), gauges.values(), strict=True):
        m = g["measured"]
        f = np.asarray(m["frequencies"])
        band = f <= 4.0 / TP
        ax.plot(f[band] * TP, np.asarray(m["target"])[band], "k-", label="target JONSWAP")
        ax.plot(f[band] * TP, np.asarray(g["linear_target_record"]["density"])[band], "k--",
                label="linear target record (Welch)")
        ax.plot(f[band] * TP, np.asarray(m["density"])[band], "C0o-", ms=3,
                label="SPH (Welch)")
        ax.set_xlabel("f Tp")
        ax.set_title(f"x = {g['x']:.2f} m ({g['x_over_depth']:.1f} d): Hm0 "
                     f"{100 * m['hm0_error']:+.1f} %, Tp {100 * m['tp_error']:+.1f} %",
                     fontsize=9)
        ax.grid(alpha=0.3)
    np.atleast_1d(axes)[0].set_ylabel("S(f) [m$^2$/Hz]")
    np.atleast_1d(axes)[0].legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def main(argv: Sequence[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--dp", type=float, default=0.02, help="particle spacing [m] (default 0.02)")
    p.add_argument("--periods", type=float, default=105.0,
                   help="peak periods simulated after the ramp and the arrival (default 105)")
    p.add_argument("--out", default="docs/irregular", help="output folder")
    p.add_argument("--replot", action="store_true",
                   help="redo the analysis and figure from OUT/records.npz, no run")
    args = p.parse_args(argv)
    if not (math.isfinite(args.dp) and args.dp > 0):
        p.error(f"--dp: must be a positive number of metres, got {args.dp!r}")
    if not (math.isfinite(args.periods) and args.periods > 0):
        p.error(f"--periods: must be a positive number, got {args.periods!r}")
    out = Path(args.out)
    fl, kwargs = flume(args.dp)
    probe = fl.scene(until=1.0, **kwargs)
    until = round(record_start(probe) + args.periods * TP, 2)
    scene = fl.scene(until=until, **kwargs)
    if args.replot:
        data = np.load(out / "records.npz")
        t, eta = data["t"], data["eta"]
        run = json.loads((out / "run.json").read_text(encoding="utf-8"))
    else:
        out.mkdir(parents=True, exist_ok=True)
        sim = scene.build()
        print(repr(sim), file=sys.stderr)
        start = time.perf_counter()

        def save() -> dict[str, Any]:
            # records and run facts every 10 s of simulated time, so an interrupted run can
            # still be analysed with --replot
            t_, eta_, _r = sim.gauges.uniform()
            np.savez_compressed(out / "records.npz", t=t_, eta=eta_)
            facts = {"dp": args.dp, "until": until, "reached": sim.time,
                     "n_particles": sim.n_particles, "n_fluid": sim.n_fluid,
                     "steps": sim.steps, "wall_s": round(time.perf_counter() - start, 1),
                     "rayon_threads": os.environ.get("RAYON_NUM_THREADS")}
            (out / "run.json").write_text(json.dumps(facts, indent=1), encoding="utf-8")
            return facts

        def checkpoint(_sim: ws.Simulation) -> None:
            save()

        sim.run(until, progress=True, callback_every=10.0, callback=checkpoint)
        run = save()
        t, eta = np.load(out / "records.npz")["t"], np.load(out / "records.npz")["eta"]
    needed = record_start(scene) + 2.0 * SEGMENT_PERIODS * TP
    if t.size < 2 or t[-1] < needed:
        raise SystemExit(f"{out / 'records.npz'}: the record ends at "
                         f"{t[-1] if t.size else 0.0:.1f} s, the analysis needs {needed:.1f} s")
    result = {"run": run, **analyse(scene, t, eta)}
    (out / "results.json").write_text(json.dumps(result, indent=1), encoding="utf-8")
    figure(result, out / "spectrum.png")
    for name, g in result["gauges"].items():
        m = g["measured"]
        print(f"{name}: Hm0 {m['hm0']:.4f} m ({100 * m['hm0_error']:+.1f} %), "
              f"Tp {m['tp']:.3f} s ({100 * m['tp_error']:+.1f} %)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
