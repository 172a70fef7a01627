"""The numerical wave flume: a paddle, a beach or a damping zone, gauges, and their analysis.

::

    import watersim as ws

    flume = ws.Flume(length=17.0, depth=0.705, beach=ws.PlaneBeach(toe=4.0, slope=1 / 15))
    sim = flume.simulation(
        wave=ws.RegularWave(period=1.275, height=0.114), paddle=ws.Piston(order=2, ramp_periods=2),
        dp=0.01, gauges=[ws.ElevationGauge(x) for x in (4.0, 12.0, 13.5)], runup=True)
    sim.run(until=30.0)
    eta = sim.gauges.elevation          # (n_samples, n_gauges), metres above still water
    sim.write_gauges_csv("gauges.csv")
    report = sim.analyse()              # wave heights, breaking, run-up, reflection, harmonics

Coordinates (the same in every input and output):

- x runs along the flume from the paddle face at rest (x = 0) to the far wall (x = ``length``);
- z is up from the flume floor (z = 0), so the still-water level (SWL) is z = ``depth``;
- y runs across the flume, from 0 to ``width`` (3D only; the tank's side walls are at y = 0 and
  y = ``width``).

Gauge *positions* are in these coordinates; *elevations* (surface elevation eta, run-up) are
reported relative to the SWL, positive up, in metres.

What is built (the core's scene, see ``crates/sph-core/src/scene/``):

- the tank box ``[x_back, length] x [0, height]`` (``x [0, width]`` in 3D), where ``x_back < 0``
  leaves room behind the paddle for its ``boundary_layers`` plate and its largest backward
  excursion. ``x_back`` is a whole number of dp from x = 0, so the particle lattice (particles at
  ``(i + 1/2) dp`` from the tank corner) puts the first fluid column exactly dp/2 in front of
  the paddle face;
- water from the paddle to the far wall up to ``depth`` (minus whatever the beach occupies);
- the beach as a piecewise-linear bed profile (solid below it), a plane beach being the profile
  ``(toe, 0) -> (x_top, height)`` continued flat at the tank top; or, in 3D, a closed triangle
  mesh (:class:`MeshBeach`, from an STL file), passed to the core as a mesh obstacle;
- the paddle: a piston or a flap (hinged at ``hinge_z``), driven by a motion law whose
  coefficients come from :mod:`watersim.wave_theory` (Biesel transfer functions, Madsen's and
  Schaffer's second order, Fenton's stream-function wave, spectral synthesis, focused groups,
  Goring's solitary wave), or a tabulated displacement;
- an optional velocity damping zone at the far end (on by default in a flume without beach);
- the gauges, all sampled by the core at their own interval.

Wave validity (``wave_theory.check_wave``) is checked when a regular wave is built: a wave
beyond second-order theory or breaking at the paddle gives a
:class:`~watersim.wave_theory.WaveValidityWarning`, not an error. Bad input raises
:class:`~watersim.SceneError` naming the field (``depth``, ``beach.toe``, ``wave.height``,
``paddle.order``, ``gauges[2].x``, ...).

Modules, one concern each: :mod:`.bed` (beaches, damping zone), :mod:`.structures`,
:mod:`.waves`, :mod:`.paddles`
(wave-makers and the resolved paddle law), :mod:`.gauges`, :mod:`.scene` (:class:`Flume`,
:class:`FlumeScene`), :mod:`.records` (gauge records, CSV), :mod:`.simulation` and
:mod:`.analyse`; :mod:`.lattice` holds the particle lattice's arithmetic, :mod:`.checks` the
small input checks the models share.
"""

from . import gauges
from .analyse import analyse_flume
from .bed import DampingZone, MeshBeach, PlaneBeach, ProfileBeach, SteepSlopeWarning
from .gauges import *  # noqa: F403 (its __all__: the gauge classes)
from .lattice import lattice_dp, lattice_layers
from .paddles import RAMPS, Flap, Piston, flap_height_to_stroke_hinged
from .records import FlumeGauges, VelocityRecord
from .scene import CHOICES, TAGS, Flume, FlumeScene
from .simulation import FlumeSimulation
from .structures import BoxStructure, ProfileStructure
from .waves import (
    SPECTRA,
    FocusedWave,
    IrregularWave,
    RegularWave,
    SolitaryWave,
    TabulatedMotion,
)

__all__ = [
    *gauges.__all__,
    "CHOICES",
    "RAMPS",
    "SPECTRA",
    "TAGS",
    "BoxStructure",
    "DampingZone",
    "Flap",
    "Flume",
    "FocusedWave",
    "FlumeGauges",
    "FlumeScene",
    "FlumeSimulation",
    "IrregularWave",
    "MeshBeach",
    "Piston",
    "PlaneBeach",
    "ProfileStructure",
    "ProfileBeach",
    "RegularWave",
    "SolitaryWave",
    "SteepSlopeWarning",
    "TabulatedMotion",
    "VelocityRecord",
    "analyse_flume",
    "flap_height_to_stroke_hinged",
    "lattice_dp",
    "lattice_layers",
]
