"""The lowest versions pyproject.toml allows are versions urdftool works with (session 21).

A user's environment keeps what it has when it satisfies the ranges: the lower bounds are a
promise. They were not kept: typer 0.24 and 0.25 have no ``typer._click`` (vendored from 0.26),
so every command Typer runs ended in a traceback; with numpy 2 (allowed, and what the analysis
extra's Pinocchio needs) trimesh before 4.4 loaded no mesh (``ndarray.ptp``), python-fcl before
0.7.0.7 and pybullet before 3.2.7 did not import (built for numpy 1); Pinocchio 2.7 has no
``Frame.parentJoint``, Pillow 10.0 no ``load_default(size=)``; MuJoCo before 3.7 and trimesh
before 5.2 read files otherwise (the crosscheck's messages, a COLLADA file recovered).

uv installs urdftool with the lowest allowed version of each direct dependency
(``--resolution lowest-direct``, wheels only, as a machine without compilers would) into fresh
virtual environments: the lint-only install, whose lowest numpy is a 1.x, and the ``analysis``
extra, whose lowest Pinocchio needs numpy 2. Each answers as urdftool answers here, with the
newest versions: the same findings on the bundled robots and on every case, the same output of
the analysis commands, and never a Python warning or a traceback. Marked ``network``: uv asks
the package index (what it downloads once stays in its cache), and ``slow``: a cold cache
downloads about a gigabyte, which `make test` (kept under four minutes) does not pay; run it
with `make test-lowest` after changing a bound.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import CASES, ROBOTS, ROOT

UV = Path(sys.executable).parent / "uv"
# what a lint-only install cannot import, hidden from this interpreter (tests/test_extras.py)
HIDE = ("import sys; sys.modules.update(pinocchio=None, fcl=None, yourdfpy=None, PIL=None); "
        "sys.argv = ['urdftool', *sys.argv[1:]]; from urdftool.cli import main; main()")

pytestmark = [pytest.mark.network, pytest.mark.slow,  # minutes of downloads: `make test-lowest`
              pytest.mark.skipif(not UV.is_file(), reason="uv is not beside this Python (make)")]


@pytest.fixture(scope="module")
def lowest(tmp_path_factory):
    """The Python of a fresh environment holding urdftool with ``extra`` at the lowest versions
    of its direct dependencies."""
    made = {}

    def python(extra: str) -> str:
        if extra not in made:
            folder = tmp_path_factory.mktemp(f"lowest-{extra or 'lint'}")
            subprocess.run([UV, "venv", "--quiet", "--python", sys.executable, folder],
                           check=True, capture_output=True, timeout=300)
            done = subprocess.run(
                [UV, "pip", "install", "--quiet", "--python", folder / "bin" / "python",
                 "--resolution", "lowest-direct", "--no-build",
                 "-e", f"{ROOT}[{extra}]" if extra else ROOT], capture_output=True, text=True,
                timeout=900)
            assert done.returncode == 0, done.stderr
            made[extra] = str(folder / "bin" / "python")
        return made[extra]

    return python


def run(python: list[str], *words, cwd=ROOT):
    environ = {key: value for key, value in os.environ.items()
               if not key.startswith(("URDFTOOL", "PYTHON"))}
    return subprocess.run([*python, *map(str, words)], capture_output=True, text=True,
                          timeout=600, cwd=cwd, env={**environ, "COLUMNS": "100"})


def findings(done) -> list:
    assert done.returncode in (0, 1, 2), done.stderr  # 2: a case's package is not installed
    return [(f["file"], f["line"], f["code"], f["message"])
            for f in json.loads(done.stdout)["diagnostics"]]


def test_the_lint_only_install_finds_what_the_newest_finds(lowest):
    python = lowest("")
    versions = run([python, "-c", "import numpy; print(numpy.__version__)"])
    assert versions.stdout.startswith("1."), versions.stdout  # numpy 1.x is allowed: tried
    words = ["check", ROBOTS, CASES, "-f", "json", "--no-cache", "--jobs", "1"]
    old = run([python, "-W", "error", "-m", "urdftool", *words])
    assert "Traceback" not in old.stderr and "Warning" not in old.stderr, old.stderr
    assert findings(old) == findings(run([sys.executable, "-c", HIDE, *words]))


@pytest.mark.parametrize("words", [
    ["tree", "r2d2/r2d2.urdf.xacro"],
    ["fk", "r2d2/r2d2.urdf.xacro"],
    ["dynamics", "humanoid/humanoid.urdf.xacro", "--samples", "5"],
    ["collisions", "r2d2/r2d2.urdf.xacro"],
    ["inertia", "humanoid/humanoid.urdf.xacro"],
    ["render", "r2d2/r2d2.urdf.xacro", "-o", os.devnull],
    ["fk", "r2d2/r2d2.urdf.xacro", "--bogus"],
])
def test_the_analysis_commands_answer_as_with_the_newest(lowest, words):
    old = run([lowest("analysis"), "-W", "error", "-m", "urdftool", *words], cwd=ROBOTS)
    new = run([sys.executable, "-m", "urdftool", *words], cwd=ROBOTS)
    assert "Traceback" not in old.stderr, old.stderr
    assert (old.returncode, old.stdout, old.stderr) == (new.returncode, new.stdout, new.stderr)
