"""The result cache, as ruff has one: a file's findings are kept and given again while nothing
they depend on has changed.

An entry is keyed by the file (its absolute path), the options it is checked with (settings,
selection, xacro arguments, packages, companions, limits), the working directory (findings name
files relative to it), the package search variables of the environment, and urdftool itself
(the modification of its source files, ``__version__`` among them, so that a development
checkout never reads results of other code). The entry lists what the result was built from,
each with a hash of its content, and is a hit only when every one is unchanged:

- every file read to build the robot: the file, its xacro includes and YAML;
- the companion files it could pick up: the ``*.yaml`` and ``*.srdf`` in its folder and its
  ``config/`` folder (which exist, and their content) and the companions named;
- every mesh it names: where the URI resolved, and the mesh's content. While that file is
  there unchanged, the URI is not resolved again: a package of the same name that appears
  earlier on the search path later is not noticed (the package variables are in the key);
- the environment, whole, when a source uses ``$(env`` or ``$(optenv``.

What the check never reads, the cache never reads either: a file or folder that is, or lies
in, a symbolic link leading outside its repository (the loader's rule) is kept as where it
leads, neither opened nor stamped. A companion named on the command line is the exception, as
it is for the check: it is read wherever it leads, so its content is compared.

Files are compared by their stamp (device, inode, size, modification and change times, as
git's index does) and, when it differs, by their content. A stamp taken less than 2 s after
the file changed is not trusted (file times tick coarsely: a file written again within the same
tick would keep them): the next run compares its content. Every file read while a run checks
is noted with a hash of the bytes read, and a result whose dependencies differ from what was
read of them when it is kept (an editor saved one while it was checked) is not kept.

A file that failed to load is not kept (it fails fast anyway), nor a result with a crash, a
budget stop or stdin.

A whole run is kept too, when each path named was checked as itself (the case of pre-commit
and of editors): keyed by the paths and the request, it lists the stamps of everything its
files' entries list, and of the settings files, package.xml and ``.git`` (present or not) in
every folder above each path. A re-run whose stamps are all the same is served from it without
looking for settings or classifying the paths; any difference and the run goes file by file.
The output of such a run (``urdftool check`` printing to a file or pipe) is kept beside it,
keyed by the command's words, the working directory, the whole environment and which standard
streams are terminals, and printed again for the same words while the run's stamps are the
same (``urdftool/__main__.py``, before the command line is even parsed).

The folder (``.urdftool_cache`` in the working directory, or ``--cache-dir``) comes with a
``CACHEDIR.TAG`` and a ``.gitignore`` of ``*``. Robot files and even the cache folder may come
from a stranger (a pull request can commit a ``.urdftool_cache`` with entries saying "no
findings"), so:

- each entry is signed (HMAC-SHA256) with a key kept outside the repository, in
  ``$XDG_CACHE_HOME/urdftool/key`` (``~/.cache``), made on first use in a folder only its
  owner may enter: an entry this machine did not write is a miss;
- a cache folder, entry or key that is a symbolic link, not a regular file, too large, not
  JSON of the expected shape or of another schema is a miss (and is overwritten, never
  followed);
- under CI (the ``CI`` variable set) the cache is off unless ``--cache-dir`` is given: a CI
  checkout is fresh and is the untrusted input itself. ``URDFTOOL_NO_CACHE`` turns the default
  off too.
"""

from __future__ import annotations

import dataclasses
import hashlib
import hmac
import json
import os
import stat
import sys
import time
from pathlib import Path

from urdftool.description.files import TooLarge, noted_reads, noting_reads, read_regular, \
    real_path, write_file
from urdftool.description.run_memo import one_run
from urdftool.diagnostics import Edit, Finding, Fix, Location, Severity
from urdftool.errors import UsageError

SCHEMA = 2  # 2: an entry is its signature, a line break and its body
FOLDER = ".urdftool_cache"
MAX_ENTRY_BYTES = 16 * 1024 * 1024
HASHED_BYTES = 512 * 1024 * 1024  # [bytes]: larger files are known by size and time
_ENVIRONMENT = ("ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH", "CMAKE_PREFIX_PATH", "COLCON_PREFIX_PATH")
_NOT_KEPT = ("U015", "U018", "U900")  # a budget stop or a crash: worth trying again
_TAG = ("Signature: 8a477f597d28d172789f06886806bc55\n"
        "# This file is a cache directory tag created by urdftool.\n"
        "# For information about cache directory tags see https://bford.info/cachedir/\n")


