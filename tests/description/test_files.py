"""Reading untrusted files: regular files only, never over the limit."""

from __future__ import annotations

import os

import pytest

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


def test_reads_are_noted_only_inside_a_block_the_last_read_of_each(tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_bytes(b"one")
    files.read_regular(path)
    assert files.noted_reads() == {}
    with files.noting_reads(len) as notes:
        files.read_regular(path)
        assert notes == {str(path): 3}
        path.write_bytes(b"three")
        with files.noting_reads(bytes.upper) as inner:  # shares the outer block's notes
            files.read_regular(tmp_path / "." / "robot.urdf")
        assert inner is notes and files.noted_reads() is notes and notes == {str(path): 5}
    assert files.noted_reads() == {}
