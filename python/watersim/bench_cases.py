"""DualSPHysics 5.4 reference cases for ``watersim bench`` and for the side-by-side comparison
``watersim bench --against`` (:mod:`watersim.bench_against`), which runs DualSPHysics on the case
XML named in ``xml`` and WaterSim on the matching case here.

Each case reproduces a DualSPHysics example's geometry and numerical settings, so that the
microseconds per particle-step compare like with like: same particle count (one layer of
boundary particles, as DualSPHysics' ``drawbox`` makes), same kernel and ``coefh``, viscosity,
density diffusion, boundary condition (DBC), time integrator, CFL and ``coefsound``, and
DualSPHysics' precision: its CPU solver forms every pair term in f32 (positions in double, the
differences rounded to float), so the cases run WaterSim's f32 pair terms
(``force_precision = "f32"``: offsets formed in f32 from positions split for it, within the
f32 rounding of a few cells' width, sums over lanes in f64, the state in f64).
``watersim bench --set force_precision=f64`` times WaterSim's default instead.

=====================  =========================================================================
``dsph-dambreak3d``    ``CaseDambreak``: tank 1.6 x 0.67 x 0.4 m, water 0.4 x 0.67 x 0.3 m at the
                       origin, column 0.12 x 0.12 x 0.45 m at (0.9, 0.24, 0); dp 0.0085 m;
                       171,496 particles (128,310 fluid); cubic spline, coefh 1.0, with
                       Monaghan's (2000) tensile correction, which DualSPHysics applies to
                       every cubic-spline pair; artificial alpha 0.1; Fourtakas delta 0.1;
                       Verlet (Euler every 40); CFL 0.2; coefsound 20.
``dsph-dambreak2d``    ``CaseDambreakVal2D``: column 1 x 2 m in a 4 m tank, dp 0.01 m, 21,001
                       particles (20,000 fluid); Wendland, coefh 1.0; alpha 0.02; Fourtakas delta
                       0.1; Verlet; CFL 0.2; coefsound 20.
``dsph-piston2d``      ``WallRegAwas2``: piston, regular waves H 0.1 m, T 1.3 s, flat tank 3 m
                       long, 0.258 m of water (43 rows of dp 0.006 m), 22,492 particles
                       (21,457 fluid); Wendland, coefh 1.2; alpha 0.01; no diffusion;
                       Symplectic; CFL 0.2; coefsound 20.
=====================  =========================================================================

No DualSPHysics timing is written here: a ratio to DualSPHysics is only what ``watersim bench
--against`` measures side by side. The scenes are the core's JSON form; the scene maker takes
dp (``watersim bench --particles N`` picks it so that the count is about N, for the O(N)
scaling check).
"""

from __future__ import annotations

import math
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
        # DualSPHysics corrects every cubic-spline pair (GetKernelCubic_Tensil), not optional
        tensile_correction={"model": "monaghan"},
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


PISTON_FLUID_COLUMNS = 499
"""Fluid columns of DualSPHysics' ``WallRegAwas2`` at dp = 6 mm (GenCase: x = 0.008 to 2.996 m)."""
PISTON_FLUID_ROWS = 43
"""Fluid rows of ``WallRegAwas2`` at dp = 6 mm (GenCase: z = 0.008 to 0.260 m, one dp above its
floor's particles at z = 0.002): 43 x 499 = 21,457 fluid particles."""
PISTON_TANK_HEIGHT = 0.6
"""Height [m] of ``WallRegAwas2``'s walls and paddle (its boxes are 0.6 m high)."""
PISTON_BED_BEHIND = 0.2
"""Length [m] of ``WallRegAwas2``'s floor behind the paddle's face (its box starts at x = -0.2)."""


def piston2d(dp: float) -> dict[str, Any]:
    """DualSPHysics' ``WallRegAwas2``: regular waves (H = 0.1 m, T = 1.3 s, first-order piston
    with a one-period ramp) from a piston in a flat tank closed by a vertical wall, at
    DualSPHysics' dp (6 mm for the reference figures).

    Its GenCase output at dp = 6 mm (run from the XML at commit cedbb95b): 21,457 fluid
    particles in 499 columns and 43 rows, a one-layer floor from 0.2 m behind the paddle to the
    far wall and that wall (635 fixed), a paddle of 4 x 100 particles (400 moving): 22,492.
    Here the same fluid (the columns and rows scale with 6 mm / dp), the floor and far wall as
    one DBC layer, the tank 0.6 m high and 0.2 m longer behind the paddle. What differs: the
    paddle is one layer thick (the core's paddle takes the wall's layers: 100 particles, not
    400) and the tank has a wall behind the paddle (100 particles DualSPHysics has not); the
    wave law is for the 0.258 m of water the lattice holds, DualSPHysics' for 0.266 m. As
    there, wall pairs have no viscous term (its ``ViscoBoundFactor`` 0, ``wall_factor=0``
    here). DualSPHysics' AWAS starts at 2.6 s, WaterSim's absorber with the paddle's start
    (Schaffer & Klopman, on here as it is there): neither matters on the short intervals the
    side-by-side runs."""
    from . import numerics as nm
    from .flume import Flume, Piston, RegularWave

    scale = 0.006 / dp
    depth = round(PISTON_FLUID_ROWS * scale) * dp
    length = round(PISTON_FLUID_COLUMNS * scale) * dp

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a steep wave on purpose: H/d = 0.39
        scene = Flume(length=length, depth=depth, height=PISTON_TANK_HEIGHT, damping=False).scene(
            RegularWave(height=0.1, period=1.3),
            paddle=Piston(order=1, ramp_periods=1.0, absorption=True),  # its AWAS
            dp=dp,
            kernel="wendland",
            coefh=1.2,
            coefsound=20.0,
            cfl=0.2,
            # its ViscoBoundFactor 0: no viscous term on wall pairs
            viscosity=nm.Artificial(alpha=0.01, wall_factor=0.0),
            diffusion=nm.NoDiffusion(),
            integrator=nm.Symplectic(),
            # DualSPHysics' DBC; the flume's own default is Adami's walls
            boundary="dbc",
            boundary_layers=1,
            # DualSPHysics' CPU pair terms are float (module docstring)
            force_precision="f32",
            gauges=[],
            runup=False,
            until=20.0,
        )
    out = scene.to_scene()
    # DualSPHysics' floor runs 0.2 m behind the paddle's face (room for its stroke); whole dp,
    # so that the lattice, which starts at the tank's corner, keeps its columns on x = 0
    behind = math.ceil(PISTON_BED_BEHIND / dp - 1e-9) * dp
    out["tank"]["min"][0] = min(out["tank"]["min"][0], -behind)
    return out


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