def default_folder(environ=os.environ) -> Path | None:
    """``.urdftool_cache`` in the working directory; None under CI (see the module docstring)
    or with ``URDFTOOL_NO_CACHE`` set (as the test suite does)."""
    return None if environ.get("CI") or environ.get("URDFTOOL_NO_CACHE") else Path(FOLDER)


class Cache:
    """Results of files checked, in ``folder``; every problem with the folder is a miss."""

    def __init__(self, folder: Path | str):
        self.folder = Path(os.path.abspath(folder))
        self._key = _secret()
        self._source = _source_stamp()
        self._resolvers: dict = {}
        self._verified: dict = {}  # (path, options) -> [kind, name, quick] of a hit or a put

    # -- the key ---------------------------------------------------------------------------

    def _entry_path(self, path: str, options) -> Path:
        return self._keyed(os.path.abspath(path), repr(options))

    def _run_path(self, paths: list[str], request) -> Path:
        """Where a whole run is kept: keyed by the paths as given (reports show them so), the
        request but its cache folder, and ``CI`` (which sets ``allow_env``'s default)."""
        return self._keyed("run", [os.path.abspath(path) for path in paths], list(paths),
                           repr(dataclasses.replace(request, cache_dir=None)),
                           os.environ.get("CI"), suffix="-run")

    def _keyed(self, *parts, suffix: str = "") -> Path:
        key = json.dumps([SCHEMA, self._source, os.getcwd(), *parts,
                          [os.environ.get(name) for name in _ENVIRONMENT]])
        return self.folder / f"v{SCHEMA}" / (hashlib.sha256(key.encode()).hexdigest() + suffix
                                             + ".json")

    # -- reading ---------------------------------------------------------------------------

    def get(self, path: str, options) -> list[Finding] | None:
        """The findings kept for ``path`` checked with ``options``, or None (a miss)."""
        if path == "-" or (content := self._content(self._entry_path(path, options))) is None:
            return None
        try:
            dependencies, current = self._dependencies(path, options), []
            for kind, name, quick, full in content["depends"]:
                now = _quick(kind, name)
                if not (now == quick and now is not None or dependencies.full(kind, name) == full):
                    return None
                current.append([kind, name, now])
            findings = [_finding(item) for item in content["findings"]]
        except (ValueError, KeyError, TypeError, IndexError, AttributeError, OSError):
            return None
        self._verified[path, repr(options)] = current
        return findings

    def get_run(self, paths: list[str], request) -> tuple[list, list[bool], list] | None:
        """The results (FileResult), their strictness and the stamps they depend on (for
        :meth:`put_output`) kept for checking ``paths`` with ``request``, or None. A run is
        kept only when each path was checked as itself (no folder, macro library or companion
        named), and is a hit only while every stamp it lists is the same: the quick state of
        what each file's result was built from, and the settings files, package manifests and
        repository markers above each path (present or not). Any difference is a miss, and the
        files are looked up one by one."""
        if "-" in paths or (content := self._content(self._run_path(paths, request))) is None:
            return None
        from urdftool.lint.options import FileResult

        try:
            if not _unchanged(content["depends"]):
                return None
            results = [FileResult(item["path"], [_finding(f) for f in item["findings"]],
                                  companions=[str(line) for line in item["companions"]])
                       for item in content["results"]]
            return results, [bool(strict) for strict in content["strict"]], content["depends"]
        except (ValueError, KeyError, TypeError, IndexError, AttributeError, OSError):
            return None

    def _content(self, entry_path: Path) -> dict | None:
        """The body of the entry at ``entry_path`` when this machine signed it for this schema;
        None when there is none, or it is a link, malformed or not signed here."""
        if self._key is None or not self._usable_folder():
            return None
        entry = _read_entry(entry_path)
        if entry is None:
            return None
        try:
            signature, _, body = entry.decode("utf-8").partition("\n")
            if not hmac.compare_digest(signature, self._sign(body)):
                return None
            content = json.loads(body)
            return content if content["schema"] == SCHEMA else None
        except (ValueError, KeyError, TypeError, IndexError, AttributeError):
            return None

    def put_run(self, paths: list[str], request, run, options_for) -> list | None:
        """Keep ``run`` for :meth:`get_run`, when every path was checked as itself and every
        result was kept (see :meth:`put`); ``options_for``: path -> its CheckOptions. Returns
        the stamps the run depends on (for :meth:`put_output`) when it was kept, else None."""
        if self._key is None or "-" in paths or run.skipped or run.notes or \
                [result.path for result in run.results] != list(paths):
            return None
        depends = []
        for path in paths:
            options = options_for(path)
            if (path, repr(options)) not in self._verified and self.get(path, options) is None:
                return None  # not kept: a crash, a budget stop, a file that did not load
            depends += self._verified[path, repr(options)]
        depends += [[kind, name, _quick(kind, name)]
                    for kind, name in _surroundings(paths, request)]
        unique = {(kind, name): quick for kind, name, quick in depends}  # robots share meshes
        depends = [[kind, name, quick] for (kind, name), quick in unique.items()]
        body = json.dumps({"schema": SCHEMA, "strict": run.strict, "depends": depends,
                           "results": [{"path": result.path, "companions": result.companions,
                                        "findings": [_record(f) for f in result.findings]}
                                       for result in run.results]})
        return depends if self._keep(self._run_path(paths, request), body) else None

    # -- a command's output ----------------------------------------------------------------

    def get_output(self, command_line: list[str], environment=os.environ
                   ) -> tuple[str, str, int] | None:
        """(standard output, standard error, exit code) of ``command_line`` started in
        ``environment``, as :meth:`put_output` kept them, while every stamp its run depended
        on is the same; else None."""
        content = self._content(self._output_path(command_line, environment))
        if content is None:
            return None
        try:
            stdout, stderr, code = content["stdout"], content["stderr"], content["code"]
            if type(stdout) is not str or type(stderr) is not str or type(code) is not int \
                    or not _unchanged(content["depends"]):
                return None
        except (ValueError, KeyError, TypeError, IndexError, AttributeError, OSError):
            return None
        return stdout, stderr, code

    def put_output(self, command_line: list[str], environment, depends: list, stdout: str,
                   stderr: str, code: int) -> None:
        """Keep what ``command_line`` started in ``environment`` printed and its exit code,
        for a run kept whole whose stamps are ``depends`` (from :meth:`get_run` or
        :meth:`put_run`)."""
        body = json.dumps({"schema": SCHEMA, "depends": depends, "stdout": stdout,
                           "stderr": stderr, "code": code})
        if len(body) < MAX_ENTRY_BYTES - 100:  # the signature and line break fit too
            self._keep(self._output_path(command_line, environment), body)

    def _output_path(self, command_line: list[str], environment) -> Path:
        """Where a command line's output is kept: keyed by its words as given, the whole
        environment (formats, colours, encodings and defaults follow variables) but ``_``
        (which the shell sets to the program it started: ``time urdftool`` is the same
        command), the Python and which standard streams are terminals."""
        environment = {name: value for name, value in environment.items() if name != "_"}
        return self._keyed("output", list(command_line), _environment(environment), sys.version,
                           [os.isatty(fd) for fd in (0, 1, 2)], suffix="-output")

    # -- writing ---------------------------------------------------------------------------

    def put(self, path: str, options, result) -> None:
        """Keep ``result`` (an engine FileResult with its robot) for ``path``, when it may be."""
        robot = result.robot
        if self._key is None or path == "-" or robot is None or \
                any(f.code in _NOT_KEPT for f in result.findings):
            return
        depends = self._dependencies(path, options).of(robot)
        if depends is None:
            return
        body = json.dumps({"schema": SCHEMA, "depends": depends,
                           "findings": [_record(f) for f in result.findings]})
        self._keep(self._entry_path(path, options), body)

    def _keep(self, entry_path: Path, body: str) -> bool:
        """Write ``body``, signed, at ``entry_path``; False when it could not be (an unusable
        folder)."""
        try:
            if self._usable_folder(create=True):
                _write(entry_path, f"{self._sign(body)}\n{body}")
                return True
        except OSError:
            pass
        return False

    def noting_reads(self):
        """A block in which every file read is noted with the digest of its bytes: a result
        kept (:meth:`put`) while a file it depends on differs from what was read of it (an
        editor saved it while it was checked) is not kept."""
        return noting_reads(_digest)

    def _dependencies(self, path: str, options) -> _Dependencies:
        return _Dependencies(path, options, self._resolvers)

    def _sign(self, body: str) -> str:
        return hmac.new(self._key, body.encode(), hashlib.sha256).hexdigest()

    def _usable_folder(self, create: bool = False) -> bool:
        """The folder (and its ``v<SCHEMA>``) exist as real folders, never links; made when
        asked."""
        for folder in (self.folder, self.folder / f"v{SCHEMA}"):
            try:
                mode = os.lstat(folder).st_mode
            except FileNotFoundError:
                if not create:
                    return False
                os.makedirs(folder, mode=0o700, exist_ok=True)
                mode = os.lstat(folder).st_mode
                if folder == self.folder:
                    _write(folder / "CACHEDIR.TAG", _TAG)
                    _write(folder / ".gitignore", "# created by urdftool\n*\n")
            except OSError:
                return False
            if not stat.S_ISDIR(mode):
                return False  # a link (to anywhere) or a file: not used
        return True


