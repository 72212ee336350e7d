"""Restore the real-repository sweep: each repository of tests/integration/real_sweep/MANIFEST.tsv
at its recorded commit, from the bare git snapshots under the mirror (``/work/.mirror``, or
``URDFTOOL_MIRROR``, or ``--mirror``) into ``<dest>/<owner+name>`` (``../sweep-repos`` beside the
project, or ``URDFTOOL_REAL_SWEEP``, or ``--dest``).

The snapshots are hostile data, and this script reads them as data only:
- the tree is listed with ``git ls-tree`` and every blob read with ``git cat-file --batch``: no
  checkout, no ``git archive``, so no filter, hook, ``.gitattributes`` or ``.gitmodules`` of the
  repository is ever consulted; git runs without system or user configuration and with
  replacement refs off, so a ``refs/replace`` planted in a snapshot cannot change what is read;
- a path with an empty, ``.`` or ``..`` part, or a ``.git`` part, is refused (not written);
- files are written without their executable bit;
- a symbolic link is made only when where it leads stays inside the repository's folder (checked
  again, fully resolved, once every link exists, so a chain of links cannot lead out); others are
  refused; submodules are skipped;
- each restored repository gets an empty ``.git`` folder (``git init`` without templates), as a
  clone has, because urdftool bounds a repository by it.

The snapshots lack files of 4 MiB and more (their blobs are absent) and Git LFS content (the
pointer file is written, as a clone without LFS has it): both are reported, and kept in
tests/integration/real_sweep/ABSENT.tsv (``--write-absent``), so that findings about them are
judged as snapshot artefacts.

One restore at a time writes into a destination: a second waits for the first (a lock file,
``.restore.lock``, in the destination). Two at once removed each other's files from a folder the
first then stamped as current.

Exit code 0 when every repository was restored; 1 when some are missing from the mirror (named).
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import os
import re
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath

ROOT = Path(__file__).resolve().parent.parent
SWEEP_DATA = ROOT / "tests" / "integration" / "real_sweep"
MANIFEST = SWEEP_DATA / "MANIFEST.tsv"
ABSENT = SWEEP_DATA / "ABSENT.tsv"
DEFAULT_MIRROR = Path(os.environ.get("URDFTOOL_MIRROR", "/work/.mirror"))
DEFAULT_DEST = Path(os.environ.get("URDFTOOL_REAL_SWEEP", ROOT.parent / "sweep-repos"))
STAMP = ".real-sweep-commit"
LFS_POINTER = b"version https://git-lfs.github.com/spec/v1"
# git as a reader of data: no configuration but ours, no replacement objects, no prompts.
GIT_ENV = {"PATH": os.environ.get("PATH", "/usr/bin:/bin"), "GIT_CONFIG_NOSYSTEM": "1",
           "GIT_CONFIG_GLOBAL": os.devnull, "GIT_NO_REPLACE_OBJECTS": "1",
           "GIT_TERMINAL_PROMPT": "0", "HOME": tempfile.gettempdir(), "LC_ALL": "C"}


def read_manifest(path: Path = MANIFEST) -> list[dict[str, str]]:
    """The manifest's rows (a dict per repository; ``#`` lines are comments)."""
    with path.open(newline="", encoding="utf-8") as handle:
        lines = [line for line in handle if line.strip() and not line.startswith("#")]
    return list(csv.DictReader(lines, delimiter="\t"))


def folder_name(repository: str) -> str:
    """``owner/name`` -> ``owner+name``, the mirror's and the destination's folder name."""
    owner, _, name = repository.partition("/")
    if not owner or not name or "/" in name or {owner, name} & {".", ".."}:
        raise ValueError(f"not an owner/name repository: {repository!r}")
    return f"{owner}+{name}"


def git_dir(mirror: Path, repository: str) -> Path | None:
    """The snapshot's git directory under the mirror (bare ``repo/``, or ``repo/.git``)."""
    base = mirror / folder_name(repository)
    for candidate in (base / "repo", base / "repo" / ".git", base / "repo.git", base):
        if (candidate / "objects").is_dir() and (candidate / "HEAD").is_file():
            return candidate
    return None


def _git(gitdir: Path, *args: str, data: bytes | None = None) -> bytes:
    return subprocess.run(["git", f"--git-dir={gitdir}", *args], input=data, env=GIT_ENV,
                          check=True, capture_output=True).stdout


@dataclass
class Entry:
    mode: str
    kind: str
    sha: str
    path: str


@dataclass
class Restored:
    repository: str
    files: int = 0
    absent: list[tuple[str, str]] = field(default_factory=list)   # (path, why)
    refused: list[tuple[str, str]] = field(default_factory=list)  # (path, why)


