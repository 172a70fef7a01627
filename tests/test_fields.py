"""Vorticity from particles and from a velocity window's grid: exact for linear velocity
fields (the corrected kernel gradient), at the free surface and the edges as in the bulk; the
snapshots' field; the window figure's time-mean vorticity panel."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from watersim import plotting
from watersim.fields import _grad_factor, grid_vorticity, particle_vorticity
from watersim.numerics import KERNELS

DP = 0.02


def _lattice(dim: int, jitter: float = 0.0) -> np.ndarray:
    axes = [np.arange(0.0, 0.3, DP) + DP / 2] * dim
    x = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, dim)
    return x + np.random.default_rng(1).normal(0.0, jitter * DP, x.shape)


finite = st.floats(-3.0, 3.0, allow_nan=False)


@settings(max_examples=20, deadline=None)
@given(a=finite, b=finite, c=finite, d=finite, kernel=st.sampled_from(KERNELS))
def test_a_linear_2d_field_gives_its_vorticity_at_every_particle(
        a: float, b: float, c: float, d: float, kernel: str) -> None:
    x = _lattice(2, jitter=0.15)
    # u = a x + b z, w = c x + d z: omega_y = du/dz - dw/dx = b - c
    v = np.c_[a * x[:, 0] + b * x[:, 1], c * x[:, 0] + d * x[:, 1]]
    omega = particle_vorticity(x, v, np.full(len(x), DP**2), 1.3 * DP, kernel)
    assert np.isfinite(omega).all()
    np.testing.assert_allclose(omega, b - c, atol=1e-9)


@pytest.mark.parametrize("kernel", KERNELS)
@pytest.mark.parametrize("dim", [2, 3])
def test_each_kernel_gradient_is_that_of_a_normalised_kernel(kernel: str, dim: int) -> None:
    """By parts, a kernel with unit integral has ``int dW/dr V(r) dr = -1``, with ``V(r)`` the
    volume of the ball of radius r (pi r^2 in 2D, 4/3 pi r^3 in 3D): the gradient factor
    ``(dW/dr)/r`` of each of the core's kernels, written again in fields.py, must meet it."""
    h = 0.7
    r = np.linspace(0.0, 2.0 * h, 200_001)[1:]
    ball = np.pi * r**2 if dim == 2 else 4.0 / 3.0 * np.pi * r**3
    dw_dr = _grad_factor(kernel, r, h, dim) * r
    assert np.trapezoid(dw_dr * ball, r) == pytest.approx(-1.0, abs=1e-6)


def test_a_rigid_rotation_in_3d_gives_twice_its_angular_velocity() -> None:
    x = _lattice(3, jitter=0.1)
    spin = np.array([0.3, -1.0, 2.0])
    omega = particle_vorticity(x, np.cross(spin, x), np.full(len(x), DP**3), 1.3 * DP)
    wet = np.isfinite(omega).all(axis=1)
    assert wet.mean() > 0.95
    np.testing.assert_allclose(omega[wet], np.broadcast_to(2.0 * spin, omega[wet].shape), atol=1e-9)


def test_a_lone_particle_has_no_vorticity_and_bad_input_is_refused() -> None:
    x = np.r_[_lattice(2), [[5.0, 5.0]]]
    omega = particle_vorticity(x, np.zeros_like(x), np.full(len(x), DP**2), 1.3 * DP)
    assert np.isnan(omega[-1]) and np.isfinite(omega[:-1]).all()
    with pytest.raises(ValueError, match="kernel"):
        particle_vorticity(x, x, np.ones(len(x)), 0.03, "gaussian")
    with pytest.raises(ValueError, match="volumes"):
        particle_vorticity(x, x, np.ones(3), 0.03)


def test_grid_vorticity_of_a_shear_in_2d_and_3d_and_dry_points() -> None:
    z, x = np.linspace(0.0, 0.3, 7), np.linspace(1.0, 2.0, 11)
    zz, xx = np.meshgrid(z, x, indexing="ij")
    velocity = np.stack([2.0 * zz, -0.5 * xx], axis=-1)[None].repeat(3, axis=0)
    omega = grid_vorticity(velocity, (0.05, 0.1))
    assert omega.shape == (3, 7, 11)
    np.testing.assert_allclose(omega, 2.5)
    velocity[:, -1, 4] = np.nan  # a dry point: NaN there and next to it, nowhere else
    omega = grid_vorticity(velocity, (0.05, 0.1))
    assert np.isnan(omega[0, -1, 3:6]).all() and np.isnan(omega[0, -2, 4])
    assert np.isfinite(omega[0, :-2]).all()
    y = np.linspace(0.0, 0.2, 3)
    zz, yy, xx = np.meshgrid(z, y, x, indexing="ij")
    spin = np.array([0.3, -1.0, 2.0])
    v3 = np.cross(spin, np.stack([xx, yy, zz], axis=-1))
    np.testing.assert_allclose(grid_vorticity(v3, (0.05, 0.1, 0.1)),
                               np.broadcast_to(2 * spin, v3.shape))
    with pytest.raises(ValueError, match="2 points"):
        grid_vorticity(velocity[:, :1], (0.05, 0.1))


def test_the_window_figure_draws_the_mean_vorticity(tmp_path: Path) -> None:
    """A window file of a shear flow (omega_y = 2 everywhere): the figure is drawn with its
    vorticity panel."""
    xs, zs = np.linspace(1.0, 1.4, 5), np.linspace(0.05, 0.25, 5)
    labels, cols = [], []
    t = np.linspace(0.0, 1.0, 11)
    for z in zs:
        for x in xs:
            label = f"x{x:.3f}_z{z:.3f}".replace(".", "p")
            labels += [f"u_{label}_m_per_s", f"w_{label}_m_per_s", f"kernel_sum_{label}"]
            cols += [np.full(t.shape, 2.0 * z), np.zeros(t.shape), np.ones(t.shape)]
    path = tmp_path / "velocity_win.csv"
    with open(path, "w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f)
        writer.writerow(["t_s", *labels])
        writer.writerows(np.column_stack([t, *cols]).tolist())
    out = plotting._plot_velocity(path, tmp_path)
    assert out is not None and out.stat().st_size > 10_000
