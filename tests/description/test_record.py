"""The record of what a check read: made as the loader and discovery read, complete when
answers are remembered between robots, compared with the disk without reading anything else."""

from __future__ import annotations

import os

import pytest

from urdftool.description import files, meshes
from urdftool.description.record import Record, recording
from urdftool.description.run_memo import one_run
from urdftool.lint.engine import load_and_check
from urdftool.lint.options import CheckOptions

ROBOT = """<?xml version="1.0"?>
<robot name="{name}" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find pkg)/urdf/arm.xacro"/>
  <xacro:property name="limits" value="${{xacro.load_yaml('limits.yaml')}}"/>
  <link name="base"><visual><origin xyz="${{limits['lower']}} 0 0"/><geometry>
    <mesh filename="package://pkg/meshes/base.stl"/></geometry></visual></link>
  <xacro:arm/>
</robot>
"""
ARM = """<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro name="arm">
  <link name="arm"/><joint name="j" type="fixed"><parent link="base"/><child link="arm"/></joint>
</xacro:macro></robot>"""


@pytest.fixture
def package(tmp_path):
    (tmp_path / ".git").mkdir()
    root = tmp_path / "pkg"
    (root / "urdf").mkdir(parents=True)
    (root / "meshes").mkdir()
    (root / "package.xml").write_text("<package><name>pkg</name></package>\n")
    (root / "urdf" / "arm.xacro").write_text(ARM)
    (root / "urdf" / "limits.yaml").write_text("lower: -1\n")
    for name in ("one", "two"):
        (root / "urdf" / f"{name}.urdf.xacro").write_text(ROBOT.format(name=name))
    import trimesh

    trimesh.creation.box((0.1, 0.1, 0.1)).export(root / "meshes" / "base.stl")
    return root


def test_the_record_holds_what_the_check_read_searched_and_resolved(package):
    result = load_and_check(str(package / "urdf" / "one.urdf.xacro"), CheckOptions())
    record = result.record
    urdf = package / "urdf"
    assert record.read_as("robot") == [str(urdf / "one.urdf.xacro")]
    assert record.read_as("include") == [str(urdf / "arm.xacro")]
    assert record.read_as("yaml") == [str(urdf / "limits.yaml")]
    assert record.read_as("mesh") == [str(package / "meshes" / "base.stl")]
    assert str(package / "package.xml") in record.read_as("package manifest")
    assert record.resolutions()["package pkg"] == str(package)
    assert record.resolutions()["mesh package://pkg/meshes/base.stl"] == \
        str(package / "meshes" / "base.stl")
    searched = record.searched()
    # the companion folders discovery looked in: config/ beside the robot and in the package
    # are not there (probed), the robot's folder was listed and held no controller YAML
    assert any(folder == str(urdf) and "yaml" in pattern for folder, pattern in searched)
    assert record.entries["probe", (str(package / "config"), False)] == ""
    assert record.entries["probe", (str(urdf / "config"), False)] == ""
    read = record.reads()[str(urdf / "arm.xacro")]
    assert read.digest == files.digest(ARM.encode()) and read.real == str(urdf / "arm.xacro")


def test_settings_looked_for_are_in_the_record_of_a_check_by_path(package):
    from urdftool.lint.runner import check_file as check_by_path

    record = check_by_path(package / "urdf" / "one.urdf.xacro").record
    for folder in (package / "urdf", package, package.parent):  # up to the repository root
        for name in ("urdftool.toml", "pyproject.toml"):
            assert record.entries["probe", (str(folder / name), True)] == ""
    assert ("probe", (str(package.parent.parent / "urdftool.toml"), True)) not in record.entries


def test_answers_remembered_for_one_robot_are_in_the_record_of_the_next(package):
    # per-run answers (the repository root, discovery's folders) and the mesh read once per
    # process are given to the second robot without asking again: their entries are replayed
    # (each in a run, as every command checks: within one, the package walk takes the
    # launch-file walk's listings, and its record is that walk's wider search)
    meshes.run_cache.clear()
    with one_run():
        alone = load_and_check(str(package / "urdf" / "two.urdf.xacro"), CheckOptions()).record
    meshes.run_cache.clear()
    with one_run():
        load_and_check(str(package / "urdf" / "one.urdf.xacro"), CheckOptions())
        second = load_and_check(str(package / "urdf" / "two.urdf.xacro"), CheckOptions()).record
    assert second.read_as("mesh") == [str(package / "meshes" / "base.stl")]
    assert set(alone.entries) <= set(second.entries)


def test_an_entry_holds_until_what_it_answered_changes(package, monkeypatch):
    monkeypatch.setattr(files, "RACY_NS", 0)
    record = load_and_check(str(package / "urdf" / "one.urdf.xacro"), CheckOptions()).record
    entries = record.dump()
    assert files.unchanged(entries) and files.unchanged(entries, quick=True)

    yaml = package / "urdf" / "limits.yaml"
    yaml.write_text("lower: -1\n")  # the same bytes, written again: a new stamp
    assert files.unchanged(entries) and not files.unchanged(entries, quick=True)
    yaml.write_text("lower: -2\n")
    assert not files.unchanged(entries)
    yaml.write_text("lower: -1\n")
    assert files.unchanged(entries)

    (package / "config").mkdir()  # a folder discovery looked for
    assert not files.unchanged(entries)
    (package / "config").rmdir()
    (package / "urdf" / "controllers.yaml").write_text("c: {type: a/B}\n")  # a folder it listed
    assert not files.unchanged(entries)
    (package / "urdf" / "controllers.yaml").unlink()
    (package / "urdf" / "notes.txt").write_text("what it did not look for\n")
    assert files.unchanged(entries)
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(package.parent))  # read to find pkg
    assert not files.unchanged(entries)


