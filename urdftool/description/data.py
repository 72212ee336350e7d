"""urdftool's own data files (``urdftool/data/``): facts extracted from upstream sources by the
scripts in ``scripts/``, read once per process."""

from __future__ import annotations

import functools
import json
import os
from pathlib import Path

from urdftool.description.files import read_own

FOLDER = Path(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))) / "data"
MAX_SIZE = 4 * 1024 * 1024  # [bytes]: the largest is 0.13 MB


@functools.lru_cache(maxsize=None)
def load(name: str) -> dict:
    """The JSON data file ``name`` of ``urdftool/data`` (urdftool's own: not in a check's
    record; the result cache's key stamps urdftool's files, these among them)."""
    data = read_own(FOLDER / name, MAX_SIZE)
    if data is None:
        raise OSError(f"urdftool's data file {FOLDER / name} cannot be read")
    return json.loads(data.decode("utf-8"))
