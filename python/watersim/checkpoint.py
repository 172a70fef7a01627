"""Checkpoint and restart: save a run's full state to a ``.npz`` file and continue it exactly.

A checkpoint holds the particle state in the solver's storage order, the integrator's history
(Verlet), the stability monitors' baselines and every gauge record; the paddle's motion law is a
function of time and needs nothing more. A run continued from a checkpoint reaches the same
``state_sha256`` as the run that never stopped (``crates/sph-core/tests/stability.rs``,
``tests/test_checkpoint.py``). The scene itself is stored too, as JSON, so that
:func:`load_checkpoint` can rebuild the simulation.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np

from ._core import SceneError
from .simulation import Simulation

__all__ = ["load_checkpoint", "save_checkpoint"]

_ARRAYS = ("positions", "velocities", "densities", "ids", "kinds", "velocities_prev", "densities_prev")
_SCALARS = ("time", "steps", "dt", "n_excluded")


def save_checkpoint(sim: Simulation, path: str | Path) -> Path:
    """Writes the state of ``sim`` to ``path`` (``.npz``); returns the path written."""
    state = sim.core.checkpoint()
    data: dict[str, Any] = {key: state[key] for key in _ARRAYS}
    for key in _SCALARS:
        data[key] = np.asarray(state[key])
    data["energy0"] = np.asarray(state["energy0"], dtype=np.float64)
    data["scene_json"] = np.asarray(json.dumps(sim.scene))
    data["n_gauges"] = np.asarray(len(state["gauges"]))
    for i, gauge in enumerate(state["gauges"]):
        data[f"gauge{i}_t"] = gauge["t"]
        data[f"gauge{i}_values"] = gauge["values"]
        data[f"gauge{i}_next_time"] = np.asarray(gauge["next_time"])
    path = Path(path)
    # write then rename, so an interrupted save never leaves a truncated checkpoint behind
    tmp = path.with_name(path.name + ".tmp.npz")
    np.savez(tmp, **data)
    tmp.replace(path)
    return path


def load_checkpoint(path: str | Path, sim: Simulation | None = None) -> Simulation:
    """Continues a run from ``path``: into ``sim`` when given (it must be built from the same
    scene), else into a new simulation built from the scene stored in the checkpoint.

    Raises:
        SceneError: the file is not a WaterSim checkpoint, or belongs to another scene.
    """
    with np.load(Path(path), allow_pickle=False) as f:
        if "scene_json" not in f:
            raise SceneError(f"checkpoint: {path} is not a WaterSim checkpoint (no scene_json)")
        if sim is None:
            sim = Simulation(str(f["scene_json"]))
        state: dict[str, Any] = {key: np.asarray(f[key]) for key in _ARRAYS}
        state["time"] = float(f["time"])
        state["steps"] = int(f["steps"])
        state["dt"] = float(f["dt"])
        state["n_excluded"] = int(f["n_excluded"])
        state["energy0"] = tuple(float(v) for v in f["energy0"])
        state["gauges"] = [
            {
                "t": np.asarray(f[f"gauge{i}_t"]),
                "values": np.asarray(f[f"gauge{i}_values"]),
                "next_time": float(f[f"gauge{i}_next_time"]),
            }
            for i in range(int(f["n_gauges"]))
        ]
    sim.core.restore(state)
    return sim
