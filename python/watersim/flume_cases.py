"""Built-in wave-flume cases of ``watersim run``: flume2d, kimmoun2d, stansby2d, bar2d,
solitary2d, seawall2d, flume3d and cylinder3d.

Each case is a function of the ``--set`` values that returns a checked
:class:`~watersim.flume.FlumeScene`. Keys are the numerical parameters of
:class:`~watersim.SceneBuilder` (``dp``, ``until``, ``coefsound``, ``alpha``, ...), plus
``sample_interval``, plus dotted keys for the case's objects: ``wave.height``, ``wave.period``,
``paddle.order``, ``paddle.ramp_periods``, ``flume.length``, ``flume.depth``, ``beach.toe``,
``beach.slope``, ``damping.length``, ... (``watersim run CASE --set bogus=1`` lists them). Gauge
positions that follow from the wave (flume2d, flume3d) are recomputed from the values set.

The defaults are coarse on purpose: each runs in a few minutes on two cores (kimmoun2d about 15,
cylinder3d, a 3D tank 1.5 m wide, about 30 CPU-minutes). They use ``coefsound = 10``
(:data:`watersim.numerics.FLUME_CASE`, which halves the number of steps against the core's 20)
and the other numerics of :mod:`watersim.numerics`. Refine with ``--set dp=...`` (and
``coefsound=20``).

Each case's default dp is a nominal spacing snapped to ``depth / round(depth / dp)``
(:func:`~watersim.flume.lattice_dp`, also after ``--set flume.depth=...``): the core fills the
water with whole particle layers, so only such a dp gives the depth asked for. A dp set with
``--set dp=...`` must divide the depth (and a 3D flume's width) too, or the case is refused with
two dp that do.
"""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from importlib import resources
from typing import Any

import numpy as np

from . import analysis as an
from . import numerics as nm
from . import wave_theory as wt
from .bodies import Cylinder
from .checks import _positive
from .errors import did_you_mean
from .flume import (
    DampingZone,
    ElevationGauge,
    Flume,
    FlumeScene,
    OvertoppingGauge,
    Piston,
    PlaneBeach,
    ProfileBeach,
    RegularWave,
    SolitaryWave,
    VelocityProbe,
    elevation_gauges_between,
    lattice_dp,
)
from .flume.gauges import ForceGauge
from .flume.paddles import PADDLE_TYPES, Paddle
from .overrides import OverrideError, Overrides
from .scenes import SceneBuilder

__all__ = [
    "BEJI_BATTJES_GAUGES",
    "CHEN_CYLINDER",
    "CHEN_OFFSET",
    "FLUME_CASES",
    "HSIAO_LIN_GAUGES",
    "HSIAO_LIN_OFFSET",
    "STANSBY_GAUGES",
    "STANSBY_UNDERTOW_GAUGES",
    "FlumeCase",
    "FlumeCaseError",
    "beji_battjes_harmonics",
    "flume_builder",
    "flume_settable_keys",
]

STANSBY_GAUGES: tuple[float, ...] = (
    1.1, 2.4, 3.4, 3.9, 4.4, 4.9, 5.3, 5.54, 5.6, 5.74, 5.88, 5.96,
    7.2, 7.6, 6.18, 6.2, 6.26, 6.34, 6.42, 6.6, 6.8, 7.1, 7.2, 7.6,
)
"""Gauge x [m] of Stansby & Feng (2005), gauges 1-24, as printed in seed 002's Table 2 (gauges 13
and 14 repeat the positions of 23 and 24, 7.2 and 7.6 m: kept as printed, so those columns come
twice, the second with a ``_2`` suffix)."""

STANSBY_UNDERTOW_GAUGES: tuple[int, ...] = (8, 10, 11, 12, 15, 17, 18, 19, 21, 23)
"""Seed 002 gauges of Table 3 (depth-averaged undertow) that get a velocity vertical in
stansby2d. Table 3 also lists gauges 13 and 14, left out: Table 2 prints them at 7.2 and 7.6 m,
the positions of gauges 23 and 24 and out of order between gauge 12 (5.96 m) and gauge 15
(6.18 m), so the table is probably wrong there and where they stood is not known."""

BEJI_BATTJES_GAUGES: tuple[float, ...] = (2.0, 4.0, 5.2, 10.5, 12.5, 13.5, 14.5, 15.7, 17.3, 19.0,
                                          21.0)
"""Gauge x [m] of the Beji & Battjes (1993) records shipped in ``watersim/data`` (waves2Foam's
a02 ... a21; ``shared/validation/SOURCES.md`` section 9)."""

HSIAO_LIN_GAUGES: dict[str, float] = {
    "WG1": 8.9, "WG3": 10.6, "WG10": 12.644, "WG22": 13.462, "WG28": 13.732, "WG37": 14.005,
    "WG40": 14.12,
}
"""Hsiao & Lin (2010) gauges used by the validation case seawall2d, at x [m] in their frame
(``shared/validation/SOURCES.md`` section 10: Basilisk's seawall.c samples its model at these
less 3 m). WG28, WG37 and WG40 stand on the seawall's front face, its back face and the ground
behind it, dry at rest: they record the inundation depth above the local ground."""

HSIAO_LIN_OFFSET = 5.0
"""Hsiao & Lin's x less the seawall2d flume's x [m]: the paddle at rest stands at their
x = 5 m, 3.9 m (19.5 depths) before WG1, room for Goring's wave to form."""

