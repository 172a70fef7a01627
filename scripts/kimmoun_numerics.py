"""kimmoun2d with chosen settings, keeping the surf-zone particles for the overturn search.

    PYTHONPATH=python python3 scripts/kimmoun_numerics.py OUT TAG [KEY=VALUE ...]

KEY=VALUE are `watersim run kimmoun2d --set` values (dp, viscosity, viscosity.nu, integrator, ...).
Writes OUT/TAG.json (settings, status, CPU and wall time, steps, analysis.json's content) and
OUT/TAG.npz (fluid particles with 9 < x < 15.5 m every 0.02 s from t = 10 s, float32), and
prints the wave height at each gauge, the breaking entry and the overturns found in the kept
snapshots by `watersim.analysis.overturned_surface` (docs/wave-flume.md, "kimmoun2d: shoaling
and breaking on the 1:15 beach").
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

import watersim.analysis as an
import watersim.flume_cases as fc


def main(out: Path, tag: str, items: list[str]) -> None:
    settings = dict(a.split("=", 1) for a in items)
    sim = fc.flume_builder("kimmoun2d", settings).build()
    dp = float(sim.params()["dp"])
    print(tag, settings, sim.n_particles, "particles", flush=True)
    times: list[float] = []
    snaps: list[np.ndarray] = []

    def keep(s: object) -> None:
        if sim.time >= 10.0:
            p = sim.fluid_positions()
            times.append(sim.time)
            snaps.append(p[(p[:, 0] > 9.0) & (p[:, 0] < 15.5)].astype(np.float32))

    wall, cpu = time.time(), time.process_time()
    try:
        sim.run(callback_every=0.02, callback=keep)
        status = "ok"
    except Exception as exc:  # an instability is a result here: record it
        status = repr(exc)
    analysis = sim.analyse()
    out.mkdir(parents=True, exist_ok=True)
    record = {"tag": tag, "settings": settings, "status": status, "wall_s": time.time() - wall,
              "cpu_s": time.process_time() - cpu, "steps": sim.steps,
              "n_particles": sim.n_particles, "t": sim.time, "analysis": analysis}
    (out / f"{tag}.json").write_text(json.dumps(record, default=float, indent=1))
    np.savez_compressed(out / f"{tag}.npz", t=np.array(times),
                        n=np.array([len(s) for s in snaps]),
                        xz=np.concatenate(snaps) if snaps else np.zeros((0, 2), np.float32))
    print(tag, status, f"cpu {record['cpu_s']:.0f} s, {sim.steps} steps")
    for g in analysis["gauges"]:
        print(f"  {g['name']:>12}: H {g.get('H_mean')}")
    print("  breaking:", json.dumps(analysis.get("breaking"), default=float))
    found = 0
    for t, p in zip(times, snaps, strict=True):
        o = an.overturned_surface(p.astype(np.float64), dp, x_range=(9.0, 15.5))
        if o is not None:
            found += 1
            print(f"  overturn at t = {t:.2f} s: {o}")
    print(f"  {found} of {len(times)} kept snapshots overturned")


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(Path(sys.argv[1]), sys.argv[2], sys.argv[3:])
