"""What the absorber sees of the paddle's own wave: eta_M - eta_T at its probe before the far
wall's reflection comes back, in the absorption2d flume (python/watersim/validation/absorption.py).

The core keeps the correction ``X_c``, the lagged difference ``e`` and its mean ``m``
(``dX_c/dt = -G (e - m) - X_c / tau``, crates/sph-core/src/absorption.rs) in the checkpoint's
``paddle_correction``; ``e - m`` is analysed. With ``--open-loop`` the gain is made negligible
and the lag removed: the paddle then runs its law alone and e is eta_M - eta_T, the target's own
mismatch; otherwise the run is the absorbing one. ``--at-face`` gives the core the target at the
face and the plain gain, without the lag (:meth:`watersim.flume.paddles._Paddle.absorber`
moves the target to the probe and adds the lag). The error's first harmonic over the whole
periods between the ramp's end and the reflection's return, relative to the target's, is
printed (a right target gives ~0).

    nice -n 10 env PYTHONPATH=python RAYON_NUM_THREADS=1 \
        python3 scripts/absorption_probe_error.py --paddle piston --resolution 1 [--open-loop]
"""

from __future__ import annotations

import argparse
import cmath
import math

import numpy as np

import watersim
from watersim import wave_theory as wt
from watersim.flume import Flap, Piston
from watersim.validation.absorption import ABSORPTION_WAVE, absorption_period, absorption_scene
from watersim.validation.cases import CASES


def first_harmonic(t: np.ndarray, y: np.ndarray, omega: float) -> complex:
    """Least-squares ``c`` with ``y ~ Re(c e^(i omega t)) + mean``."""
    basis = np.column_stack([np.cos(omega * t), -np.sin(omega * t), np.ones_like(t)])
    coef, *_ = np.linalg.lstsq(basis, y, rcond=None)
    return complex(coef[0], coef[1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--paddle", choices=("piston", "flap"), default="piston")
    parser.add_argument("--resolution", type=float, default=1.0, help="H/dp")
    parser.add_argument("--open-loop", action="store_true", help="negligible gain")
    parser.add_argument("--at-face", action="store_true",
                        help="the target at the face, the plain gain, no lag")
    args = parser.parse_args()
    dp = CASES["absorption2d"].dp(args.resolution)
    period = absorption_period()
    paddle = Piston(absorption=True) if args.paddle == "piston" else Flap(absorption=True)
    scene = absorption_scene(paddle, dp, 10.0)
    core = scene.to_scene()
    absorption = core["paddle"]["absorption"]
    if args.at_face:
        absorption.update(target=scene.law.absorption_target, gain=scene.law.absorption_gain,
                          lag_time=0.0)
    if args.open_loop:
        absorption.update(gain=absorption["gain"] * 1e-9, lag_time=0.0)
    sim = watersim.Simulation(core)
    depth = ABSORPTION_WAVE["depth"]
    cg = float(wt.group_velocity(period, depth))
    back = 2.0 * scene.flume.length / cg
    samples: list[tuple[float, float, float]] = []

    def record(s: watersim.Simulation) -> None:
        correction = s.core.checkpoint()["paddle_correction"]
        if correction is None:
            return
        offset, _, since, lagged, mean = correction
        samples.append((since, lagged - mean, offset))

    sim.run(back, callback_every=period / 40.0, callback=record)
    t, error, offset = (np.asarray(v) for v in zip(*samples, strict=True))
    omega = 2.0 * math.pi / period
    start = scene.law.ramp_duration + 0.5 * period
    end = start + period * math.floor((back - 0.3 * period - start) / period)
    sel = (t >= start) & (t < end)
    target = np.zeros_like(t)
    for a, w, phase in absorption["target"]["components"]:
        target += a * np.sin(w * t + phase)
    e1, t1 = first_harmonic(t[sel], error[sel], omega), first_harmonic(t[sel], target[sel], omega)
    ratio = e1 / t1
    half_height, half_stroke = 0.5 * ABSORPTION_WAVE["height"], 0.5 * float(scene.law.stroke)
    print(f"{args.paddle} H/dp {args.resolution:g} dp {dp:.5g} probe "
          f"{absorption['probe_offset']:.4g} m {'open' if args.open_loop else 'closed'} loop, "
          f"target at the {'face' if args.at_face else 'probe'}, lag "
          f"{absorption['lag_time']:.4g} s, window {start:.2f}-{end:.2f} s")
    print(f"  error / target (first harmonic): |r| = {abs(ratio):.4f}, arg = "
          f"{math.degrees(cmath.phase(ratio)):.1f} deg (re {ratio.real:+.4f}, im "
          f"{ratio.imag:+.4f}); k x_probe = "
          f"{float(wt.wavenumber(period, depth)) * absorption['probe_offset']:.4f}")
    print(f"  rms error / (H/2) = {np.sqrt(np.mean(error[sel] ** 2)) / half_height:.4f}; "
          f"X_c amplitude / (S/2) = "
          f"{abs(first_harmonic(t[sel], offset[sel], omega)) / half_stroke:.4f}; mean X_c / "
          f"(S/2) = {np.mean(offset[sel]) / half_stroke:+.4f}")

if __name__ == "__main__":
    main()
