"""A memory budget too small for a worker to start (docs/attacks.md, session 8): under
``--max-memory 20M`` (or ``max-memory = "20M"`` in a repository's settings, which may lower
the budget) every analysis command's worker failed to import a module (the system refuses to
map its shared library under the cap: ImportError, not MemoryError) and printed a traceback.
``pool.out_of_memory`` classes such failures with MemoryError: the piece stops with U018."""

from __future__ import annotations

import errno
import subprocess
import sys

import pytest


ROBOT = """<robot name="r"><link name="a"/><link name="b"/>
<joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>
"""


@pytest.mark.parametrize("command", [["tree"], ["fk"], ["inertia"], ["dh", "--base", "a",
                                                                         "--tip", "b"]])
def test_a_budget_too_small_to_start_is_u018_not_a_traceback(tmp_path, command):
    robot = tmp_path / "robot.urdf"
    robot.write_text(ROBOT)
    done = subprocess.run([sys.executable, "-m", "urdftool", command[0], str(robot),
                           *command[1:], "--max-memory", "20M"], capture_output=True,
                          text=True, timeout=120, cwd=tmp_path, env={"PATH": "/usr/bin:/bin",
                                                                    "URDFTOOL_NO_CACHE": "1"})
    assert "Traceback" not in done.stderr + done.stdout, done.stderr
    assert done.returncode == 1 and "U018" in done.stdout + done.stderr, done.stdout


def test_what_the_memory_cap_causes_is_out_of_memory():
    from urdftool.lint.pool import out_of_memory

    assert out_of_memory(ImportError("/x/pyexpat.so: failed to map segment from shared object"))
    assert out_of_memory(OSError(errno.ENOMEM, "Cannot allocate memory"))
    assert not out_of_memory(ImportError("No module named 'pinocchio'"))
    assert not out_of_memory(OSError(errno.ENOENT, "No such file or directory"))
    # Python 3.11's call refused at the cap (tests/lint/test_engine.py); without a cap, a bug
    assert not out_of_memory(SystemError("error return without exception set"))


def test_a_small_budget_leaves_numpy_no_way_to_end_the_worker(tmp_path):
    """OpenBLAS maps its buffers at numpy's import and at its first large product, and ends the
    process (exit code 1) when the cap refuses them: the worker died, U900 "internal error"
    in place of U018 (a 150 MiB budget on the corpus: 48 of them). budget.limit_memory maps
    them before it sets a small cap: what does not fit is Python's MemoryError."""
    script = tmp_path / "capped.py"
    script.write_text("from urdftool import budget\n"
                      "budget.limit_memory(100 << 20)\n"
                      "try:\n"
                      "    import numpy as np\n"
                      "    np.ones((300, 300)) @ np.ones((300, 300))\n"
                      "except MemoryError:\n"
                      "    pass\n"
                      "print('alive')\n")
    done = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                          timeout=120, env={"PATH": "/usr/bin:/bin"})
    assert done.returncode == 0 and done.stdout == "alive\n", (done.returncode, done.stderr)
