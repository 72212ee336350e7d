"""U620 (launch-file-not-read) over a folder check: the launch files a robot's repository holds
that could not be read say so, at the launch file."""

from __future__ import annotations

import shutil

import pytest

from conftest import CASES


def _folder(tmp_path, launch_text: str):
    """The U620 case copied, its launch file replaced by ``launch_text`` (a Python one)."""
    folder = tmp_path / "pkg"
    shutil.copytree(CASES / "U620_launch_file_not_read", folder)
    (folder / "launch" / "pan.launch.xml").unlink()
    (folder / "launch" / "pan.launch.py").write_text(launch_text)
    return folder


GOOD = '''from launch import LaunchDescription
from launch.substitutions import Command, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare
{extra}

def generate_launch_description():
    share = FindPackageShare("case_unread_launch")
    description = Command(["xacro ", PathJoinSubstitution([share, "pan.urdf.xacro"])])
    return LaunchDescription([
        Node(package="controller_manager", executable="ros2_control_node",
             parameters=[{{"robot_description": description}},
                         PathJoinSubstitution([share, "params", "ctrl.yaml"])]),
    ])
'''


def _checked(folder):
    from urdftool.lint.runner import check_paths
    from urdftool.lint.settings import CheckRequest

    run = check_paths([str(folder)], CheckRequest(jobs=1))
    return [finding for result in run.results for finding in result.findings]


def test_a_python_launch_file_ast_cannot_parse_is_a_note_in_a_folder_check(tmp_path):
    """Session 11 left it: an attribute chain 200,000 long (RecursionError in ``ast``) dropped
    the launch file from a folder check without a word, and the controllers YAML only it loads
    with it. Read, the same file loads it; not read, a note says so, at the file."""
    assert not [f for f in _checked(_folder(tmp_path / "read", GOOD.format(extra=""))) if f.code == "U620"]
    deep = "X = a" + ".b" * 200_000
    found = [f for f in _checked(_folder(tmp_path / "deep", GOOD.format(extra=deep)))
             if f.code == "U620"]
    assert [(f.location.file.endswith("launch/pan.launch.py"), f.location.line, f.severity.value)
            for f in found] == [(True, None, "info")]
    assert "RecursionError" in found[0].message and "not checked" in found[0].message


def test_a_launch_file_with_a_syntax_error_is_located_at_its_line(tmp_path):
    found = [f for f in _checked(_folder(tmp_path, GOOD.format(extra="\n\nif x:\nfoo(")))
             if f.code == "U620"]
    assert [(f.location.line, "not valid Python" in f.message) for f in found] == [(8, True)]


OUTSIDE = '''<launch>
  <let name="robot_description" value="$(command 'xacro $(find-pkg-share case_unread_launch)/pan.urdf.xacro')"/>
  <node pkg="robot_state_publisher" exec="robot_state_publisher">
    <param name="robot_description" value="$(var robot_description)"/>
  </node>
  <node pkg="controller_manager" exec="ros2_control_node">
    <param from="$(dirname)/../../../outside/ctrl.yaml"/>
    <param from="$(find-pkg-share case_unread_launch)/params/linked.yaml"/>
    <param from="$(find-pkg-share case_unread_launch)/params/ctrl.yaml"/>
    <param from="$(find-pkg-share not_here)/params/ctrl.yaml"/>
  </node>
  <include file="/etc/hostname"/>
</launch>
'''


def test_a_file_a_launch_file_names_outside_the_repository_is_a_note_naming_it(tmp_path):
    """A controller YAML at ``$(dirname)/../../../outside/ctrl.yaml``, one inside through a link
    leading out, an include of ``/etc/hostname``: none is read (containment), and each was
    left out without a word. A note at each line, naming the path as written; a package not
    in the repository (``$(find-pkg-share not_here)``) is not known, not outside: nothing."""
    import os

    folder = tmp_path / "repo" / "pkg"
    shutil.copytree(CASES / "U620_launch_file_not_read", folder)
    (tmp_path / "repo" / ".git").mkdir()
    (tmp_path / "outside").mkdir()
    shutil.copy(folder / "params" / "ctrl.yaml", tmp_path / "outside" / "ctrl.yaml")
    os.symlink(tmp_path / "outside" / "ctrl.yaml", folder / "params" / "linked.yaml")
    (folder / "launch" / "pan.launch.xml").write_text(OUTSIDE)
    found = [f for f in _checked(folder) if f.code == "U620"]
    assert [(f.location.line, f.message.split("'")[1]) for f in found] == [
        (7, "$(dirname)/../../../outside/ctrl.yaml"),
        (8, "$(find-pkg-share case_unread_launch)/params/linked.yaml"), (12, "/etc/hostname")]
    assert all(f.location.file.endswith("launch/pan.launch.xml") and f.severity.value == "info"
               and "leads outside the repository: not read" in f.message for f in found)


