"""DualSPHysics 5.4 reference cases for ``watersim bench`` and for the side-by-side comparison
``watersim bench --against`` (:mod:`watersim.bench_against`), which runs DualSPHysics on the case
XML named in ``xml`` and WaterSim on the matching case here.

Each case reproduces a DualSPHysics example's geometry and numerical settings, so that the
microseconds per particle-step compare like with like: same particle count (one layer of
boundary particles, as DualSPHysics' ``drawbox`` makes), same kernel and ``coefh``, viscosity,
density diffusion, boundary condition (DBC), time integrator, CFL and ``coefsound``, and
DualSPHysics' precision: its CPU solver forms every pair term in f32 (positions in double, the
differences rounded to float), so the cases run WaterSim's f32 pair terms
(``force_precision = "f32"``: offsets formed in f64 and rounded once, sums over lanes in f64, the
state in f64). ``watersim bench --set force_precision=f64`` times WaterSim's default instead.

=====================  =========================================================================
``dsph-dambreak3d``    ``CaseDambreak``: tank 1.6 x 0.67 x 0.4 m, water 0.4 x 0.67 x 0.3 m at the
                       origin, column 0.12 x 0.12 x 0.45 m at (0.9, 0.24, 0); dp 0.0085 m;
                       171,496 particles (128,310 fluid); cubic spline, coefh 1.0; artificial
                       alpha 0.1; Fourtakas delta 0.1; Verlet (Euler every 40); CFL 0.2;
                       coefsound 20.
``dsph-dambreak2d``    ``CaseDambreakVal2D``: column 1 x 2 m in a 4 m tank, dp 0.01 m, 21,001
                       particles (20,000 fluid); Wendland, coefh 1.0; alpha 0.02; Fourtakas delta
                       0.1; Verlet; CFL 0.2; coefsound 20.
``dsph-piston2d``      2D piston flume: depth 0.266 m (44 layers of dp: 0.264 m of water, as in
                       DualSPHysics), H 0.1 m, T 1.3 s, dp 0.006 m, DualSPHysics 22,492
                       particles; Wendland, coefh 1.2; alpha 0.01; no diffusion; Symplectic.
=====================  =========================================================================

No DualSPHysics timing is written here: a ratio to DualSPHysics is only what ``watersim bench
--against`` measures side by side. The scenes are the core's JSON form; the scene maker takes
dp (``watersim bench --particles N`` picks it so that the count is about N, for the O(N)
scaling check).
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

__all__ = ["DSPH_CASES", "DsphCase", "dsph_scene"]


@dataclass(frozen=True)
class DsphCase:
    """A DualSPHysics reference case: its scene maker and the DualSPHysics case it matches.

    Attributes:
        scene: function of the lattice spacing dp [m] returning the core's scene dict.
        dp: the case's own dp [m].
        particles: the particle count DualSPHysics' GenCase makes of ``xml`` at that dp.
        xml: file name of the DualSPHysics case XML (DualSPHysics' ``examples/``).
        description: one line for reports.
    """

    scene: Callable[[float], dict[str, Any]]
    dp: float
    particles: int
    xml: str
    description: str


def _common(dim: int, dp: float, **kw: Any) -> dict[str, Any]:
    scene: dict[str, Any] = {
        "dim": dim,
        "dp": dp,
        "gravity": 9.81,
        "rho0": 1000.0,
        "gamma": 7.0,
        "cfl": 0.2,
        "coefsound": 20.0,
        # DualSPHysics' drawbox boundaries are one particle layer thick
        "boundary_layers": 1,
        # DualSPHysics' CPU pair terms are float (module docstring)
        "force_precision": "f32",
    }
    scene.update(kw)
    return scene


def dambreak3d(dp: float) -> dict[str, Any]:
    """DualSPHysics ``CaseDambreak`` (3D dam break against a square column)."""
    return _common(
        3,
        dp,
        kernel="cubic_spline",
        coefh=1.0,
        viscosity={"model": "artificial", "alpha": 0.1},
        diffusion={"model": "fourtakas", "delta": 0.1},
        integrator={"scheme": "verlet", "euler_every": 40},
        tank={"min": [0.0, 0.0, 0.0], "max": [1.6, 0.67, 0.4]},
        obstacles=[{"shape": "box", "min": [0.9, 0.24, 0.0], "max": [1.02, 0.36, 0.45]}],
        fluid=[{"min": [0.0, 0.0, 0.0], "max": [0.4, 0.67, 0.3]}],
    )


def dambreak2d(dp: float) -> dict[str, Any]:
    """DualSPHysics ``CaseDambreakVal2D`` (1 m x 2 m column in a 4 m tank)."""
    return _common(
        2,
        dp,
        kernel="wendland",
        coefh=1.0,
        viscosity={"model": "artificial", "alpha": 0.02},
        diffusion={"model": "fourtakas", "delta": 0.1},
        integrator={"scheme": "verlet", "euler_every": 40},
        tank={"min": [0.0, 0.0], "max": [4.0, 3.0]},
        fluid=[{"min": [0.0, 0.0], "max": [1.0, 2.0]}],
    )


PISTON_LENGTH = 1.565
"""Length [m] of the piston flume's flat bed in front of its beach, chosen so that dp = 6 mm
gives DualSPHysics' 22,492 particles (the example's exact bathymetry is not given; particle
count, depth, wave, kernel and numerics are)."""


def piston2d(dp: float) -> dict[str, Any]:
    """2D piston flume with regular waves (nominal d = 0.266 m, H = 0.1 m, T = 1.3 s) on a 1:10
    beach, at DualSPHysics' own dp (6 mm for the reference figures).

    A particle lattice fills whole layers, so DualSPHysics' 0.266 m box holds 44 layers of 6 mm:
    0.264 m of water. The flume here is built with that water depth,
    ``lattice_layers(0.266, dp) * dp`` (the flume refuses a depth that is not whole layers), so
    dp, the particles and the water stay DualSPHysics' and the paddle law is computed for the
    water that is really there."""
    from . import numerics as nm
    from .flume import Flume, Piston, PlaneBeach, RegularWave, lattice_layers

    depth = lattice_layers(0.266, dp) * dp

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a steep wave on purpose: H/d = 0.38
        scene = Flume(
            length=PISTON_LENGTH + 0.266 * 10.0 + 0.3,
            depth=depth,
            beach=PlaneBeach(toe=PISTON_LENGTH, slope=0.1),
        ).scene(
            RegularWave(height=0.1, period=1.3),
            paddle=Piston(order=1, ramp_periods=1.0),
            dp=dp,
            kernel="wendland",
            coefh=1.2,
            coefsound=20.0,
            cfl=0.2,
            viscosity=nm.Artificial(alpha=0.01),
            diffusion=nm.NoDiffusion(),
            integrator=nm.Symplectic(),
            # DualSPHysics' DBC; the flume's own default is Adami's walls
            boundary="dbc",
            boundary_layers=1,
            # DualSPHysics' CPU pair terms are float (module docstring)
            force_precision="f32",
            until=10.0,
        )
    return scene.to_scene()


DSPH_CASES: dict[str, DsphCase] = {
    "dsph-dambreak3d": DsphCase(dambreak3d, 0.0085, 171_496, "CaseDambreak_Def.xml",
                                "3D dam break with obstacle (DualSPHysics CaseDambreak)"),
    "dsph-dambreak2d": DsphCase(dambreak2d, 0.01, 21_001, "CaseDambreakVal2D_Def.xml",
                                "2D dam break (DualSPHysics CaseDambreakVal2D)"),
    "dsph-piston2d": DsphCase(piston2d, 0.006, 22_492, "WallRegAwas2.xml",
                              "2D piston flume, regular waves"),
}
"""The DualSPHysics reference cases of ``watersim bench --case``."""


def dsph_scene(case: str, dp: float | None = None) -> dict[str, Any]:
    """The scene dict of DualSPHysics reference ``case`` at lattice spacing ``dp`` (default: the
    case's own)."""
    spec = DSPH_CASES[case]
    return spec.scene(spec.dp if dp is None else dp)
