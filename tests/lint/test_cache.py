"""The result cache: never stale, never trusting a cache folder it did not write."""

from __future__ import annotations

import contextlib
import json
import os
import sys
from pathlib import Path

import pytest

from urdftool.description import files as files_module
from urdftool.lint import cache as cache_module
from urdftool.lint import engine
from urdftool.lint.runner import check_paths

pytestmark = pytest.mark.worker  # budgets and deaths: run_cli's commands in the forked worker

ROBOT = """<?xml version="1.0"?>
<robot name="bot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="parts.xacro"/>
  <link name="base"/>
  <xacro:part name="arm"/>
  <joint name="arm_joint" type="revolute"><parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
</robot>
"""
PARTS = """<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="part" params="name">
    <link name="${{name}}">
      <inertial><mass value="{mass}"/>
        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
      <visual><geometry><mesh filename="part.stl"/></geometry></visual>
    </link>
  </xacro:macro>
</robot>
"""
CONTROLLERS = """arm_controller:
  type: position_controllers/JointGroupPositionController
  joints: [{joint}]
"""


@pytest.fixture(autouse=True)
def _own_key(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "home-cache"))


@contextlib.contextmanager
def _opened_below(folder):
    """The paths below ``folder`` opened or listed while the block runs (an audit hook: it
    sees every open of Python and of the C libraries it calls through Python)."""
    opened, watching = [], [True]
    prefix = str(folder)

    def hook(event, args):
        if watching[0] and event in ("open", "os.listdir", "os.scandir") and args and \
                isinstance(args[0], (str, bytes, os.PathLike)):
            name = os.fsdecode(args[0]) if not isinstance(args[0], os.PathLike) \
                else os.fspath(args[0])
            if os.path.realpath(name).startswith(prefix):
                opened.append(name)

    sys.addaudithook(hook)  # hooks cannot be removed: this one is turned off at the end
    try:
        yield opened
    finally:
        watching[0] = False


def _write_mesh(path, size: float) -> None:
    import trimesh

    trimesh.creation.box((size, size, size)).export(path)


@pytest.fixture
def robot(tmp_path):
    folder = tmp_path / "bot"
    (folder / "config").mkdir(parents=True)
    (folder / "bot.urdf.xacro").write_text(ROBOT)
    (folder / "parts.xacro").write_text(PARTS.format(mass=-1))
    (folder / "config" / "controllers.yaml").write_text(CONTROLLERS.format(joint="elbow"))
    _write_mesh(folder / "part.stl", 0.1)
    return folder


def _messages(folder, cache_dir) -> set[tuple[str, str]]:
    run = check_paths([str(folder / "bot.urdf.xacro")], cache_dir=cache_dir, timeout=0,
                      max_memory="0", jobs=1)
    return {(f.code, f.message) for f in run.results[0].findings}


def _entries(cache_dir, kind: str = "file") -> list:
    """The entries of one file's results ('file') or of whole runs ('run')."""
    suffix = {"run": "-run.json"}
    return [entry for entry in (cache_dir / f"v{cache_module.SCHEMA}").iterdir()
            if entry.name.endswith(suffix.get(kind, ".json"))
            and (kind in suffix or not entry.name.endswith(tuple(suffix.values())))]


def _counting_checks(monkeypatch) -> list:
    checked = []
    real = engine.load_and_check
    monkeypatch.setattr(engine, "load_and_check", lambda path, *rest, **kw: checked.append(path)
                        or real(path, *rest, **kw))
    return checked


def test_an_unchanged_robot_is_not_checked_again(robot, tmp_path, monkeypatch):
    cache_dir = tmp_path / "cache"
    first = _messages(robot, cache_dir)
    checked = _counting_checks(monkeypatch)
    assert _messages(robot, cache_dir) == first
    assert checked == []
    assert (cache_dir / "CACHEDIR.TAG").read_text().startswith("Signature: 8a477f597d28d172")
    assert (cache_dir / ".gitignore").read_text().splitlines()[-1] == "*"


def test_an_edited_macro_file_mesh_or_companion_changes_the_findings(robot, tmp_path):
    cache_dir = tmp_path / "cache"
    before = _messages(robot, cache_dir)
    assert any(code == "U302" and "-1 kg" in message for code, message in before)
    assert any(code == "U602" and "'elbow'" in message for code, message in before)
    assert not any(code == "U410" for code, _ in before)

    (robot / "parts.xacro").write_text(PARTS.format(mass=-2))
    after_macro = _messages(robot, cache_dir)
    assert any(code == "U302" and "-2 kg" in message for code, message in after_macro)

    _write_mesh(robot / "part.stl", 80.0)  # 80 m: an implausible size
    after_mesh = _messages(robot, cache_dir)
    assert after_mesh - after_macro and all(code != "U302" or "-2 kg" in message
                                            for code, message in after_mesh)

    (robot / "config" / "controllers.yaml").write_text(CONTROLLERS.format(joint="wrist"))
    after_yaml = _messages(robot, cache_dir)
    assert any(code == "U602" and "'wrist'" in message for code, message in after_yaml)
    assert not any("'elbow'" in message for _, message in after_yaml)


