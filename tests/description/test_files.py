"""Reading untrusted files: regular files only, never over the limit."""

from __future__ import annotations

import ast
import os
from pathlib import Path

import pytest

from conftest import walked
from urdftool.description import files


def _stat_says(monkeypatch, path, size: int) -> None:
    """``os.stat`` reports ``size`` bytes for ``path``: the file grew after it was looked at."""
    real = os.stat

    def stat(name, *args, **kwargs):
        found = real(name, *args, **kwargs)
        if os.fspath(name) != str(path):
            return found
        fields = list(found)
        fields[6] = size  # st_size
        return os.stat_result(fields)

    monkeypatch.setattr(files.os, "stat", stat)


def test_a_regular_file_is_read_whole(tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_bytes(b"<robot/>" * 1000)
    assert files.read_regular(path, limit=8000) == b"<robot/>" * 1000
    with pytest.raises(files.TooLarge):
        files.read_regular(path, limit=7999)


def test_a_file_that_grew_after_its_stat_is_read_to_the_end_within_the_limit(tmp_path,
                                                                             monkeypatch):
    path = tmp_path / "robot.urdf"
    path.write_bytes(b"x" * 5000)
    _stat_says(monkeypatch, path, 10)
    assert files.read_regular(path, limit=5000) == b"x" * 5000


def test_a_file_that_grew_over_the_limit_after_its_stat_is_refused(tmp_path, monkeypatch):
    path = tmp_path / "robot.urdf"
    path.write_bytes(b"x" * 5000)
    _stat_says(monkeypatch, path, 10)
    with pytest.raises(files.TooLarge):
        files.read_regular(path, limit=4999)


def test_a_folder_or_fifo_is_not_read(tmp_path):
    with pytest.raises(OSError, match="not a regular file"):
        files.read_regular(tmp_path)
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    with pytest.raises(OSError, match="not a regular file"):
        files.read_regular(fifo)


def test_real_path_is_realpaths_answer_within_a_run_and_without(tmp_path, monkeypatch):
    from urdftool.description.run_memo import one_run

    (tmp_path / "pkg" / "meshes").mkdir(parents=True)
    (tmp_path / "pkg" / "meshes" / "arm.stl").write_bytes(b"solid")
    (tmp_path / "elsewhere").mkdir()
    (tmp_path / "elsewhere" / "secret.stl").write_bytes(b"solid")
    (tmp_path / "pkg" / "meshes" / "link.stl").symlink_to(tmp_path / "elsewhere" / "secret.stl")
    (tmp_path / "pkg" / "linked").symlink_to(tmp_path / "elsewhere")
    (tmp_path / "pkg" / "dangling.stl").symlink_to(tmp_path / "nowhere.stl")
    (tmp_path / "pkg" / "loop").symlink_to(tmp_path / "pkg" / "loop")
    monkeypatch.chdir(tmp_path / "pkg")
    names = ["meshes/arm.stl", "meshes/link.stl", "linked/secret.stl", "linked/../meshes/arm.stl",
             "dangling.stl", "missing/arm.stl", "loop", "loop/arm.stl", "meshes/", "meshes/.",
             "meshes/..", ".", "arm.stl", "//" + str(tmp_path)[1:] + "/pkg/meshes/arm.stl",
             str(tmp_path / "pkg" / "linked" / "secret.stl"), "/"]
    expected = [os.path.realpath(name) for name in names]
    assert [files.real_path(name) for name in names] == expected
    with one_run():
        assert [files.real_path(name) for name in names] == expected
        assert [files.real_path(name) for name in reversed(names)] == expected[::-1]


# ---- the one door: no module of urdftool but files.py touches the file system itself -----------

PACKAGE = Path(__file__).resolve().parents[2] / "urdftool"
DOOR = "description/files.py"
# Modules that still reach the file system themselves, each with why; the test fails on an
# entry no longer needed, so the list only shrinks.
ELSEWHERE = {
    "description/revision.py": "runs git to unpack an old revision into a temporary folder "
                               "(git's objects, not the work tree a check's record describes)",
    # urdftool's own files, never a robot's (to move onto files.read_own and friends):
    "__main__.py": "reads urdftool's own help texts and command modules before anything else "
                   "is imported, for a fast --help",
    "docs.py": "generates urdftool's own documentation from its checkout (make docs)",
    "origin.py": "reads where urdftool itself was installed from (its dist-info, its checkout)",
    "budget.py": "a worker's own address space (/proc/self/statm) and the machine's load "
                 "(/proc/loadavg), never a file a check reads",
}
# Calls that open, stat, list, glob, follow links or write, by the dotted name they are made
# through (a module's function) ...
_MODULE_CALLS = {
    "open", "io.open", "os.open", "os.stat", "os.lstat", "os.listdir", "os.scandir", "os.walk",
    "os.fwalk", "os.readlink", "os.access", "os.path.exists", "os.path.lexists",
    "os.path.isfile", "os.path.isdir", "os.path.islink", "os.path.ismount", "os.path.getsize",
    "os.path.getmtime", "os.path.getctime", "os.path.getatime", "os.path.realpath",
    "os.path.samefile", "os.makedirs", "os.mkdir", "os.remove", "os.unlink", "os.rename",
    "os.replace", "os.chmod", "os.rmdir", "glob.glob", "glob.iglob", "tomllib.load",
    "np.load", "np.fromfile", "numpy.load", "numpy.fromfile",
}
# ... library functions that take a path or a file object: only what is in memory (bytes read
# through the door in ``io.BytesIO(data)``, a list of lines) may be given ...
_PATH_OR_FILE = {"etree.parse", "lxml.etree.parse", "ElementTree.parse", "trimesh.load",
                 "trimesh.load_mesh", "zipfile.is_zipfile", "zipfile.ZipFile", "tarfile.open",
                 "Image.open", "PIL.Image.open", "shutil.copy", "shutil.copyfile", "np.loadtxt",
                 "numpy.loadtxt", "np.genfromtxt"}
# ... and pathlib's methods (any receiver; ``resolve``, ``exists`` and ``stat`` without
# arguments, so that ``meshes.resolve(robot, uri)`` is not one).
_PATH_METHODS = {"glob", "rglob", "iterdir", "is_file", "is_dir", "is_symlink", "read_bytes",
                 "read_text", "write_bytes", "write_text", "open", "samefile", "readlink",
                 "is_mount", "touch", "mkdir", "unlink", "rmdir", "lstat", "walk"}
_PATH_METHODS_WITHOUT_ARGUMENTS = {"resolve", "exists", "stat"}
_DOOR_NAMES = {"files"}  # ``files.listing(...)``: the door's own functions


def _dotted(node) -> str | None:
    parts = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    if isinstance(node, ast.Name):
        return ".".join([node.id, *reversed(parts)])
    return None


def _in_memory(node) -> bool:
    return isinstance(node, (ast.List, ast.ListComp)) or isinstance(node, ast.Call) and \
        _dotted(node.func) in ("io.BytesIO", "BytesIO", "io.StringIO", "StringIO")


def file_system_calls(source: str) -> list[tuple[int, str]]:
    """(line, call) of every place ``source`` touches the file system itself."""
    found = []
    for node in walked(source):
        if isinstance(node, ast.ImportFrom) and node.module in ("os", "os.path", "glob",
                                                                 "shutil", "pathlib"):
            for alias in node.names:
                if f"{node.module}.{alias.name}" in _MODULE_CALLS or node.module in (
                        "glob", "shutil"):
                    found.append((node.lineno, f"from {node.module} import {alias.name}"))
        if not isinstance(node, ast.Call):
            continue
        name = _dotted(node.func)
        if name == "os.open" and node.args and _dotted(node.args[0]) == "os.devnull":
            continue  # standard output sent nowhere (a closed pipe): no file of anyone's
        if name in _MODULE_CALLS:
            found.append((node.lineno, name))
        elif name in _PATH_OR_FILE:
            if not (node.args and _in_memory(node.args[0])):
                found.append((node.lineno, name))
        elif isinstance(node.func, ast.Attribute):
            method, receiver = node.func.attr, _dotted(node.func.value)
            if receiver in _DOOR_NAMES:
                continue
            if method in _PATH_METHODS or method in _PATH_METHODS_WITHOUT_ARGUMENTS and \
                    not node.args:
                found.append((node.lineno, f".{method}()"))
    return found


def _modules() -> dict[str, Path]:
    """Every module of urdftool, by its path below the package."""
    return {path.relative_to(PACKAGE).as_posix(): path for path in sorted(PACKAGE.rglob("*.py"))}


# ---- unsaved buffers (the language server's overlay) -----------------------------------

MACRO = b'<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro name="m"/></robot>'


def test_an_unsaved_buffer_is_read_for_its_file_and_recorded_as_read_so(tmp_path):
    from urdftool.description.record import recording

    path = tmp_path / "arm.xacro"
    path.write_bytes(b"<robot/>")
    link = tmp_path / "link.xacro"
    link.symlink_to(path)
    with recording() as record, files.unsaved({str(path): "<robot>é</robot>"}) as served:
        assert served == set()
        assert files.read_regular(link) == "<robot>é</robot>".encode()  # the file it leads to
        assert files.read_regular(path) == "<robot>é</robot>".encode()
    assert served == {str(path)}
    assert files.read_regular(path) == b"<robot/>"  # the block ended
    read = record.reads()[str(path)]
    assert (read.stamp, read.size, read.digest) == \
        (None, 17, files.digest("<robot>é</robot>".encode()))
    entries = record.dump()
    assert not files.unchanged(entries)  # the disk has other bytes: not a result from disk
    path.write_text("<robot>é</robot>")
    assert files.unchanged(entries)  # saved: the same bytes


def test_a_buffer_obeys_the_size_limit_and_nested_blocks_add_theirs(tmp_path):
    path, other = tmp_path / "a.xacro", tmp_path / "b.xacro"
    path.write_bytes(b"x")
    other.write_bytes(b"y")
    with files.unsaved({str(path): b"z" * 100}) as outer:
        with pytest.raises(files.TooLarge) as error:
            files.read_regular(path, limit=99)
        assert error.value.size == 100
        assert outer == set()  # refused: not read
        with files.unsaved({str(other): b"w"}) as inner:
            assert files.read_regular(path) == b"z" * 100
            assert files.read_regular(other) == b"w"
        assert (outer, inner) == ({str(path)}, {str(other)})
    assert files.read_own(path, 100) == b"x"


def test_a_buffer_is_read_only_where_the_disk_would_be(tmp_path):
    """A buffer for a file outside the repository, or reached through a link leading out of
    it, is not read by a check that would not read that file from disk."""
    from urdftool.description.load import load
    from urdftool.errors import LoadError

    repository, outside = tmp_path / "repo", tmp_path / "elsewhere"
    (repository / ".git").mkdir(parents=True)
    outside.mkdir()
    (outside / "arm.xacro").write_bytes(MACRO)
    (repository / "link.xacro").symlink_to(outside / "arm.xacro")
    buffers = {str(outside / "arm.xacro"): MACRO.replace(b'name="m"', b'name="n"'),
               str(repository / "link.xacro"): MACRO}
    for include in ["link.xacro", "../elsewhere/arm.xacro"]:
        robot = repository / "robot.urdf.xacro"
        robot.write_text(f'<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                         f'<xacro:include filename="{include}"/><link name="a"/></robot>')
        with files.unsaved(buffers) as served, pytest.raises(LoadError) as error:
            load(robot, allow_env=False)
        assert error.value.kind in ("link", "outside"), include
        assert served == set(), include


def test_only_the_door_opens_stats_lists_or_globs_files():
    """Every read of urdftool (the description, the linter, the commands, the cross-check, the
    pytest plugin, ...) goes through description/files.py, which records it: a reader cannot
    forget to record what it read, nor be given a link the door would refuse, because it cannot
    read."""
    offenders = [f"urdftool/{name}:{line}: {call}"
                 for name, path in _modules().items()
                 if name != DOOR and name not in ELSEWHERE
                 for line, call in file_system_calls(path.read_text())]
    assert offenders == [], (
        "these touch the file system themselves; use urdftool.description.files "
        "(read_regular, kind_of, identity, listing, glob, real_path, inside; read_own for "
        "urdftool's own files), so that the check's record (description/record.py) sees it:\n"
        + "\n".join(offenders))


def test_every_exception_is_still_needed():
    modules = _modules()
    assert [name for name in ELSEWHERE if name in modules and
            file_system_calls(modules[name].read_text())] == list(ELSEWHERE)


@pytest.mark.parametrize("source", [
    "open('x')", "os.stat(p)", "os.path.exists(p)", "os.listdir(p)", "os.scandir(p)",
    "Path(p).glob('*.yaml')", "p.iterdir()", "p.is_file()", "p.resolve()", "p.exists()",
    "p.stat()", "etree.parse(str(p))", "trimesh.load(str(p))", "zipfile.is_zipfile(p)",
    "glob.glob(p)", "os.walk(p)", "from os.path import isfile", "os.path.realpath(p)",
    "p.read_bytes()", "tomllib.load(handle)", "np.loadtxt(path)", "os.open(p, os.O_RDONLY)"])
def test_the_scan_sees_each_way_of_touching_files(source):
    assert file_system_calls(source)


@pytest.mark.parametrize("source", [
    "files.read_regular(p)", "meshes.resolve(robot, uri)", "robot.resolve_uri(uri)",
    "trimesh.load(io.BytesIO(data), file_type='stl')", "files.walk(folder)", "d.get(k)",
    "zipfile.is_zipfile(io.BytesIO(data))", "text.replace('a', 'b')", "match.group(1)",
    "np.loadtxt([text])", "os.open(os.devnull, os.O_WRONLY)"])
def test_the_scan_lets_the_door_and_bytes_through(source):
    assert file_system_calls(source) == []


def test_real_path_of_a_folder_deeper_than_the_recursion_limit(tmp_path):
    """_real_path asks the folder above for its answer (each a few frames): a folder 400 deep,
    committed in a repository, ended `check DIR` in a RecursionError."""
    from urdftool.description.run_memo import one_run

    deep = tmp_path.joinpath(*["d"] * 400)
    deep.mkdir(parents=True)
    (deep / "r.urdf").write_text("<robot/>")
    with one_run():
        assert files.real_path(deep / "r.urdf") == os.path.realpath(deep / "r.urdf")


def test_a_path_that_cannot_be_reached_is_not_said_missing(tmp_path, monkeypatch, run_cli):
    """A robot behind a folder the user may not search was reported as 'does not exist', a
    file that may well be there (attack8, session 8): the system's reason is said instead."""
    from urdftool.description import files

    assert files.unreachable(tmp_path / "nothing.urdf") == "does not exist"
    (tmp_path / "link.urdf").symlink_to(tmp_path / "nothing.urdf")
    assert files.unreachable(tmp_path / "link.urdf") == "does not exist"
    robot = tmp_path / "robot.urdf"

    def refused(path, *args, **kwargs):
        raise PermissionError(13, "Permission denied", str(path))

    monkeypatch.setattr(files.os, "stat", refused)
    monkeypatch.setattr(files.os, "lstat", refused)
    assert files.unreachable(robot) == "cannot be reached: permission denied"
    result = run_cli("check", robot)
    assert result.exit_code == 2 and "cannot be reached: permission denied" in result.stderr


def test_walk_depth_first_or_breadth_first_and_bounded(tmp_path):
    """walk lists each folder once, in sorted order depth first, or level by level (the
    package scan's order: the shallower of two packages of one name wins), at most ``most``
    folders; a hidden folder, one in ``skip`` or one past ``depth`` is not entered; a link
    (here to a folder) is listed, never entered; each listing is recorded."""
    from urdftool.description.record import SEARCH, recording

    for name in ("a/x/deep", "b/y", "c", ".hidden/h", "skipped/s"):
        (tmp_path / name).mkdir(parents=True)
    (tmp_path / "a" / "x" / "f.txt").write_text("")
    (tmp_path / "link").symlink_to(tmp_path / "b")

    def order(**options):
        with recording() as record:
            found = [(os.path.relpath(folder, tmp_path), entries) for folder, entries in
                     files.walk(tmp_path, "*/|*.txt", options.pop("depth", 9), {"skipped"},
                                **options)]
        listed = [os.path.relpath(key[0], tmp_path) for kind, key in record.entries
                  if kind == SEARCH]
        assert listed == [folder for folder, _ in found]
        return found

    depth_first = order()
    assert [folder for folder, _ in depth_first] == [".", "a", "a/x", "a/x/deep", "b", "b/y",
                                                     "c"]
    assert dict(depth_first)["a/x"] == [("deep", "folder"), ("f.txt", "file")]
    assert ("link", "link") in dict(depth_first)["."]
    assert [folder for folder, _ in order(breadth_first=True)] == [
        ".", "a", "b", "c", "a/x", "b/y", "a/x/deep"]
    assert [folder for folder, _ in order(breadth_first=True, most=4)] == [".", "a", "b", "c"]
    assert [folder for folder, _ in order(breadth_first=True, depth=2)] == [".", "a", "b", "c"]


@pytest.mark.parametrize("pattern", [
    "*", "", "*.launch|*.py|*.xml|*.yaml|*.yml|[!.]*/", "package.xml|[!.]*/", "[!.]*",
    "*.launch.py", "a*b|x?y|*.[ch]", ".*|*/", "CMakeLists.txt|*.stl/", "*[!/]|[a-c]*.py"])
def test_a_listings_pattern_matches_as_fnmatch_does(pattern):
    """The walk's and listing's selection (names compared, endings, a first character, or one
    expression) takes the entries :func:`urdftool.description.record.matches` takes, of every
    kind."""
    import random

    from urdftool.description.record import matches

    pool = ["", ".", "..", ".git", "a", "b.py", "x.launch.py", "package.xml", "Package.xml",
            "a\nb.py", "a.c", "a.h", "xzy", "acb", "a*b", "*.py", "[!.]", "CMakeLists.txt",
            "m.STL", "m.stl", ".y.yml", "launch", "é.xml", "a/"]
    generated = ["".join(random.Random(seed).choices("ab.*?[]!/\nxyl", k=seed % 7))
                 for seed in range(300)]
    entries = tuple((name, kind) for name in pool + generated
                    for kind in ("file", "folder", "link", "other"))
    assert files._selected(pattern)(entries) == \
        tuple(entry for entry in entries if matches(*entry, pattern))


def test_a_file_replaced_keeps_its_owner_and_group_where_the_writer_may_give_them(tmp_path):
    """``sudo urdftool check --fix`` (and ``-o`` over a file of another's) left the file root's:
    the temporary file that replaces it kept the writer's owner."""
    target = tmp_path / "robot.urdf"
    target.write_text("<robot/>")
    others = [group for group in os.getgroups() if group != os.getegid()]
    if os.geteuid() == 0:
        owner, group = 4321, 4321
    elif others:
        owner, group = os.geteuid(), others[0]
    else:
        pytest.skip("not root and in no other group: no owner to give a file")
    os.chown(target, owner, group)
    files.write_file(target, "<robot name='x'/>", rewrites=True)
    kept = target.stat()
    assert (kept.st_uid, kept.st_gid) == (owner, group)
    assert target.read_text() == "<robot name='x'/>"


def test_a_file_no_one_may_write_is_not_replaced(tmp_path):
    """``check --fix`` of a robot at mode 0444 (a generated or installed file) replaced it by a
    rename, which the file's mode does not guard (as root or not), where ``>`` refuses it."""
    from urdftool.errors import UsageError

    target = tmp_path / "robot.urdf"
    target.write_text("<robot/>")
    target.chmod(0o444)
    with pytest.raises(UsageError, match=r"cannot write '.*robot.urdf': it is read-only "
                                         r"\(mode 0444\)"):
        files.write_file(target, "<robot name='x'/>", rewrites=True)
    assert target.read_text() == "<robot/>" and [p.name for p in tmp_path.iterdir()] == \
        ["robot.urdf"]
    target.chmod(0o644)
    files.write_file(target, "<robot name='x'/>", rewrites=True)
    assert target.read_text() == "<robot name='x'/>"


@pytest.mark.parametrize("name", ["r" * 250 + ".urdf", "é" * 125 + ".urdf",
                                  os.fsdecode(b"\xff" * 250 + b".urdf")])
def test_a_file_whose_name_fills_the_folders_longest_name_is_written(tmp_path, name):
    """``check --fix`` of a robot named with 255 bytes was "File name too long": the temporary
    file beside it was named ``.NAME.XXXXXXXX.tmp``, its name and 14 more bytes."""
    target = tmp_path / name
    target.write_text("<robot/>")
    files.write_file(target, "<robot name='x'/>", rewrites=True)
    assert target.read_text() == "<robot name='x'/>"
    assert [p.name for p in tmp_path.iterdir()] == [name]
