"""A file at a git revision, with its includes from the same revision; the work tree untouched."""

from __future__ import annotations

import re
import shutil
import subprocess

import pytest
from conftest import walked
from hostile_git import (config, embed_bare_repository, git, has_git, make_partial,
                         markers_found, repository)

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


# ---- git is told its repository, and runs nothing a repository's configuration names -------



@pytest.fixture
def hostile(tmp_path):
    """A repository with robot/robot.urdf, a marker folder outside it, and a hooks folder."""
    if not has_git():
        pytest.skip("git is not installed")
    markers = tmp_path / "markers"
    return repository(tmp_path / "repo", markers), markers


def test_an_embedded_bare_repository_is_never_taken_for_the_repository(hostile):
    """A pull request commits HEAD, config, objects/ and refs/ into the robot's folder: git's
    own discovery from that folder takes it for a repository and runs the filter its config
    names (the positive control); urdftool names the repository itself and reads the real
    one's commit, and nothing the planted config names runs."""
    root, markers = hostile
    embed_bare_repository(root / "robot", markers)
    git(root, "add", "-f", "robot")
    git(root, "commit", "-qm", "a repository inside the robot's folder")
    control = subprocess.run(["git", "-C", str(root / "robot"), "archive", "HEAD"],
                             capture_output=True, env={"PATH": "/usr/bin:/bin",
                                                       "GIT_CONFIG_NOSYSTEM": "1"})
    assert "filter.process" in markers_found(markers), control.stderr
    for marker in markers.iterdir():
        marker.unlink()
    with checkout(root / "robot" / "robot.urdf", "HEAD") as (tree, path):
        assert path == tree / "robot" / "robot.urdf"  # the real repository's layout
        assert (tree / "robot" / "config").is_file()  # the planted files are data
    assert markers_found(markers) == []


def test_the_repository_configuration_runs_nothing(hostile, monkeypatch):
    """The repository's own config (a stranger's, in an unpacked archive) names a program for
    every key that can run one, the tree names the filter and diff driver, the blob of the
    robot is missing as in a partial clone, and the caller's environment points git
    elsewhere: a plain ``git cat-file`` runs the remote's ssh command (the positive
    control); urdftool reads what is there and runs nothing."""
    root, markers = hostile
    (root / "robot" / "other.urdf").write_text("<robot name='o'/>\n")
    git(root, "add", ".")
    git(root, "commit", "-qm", "another robot")
    make_partial(root, "robot/other.urdf")
    with open(root / ".git" / "config", "a") as handle:
        handle.write(config(markers))
    control = subprocess.run(["git", "-C", str(root), "cat-file", "-p", "HEAD:robot/other.urdf"],
                             capture_output=True, env={"PATH": "/usr/bin:/bin",
                                                       "GIT_CONFIG_NOSYSTEM": "1"})
    assert control.returncode != 0 and "core.sshCommand" in markers_found(markers)
    for marker in markers.iterdir():
        marker.unlink()
    elsewhere = root.parent / "elsewhere"
    elsewhere.mkdir()
    for name, value in {"GIT_DIR": str(elsewhere), "GIT_WORK_TREE": str(elsewhere),
                        "GIT_EXTERNAL_DIFF": f"touch {markers}/GIT_EXTERNAL_DIFF",
                        "GIT_SSH_COMMAND": f"touch {markers}/GIT_SSH_COMMAND",
                        "GIT_PAGER": f"touch {markers}/GIT_PAGER",
                        "GIT_CONFIG_PARAMETERS": "'core.fsmonitor'='touch /dev/null'"}.items():
        monkeypatch.setenv(name, value)
    with checkout(root / "robot" / "robot.urdf", "HEAD") as (tree, path):
        assert path.read_text() == (root / "robot" / "robot.urdf").read_text()
        assert not (tree / "robot" / "other.urdf").exists()  # missing, never fetched
    with pytest.raises(UsageError, match="not in the repository's object store"):
        with checkout(root / "robot" / "other.urdf", "HEAD"):
            pass
    assert markers_found(markers) == []


def test_diff_rev_through_the_command_line_runs_nothing(hostile, run_cli):
    root, markers = hostile
    embed_bare_repository(root / "robot", markers)
    git(root, "add", "-f", "robot")
    git(root, "commit", "-qm", "planted")
    with open(root / ".git" / "config", "a") as handle:
        handle.write(config(markers).replace("[extensions]\n\tpartialClone = origin\n", ""))
    result = run_cli("diff", "--rev", "HEAD", root / "robot" / "robot.urdf")
    assert result.exit_code == 0, result.output
    assert "HEAD:robot/robot.urdf" in result.output
    assert markers_found(markers) == []


