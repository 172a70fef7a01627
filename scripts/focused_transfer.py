"""Why the focused group's crest comes out low (issue 31): the flume's transfer function, measured
spectrum over the linear target's at gauges from the paddle to past the focus.

examples/focused_group.py's flume (d = 0.3 m, JONSWAP Tp = 1 s, 0.6-2 fp, A = 0.04 m at x_f = 2.5 m,
t_f = 13 s; alpha 0.003, Verlet, c0 = 10 sqrt(g d)) with kernel gauges at 0.5-3.0 m and a particle
gauge at x_f, run to 17 s (the group has passed x_f by then):

    RAYON_NUM_THREADS=1 python3 scripts/focused_transfer.py --dp 0.02 --out runs/focused-dp0.02.npz
    python3 scripts/focused_transfer.py --replot runs/focused-dp0.02.npz

Prints, per gauge, the highest crest against the linear target and the gain |measured / target|
of the record's Fourier transform, weighted by the target's, in four frequency bands; the phase
change of each band from 0.5 m to x_f; and the crest at x_f rebuilt from the target's spectrum
with the measured gain and phase there, with the gain only, with the phase only, and with the
gain measured at 0.5 m (the paddle's transfer and the first half metre) only.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

import watersim as ws
from watersim.numerics import WAVE_CARRYING

DEPTH, TP, AMPLITUDE, FOCUS_X, FOCUS_TIME = 0.3, 1.0, 0.04, 2.5, 13.0
XS = (0.5, 1.0, 1.5, 1.9, 2.1, 2.2, 2.3, 2.4, 2.5, 2.6, 2.7, 3.0)
BANDS = ((0.6, 0.9), (0.9, 1.2), (1.2, 1.5), (1.5, 2.0))
WAVE = ws.FocusedWave(amplitude=AMPLITUDE, tp=TP, focus_x=FOCUS_X, focus_time=FOCUS_TIME,
                      frequency_range=(0.6, 2.0))


def run(dp: float, out: Path) -> None:
    flume = ws.Flume(length=6.5, depth=DEPTH, damping=ws.DampingZone(length=2.0))
    gauges = [ws.ElevationGauge(x) for x in XS]
    gauges.append(ws.ElevationGauge(FOCUS_X, method="particle", name="particle_xf"))
    sim = flume.simulation(WAVE, paddle=ws.Piston(), dp=dp, gauges=gauges, until=17.0,
                           sample_interval=0.01, **dict(WAVE_CARRYING, coefsound=10.0))
    start = time.time()
    sim.run()
    np.savez(out, t=np.asarray(sim.gauges.t), eta=np.asarray(sim.gauges.elevation),
             xs=np.asarray(XS), dp=dp, wall=time.time() - start, steps=sim.steps,
             particles=sim.n_particles)


def report(path: Path) -> None:
    rec = np.load(path)
    t, eta = rec["t"], rec["eta"]
    print(f"dp = {float(rec['dp'])} m: {int(rec['particles'])} particles, {int(rec['steps'])} "
          f"steps, {float(rec['wall']):.0f} s wall")
    motion = WAVE.motion(ws.Piston(), DEPTH, 9.81)
    n = 8192
    freq = np.fft.rfftfreq(n, float(t[1] - t[0]))
    band = (freq > 0.6) & (freq < 2.0)
    gains = {}
    for j, x in enumerate(XS):
        e = np.nan_to_num(eta[:, j])
        target = np.asarray(motion.target_elevation(t, x))
        spectrum = np.fft.rfft(target, n)
        gains[x] = np.fft.rfft(e, n)[band] / spectrum[band]
        weight = np.abs(spectrum[band])
        k, kt = int(np.argmax(e)), int(np.argmax(target))
        parts = []
        for lo, hi in BANDS:
            s = (freq[band] >= lo) & (freq[band] < hi)
            gain = np.sum(np.abs(gains[x][s]) * weight[s]) / np.sum(weight[s])
            parts.append(f"{lo}-{hi} Hz {gain:.3f}")
        print(f"x = {x:.2f} m: crest {e[k]:.4f} m at {t[k]:.2f} s, target {target[kt]:.4f} m at "
              f"{t[kt]:.2f} s ({e[k] / target[kt] - 1:+.1%}); gain " + ", ".join(parts))
    jf = XS.index(FOCUS_X)
    print(f"at x_f: kernel gauge crest {np.nanmax(eta[:, jf]):.4f} m, particle gauge "
          f"{np.nanmax(eta[:, -1]):.4f} m")
    fb = freq[band]
    phase = np.unwrap(np.angle(gains[FOCUS_X])) - np.unwrap(np.angle(gains[0.5]))
    for lo, hi in BANDS:
        s = (fb >= lo) & (fb < hi)
        print(f"phase change 0.5 m -> x_f, {lo}-{hi} Hz: {np.mean(phase[s]):+.3f} rad")
    spectrum = np.fft.rfft(np.asarray(motion.target_elevation(t, FOCUS_X)), n)
    measured = gains[FOCUS_X]
    for name, gain in (("measured gain and phase", measured), ("gain only", np.abs(measured)),
                       ("phase only", np.exp(1j * np.angle(measured))),
                       ("gain at 0.5 m only", np.abs(gains[0.5]))):
        s = spectrum.copy()
        s[band] = s[band] * gain
        rebuilt = np.fft.irfft(s, n)[: t.size]
        k = int(np.argmax(rebuilt))
        print(f"linear crest at x_f rebuilt with the {name}: {rebuilt[k]:.4f} m "
              f"({rebuilt[k] / AMPLITUDE - 1:+.1%}) at {t[k]:.2f} s")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dp", type=float, default=0.02)
    parser.add_argument("--out", type=Path)
    parser.add_argument("--replot", type=Path)
    args = parser.parse_args()
    if args.replot is None:
        if args.out is None:
            parser.error("--out FILE.npz (or --replot FILE.npz)")
        run(args.dp, args.out)
    report(args.replot or args.out)


if __name__ == "__main__":
    main()
