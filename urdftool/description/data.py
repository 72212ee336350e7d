"""urdftool's own data files (``urdftool/data/``): facts extracted from upstream sources by the
scripts in ``scripts/``, read once per process."""

from __future__ import annotations

import functools
import json
from pathlib import Path

from urdftool.description.files import read_regular

FOLDER = Path(__file__).resolve().parents[1] / "data"
MAX_SIZE = 4 * 1024 * 1024  # [bytes]: the largest is 0.13 MB


@functools.lru_cache(maxsize=None)
def load(name: str) -> dict:
    """The JSON data file ``name`` of ``urdftool/data``."""
    return json.loads(read_regular(FOLDER / name, MAX_SIZE).decode("utf-8"))
