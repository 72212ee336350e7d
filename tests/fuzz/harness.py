"""Run one fuzz case through the check engine in-process and list what went wrong.

Invariants: no traceback escapes, no U900 (a crash inside urdftool), no hang, every file that
fails to load has at least one error with a line, and nothing from /etc/passwd reaches output.
"""

from __future__ import annotations

import hashlib
import json
import signal
from pathlib import Path

from urdftool.engine import CheckOptions, check_file

from .mutate import CORPUS, ROOT, Seed

REGRESSIONS = Path(__file__).resolve().parent / "regressions"
HANG_SECONDS = 60
_UNLOCATED_OK = {"U008"}  # file-too-large is about the whole file


class _Hang(Exception):
    pass


def _alarm(signum, frame):
    raise _Hang()


def problems(seed: Seed, data: bytes) -> list[str]:
    """What this case violates (empty when it behaves)."""
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(HANG_SECONDS)
    try:
        result = check_file(str(seed.path), CheckOptions(xacro_args=dict(seed.args),
                                                         allow_env=False), data=data)
    except _Hang:
        return [f"hang: over {HANG_SECONDS} s"]
    except BaseException as error:  # the point of the harness
        return [f"traceback: {type(error).__name__}: {error}"]
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)
    found = []
    for finding in result.findings:
        if finding.code == "U900":
            found.append(f"U900 at {finding.location}: {finding.message}")
        if "root:x:0:0" in finding.message:
            found.append(f"/etc/passwd leaked into {finding.code}")
    if result.robot is None:
        located = [f for f in result.findings if f.severity.value == "error"
                   and (f.line is not None or f.code in _UNLOCATED_OK)]
        if not located:
            found.append("load failed without a located error: "
                         + "; ".join(f"{f.code} {f.location}" for f in result.findings))
    elif "root:x:0:0" in result.robot.urdf:
        found.append("/etc/passwd leaked into the expanded URDF")
    return found


def save_regression(seed: Seed, data: bytes, why: list[str]) -> Path:
    """Keep a failing input as tests/fuzz/regressions/<hash>.bin plus a .json describing it."""
    REGRESSIONS.mkdir(exist_ok=True)
    digest = hashlib.sha256(data).hexdigest()[:12]
    path = REGRESSIONS / f"{digest}.bin"
    path.write_bytes(data)
    meta = {"seed": _portable(seed.path), "args": {k: _portable_text(v) for k, v in seed.args.items()},
            "found": why}
    path.with_suffix(".json").write_text(json.dumps(meta, indent=1) + "\n")
    return path


def load_regression(path: Path) -> tuple[Seed, bytes]:
    meta = json.loads(path.with_suffix(".json").read_text())
    seed_path = Path(meta["seed"].replace("<corpus>", str(CORPUS)).replace("<root>", str(ROOT)))
    args = {k: v.replace("<corpus>", str(CORPUS)) for k, v in meta["args"].items()}
    return Seed(seed_path, args), path.read_bytes()


def _portable(path: Path) -> str:
    return _portable_text(str(path))


def _portable_text(text: str) -> str:
    return text.replace(str(CORPUS), "<corpus>").replace(str(ROOT), "<root>")