HSIAO_LIN_BED: tuple[tuple[float, float], ...] = (
    (10.0, 0.0), (13.6, 0.18), (13.9, 0.256), (13.948, 0.256), (14.045, 0.20225),
)
"""The bed of Hsiao & Lin's flume (their Fig. 1 as Basilisk's seawall.c writes it), (x, z) [m]
in their frame above the 0.2 m deep floor: a 1:20 slope from x = 10 m, the seawall's front face
(13.6-13.9 m), its crest 0.056 m above the still water (to 13.948 m) and its back face down to
the 1:20 slope, which goes on behind the wall."""


CHEN_WAVE: dict[str, float] = {"depth": 0.505, "height": 0.07, "period": 1.22}
"""The regular wave of Chen et al. (2014) as REEF3D's tutorial "Non-Breaking Wave Forces" sets
it up (``shared/validation/SOURCES.md`` section 11): still-water depth, height and period."""

CHEN_CYLINDER: dict[str, float] = {"x": 7.5, "diameter": 0.25, "gauge_x": 5.0, "width": 3.0}
"""The tutorial's vertical cylinder (axis at x = 7.5 m on the centre line of a 3 m wide tank),
its elevation gauge (x = 5 m) and the tank's width, in the tutorial's frame [m]."""

CHEN_OFFSET = 3.5
"""The tutorial's x less the cylinder3d flume's x [m]: the paddle at rest stands at the
tutorial's x = 3.5 m, 1.5 m (0.7 L) before the gauge and 4 m (1.8 L) before the cylinder: past
the paddle's evanescent modes (``exp(-pi x / d)``, 1e-4 at the gauge) and as short a crossing as
that allows (the tutorial's 7.5 m cost the wave height that a coarse 3D run loses per
wavelength)."""


BEJI_BATTJES_FILES: dict[float, str] = {
    x: f"beji_battjes1993_a{n:02d}_x{x:.1f}m_waves2foam.csv"
    for n, x in zip((2, 4, 5, 10, 12, 13, 14, 15, 17, 19, 21), BEJI_BATTJES_GAUGES, strict=True)
}


FlumeCaseError = OverrideError
"""A bad ``--set`` key or value for a flume case (the CLI prints it, exit code 2)."""


# ------------------------------------------------------------------------------------------------
# --set handling


class _Settings(Overrides):
    """The ``--set`` values of one flume case: its objects' dotted keys (:meth:`apply`), its
    positive lengths (:meth:`value`) and its numerical parameters (:meth:`numerics`)."""

    def value(self, key: str, default: Any, hint: Any = float) -> Any:
        """A single case parameter ``key`` (default ``default``); a float must be positive."""
        value = super().value(key, default, hint)
        if hint is float and self.was_set(key):
            _positive(key, value)
        return value

    def paddle(self, default: Paddle) -> Paddle:
        """The case's wave-maker: ``default`` with the ``paddle.*`` values applied;
        ``paddle.type`` switches its law (``piston``, ``flap``), keeping the settings the two
        share (order, ramp, absorption, stroke limit)."""
        return self.apply_tagged("paddle", default, PADDLE_TYPES)

    def numerics(self, **defaults: Any) -> dict[str, Any]:
        """The numerical parameters (:class:`~watersim.SceneBuilder` fields and
        ``sample_interval``): the case's ``defaults`` with the values set applied, an option's
        parameters by their dotted keys (``viscosity.alpha``)."""
        # dim is fixed by the flume; the energy monitor does not run with a paddle
        names = [n for n in (*SceneBuilder.field_names(), "sample_interval")
                 if n not in ("dim", "energy_growth_limit", *nm.OPTION_CLASSES)]
        out = self.fields(FlumeScene, names, defaults)
        for name in nm.OPTION_CLASSES:
            self.keys += nm.option_keys(name)
            value = nm.from_settings(name, defaults.get(name), self.items)
            if value is not None:
                out[name] = value
        return out

    def only_numerics(self, case: str) -> None:
        """Refuses any item that is not a numerical key read by :meth:`numerics` (called
        before), ``dp`` and ``until`` included: a validation case fixes them itself.

        Raises:
            FlumeCaseError: naming the first such key, the case and the valid keys.
        """
        valid = sorted(k for k in self.keys if k not in ("dp", "until"))
        unknown = sorted(k for k in self.items if k not in valid)
        if unknown:
            raise FlumeCaseError(f"--set: key {unknown[0]!r} is not a numerical setting of "
                                 f"{case} (dp and until follow from the case); valid keys: "
                                 f"{', '.join(valid)}")


def _quiet_scene(**kwargs: Any) -> FlumeScene:
    """A FlumeScene built without emitting wave-validity warnings (for sizing a case)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return FlumeScene(**kwargs)


def _finish(
    s: _Settings, n_periods: float | None, x_far: float | None, **kwargs: Any
) -> FlumeScene:
    """The case's scene; ``until`` (unless set) = ramp + arrival at ``x_far`` + ``n_periods``."""
    if n_periods is not None and x_far is not None and not s.was_set("until"):
        probe = _quiet_scene(**{**kwargs, "until": 1.0})
        assert probe.period is not None
        until = probe.law.ramp_duration + probe.arrival_time(x_far) + n_periods * probe.period
        kwargs["until"] = round(until, 2)
    return FlumeScene(**kwargs)


# ------------------------------------------------------------------------------------------------
# the cases


def _reflection_triplet(x0: float, wavelength: float) -> list[ElevationGauge]:
    """Three gauges for Mansard & Funke (1980): spacings L/10 and L/4 from ``x0`` (their advice:
    x12 ~ L/10, L/6 < x13 < L/3)."""
    return [ElevationGauge(round(x0 + f * wavelength, 3)) for f in (0.0, 0.1, 0.25)]


