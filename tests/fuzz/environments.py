"""Fuzz mode ``--environments``: the process urdftool runs in, and where its output goes.

Each case draws an environment (HOME unset, empty or relative; XDG_CACHE_HOME relative; odd
COLUMNS, LANG, TERM, NO_COLOR/FORCE_COLOR; CI set or not), a small memory budget or none, how
standard output and error are given (closed, /dev/full, a pipe), and an output target for a
writer (a name past NAME_MAX or PATH_MAX, a named pipe nobody reads, /dev/full, /dev/null, a
folder, a missing folder, a name with a line break), then one drawn command on a small robot
in a throw-away repository whose working folder holds a planted cache key
(``urdftool/key``, ``.cache/urdftool/key``). It runs ``python -m urdftool`` in a subprocess
(the environment and descriptors are the process's own) and holds (docs/attacks.md, session
8): it ends within the time limit, its exit status is 0, 1 or 2, standard error holds no
traceback, no raw control character and no Python warning's source line, and the planted key
is never read (a cache entry signed with it is never served).

A failing case is kept as ``env-<hash>.json`` in tests/fuzz/regressions and replayed by
tests/integration/test_fuzz_output.py.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from hypothesis import strategies as st

from .harness import REGRESSIONS

ROBOT = """<robot name="r"><link name="a"/><link name="b">
<collision><geometry><box size="1 1 1"/></geometry></collision></link>
<joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
<limit lower="1" upper="-1" effort="1" velocity="1"/></joint></robot>
"""
PLANTED_KEY = "ab" * 32
ENVIRONMENTS = {
    "HOME": [None, "", ".", "relative/home", "/nonexistent", "/proc"],
    "XDG_CACHE_HOME": [None, "", ".", "cache"],
    "COLUMNS": [None, "0", "-5", "abc", "1", "99999999999"],
    "LANG": [None, "C", "POSIX", "xx_YY.BOGUS"],
    "TERM": [None, "dumb", "\x1b]0;x\x07"],
    "NO_COLOR": [None, "1"],
    "FORCE_COLOR": [None, "1"],
    "CI": [None, "true"],
}
STREAMS = ["pipe", "stdout closed", "stdout /dev/full", "stderr closed", "both closed"]
TARGETS = ["x" * 300 + ".txt", "/".join(["y" * 200] * 25) + ".txt", "<fifo>", "/dev/full",
           "/dev/null", "<folder>", "missing/out.txt", "a\nb.txt", "out.txt"]
COMMANDS = [["check", "robot.urdf"], ["check", "."], ["check", "robot.urdf", "-f", "json"],
            ["check", "robot.urdf", "-f", "sarif"], ["check", "robot.urdf", "-f", "github"],
            ["tree", "robot.urdf"], ["fk", "robot.urdf"], ["xacro", "robot.urdf"],
            ["graph", "robot.urdf"], ["inertia", "robot.urdf"], ["rules"],
            ["diff", "robot.urdf", "robot.urdf"]]
WRITERS = {"check", "tree", "fk", "xacro", "diff", "rules"}  # commands that take -o FILE
MEMORY = [None, "20M", "1K", "300M"]


@st.composite
def cases(draw):
    environ = {name: draw(st.sampled_from(values)) for name, values in ENVIRONMENTS.items()}
    command = draw(st.sampled_from(COMMANDS))
    target = draw(st.sampled_from(TARGETS)) if command[0] in WRITERS and draw(
        st.booleans()) else None
    memory = draw(st.sampled_from(MEMORY)) if command[0] != "rules" else None
    return {"environ": environ, "command": command, "target": target, "memory": memory,
            "streams": draw(st.sampled_from(STREAMS))}


def _redirections(streams: str) -> dict:
    """Keyword arguments of subprocess.run for how the case's streams are given."""
    if streams == "pipe":
        return {"stdout": subprocess.PIPE, "stderr": subprocess.PIPE}
    full = open(os.devnull if "full" not in streams else "/dev/full", "wb")  # noqa: SIM115
    return {"stdout": subprocess.DEVNULL if "closed" in streams and "stderr" not in streams
            else full if "full" in streams else subprocess.PIPE,
            "stderr": subprocess.PIPE if streams != "both closed" else subprocess.DEVNULL}


