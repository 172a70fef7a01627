"""The mean water level of flume2d over a long record: drift, or the flume's seiche?

    PYTHONPATH=python python3 scripts/flume2d_mean_level.py run OUT.npz [KEY=VALUE ...]
    PYTHONPATH=python python3 scripts/flume2d_mean_level.py analyse OUT.npz

`run` runs `watersim run flume2d` with the `--set` values given (e.g. dp=0.02 wave.height=0.1
until=60) and keeps the uniform gauge record (t, eta, gauge names and x, CPU time). `analyse`
prints, for the gauges at 1, 2 and 3 wavelengths, the mean level of each wave period after the
wave's arrival, its least-squares trend over the record (the validation's `mwl_drift`), and the
trend left after fitting the flume's first seiche (period 2 L_flume / sqrt(g d), the long wave
the paddle's ramp starts in the closed flume), with the bound set-down under the wave
(Longuet-Higgins & Stewart 1962: -k H^2 / (8 sinh 2kd)) for comparison (docs/wave-flume.md,
"The mean water level").
"""

from __future__ import annotations

import json
import math
import sys
import time

import numpy as np

import watersim.analysis as an
import watersim.flume_cases as fc
import watersim.wave_theory as wt


def run(out: str, items: list[str]) -> None:
    settings = dict(a.split("=", 1) for a in items)
    setup = fc.flume_builder("flume2d", settings)
    sim = setup.build()
    print(settings, sim.n_particles, "particles", flush=True)
    cpu = time.process_time()
    sim.run(progress=False)
    cpu = time.process_time() - cpu
    t, eta, _ = sim.gauges.uniform()
    meta = {"settings": settings, "cpu_s": cpu, "steps": sim.steps, "n_particles": sim.n_particles,
            "depth": setup.flume.depth, "length": setup.flume.length,
            "damping_length": setup.flume.damping.length if setup.flume.damping else 0.0,
            "period": setup.wave.period, "height": setup.wave.height,
            "ramp": setup.paddle.ramp_periods * setup.wave.period}
    np.savez_compressed(out, t=t, eta=eta, names=np.array(sim.gauges.names),
                        x=np.asarray(sim.gauges.x), meta=json.dumps(meta))
    print(f"cpu {cpu:.0f} s, {sim.steps} steps", flush=True)


def analyse(path: str) -> None:
    d = np.load(path)
    meta = json.loads(str(d["meta"]))
    t, eta, xs = d["t"], d["eta"], d["x"]
    depth, period, height = meta["depth"], meta["period"], meta["height"]
    g = 9.81
    wl = float(wt.wavelength(period, depth))
    k = 2 * math.pi / wl
    set_down = -k * height**2 / (8 * math.sinh(2 * k * depth))
    seiche = 2 * meta["length"] / math.sqrt(g * depth)
    print(f"{meta['settings']}: {meta['n_particles']} particles, cpu {meta['cpu_s']:.0f} s; "
          f"H {height} m, L {wl:.3f} m, bound set-down {1e3 * set_down:.2f} mm, "
          f"first seiche {seiche:.2f} s")
    dt = float(t[1] - t[0])
    per = round(period / dt)
    cg = float(wt.group_velocity(period, depth))
    for j, x in enumerate(xs):
        n_l = x / wl
        if min(abs(n_l - n) for n in (1, 2, 3)) > 0.01:
            continue
        start = meta["ramp"] + x / cg + period
        sel = np.flatnonzero(t >= start)
        n = sel.size // per
        block = eta[sel[: n * per], j].reshape(n, per)
        means = block.mean(axis=1)
        centres = t[sel[: n * per]].reshape(n, per).mean(axis=1)
        trend = np.polyfit(centres, means, 1)[0]
        w = 2 * math.pi / seiche
        basis = np.column_stack([np.ones_like(centres), centres - centres.mean(),
                                 np.cos(w * centres), np.sin(w * centres)])
        coef, *_ = np.linalg.lstsq(basis, means, rcond=None)
        span = centres[-1] - centres[0] + period
        print(f"  x = {x:.3f} m ({n_l:.0f} L), {n} periods from t = {start:.1f} s: mean "
              f"{1e3 * means.mean():+.2f} mm, period means {1e3 * means.min():+.2f} .. "
              f"{1e3 * means.max():+.2f} mm; trend {1e3 * trend * span:+.2f} mm over the record "
              f"({100 * abs(trend) * span / height:.1f} % of H); with the seiche fitted: "
              f"amplitude {1e3 * math.hypot(coef[2], coef[3]):.2f} mm, trend "
              f"{1e3 * coef[1] * span:+.2f} mm ({100 * abs(coef[1]) * span / height:.1f} % of H)")
        waves = an.zero_crossing_waves(eta[sel[: n * per], j], t[sel[: n * per]])
        hm = float(np.mean(waves.heights))
        print(f"    wave height {hm:.4f} m ({100 * (hm / height - 1):+.1f} %),"
              f" {waves.heights.size} waves; period means [mm]:",
              " ".join(f"{1e3 * v:+.1f}" for v in means))


if __name__ == "__main__":
    if sys.argv[1] == "run":
        run(sys.argv[2], sys.argv[3:])
    else:
        analyse(sys.argv[2])
