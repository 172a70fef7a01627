"""The flume3d case's across-the-width report on synthetic records with a known answer: a Stokes
second-order wave whose height is 5 % lower at the quarter widths than on the centre line, with
one stray low reading per wave at the centre gauge (what the particle method shows at coarse
dp)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from watersim import wave_theory as wt
from watersim.flume import FlumeGauges, analyse_flume
from watersim.flume_cases import across_width, flume_builder


def test_across_width_reports_zero_crossing_and_first_harmonic_spreads() -> None:
    setup = flume_builder("flume3d", {})
    assert setup.wave.height == 0.05  # type: ignore[union-attr]
    period, depth, target = 1.0, setup.flume.depth, 0.05
    k = float(wt.wavenumber(period, depth))
    w = 2.0 * math.pi / period
    t = np.arange(0.0, float(setup.until), float(setup.sample_interval))
    records: list[dict[str, Any]] = []
    heights: dict[str, float] = {}
    for spec in setup.to_scene()["gauges"]:
        x, y = spec["position"][0], spec["position"][1]
        centre = abs(y - 0.5 * setup.flume.width) < 1e-9  # type: ignore[operator]
        height = target * (1.0 if centre else 0.95)
        heights[spec["name"]] = height + (0.03 * target if centre else 0.0)
        a1 = 0.5 * height
        a2 = float(wt.stokes2_second_harmonic_amplitude(height, period, depth))
        phase = w * t - k * x
        eta = a1 * np.cos(phase) + a2 * np.cos(2.0 * phase)
        if centre:
            # a spike of 0.3 H, one sample per wave at the trough: the zero-crossing height
            # takes all of it, the first harmonic's 2 a1 only 2 x 2 x 0.3 H / 40 samples per
            # period = 3 % of H
            troughs = ((math.pi + k * x) / w + period * np.arange(20)) / float(
                setup.sample_interval)
            idx = np.round(troughs).astype(int)
            eta[idx[idx < t.size]] -= 0.3 * target
        records.append({"type": "elevation", "name": spec["name"], "t": t, "z": depth + eta})
    gauges = FlumeGauges(setup, records)
    analysis = analyse_flume(setup, gauges)
    report = across_width(setup, analysis)
    at_1l = f"{setup.wavelength:.3f}"
    # 2 a1 is the Stokes second-order wave's height, gauge by gauge
    for name, h in heights.items():
        assert report["H1"][name] == pytest.approx(h, rel=0.003)
    assert report["H1_spread_over_H"][at_1l] == pytest.approx(0.08, abs=0.003)
    # the spike inflates the zero-crossing height at the centre, hence its spread
    assert report["H_spread_over_H"][at_1l] > 0.2
    assert set(report["H1_spread"]) == {at_1l}  # one gauge at 0.5 L: no spread there