def test_names_in_the_tree_that_are_not_plain_are_left_out(repo):
    """A tree object can hold any name (one fetched without fsck): '..' and the like never
    become a path out of the temporary folder; links leading out are not made."""
    (repo / "inside").symlink_to("parts")
    (repo / "loop").symlink_to("loop2")
    (repo / "loop2").symlink_to("./loop")
    git(repo, "add", "inside", "loop", "loop2")
    git(repo, "commit", "-qm", "links")
    tree_id = git(repo, "rev-parse", "HEAD^{tree}")
    blob = git(repo, "rev-parse", "HEAD:robot.urdf.xacro")
    listing = git(repo, "ls-tree", tree_id)
    crafted = subprocess.run(
        ["git", "-C", str(repo), "mktree", "--missing"], check=True, capture_output=True,
        text=True, input=listing + f"\n100644 blob {blob}\t..\n100644 blob {blob}\t.git\n"
    ).stdout.strip()
    commit = git(repo, "commit-tree", crafted, "-m", "crafted")
    with checkout(repo / "robot.urdf.xacro", commit) as (tree, path):
        assert path.is_file() and (tree / "inside" / "link.xacro").is_file()
        assert not (tree / "loop").exists() or (tree / "loop").resolve().is_relative_to(tree)
        assert sorted(p.name for p in tree.parent.iterdir()) == ["tree"]


def test_the_size_of_the_tree_is_known_before_any_blob_is_read(repo, monkeypatch):
    from urdftool.description import revision

    read = []
    monkeypatch.setattr(revision, "_write_tree", lambda *args: read.append(args))
    with pytest.raises(UsageError, match="over 100 bytes"):
        with checkout(repo / "robot.urdf.xacro", "HEAD", max_bytes=100):
            pass
    assert read == []


def test_git_runs_in_one_module_only():
    """Only description/revision.py starts git; report/dot.py starts Graphviz's dot and
    crosscheck/loaders.py sdformat's `gz sdf` (docs/security.md, "programs started"); no other
    module imports subprocess, and neither of those names git."""
    import ast
    from pathlib import Path

    import urdftool

    package = Path(urdftool.__file__).parent
    starting = set()
    for module in package.rglob("*.py"):
        source = module.read_text()
        for node in walked(source):
            names = ([alias.name for alias in node.names] if isinstance(node, ast.Import) else
                     [node.module] if isinstance(node, ast.ImportFrom) else [])
            if any(name and name.split(".")[0] in ("subprocess", "pty") for name in names) or (
                    isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
                    and node.value.id == "os" and node.attr.startswith(("system", "popen",
                                                                        "exec", "spawn"))):
                starting.add(module.relative_to(package).as_posix())
    assert starting == {"description/revision.py", "report/dot.py", "crosscheck/loaders.py"}
    for other in ("report/dot.py", "crosscheck/loaders.py"):
        assert not re.search(r"\bgit\b", (package / other).read_text()), other


@pytest.mark.parametrize("section", ["[include]\n\tpath = {outside}\n",
                                     '[includeIf "gitdir:/"]\n\tpath = {outside}\n',
                                     "  [INCLUDE]\n  path = {outside}\n"])
def test_a_configuration_including_other_files_is_refused(hostile, section):
    """No command line turns git's config includes off: a repository (an unpacked archive's)
    whose config includes a file outside would have git read it. Refused before git runs."""
    root, markers = hostile
    outside = markers.parent / "outside.gitconfig"
    outside.write_text(f"[core]\n\tfsmonitor = touch {markers}/included\n")
    with open(root / ".git" / "config", "a") as handle:
        handle.write(section.format(outside=outside))
    with pytest.raises(UsageError, match="includes other files"):
        with checkout(root / "robot" / "robot.urdf", "HEAD"):
            pass
    assert markers_found(markers) == []


def test_a_worktree_reads_its_common_configuration(hostile, tmp_path):
    """A linked worktree's .git is a file naming its git folder; the common folder's config is
    the one looked at (and used)."""
    root, _ = hostile
    git(root, "worktree", "add", "-q", str(tmp_path / "linked"))
    with checkout(tmp_path / "linked" / "robot" / "robot.urdf", "HEAD") as (_, path):
        assert path.is_file()
    with open(root / ".git" / "config", "a") as handle:
        handle.write("[include]\n\tpath = /dev/null\n")
    with pytest.raises(UsageError, match="includes other files"):
        with checkout(tmp_path / "linked" / "robot" / "robot.urdf", "HEAD"):
            pass


