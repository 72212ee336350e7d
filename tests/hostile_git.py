"""Git repositories whose configuration names a program for every key that can run one, each
program writing a marker file: the tests of ``diff --rev`` (tests/description/test_revision.py)
and the fuzzer's embedded repositories (tests/fuzz/cases.py) build them here.

The keys come from git-config(1) and gitattributes(5): the ones git reads to run a program by
itself (fsmonitor, hooks, pager, editors, filters, diff and merge drivers, transports and their
helpers, signing), plus ``core.worktree`` and ``include.path`` that would move what git reads.
"""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

ROBOT = '<robot name="r"><link name="a"/></robot>\n'
HOOKS = ("pre-commit", "post-checkout", "post-index-change", "reference-transaction",
         "pre-auto-gc", "post-merge", "pre-push", "post-rewrite", "fsmonitor-watchman")
_USER = ("-c", "user.email=t@t", "-c", "user.name=t", "-c", "commit.gpgSign=false")


def git(folder: Path, *args: str) -> str:
    """Plain git on ``folder`` (the tests' own, trusted use), without the user's config."""
    done = subprocess.run(["git", "-C", str(folder), *_USER, *args], check=True,
                          capture_output=True, text=True,
                          env={"PATH": "/usr/bin:/bin", "HOME": str(folder),
                               "GIT_CONFIG_NOSYSTEM": "1", "GIT_CONFIG_GLOBAL": "/dev/null"})
    return done.stdout.strip()


def has_git() -> bool:
    return shutil.which("git") is not None


def config(markers: Path) -> str:
    """A git config naming, for every key that runs a program, one that writes a file named
    after the key into ``markers``."""
    def run(name: str, then: str = "false") -> str:
        return f'"touch {markers}/{name}; {then}"'

    return f"""[core]
\trepositoryformatversion = 1
\tbare = false
\tfsmonitor = {run("core.fsmonitor")}
\thooksPath = {markers.parent / "hooks"}
\tpager = {run("core.pager", "cat")}
\teditor = {run("core.editor")}
\tsshCommand = {run("core.sshCommand")}
\tgitProxy = {run("core.gitProxy")}
\taskPass = {run("core.askPass")}
\talternateRefsCommand = {run("core.alternateRefsCommand")}
\tuntrackedCache = true
[sequence]
\teditor = {run("sequence.editor")}
[filter "evil"]
\tsmudge = {run("filter.smudge", "cat")}
\tclean = {run("filter.clean", "cat")}
\tprocess = {run("filter.process")}
\trequired = true
[diff]
\texternal = {run("diff.external")}
[diff "evil"]
\ttextconv = {run("diff.textconv", "cat")}
\tcommand = {run("diff.command")}
[merge "evil"]
\tdriver = {run("merge.driver")}
[credential]
\thelper = {run("credential.helper")}
[gpg]
\tprogram = {run("gpg.program")}
[log]
\tshowSignature = true
[uploadpack]
\tpackObjectsHook = {run("uploadpack.packObjectsHook")}
[extensions]
\tpartialClone = origin
[remote "origin"]
\turl = ssh://example.invalid/robot
\tpromisor = true
\tuploadpack = {run("remote.uploadpack")}
\treceivepack = {run("remote.receivepack")}
[protocol]
\tallow = always
[alias]
\tcat-file = {run("alias")}
"""


def including(path: Path) -> str:
    """Config lines that include ``path`` (git reads it as configuration, wherever it is)."""
    return f"[include]\n\tpath = {path}\n"


def hooks(markers: Path) -> None:
    """A hooks folder (``core.hooksPath``) whose every hook writes its marker."""
    folder = markers.parent / "hooks"
    folder.mkdir(exist_ok=True)
    for name in HOOKS:
        hook = folder / name
        hook.write_text(f"#!/bin/sh\ntouch {markers}/hook-{name}\n")
        hook.chmod(0o755)


def repository(root: Path, markers: Path) -> Path:
    """A repository at ``root`` with ``robot/robot.urdf`` and a ``.gitattributes`` naming the
    filter and diff driver ``evil`` for every file, committed; ``markers`` made empty."""
    markers.mkdir(parents=True, exist_ok=True)
    hooks(markers)
    (root / "robot").mkdir(parents=True, exist_ok=True)
    (root / "robot" / "robot.urdf").write_text(ROBOT)
    (root / ".gitattributes").write_text("* filter=evil diff=evil merge=evil\n")
    git(root, "init", "-q")
    git(root, "add", ".")
    git(root, "commit", "-qm", "robot")
    return root


def embed_bare_repository(folder: Path, markers: Path) -> str:
    """Make ``folder`` (a folder of a checkout) a bare repository as a pull request can commit
    it: ``HEAD``, ``config`` (every key of :func:`config`, and ``core.worktree = .`` so that
    git takes the folder for the top level), ``objects/`` holding a commit of its own whose
    tree has the folder's ``robot.urdf`` and a ``.gitattributes`` naming the filter, and
    ``refs/``. Returns that commit."""
    source = folder.parent / f".{folder.name}-source"
    source.mkdir()
    (source / "robot.urdf").write_text(ROBOT)
    (source / ".gitattributes").write_text("* filter=evil diff=evil\n")
    git(source, "init", "-q")
    git(source, "add", ".")
    git(source, "commit", "-qm", "planted")
    commit = git(source, "rev-parse", "HEAD")
    shutil.copytree(source / ".git" / "objects", folder / "objects", dirs_exist_ok=True)
    shutil.rmtree(source)
    (folder / "HEAD").write_text(commit + "\n")
    (folder / "refs" / "heads").mkdir(parents=True, exist_ok=True)
    (folder / "refs" / "heads" / ".keep").write_text("")
    (folder / "config").write_text(config(markers).replace(
        "repositoryformatversion = 1", "repositoryformatversion = 0\n\tworktree = .")
        .replace("[extensions]\n\tpartialClone = origin\n", ""))
    return commit


def make_partial(root: Path, path: str) -> None:
    """Remove the blob of ``path`` at HEAD from the object store of the repository at ``root``,
    as a partial clone lacks it: git fetches it from the promisor remote when asked for it."""
    blob = git(root, "rev-parse", f"HEAD:{path}")
    (root / ".git" / "objects" / blob[:2] / blob[2:]).unlink()


def markers_found(markers: Path) -> list[str]:
    return sorted(path.name for path in markers.iterdir())
