"""``python -m urdftool`` is the command line, as the ``urdftool`` script is."""

from __future__ import annotations

import subprocess
import sys

from conftest import ROOT


def _module(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "urdftool", *args], capture_output=True,
                          text=True, cwd=ROOT, timeout=120)


def test_python_m_urdftool_runs_the_command_line():
    version = _module("--version")
    assert version.returncode == 0 and version.stdout.startswith("urdftool "), version.stderr
    assert "Usage: urdftool" in _module("--help").stdout
    broken = _module("check", "--timeout", "0", "tests/cases/U204_inverted_limits.urdf")
    assert broken.returncode == 1 and "U204" in broken.stdout, broken.stdout + broken.stderr