def case_flume2d(s: _Settings) -> FlumeScene:
    """Flat 2D flume with a damping zone; regular wave; gauges at 1, 2 and 3 wavelengths.

    d = 0.3 m, T = 1.2 s (L = 1.77 m, kd = 1.06), H = 0.05 m, second-order piston with a
    two-period ramp; flume 4.75 L long with a 1.5 L damping zone; gauges at 1, 2 and 3 L plus a
    Mansard-Funke triplet from 1.5 L for the reflection coefficient. dp = 0.025 m (12 layers,
    H/dp = 2, about 6,000 particles), until = ramp + arrival at 3 L + 4 periods (about 12 s).

    Numerics for a non-breaking wave carried over several wavelengths (docs/wave-flume.md,
    "How far WaterSim carries a wave"): ``alpha = 0.003`` instead of the flume default 0.01,
    whose artificial viscosity (nu = alpha h c0 / 8) alone takes 1.8 % of the height per
    wavelength at dp = 0.01 m and 4.5 % at 0.025 m (Lamb's viscous decay; measured 3-7 %); and the
    Verlet integrator, one force evaluation per step against two for Symplectic, at the same
    measured decay.
    """
    wave = s.apply("wave", RegularWave(height=0.05, period=1.2))
    paddle = s.paddle(Piston(order=2, ramp_periods=2.0))
    depth = s.value("flume.depth", 0.3)
    wl = float(wt.wavelength(wave.period, depth))
    length = s.value("flume.length", round(4.75 * wl, 2))
    damping = s.apply("damping", DampingZone(length=round(1.5 * wl, 2)))
    flume = Flume(length=length, depth=depth, damping=damping)
    gauges = [ElevationGauge(round(n * wl, 3)) for n in (1, 2, 3)]
    gauges += _reflection_triplet(1.5 * wl, wl)
    num = s.numerics(dp=lattice_dp(depth, 0.025), **nm.FLUME_CASE, **nm.WAVE_CARRYING)
    return _finish(s, 4.0, 3.0 * wl, flume=flume, wave=wave, paddle=paddle, gauges=gauges, **num)


def case_kimmoun2d(s: _Settings) -> FlumeScene:
    """Seed 001 (Roselli et al.; Kimmoun & Branger 2007): regular waves plunging on a 1:15 beach.

    Flume 17 m, d = 0.705 m, plane 1:15 beach from x = 4 m (shoreline at 14.575 m), T =
    1.275 s, amplitude a = 5.70 cm observed before the slope, so H = 2a = 0.114 m (second-order
    piston, two-period ramp). Gauges: x = 4.0 m (the toe, seed Fig. 4); 12.095, 13.155 and
    14.155 m (seed Fig. 5: 248, 142 and 42 cm before the shoreline: incipient breaking,
    splash-up, roller); a line every 0.5 m from 8 to 14.5 m for the envelopes and the breaking
    position; a Mansard-Funke triplet from 1.5 m; and the run-up gauge on the slope. The
    elevation gauges over the slope use seed 001's method (the highest particle), those over
    the flat floor the kernel method (the mean level near the paddle). Velocity verticals (12
    points from the bed to the crest) at 240 and 142 cm before the shoreline, where the seed
    gives the crest velocity against sqrt(g D). The six gauges 18 cm apart
    of the experiment are not placed: the seed does not give where they were. dp = 0.705 / 42 =
    0.016786 m (42 layers, H/dp = 6.8, 33,037 particles, 23,247 fluid), until = 20 periods
    (25.5 s): the coarsest spacing at which the wave plunges with a clear lip (docs/wave-flume.md,
    "The lip against resolution": none at H/dp 4.5, marginal at 5.7; at 6.8 it breaks at 12.1 m
    with H 0.134 m against the seed's 12.1 m and 0.14 m, and the overturn search reports
    "plunging"). It costs about 25 minutes of CPU; ``--set dp=0.050357143`` (0.705 / 14) runs
    twenty times faster and breaks without a lip.

    Numerics: water's laminar viscosity (nu = 1e-6 m^2/s) and Verlet, as flume3d. The flume
    default, alpha = 0.01, acts on the fluid-bed pairs too: at dp = 0.05 m its equivalent
    viscosity (alpha h c0 / 8, about 3e-3 m^2/s) is a bottom boundary layer that takes the wave's
    energy over the 10 m of the slope instead of letting it shoal (docs/wave-flume.md,
    "kimmoun2d: shoaling and breaking").
    """
    wave = s.apply("wave", RegularWave(height=0.114, period=1.275))
    paddle = s.paddle(Piston(order=2, ramp_periods=2.0))
    beach = s.apply("beach", PlaneBeach(toe=4.0, slope=1.0 / 15.0))
    depth = s.value("flume.depth", 0.705)
    length = s.value("flume.length", 17.0)
    flume = Flume(length=length, depth=depth, beach=beach)
    wl = float(wt.wavelength(wave.period, depth))
    shore = beach.toe + depth / beach.slope
    gauges = [ElevationGauge(4.0)]
    gauges += [ElevationGauge(round(shore - d, 3)) for d in (2.48, 1.42, 0.42)]
    gauges += [g for g in elevation_gauges_between(8.0, min(14.5, length), 0.5)]
    gauges += _reflection_triplet(1.5, wl)
    # Over the slope, seed 001's free surface: the highest particle at the gauge (it also
    # sees the water over the upper slope, a few particles deep at coarse dp, which the kernel
    # method reads as dry). Over the flat floor the kernel method: once the particles leave
    # their initial lattice, the highest particle in a strip one dp wide sits about dp/3 below
    # the lattice's top row, so a particle gauge zeroed at t = 0 reads the still level that
    # much low (measured: -15 mm at dp 0.05 after 60 s with a 5 mm wave, where the kernel
    # surface reads +1 mm), which the mean level near the paddle cannot afford.
    gauges = [g if g.x <= beach.toe else dataclasses.replace(g, method="particle")
              for g in _unique_positions(gauges)]
    num = s.numerics(dp=lattice_dp(depth, 0.0168), until=round(20 * wave.period, 3),
                     **nm.FLUME_CASE, **nm.WATER, integrator=nm.Verlet())
    # velocity verticals where seed 001 reports the crest velocity (1.20 sqrt(g D) measured,
    # 1.05 in its SPH, 240 cm before the shoreline) and after the splash-up (142 cm)
    for before_shore in (2.40, 1.42):
        x = round(shore - before_shore, 3)
        bed = max(0.0, (x - beach.toe) * beach.slope)  # off the slope with a steep beach
        zs = np.linspace(bed + 0.5 * num["dp"], depth + wave.height, 12)
        gauges.append(VelocityProbe(points=tuple((x, round(float(z), 4)) for z in zs),
                                    name=f"u_x{x:.3f}"))
    return FlumeScene(flume=flume, wave=wave, paddle=paddle, gauges=gauges, runup=True, **num)


