"""A validation case's registry entry: :class:`Case`. Each case module owns its entry (its
scene, runner, metrics and report text); :data:`watersim.validation.cases.CASES` lists them in
report order."""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .._core import SceneError
from ..checks import _positive
from ..flume import FlumeScene, lattice_dp
from .running import _Clock, make_record

__all__ = ["Case"]


@dataclass(frozen=True)
class Case:
    """A validation case.

    Attributes:
        name: the case's name (``watersim validate NAME``).
        description: one line.
        reference: where the reference comes from.
        resolution_meaning: what the resolution counts, e.g. ``"column width / dp"``.
        length: the characteristic length [m]: ``dp = length / resolution`` (snapped for the
            wave flumes, see ``depth``).
        resolutions: the full sweep's resolutions.
        quick_resolutions: the ``--quick`` sweep's resolutions.
        primary: the metric the accuracy target applies to.
        target: the accuracy target of ``primary`` (an error at most this large meets it).
        target_text: the target in words, for the report.
        runner: ``runner(case, resolution, quick, progress) -> record``.
        report_note: what the report should say about the case's metrics.
        report_details: keys of the records' ``details`` the report tabulates.
        depth: a wave flume's still-water depth [m], which dp must divide (:meth:`dp`); ``None``
            for the other cases.
        modules: optional packages (not WaterSim's own dependencies) the case imports, checked
            before a sweep starts.
        figure: ``figure(runs, path)`` draws the case's own measurements from its run records
            into ``path`` (a PNG), shown in the report under the error plots; ``None``: none.
    """

    name: str
    description: str
    reference: str
    resolution_meaning: str
    length: float
    resolutions: tuple[float, ...]
    quick_resolutions: tuple[float, ...]
    primary: str
    target: float
    target_text: str
    runner: Callable[[Case, float, bool, bool], dict[str, Any]]
    report_note: str = ""
    report_details: tuple[str, ...] = ()
    depth: float | None = None
    modules: tuple[str, ...] = ()
    figure: Callable[[Sequence[Mapping[str, Any]], Path], None] | None = None
    scene: Callable[[float, Mapping[str, str]], tuple[FlumeScene, list[str]]] | None = None
    """For a case that takes numerical ``--set`` items (``watersim validate --set``):
    ``scene(dp, settings)`` builds its scene (and checks the items); its runner then takes the
    items as a fifth argument. ``None``: the case takes none."""

    @property
    def settable(self) -> bool:
        """Whether the case takes numerical ``--set`` items."""
        return self.scene is not None

    def dp(self, resolution: float) -> float:
        """Particle spacing [m] of a resolution: ``length / resolution``, for a wave flume
        snapped to ``depth / round(depth / dp)`` (:func:`~watersim.flume.lattice_dp`): the core
        fills the water with whole particle layers, so only such a dp gives the flume the depth
        its wave theory and paddle law are computed for (the resolution is then nominal, the
        actual ``length / dp`` within half a layer's share of it)."""
        dp = self.length / resolution
        return dp if self.depth is None else lattice_dp(self.depth, dp)

    def run(self, resolution: float, quick: bool = False, progress: bool = False,
            settings: Mapping[str, str] | None = None) -> dict[str, Any]:
        """Run the case at ``resolution`` with numerical ``--set`` ``settings`` (key -> text,
        for a case that takes them); returns the run record (never raises for a failed
        simulation or a case that cannot be built at this resolution: the record's ``status``
        says what happened).

        Raises:
            ValueError: a resolution that is not a positive number, or settings for a case
                that takes none.
        """
        _positive("resolution", resolution)
        if settings and not self.settable:
            raise ValueError(f"--set: {self.name} takes no settings")
        clock = _Clock()
        try:
            if self.settable:
                return self.runner(self, float(resolution), quick, progress,  # type: ignore[call-arg]
                                   dict(settings or {}))
            return self.runner(self, float(resolution), quick, progress)
        except (SceneError, ValueError, RuntimeError, FloatingPointError) as exc:
            # a case that cannot be built or measured at this resolution is a result, not a crash
            return make_record(self.name, resolution, self.dp(resolution), None, clock.wall(),
                               clock.cpu(), "error", f"{type(exc).__name__}: {exc}", {}, {})
