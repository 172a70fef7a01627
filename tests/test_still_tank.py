"""Still-water tank: stays still, keeps its level and a hydrostatic pressure (2D and 3D)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from watersim import Tank

CASES = {
    2: Tank(dim=2, length=1.0, depth=0.5, height=0.7, dp=0.05),
    3: Tank(dim=3, length=0.6, width=0.3, depth=0.3, height=0.4, dp=0.05),
}


@pytest.mark.slow
@pytest.mark.parametrize("dim", [2, 3])
def test_still_tank_stays_still_for_two_seconds(dim: int) -> None:
    b = CASES[dim]
    assert b.depth is not None and b.length is not None and b.dp is not None
    sim = b.build()
    sim.run(2.0)
    g, d, dp = b.g, b.depth, b.dp
    h = sim.params()["h"]

    speed = np.linalg.norm(sim.fluid_velocities(), axis=1).max()
    print(
        f"\n{dim}D still tank: max speed {speed:.4f} m/s = "
        f"{speed / math.sqrt(g * d):.4f} sqrt(g d)",
        end="",
    )
    assert speed < 0.02 * math.sqrt(g * d)

    pos = sim.fluid_positions()
    middle = np.abs(pos[:, 0] - 0.5 * b.length) <= 0.25 * b.length
    if dim == 3:
        assert b.width is not None
        middle &= np.abs(pos[:, 1] - 0.5 * b.width) <= 0.25 * b.width
    surface = pos[middle, -1].max() + 0.5 * dp
    print(f"; surface {surface:.4f} m (depth {d} m)", end="")
    assert abs(surface - d) <= dp

    centre = [0.5 * b.length] + ([0.5 * b.width] if dim == 3 else [])
    z = 2.0 * h
    probe = sim.interpolate(np.array([centre + [z]]))
    expected = b.core_value("rho0") * g * (d - z)
    print(f"; p({z:.3f} m) = {probe['pressure'][0]:.1f} Pa vs {expected:.1f} Pa")
    assert probe["kernel_sum"][0] > 0.9
    assert probe["pressure"][0] == pytest.approx(expected, rel=0.05)