def _unique_positions(gauges: list[ElevationGauge]) -> list[ElevationGauge]:
    """Drop gauges at a position already gauged (within 1 mm), keeping the first."""
    out: list[ElevationGauge] = []
    for g in gauges:
        if all(abs(g.x - h.x) > 1e-3 or g.y != h.y for h in out):
            out.append(g)
    return out


def case_stansby2d(s: _Settings) -> FlumeScene:
    """Seed 002 (Makris et al.; Stansby & Feng 2005): spilling/plunging breakers on a 1:20 beach.

    d = 0.34 m, slope 1:20, H = 0.105 m, T = 2.42 s (seed Table 1), a piston following the
    stream-function law (the wave's Ursell number, 48, is beyond Madsen's second order, so
    ``theory = "auto"`` picks it; ``--set wave.theory=stokes2`` gives the second-order law,
    with a WaveValidityWarning), the 24
    gauges of seed Table 2, plus gauges at 0.8 and 1.8 m over the flat floor for the reflection
    coefficient, and the run-up gauge. The elevation gauges take the highest particle (the
    surf-zone gauges stand in water a few particles deep at the default dp, which the kernel
    method reads as dry). Velocity verticals (12 points from dp/2 above the bed to H above the
    still water) at the gauges of seed Table 3 (:data:`STANSBY_UNDERTOW_GAUGES`), for the
    depth-averaged undertow analysis.json gives there. Flume 11 m long (seed Table 1's
    horizontal extent lx).
    The seed does not give where the slope starts: ``beach.toe`` = 2.0 m is an estimate that puts
    depth-limited breaking (Green's-law shoaling, H/d = 0.78, d_b about 0.16 m) at the seed's
    incipient-breaking gauges 8-10 (x = 5.5-5.7 m); set it if you know better.
    dp = 0.34 / 11 = 0.030909 m (11 layers; nominal 0.03 m, H/dp = 3.4, about 5,200 particles,
    1,800 fluid), until = 10 periods (24.2 s).
    """
    wave = s.apply("wave", RegularWave(height=0.105, period=2.42))
    paddle = s.paddle(Piston(order=2, ramp_periods=2.0))
    beach = s.apply("beach", PlaneBeach(toe=2.0, slope=1.0 / 20.0))
    depth = s.value("flume.depth", 0.34)
    length = s.value("flume.length", 11.0)
    flume = Flume(length=length, depth=depth, beach=beach)
    gauges = [ElevationGauge(x, method="particle") for x in STANSBY_GAUGES]
    gauges += [ElevationGauge(0.8, method="particle"), ElevationGauge(1.8, method="particle")]
    num = s.numerics(dp=lattice_dp(depth, 0.03), **nm.FLUME_CASE, until=round(10 * wave.period, 3))
    for n in STANSBY_UNDERTOW_GAUGES:
        x = STANSBY_GAUGES[n - 1]
        bed = max(0.0, (x - beach.toe) * beach.slope)
        if bed < depth:
            zs = np.linspace(bed + 0.5 * num["dp"], depth + wave.height, 12)
            gauges.append(VelocityProbe(points=tuple((x, round(float(z), 4)) for z in zs),
                                        name=f"u_gauge{n}"))
    return FlumeScene(flume=flume, wave=wave, paddle=paddle, gauges=gauges, runup=True, **num)


def beji_battjes_profile() -> ProfileBeach:
    """The Beji & Battjes (1993) bar (SOURCES.md section 9, from Basilisk's bar.c): depth 0.4 m
    for x < 6 m, a 1:20 rise to a 0.1 m deep crest over 6-12 m, crest 12-14 m, 1:10 fall back to
    0.4 m over 14-17 m."""
    return ProfileBeach(x=(6.0, 12.0, 14.0, 17.0), z=(0.0, 0.3, 0.3, 0.0))


