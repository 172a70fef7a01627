"""What a run will hold in memory at its peak, estimated before it starts, and the refusal of
a run that would not fit.

The core's own check (``Scene::validate_memory``) counts its particle arrays and its grid. A
whole ``watersim run`` holds more (docs/stability.md, "Memory of a run", compares these
estimates with measured peaks):

- what the process holds once the simulation is built (its resident set: the interpreter, the
  imported libraries and the core's arrays), and for a mesh beach the copies of the scene, mesh
  and all, that the run's summary, checkpoints and analysis make (:data:`MESH_COPY_BYTES` a
  triangle);
- the last good state (``LastGood``): a checkpoint, ``24 dim + 29`` bytes a particle plus a copy
  of the gauge records, two of them while one replaces the other;
- the gauge records, which grow by their values per sample times the samples,
  ``(until - t) / interval``: the core's arrays (up to twice their length in capacity, three
  times while one grows), a flume's decoded copy (two while one replaces the other) and the last
  good state's copies;
- the largest of the passing costs: the state hash (``16 dim + 8`` bytes a particle), a
  snapshot (its mesh arrays and their encoding, and the vorticity's pair arrays, about
  :data:`VORTICITY_PAIR_BYTES` per fluid pair).

A run whose estimate exceeds the memory available (the scene's ``memory_limit_bytes``, else 80 %
of ``MemAvailable``, as the core's check) is refused before its folder is made, naming what
grows most: a gauge (``gauges[i].interval``, with its values per sample and sample count), or
``dp``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from ._core import SceneError

__all__ = ["RunMemory", "available_memory_bytes", "estimate_run_memory", "resident_bytes"]

GIB = 1024.0**3

VORTICITY_PAIR_BYTES = {2: 320.0, 3: 500.0}
"""Bytes per unique fluid pair that a snapshot's vorticity (``fields.particle_vorticity``)
holds at its peak: the pair list, both directions' indices, offsets, kernel gradients, weighted
gradients, velocity differences and one outer product at a time (counted from the code: 304 in
2D, 480 in 3D, rounded up)."""

SNAPSHOT_PARTICLE_BYTES = 300.0
"""Bytes per particle of a snapshot's mesh arrays (positions, velocity and vorticity as 3-vectors,
density, pressure, kind, id, the vertex cells: 124) and meshio's binary encoding of them."""

CHECKPOINT_PARTICLE_BYTES = (24, 29)
"""A checkpoint's bytes per particle, ``24 dim + 29``: positions, velocities and their previous
values, densities and their previous values, ids, kinds."""

MESH_COPY_BYTES = 2000.0
"""Bytes per mesh triangle a run adds after its start: the scene, mesh and all, copied into
its summary, checkpoints and analysis (a 1,004,498-triangle bed: 1.80 GB beyond the resident
set at the start, measured with /usr/bin/time; docs/stability.md)."""

RECORD_COPIES_CORE = 3.0
"""The core's gauge arrays at their peak, in record lengths: a growing vector holds up to twice
its length, three times while it moves to a larger buffer."""


def resident_bytes() -> float:
    """The resident set of this process now [bytes] (``VmRSS`` of /proc/self/status; 0 where it
    is not readable)."""
    try:
        with open("/proc/self/status", encoding="ascii") as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return float(line.split()[1]) * 1024.0
    except OSError:
        pass
    return 0.0


def available_memory_bytes(scene: Mapping[str, Any]) -> float:
    """The memory a run may use [bytes]: the scene's ``memory_limit_bytes``, else 80 % of
    ``MemAvailable`` (/proc/meminfo), as the core's check; infinite where neither is known."""
    limit = scene.get("memory_limit_bytes")
    if limit is not None:
        return float(limit)
    try:
        with open("/proc/meminfo", encoding="ascii") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return 0.8 * float(line.split()[1]) * 1024.0
    except OSError:
        pass
    return math.inf


@dataclass(frozen=True)
class GaugeRecord:
    """One gauge's record at the run's end: what it stores per sample and how many samples."""

    index: int
    name: str
    values_per_sample: int
    interval: float
    samples: int

    @property
    def bytes(self) -> float:
        """The record's length [bytes]: its times and values, 8 bytes each."""
        return 8.0 * (self.values_per_sample + 1) * self.samples


