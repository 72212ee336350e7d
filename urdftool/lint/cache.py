"""The result cache, as ruff has one: a file's findings are kept and given again while nothing
they depend on has changed.

An entry is keyed by the file (its absolute path), the options it is checked with (settings,
selection, xacro arguments, packages, companions, limits), the working directory (findings name
files relative to it) and urdftool itself (the modification of its source files,
``__version__`` among them, and of its data files, so that a development checkout never reads
results of other code).
What the result depends on is the record of its check (:mod:`urdftool.description.record`),
made by the loader, discovery and the rules as they read: every file read (with a stamp and a
digest of the bytes read), every folder searched for companions or packages (found empty too:
a file appearing there later, or the folder itself, is a change), every path probed and every
link followed, every environment variable read. The cache keeps that record, and nothing else:
it has no list of folders or package resolvers of its own, and it reads no file of a robot's
but to compare an entry of the record with the disk (:func:`urdftool.description.files.holds`).
An entry is a hit only when every entry of its record still holds, so a kept result is stale
exactly when something its check read, searched or followed has changed.

What the check never reads, the cache never reads either: a mesh the loader refused (outside
the repository, through ``file://`` or ``../..``) is not in the record; a file that now leads
elsewhere through a symbolic link is a change, and where it leads is not read. A companion
named on the command line is read wherever it leads, by the check and so by the comparison.

Files are compared by their stamp (device, inode, size, modification and change times, as
git's index does) and, when it differs, by their content. A stamp taken less than 2 s after
the file changed is not trusted (file times tick coarsely: a file written again within the same
tick would keep them): the next run compares its content. A result whose record no longer
holds when it is to be kept (an editor saved a file while it was checked) is not kept.

A file that failed to load is not kept (it fails fast anyway), nor a result with a crash, a
budget stop or stdin.

A whole run is kept too, when each path named was checked as itself (the case of pre-commit
and of editors): keyed by the paths and the request, it lists the records of its files and the
record of finding their targets and settings (settings files, ``.git`` and package.xml probed
in the folders above each path). A re-run whose entries all hold by their stamps alone is
served from it without looking for settings or classifying the paths; any difference and the
run goes file by file.

The folder (``.urdftool_cache`` in the working directory, or ``--cache-dir``) comes with a
``CACHEDIR.TAG`` and a ``.gitignore`` of ``*``, written into it before any entry whoever made
it; a folder holding other files of those names is not written into. Robot files and even the
cache folder may come from a stranger (a pull request can commit a ``.urdftool_cache`` with
entries saying "no findings"), so:

- each entry is signed (HMAC-SHA256) with a key kept outside the repository, in
  ``$XDG_CACHE_HOME/urdftool/key`` (``~/.cache``), made on first use in a folder only its
  owner may enter: an entry this machine did not write is a miss; the signature covers the
  entry's name (its key) with its body, so that an entry this machine wrote, copied over
  another's name (a good robot's result over a bad one's), is a miss too;
- a cache folder, entry or key that is a symbolic link, not a regular file, too large, not
  JSON of the expected shape or of another schema is a miss (and is overwritten, never
  followed);
- under CI (the ``CI`` variable set) the cache is off unless ``--cache-dir`` is given: a CI
  checkout is fresh and is the untrusted input itself. ``URDFTOOL_NO_CACHE`` turns the default
  off too.
"""

from __future__ import annotations

import hashlib
import hmac
import json
import os
from pathlib import Path

from urdftool import records
from urdftool.description.files import kind_of, make_folders, own_folder, read_own, \
    remove_file, tree_stamp, unchanged, write_file
from urdftool.description.record import entry_key
from urdftool.diagnostics import Edit, Finding, Fix, Location, Severity, display_path
from urdftool.errors import UsageError