def list_tree(gitdir: Path, commit: str) -> list[Entry]:
    """Every entry of ``commit``'s tree, recursively (``ls-tree -r -z``, names as bytes)."""
    out = _git(gitdir, "ls-tree", "-r", "-z", "--full-tree", commit)
    entries = []
    for record in out.split(b"\0"):
        if not record:
            continue
        meta, _, path = record.partition(b"\t")
        mode, kind, sha = meta.decode("ascii").split()
        entries.append(Entry(mode, kind, sha, path.decode("utf-8", "surrogateescape")))
    return entries


def unsafe_path(path: str) -> str | None:
    """Why ``path`` (from a tree) must not be written, or None."""
    parts = PurePosixPath(path).parts
    if not path or path.startswith("/") or any(p in ("", ".", "..") for p in path.split("/")):
        return "a path with an empty, '.' or '..' part"
    if any(part.lower() == ".git" for part in parts):
        return "a path inside a '.git' folder"
    return None


class BlobReader:
    """``git cat-file --batch``: a blob's bytes by id, or None when the snapshot lacks it."""

    def __init__(self, gitdir: Path):
        self._process = subprocess.Popen(["git", f"--git-dir={gitdir}", "cat-file", "--batch"],
                                         stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                         env=GIT_ENV)

    def read(self, sha: str) -> bytes | None:
        assert self._process.stdin and self._process.stdout
        self._process.stdin.write(sha.encode("ascii") + b"\n")
        self._process.stdin.flush()
        header = self._process.stdout.readline().split()
        if len(header) != 3:  # "<sha> missing"
            return None
        size = int(header[2])
        data = self._process.stdout.read(size)
        self._process.stdout.read(1)  # the newline after the content
        return data if header[1] == b"blob" else None

    def close(self) -> None:
        assert self._process.stdin
        self._process.stdin.close()
        self._process.wait()


def _inside(path: Path, root: Path) -> bool:
    return path == root or root in path.parents


def restore(gitdir: Path, commit: str, dest: Path, repository: str) -> Restored:
    """Write ``commit``'s tree into ``dest`` (made anew) as data; see the module docstring."""
    done = Restored(repository)
    entries = list_tree(gitdir, commit)
    if dest.exists():
        shutil.rmtree(dest)
    dest.mkdir(parents=True)
    root = dest.resolve()
    links = []
    reader = BlobReader(gitdir)
    try:
        for entry in entries:
            why = unsafe_path(entry.path)
            if why:
                done.refused.append((entry.path, why))
            elif entry.kind == "commit":
                done.refused.append((entry.path, "a submodule (not in the snapshot)"))
            elif entry.mode == "120000":
                links.append(entry)
            else:
                data = reader.read(entry.sha)
                if data is None:
                    done.absent.append((entry.path, "blob absent from the snapshot (4 MiB or more)"))
                    continue
                if data.startswith(LFS_POINTER):
                    done.absent.append((entry.path, "Git LFS pointer (content not in the snapshot)"))
                target = root / entry.path
                if any(p.is_symlink() for p in [target, *target.parents] if _inside(p, root)):
                    done.refused.append((entry.path, "a path through a symbolic link"))
                    continue
                target.parent.mkdir(parents=True, exist_ok=True)
                flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0)
                with os.fdopen(os.open(target, flags, 0o644), "wb") as handle:
                    handle.write(data)
                done.files += 1
        made = []
        for entry in links:
            target_text = reader.read(entry.sha)
            link = root / entry.path
            where = (target_text or b"").decode("utf-8", "surrogateescape")
            lexical = Path(os.path.normpath(link.parent / where))
            if not where or where.startswith("/") or not _inside(lexical, root):
                done.refused.append((entry.path, f"a symbolic link leading out ({where})"))
                continue
            link.parent.mkdir(parents=True, exist_ok=True)
            if os.path.lexists(link) or any(p.is_symlink() for p in link.parents
                                            if _inside(p, root)):
                done.refused.append((entry.path, "a link over another entry"))
                continue
            os.symlink(where, link)
            made.append(entry.path)
    finally:
        reader.close()
    for path in made:  # fully resolved now that every link exists: chains cannot lead out
        if not _inside(Path(os.path.realpath(root / path)), root):
            os.unlink(root / path)
            done.refused.append((path, "a symbolic link leading out through other links"))
    subprocess.run(["git", "init", "--quiet", "--template=", str(dest)], env=GIT_ENV,
                   check=True, capture_output=True)
    (dest / ".git" / STAMP).write_text(commit + "\n")
    done.files += len(made)
    return done


ROBOT_SUFFIXES = (".urdf", ".xacro")
LAUNCH = re.compile(r"\.launch(\.py|\.xml|\.ya?ml)?$|(^|/)launch/[^/]*\.(py|xml|ya?ml)$")
CONTROLLERS = re.compile(r"controller_manager|type:\s*['\"]?\w+_controllers?/|/\w*_?controller\b")


