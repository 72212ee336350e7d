"""U620 (launch-file-not-read) over a folder check: the launch files a robot's repository holds
that could not be read say so, at the launch file."""

from __future__ import annotations

import shutil

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
