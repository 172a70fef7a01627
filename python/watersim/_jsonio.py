"""Strict JSON output shared by the run outputs, the command line, the stress matrix and the
validation sweep."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

from ._files import write_text_atomic


def json_ready(value: Any) -> Any:
    """NumPy values as Python ones and non-finite floats as None (strict JSON)."""
    if isinstance(value, dict):
        return {str(k): json_ready(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_ready(v) for v in value]
    if hasattr(value, "tolist"):
        return json_ready(value.tolist())
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def write_json_atomic(path: Path, data: Any, indent: int) -> None:
    """Write ``data`` (made :func:`json_ready`) to ``path`` atomically
    (:func:`watersim._files.atomic_path`), so a crash leaves the previous version."""
    write_text_atomic(path, json.dumps(json_ready(data), indent=indent, allow_nan=False) + "\n")
