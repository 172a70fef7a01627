"""The particle lattice: how many layers the core fills, and the spacing that fills a depth."""

from __future__ import annotations

import math

LATTICE_RTOL = 1e-6
"""Relative tolerance within which ``depth / dp`` (and a 3D flume's ``width / dp``) counts as a
whole number: the core then fills exactly that many layers (see :func:`lattice_layers`)."""


MAX_PARTICLES = 1e10
"""Fluid particle count past which a flume is refused before anything is derived from dp (far
beyond any machine's memory; the core's estimate then refuses what does not fit this one)."""


def lattice_layers(extent: float, dp: float) -> int:
    """Number of fluid layers the core puts in ``[0, extent]`` [m] at spacing ``dp`` [m].

    The core (crates/sph-core/src/geometry.rs, ``sample``) places particles at ``(i + 1/2) dp``
    from the tank's inner corner and keeps those strictly inside a fluid box, so a still-water
    depth (or a 3D flume's width) holds the whole layers whose centres lie below it: about
    ``round(extent / dp)`` (a half rounds down), computed here with the core's own floating-point
    expression. The water it makes is ``lattice_layers(extent, dp) * dp`` deep (wide).
    """
    n = max(math.floor(extent / dp - 0.5) - 1, 0)
    while (n + 0.5) * dp < extent:
        n += 1
    return n


def _whole(extent: float, dp: float) -> bool:
    """Whether ``extent / dp`` is a whole number within :data:`LATTICE_RTOL`."""
    q = extent / dp
    return abs(q - round(q)) <= LATTICE_RTOL * q


def lattice_dp(depth: float, dp: float, width: float | None = None) -> float:
    """The spacing [m] nearest ``dp`` [m] that makes ``depth`` [m] a whole number of layers:
    ``dp`` itself when it already is one, else ``depth / n`` with ``n = round(depth / dp)`` (at
    least 2), so the core fills exactly the depth asked for (:func:`lattice_layers`).

    With a 3D flume's ``width`` [m], the smallest ``n`` from ``round(depth / dp)`` up to twice
    that for which the width is also a whole number of ``depth / n``; when none is, the depth's
    ``n`` (the flume then refuses the width, naming it).
    """
    if _whole(depth, dp) and (width is None or _whole(width, dp)):
        return dp  # already whole: keep it as given (0.025, not 0.3 / 12 = 0.024999...)
    n0 = max(round(depth / dp), 2)
    if width is not None:
        for n in range(n0, 2 * n0 + 1):
            if _whole(width, depth / n):
                return depth / n
    return depth / n0


def _lattice_error(field: str, what: str, extent: float, dp: float, unit: str) -> str:
    """The refusal of an ``extent`` [m] that is not a whole number of dp (see
    :meth:`FlumeScene._check_lattice`)."""
    q = extent / dp
    filled = lattice_layers(extent, dp) * dp
    lo, hi = math.floor(q), math.ceil(q)
    if field == "dp":
        fix = (f"use dp = {extent / lo:.8g} ({lo} {unit}) or {extent / hi:.8g} ({hi} {unit}), "
               f"or a {what.split()[-1]} that is a whole number of dp")
    else:
        fix = (f"use a {field} of {lo * dp:.6g} m ({lo} dp) or {hi * dp:.6g} m ({hi} dp), or a "
               "dp that divides both the depth and the width")
    n = lattice_layers(extent, dp)
    return (f"{field}: the {what} {extent:.6g} m is {q:.6g} dp (dp = {dp:.6g} m); the particle "
            f"lattice fills whole {unit}, so the water would be {filled:.6g} m "
            f"{'deep' if field == 'dp' else 'wide'} ({n} {unit}); {fix}")