def _outside(path: str) -> str | None:
    """What is kept of ``path`` instead of its stamps or content when it is, or lies in a
    folder that is, a symbolic link leading outside its repository: where it leads. The loader
    never reads such a file (:func:`~urdftool.description.packages.link_out`), so no result
    depends on what is there, and the cache must not read it either: a link planted in a pull
    request (``config/limits.yaml -> /etc/passwd``) would have it opened, and its hash, size
    and times kept in the repository's cache. None for any other path.

    A path with no link on the way (its real path is itself: one ``lstat`` per new folder in a
    run) is inside whatever folder holds it; only the others are judged by the loader's rule."""
    absolute = os.path.abspath(path)
    if real_path(absolute) == absolute:
        return None
    from urdftool.description.packages import link_out

    out = link_out(absolute)
    return None if out is None else f"outside:{out[0]}"


def _hash_file(path: str) -> str | None:
    """blake2b of a regular file's content; None when there is none, its size and time when it
    is over :data:`HASHED_BYTES`."""
    try:
        return _digest(read_regular(path, HASHED_BYTES))
    except TooLarge:
        status = os.stat(path)
        return f"large:{status.st_size}:{status.st_mtime_ns}"
    except OSError as error:
        return None if isinstance(error, FileNotFoundError) else f"unreadable:{error.strerror}"


