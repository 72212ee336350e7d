"""An output never replaces a file the command read (docs/attacks.md, session 8, second
wave): ``terminal.replaced_input`` refuses the words named before the work; what the command
read without being named (a robot a launch file builds, an include, a mesh, a companion, a
package.xml) is refused where the text leaves, by ``files.write_file``, from the files this
process read and those its workers report (``FileResult.read``). A rewrite meant (``inertia
--write`` over its URDF, ``collisions --write-srdf`` over the SRDF it updates) goes on."""

from __future__ import annotations

import struct
import subprocess
import sys
from pathlib import Path

import pytest

MESH = b"\0" * 80 + struct.pack("<I", 1) + struct.pack("<12f", 0, 0, 0, 0, 0, 0, 1, 0, 0, 0,
                                                          1, 0) + b"\0\0"
INERTIAL = ('<inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" '
            'ixz="0" iyz="0"/></inertial>')
ROBOT = f"""<?xml version="1.0"?>
<robot name="r">
  <link name="base"><visual><geometry><mesh filename="package://pkg/meshes/base.stl"/>
  </geometry></visual>{INERTIAL}</link>
  <link name="arm">{INERTIAL}</link>
  <joint name="j" type="fixed"><parent link="base"/><child link="arm"/></joint>
</robot>
"""
INCLUDED = f"""<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro name="lk" params="n">
<link name="${{n}}">{INERTIAL}</link></xacro:macro></robot>
"""
TOP = """<?xml version="1.0"?>
<robot name="t" xmlns:xacro="http://www.ros.org/wiki/xacro">
<xacro:include filename="inc.xacro"/><xacro:lk n="a"/><xacro:lk n="b"/>
<joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint></robot>
"""
LAUNCH = '<launch><param name="robot_description" textfile="$(find pkg)/urdf/robot.urdf"/></launch>\n'
PACKAGE = ('<package format="3"><name>pkg</name><version>0.0.0</version><description>x'
           '</description><maintainer email="a@b.c">a</maintainer><license>MIT</license>'
           '</package>\n')


@pytest.fixture
def repo(tmp_path) -> Path:
    for name, data in {"pkg/package.xml": PACKAGE, "pkg/urdf/robot.urdf": ROBOT,
                       "pkg/urdf/inc.xacro": INCLUDED, "pkg/urdf/top.urdf.xacro": TOP,
                       "pkg/launch/show.launch": LAUNCH, "pkg/meshes/base.stl": MESH}.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_bytes(data if isinstance(data, bytes) else data.encode())
    (tmp_path / ".git").mkdir()
    return tmp_path


def _run(repo: Path, *words: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "urdftool", *words], cwd=repo,
                          capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize("words, replaced", [
    (["check", "--no-cache", "pkg/launch/show.launch", "-o"], "pkg/urdf/robot.urdf"),
    (["check", "--no-cache", "pkg", "-o"], "pkg/meshes/base.stl"),
    (["check", "--no-cache", "pkg", "-o"], "pkg/package.xml"),
    (["check", "--no-cache", "pkg/urdf/robot.urdf", "-o"], "pkg/meshes/base.stl"),
    (["check", "--no-cache", "pkg/urdf/top.urdf.xacro", "-o"], "pkg/urdf/inc.xacro"),
    (["xacro", "pkg/urdf/top.urdf.xacro", "-o"], "pkg/urdf/inc.xacro"),
    (["diff", "pkg/urdf/robot.urdf", "pkg/urdf/top.urdf.xacro", "-o"], "pkg/urdf/inc.xacro"),
    (["inertia", "pkg/urdf/top.urdf.xacro", "--all", "--write"], "pkg/urdf/top.urdf.xacro"),
    (["inertia", "pkg/urdf/robot.urdf", "--all", "--write"], "pkg/meshes/base.stl"),
], ids=lambda value: " ".join(value) if isinstance(value, list) else value)
@pytest.mark.integration
def test_an_output_over_a_file_the_command_read_is_refused(repo, words, replaced):
    before = (repo / replaced).read_bytes()
    done = _run(repo, *words, replaced)
    assert done.returncode == 2, done.stderr
    assert "it is a file the command read" in done.stderr, done.stderr
    assert "Traceback" not in done.stderr, done.stderr
    assert (repo / replaced).read_bytes() == before


@pytest.mark.integration
def test_a_rewrite_meant_goes_on(repo):
    done = _run(repo, "inertia", "pkg/urdf/robot.urdf", "--all", "--write", "pkg/urdf/robot.urdf")
    assert done.returncode == 0, done.stderr
    done = _run(repo, "check", "--no-cache", "pkg/urdf/robot.urdf", "-o", "report.txt")
    assert done.returncode in (0, 1), done.stderr
    done = _run(repo, "check", "--no-cache", "pkg/urdf/robot.urdf", "-o", "report.txt")
    assert done.returncode in (0, 1), done.stderr  # a report written over the last one


@pytest.mark.integration
def test_an_srdf_update_over_an_include_shaped_as_an_srdf_is_refused(repo):
    # session 13: the grant of an SRDF's update was "any file but the robot": an include of
    # materials (nothing in it an SRDF lacks) was rewritten as an SRDF
    colours = repo / "pkg/urdf/colours.xacro"
    colours.write_text('<robot>\n  <material name="m"><color rgba="1 0 0 1"/></material>\n'
                       '</robot>\n')
    top = repo / "pkg/urdf/top.urdf.xacro"
    top.write_text(TOP.replace('<xacro:include filename="inc.xacro"/>',
                               '<xacro:include filename="inc.xacro"/>'
                               '<xacro:include filename="colours.xacro"/>'))
    before = colours.read_bytes()
    done = _run(repo, "collisions", "pkg/urdf/top.urdf.xacro", "--matrix", "--samples", "5",
                "--write-srdf", "pkg/urdf/colours.xacro")
    assert done.returncode == 2, done.stderr
    assert "it is a file the command read (as companion SRDF, include)" in done.stderr
    assert colours.read_bytes() == before