def test_a_rerun_of_the_same_paths_is_served_whole(robot, tmp_path, monkeypatch):
    from urdftool.lint import targets

    monkeypatch.setattr(files_module, "RACY_NS", 0)  # files written just now: trust stamps
    cache_dir = tmp_path / "cache"
    first = _messages(robot, cache_dir)
    assert len(_entries(cache_dir, "run")) == 1

    def refused(*args):
        raise AssertionError("targets expanded on a re-run")

    monkeypatch.setattr(targets, "expand", refused)
    checked = _counting_checks(monkeypatch)
    assert _messages(robot, cache_dir) == first
    assert checked == []


@pytest.mark.parametrize("settings", ["pyproject.toml", "urdftool.toml", "../pyproject.toml"])
def test_a_new_settings_file_above_the_robot_is_seen(robot, tmp_path, settings):
    cache_dir = tmp_path / "cache"
    assert any(code == "U302" for code, _ in _messages(robot, cache_dir))
    table = "" if settings == "urdftool.toml" else "[tool.urdftool]\n"
    (robot / settings).write_text(table + 'ignore = ["U302"]\n')
    assert not any(code == "U302" for code, _ in _messages(robot, cache_dir))


def test_a_run_through_a_folder_is_not_kept_whole(robot, tmp_path):
    cache_dir = tmp_path / "cache"
    check_paths([str(robot)], cache_dir=cache_dir, timeout=0, max_memory="0", jobs=1)
    assert _entries(cache_dir, "file") and not _entries(cache_dir, "run")


def test_a_file_rewritten_within_its_clock_tick_is_seen(robot, tmp_path, monkeypatch):
    # a coarse file clock: the macro file rewritten keeps its size and every time stamp
    import types

    parts = str(robot / "parts.xacro")
    frozen = os.stat(parts)
    real_os = types.SimpleNamespace(**vars(os))
    real_os.stat = lambda path, *a, **k: frozen if os.fspath(path) == parts else os.stat(
        path, *a, **k)
    monkeypatch.setattr(files_module, "os", real_os)
    # the check reads the file within the tick it was written in, however loaded the host
    monkeypatch.setattr(files_module, "RACY_NS", 600 * 10 ** 9)
    cache_dir = tmp_path / "cache"
    assert any("-1 kg" in message for _, message in _messages(robot, cache_dir))
    (robot / "parts.xacro").write_text(PARTS.format(mass=-2))
    assert any("-2 kg" in message for _, message in _messages(robot, cache_dir))


def test_a_new_companion_file_is_seen(robot, tmp_path):
    cache_dir = tmp_path / "cache"
    (robot / "config" / "controllers.yaml").unlink()
    assert not any(code == "U602" for code, _ in _messages(robot, cache_dir))
    (robot / "config" / "more.yaml").write_text(CONTROLLERS.format(joint="elbow"))
    assert any(code == "U602" for code, _ in _messages(robot, cache_dir))


@pytest.mark.parametrize("kind", ["file", "run"])
def test_a_planted_entry_is_a_miss(robot, tmp_path, monkeypatch, kind):
    cache_dir = tmp_path / "cache"
    honest = _messages(robot, cache_dir)
    for entry in _entries(cache_dir, kind):
        signature, body = entry.read_text().split("\n", 1)
        body = json.loads(body)
        for result in body.get("results", [body]):
            result["findings"] = []  # "no problems": what an attacker would plant
        entry.write_text(signature + "\n" + json.dumps(body))
    assert _messages(robot, cache_dir) == honest
    # signed with a key of its own (written by another machine): a miss as well
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "other-home"))
    checked = _counting_checks(monkeypatch)
    assert _messages(robot, cache_dir) == honest
    assert len(checked) == 1