SCHEMA = 8  # 3: an entry's dependencies are its check's record; 4: findings' repeated parts;
# 5: the names a message lists as available among those parts (urdftool.errors.available);
# 6: an available list's detail says how many ("31 links"); 7: whether urdfdom takes a finding;
# 8: the xacro arguments given that the robot's files name (FileResult.arguments)
FOLDER = ".urdftool_cache"
MAX_ENTRY_BYTES = 16 * 1024 * 1024
_NO_KEY = ("no signing key: $XDG_CACHE_HOME/urdftool/key (or ~/.cache/urdftool/key) could not "
           "be read or made")
_NOT_KEPT = ("U015", "U018", "U900")  # a budget stop or a crash: worth trying again
_TAG = ("Signature: 8a477f597d28d172789f06886806bc55\n"
        "# This file is a cache directory tag created by urdftool.\n"
        "# For information about cache directory tags see https://bford.info/cachedir/\n")
_MARKS = (("CACHEDIR.TAG", _TAG), (".gitignore", "# created by urdftool\n*\n"))


def default_folder(environ=os.environ) -> Path | None:
    """``.urdftool_cache`` in the working directory; None under CI (see the module docstring)
    or with ``URDFTOOL_NO_CACHE`` set (as the test suite does)."""
    from urdftool.description.files import under_ci

    return None if under_ci(environ) or environ.get("URDFTOOL_NO_CACHE") else Path(FOLDER)


