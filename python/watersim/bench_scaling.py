"""How the cost of a step grows with the particle count (``watersim bench --scaling``).

A scaled case (the same geometry at a finer dp) changes more than N: the walls are a surface
and the fluid a volume, so the walls' share of the particles falls as dp shrinks (one-layer
walls: 42 % of the 3D dam break's particles at 20,000, 12 % at 2,000,000). A wall particle
under the dynamic boundary condition costs a small part of a fluid one (its continuity sum
only), so the time per particle-step counted over all particles rises with N even when the
solver is exactly O(N). This module separates the two: it fits each run's time per step with

    t_step = a * N_fluid + b * N_wall

(least squares on relative errors), whose residuals say whether the cost is linear in each kind
of particle, and reports the spread of the time per particle-step counted over all particles,
per fluid particle and per pair, each against the 25 % the performance issue allows.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["ScalingRun", "fit_scaling", "SPREAD_LIMIT"]

#: Largest relative spread (max / min - 1) of a cost per unit of work across the sizes that
#: still counts as O(N) (the performance issue's "within 25 %").
SPREAD_LIMIT = 0.25


@dataclass(frozen=True)
class ScalingRun:
    """One size of a scaling sweep.

    Attributes:
        n_particles: all particles.
        n_fluid: fluid particles (the rest are walls).
        wall_s: wall time of ``steps`` steps [s].
        steps: timed steps.
        fluid_pairs: fluid-particle pairs within the support (per force evaluation).
        force_evaluations_per_step: force evaluations per step (2 for Symplectic).
    """

    n_particles: int
    n_fluid: int
    wall_s: float
    steps: int
    fluid_pairs: int
    force_evaluations_per_step: int

    @property
    def n_walls(self) -> int:
        return self.n_particles - self.n_fluid

    @property
    def step_s(self) -> float:
        return self.wall_s / self.steps


def _spread(values: Sequence[float]) -> float:
    return max(values) / min(values) - 1.0


def fit_scaling(runs: Sequence[ScalingRun]) -> dict[str, Any]:
    """The spreads of the cost per unit of work over ``runs`` and the fit of the time per step
    to fluid and wall particles (see the module's doc). Needs two runs at least; the fit's
    residuals mean something from three on (two sizes fit any two costs exactly)."""
    if len(runs) < 2:
        raise ValueError(f"runs: a scaling fit needs two sizes at least, got {len(runs)}")
    for i, r in enumerate(runs):
        if not (r.wall_s > 0 and r.steps > 0 and 0 < r.n_fluid <= r.n_particles):
            raise ValueError(f"runs[{i}]: needs wall_s > 0, steps > 0 and 0 < n_fluid <= "
                             f"n_particles, got {r}")
    counted = [1e6 * r.step_s / r.n_particles for r in runs]
    per_fluid = [1e6 * r.step_s / r.n_fluid for r in runs]
    per_pair = ([1e9 * r.step_s / (r.fluid_pairs * r.force_evaluations_per_step) for r in runs]
                if all(r.fluid_pairs > 0 for r in runs) else None)
    # t_i = a Nf_i + b Nw_i, each row divided by t_i: every size weighs the same, and the
    # model's relative residual is the row's product with (a, b) less one
    t = np.array([r.step_s for r in runs])
    design = np.array([[r.n_fluid, r.n_walls] for r in runs], dtype=float) / t[:, None]
    (a, b), *_ = np.linalg.lstsq(design, np.ones(len(runs)), rcond=None)
    residuals = design @ np.array([a, b]) - 1.0
    spreads = {"counted": _spread(counted), "per_fluid_particle": _spread(per_fluid)}
    if per_pair is not None:
        spreads["per_pair"] = _spread(per_pair)
    return {
        "sizes": [r.n_particles for r in runs],
        "wall_share": [r.n_walls / r.n_particles for r in runs],
        "us_per_particle_step": counted,
        "us_per_fluid_particle_step": per_fluid,
        "ns_per_pair": per_pair,
        "spread": spreads,
        "within_limit": {k: v <= SPREAD_LIMIT for k, v in spreads.items()},
        "spread_limit": SPREAD_LIMIT,
        "fit": {
            "us_per_fluid_particle_step": 1e6 * float(a),
            "us_per_wall_particle_step": 1e6 * float(b),
            "relative_residuals": [float(x) for x in residuals],
            "max_abs_relative_residual": float(np.max(np.abs(residuals))),
        },
    }