@dataclass(frozen=True)
class RunMemory:
    """A run's memory at its peak, by part [bytes] (see the module's description)."""

    resident: float
    mesh: float
    last_good: float
    records: float
    passing: float
    passing_part: str
    gauges: tuple[GaugeRecord, ...] = field(default=())
    limit: float = math.inf

    @property
    def total(self) -> float:
        return self.resident + self.mesh + self.last_good + self.records + self.passing

    def parts(self) -> dict[str, float]:
        """The parts by name, for summaries and messages."""
        return {"resident_at_start": self.resident, "mesh_copies": self.mesh,
                "last_good": self.last_good,
                "gauge_records": self.records, self.passing_part: self.passing}

    def describe(self) -> str:
        return ", ".join(f"{name.replace('_', ' ')} {b / GIB:.3g}" for name, b in
                         self.parts().items()) + " GiB"

    def check(self) -> None:
        """Refuses a run whose estimate exceeds :attr:`limit`, naming the gauge whose record
        grows most when records are the largest part, else ``dp``.

        Raises:
            SceneError: ``field: reason`` with the estimate and its parts.
        """
        if self.total <= self.limit:
            return
        over = (f"the run would need about {self.total / GIB:.3g} GiB ({self.describe()}), more "
                f"than the {self.limit / GIB:.3g} GiB available")
        if self.gauges and self.records >= max(self.resident, self.mesh, self.last_good,
                                               self.passing):
            g = max(self.gauges, key=lambda r: r.bytes)
            raise SceneError(
                f"gauges[{g.index}].interval: gauge {g.name!r} records {g.values_per_sample} "
                f"values a sample every {g.interval:g} s, {g.samples} samples to the end: "
                f"{g.bytes / GIB:.3g} GiB of record; {over}; sample it less often or at fewer "
                "points")
        raise SceneError(f"dp: {over}; use a larger dp")


def gauge_records(sim: Any, until: float) -> tuple[GaugeRecord, ...]:
    """Each gauge's record at ``until``: its values per sample (from the core's empty records'
    shapes) and its sample count ``(until - t) / interval + 1``."""
    specs = sim.scene.get("gauges") or []
    out = []
    for i, (record, spec) in enumerate(zip(sim.core.gauges(), specs, strict=False)):
        columns = [v for k, v in record.items()
                   if k not in ("name", "type", "t", "points", "shape") and hasattr(v, "shape")]
        per_sample = sum(math.prod(c.shape[1:]) for c in columns)
        interval = float(spec["interval"])
        samples = math.floor(max(until - sim.time, 0.0) / interval) + 2
        out.append(GaugeRecord(i, str(record["name"]), int(per_sample), interval, samples))
    return tuple(out)


def estimate_run_memory(sim: Any, until: float, *, last_good: bool = True,
                        snapshots: bool = False, flume: bool = False) -> RunMemory:
    """The peak memory of running ``sim`` to ``until`` as ``watersim run`` does: with a last good
    state, with snapshots, with a flume's decoded gauge records."""
    n, dim = sim.n_particles, sim.dim
    per_particle = CHECKPOINT_PARTICLE_BYTES[0] * dim + CHECKPOINT_PARTICLE_BYTES[1]
    gauges = gauge_records(sim, until)
    record_bytes = sum(g.bytes for g in gauges)
    copies = RECORD_COPIES_CORE + (2.0 if flume else 0.0) + (2.0 if last_good else 0.0)
    passing = {"state_hash": (16.0 * dim + 8.0) * n}
    if snapshots:
        pairs = 0.5 * sim.fluid_pairs()
        passing["snapshot"] = SNAPSHOT_PARTICLE_BYTES * n + VORTICITY_PAIR_BYTES[dim] * pairs
    name, peak = max(passing.items(), key=lambda kv: kv[1])
    triangles = sum(len(o.get("triangles") or []) for o in sim.scene.get("obstacles") or []
                    if o.get("shape") == "mesh")
    return RunMemory(
        resident=resident_bytes(),
        mesh=MESH_COPY_BYTES * triangles,
        last_good=2.0 * per_particle * n if last_good else 0.0,
        records=copies * record_bytes,
        passing=peak,
        passing_part=name,
        gauges=gauges,
        limit=available_memory_bytes(sim.scene),
    )