class Cache:
    """Results of files checked, in ``folder``; every problem with the folder is a miss."""

    def __init__(self, folder: Path | str):
        self.folder = Path(os.path.abspath(folder))
        self._key = _secret()
        self._source = _source_stamp()
        self._verified: dict = {}  # (path, options) -> the record entries of a hit or a put
        self._arguments: dict = {}  # (path, options) -> its FileResult.arguments, as kept
        self.failure: str | None = None  # why results could not be kept, the first time
        self._marks: bool | None = None  # whether the folder carries urdftool's marks

    def unkept(self) -> str | None:
        """What a run says, once, when results could not be kept (a full or read-only file
        system, a folder it may not write, a link or a file where the folder should be, no
        signing key): the check goes on, and the next run checks every file again."""
        if self.failure is None:
            return None
        return (f"results are not kept in the cache folder {display_path(str(self.folder))}: "
                f"{self.failure}; every file is checked again next time")

    def failed(self, why: str) -> None:
        """Remember why results were not kept, the first reason given (:meth:`unkept`)."""
        self.failure = self.failure or why

    # -- the key ---------------------------------------------------------------------------

    def _entry_path(self, path: str, options) -> Path:
        return self._keyed(os.path.abspath(path), repr(options))

    def _run_path(self, paths: list[str], request) -> Path:
        """Where a whole run is kept: keyed by the paths as given (reports show them so), the
        request but its cache folder, and ``CI`` (which sets ``allow_env``'s default)."""
        return self._keyed("run", [os.path.abspath(path) for path in paths], list(paths),
                           repr(records.replace(request, cache_dir=None)),
                           os.environ.get("CI"), suffix="-run")

    def _keyed(self, *parts, suffix: str = "") -> Path:
        key = json.dumps([SCHEMA, self._source, os.getcwd(), *parts])
        return self.folder / f"v{SCHEMA}" / (hashlib.sha256(key.encode()).hexdigest() + suffix
                                             + ".json")

    # -- reading ---------------------------------------------------------------------------

    def get(self, path: str, options) -> list[Finding] | None:
        """The findings kept for ``path`` checked with ``options``, or None (a miss)."""
        if path == "-" or (content := self._content(self._entry_path(path, options))) is None:
            return None
        try:
            depends = content["depends"]
            if not isinstance(depends, list) or not unchanged(depends):
                return None
            findings = [_finding(item) for item in content["findings"]]
            arguments = _arguments(content.get("arguments"))
        except (ValueError, KeyError, TypeError, IndexError, AttributeError, OSError):
            return None
        self._verified[path, repr(options)] = depends
        self._arguments[path, repr(options)] = arguments
        return findings

    def arguments(self, path: str, options) -> list | None:
        """The :attr:`~urdftool.lint.options.FileResult.arguments` kept with the result of
        ``path`` checked with ``options`` (after a hit or a put; None otherwise)."""
        return self._arguments.get((path, repr(options)))

    def reads(self, path: str, options) -> tuple[str, ...]:
        """The real paths of the files the check of ``path`` with ``options`` read, as kept
        with its result (after a hit or a put; empty otherwise): what a worker returns for a
        file it checks (:class:`~urdftool.lint.options.FileResult`'s ``read``)."""
        from urdftool.description.record import READ

        return tuple(entry[2] for entry in self._verified.get((path, repr(options)), ())
                     if entry[0] == READ and entry[4] is not None)

    def get_run(self, paths: list[str], request) -> tuple[list, list[bool], list] | None:
        """The results (FileResult), their strictness and the record entries they depend on
        kept for checking ``paths`` with ``request``, or None. A run
        is kept only when each path was checked as itself (no folder, macro library or
        companion named), and is a hit only while every entry it lists holds by its stamps
        alone: the records of its files, and of finding their settings and targets. Any
        difference is a miss, and the files are looked up one by one."""
        if "-" in paths or (content := self._content(self._run_path(paths, request))) is None:
            return None
        from urdftool.lint.options import FileResult

        try:
            if not isinstance(content["depends"], list) or \
                    not unchanged(content["depends"], quick=True):
                return None
            results = [FileResult(item["path"], [_finding(f) for f in item["findings"]],
                                  companions=[str(line) for line in item["companions"]],
                                  arguments=_arguments(item.get("arguments")))
                       for item in content["results"]]
            return results, [bool(strict) for strict in content["strict"]], content["depends"]
        except (ValueError, KeyError, TypeError, IndexError, AttributeError, OSError):
            return None

    def _content(self, entry_path: Path) -> dict | None:
        """The body of the entry at ``entry_path`` when this machine signed it for this schema;
        None when there is none, or it is a link, malformed or not signed here."""
        if self._key is None or not self._usable_folder():
            return None
        entry = read_own(entry_path, MAX_ENTRY_BYTES)
        if entry is None:
            return None
        try:
            signature, _, body = entry.decode("utf-8").partition("\n")
            if not hmac.compare_digest(signature, self._sign(entry_path, body)):
                return None
            content = json.loads(body)
            return content if content["schema"] == SCHEMA else None
        except (ValueError, KeyError, TypeError, IndexError, AttributeError):
            return None

    def put_run(self, paths: list[str], request, run, options_for, surroundings=None
                ) -> list | None:
        """Keep ``run`` for :meth:`get_run`, when every path was checked as itself and every
        result was kept (see :meth:`put`); ``options_for``: path -> its CheckOptions;
        ``surroundings``: the record of finding the paths' targets and settings. Returns the
        record entries the run depends on when it was kept, else None."""
        if self._key is None:
            self.failed(_NO_KEY)
            return None
        if "-" in paths or run.skipped or run.notes or \
                [result.path for result in run.results] != list(paths):
            return None
        depends = []
        for path in paths:
            options = options_for(path)
            if (path, repr(options)) not in self._verified and self.get(path, options) is None:
                return None  # not kept: a crash, a budget stop, a file that did not load
            depends += self._verified[path, repr(options)]
        around = surroundings.dump() if surroundings is not None else []
        if not unchanged(around):
            return None
        unique = {entry_key(entry): entry for entry in [*around, *depends]}  # shared meshes
        depends = list(unique.values())
        body = json.dumps({"schema": SCHEMA, "strict": run.strict, "depends": depends,
                           "results": [{"path": result.path, "companions": result.companions,
                                        "findings": [_record(f) for f in result.findings],
                                        "arguments": result.arguments}
                                       for result in run.results]})
        return depends if self._keep(self._run_path(paths, request), body) else None

    # -- writing ---------------------------------------------------------------------------

    def put(self, path: str, options, result) -> None:
        """Keep ``result`` (an engine FileResult with its robot and record) for ``path``, when
        it may be: not when a file its check read has changed since (its record no longer
        holds: the findings would describe a file that is not there)."""
        if self._key is None:
            self.failed(_NO_KEY)
            return
        if path == "-" or result.robot is None or result.record is None \
                or any(f.code in _NOT_KEPT for f in result.findings):
            return
        depends = result.record.dump()
        if not unchanged(depends):
            return
        body = json.dumps({"schema": SCHEMA, "depends": depends,
                           "findings": [_record(f) for f in result.findings],
                           "arguments": result.arguments})
        if self._keep(self._entry_path(path, options), body):
            self._verified[path, repr(options)] = depends
            self._arguments[path, repr(options)] = result.arguments

    def _keep(self, entry_path: Path, body: str) -> bool:
        """Write ``body``, signed, at ``entry_path``; False when it could not be (an unusable
        folder, a write the system refused: :attr:`failure` says why)."""
        try:
            if self._usable_folder(create=True):
                _write(entry_path, f"{self._sign(entry_path, body)}\n{body}")
                return True
            self.failed(self._unusable())
        except OSError as error:
            self.failed(error.strerror or str(error))
        return False

    def _unusable(self) -> str:
        """Why :meth:`_usable_folder` refused the folder (or its ``v<SCHEMA>``)."""
        for folder, it in ((self.folder, "it"), (self.folder / f"v{SCHEMA}", f"its v{SCHEMA}")):
            kind = kind_of(folder, follow=False)
            if not kind:
                try:
                    make_folders(folder, 0o700)
                except (OSError, UsageError) as error:
                    return f"{it} could not be made ({getattr(error, 'strerror', None) or error})"
                continue
            if kind == "link":
                return f"{it} is a symbolic link, which is never followed"
            if kind != "folder":
                return f"{it} is not a folder"
        if self._marks is False:
            return ("it holds a CACHEDIR.TAG or .gitignore urdftool did not write (the entries "
                    "kept there could be committed)")
        return "it could not be used"

    def _sign(self, entry_path: Path, body: str) -> str:
        """The signature of ``body`` kept at ``entry_path``: the entry's name (its key) is
        signed with it, so that a signed entry copied over another key's is a miss, not the
        other file's result."""
        message = f"{entry_path.name}\n{body}"
        return hmac.new(self._key, message.encode(), hashlib.sha256).hexdigest()

    def _usable_folder(self, create: bool = False) -> bool:
        """The folder (and its ``v<SCHEMA>``) exist as real folders, never links; made when
        asked; to be written into (``create``), it carries urdftool's marks
        (:meth:`_marked`)."""
        for folder in (self.folder, self.folder / f"v{SCHEMA}"):
            if not own_folder(folder, create):
                return False  # missing, a link (to anywhere) or a file: not used
            if create and folder == self.folder and not self._marked():
                return False
        return True

    def _marked(self) -> bool:
        """The folder holds urdftool's ``CACHEDIR.TAG`` and ``.gitignore`` of ``*``, each
        written where there is none, whoever made the folder: one committed in the repository
        (git keeps a folder that holds a file) or planted got none, and the entries kept there
        (the absolute paths of every file a check read) were untracked files for ``git add -A``
        to commit. A folder holding anything else of either name (a ``.gitignore`` of ``!*``, a
        link, a folder) is not urdftool's: nothing is kept there, and nothing of it rewritten
        (it may be a file of the repository's). Once a run (a cache is one run's)."""
        if self._marks is None:
            for name, text in _MARKS:
                path = self.folder / name
                if not kind_of(path, follow=False):
                    _write(path, text)  # (OSError: the entry is not kept, and asks again)
                elif read_own(path, len(text) + 1) != text.encode():
                    self._marks = False
                    return False
            self._marks = True
        return self._marks