@pytest.mark.parametrize("kind", ["file", "run"])
def test_an_entry_this_machine_signed_for_another_file_is_a_miss(robot, tmp_path, kind):
    """A clean robot's entry, signed here, copied over the name of a robot with errors (by
    anyone who may write the cache folder, without the key): was served, "no problems
    found"; the signature covers the entry's name."""
    cache_dir = tmp_path / "cache"
    clean = tmp_path / "clean" / "clean.urdf"
    clean.parent.mkdir()
    clean.write_text('<robot name="clean"><link name="a"/></robot>\n')
    run = check_paths([str(clean)], cache_dir=cache_dir, timeout=0, max_memory="0", jobs=1)
    assert run.results[0].findings == []
    kept = {entry.name: entry.read_bytes() for entry in _entries(cache_dir, kind)}
    honest = _messages(robot, cache_dir)
    assert honest
    [entry] = [entry for entry in _entries(cache_dir, kind) if entry.name not in kept]
    [body] = kept.values()
    entry.write_bytes(body)
    assert _messages(robot, cache_dir) == honest


@pytest.mark.parametrize("kind", ["file", "run"])
@pytest.mark.parametrize("garbage", [b"", b"{", b"[]", b'{"body": "{}", "mac": 1}', b"0" * 64 + b"\n{}", b"\xff" * 10])
def test_a_corrupt_entry_is_a_miss(robot, tmp_path, garbage, kind):
    cache_dir = tmp_path / "cache"
    honest = _messages(robot, cache_dir)
    [entry] = _entries(cache_dir, kind)
    entry.write_bytes(garbage)
    assert _messages(robot, cache_dir) == honest


def test_a_cache_folder_that_is_a_link_is_not_followed(robot, tmp_path, monkeypatch):
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    link = tmp_path / "cache"
    link.symlink_to(elsewhere)
    honest = _messages(robot, link)
    checked = _counting_checks(monkeypatch)
    assert _messages(robot, link) == honest
    assert checked and list(elsewhere.iterdir()) == []


@pytest.mark.parametrize("planted", [None, ".gitignore", "CACHEDIR.TAG", "link"])
def test_a_cache_folder_urdftool_did_not_make_is_marked_before_an_entry_or_not_used(
        robot, tmp_path, planted):
    """Session 20 left it: a cache folder committed in the repository (git keeps a folder that
    holds a file) or planted got no CACHEDIR.TAG or .gitignore (they were written only into a
    folder urdftool made), so the entries kept there, the absolute paths of every file read,
    were untracked files for ``git add -A`` to commit; a ``.gitignore`` of ``!*`` planted
    there did the same. Now the marks are written into any folder before an entry; a folder
    holding other files of those names is written nothing (and they are left as they are)."""
    cache_dir = tmp_path / "cache"
    cache_dir.mkdir()
    (cache_dir / "README").write_text("committed\n")
    if planted == "link":
        (tmp_path / "mine").write_text("# created by urdftool\n*\n")
        (cache_dir / ".gitignore").symlink_to(tmp_path / "mine")
    elif planted is not None:
        (cache_dir / planted).write_text("!*\n")
    run = check_paths([str(robot / "bot.urdf.xacro")], cache_dir=cache_dir, timeout=0,
                      max_memory="0", jobs=1)
    marks = {"CACHEDIR.TAG": cache_module._TAG, ".gitignore": "# created by urdftool\n*\n"}
    if planted is None:
        assert {name: (cache_dir / name).read_text() for name in marks} == marks
        assert _entries(cache_dir) and not run.notes
        return
    assert not (cache_dir / f"v{cache_module.SCHEMA}").exists() or \
        not list((cache_dir / f"v{cache_module.SCHEMA}").iterdir())
    assert [note for note in run.notes if "did not write" in note], run.notes
    if planted == "link":
        assert (cache_dir / ".gitignore").is_symlink()
    else:
        assert (cache_dir / planted).read_text() == "!*\n"


@pytest.mark.parametrize("kind", ["file", "run"])
def test_an_entry_that_is_a_link_is_not_followed(robot, tmp_path, kind):
    cache_dir = tmp_path / "cache"
    honest = _messages(robot, cache_dir)
    if kind == "file":  # the run's entry would serve the run without reading the file's
        [run] = _entries(cache_dir, "run")
        run.unlink()
    [entry] = _entries(cache_dir, kind)
    target = tmp_path / "secret.txt"
    target.write_text(entry.read_text())
    entry.unlink()
    entry.symlink_to(target)
    assert _messages(robot, cache_dir) == honest
    assert not entry.is_symlink()  # replaced by a fresh entry, the target left alone
    assert target.read_text().split("\n", 1)[1].startswith('{"schema"')


