"""The flume package's shape (issue 27): one class per model, dispatch by method, small modules
without import cycles, and the registries the scene file and the records read. Builds only, no
stepping."""

from __future__ import annotations

import ast
import csv
import dataclasses
import typing
from pathlib import Path
from typing import Any, ClassVar

import numpy as np
import pytest

import watersim as ws
from watersim import flume
from watersim.flume import gauges as flume_gauges

PACKAGE = Path(flume.__file__).parent
MODULES = sorted(PACKAGE.glob("*.py"))


def _runtime_imports(path: Path) -> set[str]:
    """The flume modules ``path`` imports when it is loaded (``if TYPE_CHECKING:`` blocks and
    imports inside functions left out)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    out: set[str] = set()
    for node in tree.body:
        if isinstance(node, ast.ImportFrom) and node.level == 1:
            if node.module is not None:
                out.add(node.module.split(".")[0])
            else:
                out.update(alias.name for alias in node.names)
    return out


def test_the_flume_modules_import_each_other_without_a_cycle() -> None:
    graph = {p.stem: _runtime_imports(p) - {p.stem} for p in MODULES if p.stem != "__init__"}
    done: set[str] = set()

    def visit(name: str, path: tuple[str, ...]) -> None:
        assert name not in path, f"import cycle: {' -> '.join((*path, name))}"
        if name in done:
            return
        for dep in sorted(graph.get(name, ())):
            visit(dep, (*path, name))
        done.add(name)

    for name in graph:
        visit(name, ())


def test_modules_and_functions_stay_small_and_dispatch_is_by_method() -> None:
    isinstance_lines = 0
    for path in MODULES:
        text = path.read_text(encoding="utf-8")
        assert text.count("\n") <= 1100, path.name
        isinstance_lines += sum("isinstance" in line for line in text.splitlines())
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                assert node.end_lineno is not None
                length = node.end_lineno - node.lineno + 1
                assert length <= 100, f"{path.name}: {node.name} is {length} lines"
    assert isinstance_lines <= 20


def test_every_model_class_declares_its_scene_file_tag_and_choices() -> None:
    assert set(flume.TAGS) == {*typing.get_args(flume.scene.Beach), *typing.get_args(
        flume.waves.Wave), *typing.get_args(flume.paddles.Paddle), *typing.get_args(
        flume_gauges.Gauge), *typing.get_args(flume.structures.Structure)}
    # a tag names a class among those one field takes (a beach and a structure may both be
    # a "mesh")
    for union in (flume.scene.Beach, flume.waves.Wave, flume.paddles.Paddle, flume_gauges.Gauge,
                  flume.structures.Structure):
        tags = [flume.TAGS[c] for c in typing.get_args(union)]
        assert len(set(tags)) == len(tags), union
    assert flume.TAGS[ws.RegularWave] == "regular" and flume.TAGS[ws.VelocityWindow] == "window"
    assert flume.CHOICES[(ws.IrregularWave, "spectrum")] == tuple(flume.SPECTRA)
    assert flume.CHOICES[(ws.RunupGauge, "method")] == flume.RUNUP_METHODS


def test_the_core_gauge_types_are_the_gauge_classes_tags() -> None:
    scene = ws.Flume(length=6.0, depth=0.3, beach=ws.PlaneBeach(toe=3.0, slope=0.1)).scene(
        ws.RegularWave(period=1.0, height=0.05), dp=0.03, until=1.0,
        gauges=[ws.ElevationGauge(1.0), ws.VelocityProbe(points=((1.0, 0.1),)),
                ws.VelocityWindow(min=(1.0, 0.05), max=(1.5, 0.2), n=(2, 2))])
    specs = scene.to_scene()["gauges"]
    gauges = [*scene.gauges, scene.runup_gauge]
    assert [flume.GAUGE_TYPES[s["type"]] for s in specs] == [type(g) for g in gauges]


def test_every_gauge_class_is_exported_from_its_own_file() -> None:
    """A gauge class is listed once, in ``gauges.__all__``; both packages export that list."""
    for cls in flume.GAUGE_TYPES.values():
        assert cls.__name__ in flume_gauges.__all__
        assert getattr(ws, cls.__name__) is cls
        assert getattr(flume, cls.__name__) is cls
    assert set(flume_gauges.__all__) <= set(ws.__all__) & set(flume.__all__)


@dataclasses.dataclass(frozen=True)
class _PointGauge(flume_gauges._Gauge):
    """A gauge kind the records do not know: its class alone says how it reads and writes."""

    name: str = "p0"
    TAG: ClassVar[str] = "point"

    @classmethod
    def csv_series(cls, gauges: flume.FlumeGauges) -> list[flume_gauges.Series]:
        return [(name, rec["t"], rec["value"]) for name, rec in gauges.records.items()]


def test_a_new_gauge_kind_needs_only_its_class(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setitem(flume_gauges.GAUGE_TYPES, _PointGauge.TAG, _PointGauge)
    scene = ws.Flume(length=4.0, depth=0.3).scene(
        ws.RegularWave(period=1.0, height=0.03), dp=0.03, until=1.0,
        gauges=[ws.ElevationGauge(1.0, name="eta")])
    t = [0.0, 0.5, 1.0]
    records: list[dict[str, Any]] = [
        {"type": "elevation", "name": "eta", "t": t, "z": [0.3, 0.31, 0.29]},
        {"type": "point", "name": "p0", "t": [0.0, 1.0], "value": [1.0, 3.0]},
    ]
    gauges = flume.FlumeGauges(scene, records)
    np.testing.assert_array_equal(gauges.records["p0"]["value"], [1.0, 3.0])
    assert gauges.columns() == ["t_s", "eta_m", "p0"]
    with open(gauges.to_csv(tmp_path / "gauges.csv"), encoding="utf-8") as f:
        rows = list(csv.reader(f))
    assert rows[0] == ["t_s", "eta_m", "p0"]
    assert [float(r[2]) for r in rows[1:]] == [1.0, 2.0, 3.0]