def case_bar2d(s: _Settings) -> FlumeScene:
    """Beji & Battjes (1993): regular waves over a submerged trapezoidal bar (non-breaking).

    d = 0.4 m, H = 0.02 m, T = 2.02 s (waves2Foam's set-up of the case), second-order piston,
    the bar of :func:`beji_battjes_profile`, gauges at the eleven measured positions
    (:data:`BEJI_BATTJES_GAUGES`), flume 21.5 m + one wavelength of damping zone.
    analysis.json compares the first three harmonic amplitudes at each gauge with the
    measured records (``beji_battjes``). The default dp = 0.04 m (10 layers) is far too coarse
    for a 2 cm wave (H/dp = 0.5: the wave is numerically damped); it only shows the case runs,
    in about three minutes. H/dp >= 5 (dp = 0.004 m) is what a comparison needs.
    until = ramp + arrival at 21 m + 4 periods (about 27 s: one period for the steady part to
    settle and the three the analysis needs at the last gauge).
    """
    wave = s.apply("wave", RegularWave(height=0.02, period=2.02))
    paddle = s.paddle(Piston(order=2, ramp_periods=2.0))
    depth = s.value("flume.depth", 0.4)
    wl = float(wt.wavelength(wave.period, depth))
    length = s.value("flume.length", round(21.5 + wl, 2))
    damping = s.apply("damping", DampingZone(length=round(wl, 2)))
    flume = Flume(length=length, depth=depth, beach=beji_battjes_profile(), damping=damping)
    gauges = [ElevationGauge(x) for x in BEJI_BATTJES_GAUGES if x <= length]
    num = s.numerics(dp=lattice_dp(depth, 0.04), **nm.FLUME_CASE)
    return _finish(s, 4.0, max(g.x for g in gauges), flume=flume, wave=wave, paddle=paddle,
                   gauges=gauges, runup=False, **num)


def case_solitary2d(s: _Settings) -> FlumeScene:
    """A solitary wave running up a plane 1:19.85 beach (Synolakis 1987's slope).

    d = 0.3 m, H/d = 0.3 (H = 0.09 m: a breaking wave, as the NTHMP laboratory benchmark's case
    H/d = 0.3), Goring piston motion; beach toe 4 m from the paddle (shoreline at 9.955 m),
    flume 16 m; gauges at 2, 4 (toe), 6, 8 and 9.5 m and the run-up gauge. analysis.json adds
    Synolakis's non-breaking run-up law for reference (it over-predicts a breaking wave's
    run-up). dp = 0.03 m (10 layers, H/dp = 3, about 4,500 particles), until = 14 s.
    """
    wave = s.apply("wave", SolitaryWave(height=0.09))
    paddle = s.paddle(Piston(order=1, ramp_periods=0.0))
    beach = s.apply("beach", PlaneBeach(toe=4.0, slope=1.0 / 19.85))
    depth = s.value("flume.depth", 0.3)
    length = s.value("flume.length", 16.0)
    flume = Flume(length=length, depth=depth, beach=beach)
    gauges = [ElevationGauge(x) for x in (2.0, 4.0, 6.0, 8.0, 9.5) if x <= length]
    num = s.numerics(dp=lattice_dp(depth, 0.03), **nm.FLUME_CASE, until=14.0)
    return FlumeScene(flume=flume, wave=wave, paddle=paddle, gauges=gauges, runup=True, **num)


def case_seawall2d(s: _Settings) -> FlumeScene:
    """Hsiao & Lin (2010): a breaking solitary wave overtopping a seawall (their "type 1" wave).

    d = 0.2 m, H = 0.07 m (H/d = 0.35), Goring piston motion; the bed of
    :data:`HSIAO_LIN_BED` (a 1:20 slope, a seawall whose crest stands 0.056 m above the still
    water, the slope going on behind it), the flume's x their x less
    :data:`HSIAO_LIN_OFFSET` (5 m); flume 11 m (their x = 16 m, where the ground behind the
    wall stands 0.1 m above the still water). Gauges at their seven positions
    (:data:`HSIAO_LIN_GAUGES`, named WG1 ... WG40) and an overtopping gauge (``crest``) at the
    crest's landward edge (their x = 13.948 m). Walls 0.45 m high.
    dp = 0.2 / 9 = 0.02222 m (9 layers, H/dp = 3.15, about 3,400 particles); until = half the
    paddle motion + travel to WG1 + 12 s (the records' span after the crest passes WG1).
    """
    wave = s.apply("wave", SolitaryWave(height=0.07))
    paddle = s.paddle(Piston(order=1, ramp_periods=0.0))
    depth = 0.2
    length = 11.0
    end = length + HSIAO_LIN_OFFSET
    bx, bz = zip(*(*HSIAO_LIN_BED, (end, (end - 10.0) / 20.0)), strict=True)
    beach = ProfileBeach(x=tuple(round(x - HSIAO_LIN_OFFSET, 6) for x in bx), z=bz)
    flume = Flume(length=length, depth=depth, beach=beach, height=0.45)
    gauges: list[Any] = [ElevationGauge(round(x - HSIAO_LIN_OFFSET, 6), name=name)
                         for name, x in HSIAO_LIN_GAUGES.items()]
    gauges.append(OvertoppingGauge(round(13.948 - HSIAO_LIN_OFFSET, 6), name="crest"))
    num = s.numerics(dp=lattice_dp(depth, 0.0233), **nm.FLUME_CASE)
    if not s.was_set("until"):
        probe = _quiet_scene(flume=flume, wave=wave, paddle=paddle, gauges=gauges, **num,
                             until=1.0)
        assert probe.law.duration is not None
        c = float(wt.solitary_celerity(wave.height, depth, probe.g))
        x_wg1 = HSIAO_LIN_GAUGES["WG1"] - HSIAO_LIN_OFFSET
        num["until"] = round(wave.delay + 0.5 * probe.law.duration + x_wg1 / c + 12.0, 2)
    return FlumeScene(flume=flume, wave=wave, paddle=paddle, gauges=gauges, **num)