def _digest(data: bytes) -> str:
    return hashlib.blake2b(data, digest_size=20).hexdigest()


RACY_NS = 2_000_000_000  # [ns] a file changed this recently may change again unseen


def _stamp(path: str, named: bool = False) -> str | None:
    """A file's identity and change times, as git's index keeps them: while they are the same
    the content is taken to be (the change time cannot be set back by a user). "" for a file
    that is not there. None when it cannot be trusted: unreadable, or changed in the last
    :data:`RACY_NS` (file times tick coarsely, by milliseconds to seconds, so a file written
    again within the same tick keeps its times: git calls it racily clean); its content is
    compared instead. A link leading outside the repository is where it leads (:func:`_outside`),
    unless the file was ``named`` on the command line (a companion given with ``--controllers``,
    ``--srdf`` or ``--spec``: the user asked for it, and the check reads it wherever it is)."""
    if not named and (outside := _outside(path)) is not None:
        return outside
    try:
        status = os.stat(path)
    except (FileNotFoundError, NotADirectoryError):
        return ""
    except OSError:
        return None
    if time.time_ns() - max(status.st_mtime_ns, status.st_ctime_ns) < RACY_NS:
        return None
    return f"{status.st_dev}:{status.st_ino}:{status.st_size}:{status.st_mtime_ns}:" \
           f"{status.st_ctime_ns}"


def _companion_folders(path: str) -> list[str]:
    base = os.path.dirname(os.path.abspath(path))
    return [base, os.path.join(base, "config")]


def _listing(folder: str, measure) -> str | None:
    """The companion candidates in ``folder``: names, each with ``measure(path)``; None when
    a measure is None (see :func:`_stamp`). A folder leading outside the repository is not
    listed: it is where it leads (:func:`_outside`)."""
    if (outside := _outside(folder)) is not None:
        return outside
    try:
        names = sorted(n for n in os.listdir(folder) if n.endswith((".yaml", ".srdf")))
    except OSError:
        return "[]"
    measures = [measure(os.path.join(folder, name)) for name in names]
    if measure is _stamp and None in measures:
        return None
    return json.dumps([f"{name}:{value}" for name, value in zip(names, measures)])


_SETTINGS_AND_MANIFESTS = ("urdftool.toml", "pyproject.toml", "package.xml")


