"""A file as it was at a git revision, with everything it may include from that revision; and
the one place urdftool runs git.

Every git command goes through :func:`_git`, which tells git which repository to use: the
``.git`` of the repository holding the file by urdftool's own rule
(:func:`~urdftool.description.files.repository_root`, the nearest folder above holding
``.git``), as ``--git-dir`` and ``--work-tree``. git never looks for a repository itself, so a
folder of the pull request holding ``HEAD``, ``config``, ``objects/`` and ``refs/`` (a bare
repository committed inside the checkout) is never taken for one, and its ``config`` never
read; ``GIT_CEILING_DIRECTORIES`` and ``safe.bareRepository=explicit`` refuse discovery should
anything ask for it. ``safe.directory`` names that top level, so that a checkout owned by another
user is read (git checks ownership today only for a repository it discovers; the key keeps
``diff --rev`` working should it check a repository it is told too). No system or global configuration is read, every ``GIT_*`` variable of the
caller is dropped, and the repository's own configuration (itself a stranger's in an unpacked
archive) is overridden on the command line for every key that names a program git may run on
its own: fsmonitor, hooks, pager, editor, external diff, ssh and proxy commands, askpass and
credential helpers, gpg; transports are off, so that a missing object is never fetched (a
partial clone's lazy fetch runs the remote's transport). A configuration that includes other
files (``include.path``: no option turns includes off) is refused before git runs. Only ``rev-parse``, ``ls-tree`` and
``cat-file`` (blobs as stored: no ``--filters``, no ``--textconv``) run: nothing reads the
index, checks out, archives or diffs, so no filter, textconv or diff driver is ever looked up.

The tree at the revision is written into a temporary folder with the repository's layout (a
``.git`` folder marks it as the repository), so that the old side's xacro includes,
``$(find pkg)`` packages (found by their package.xml) and meshes all come from the same
revision, and the work tree is never touched. Its size is known from ``ls-tree -l`` and bounded
before any blob is read; names are plain (no ``..``, no absolute path), gitlinks (submodules)
are left out, and a symbolic link is made only when it stays in the tree. What is loaded from
there goes through the same reader as any robot (containment, size limits).
"""

from __future__ import annotations

import os
import re
import subprocess
from contextlib import contextmanager
from pathlib import Path

from urdftool.description.files import (link_new, read_regular, remove_links_out,
                                        repository_root, temporary_folder, write_new)
from urdftool.description.inputs import MAX_MESH_BYTES
from urdftool.errors import UsageError

MAX_ARCHIVE_BYTES = 512 * 1024 * 1024  # [bytes] the blobs of the tree at a revision
MAX_ENTRIES = 200_000  # files in the tree at a revision
MAX_BLOB = MAX_MESH_BYTES  # [bytes] a larger file is left out of the tree (nothing reads it)
MAX_LISTING = 64 * 1024 * 1024  # [bytes] of ls-tree's output
GIT_TIMEOUT = 60  # [s]

# -c overrides: the command line outranks every configuration file, the repository's included
# (git-config(1), "CONFIGURATION FILE", scopes). Each names a program git may run by itself.
_OVERRIDES = (
    "safe.bareRepository=explicit",  # no repository found by discovery that is a bare one
    "core.fsmonitor=false", "core.hooksPath=/dev/null", "core.pager=cat",
    "core.editor=false", "sequence.editor=false", "core.askPass=", "credential.helper=",
    "core.sshCommand=false", "core.gitProxy=", "core.alternateRefsCommand=",
    "diff.external=", "gpg.program=false", "protocol.allow=never",
    "uploadpack.packObjectsHook=", "core.untrackedCache=false", "log.showSignature=false",
)
_BLOB_MODES = {"100644", "100755"}
_LINK_MODE = "120000"


def _environment(root: Path) -> dict[str, str]:
    """The caller's environment without any ``GIT_*`` variable (``GIT_DIR``,
    ``GIT_CONFIG_PARAMETERS``, ``GIT_EXEC_PATH``, ``GIT_SSH_COMMAND``, ...), with no system or
    global configuration, no discovery above the repository, no lazy fetch, no prompt and no
    pager."""
    environment = {name: value for name, value in os.environ.items()
                   if not name.startswith("GIT_") and name not in ("PAGER", "EDITOR", "VISUAL")}
    environment.update(
        GIT_CONFIG_NOSYSTEM="1", GIT_CONFIG_GLOBAL=os.devnull, GIT_CONFIG_SYSTEM=os.devnull,
        GIT_CEILING_DIRECTORIES=str(root.parent), GIT_NO_LAZY_FETCH="1",
        GIT_TERMINAL_PROMPT="0", GIT_PAGER="cat", PAGER="cat", GIT_OPTIONAL_LOCKS="0",
        GIT_ATTR_NOSYSTEM="1", GIT_NO_REPLACE_OBJECTS="1", GIT_PROTOCOL_FROM_USER="0")
    return environment