def run_case(case: dict, time_limit: float = 90.0) -> list[str]:
    """The problems of one case (empty when it holds)."""
    root = Path(tempfile.mkdtemp(prefix="urdffuzz-env-"))
    try:
        (root / ".git").mkdir()
        (root / "robot.urdf").write_text(ROBOT)
        for planted in (root / "urdftool", root / ".cache" / "urdftool",
                        root / "cache" / "urdftool"):
            planted.mkdir(parents=True)
            (planted / "key").write_text(PLANTED_KEY)
        argv = [sys.executable, "-m", "urdftool", *case["command"]]
        if case["memory"]:
            argv += ["--max-memory", case["memory"]]
        target = case["target"]
        if target == "<fifo>":
            os.mkfifo(root / "report.fifo")
            target = "report.fifo"
        elif target == "<folder>":
            target = str(root)
        if target is not None:
            argv += ["-o", target]
        environ = {key: value for key, value in os.environ.items()
                   if key not in ENVIRONMENTS and not key.startswith("URDFTOOL")}
        environ.update({k: v for k, v in case["environ"].items() if v is not None})
        environ["PYTHONPATH"] = os.pathsep.join(sys.path[:1] + [str(Path(__file__).parents[2])])
        streams = case["streams"]
        keywords = _redirections(streams)
        if "stdout closed" in streams or streams == "both closed":
            argv = ["sh", "-c", '"$@" >&-' + (" 2>&-" if streams == "both closed" else ""),
                    "sh", *argv]
        started = time.monotonic()
        try:
            done = subprocess.run(argv, cwd=root, env=environ, timeout=time_limit, **keywords)
        except subprocess.TimeoutExpired:
            return [f"hang: {case['command']} did not end within {time_limit} s"]
        problems = []
        stderr = (done.stderr or b"").decode("utf-8", "replace")
        if done.returncode not in (0, 1, 2):
            problems.append(f"exit: {done.returncode}: {stderr[-300:]}")
        if "Traceback (most recent call last)" in stderr:
            problems.append(f"traceback: {stderr[-400:]}")
        if re.search(r"\.py:\d+: \w*Warning", stderr):
            problems.append(f"warning: a Python warning printed raw: {stderr[-300:]}")
        shown = re.sub("\x1b\\[[0-9;]*m", "", stderr) if case["environ"].get("FORCE_COLOR") \
            else stderr  # (colours asked for)
        if re.search("[\x00-\x08\x0b-\x1f\x7f]", shown):
            problems.append(f"control: a raw control character on standard error: "
                            f"{stderr[-300:]!r}")
        cache = root / ".urdftool_cache"
        if cache.is_dir() and any(cache.rglob("*.json")) and case["environ"].get("HOME") in (
                ".", "relative/home") and case["environ"].get("XDG_CACHE_HOME") in (
                None, "", ".", "cache"):
            problems.append("key: entries kept with no absolute place for the signing key "
                            "(the planted one was taken)")
        if time.monotonic() - started > time_limit:
            problems.append("hang: over the time limit")
        return problems
    finally:
        shutil.rmtree(root, ignore_errors=True)


def save(case: dict, problems: list[str]) -> Path:
    data = {"mode": "environments", "case": case, "found": problems[:20]}
    digest = hashlib.sha256(json.dumps(case, sort_keys=True).encode()).hexdigest()
    REGRESSIONS.mkdir(exist_ok=True)
    path = REGRESSIONS / f"env-{digest[:12]}.json"
    path.write_text(json.dumps(data, indent=1, ensure_ascii=True) + "\n")
    return path


def replay(path: Path) -> list[str]:
    return run_case(json.loads(path.read_text())["case"])


def run(count: int, seed: int = 0, keep: bool = True) -> dict:
    """``count`` cases; figures: cases, failures, seconds."""
    from .run import drive

    def attempt(drawn, stats):
        problems = run_case(drawn)
        return problems, lambda: save(drawn, problems)

    return drive(cases(), attempt, count, seed, keep)