def _surroundings(paths: list[str], request) -> list[tuple[str, str]]:
    """What finding and reading a path's settings and packages looks at above it: in every
    folder up to ``/``, the settings files and package.xml (their stamps; "" while absent)
    and ``.git`` (whether present: it bounds the repository); and a ``--config`` file."""
    folders: dict[str, None] = {}
    for path in paths:
        folder = os.path.dirname(os.path.abspath(path))
        while folder not in folders:
            folders[folder] = None
            folder = os.path.dirname(folder)
    found = [("exists", os.path.join(folder, ".git")) for folder in folders]
    found += [("file", os.path.join(folder, name)) for folder in folders
              for name in _SETTINGS_AND_MANIFESTS]
    if request.settings_file is not None:
        found.append(("file", os.path.abspath(request.settings_file)))
    return found


def _unchanged(depends: list) -> bool:
    """Whether every [kind, name, quick] stamp in ``depends`` is still the same; a None stamp
    (racy, or a mesh that did not resolve) never is."""
    with one_run():  # outside a run (the replay before Typer): each folder looked up once
        return all(quick is not None and _quick(kind, name) == quick
                   for kind, name, quick in depends)


def _quick(kind: str, name: str) -> str | None:
    """The quick state of a dependency: stamps, compared before content (see
    :class:`_Dependencies`); needs neither the file depending on it nor its options."""
    if kind == "exists":  # a marker whose presence alone matters (.git)
        return "folder" if os.path.isdir(name) else "file" if os.path.lexists(name) else ""
    if kind in ("file", "named"):
        return _stamp(name, named=kind == "named")
    if kind == "folder":
        return _listing(name, _stamp)
    if kind == "mesh":  # the file it resolved to, unchanged (see the module docstring)
        resolved = name.split("\0")[-1]
        stamp = _stamp(resolved) if os.path.isabs(resolved) else None
        return None if stamp is None else f"{resolved}:{stamp}"
    if kind == "environment":
        return _environment()
    raise ValueError(kind)


def _environment(environment=os.environ) -> str:
    return hashlib.sha256(json.dumps(sorted(environment.items())).encode()).hexdigest()


class _Dependencies:
    """What a result depends on, each as (quick, full): the quick state (stamps) is compared
    first, and the full state (content hashes) only when the quick one differs."""

    def __init__(self, path: str, options, resolvers: dict):
        """resolvers: package resolvers by (folder, packages), shared by every file of a run"""
        self.path, self.options = path, options
        self._resolvers = resolvers
        self.changed = False  # a file hashed differs from what the run read of it

    def _hash(self, path: str, named: bool = False) -> str | None:
        if not named and (outside := _outside(path)) is not None:
            return outside  # never read (nor did the run read it)
        read = noted_reads().get(os.path.abspath(path))  # before reading it again notes it anew
        now = _hash_file(path)
        if read is not None and read != now:
            self.changed = True
        return now

    def _resolved(self, uri: str) -> tuple[str | None, str]:
        from urdftool.description.packages import PackageResolver
        from urdftool.errors import UrdftoolError

        folder = Path(os.path.dirname(os.path.abspath(self.path)))
        key = (folder, tuple(sorted((k, str(v)) for k, v in self.options.packages.items())))
        if key not in self._resolvers:
            self._resolvers[key] = PackageResolver(self.options.packages, start=folder)
        try:
            resolved = self._resolvers[key].resolve_uri(uri, folder)
        except (UrdftoolError, OSError, ValueError) as error:
            return None, f"unresolved:{type(error).__name__}:{error}"
        return os.path.abspath(resolved), ""

    def full(self, kind: str, name: str) -> str | None:
        if kind in ("file", "named"):
            return self._hash(name, named=kind == "named")
        if kind == "folder":
            return _listing(name, self._hash)
        if kind == "mesh":
            resolved, problem = self._resolved(name.split("\0")[0])
            return f"{resolved}:{self._hash(resolved)}" if resolved else problem
        if kind == "environment":
            return _environment()
        raise ValueError(kind)

    def of(self, robot) -> list[list] | None:
        """[kind, name, quick, full] of everything ``robot``'s result was built from; None
        when a file read during the run has changed since (see :meth:`Cache.noting_reads`):
        the stamps and content now would describe a file the findings did not come from."""
        entries = []
        files = [os.path.abspath(self.path),
                 *(os.path.abspath(f) for f in robot.files if f != "-")]
        entries += [("file", file) for file in dict.fromkeys(files)]
        # companions named on the command line are read wherever they lead
        entries += [("named", named) for named in dict.fromkeys(
            os.path.abspath(p) for p in self.options.companions.named()) if named not in files]
        entries += [("folder", folder) for folder in _companion_folders(self.path)]
        uris = {element.get("filename") for element in robot.root.iter("mesh")} - {None}
        # a mesh is named by its URI and where it resolved: "uri\0path"
        entries += [("mesh", f"{uri}\0{self._resolved(uri)[0] or ''}") for uri in sorted(uris)]
        if any(b"$(env" in data or b"$(optenv" in data for data in robot.sources.values()):
            entries.append(("environment", ""))
        self.changed = False
        depends = [[kind, name, _quick(kind, name), self.full(kind, name)]
                   for kind, name in entries]
        return None if self.changed else depends