def case_flume3d(s: _Settings) -> FlumeScene:
    """A narrow, coarse 3D flume with a piston: the wave-maker in 3D.

    d = 0.2 m, width 0.2 m (nine particles across), T = 1.0 s (L = 1.21 m), H = 0.05 m,
    second-order piston with a one-period ramp; flume 1.8 L long with a 0.55 L damping zone,
    walls 0.27 m high; gauges at 0.5 L on the centre line and at 1 L at y = 1/4, 1/2 and 3/4 of
    the width (the wave should stay long-crested), kernel method (its sum counts the walls'
    share of the kernel, so it reads right next to the side walls). Adami's walls (the flume
    default): with DBC walls the water next to a side wall could not rise above the still
    water (25 % of the wave height there, docs/wave-flume.md, "Walls that remember").
    Laminar viscosity with water's nu = 1e-6 m^2/s instead of the flumes' artificial
    viscosity: at this h, alpha = 0.01 acts like nu ~ alpha h c0 / 10 ~ 9e-4 m^2/s, and the
    boundary layers of the side walls and floor of a channel this narrow then damp the wave
    (Hunt 1952: about 30 % per wavelength, against 1 % with water's viscosity). dp = 0.2 / 9
    = 0.022222 m (9 layers deep and 9 columns across; nominal 0.022 m, H/dp = 2.25; 34,543
    particles, 7,938 of them fluid), until = ramp + arrival at L + 5 periods (7.31 s: three
    waves analysed at 1 L). analysis.json's ``across_width`` gives the spread across the width
    of the zero-crossing heights and of the first-harmonic heights ``2 a1``
    (:func:`across_width`). Measured (2026-11-30, docs/wave-flume.md): at 1 L the
    zero-crossing heights are 7.8 % and 8.2 % below the target at the quarter widths and on
    the centre line, spread 0.4 % of H (first harmonic: -10.2 %, -9.9 %, spread 0.3 %).
    """
    wave = s.apply("wave", RegularWave(height=0.05, period=1.0))
    paddle = s.paddle(Piston(order=2, ramp_periods=1.0))
    depth = s.value("flume.depth", 0.2)
    width = s.value("flume.width", 0.2)
    height = s.value("flume.height", 0.27)
    wl = float(wt.wavelength(wave.period, depth))
    length = s.value("flume.length", round(1.8 * wl, 2))
    damping = s.apply("damping", DampingZone(length=round(0.55 * wl, 2)))
    flume = Flume(length=length, depth=depth, width=width, height=height, damping=damping)
    y_mid = round(0.5 * width, 4)
    gauges = [ElevationGauge(round(0.5 * wl, 3), y=y_mid)]
    gauges += [ElevationGauge(round(wl, 3), y=round(f * width, 4)) for f in (0.25, 0.5, 0.75)]
    num = s.numerics(dp=lattice_dp(depth, 0.022, width), **nm.FLUME_CASE, **nm.WATER)
    return _finish(s, 5.0, wl, flume=flume, wave=wave, paddle=paddle, gauges=gauges, **num)


def case_cylinder3d(s: _Settings) -> FlumeScene:
    """Chen et al. (2014): the inline force of a regular wave on a vertical cylinder (3D), as
    REEF3D's tutorial sets it up (:data:`CHEN_WAVE`, :data:`CHEN_CYLINDER`), with the flume's x
    the tutorial's less :data:`CHEN_OFFSET` (3.5 m).

    Half the tank by symmetry: the side wall y = 0 is the tutorial's centre line, a plane of
    symmetry (``symmetry_y_min``) through the pile's axis (the pile, named ``half_pile``,
    crosses it and owns the wall's particles inside it, which stand for its mirror half; its
    force gauge reads half the pile's force), the other wall at the tutorial's 1.5 m (rounded
    to whole dp).
    Flume 7.3 m long (the cylinder's axis at 4 m) with a 2.4 m (1.1 L) damping zone at the far
    end; walls 0.8 m high and the cylinder as tall; second-order piston with a two-period ramp
    and active absorption (the cylinder scatters part of each wave back to the paddle).
    Gauges: ``WG5`` at the tutorial's x = 5 m, 0.15 m off the centre line. Numerics
    :data:`watersim.numerics.LOW_DISSIPATION` (a non-breaking wave carried over two
    wavelengths; its free-slip walls make the wall y = 0 a plane of symmetry).
    dp = 0.505 / 10 = 0.0505 m (H/dp 1.39, D/dp 4.95); until = ramp + arrival at the cylinder
    + 8 periods.
    """
    wave = s.apply("wave", RegularWave(height=CHEN_WAVE["height"], period=CHEN_WAVE["period"]))
    paddle = s.paddle(Piston(order=2, ramp_periods=2.0, absorption=True))
    depth = CHEN_WAVE["depth"]
    num = s.numerics(dp=lattice_dp(depth, 0.0505), **nm.FLUME_CASE, **nm.LOW_DISSIPATION)
    dp = float(num["dp"])
    # the half width to whole dp (0.505 m has no divisor that also divides 1.5 m)
    width = round(round(0.5 * CHEN_CYLINDER["width"] / dp) * dp, 9)
    flume = Flume(length=7.3, depth=depth, width=width, height=0.8,
                  damping=s.apply("damping", DampingZone(length=2.4)))
    x_cylinder = CHEN_CYLINDER["x"] - CHEN_OFFSET
    pile = Cylinder((x_cylinder, 0.0, 0.0), (x_cylinder, 0.0, 0.8), 0.5 * CHEN_CYLINDER["diameter"],
                    name="half_pile")
    gauges: list[Any] = [
        ElevationGauge(CHEN_CYLINDER["gauge_x"] - CHEN_OFFSET, y=0.15, name="WG5"),
        ForceGauge("half_pile", point=(x_cylinder, 0.0, 0.0)),
    ]
    return _finish(s, 8.0, x_cylinder, flume=flume, wave=wave, paddle=paddle, gauges=gauges,
                   bodies=[pile], symmetry_y_min=True, **num)


