"""Python warnings leave urdftool as one escaped line (docs/attacks.md, session 8). numpy
warned on a mesh of 1e38 and NaN vertices (``RuntimeWarning: invalid value encountered in
cast``) and Python printed it with its source file and line, raw, on standard error of
``check``, ``collisions``, ``render``; a library warning quoting a file's text would have
printed its line breaks and escape sequences as they were. ``streams.guard``, which every
way urdftool runs goes through, routes ``warnings.showwarning`` through the escaper."""

from __future__ import annotations

import re
import subprocess
import sys

MESH_ROBOT = """<robot name="m"><link name="base"/>
<link name="l"><collision><geometry><mesh filename="huge.stl"/></geometry></collision></link>
<joint name="j" type="fixed"><parent link="base"/><child link="l"/></joint></robot>
"""
FACET = ("facet normal nan nan nan\nouter loop\nvertex 1e38 1e38 1e38\n"
         "vertex -1e38 -1e38 -1e38\nvertex 1e38 -1e38 1e38\nendloop\nendfacet\n")


def test_a_warning_is_one_escaped_line():
    code = ("from urdftool import streams\nstreams.guard()\nimport warnings\n"
            "warnings.warn('quoted\\n::error::forged\\x1b[2J')\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=60)
    lines = done.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("urdftool: warning: UserWarning: "), lines
    assert "\x1b" not in done.stderr and "\\n::error::" in done.stderr


def test_a_mesh_numpy_warns_about_prints_no_source_line(tmp_path):
    (tmp_path / ".git").mkdir()
    (tmp_path / "m.urdf").write_text(MESH_ROBOT)
    (tmp_path / "huge.stl").write_text("solid x\n" + FACET * 10 + "endsolid\n")
    done = subprocess.run([sys.executable, "-m", "urdftool", "check", "m.urdf", "--no-cache"],
                          capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert done.returncode in (0, 1), done.stderr
    for line in done.stderr.splitlines():
        assert line.startswith("urdftool: "), done.stderr  # no "  return (vertices * ..."
    assert not re.search(r"\.py:\d+: \w*Warning", done.stderr), done.stderr