def _record(finding: Finding) -> dict:
    """A finding as kept: everything a report or ``--fix`` uses of it (its fix too)."""
    record = {"code": finding.code, "name": finding.name, "severity": finding.severity.value,
              "message": finding.message, "location": _location_record(finding.location)}
    if finding.fix is not None:
        record["fix"] = {"description": finding.fix.description, "safe": finding.fix.safe,
                         "edits": [records.astuple(edit) for edit in finding.fix.edits]}
    if finding.target is not None:
        record["target"] = finding.target
    if finding.repeated:
        record["repeated"] = [list(part) for part in finding.repeated]
    if finding.urdfdom_takes:
        record["urdfdom_takes"] = True
    if finding.urdfdom_refuses:
        record["urdfdom_refuses"] = True
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
    repeated = tuple(tuple(part) for part in record.get("repeated", ()))
    if not all(len(part) == 3 and all(type(item) is str for item in part) for part in repeated):
        raise TypeError("malformed finding")
    takes, refuses = record.get("urdfdom_takes", False), record.get("urdfdom_refuses", False)
    if type(takes) is not bool or type(refuses) is not bool:
        raise TypeError("malformed finding")
    return Finding(code, name, _SEVERITIES[record["severity"]], message,
                   _location(record["location"]), None if fix is None else _fix(fix), target,
                   repeated=repeated, urdfdom_takes=takes, urdfdom_refuses=refuses)


