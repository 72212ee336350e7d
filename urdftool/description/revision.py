"""A file as it was at a git revision, with everything it may include from that revision.

``git archive`` writes the repository's tree at the revision as a tar stream; it is unpacked
into a temporary folder with the repository's layout, so that the old side's xacro includes,
``$(find pkg)`` packages (found by their package.xml) and meshes all come from the same
revision, and the work tree is never touched. The stream is bounded in size, and unpacked with
tarfile's ``data`` filter: no links leading out, no device files, no absolute paths. What is
loaded from there goes through the same reader as any robot (containment, size limits).
"""

from __future__ import annotations

import os
import subprocess
import tarfile
import tempfile
from contextlib import contextmanager
from pathlib import Path

from urdftool.errors import UsageError

MAX_ARCHIVE_BYTES = 512 * 1024 * 1024
GIT_TIMEOUT = 60  # [s]


def _git(folder: Path, *args: str) -> str:
    try:
        done = subprocess.run(["git", "-C", str(folder), *args], capture_output=True,
                              text=True, timeout=GIT_TIMEOUT, check=False)
    except (OSError, subprocess.TimeoutExpired) as error:
        raise UsageError(f"git failed: {error}") from None
    if done.returncode:
        last = (done.stderr.strip().splitlines() or ["failed"])[-1]
        raise UsageError(f"git {args[0]}: {last}")
    return done.stdout.strip()


def repository_of(path) -> tuple[Path, str]:
    """(repository root, the path of ``path`` relative to it, with / separators); UsageError
    when ``path`` is not in a git work tree."""
    folder = Path(os.path.abspath(path)).parent
    if not folder.is_dir():
        raise UsageError(f"'{path}': folder does not exist")
    root = Path(_git(folder, "rev-parse", "--show-toplevel"))
    relative = Path(os.path.realpath(folder)).relative_to(os.path.realpath(root))
    return root, (relative / Path(path).name).as_posix()


def _safe_member(member, destination):
    """tarfile's ``data`` filter, member by member: what it refuses (a link leading out of the
    tree, a device file) is left out instead of stopping the whole unpacking."""
    try:
        return tarfile.data_filter(member, destination)
    except tarfile.FilterError:
        return None


@contextmanager
def checkout(path, revision: str, max_bytes: int = MAX_ARCHIVE_BYTES):
    """Yield (the root of the repository at ``revision`` in a temporary folder, the path of
    ``path`` in it); the folder is removed afterwards. UsageError when the revision or the
    file at it does not exist, or the tree is over ``max_bytes``."""
    if revision.startswith("-"):
        raise UsageError(f"revision '{revision}' may not start with '-'")
    root, relative = repository_of(path)
    try:
        commit = _git(root, "rev-parse", "--verify", "--quiet", "--end-of-options",
                      f"{revision}^{{commit}}") if revision else ""
    except UsageError:
        commit = ""
    if not commit:
        raise UsageError(f"revision '{revision}' not found in {root}")
    kind = subprocess.run(["git", "-C", str(root), "cat-file", "-t", f"{commit}:{relative}"],
                          capture_output=True, text=True, timeout=GIT_TIMEOUT)
    if kind.returncode or kind.stdout.strip() != "blob":
        raise UsageError(f"'{relative}' does not exist at revision '{revision}'")
    with tempfile.TemporaryDirectory(prefix="urdftool-rev-") as folder:
        archive = Path(folder) / "tree.tar"
        with open(archive, "wb") as out:
            process = subprocess.Popen(["git", "-C", str(root), "archive", "--format=tar",
                                        commit], stdout=subprocess.PIPE,
                                       stderr=subprocess.DEVNULL)
            written = 0
            while chunk := process.stdout.read(1 << 20):
                written += len(chunk)
                if written > max_bytes:
                    process.kill()
                    process.wait()
                    raise UsageError(f"the repository at '{revision}' is over {max_bytes} "
                                     "bytes; not unpacked")
                out.write(chunk)
            if process.wait(timeout=GIT_TIMEOUT):
                raise UsageError(f"git archive {revision} failed")
        tree = Path(folder) / "tree"
        tree.mkdir()
        with tarfile.open(archive) as tar:
            tar.extractall(tree, filter=_safe_member)
        archive.unlink()
        yield tree, tree / relative
