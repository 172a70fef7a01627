"""2D dam break: surge front against Martin & Moyce (1952), n^2 = 2, at an affordable dp."""

from __future__ import annotations

import numpy as np
import pytest

from watersim import DamBreak, front_error, front_position

# The column of the default case (1 m x 2 m in a 4 m tank), at a coarse but affordable dp, with
# the default (standard) numerics: nothing here is tuned to the data.
DP = 0.04
UNTIL = 0.7  # s: past the last Lethe point (tau = 2.96, t = 0.668 s for L1 = 1 m)


@pytest.mark.slow
def test_dambreak_2d_front_follows_martin_moyce() -> None:
    b = DamBreak(dp=DP, until=UNTIL)
    sim = b.build()
    times: list[float] = []
    fronts: list[float] = []

    def sample(s) -> None:  # type: ignore[no-untyped-def]
        times.append(s.time)
        fronts.append(front_position(s.fluid_positions(), DP))

    sim.run(UNTIL, callback_every=0.01, callback=sample)
    assert fronts[0] == pytest.approx(b.width)
    assert np.all(np.isfinite(fronts))
    err = front_error(times, fronts, b.width, b.g, x_max=b.tank_length)
    print(
        f"\ndam break 2D dp={DP}: {sim.n_particles} particles, {sim.steps} steps; "
        f"RMS relative front error {100 * err.rms_rel_error:.1f} % over {err.n_points} points "
        f"(max {100 * err.max_rel_error:.1f} %), mean lead {err.mean_lead_s:+.3f} s"
    )
    assert err.n_points >= 12
    assert err.rms_rel_error < 0.15


def test_dambreak_3d_runs_and_starts_from_the_column() -> None:
    b = DamBreak(dim=3, dp=0.1, tank_width=0.3, until=0.05)
    sim = b.build()
    assert front_position(sim.fluid_positions(), b.dp) == pytest.approx(b.width)
    sim.run(0.05)
    pos = sim.fluid_positions()
    assert np.all(np.isfinite(pos)) and np.all(np.isfinite(sim.densities))
    assert pos[:, 1].min() > 0.0 and pos[:, 1].max() < 0.3  # stays between the side walls
    assert front_position(pos, b.dp) >= b.width