def _write(path: Path, text: str, private: bool = False) -> None:
    """:func:`~urdftool.description.files.write_file` (a link at ``path`` is replaced, not
    followed); OSError when it cannot. A named pipe or a device where a file of the cache goes
    is replaced too: ``write_file`` writes into one (a report's ``-o``), and a pipe planted as
    an entry held every run 10 s (waiting for a reader) and was never replaced."""
    try:
        if kind_of(path, follow=False) == "other":
            remove_file(path)
        write_file(path, text, rewrites=True, private=private)
    except UsageError as error:
        raise OSError(str(error)) from None


def _secret() -> bytes | None:
    """This user's signing key, made on first use; None (no cache) when it cannot be had. A
    relative ``XDG_CACHE_HOME`` is ignored, as the XDG specification says, and a relative
    ``HOME`` gives no key: either put the key in the working folder, the repository being
    checked, where a stranger can commit one and sign entries with it."""
    home = os.environ.get("XDG_CACHE_HOME", "")
    if not os.path.isabs(home):
        home = os.path.join(os.path.expanduser("~"), ".cache")
    if not os.path.isabs(home):
        return None
    folder = Path(home) / "urdftool"
    path = folder / "key"
    key = read_own(path, 1024)
    if key is not None and len(key) >= 32:
        return key
    try:
        make_folders(folder, 0o700)
        _write(path, os.urandom(32).hex(), private=True)  # (a secret: its folder's mode is
        # 0700 only when made here: one made by another, or a link, may be anyone's to read)
    except (OSError, UsageError):
        return None
    key = read_own(path, 1024)
    return key if key is not None and len(key) >= 32 else None


def _source_stamp() -> str:
    """The count and newest modification of urdftool's source and data files
    (``__version__`` among them): a result is never read by other code than wrote it."""
    return tree_stamp(os.path.dirname(os.path.dirname(__file__)))


def _arguments(kept) -> list | None:
    """A kept ``FileResult.arguments``: ``[named, declared]``, two lists of names, or None;
    ValueError for anything else (a malformed entry is a miss)."""
    if kept is None:
        return None
    named, declared = kept
    if not all(isinstance(name, str) for name in [*named, *declared]):
        raise ValueError("arguments")
    return [list(named), list(declared)]
