"""A reader of the user's files that crashes outside a rule (a launch file read while finding
targets, or for a rule) is urdftool's internal error: U900 at the file being read, naming the
reader, the run going on with the other robots (urdftool.description.crashes, drained by the
engine and the runner)."""

from __future__ import annotations

import json

import pytest

import urdftool.description.launch_configs as launch_configs
from urdftool.lint.runner import check_paths

ROBOT = '<?xml version="1.0"?>\n<robot name="{}"><link name="base"/></robot>\n'
PYTHON_LAUNCH = '''from launch import LaunchDescription
from launch_ros.actions import Node
def generate_launch_description():
    return LaunchDescription([Node(package="robot_state_publisher",
        executable="robot_state_publisher",
        parameters=[{"robot_description": open("urdf/a.urdf").read()}])])
'''
XML_LAUNCH = ('<launch><param name="robot_description" '
              'textfile="$(find pkg)/urdf/a.urdf"/></launch>\n')
PACKAGE = ('<?xml version="1.0"?>\n<package format="3"><name>pkg</name><version>0.0.0</version>'
           '<description>x</description><maintainer email="a@b.c">a</maintainer>'
           '<license>MIT</license></package>\n')


@pytest.fixture
def repository(tmp_path):
    (tmp_path / ".git").mkdir()
    package = tmp_path / "pkg"
    (package / "urdf").mkdir(parents=True)
    (package / "launch").mkdir()
    (package / "package.xml").write_text(PACKAGE)
    for name in "ab":
        (package / "urdf" / f"{name}.urdf").write_text(ROBOT.format(name))
    (package / "launch" / "x.launch.py").write_text(PYTHON_LAUNCH)
    (package / "launch" / "y.launch").write_text(XML_LAUNCH)
    return package


def _boom(*args, **kwargs):
    raise RuntimeError("boom")


@pytest.fixture(params=["python", "xml"])
def crashing(request, monkeypatch):
    """The launch file whose reader crashes, by reader."""
    if request.param == "python":
        monkeypatch.setattr(launch_configs, "read_python_launch", _boom)
        return "x.launch.py", "the Python launch reader"
    read = launch_configs.read_launch_text
    monkeypatch.setattr(launch_configs, "read_launch_text",
                        lambda path: _boom() if path.name == "y.launch" else read(path))
    return "y.launch", "the launch reader"


def _crashes(run):
    return [(f.location.file, f.message) for r in run.results for f in r.findings
            if f.code == "U900"]


def test_a_launch_file_named_whose_reader_crashes_is_u900_there(repository, crashing):
    name, reader = crashing
    run = check_paths([str(repository / "launch" / name)], jobs=1, timeout=0)
    crashes = _crashes(run)
    assert len(crashes) == 1 and crashes[0][0].endswith(name)
    assert crashes[0][1].startswith(f"{reader} crashed: RuntimeError: boom")
    assert run.exit_code == 1


def test_a_robot_checked_beside_a_crashing_launch_file_says_it_once_and_is_checked(
        repository, crashing):
    name, reader = crashing
    run = check_paths([str(repository)], jobs=1, timeout=0)
    assert {r.path.rsplit("/", 1)[-1] for r in run.results} >= {"a.urdf", "b.urdf"}
    crashes = _crashes(run)
    assert len(crashes) == 1 and crashes[0][0].endswith(name), crashes  # (no rule's U900)
    assert reader in crashes[0][1]


def test_cli_json_locates_the_crash_at_the_launch_file(run_cli, repository, crashing):
    name, reader = crashing
    result = run_cli("check", repository / "launch" / name, "-f", "json")
    assert result.exit_code == 1, result.output
    found = [f for f in json.loads(result.output)["diagnostics"] if f["code"] == "U900"]
    assert [f["file"].rsplit("/", 1)[-1] for f in found] == [name]


@pytest.mark.parametrize("module, reader", [
    ("urdftool.description.packages:_manifest_of", "the Python launch reader"),
    ("urdftool.lint.settings:for_file", "finding the robots to check")])
def test_a_crash_finding_targets_is_u900_at_the_path_and_the_others_are_checked(
        repository, monkeypatch, module, reader):
    """package.xml's reader, the settings' reader: whatever finding targets reads."""
    import importlib

    name, attribute = module.split(":")
    launch = str(repository / "launch" / "x.launch.py")
    original = getattr(importlib.import_module(name), attribute)

    def crashing(path, *rest):  # (the settings' on the launch file's question only)
        if str(path) == launch or attribute == "_manifest_of":
            raise RuntimeError("boom")
        return original(path, *rest)

    monkeypatch.setattr(importlib.import_module(name), attribute, crashing)
    robot = str(repository / "urdf" / "b.urdf")
    run = check_paths([launch, robot], jobs=1, timeout=0)
    assert any(r.path == robot for r in run.results)
    crashes = _crashes(run)
    assert any(file == launch and message.startswith(f"{reader} crashed: RuntimeError: boom")
               for file, message in crashes), crashes
    assert run.exit_code == 1


def test_check_file_as_the_server_asks_says_the_crash_once_at_the_launch_file(repository,
                                                                              crashing):
    """The language server and the API check one file (``check_file``): the rules that read
    the launch files go on without it, the crash said once where it was."""
    from urdftool.lint.runner import check_file

    name, reader = crashing
    result = check_file(str(repository / "urdf" / "a.urdf"))
    crashes = [(f.location.file, f.message) for f in result.findings if f.code == "U900"]
    assert len(crashes) == 1 and crashes[0][0].endswith(name), crashes
    assert crashes[0][1].startswith(f"{reader} crashed")


@pytest.mark.parametrize("named", ["folder", "companion"])
def test_a_crash_reading_one_file_of_a_folder_is_u900_there_and_its_other_robots_are_checked(
        repository, monkeypatch, named):
    """Finding the robots of a folder reads each of its robot files (is it a robot, what does
    it include): a crash reading one was the folder's (U900 at the folder), and none of its
    robots was checked. It is one U900 at that file; the others are checked."""
    import importlib

    targets = importlib.import_module("urdftool.lint.targets")
    answer = targets._top_level_answer

    def crashing(data):
        if b'name="b"' in data:
            raise RuntimeError("boom")
        return answer(data)

    monkeypatch.setattr(targets, "_top_level_answer", crashing)
    (repository / "config").mkdir()
    (repository / "config" / "a_controllers.yaml").write_text(
        "controller_manager:\n  ros__parameters:\n    update_rate: 100\n")
    path = repository if named == "folder" else repository / "config" / "a_controllers.yaml"
    run = check_paths([str(path)], jobs=1, timeout=0)
    assert any(r.path.endswith("a.urdf") for r in run.results), run.results
    crashes = _crashes(run)
    assert len(crashes) == 1 and crashes[0][0].endswith("b.urdf"), crashes
    assert crashes[0][1].startswith("finding the robots to check crashed: RuntimeError: boom")
