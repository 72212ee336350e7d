"""urdftool's own data files (``urdftool/data/``): facts extracted from upstream sources by the
scripts in ``scripts/``, read once per process."""

from __future__ import annotations

import functools
import json
import os
import re
from collections.abc import Mapping
from pathlib import Path

from urdftool.description.files import read_own

FOLDER = Path(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))) / "data"
MAX_SIZE = 4 * 1024 * 1024  # [bytes]: the largest is 0.13 MB


@functools.lru_cache(maxsize=None)
def load(name: str, lazy: str | None = None) -> dict:
    """The JSON data file ``name`` of ``urdftool/data`` (urdftool's own: not in a check's
    record; the result cache's key stamps urdftool's files, these among them). ``lazy``: a
    table of the file whose entries are decoded when first asked (:class:`Table`: a check
    reads a few of ros2_controllers' 69 schemas), when the file is laid out as the scripts
    write it; else the file is decoded whole."""
    data = read_own(FOLDER / name, MAX_SIZE)
    if data is None:
        raise OSError(f"urdftool's data file {FOLDER / name} cannot be read")
    text = data.decode("utf-8")
    found = _with_lazy_table(text, lazy) if lazy is not None else None
    return json.loads(text) if found is None else found


class Table(Mapping):
    """A table of a data file, each entry decoded from its text when first asked."""

    def __init__(self, text: str, spans: dict):
        self._text, self._spans, self._decoded = text, spans, {}

    def __getitem__(self, key):
        try:
            return self._decoded[key]
        except KeyError:
            start, end = self._spans[key]
            value = self._decoded[key] = json.loads(self._text[start:end])
            return value

    def __contains__(self, key) -> bool:
        return key in self._spans

    def __iter__(self):
        return iter(self._spans)

    def __len__(self) -> int:
        return len(self._spans)


# an entry of a table the scripts write (their dump(): a table's entries on lines of their own,
# four spaces in, below a top-level key two spaces in; a string holds no line break)
_ENTRY = re.compile(r'\n    ("(?:[^"\\\n]|\\.)*"): ')


def _with_lazy_table(text: str, table: str) -> dict | None:
    """The document ``text`` decoded but for its top-level ``table``, a :class:`Table` of it;
    None when the text is not laid out as the scripts write it (then decoded whole)."""
    head = f"\n  {json.dumps(table)}: {{\n"
    start = text.find(head)
    end = text.find("\n  }", start + len(head)) if start >= 0 else -1
    if end < 0:
        return None
    document = json.loads(f"{text[:start]}\n  {json.dumps(table)}: {{}}{text[end + 4:]}")
    marks = list(_ENTRY.finditer(text, start + len(head) - 1, end))
    spans = {}
    for mark, following in zip(marks, [*marks[1:], None]):
        value = text[mark.end():following.start() if following else end].rstrip()
        spans[json.loads(mark.group(1))] = (mark.end(), mark.end() + len(value.removesuffix(",")))
    document[table] = Table(text, spans)
    return document
