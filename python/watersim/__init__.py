"""WaterSim: a weakly-compressible SPH numerical wave flume (Rust core, Python front).

Public names:

- :class:`Simulation`: a running simulation (wrapper of the core's); :class:`Snapshot`, a
  consistent copy of its state that another thread may take while it steps.
- :class:`Scene`: the general scene (a tank, :class:`FluidBlock` / :class:`FillTo` water,
  bodies of :mod:`watersim.bodies` (:class:`Box`, :class:`Sphere`, :class:`Cylinder`,
  :class:`Capsule`, :class:`Polygon`, :class:`HalfSpace`, :class:`Mesh`) and gauges), and its
  presets :class:`DamBreak`, :class:`Tank`: scene builders, checked field by field.
- :class:`Flume` (with :class:`PlaneBeach`, :class:`ProfileBeach`, :class:`MeshBeach` (3D,
  from an STL file), :class:`DampingZone`): the wave
  flume; :meth:`Flume.simulation` takes a wave (:class:`RegularWave`, :class:`IrregularWave`,
  :class:`FocusedWave`, :class:`SolitaryWave`, :class:`TabulatedMotion`), a paddle
  (:class:`Piston`, :class:`Flap`) and gauges (:class:`ElevationGauge`, :class:`VelocityProbe`,
  :class:`VelocityWindow`, :class:`PressureGauge`, :class:`RunupGauge`) and gives a
  :class:`FlumeSimulation`.
- :class:`SceneError`: a refused scene (a ``ValueError``; message ``field: reason``).
- :class:`InstabilityError`: a run stopped by a stability monitor (a ``RuntimeError``).
- :func:`front_position`: dam-break surge front from fluid positions.
- :func:`load`: a flume run's records from its folder, as an ``xarray.Dataset``
  (:mod:`watersim.rundir`: checkpoints, resume, re-analysis).
- :func:`load_scene`: a scene file (TOML, :mod:`watersim.scenefile`) as builder + output options.
- :mod:`wave_theory`, :mod:`analysis`: wave-maker theory and gauge analysis.
- :mod:`numerics`: the numerical options (``ws.numerics.Laminar(nu=2e-6)``) and the presets of
  the built-in cases.
"""

from __future__ import annotations

from . import analysis, numerics, wave_theory
from . import flume as _flume
from ._core import InstabilityError, SceneError
from ._version import __version__
from .bodies import Box, Capsule, Cylinder, HalfSpace, Mesh, Polygon, Sphere
from .checkpoint import load_checkpoint, save_checkpoint
from .flume import *  # noqa: F403 (its __all__: the flume's models, gauges and analysis)
from .measure import front_error, front_position, load_martin_moyce, water_column_height
from .rundir import load
from .scenefile import load as load_scene
from .scenes import (
    DamBreak,
    FillTo,
    FluidBlock,
    Scene,
    SceneBuilder,
    SceneSimulation,
    StiffFluidWarning,
    Tank,
)
from .simulation import Simulation, Snapshot

__all__ = [
    *_flume.__all__,
    "Box",
    "Capsule",
    "Cylinder",
    "DamBreak",
    "FillTo",
    "FluidBlock",
    "HalfSpace",
    "Mesh",
    "Polygon",
    "Scene",
    "SceneSimulation",
    "Sphere",
    "InstabilityError",
    "SceneBuilder",
    "StiffFluidWarning",
    "SceneError",
    "Simulation",
    "Snapshot",
    "Tank",
    "__version__",
    "analysis",
    "front_error",
    "front_position",
    "load",
    "load_checkpoint",
    "load_martin_moyce",
    "load_scene",
    "numerics",
    "save_checkpoint",
    "water_column_height",
    "wave_theory",
]