def _record(finding: Finding) -> dict:
    """A finding as kept: everything a report or ``--fix`` uses of it (its fix too)."""
    record = {"code": finding.code, "name": finding.name, "severity": finding.severity.value,
              "message": finding.message, "location": _location_record(finding.location)}
    if finding.fix is not None:
        record["fix"] = {"description": finding.fix.description, "safe": finding.fix.safe,
                         "edits": [dataclasses.astuple(edit) for edit in finding.fix.edits]}
    if finding.target is not None:
        record["target"] = finding.target
    return record


def _location_record(location: Location) -> list:
    return [location.file, location.line, [_location_record(v) for v in location.via],
            location.column]


def _location(record) -> Location:
    file, line, via, column = record
    if type(file) is not str or line is not None and type(line) is not int or \
            column is not None and type(column) is not int:
        raise TypeError("malformed location")
    return Location(file, line, tuple(map(_location, via)) if via else (), column)


def _fix(record) -> Fix | None:
    if record is None:
        return None
    edits = tuple(Edit(*fields) for fields in record["edits"])
    if not isinstance(record["description"], str) or not isinstance(record["safe"], bool) or \
            not all(isinstance(e.file, str) and isinstance(e.text, str) and isinstance(e.old, str)
                    and all(isinstance(v, int) for v in (e.start, e.end, e.line, e.column,
                                                           e.end_line, e.end_column))
                    for e in edits):
        raise TypeError("malformed fix")
    return Fix(record["description"], edits, record["safe"])


_SEVERITIES = {severity.value: severity for severity in Severity}


def _finding(record: dict) -> Finding:
    code, name, message = record["code"], record["name"], record["message"]
    if type(code) is not str or type(name) is not str or type(message) is not str:
        raise TypeError("malformed finding")
    fix, target = record.get("fix"), record.get("target")
    if target is not None and type(target) is not str:
        raise TypeError("malformed finding")
    return Finding(code, name, _SEVERITIES[record["severity"]], message,
                   _location(record["location"]), None if fix is None else _fix(fix), target)


def _read_entry(path: Path, limit: int = MAX_ENTRY_BYTES) -> bytes | None:
    """A regular file's bytes, not through a link, under ``limit``; else None."""
    try:
        if stat.S_ISLNK(os.lstat(path).st_mode):
            return None
        return read_regular(path, limit)
    except OSError:
        return None


def _write(path: Path, text: str) -> None:
    """:func:`~urdftool.description.files.write_file` (a link at ``path`` is replaced, not
    followed); OSError when it cannot."""
    try:
        write_file(path, text)
    except UsageError as error:
        raise OSError(str(error)) from None


def _secret() -> bytes | None:
    """This user's signing key, made on first use; None (no cache) when it cannot be had."""
    home = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    folder = Path(home) / "urdftool"
    path = folder / "key"
    key = _read_entry(path, 1024)
    if key is not None and len(key) >= 32:
        return key
    try:
        os.makedirs(folder, mode=0o700, exist_ok=True)
        _write(path, os.urandom(32).hex())
    except OSError:
        return None
    key = _read_entry(path, 1024)
    return key if key is not None and len(key) >= 32 else None


def _source_stamp() -> str:
    """The count and newest modification of urdftool's source files (``__version__`` among
    them): a result is never read by other code than wrote it."""
    root = Path(__file__).resolve().parent.parent
    newest, count = 0, 0
    for folder, _, names in os.walk(root):
        for name in names:
            if name.endswith(".py"):
                count += 1
                newest = max(newest, os.stat(os.path.join(folder, name)).st_mtime_ns)
    return f"{root}:{count}:{newest}"
