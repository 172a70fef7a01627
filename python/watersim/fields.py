"""Vorticity, the field seed 002 (Stansby & Feng) draws under breaking waves (Figs. 6-7): from
the particles (each snapshot's ``vorticity`` for ParaView) and from a velocity window's grid.

In 2D the flume lies in the x-z plane and the vorticity is its one component across it,
``omega_y = du/dz - dw/dx`` [1/s]: positive where the flow turns clockwise seen with x to the
right and z up (under a crest travelling toward +x, the roller at its front turns clockwise). In
3D it is the vector ``curl v``.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
from scipy.spatial import cKDTree

__all__ = ["grid_vorticity", "particle_vorticity"]

FloatArray = npt.NDArray[np.float64]

MIN_GRADIENT_DETERMINANT = 0.05
"""Below this determinant of the kernel-gradient moment matrix (1 for a particle with a full
support, about 0.5 at a flat free surface, 0.125 in a 3D corner), the particle has too few
neighbours on too few sides for a velocity gradient: its vorticity is NaN (splashes, drops)."""


def _grad_factor(kernel: str, r: FloatArray, h: float, dim: int) -> FloatArray:
    """``(dW/dr) / r`` [1/m^(dim+2)] of the core's kernels (crates/sph-core/src/kernel.rs), so
    that ``grad_i W_ij = (x_i - x_j) * factor``."""
    q = r / h
    if kernel == "wendland":  # Wendland C2: dW/dq = -5 q alpha_D (1 - q/2)^3
        alpha = 7.0 / (4.0 * math.pi * h**2) if dim == 2 else 21.0 / (16.0 * math.pi * h**3)
        t = np.clip(1.0 - 0.5 * q, 0.0, None)
        return -5.0 * alpha / h**2 * t**3
    if kernel == "wendland_c4":  # Wendland C4: dW/dq = -14/3 alpha_D q (1 - q/2)^5 (1 + 5/2 q)
        alpha = 9.0 / (4.0 * math.pi * h**2) if dim == 2 else 495.0 / (256.0 * math.pi * h**3)
        t = np.clip(1.0 - 0.5 * q, 0.0, None)
        return -14.0 / 3.0 * alpha / h**2 * t**5 * (1.0 + 2.5 * q)
    if kernel == "cubic_spline":  # Monaghan & Lattanzio (1985) M4
        alpha = 10.0 / (7.0 * math.pi * h**2) if dim == 2 else 1.0 / (math.pi * h**3)
        t = np.clip(2.0 - q, 0.0, None)
        with np.errstate(divide="ignore", invalid="ignore"):
            outer = -0.75 * t**2 / np.maximum(q, 1e-12)
        return alpha / h**2 * np.where(q < 1.0, -3.0 + 2.25 * q, outer)
    raise ValueError(f"kernel: unknown kernel {kernel!r} (wendland, wendland_c4, cubic_spline)")


def particle_vorticity(positions: npt.ArrayLike, velocities: npt.ArrayLike,
                       volumes: npt.ArrayLike, h: float, kernel: str = "wendland") -> FloatArray:
    """Vorticity of each particle from its neighbours within ``2 h``, with the velocity gradient
    of the corrected kernel gradient (Bonet & Lok 1999, Eq. 32; Randles & Libersky 1996): the
    gradient ``M_i^-1 sum_j V_j grad_i W_ij (v_j - v_i)^T`` with
    ``M_i = sum_j V_j grad_i W_ij (x_j - x_i)^T`` is exact for a linear velocity field, at a free
    surface and next to a wall as in the bulk.

    Args:
        positions, velocities: (N, dim) of the particles to use (usually the fluid's) [m], [m/s].
        volumes: (N,) ``m / rho`` [m^dim].
        h: smoothing length [m] (the support is ``2 h``, as both core kernels have).
        kernel: ``"wendland"``, ``"wendland_c4"`` or ``"cubic_spline"``
            (``Simulation.params()["kernel"]``).

    Returns:
        2D: (N,) ``omega_y = du/dz - dw/dx`` [1/s]; 3D: (N, 3) ``curl v``. NaN where the
        particle's neighbours do not surround it enough (:data:`MIN_GRADIENT_DETERMINANT`).
    """
    x = np.asarray(positions, dtype=np.float64)
    v = np.asarray(velocities, dtype=np.float64)
    vol = np.asarray(volumes, dtype=np.float64)
    n, dim = x.shape
    if dim not in (2, 3) or v.shape != x.shape or vol.shape != (n,):
        raise ValueError("positions, velocities: (N, 2) or (N, 3) each; volumes: (N,)")
    pairs = cKDTree(x).query_pairs(2.0 * h, output_type="ndarray")
    i = np.concatenate([pairs[:, 0], pairs[:, 1]])
    j = np.concatenate([pairs[:, 1], pairs[:, 0]])
    dx = x[j] - x[i]
    grad = -dx * _grad_factor(kernel, np.linalg.norm(dx, axis=1), h, dim)[:, None]
    weighted = vol[j][:, None] * grad
    moments = np.zeros((n, dim, dim))
    velocity_moments = np.zeros((n, dim, dim))
    np.add.at(moments, i, weighted[:, :, None] * dx[:, None, :])
    np.add.at(velocity_moments, i, weighted[:, :, None] * (v[j] - v[i])[:, None, :])
    det = np.linalg.det(moments)
    ok = det > MIN_GRADIENT_DETERMINANT
    gradient = np.full((n, dim, dim), np.nan)  # gradient[k, a, b] = d v_b / d x_a
    gradient[ok] = np.linalg.solve(moments[ok], velocity_moments[ok])
    return _curl(gradient)


def _curl(gradient: FloatArray) -> FloatArray:
    """``curl v`` from ``gradient[..., a, b] = d v_b / d x_a``: its y component in 2D (x-z
    plane, axes 0 and 1), the vector in 3D."""
    g = gradient
    if g.shape[-1] == 2:
        return g[..., 1, 0] - g[..., 0, 1]
    return np.stack([g[..., 1, 2] - g[..., 2, 1], g[..., 2, 0] - g[..., 0, 2],
                     g[..., 0, 1] - g[..., 1, 0]], axis=-1)


def grid_vorticity(velocity: npt.ArrayLike, spacing: tuple[float, ...]) -> FloatArray:
    """Vorticity on a velocity window's regular grid by central differences (one-sided at the
    window's edges; NaN next to a dry point, which is NaN).

    Args:
        velocity: (..., n_z, n_x, 2) in 2D, (..., n_z, n_y, n_x, 3) in 3D [m/s] (the layout of
            ``VelocityRecord.velocity`` for a window), NaN where dry.
        spacing: the grid step along each grid axis in that order, (dz, dx) or (dz, dy, dx) [m].

    Returns:
        (..., n_z, n_x) ``omega_y`` in 2D, (..., n_z, n_y, n_x, 3) ``curl v`` in 3D [1/s].
    """
    u = np.asarray(velocity, dtype=np.float64)
    dim = u.shape[-1]
    if dim not in (2, 3) or len(spacing) != dim or u.ndim < dim + 1:
        raise ValueError("velocity: (..., grid..., dim) with one spacing per grid axis")
    if any(n < 2 for n in u.shape[-dim - 1:-1]):
        raise ValueError("velocity: a window needs at least 2 points along each axis")
    grid_axes = [u.ndim - 1 - dim + k for k in range(dim)]  # z, (y,) x
    coordinate = list(reversed(range(dim)))  # grid axis k is coordinate dim-1-k (z last)
    gradient = np.empty((*u.shape[:-1], dim, dim))
    for k, axis in enumerate(grid_axes):
        gradient[..., coordinate[k], :] = np.gradient(u, spacing[k], axis=axis)
    return _curl(gradient)