def _command(root: Path, args) -> list[str]:
    return ["git", "--no-pager", f"--git-dir={root / '.git'}", f"--work-tree={root}",
            *(word for pair in (*_OVERRIDES, *_trusted(root)) for word in ("-c", pair)), *args]


def _trusted(root: Path) -> tuple[str, ...]:
    """``safe.directory`` naming the one top level git is told to use, by its real path (the
    work tree as git compares it), so that a checkout owned by another user (a CI container's
    workspace) is read. git honours the key only from protected configuration (system, global,
    command line: the repository cannot set it), and its ownership check guards against a
    stranger's configuration running programs, which the overrides above already neutralise for
    every repository, whoever owns it. A path ending in ``*`` (git's wildcard) is not passed."""
    real = os.path.realpath(root)
    return () if real.endswith("*") else (f"safe.directory={real}",)


def _git(root: Path, *args: str) -> str:
    """Run ``git ARGS`` on the repository at ``root`` (see the module docstring); its output,
    stripped. UsageError when git fails, with the last line it wrote."""
    try:
        done = subprocess.run(_command(root, args), capture_output=True, text=True, cwd=root,
                              env=_environment(root), stdin=subprocess.DEVNULL,
                              timeout=GIT_TIMEOUT, check=False)
    except (OSError, subprocess.TimeoutExpired) as error:
        raise UsageError(f"git failed: {error}") from None
    if done.returncode:
        from urdftool.guardian import ended

        said = done.stderr.strip().splitlines()  # (killed: the signal, whatever it said)
        raise UsageError(f"git {args[0]}: " + (said[-1] if said and done.returncode > 0
                                                else ended(done.returncode)))
    return done.stdout.strip()