def survey(folder: Path) -> dict[str, str]:
    """What a restored repository holds, as the manifest records it: ``ros`` (``1``, ``2``,
    ``1+2`` from its package.xml build tools, or ``-``), ``robots`` (how many .urdf/.xacro
    files) and ``has``: ``launch`` (launch files), ``controllers`` (controller YAML),
    ``ros2_control`` (a robot file with ``<ros2_control>``), ``moveit`` (an SRDF)."""
    ros, has, robots = set(), set(), 0
    for path in sorted(folder.rglob("*")):
        relative = path.relative_to(folder).as_posix()
        if relative.startswith(".git/") or path.is_symlink() or not path.is_file():
            continue
        text = path.read_text(errors="replace") if path.stat().st_size < 8 << 20 else ""
        if path.name == "package.xml":
            ros |= {"2"} if "ament_" in text else {"1"} if "catkin" in text else set()
        elif relative.lower().endswith(ROBOT_SUFFIXES):  # NAME.URDF, as SolidWorks writes it
            robots += 1
            has |= {"ros2_control"} if "<ros2_control" in text else set()
        if LAUNCH.search(relative):
            has.add("launch")
        if relative.endswith((".yaml", ".yml")) and CONTROLLERS.search(text):
            has.add("controllers")
        if relative.endswith((".srdf", ".srdf.xacro")):
            has.add("moveit")
    order = ("launch", "controllers", "ros2_control", "moveit")
    return {"ros": "+".join(sorted(ros)) or "-", "robots": str(robots),
            "has": ",".join(h for h in order if h in has) or "-"}


def is_current(dest: Path, commit: str) -> bool:
    stamp = dest / ".git" / STAMP
    return stamp.is_file() and stamp.read_text().strip() == commit


def write_absent(rows: list[tuple[str, str, str]], path: Path = ABSENT) -> None:
    with path.open("w", newline="", encoding="utf-8") as handle:
        handle.write("# Files the snapshots lack (written by scripts/restore_real_sweep.py "
                     "--write-absent): findings about them are snapshot artefacts.\n")
        writer = csv.writer(handle, delimiter="\t", lineterminator="\n")
        writer.writerow(["repository", "path", "why"])
        writer.writerows(sorted(rows))


@contextlib.contextmanager
def one_restore_at_a_time(dest: Path):
    """Hold ``dest``'s lock for the block, waiting (and saying so) while another restore holds it."""
    try:
        import fcntl
    except ImportError:  # not POSIX: no lock
        yield
        return
    with open(dest / ".restore.lock", "ab") as lock:
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            print(f"another restore is writing into {dest}: waiting for it", file=sys.stderr)
            fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--mirror", type=Path, default=DEFAULT_MIRROR)
    parser.add_argument("--dest", type=Path, default=DEFAULT_DEST)
    parser.add_argument("--manifest", type=Path, default=MANIFEST)
    parser.add_argument("--force", action="store_true", help="restore even the current ones")
    parser.add_argument("--write-absent", action="store_true",
                        help=f"rewrite {ABSENT.relative_to(ROOT)} (every repository restored)")
    parser.add_argument("only", nargs="*", help="owner/name of the repositories to restore")
    args = parser.parse_args(argv)
    rows = [row for row in read_manifest(args.manifest)
            if not args.only or row["repository"] in args.only]
    args.dest.mkdir(parents=True, exist_ok=True)
    with one_restore_at_a_time(args.dest):
        return _restore_rows(args, rows)


def _restore_rows(args: argparse.Namespace, rows: list[dict[str, str]]) -> int:
    missing, absent = [], []
    for row in rows:
        repository, commit = row["repository"], row["commit"]
        dest = args.dest / folder_name(repository)
        gitdir = git_dir(args.mirror, repository)
        if gitdir is None:
            missing.append(f"{repository} (no snapshot under {args.mirror})")
            continue
        try:
            _git(gitdir, "cat-file", "-e", f"{commit}^{{commit}}")
        except subprocess.CalledProcessError:
            missing.append(f"{repository} (commit {commit} not in the snapshot)")
            continue
        if is_current(dest, commit) and not args.force and not args.write_absent:
            continue
        done = restore(gitdir, commit, dest, repository)
        absent += [(repository, path, why) for path, why in done.absent]
        print(f"{repository}: {done.files} files, {len(done.absent)} absent, "
              f"{len(done.refused)} refused", file=sys.stderr)
        for path, why in done.refused:
            print(f"  refused {path}: {why}", file=sys.stderr)
    if args.write_absent and not missing:
        write_absent(absent)
    if missing:
        print(f"{len(missing)} of {len(rows)} repositories are missing from the mirror "
              "(fetch them, or set URDFTOOL_MIRROR):", file=sys.stderr)
        for line in missing:
            print(f"  {line}", file=sys.stderr)
        return 1
    print(f"{len(rows)} repositories in {args.dest}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
