"""What a run will cost: an estimate said before it starts, and the measured figure once it runs.

Before the run: particles, steps and CPU time. The steps are the simulated time over the
acoustic time-step bound ``cfl h / c0`` (the core's step is this or shorter, so the estimate is a
lower bound); the CPU time is the particle-steps at :data:`REFERENCE_US_PER_PARTICLE_STEP`, the
speed ``watersim bench`` measured on one core. Once the run has taken
:data:`MEASURE_AFTER_STEPS` steps, :class:`SpeedMeter` says the speed measured on this run
and the time left at that speed.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from dataclasses import dataclass

from . import _core
from .simulation import Simulation

__all__ = ["REFERENCE_US_PER_PARTICLE_STEP", "CostEstimate", "SpeedMeter", "estimate"]

REFERENCE_US_PER_PARTICLE_STEP: dict[int, float] = {2: 0.55, 3: 1.45}
"""Microseconds per particle-step on one core of an AMD EPYC (the project's machine class):
``watersim bench --case dsph-piston2d`` (2D flume, Adami walls: 0.543) and ``--case
dsph-dambreak3d`` (1.43), docs/benchmarks.md."""

PARALLEL_EFFICIENCY = 0.85
"""Speed-up per thread assumed for the estimate (1.7 on two threads, docs/benchmarks.md)."""

MEASURE_AFTER_STEPS = 200
"""Steps after which :class:`SpeedMeter` reports the measured speed."""


@dataclass(frozen=True)
class CostEstimate:
    """The cost of running a simulation from its current time to ``until``."""

    particles: int
    steps: float
    """At least this many steps (simulated time over ``cfl h / c0``)."""
    cpu_s: float
    """CPU seconds at the reference speed."""
    wall_s: float
    """Wall seconds on ``threads`` threads at the reference speed."""
    threads: int
    dim: int

    def line(self) -> str:
        us = REFERENCE_US_PER_PARTICLE_STEP[self.dim]
        return (f"  cost: {self.particles:,} particles x at least {self.steps:,.0f} steps; about "
                f"{_duration(self.cpu_s)} of CPU at {us:g} us per particle-step (watersim bench, "
                f"{self.dim}D, one core), {_duration(self.wall_s)} on {self.threads} threads")


def estimate(sim: Simulation, until: float, threads: int) -> CostEstimate:
    """The cost of running ``sim`` to ``until`` [s] on ``threads`` threads."""
    resolved = json.loads(_core.resolve_scene(json.dumps(sim.scene)))
    params = sim.params()
    dt = float(resolved["cfl"]) * float(params["h"]) / float(params["c0"])
    steps = max(0.0, until - sim.time) / dt
    cpu = steps * sim.n_particles * REFERENCE_US_PER_PARTICLE_STEP[sim.dim] * 1e-6
    wall = cpu / max(1.0, threads * PARALLEL_EFFICIENCY)
    return CostEstimate(sim.n_particles, steps, cpu, wall, threads, sim.dim)


class SpeedMeter:
    """A run callback that, once the run has taken :data:`MEASURE_AFTER_STEPS` steps, says the
    speed measured (wall and CPU microseconds per particle-step) and the time left at it."""

    def __init__(self, sim: Simulation, until: float, say: Callable[[str], None]) -> None:
        self.until, self.say = until, say
        self.t0, self.steps0 = sim.time, sim.steps
        self.wall0, self.cpu0 = time.perf_counter(), time.process_time()
        self.done = False

    def __call__(self, sim: Simulation) -> None:
        steps = sim.steps - self.steps0
        if self.done or steps < MEASURE_AFTER_STEPS or sim.time <= self.t0:
            return
        self.done = True
        wall, cpu = time.perf_counter() - self.wall0, time.process_time() - self.cpu0
        per = 1e6 / (steps * sim.n_particles)
        left = wall * (self.until - sim.time) / (sim.time - self.t0)
        self.say(f"  measured: {wall * per:.3g} us per particle-step ({cpu * per:.3g} of CPU) "
                 f"over {steps} steps; about {_duration(left)} left at this speed")


def _duration(seconds: float) -> str:
    if seconds < 120.0:
        return f"{seconds:.0f} s"
    if seconds < 7200.0:
        return f"{seconds / 60.0:.0f} min"
    return f"{seconds / 3600.0:.1f} h"