@dataclass(frozen=True)
class FlumeCase:
    """A built-in flume case: its one-line description and the function building it."""

    description: str
    make: Callable[[_Settings], FlumeScene]


FLUME_CASES: dict[str, FlumeCase] = {
    "flume2d": FlumeCase("flat 2D flume, damping zone, regular wave, gauges at 1-3 L",
                         case_flume2d),
    "kimmoun2d": FlumeCase("seed 001: regular waves plunging on a 1:15 beach", case_kimmoun2d),
    "stansby2d": FlumeCase("seed 002: breakers on a 1:20 beach, gauges of Table 2",
                           case_stansby2d),
    "bar2d": FlumeCase("Beji & Battjes (1993) submerged bar", case_bar2d),
    "solitary2d": FlumeCase("solitary wave running up a 1:19.85 beach", case_solitary2d),
    "seawall2d": FlumeCase("Hsiao & Lin (2010): breaking solitary wave over a seawall",
                           case_seawall2d),
    "flume3d": FlumeCase("narrow coarse 3D flume with a piston", case_flume3d),
    "cylinder3d": FlumeCase("Chen et al. (2014): regular wave force on a vertical cylinder",
                            case_cylinder3d),
}
"""The built-in flume cases of ``watersim run``."""


def flume_settable_keys(case: str) -> list[str]:
    """The ``--set`` keys of a flume case, sorted."""
    s = _Settings({})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        FLUME_CASES[case].make(s)
    return sorted(set(s.keys))


def flume_builder(case: str, items: Mapping[str, str]) -> FlumeScene:
    """The case's scene with the ``--set`` values ``items`` (key -> text) applied.

    Raises:
        FlumeCaseError: an unknown key or a value of the wrong type.
        SceneError: a value the builders refuse (the message names the field).
    """
    valid = flume_settable_keys(case)
    for key in items:
        prefix, _, last = key.rpartition(".")
        if key not in valid and last == "type" and any(k.startswith(f"{prefix}.") for k in valid):
            raise FlumeCaseError(
                f"--set: key {key!r}: the {prefix} of {case} is of a fixed type; to choose "
                f"another, write the case as a scene file (watersim show-scene {case} > "
                f"{case}.toml) and set its [{prefix}] type there"
            )
        if key not in valid:
            raise FlumeCaseError(
                f"--set: key {key!r} is unknown for {case}{did_you_mean(key, valid)}; valid "
                f"keys: {', '.join(valid)}"
            )
    s = _Settings(items)
    return FLUME_CASES[case].make(s)


# ------------------------------------------------------------------------------------------------
# case-specific analysis


def _load_csv(name: str) -> tuple[np.ndarray, np.ndarray]:
    text = resources.files("watersim.data").joinpath(name).read_text("utf-8")
    rows = [line.split(",") for line in text.splitlines()[1:] if line.strip()]
    data = np.array([[float(a), float(b)] for a, b in rows], dtype=np.float64)
    return data[:, 0], data[:, 1]


def beji_battjes_harmonics(period: float = 2.02, n_harmonics: int = 3) -> dict[float, list[float]]:
    """First harmonic amplitudes [m] of the Beji & Battjes (1993) records, by gauge x [m].

    Each record (regularly sampled, about 42 s) is analysed over all its whole periods with
    :func:`watersim.analysis.harmonic_analysis`.
    """
    out: dict[float, list[float]] = {}
    for x, name in BEJI_BATTJES_FILES.items():
        t, eta = _load_csv(name)
        dt = (t[-1] - t[0]) / (t.size - 1)
        grid = t[0] + dt * np.arange(t.size)
        harm = an.harmonic_analysis(eta, grid, period, n_harmonics)
        out[x] = [float(a) for a in harm.amplitudes]
    return out


def case_extras(case: str, setup: FlumeScene, analysis: dict[str, Any]) -> dict[str, Any]:
    """Case-specific additions to analysis.json (reference comparisons)."""
    extras: dict[str, Any] = {}
    if case == "bar2d":
        try:
            measured = beji_battjes_harmonics(setup.period or 2.02)
        except (OSError, ValueError) as exc:  # pragma: no cover - data shipped with the package
            return {"beji_battjes": {"error": str(exc)}}
        rows = []
        for g in analysis.get("gauges", []):
            ref = measured.get(round(g["x"], 1))
            if ref is None:
                continue
            sim = g.get("harmonics")
            rows.append({
                "x": g["x"],
                "measured": ref,
                "simulated": sim,
                "ratio": None if sim is None else [
                    (a / b if a is not None and b else None) for a, b in zip(sim, ref, strict=True)
                ],
            })
        extras["beji_battjes"] = {
            "source": "waves2Foam tutorial records of Beji & Battjes (1993), watersim/data",
            "quantity": "amplitudes of the first three harmonics [m]",
            "gauges": rows,
        }
    if case == "solitary2d" and isinstance(setup.wave, SolitaryWave):
        slope = setup.beach_slope or 1.0
        h_over_d = setup.wave.height / setup.flume.depth
        law = float(wt.synolakis_runup(setup.wave.height, setup.flume.depth, slope))
        runup = analysis.get("runup") or {}
        extras["synolakis"] = {
            "H_over_d": h_over_d,
            "runup_over_d_law": law,
            "runup_over_d_simulated": (None if runup.get("max") is None
                                       else runup["max"] / setup.flume.depth),
            "note": "Synolakis (1987) law, valid for non-breaking waves (H/d < 0.045 on 1:19.85)",
        }
    if case == "flume3d":
        extras["across_width"] = across_width(setup, analysis)
    return extras