def test_a_file_that_became_a_link_out_is_not_read_to_compare_it(package, tmp_path):
    record = load_and_check(str(package / "urdf" / "one.urdf.xacro"), CheckOptions()).record
    entries = [entry for entry in record.dump() if entry[0] == "read"]
    outside = tmp_path / "outside.yaml"
    outside.write_text("lower: -1\n")  # the same content, elsewhere
    yaml = package / "urdf" / "limits.yaml"
    yaml.unlink()
    yaml.symlink_to(outside)
    os.chmod(outside, 0)  # were it opened, it could not be read: the answer would differ
    try:
        assert not files.unchanged(entries)
    finally:
        os.chmod(outside, 0o644)


def test_what_a_record_concerns(tmp_path):
    record = Record()
    with recording(record):
        files.read_regular(_write(tmp_path / "a.xacro", "<robot/>"), as_="include")
        files.listing(tmp_path, "*.yaml|*.srdf")
        files.kind_of(tmp_path / "config", follow=False)  # not there
        files.real_path(tmp_path / "link")
    assert record.concerns(tmp_path / "a.xacro")
    assert record.concerns(tmp_path / "new.yaml") and record.concerns(tmp_path / "r.srdf")
    assert not record.concerns(tmp_path / "notes.txt")
    assert record.concerns(tmp_path / "config" / "anything.txt")  # config/ was not there
    assert record.concerns(tmp_path / "link")
    assert not record.concerns(tmp_path.parent / "other.yaml")


def test_nothing_is_recorded_outside_a_block_or_in_an_unrecorded_one(tmp_path):
    from urdftool.description.record import unrecorded

    path = _write(tmp_path / "a.urdf", "<robot/>")
    with recording() as outer:
        with unrecorded():
            files.read_regular(path)
        with recording() as inner:
            files.kind_of(path)
    assert files.read_regular(path) == b"<robot/>"
    assert list(outer.entries) == list(inner.entries) == [("probe", (str(path), True))]


def _write(path, text: str):
    path.write_text(text)
    return path


def test_a_folder_changed_concerns_what_was_read_below_it_and_a_new_file_no_folder_search(
        tmp_path):
    (tmp_path / "pkg" / "meshes").mkdir(parents=True)
    mesh = _write(tmp_path / "pkg" / "meshes" / "base.stl", "solid\n")
    with recording() as record:
        files.read_regular(mesh, as_="mesh")
        files.listing(tmp_path, "*/")  # subfolders, as the package scan lists them
    assert record.concerns(tmp_path / "pkg" / "meshes")  # removed, or made a link
    assert record.concerns(tmp_path / "pkg")
    assert record.concerns(tmp_path / "new-folder")  # gone or a folder: it may be one
    assert not record.concerns(_write(tmp_path / "notes.txt", "a file, no folder\n"), file=True)


def test_an_include_pattern_is_a_search_a_new_match_changes(tmp_path):
    (tmp_path / ".git").mkdir()
    (tmp_path / "parts").mkdir()
    (tmp_path / "parts" / "a.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="a"/></robot>')
    robot = _write(tmp_path / "r.urdf.xacro",
                   '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                   '<xacro:include filename="parts/*.xacro"/></robot>')
    record = load_and_check(str(robot), CheckOptions()).record
    assert record.read_as("include") == [str(tmp_path / "parts" / "a.xacro")]
    assert record.concerns(tmp_path / "parts" / "b.xacro")
    entries = record.dump()
    assert files.unchanged(entries)
    (tmp_path / "parts" / "b.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="b"/></robot>')
    assert not files.unchanged(entries)


def test_files_are_digested_only_for_the_cache_which_compares_them_with_the_disk(package,
                                                                                 tmp_path,
                                                                                 monkeypatch):
    from urdftool.description.meshes import run_cache
    from urdftool.lint.runner import check_paths

    robot, mesh = package / "urdf" / "one.urdf.xacro", package / "meshes" / "base.stl"
    digested = []
    real_digest = files.digest
    monkeypatch.setattr(files, "digest", lambda data: digested.append(data) or real_digest(data))
    for cache_dir in (None, tmp_path / "cache"):
        run_cache.clear()  # the mesh read again, not replayed from the last run
        digested.clear()
        check_paths([str(robot)], jobs=1, timeout=0, max_memory=0,  # in this process
                    cache_dir=None if cache_dir is None else str(cache_dir))
        wanted = cache_dir is not None
        assert (mesh.read_bytes() in digested, robot.read_bytes() in digested) == (wanted, wanted)
    kept = "".join(entry.read_text() for entry in (tmp_path / "cache").rglob("*")
                   if entry.is_file())
    assert real_digest(mesh.read_bytes()) in kept and real_digest(robot.read_bytes()) in kept
    with recording() as record:  # a record made outside a run: digests, as the server's
        load_and_check(str(robot), CheckOptions())
    assert record.reads()[str(robot)].digest == real_digest(robot.read_bytes())


def test_the_records_per_thread_state_is_threading_local_without_importing_threading():
    # The record of the block running and the editor's unsaved buffers are per thread
    # (threading.local, which is _thread._local): threading itself (its 40 kB of bytecode
    # and classes) is not imported for them, and the door reads no thread of its making
    # when it is not imported.
    import subprocess
    import sys

    code = ("import sys; from urdftool.description import files, record; "
            "assert 'threading' not in sys.modules, 'threading imported'; import threading; "
            "assert threading.local in record._Active.__mro__ and "
            "threading.local in files._Unsaved.__mro__")
    subprocess.run([sys.executable, "-c", code], check=True)