def test_the_default_is_off_under_ci():
    assert cache_module.default_folder({"CI": "true"}) is None
    # one answer with the safe mode's: CI=false turned the cache off, the full mode on
    from urdftool.description.files import env_allowed

    for value in ("false", "0", "no", " ", "true", "1", "yes"):
        with pytest.MonkeyPatch.context() as patch:
            patch.setenv("CI", value)
            patch.delenv("URDFTOOL_NO_CACHE", raising=False)  # (the suite's)
            assert (cache_module.default_folder() is None) == (not env_allowed(None)), value
    assert cache_module.default_folder({}) == cache_module.Path(".urdftool_cache")


def test_check_no_cache_writes_nothing(robot, tmp_path, run_cli, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("URDFTOOL_NO_CACHE")
    monkeypatch.delenv("CI", raising=False)
    run_cli("check", "--no-cache", str(robot / "bot.urdf.xacro"))
    assert not (tmp_path / ".urdftool_cache").exists()
    run_cli("check", str(robot / "bot.urdf.xacro"))
    assert len(_entries(tmp_path / ".urdftool_cache")) == 1


def test_a_cached_result_keeps_columns_call_sites_and_fixes(tmp_path, monkeypatch):
    """A hit gives back the findings as checked: --fix and the editors need all of it."""
    (tmp_path / ".git").mkdir()
    path = tmp_path / "r.urdf"
    path.write_text('<robot name="r"><link name="a"/><link name="b"/>\n  <joint name="j" '
                    'type="revolute"><parent link="a"/><child link="b"/>\n    <limit lower="1" '
                    'upper="-1" effort="1" velocity="1"/></joint></robot>\n')
    cache_dir = tmp_path / "cache"
    [first] = check_paths([str(path)], jobs=1, timeout=0, cache_dir=cache_dir).results
    checked = _counting_checks(monkeypatch)
    [again] = check_paths([str(path)], jobs=1, timeout=0, cache_dir=cache_dir).results
    assert checked == []  # a hit
    assert again.findings == first.findings
    [finding] = [f for f in again.findings if f.code == "U204"]
    assert finding.location.column == 5 and finding.fix is not None and finding.fix.safe


def _kept_run(robot, cache_dir):
    return check_paths([str(robot / "bot.urdf.xacro")], cache_dir=cache_dir, timeout=0,
                       max_memory="0", jobs=1)


def test_a_run_kept_whole_is_served_with_what_it_depends_on(robot, tmp_path, monkeypatch):
    monkeypatch.setattr(files_module, "RACY_NS", 0)  # files written just now: trust stamps
    cache_dir = tmp_path / "cache"
    run = _kept_run(robot, cache_dir)
    assert run.depends and _kept_run(robot, cache_dir).depends == run.depends  # as served


@pytest.mark.parametrize("saved", ["macro", "mesh", "companion"])
def test_a_file_changed_while_it_is_checked_is_not_kept(robot, tmp_path, monkeypatch, saved):
    # an editor saves a file while the check runs: the findings come from the old content, the
    # file's stamps and content are the new ones
    real = engine.load_and_check

    def save():
        if saved == "macro":
            (robot / "parts.xacro").write_text(PARTS.format(mass=-2))
        elif saved == "mesh":
            _write_mesh(robot / "part.stl", 80.0)  # 80 m: an implausible size
        else:
            (robot / "config" / "controllers.yaml").write_text(CONTROLLERS.format(joint="wrist"))

    def saved_meanwhile(path, *rest, **kw):
        result = real(path, *rest, **kw)
        save()
        return result

    monkeypatch.setattr(engine, "load_and_check", saved_meanwhile)
    cache_dir = tmp_path / "cache"
    before = _messages(robot, cache_dir)
    monkeypatch.setattr(engine, "load_and_check", real)
    after = _messages(robot, cache_dir)
    assert after != before
    assert after == _messages(robot, tmp_path / "another-cache")  # as checked afresh


def test_links_leading_out_of_the_repository_are_neither_read_nor_stamped(robot, tmp_path):
    # found by make fuzz with the cache on: to tell a kept result stale, the cache hashed every
    # .yaml and .srdf beside the robot and in config/, and every mesh, following links that the
    # loader refuses to follow (limits.yaml -> /etc/passwd was opened, its hash kept in the
    # repository's cache)
    outside = tmp_path / "outside"
    outside.mkdir()
    secret = outside / "secret.yaml"
    secret.write_text("password: hunter2\n")
    _write_mesh(outside / "part.stl", 0.1)
    (robot / "limits.yaml").symlink_to(secret)
    (robot / "config" / "leak.yaml").symlink_to(secret)
    (robot / "part.stl").unlink()
    (robot / "part.stl").symlink_to(outside / "part.stl")
    cache_dir = tmp_path / "cache"
    with _opened_below(outside) as opened:
        first = _messages(robot, cache_dir)
        checked = []
        with pytest.MonkeyPatch.context() as patch:
            checked = _counting_checks(patch)
            assert _messages(robot, cache_dir) == first and checked == []  # still served
    assert opened == []
    kept = "".join(entry.read_text() for kind in ("file", "run")
                   for entry in _entries(cache_dir, kind))
    status = os.stat(secret)
    assert f"{status.st_dev}:{status.st_ino}:" not in kept
    assert files_module.digest(secret.read_bytes()) not in kept
    assert str(secret) in kept and str(outside / "part.stl") in kept  # where the links lead


def test_a_companion_named_on_the_command_line_is_followed_wherever_it_leads(robot, tmp_path):
    # the check reads a companion the user names (--controllers) even through a link leading
    # out of the repository, so the cache must see its target change (it kept only where the
    # link led, and served the old findings)
    from urdftool.description.inputs import CompanionPaths

    (robot / "config" / "controllers.yaml").unlink()
    target = tmp_path / "outside" / "controllers.yaml"
    target.parent.mkdir()
    target.write_text(CONTROLLERS.format(joint="arm_joint"))
    link = robot / "named.yaml"
    link.symlink_to(target)
    cache_dir = tmp_path / "cache"

    def codes():
        run = check_paths([str(robot / "bot.urdf.xacro")], cache_dir=cache_dir, timeout=0,
                          max_memory="0", jobs=1, companions=CompanionPaths((str(link),)))
        return {f.code for f in run.results[0].findings}

    assert "U602" not in codes()
    target.write_text(CONTROLLERS.format(joint="elbow"))
    assert "U602" in codes()


LAUNCH = """<launch>
  <param name="robot_description" command="xacro $(dirname)/../bot.urdf.xacro"/>
  <rosparam file="$(dirname)/../config/controllers.yaml" command="load"/>
  <node name="s" pkg="controller_manager" type="spawner" args="{spawned}"/>
</launch>
"""


def test_an_edited_or_new_launch_file_changes_the_findings(robot, tmp_path):
    # which controllers run is the launch files' say (description/runtime.py): a result kept
    # while arm_controller was started nowhere is stale once a launch file starts it
    cache_dir = tmp_path / "cache"
    (robot / ".git").mkdir()  # launch files are the repository's (or package's)
    (robot / "launch").mkdir()
    (robot / "launch" / "bot.launch").write_text(LAUNCH.format(spawned="other"))
    assert not any(code == "U602" for code, _ in _messages(robot, cache_dir))
    (robot / "launch" / "bot.launch").write_text(LAUNCH.format(spawned="arm_controller"))
    assert any(code == "U602" for code, _ in _messages(robot, cache_dir))
    (robot / "launch" / "bot.launch").write_text(LAUNCH.format(spawned="other"))
    assert not any(code == "U602" for code, _ in _messages(robot, cache_dir))
    (robot / "launch" / "more.launch").write_text(LAUNCH.format(spawned="arm_controller"))
    assert any(code == "U602" for code, _ in _messages(robot, cache_dir))


PYTHON_LAUNCH = """
import helpers
def generate_launch_description():
    return [Node(package="robot_state_publisher", executable="robot_state_publisher",
                 parameters=[{"robot_description": Command(["xacro ", "../bot.urdf.xacro"])}]),
            Node(package="controller_manager", executable="ros2_control_node",
                 parameters=["../config/controllers.yaml"]),
            helpers.spawner()]
"""
HELPERS = """
def spawner():
    return Node(package="controller_manager", executable="spawner", arguments=["{spawned}"])
"""


def test_an_edited_module_a_python_launch_file_imports_changes_the_findings(robot, tmp_path):
    # the launch file's own text is unchanged: the module it imports (read, never run) decides
    # which controller it starts, so the result kept must follow that module, and its coming
    cache_dir = tmp_path / "cache"
    (robot / ".git").mkdir()
    (robot / "launch").mkdir()
    (robot / "launch" / "bot.launch.py").write_text(PYTHON_LAUNCH)
    assert not any(code == "U602" for code, _ in _messages(robot, cache_dir))
    (robot / "launch" / "helpers.py").write_text(HELPERS.format(spawned="arm_controller"))
    assert any(code == "U602" for code, _ in _messages(robot, cache_dir))
    (robot / "launch" / "helpers.py").write_text(HELPERS.format(spawned="other"))
    assert not any(code == "U602" for code, _ in _messages(robot, cache_dir))


@pytest.fixture
def package(tmp_path):
    """A ROS package whose robot is in urdf/ and whose controllers go in the package's
    config/, which does not exist yet."""
    (tmp_path / ".git").mkdir()
    folder = tmp_path / "pkg"
    (folder / "urdf").mkdir(parents=True)
    (folder / "package.xml").write_text("<package><name>pkg</name></package>\n")
    (folder / "urdf" / "bot.urdf").write_text(
        '<robot name="bot"><link name="base"/><link name="arm"/>\n'
        '<joint name="arm_joint" type="revolute"><parent link="base"/><child link="arm"/>'
        '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        '</robot>\n')
    return folder


def _codes(robot_file, cache_dir) -> set[str]:
    run = check_paths([str(robot_file)], cache_dir=cache_dir, timeout=0, max_memory="0",
                      jobs=1)
    return {f.code for f in run.results[0].findings}


@pytest.mark.parametrize("config", ["created later", "there, empty"])
def test_a_companion_added_to_the_package_of_a_robot_checked_clean_is_seen(package, tmp_path,
                                                                          config):
    # issue 31: the cache kept its own list of companion folders (the robot's and its config/),
    # not discovery's (the package's config/ too): adding pkg/config/controllers.yaml went
    # unnoticed by a cached run while --no-cache reported U602
    robot_file = package / "urdf" / "bot.urdf"
    if config == "there, empty":
        (package / "config").mkdir()
    cache_dir = tmp_path / "cache"
    assert "U602" not in _codes(robot_file, cache_dir)
    (package / "config").mkdir(exist_ok=True)
    (package / "config" / "controllers.yaml").write_text(CONTROLLERS.format(joint="elbow"))
    uncached = _codes(robot_file, tmp_path / "fresh-cache")
    assert "U602" in uncached
    assert _codes(robot_file, cache_dir) == uncached


def test_a_settings_file_or_package_manifest_made_later_is_seen(package, tmp_path, monkeypatch):
    # what finding the settings and the package probed, found missing, is in the record too
    monkeypatch.setattr(files_module, "RACY_NS", 0)
    robot_file = package / "urdf" / "bot.urdf"
    cache_dir = tmp_path / "cache"
    (package / "urdf" / "bot.urdf").write_text(
        robot_file.read_text().replace('upper="1"', 'upper="-2"'))
    assert "U204" in _codes(robot_file, cache_dir)
    (package / "urdftool.toml").write_text('ignore = ["U204"]\n')
    assert "U204" not in _codes(robot_file, cache_dir)


@pytest.mark.parametrize("uri", ["file://{outside}/part.stl", "../../outside/part.stl"])
def test_a_mesh_outside_the_repository_is_never_opened_by_the_cache(tmp_path, uri):
    # issue 29, item 5: the loader refuses such a mesh (U409), and the cache resolved the URI
    # itself, opened the file and kept its hash
    outside = tmp_path / "outside"
    outside.mkdir()
    _write_mesh(outside / "part.stl", 0.1)
    repository = tmp_path / "repo"
    (repository / ".git").mkdir(parents=True)
    (repository / "urdf").mkdir()
    robot_file = repository / "urdf" / "bot.urdf"
    robot_file.write_text(
        '<robot name="bot"><link name="base"><visual><geometry><mesh filename="'
        f'{uri.format(outside=outside)}"/></geometry></visual></link></robot>\n')
    cache_dir = tmp_path / "cache"
    with _opened_below(outside) as opened:
        first = _codes(robot_file, cache_dir)
        assert "U409" in first
        assert _codes(robot_file, cache_dir) == first
    assert opened == []
    kept = "".join(entry.read_text() for kind in ("file", "run")
                   for entry in _entries(cache_dir, kind))
    assert files_module.digest((outside / "part.stl").read_bytes()) not in kept
    status = os.stat(outside / "part.stl")
    assert f"{status.st_dev}:{status.st_ino}:" not in kept


def test_the_cache_folder_made_in_the_repository_is_no_change(tmp_path, monkeypatch):
    # a package found by scanning the repository: the scan lists its folders, and the cache's
    # own folder, made by the first run, is one of them; hidden folders are not scanned (as
    # catkin and colcon crawl), so the second run is served
    monkeypatch.setattr(files_module, "RACY_NS", 0)
    monkeypatch.chdir(tmp_path)
    (tmp_path / ".git").mkdir()
    (tmp_path / "robots").mkdir()
    (tmp_path / "other" / "pkg_b" / "meshes").mkdir(parents=True)
    (tmp_path / "other" / "pkg_b" / "package.xml").write_text("<package><name>pkg_b</name></package>")
    _write_mesh(tmp_path / "other" / "pkg_b" / "meshes" / "m.stl", 0.1)
    (tmp_path / "robots" / "r.urdf").write_text(
        '<robot name="r"><link name="a"><visual><geometry>'
        '<mesh filename="package://pkg_b/meshes/m.stl"/></geometry></visual></link></robot>\n')
    first = _codes(tmp_path / "robots" / "r.urdf", cache_module.FOLDER)
    checked = _counting_checks(monkeypatch)
    assert _codes(tmp_path / "robots" / "r.urdf", cache_module.FOLDER) == first
    assert checked == []


def test_a_file_a_rule_looked_for_made_later_is_seen(package, tmp_path):
    # rules ask the door too: MuJoCo looks for meshes in its meshdir (U922 until the file is
    # there), which is no folder the loader or discovery reads
    _write_mesh(package / "urdf" / "base.stl", 0.1)
    robot_file = package / "urdf" / "bot.urdf"
    robot_file.write_text(robot_file.read_text().replace(
        '<link name="base"/>', '<mujoco><compiler meshdir="../assets"/></mujoco><link '
        'name="base"><collision><geometry><mesh filename="base.stl"/></geometry></collision>'
        '</link>'))

    def codes(cache_dir):
        run = check_paths([str(robot_file)], cache_dir=cache_dir, timeout=0, max_memory="0",
                          jobs=1, targets=["mujoco"])
        return {f.code for f in run.results[0].findings}

    cache_dir = tmp_path / "cache"
    assert "U922" in codes(cache_dir)
    (package / "assets").mkdir()
    _write_mesh(package / "assets" / "base.stl", 0.1)
    assert "U922" not in codes(tmp_path / "fresh-cache")
    assert "U922" not in codes(cache_dir)


def test_a_result_checked_from_unsaved_buffers_is_never_served_for_the_disk(robot, tmp_path):
    """The language server's buffers (an included macro file, a companion) are what the record
    stamps: the result is not kept while the disk holds other bytes, nor served for them."""
    from urdftool.lint.runner import check_file
    from urdftool.lint.settings import CheckRequest, for_file

    path = str(robot / "bot.urdf.xacro")
    options = for_file(path, CheckRequest()).options
    buffers = {str(robot / "parts.xacro"): PARTS.format(mass=-3),
               str(robot / "config" / "controllers.yaml"): CONTROLLERS.format(joint="wrist")}
    with files_module.unsaved(buffers):
        result = check_file(path)
    messages = {f.message for f in result.findings}
    assert any("-3 kg" in m for m in messages) and any("'wrist'" in m for m in messages)
    cache = cache_module.Cache(tmp_path / "cache")
    cache.put(path, options, result)
    assert cache.get(path, options) is None
    assert not files_module.unchanged(result.record.dump())
    disk = {f.message for f in check_file(path).findings}
    assert any("-1 kg" in m for m in disk) and any("'elbow'" in m for m in disk)

    for name, text in buffers.items():  # saved: the same bytes, the result holds
        Path(name).write_text(text)
    assert files_module.unchanged(result.record.dump())


@pytest.mark.parametrize("where", ["a file", "full", "no key"])
def test_results_that_cannot_be_kept_are_said_once_and_the_check_goes_on(
        robot, tmp_path, monkeypatch, where):
    """Session 11 left it: ``--cache-dir`` on a full or read-only file system (or a file, or
    with no signing key) was a miss on every run without a word. Two files in two workers
    (each a copy of the cache) that cannot keep their results: one note, the findings as
    without a cache."""
    second = robot.parent / "second"
    second.mkdir()
    (second / "bot.urdf.xacro").write_text(ROBOT)
    (second / "parts.xacro").write_text(PARTS.format(mass=-1))
    paths = [str(robot / "bot.urdf.xacro"), str(second / "bot.urdf.xacro")]
    cache_dir = tmp_path / "cache"
    if where == "a file":
        cache_dir.write_text("not a folder")
    elif where == "full":
        assert cache_module._secret() is not None  # the key made first, in another place

        def full(path, text):
            raise OSError(28, "No space left on device")

        monkeypatch.setattr(cache_module, "_write", full)
    else:
        monkeypatch.setattr(cache_module, "_secret", lambda: None)
    without = check_paths(paths, jobs=2)
    run = check_paths(paths, cache_dir=cache_dir, jobs=2)
    assert [[f.message for f in r.findings] for r in run.results] == \
        [[f.message for f in r.findings] for r in without.results]
    said = [note for note in run.notes if "not kept" in note]
    assert len(said) == 1 and {"a file": "is not a folder", "full": "No space left",
                               "no key": "no signing key"}[where] in said[0], run.notes


def test_an_entry_that_is_a_named_pipe_is_replaced_not_written_into(robot, tmp_path,
                                                                     monkeypatch):
    """A pipe planted as an entry held every run 10 s (write_file waits for a reader, as for
    a report's ``-o``) and stayed: the results were never kept."""
    from urdftool.description import files

    cache_dir = tmp_path / "cache"
    honest = _messages(robot, cache_dir)
    [run] = _entries(cache_dir, "run")
    run.unlink()
    [entry] = _entries(cache_dir)
    entry.unlink()
    os.mkfifo(entry)
    monkeypatch.setattr(files, "PIPE_READER_WAIT", 0.1)
    checked = _counting_checks(monkeypatch)
    assert _messages(robot, cache_dir) == honest and checked
    assert entry.is_file() and not entry.is_symlink()
    checked.clear()
    assert _messages(robot, cache_dir) == honest and not checked  # kept: served


def test_the_signing_key_is_readable_by_its_owner_only_whatever_its_folder(tmp_path, monkeypatch):
    """The key signs entries: one readable by others lets them sign entries for a cache folder
    they may write. Its folder is made 0700, but one that was there (made by another program,
    a link to a shared folder) kept a 0644 key readable by every user."""
    import stat

    from urdftool.lint import cache

    (tmp_path / "urdftool").mkdir(mode=0o755)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    key = cache._secret()
    assert key and stat.S_IMODE((tmp_path / "urdftool" / "key").stat().st_mode) == 0o600


def test_a_kept_finding_keeps_the_parts_a_report_says_once():
    """Finding.repeated is kept with the finding: a result the cache serves is reported as the
    check's own (U640's evidence, a package's places, written once per file)."""
    from urdftool.diagnostics import Finding, Location, Severity

    finding = Finding("U640", "gazebo-plugin-other-version", Severity.ERROR, "a (why) b",
                      Location("r.urdf", 3), repeated=(("why", " (why)", ""),))
    assert cache_module._finding(json.loads(json.dumps(cache_module._record(finding)))) == finding
    with pytest.raises(TypeError):
        cache_module._finding({**cache_module._record(finding), "repeated": [["why", 1]]})


def test_a_kept_finding_keeps_whether_urdfdom_takes_it():
    """Finding.urdfdom_takes is kept: a served result tells a refusal of urdfdom from a shape it
    parses as the check did; a finding without it keeps no key."""
    from urdftool.diagnostics import Finding, Location, Severity

    finding = Finding("U103", "missing-name", Severity.ERROR, "<joint> has an empty name",
                      Location("r.urdf", 3), urdfdom_takes=True)
    assert cache_module._finding(json.loads(json.dumps(cache_module._record(finding)))) == finding
    assert "urdfdom_takes" not in cache_module._record(Finding(
        "U103", "missing-name", Severity.ERROR, "m", Location("r.urdf", 3)))
    with pytest.raises(TypeError):
        cache_module._finding({**cache_module._record(finding), "urdfdom_takes": 1})


def test_a_kept_finding_keeps_whether_it_is_urdfdoms_refusal_below_an_error():
    """Finding.urdfdom_refuses is kept: a served warning on a file Drake reads is still the
    refusal it was."""
    from urdftool.diagnostics import Finding, Location, Severity

    finding = Finding("U202", "missing-limit", Severity.WARNING, "if urdfdom loads it: m",
                      Location("r.urdf", 3), urdfdom_refuses=True)
    assert cache_module._finding(json.loads(json.dumps(cache_module._record(finding)))) == finding
    assert cache_module._finding(json.loads(json.dumps(cache_module._record(
        finding)))).urdfdom_refuses
    with pytest.raises(TypeError):
        cache_module._finding({**cache_module._record(finding), "urdfdom_refuses": 1})


def test_a_file_the_cache_holds_still_says_what_its_check_read(robot, tmp_path, monkeypatch):
    """A result served from the cache names the files its check read, as a worker's does
    (check's warning of a xacro argument no file names reads them: a hit said nothing)."""
    cache_dir = tmp_path / "cache"
    first = check_paths([str(robot)], cache_dir=cache_dir, timeout=0, max_memory="0", jobs=1)
    checked = _counting_checks(monkeypatch)
    again = check_paths([str(robot)], cache_dir=cache_dir, timeout=0, max_memory="0", jobs=1)
    assert checked == []
    assert set(again.results[0].read) == set(first.results[0].read)
    assert any(path.endswith("parts.xacro") for path in again.results[0].read)