def across_width(setup: FlumeScene, analysis: dict[str, Any]) -> dict[str, Any]:
    """How long-crested a 3D flume's wave is: at each x with gauges across the width, the
    spread (largest minus smallest) of the wave heights, two ways:

    - ``H_spread``: of the zero-crossing mean heights ``H_mean``;
    - ``H1_spread``: of the first-harmonic heights ``H1 = 2 a1`` (``a1`` the first harmonic's
      amplitude over the whole periods of the steady window). For a Stokes second-order wave
      the crest-to-trough height is exactly ``2 a1`` (crest ``a1 + a2``, trough ``-a1 + a2``),
      and the harmonic fit averages over every period, where a zero-crossing height takes each
      wave's single highest and lowest samples: with the particle method at coarse dp those are
      where one stray particle near the gauge line shows.

    Each spread also over the target height (``..._over_H``), with the heights per gauge
    (``H1`` by gauge name).
    """
    target = setup.wave.height if isinstance(setup.wave, RegularWave) else None
    zc: dict[str, list[float]] = {}
    h1: dict[str, list[float]] = {}
    heights: dict[str, float] = {}
    for g in analysis.get("gauges", []):
        x = f"{g['x']:.3f}"
        if g.get("H_mean") is not None:
            zc.setdefault(x, []).append(g["H_mean"])
        harmonics = g.get("harmonics")
        if harmonics and harmonics[0] is not None:
            h1.setdefault(x, []).append(2.0 * harmonics[0])
            heights[g["name"]] = 2.0 * harmonics[0]
    spread = {x: max(h) - min(h) for x, h in zc.items() if len(h) > 1}
    spread1 = {x: max(h) - min(h) for x, h in h1.items() if len(h) > 1}
    return {
        "H_spread": spread,
        "H_spread_over_H": {k: v / target for k, v in spread.items()} if target else None,
        "H1": heights,
        "H1_over_H": {k: v / target for k, v in heights.items()} if target else None,
        "H1_spread": spread1,
        "H1_spread_over_H": {k: v / target for k, v in spread1.items()} if target else None,
    }


def headline(case: str, analysis: dict[str, Any]) -> list[str]:
    """A few lines summarising analysis.json for the terminal."""
    lines = []
    for g in analysis.get("gauges", []):
        if g.get("H_mean") is not None:
            err = g.get("H_rel_error")
            extra = "" if err is None else f" ({100 * err:+.1f} % of target)"
            lines.append(f"  {g['name']}: H = {g['H_mean']:.4f} m, T = {g['T_mean']:.3f} s{extra}")
        elif g.get("eta_max") is not None:
            lines.append(f"  {g['name']}: eta_max = {g['eta_max']:.4f} m at t = {g['t_max']:.2f} s")
    br = analysis.get("breaking") or {}
    if br.get("position") is not None:
        lines.append(f"  breaking: x = {br['position']:.2f} m at t = {br['time']:.2f} s, "
                     f"{br.get('breaker_type')} by its Iribarren number")
    first = (br.get("overturn") or {}).get("first")
    if first is not None:
        lines.append(f"  plunging: the surface overturned first at t = {first['time']:.2f} s, "
                     f"x = {first['x_min']:.2f}-{first['x_max']:.2f} m "
                     f"({br['overturn']['seen']} of {br['overturn']['checks']} samples)")
    pa = br.get("phase_averaged") or {}
    if pa.get("position") is not None:
        lines.append(f"  breaking of the phase-averaged wave ({pa['n_waves']} waves): "
                     f"x = {pa['position']:.2f} m, H = {pa['wave_height']:.4f} m there")
    for v in analysis.get("velocity_verticals") or []:
        if v.get("crest_velocity") is not None:
            lines.append(f"  {v['name']}: crest u = {v['crest_velocity_over_sqrt_gD']:.2f}, "
                         f"trough u = {v['trough_velocity_over_sqrt_gD']:.2f} sqrt(g D)")
    mwl = analysis.get("mean_level_near_paddle") or {}
    if mwl.get("spread") is not None:
        lines.append(f"  mean level at {mwl['gauge']}: spread {mwl['spread']:.4f} m "
                     f"({100 * mwl['spread_over_H']:.1f} % of H) over "
                     f"{len(mwl['block_means'])} blocks of {mwl['block_periods']} periods")
    for f in analysis.get("forces") or []:
        if f.get("Fx_max") is not None:
            unit = "N/m" if analysis.get("dim") == 2 else "N"
            significant = ("" if f.get("Fx_significant") is None
                           else f", significant {f['Fx_significant']:.4g} {unit} over "
                                f"{f['n_waves']} waves")
            lines.append(f"  {f['name']}: Fx from {f['Fx_min']:.4g} to {f['Fx_max']:.4g} "
                         f"{unit}{significant}")
    ru = analysis.get("runup") or {}
    if ru.get("mean") is not None:
        lines.append(f"  run-up: mean {ru['mean']:.4f} m, std {ru['std']:.4f} m over "
                     f"{ru['n_waves']} waves")
    elif ru.get("max") is not None:
        lines.append(f"  run-up: max {ru['max']:.4f} m")
    refl = analysis.get("reflection")
    if refl and refl.get("coefficient") is not None:
        lines.append(f"  reflection coefficient {refl['coefficient']:.3f} ({refl['method']})")
    return lines[:40]


