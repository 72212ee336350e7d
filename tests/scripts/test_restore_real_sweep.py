"""scripts/restore_real_sweep.py: one restore at a time writes into a destination."""

from __future__ import annotations

import fcntl
import importlib.util
import sys
import threading
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _script():
    spec = importlib.util.spec_from_file_location(
        "restore_real_sweep", ROOT / "scripts" / "restore_real_sweep.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules.setdefault(spec.name, module)  # its dataclasses look their module up
    spec.loader.exec_module(module)
    return module


def test_a_second_restore_waits_for_the_first(tmp_path, capsys):
    # Two restores at once removed each other's files from a folder that one then stamped as
    # current (session 22, a machine restored by two helpers).
    restore = _script()
    manifest = tmp_path / "MANIFEST.tsv"
    manifest.write_text("repository\tcommit\n", encoding="utf-8")
    dest = tmp_path / "sweep"
    dest.mkdir()
    words = ["--mirror", str(tmp_path / "mirror"), "--dest", str(dest),
             "--manifest", str(manifest)]
    codes = []
    with open(dest / ".restore.lock", "ab") as held:
        fcntl.flock(held, fcntl.LOCK_EX)
        second = threading.Thread(target=lambda: codes.append(restore.main(words)))
        second.start()
        second.join(1.0)
        assert second.is_alive() and not codes, "the second restore ran beside the first"
        fcntl.flock(held, fcntl.LOCK_UN)
    second.join(30)
    assert codes == [0]
    assert "another restore is writing into" in capsys.readouterr().err
