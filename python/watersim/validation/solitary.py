"""Validation case solitary2d: a non-breaking solitary wave (H/d = 0.15) running up a 1:3 beach,
against Synolakis' (1987) run-up law, the run-up read from the wet front on the bed (issue 30).

The numerics are the flume cases' (:data:`watersim.numerics.FLUME_CASE`) unless ``watersim
validate solitary2d --set KEY=VALUE`` changes them (``boundary=mdbc``,
``boundary.slip=free_slip``, ...): one command measures each wall model on the same wave.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

from .. import wave_theory as wt
from ..flume import FlumeScene, RunupGauge
from .running import numerical_case_scene

SOLITARY_SLOPE = 1.0 / 3.0
"""Beach slope of the run-up case: steep enough that H/d = 0.15 does not break."""


SOLITARY_DEPTH, SOLITARY_HEIGHT = 0.3, 0.045
"""Depth and wave height of the run-up case [m] (H/d = 0.15)."""


def solitary_scene(dp: float, settings: Mapping[str, str] | None = None
                   ) -> tuple[FlumeScene, list[str]]:
    """solitary2d set up non-breaking at ``dp``, with ``--set``-style numerical ``settings``
    (the wall model, say: ``boundary=mdbc`` and ``boundary.slip=free_slip``), and the
    warnings its build gave (as notes): d = 0.3 m, H/d = 0.15 (H = 0.045 m), a 1:3 beach from
    x = 3 m, flume 4.8 m (walls d + d/2 = 0.45 m high, above the law's run-up of 0.137 m);
    until = half the paddle motion + travel to the shoreline + 1 s; the run-up gauge reads
    the wet front.

    Raises:
        FlumeCaseError: a settings key that is not a numerical key of the flume cases.
    """
    depth, height = SOLITARY_DEPTH, SOLITARY_HEIGHT
    fixed = {"wave.height": repr(height), "beach.slope": repr(SOLITARY_SLOPE),
             "beach.toe": "3.0", "flume.length": "4.8"}

    def until(s: FlumeScene) -> float:
        assert s.law.duration is not None and s.shoreline is not None
        c = float(wt.solitary_celerity(height, depth, s.g))
        # Goring's motion is symmetric about the crest's release at half its duration; the
        # run-up peaks within about a second of the crest reaching the shoreline
        return 0.5 * s.law.duration + s.shoreline / c + 1.0

    scene, notes = numerical_case_scene("solitary2d", dp, settings, until, fixed)
    return dataclasses.replace(scene, runup=RunupGauge(method="wet_front")), notes
