"""A flume run: the simulation with its gauges, overturn watch and analysis."""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .. import analysis as an
from ..simulation import Simulation
from .analyse import analyse_flume
from .records import FlumeGauges

if TYPE_CHECKING:
    from .scene import FlumeScene


class FlumeSimulation(Simulation):
    """A flume run: a :class:`~watersim.Simulation` that knows its flume, with gauges as NumPy,
    CSV output and the wave analysis.

    Args:
        setup: the :class:`FlumeScene`.
    """

    def __init__(self, setup: FlumeScene) -> None:
        super().__init__(setup.to_scene())
        self.setup = setup
        self._gauges_cache: tuple[int, FlumeGauges] | None = None
        self.overturns: list[tuple[float, an.Overturn]] = []
        """Overturned free surfaces seen over the beach, ``(time [s], overturn)``: with a beach,
        :meth:`run` looks for one in every ``sample_interval``
        (:func:`watersim.analysis.overturned_surface`, from the toe to the far wall)."""
        self.overturn_checks = 0
        """Snapshots searched for an overturned surface so far."""
        self._dp = float(self.params()["dp"])

    @property
    def gauges(self) -> FlumeGauges:
        """The gauge records so far (:class:`FlumeGauges`)."""
        if self._gauges_cache is None or self._gauges_cache[0] != self.steps:
            self._gauges_cache = (self.steps, FlumeGauges(self.setup, self._sim.gauges()))
        return self._gauges_cache[1]

    def run(  # type: ignore[override]
        self,
        until: float | None = None,
        progress: bool = False,
        callback_every: float | None = None,
        callback: Callable[[Simulation], None] | None = None,
    ) -> None:
        """Advance to ``until`` [s] (default the scene's ``until``).

        Args:
            until: end time [s].
            progress: show a progress bar on stderr (see :meth:`watersim.Simulation.run`).
            callback_every, callback: as :meth:`watersim.Simulation.run`.

        Raises:
            InstabilityError: a stability monitor stopped the run; the gauge records up to the
                last good step stay readable (:attr:`gauges`).
        """
        end = float(self.setup.until if until is None else until)  # type: ignore[arg-type]
        super().run(end, callback_every=callback_every, callback=callback, progress=progress)

    def _monitors(self) -> list[tuple[float, Callable[[Simulation], Any]]]:
        # a plunging breaker shows as a jet over air; only a beach makes one
        if self.setup.flume.beach is None:
            return []
        return [(float(self.setup.sample_interval),  # type: ignore[arg-type, list-item]
                 FlumeSimulation._watch_overturn)]

    def _watch_overturn(self) -> None:
        """Record an overturned surface over the beach in the current state, if there is one."""
        found = an.overturned_surface(self.fluid_positions(), self._dp,
                                      x_range=(self.setup.toe, self.setup.flume.length))
        self.overturn_checks += 1
        if found is not None:
            self.overturns.append((self.time, found))

    def __repr__(self) -> str:
        setup = self.setup
        flume = setup.flume
        size = f"{flume.length:g} m long, {flume.depth:g} m deep"
        if flume.width is not None:
            size += f", {flume.width:g} m wide"
        n_gauges = len(setup.gauges) + (setup.runup_gauge is not None)
        return (
            f"{super().__repr__()[:-1]}, flume {size}, {type(setup.wave).__name__}, "
            f"{type(setup.paddle).__name__}, {n_gauges} gauges, until={setup.until:g} s)"
        )

    def write_gauges_csv(self, path: str | os.PathLike[str]) -> Path:
        """Write ``gauges.csv`` (see :meth:`FlumeGauges.to_csv`)."""
        return self.gauges.to_csv(path)

    def write_velocity_csvs(self, directory: str | os.PathLike[str]) -> dict[str, Path]:
        """Write ``velocity_NAME.csv`` per velocity probe and window into ``directory`` (see
        :meth:`FlumeGauges.velocity_to_csv`); returns the files by gauge name."""
        return self.gauges.velocity_to_csv(directory)

    def analyse(self, t_start: float | None = None) -> dict[str, Any]:
        """The wave analysis of the records so far (see :func:`analyse_flume`)."""
        return analyse_flume(self.setup, self.gauges, t_start=t_start,
                             overturns=self.overturns, overturn_checks=self.overturn_checks)