def test_a_blob_no_reader_takes_is_left_out(repo, monkeypatch):
    """A file over the largest any reader takes is read past, not kept; the files after it in
    the tree still come (the stream stays in step)."""
    from urdftool.description import revision

    (repo / "a_big.bin").write_bytes(b"x" * 5000)
    (repo / "z_after.xacro").write_text(PART)
    git(repo, "add", "a_big.bin", "z_after.xacro")
    git(repo, "commit", "-qm", "big")
    monkeypatch.setattr(revision, "MAX_BLOB", 1000)
    with checkout(repo / "robot.urdf.xacro", "HEAD") as (tree, path):
        assert not (tree / "a_big.bin").exists()
        assert (tree / "z_after.xacro").read_text() == PART and path.is_file()


def test_a_checkout_owned_by_another_user_is_read_and_runs_nothing(hostile, monkeypatch):
    """A CI container's workspace belongs to the user that checked it out: git refuses it
    ("dubious ownership") when it discovers the repository (the positive control). urdftool
    tells git the repository and names its top level in ``safe.directory`` on the command line
    (protected configuration: the repository cannot set it), so the old side is read; the
    repository's config, whose programs are what the ownership check guards against, still
    runs nothing."""
    import os
    import pwd

    from urdftool.description import revision

    if os.geteuid() != 0:
        pytest.skip("making a checkout another user's needs root")
    root, markers = hostile
    with open(root / ".git" / "config", "a") as handle:
        handle.write(config(markers).replace("[extensions]\n\tpartialClone = origin\n", ""))
    nobody = pwd.getpwnam("nobody").pw_uid
    for folder, names, files in os.walk(root):
        for name in [*names, *files, "."]:
            os.lchown(os.path.join(folder, name), nobody, nobody)
    control = subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True,
                             text=True, env={"PATH": "/usr/bin:/bin", "GIT_CONFIG_NOSYSTEM": "1",
                                             "GIT_CONFIG_GLOBAL": os.devnull})
    assert control.returncode != 0 and "dubious ownership" in control.stderr
    commands = []
    started = subprocess.Popen

    def spy(command, *args, **kwargs):
        commands.append(command)
        return started(command, *args, **kwargs)

    monkeypatch.setattr(revision.subprocess, "Popen", spy)
    with checkout(root / "robot" / "robot.urdf", "HEAD") as (tree, path):
        assert path.read_text() == (root / "robot" / "robot.urdf").read_text()
    assert commands and all(f"safe.directory={os.path.realpath(root)}" in command
                            for command in commands)
    assert markers_found(markers) == []


def test_a_robot_file_that_was_a_link_at_the_revision_is_followed_within_the_tree(repo):
    """A committed link (``robot.urdf -> urdf/real.urdf``) is read at a revision as in the
    work tree; it was said "does not exist at revision". A link out of the tree is refused,
    saying so."""
    import os

    from urdftool.description.load import load

    def commit(message):
        for args in (["add", "-A"], ["commit", "-qm", message]):
            subprocess.run(["git", "-C", str(repo), "-c", "user.email=t@t", "-c", "user.name=t",
                            *args], check=True, capture_output=True)

    (repo / "urdf").mkdir()
    (repo / "urdf" / "real.urdf").write_text('<robot name="r"><link name="old"/></robot>\n')
    os.symlink("urdf/real.urdf", repo / "robot.urdf")
    commit("a link")
    (repo / "robot.urdf").unlink()
    (repo / "robot.urdf").write_text('<robot name="r"><link name="new"/></robot>\n')
    with checkout(repo / "robot.urdf", "HEAD") as (_, path):
        assert list(load(path).links) == ["old"]
    os.unlink(repo / "robot.urdf")
    os.symlink("/etc/hostname", repo / "robot.urdf")
    commit("a link out")
    os.unlink(repo / "robot.urdf")
    (repo / "robot.urdf").write_text('<robot name="r"><link name="new"/></robot>\n')
    with pytest.raises(UsageError, match="robot.urdf' at revision 'HEAD' is a symbolic link "
                                         "leading out of the repository"):
        with checkout(repo / "robot.urdf", "HEAD"):
            pass