NAMING = ('<launch>\n<let name="robot_description" value="$(command \'xacro '
          '$(find-pkg-share case_unread_launch)/pan.urdf.xacro\')"/>\n')


@pytest.mark.parametrize("name, data, said, line", [
    ("a.launch.xml", b'<!DOCTYPE launch [\n<!ENTITY e "x">]>\n' + NAMING.encode() + b"</launch>\n",
     "not read: entity declaration 'e' refused: urdftool reads no XML that declares entities", 2),
    ("b.launch.xml", b"<!DOCTYPE launch SYSTEM 'http://x/y.dtd'>\n" + NAMING.encode()
     + b"</launch>\n", "not read: external DTD 'http://x/y.dtd' refused", 1),
    ("c.launch.xml", NAMING.encode() + b"<group>" * 300 + b"</group>" * 300 + b"</launch>",
     "not read: elements nested deeper than 256 levels", 3),
    ("d.launch.xml", NAMING.encode() + b"\x00</launch>\n", "not read: file is binary", 1),
    ("e.launch.xml", NAMING.encode() + b"<arg name='\xff'/></launch>\n",
     "not UTF-8 text: byte 0xff on line 3", 3),
    ("f.launch.xml", NAMING.encode() + b"<arg></launch>\n", "not well-formed XML: mismatched", 3),
    ("g.launch.yaml", b"launch: [\n - {include: {file: pan.urdf.xacro}}\n",
     "not valid YAML: expected the node content", 2),
    ("h.launch.xml", NAMING.encode() + b"<!--" + b"x" * 600_000 + b"--></launch>\n",
     "larger than 524288 bytes; not read", None),
    ("i.launch.yaml", b"launch: []\n# pan.urdf.xacro " + b"x" * 600_000 + b"\n",
     "larger than 524288 bytes; not read", None),
])
def test_each_launch_file_not_read_is_said_with_its_own_cause_at_its_line(tmp_path, name, data,
                                                                         said, line):
    """An entity declared, an external DTD, nesting past 256 levels and NUL bytes were all
    "not well-formed XML", and said that robot descriptions may not declare entities; a byte
    that is not UTF-8 was Python's codec error at a byte position; a YAML launch file's error
    was the parser's words alone, without its line, and it was read up to 16 MiB where every
    other launch file stops at 512 KiB; a launch file over that size was left out in silence."""
    folder = tmp_path / "pkg"
    shutil.copytree(CASES / "U620_launch_file_not_read", folder)
    (folder / "launch" / "pan.launch.xml").unlink()
    (folder / "launch" / name).write_bytes(data)
    found = [f for f in _checked(folder) if f.code == "U620"]
    assert [(f.location.line, f"could not be read ({said}" in f.message) for f in found] == [
        (line, True)], [f.message for f in found]
    assert "robot descriptions may not" not in found[0].message


def test_a_launch_file_asked_why_again_gives_its_own_reading_not_a_spent_rooms(tmp_path,
                                                                                monkeypatch):
    """The repository's reading room (what its Python launch files may cost) was drawn on
    again when a finding asked why a file was not read: after the other files had spent it, a
    launch file refused as not valid Python was said to be "too large to read all", its line
    lost. A launch file is read once a run."""
    from urdftool.description import launch_python

    monkeypatch.setattr(launch_python, "MAX_REPOSITORY_CHARACTERS", 20_000)
    folder = _folder(tmp_path, "# " + "y" * 8_000 + "\n" + GOOD.format(extra="\n\nif x:\nfoo("))
    for index in range(3):  # read after it (sorted), spending the room
        (folder / "launch" / f"z{index}.launch.py").write_text(
            "# " + "z" * 5_000 + "\n" + GOOD.format(extra=""))
    found = [f for f in _checked(folder) if f.code == "U620"
             and f.location.file.endswith("pan.launch.py")]
    assert [(f.location.line, "not valid Python" in f.message) for f in found] == [(9, True)], \
        [f.message for f in found]
