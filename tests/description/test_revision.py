"""A file at a git revision, with its includes from the same revision; the work tree untouched."""

from __future__ import annotations

import shutil
import subprocess

import pytest

from urdftool.description.revision import checkout
from urdftool.errors import UsageError

MAIN = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="parts/link.xacro"/>
  <xacro:part name="a"/>
</robot>
"""
PART = """<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="part" params="name"><link name="${name}"/></xacro:macro>
</robot>
"""


@pytest.fixture
def repo(tmp_path):
    if shutil.which("git") is None:
        pytest.skip("git is not installed")
    (tmp_path / "parts").mkdir()
    (tmp_path / "robot.urdf.xacro").write_text(MAIN)
    (tmp_path / "parts" / "link.xacro").write_text(PART)

    def git(*args):
        subprocess.run(["git", "-C", str(tmp_path), *args], check=True, capture_output=True)

    git("init", "-q")
    git("-c", "user.email=t@t", "-c", "user.name=t", "add", ".")
    git("-c", "user.email=t@t", "-c", "user.name=t", "commit", "-qm", "one")
    # the work tree moves on: the include now names another link
    (tmp_path / "parts" / "link.xacro").write_text(PART.replace("${name}", "${name}_new"))
    return tmp_path


def test_the_old_side_reads_its_includes_from_the_same_revision(repo):
    from urdftool.description.load import load

    with checkout(repo / "robot.urdf.xacro", "HEAD") as (tree, path):
        assert path == tree / "robot.urdf.xacro" and tree != repo
        assert list(load(path).links) == ["a"]
    assert list(load(repo / "robot.urdf.xacro").links) == ["a_new"]
    assert not tree.exists()  # removed afterwards
    status = subprocess.run(["git", "-C", str(repo), "status", "--porcelain"],
                            capture_output=True, text=True).stdout
    assert status.strip() == "M parts/link.xacro"  # the work tree as it was


@pytest.mark.parametrize("revision, message", [
    ("nope", "revision 'nope' not found"),
    ("--output=x", "may not start with '-'"),
])
def test_a_bad_revision_is_a_usage_error(repo, revision, message):
    with pytest.raises(UsageError, match=message):
        with checkout(repo / "robot.urdf.xacro", revision):
            pass


def test_a_file_absent_at_the_revision_is_a_usage_error(repo):
    (repo / "new.urdf").write_text("<robot name='n'/>")
    with pytest.raises(UsageError, match="does not exist at revision 'HEAD'"):
        with checkout(repo / "new.urdf", "HEAD"):
            pass


def test_a_file_outside_a_repository_is_a_usage_error(tmp_path):
    (tmp_path / "r.urdf").write_text("<robot name='n'/>")
    with pytest.raises(UsageError, match="git"):
        with checkout(tmp_path / "r.urdf", "HEAD"):
            pass


def test_the_tree_is_bounded_in_size(repo):
    with pytest.raises(UsageError, match="over 100 bytes"):
        with checkout(repo / "robot.urdf.xacro", "HEAD", max_bytes=100):
            pass


def test_a_link_leading_out_of_the_tree_is_left_out(repo):
    (repo / "escape").symlink_to("/etc")
    for args in (["add", "escape"], ["commit", "-qm", "link"]):
        subprocess.run(["git", "-C", str(repo), "-c", "user.email=t@t", "-c", "user.name=t",
                        *args], check=True, capture_output=True)
    with checkout(repo / "robot.urdf.xacro", "HEAD") as (tree, path):
        assert path.is_file() and not (tree / "escape").exists()
        assert not (tree / "escape").is_symlink()