def _git_process(root: Path, *args: str, stdin: bool = False) -> subprocess.Popen:
    """``git ARGS`` started as :func:`_git` runs it, its output (and input) as pipes."""
    try:
        return subprocess.Popen(_command(root, args), cwd=root, env=_environment(root),
                                stdin=subprocess.PIPE if stdin else subprocess.DEVNULL,
                                stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
    except OSError as error:
        raise UsageError(f"git failed: {error}") from None


_INCLUDE = re.compile(rb"^[ \t]*\[[ \t]*include(if)?\b", re.I | re.M)  # line ends: git's (LF)
MAX_CONFIG = 1024 * 1024  # [bytes] of a repository's config read to look for includes


def _refuse_includes(root: Path) -> None:
    """UsageError when the repository's own configuration includes other files
    (``include.path``, ``includeIf``): git would read them, wherever they are, and no command
    line can turn that off. A clone's config is the user's; an unpacked archive's is the
    stranger's. Looked for in ``config`` and ``config.worktree`` of the git folder ``.git``
    names (a worktree's or submodule's ``.git`` file) and of its common folder."""
    git_dir = root / ".git"
    try:
        if git_dir.is_file():
            pointer = read_regular(git_dir, 4096).decode("utf-8", "replace").strip()
            if pointer.startswith("gitdir:"):
                git_dir = (root / pointer[len("gitdir:"):].strip()).resolve()
        folders = [git_dir]
        if (git_dir / "commondir").is_file():
            common = read_regular(git_dir / "commondir", 4096).decode("utf-8", "replace")
            folders.append((git_dir / common.strip()).resolve())
        for folder in folders:
            for name in ("config", "config.worktree"):
                if (folder / name).is_file() and \
                        _INCLUDE.search(read_regular(folder / name, MAX_CONFIG)):
                    raise UsageError(f"the git configuration of {root} includes other files "
                                     "(include.path, includeIf); diff --rev does not run git "
                                     "on it")
    except OSError as error:
        raise UsageError(f"cannot read the git configuration of {root}: "
                         f"{error.strerror}") from None


def repository_of(path) -> tuple[Path, str]:
    """(repository root, the path of ``path`` relative to it, with / separators); UsageError
    when ``path`` is not in a git repository (no folder above it holds ``.git``)."""
    folder = Path(os.path.abspath(path)).parent
    if not folder.is_dir():
        raise UsageError(f"'{path}': folder does not exist")
    root = repository_root(folder)
    if root is None:
        raise UsageError(f"'{path}' is not in a git repository (no folder above it holds .git)")
    try:
        relative = Path(os.path.realpath(folder)).relative_to(os.path.realpath(root))
    except ValueError:
        raise UsageError(f"'{path}' leads outside its repository ({root})") from None
    return root, (relative / Path(path).name).as_posix()


def _tree(root: Path, commit: str) -> list[tuple[str, str, int, str]]:
    """(mode, object, size, path) of every entry of the tree at ``commit``; UsageError when
    the listing is over MAX_LISTING bytes or MAX_ENTRIES entries."""
    process = _git_process(root, "ls-tree", "-r", "-l", "-z", "--full-tree", commit)
    listing = process.stdout.read(MAX_LISTING + 1)
    if len(listing) > MAX_LISTING:
        process.kill()
    process.stdout.close()
    if (code := process.wait(timeout=GIT_TIMEOUT)) and len(listing) <= MAX_LISTING:
        from urdftool.guardian import ended

        raise UsageError(f"git ls-tree {commit} failed: {ended(code)}")
    entries = []
    for record in listing.split(b"\0"):
        if not record:
            continue
        head, _, name = record.partition(b"\t")
        mode, _, rest = head.decode("ascii", "replace").partition(" ")
        _, _, rest = rest.partition(" ")
        objectname, _, size = rest.strip().partition(" ")
        entries.append((mode, objectname, int(size.strip()) if size.strip().isdigit() else 0,
                        name.decode("utf-8", "surrogateescape")))
        if len(entries) > MAX_ENTRIES:
            break
    if len(listing) > MAX_LISTING or len(entries) > MAX_ENTRIES:
        raise UsageError(f"the tree at {commit} has over {MAX_ENTRIES} files; not read")
    return entries


@contextmanager
def checkout(path, revision: str, max_bytes: int = MAX_ARCHIVE_BYTES):
    """Yield (the root of the repository at ``revision`` in a temporary folder, the path of
    ``path`` in it); the folder is removed afterwards. UsageError when the revision or the
    file at it does not exist, or its tree is over ``max_bytes``."""
    if revision.startswith("-"):
        raise UsageError(f"revision '{revision}' may not start with '-'")
    root, relative = repository_of(path)
    _refuse_includes(root)
    try:
        commit = _git(root, "rev-parse", "--verify", "--quiet", "--end-of-options",
                      f"{revision}^{{commit}}") if revision else ""
    except UsageError:
        commit = ""
    if not commit:
        raise UsageError(f"revision '{revision}' not found in {root}")
    entries = _tree(root, commit)
    blobs = [entry for entry in entries if entry[0] in _BLOB_MODES | {_LINK_MODE}]
    mode = next((mode for mode, _, _, name in blobs if name == relative), None)
    if mode is None:  # (a link is followed as in the work tree, when it stays in the tree)
        raise UsageError(f"'{relative}' does not exist at revision '{revision}'")
    if sum(size for _, _, size, _ in blobs) > max_bytes:
        raise UsageError(f"the repository at '{revision}' is over {max_bytes} bytes; not "
                         "unpacked")
    with temporary_folder("urdftool-rev-") as folder:
        tree = folder / "tree"
        _write_tree(root, tree, blobs, max_bytes)
        if not (tree / relative).is_file():
            raise UsageError(f"'{relative}' at revision '{revision}' is a symbolic link leading "
                             "out of the repository or to no file; not followed"
                             if mode == _LINK_MODE else
                             f"'{relative}' at revision '{revision}' is not in the repository's "
                             "object store (a partial clone?); urdftool fetches nothing")
        yield tree, tree / relative


def _write_tree(root: Path, tree: Path, blobs, max_bytes: int) -> None:
    """Read ``blobs`` raw with ``cat-file --batch`` and write them below ``tree``; names that
    are not plain are left out, and links that lead out of ``tree``."""
    write_new(tree, ".git/urdftool", b"the repository root of a git revision urdftool read\n")
    process = _git_process(root, "cat-file", "--batch", stdin=True)
    links, written = [], 0
    try:
        for mode, objectname, _, name in blobs:
            process.stdin.write(objectname.encode("ascii") + b"\n")
            process.stdin.flush()
            header = process.stdout.readline().split()
            if len(header) == 2 and header[1] == b"missing":
                continue  # not in a partial clone's object store: never fetched
            if len(header) != 3 or header[1] != b"blob" or not header[2].isdigit():
                raise UsageError(f"git cat-file could not read '{name}'")
            size = int(header[2])
            written += size
            if written > max_bytes:
                raise UsageError(f"the repository is over {max_bytes} bytes; not unpacked")
            if size > MAX_BLOB:  # no reader takes it (meshes stop at 128 MiB): not kept
                left = size + 1  # and the newline after it
                while left > 0 and (chunk := process.stdout.read(min(left, 1 << 20))):
                    left -= len(chunk)
                continue
            data = process.stdout.read(size)
            process.stdout.read(1)  # the newline after the content
            try:
                if mode == _LINK_MODE:
                    if link_new(tree, name, data.decode("utf-8", "surrogateescape")):
                        links.append(name)
                else:
                    write_new(tree, name, data)
            except (ValueError, OSError):
                continue  # a name that is not plain, or a file where a folder is: left out
    finally:
        process.kill()
        process.wait()
    remove_links_out(tree, links)
