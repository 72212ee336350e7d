"""``urdftool`` and ``python -m urdftool``: the command line, and the one door for the tricks
that make it start fast. Each stays while ``make bench`` shows it saves 50 ms or more on what
users run (benchmarks/bench_startup.py times each with and without it).

``urdftool --help``, ``-h``, ``-V``, ``--version``, no words, and ``urdftool COMMAND --help``
print the texts Typer prints (kept in ``urdftool/data/help.txt``, made from the Typer app by
:mod:`urdftool.help_text`) without importing Typer: 0.1 s of imports saved on a run that
costs less than that otherwise. On a terminal narrower than Typer's 80 columns (where Typer wraps
its text to the width), or when the kept texts were made from other command modules, Typer
answers.

``urdftool check`` with plain words (paths, and options written in full: :func:`plain_words`)
runs without Typer (:func:`_check`): the words are read with the parameters of the Typer
command kept in the same file as the help texts, and the command's work
(:func:`urdftool.checking.run`) prints through a :class:`urdftool.terminal.Terminal` that writes
as click does, on streams click would write to as they are. Any other words, or streams, and
Typer answers.

Every command but those answered above starts with the compiled forms of the class methods
:mod:`dataclasses` writes and of the regular expressions a check compiles, kept beside the
bytecode by :mod:`urdftool.kept_code` (``make`` writes them): Python compiled the source of
the methods of each dataclass (urdftool's records on a check's path are plain classes,
:mod:`urdftool.records`) and parsed a hundred patterns again on every run. A form is used only
for the very text or pattern it was made from, and only by the Python that made it
(:func:`kept_code`).

``check`` imports the rules and its own work with the cyclic garbage collector off (from its
first step, the kept code, on: the collections it made of them found nothing to free, 5 M
instructions of r2d2's check) and freezes them, then runs the collector less often around each
robot (:func:`_collect_less`, installed into the engine): it saves a fifth of the check of a
10,000-link robot, and the collector's passes over the imports, in the parent and, page by page,
in the forked worker, of a one-file check (``make bench``). A check run without Typer ends
without tearing the interpreter down (:func:`_end`): under 50 ms on the corpus and on a
10,000-link robot, it stays while the check of robots/r2d2 misses its goal without it.

A plain check forks first, small, into a guardian and the process that runs the command
(:func:`_guarded`, :mod:`urdftool.guardian`): a budgeted file checked alone is checked in that
process, not in a worker forked after the rules were imported (whose pages it copied one by
one), and the guardian, outside, keeps the budget a worker had (a hung C call is killed at
--timeout, the stop reported by the guardian: U015; a death in the check: U900).

The door acts on its process (forks it into a guardian, ends it with ``os._exit``) only when
it is the program: :func:`main` called from the top level of the script Python runs, decided
once (:data:`PROGRAM`). A caller running the door inside its own program (a test runner's
worker, with a thread of its own reading its orders) keeps its process, and gets SystemExit.

``python -m urdftool`` runs in the folder being checked, which Python puts first on
``sys.path`` (``''`` or its name): a ``yaml.py`` or ``numpy.py`` committed there would be
imported in place of the library. The door's first statement takes that entry out (no
``from __future__`` line comes before it: that is an import too), before anything else is
imported; ``-P``/``-I`` (Python's own guard) leave no such entry to take.
"""

import os
import sys

if __name__ == "__main__" and not sys.flags.safe_path and sys.path:
    try:
        _here = os.getcwd()
    except OSError:  # the folder was deleted under it: Python put '' there
        _here = ""
    if sys.path[0] in ("", _here):
        del sys.path[0]
    del _here

from contextlib import contextmanager  # noqa: E402 (after the guard above)


def main() -> None:
    """The program: :func:`_main` within :func:`urdftool.streams.run` (how it writes and ends
    when its output or its reader fails). Whether this call is the program's, the top level of
    the script Python runs (``urdftool``, ``python -m urdftool``, ``python -c``) and the first,
    is decided here, once (:data:`PROGRAM`): only then may the door fork its guardian
    (:func:`_guarded`); a caller running the door inside a process of its own (a test runner)
    is no such program, and its process must not be forked."""
    caller = sys._getframe(1)
    PROGRAM["entry"] = PROGRAM["entry"] is None and caller.f_code.co_name == "<module>" and \
        caller.f_globals.get("__name__") == "__main__"
    from urdftool.streams import run

    run(_main)


# entry: None before main() is first called; then whether that call was the program's own
PROGRAM: dict = {"entry": None}


def _main() -> None:
    words = sys.argv[1:]
    _help(words)
    if _guarded(words):  # the child: it runs the command, and ends as the program
        from urdftool.guardian import end_after

        end_after(lambda: _ended(words))
    with _verdict_given():
        _command(words)


def _ended(words: list[str]) -> None:
    """The command run as the program (:func:`urdftool.streams.run`), ended by :func:`_end`
    (the exit functions run, the status the streams allow) however it ends."""
    from urdftool.streams import run

    try:
        run(lambda: _command(words))
    except SystemExit as ended:
        code = ended.code
        if code is not None and not isinstance(code, int):
            sys.stderr.write(f"{code}\n")  # (as Python ends on such an exit)
            code = 1
        _end(code or 0)


def _command(words: list[str]) -> None:
    check = words[:1] == ["check"]
    if check:
        _pause_collector()
    try:
        kept_code()
        if check:
            _check(words)
            _collect_less()
    finally:
        _resume_collector()
    from urdftool.cli import main as run

    run()


def _check(words: list[str]) -> None:
    """Run ``check`` without Typer when its words are plain (:func:`plain_words`, with the
    parameters kept from the Typer app) and the standard streams are ones click writes to as
    they are (:func:`urdftool.terminal.plain`), and exit as Typer would; else return."""
    from urdftool.terminal import option_named_by_a_file

    if option_named_by_a_file(words[1:]) is not None:  # Typer's usage error says it
        return
    values = _plain_check(words)
    if values is None:
        return
    from urdftool.terminal import plain

    terminal = plain()
    if terminal is None:
        return
    _collect_less()
    _resume_collector()
    from urdftool.checking import run

    try:
        code = run(terminal, **values)
    except (KeyboardInterrupt, EOFError):  # as click says it
        terminal.echo("", err=True)
        terminal.say("Aborted!", err=True)
        code = 1
    except SystemExit as ended:  # a usage error
        if not isinstance(ended.code, int):
            raise
        code = ended.code
    _end(code)


def _plain_check(words: list[str]) -> dict | None:
    """The values of ``check``'s parameters for ``words`` when they are plain (with the
    parameters kept from the Typer app), else None; None too when click's shell completion
    asks."""
    if "_URDFTOOL_COMPLETE" in os.environ:
        return None
    read = _READ.pop(tuple(words), _READ)  # (read by _guarded, in this program's process)
    if read is not _READ:
        return read
    parameters = kept_words("check")
    return None if parameters is None else plain_words(words[1:], parameters)


# the words of the program (a tuple) -> their values as _guarded read them, for _check to
# take once (reading the kept texts and the commands' digest again cost 1.6 M instructions)
_READ: dict = {}


def _guarded(words: list[str]) -> bool:
    """Run a check whose words are plain (:func:`plain_words`) under a guardian forked now
    (:func:`urdftool.guardian.guarded`), before anything else is imported or the kept code is
    given, rather than in a budgeted worker forked after the rules are imported (whose pages it
    copied one by one). True in the child, which runs the command (a budgeted file checked
    alone is checked there). In the guardian: end as the child ended, or return False to run
    the command again with the piece the child was stopped in given its Stop (over its time,
    or died: U015, U900) without doing it. False with nothing forked for other words, standard
    input (read once), ``--fix`` and ``--diff`` (files written between two checks), without
    budgets (``--timeout 0 --max-memory 0``: the command line wins over settings files, and
    the check runs in one process, nothing to guard), when the
    door is not the program (:data:`PROGRAM`: a caller's process is not ours to fork, nor to
    end), or in a process where other threads run (a process forked from them may find a lock
    one of them held forever): those check in budgeted workers."""
    if not PROGRAM["entry"] or words[:1] != ["check"]:
        return False
    values = _READ[tuple(words)] = _plain_check(words)
    if values is None or "-" in values["words"] or values["fix"] or values["diff"] or \
            values["timeout"] == 0 and values["max_memory"] == "0" or not _one_thread():
        return False
    from urdftool import guardian

    found = guardian.guarded()
    if found is None:
        return guardian.guarding()
    code, verdict = found
    if verdict is None:
        _end(code, exit_functions=False)  # (the child's, which ran them)
    guardian.stopped_as(verdict)
    return False


def _one_thread() -> bool:
    """Whether this process runs one thread, as the system counts them (Linux: a thread
    started below :mod:`threading`, by ``_thread`` or a library's C code, counts too); else as
    :mod:`threading` counts them (not imported: none of its making runs)."""
    try:
        return len(os.listdir("/proc/self/task")) == 1
    except OSError:
        threading = sys.modules.get("threading")
        return threading is None or threading.active_count() == 1


@contextmanager
def _verdict_given():
    """No verdict of :func:`_guarded` left for what this process does after the check (a
    caller running the door in its own process)."""
    try:
        yield
    finally:
        from urdftool import guardian

        guardian.stopped_as(None)


def _end(code: int, exit_functions: bool = True) -> None:
    """Exit with ``code`` as ``SystemExit`` would, without tearing the interpreter down: the
    standard streams flushed, the exit functions run (last registered first, once), the
    streams flushed again, then the process ends, not freeing the rules', the robot's and the
    libraries' objects one by one (the system frees the memory at once). Files are closed by
    then (the cache and ``--output`` write within ``with``); the status is the one
    :func:`urdftool.streams.end` gives when the output failed (a reader that left, a full
    disk). Python ends as usual instead (``SystemExit``) while another thread of
    :mod:`threading` runs (its work would be cut short), and when the door is not the program
    (:data:`PROGRAM`: the process is its caller's to end)."""
    threading = sys.modules.get("threading")  # (not imported: no thread of its making runs)
    if not PROGRAM["entry"] or threading is not None and threading.active_count() > 1:
        raise SystemExit(code)
    from urdftool.streams import end

    code = end(code)
    if exit_functions:
        import atexit

        atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except Exception:  # (after the exit functions: what Python's ending gives then)
            code = code or 120
    os._exit(code)


def _collect_less() -> None:
    """Install into the engine (:data:`urdftool.lint.engine.COLLECTION`) the collector's
    rhythm for a check: the cyclic collector runs after 100,000 new objects rather than
    Python's 700 while a robot loads (millions of short-lived tuples, freed by reference
    counting: a tenth of a 10,000-link robot's check), and what the rules build and keep for
    as long as the robot lives is moved to the oldest generation unexamined (the collector
    examined all of it twice, young then middle, to find a few cycles). The cycles left
    (trimesh's, a few MB per robot) are freed by a full collection before the check that
    follows 250,000 objects moved so.

    The modules the check needs (the command's work now, the rules once files are to be
    checked: :func:`_import_rules`, never for a run the result cache serves) are imported with
    the collector off and then frozen (``gc.freeze()``): objects that live as long as the
    program, which the collector examined again and again as they were made, and which a
    worker forked to check a file would copy page by page as its collector wrote into them.

    The robot last checked is kept until the program ends (:data:`urdftool.lint.engine.
    LATEST`), which frees no object one by one (:func:`_end`, a worker's ``os._exit``)."""
    import gc

    gc.disable()
    try:
        import urdftool.checking  # noqa: F401  (the command, run by Typer or by _check)
        from urdftool.lint import runner
    finally:
        gc.freeze()
        _FROZEN["imports"] = True
        gc.enable()
    runner.import_rules = _import_rules


def _pause_collector() -> None:
    """The collector off from a check's first step (the kept code, the command's imports) until
    :func:`_collect_less` froze what they made (:func:`_resume_collector`): its collections of
    them found nothing to free (5 M instructions of r2d2's check, 10 of its 32 collections).
    Part of the collector's rhythm (``make bench`` patches both out)."""
    import gc

    if gc.isenabled():
        gc.disable()
        _PAUSED["collector"] = True


def _resume_collector() -> None:
    """The collector on again, if :func:`_pause_collector` turned it off (once)."""
    if _PAUSED["collector"]:
        import gc

        _PAUSED["collector"] = False
        gc.enable()


_PAUSED = {"collector": False}  # whether _pause_collector turned the collector off


def _import_rules() -> None:
    """The rules (the engine) imported as :func:`_collect_less` imports the command, and the
    collector's rhythm installed into the engine: when files are to be checked, before the
    workers that check them fork; a run the result cache serves whole imports no rule (33-75
    ms of the corpus's cached re-check did, from session 5 to 10)."""
    import gc

    from urdftool.lint import runner

    runner.import_rules = None  # (once)
    gc.disable()
    try:
        from urdftool.lint import engine
    finally:
        gc.freeze()
        _FROZEN["imports"] = True
        gc.enable()
    engine.COLLECTION = (_fewer_collections, _unexamined)
    engine.LATEST = []


# imports: whether what is frozen is what this program froze itself (the imports), not counted
# (gc.get_freeze_count() walks every frozen object: a millisecond after the imports)
_FROZEN = {"imports": False}
_PROMOTED = {"objects": 0}  # moved to the oldest generation since the last full collection
FULL_COLLECTION_AFTER = 250_000


@contextmanager
def _fewer_collections(young: int = 100_000):
    import gc

    threshold = gc.get_threshold()
    gc.set_threshold(max(young, threshold[0]), *threshold[1:])
    try:
        yield
    finally:
        gc.set_threshold(*threshold)


@contextmanager
def _unexamined():
    """The rules run with the collector paused; what they kept is then moved to the oldest
    generation (``gc.freeze()`` then ``gc.unfreeze()``; the imports :func:`_collect_less`
    froze go there too). Left to Python's collector when it is off or objects are frozen by
    another (a forking parent's own ``gc.freeze()`` must stay)."""
    import gc

    # (frozen, and not the imports _collect_less froze, some of which may be freed since)
    if not gc.isenabled() or not _FROZEN["imports"] and gc.get_freeze_count() > 0:
        yield
        return
    if _PROMOTED["objects"] > FULL_COLLECTION_AFTER:
        gc.collect()
        _PROMOTED["objects"] = 0
    gc.disable()
    try:
        yield
    finally:
        _PROMOTED["objects"] += gc.get_count()[0]
        gc.freeze()
        gc.unfreeze()
        _FROZEN["imports"] = False  # (no longer frozen)
        gc.enable()


KEPT_CODE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "__pycache__",
                         f"kept_code.{sys.implementation.cache_tag}.marshal")


def kept_code(path: str | None = None) -> None:
    """Give :mod:`dataclasses` and :mod:`re` the compiled forms of the class methods and
    regular expressions kept in ``path`` (KEPT_CODE) by :mod:`urdftool.kept_code`, when it
    was written by this very Python and is whole (:func:`kept_code_file`): a text or pattern
    kept is not compiled again; any other is, as always."""
    read = _kept_forms(path or KEPT_CODE)
    if read is None:
        return
    functions, patterns = read
    import builtins
    import dataclasses
    import re

    import _sre

    def exec_kept(source, globals=None, locals=None):
        if isinstance(source, str):
            source = functions.get(source, source)
        return builtins.exec(source, globals, locals)

    compile_pattern, cache, flag = re._compile, re._cache, re.RegexFlag
    unkept = re.DEBUG.value | re.TEMPLATE.value

    def compile_kept(pattern, flags):
        """``re._compile`` giving a kept pattern its compiled form, cached as it caches one;
        its flags tested as numbers (``flags & re.DEBUG`` is enum's ``__and__`` in Python, twice
        for each pattern compiled). Any other pattern, and one asking for re.DEBUG or
        re.TEMPLATE, is ``re._compile``'s."""
        if isinstance(flags, flag):
            flags = flags.value
        try:
            return cache[type(pattern), pattern, flags]
        except KeyError:
            pass
        found = patterns.get((pattern, flags)) if isinstance(pattern, (str, bytes)) else None
        if found is None or flags & unkept:
            return compile_pattern(pattern, flags)
        compiled = _sre.compile(pattern, *found)
        if len(cache) >= re._MAXCACHE:  # (as re drops the oldest)
            try:
                del cache[next(iter(cache))]
            except (StopIteration, RuntimeError, KeyError):
                pass
        cache[type(pattern), pattern, flags] = compiled
        return compiled

    dataclasses.exec = exec_kept  # (its module's global, found before the built-in)
    re._compile = compile_kept  # (re's functions call their module's global)


def kept_code_header() -> tuple:
    """What a KEPT_CODE file must have been written by: this Python, its bytecode, its regular
    expression engine."""
    from importlib._bootstrap_external import MAGIC_NUMBER
    from re._constants import MAGIC

    return sys.version, MAGIC_NUMBER, MAGIC


def kept_code_file(functions: dict, patterns: dict) -> bytes:
    """The KEPT_CODE file of ``functions`` and ``patterns``: the length of what follows it (8
    bytes, little end first), this Python's header (:func:`kept_code_header`) and a checksum
    of the marshalled forms (marshalled together), then the forms, as they are: read in place
    from the mapped file (:func:`_kept_forms`), never copied whole into memory first."""
    import marshal
    import zlib

    forms = marshal.dumps((functions, patterns))
    head = marshal.dumps((kept_code_header(), zlib.crc32(forms)))
    return len(head).to_bytes(8, "little") + head + forms


def _kept_forms(path: str) -> tuple[dict, dict] | None:
    """(functions, patterns) of the KEPT_CODE file at ``path``, or None when it is absent,
    unreadable, written by another Python, or not whole: a truncated or corrupt file, whose
    forms unmarshalled would raise (marshal's SystemError on a bad code object, _sre's
    "invalid SRE code") or, worse, run a flipped instruction, is caught by its checksum before
    a form is read. (The file is as trusted as the bytecode beside it: whoever can write one
    can write the other.) The file is mapped, not read: its bytes are checksummed and
    unmarshalled where the system keeps them (a copy of them cost a page fault per page)."""
    import marshal
    import mmap
    import zlib

    try:
        with open(path, "rb") as handle:
            data = mmap.mmap(handle.fileno(), 0, access=mmap.ACCESS_READ)
        try:
            size = int.from_bytes(data[:8], "little")
            header, checksum = marshal.loads(data[8:8 + size])
            if header != kept_code_header() or size < 1 or \
                    checksum != zlib.crc32(memoryview(data)[8 + size:]):
                return None
            functions, patterns = marshal.loads(memoryview(data)[8 + size:])
        finally:
            data.close()
    except Exception:  # (what marshal raises on data of another Python or none at all)
        return None
    return (functions, patterns) if type(functions) is dict and type(patterns) is dict else None


HELP_FILE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "help.txt")
HELP_MARK = "\f"  # starts each section of HELP_FILE (no help text holds one)
HELP_COLUMNS = 80  # click wraps help to min(terminal columns, 80) - 2


def _help(words: list[str]) -> None:
    """Exit with Typer's answer to ``words`` when they ask for help or the version and the
    kept help texts are current; else return."""
    if words in (["-V"], ["--version"]):
        from urdftool import __version__

        _exit_with(f"urdftool {__version__}\n", "", 0)
    if not words or words in (["--help"], ["-h"]):
        name = ""
    elif len(words) == 2 and words[1] in ("--help", "-h") and words[0][:1] not in ("-", ""):
        name = words[0]
    else:
        return
    if _columns() < HELP_COLUMNS or (text := kept_help().get(name)) is None:
        return
    if words:
        _exit_with(text, "", 0)
    _exit_with("", text, 2)  # no words: the help, as the usage error click makes of them


def _columns() -> int:
    """The terminal's width as click reads it (``shutil.get_terminal_size``, without importing
    shutil and what it imports)."""
    try:
        columns = int(os.environ["COLUMNS"])
    except (KeyError, ValueError):
        columns = 0
    if columns <= 0:
        try:
            columns = os.get_terminal_size(sys.__stdout__.fileno()).columns
        except (AttributeError, ValueError, OSError):
            columns = 0
    return columns or 80


def kept_help() -> dict[str, str]:
    """The help texts of HELP_FILE ("" for the program's, else by command), or none when it
    is absent or was made from other command modules than these."""
    return {head.removeprefix("help "): text for head, text in _kept().items()
            if head.startswith("help ")}


def _kept() -> dict[str, str]:
    """The sections of HELP_FILE by their heads, or none when it is absent or was made from
    other command modules than these."""
    try:
        with open(HELP_FILE, encoding="utf-8") as handle:
            sections = handle.read().split(HELP_MARK)[1:]
    except (OSError, UnicodeDecodeError):
        return {}
    if not sections or sections[0] != f"digest {commands_digest()}\n":
        return {}
    return dict(section.partition("\n")[::2] for section in sections[1:])


def kept_words(command: str) -> list[list[str]] | None:
    """The parameters of ``command`` kept in HELP_FILE by :mod:`urdftool.help_text` (name,
    kind, option names, negative option names, default), or None."""
    text = _kept().get(f"words {command}")
    return None if text is None else [line.split("\t") for line in text.splitlines()]


def _default(kind: str, text: str):
    """A default as :func:`urdftool.help_text.words` kept it."""
    if text == "[]":
        return []
    if text[:1] == "'":
        return text[1:]
    if text in ("None", "False", "True"):
        return {"None": None, "False": False, "True": True}[text]
    return float(text) if kind == "float" else int(text)


def plain_words(words: list[str], parameters: list[list[str]]) -> dict | None:
    """The values Typer gives a command's parameters (:func:`kept_words`) for ``words``, when
    they are plain: each word a path, an option named in full and alone (``-f json``,
    ``--format json``, ``--format=json``, ``--strict``; not ``-fjson``, ``-qv``, ``--``),
    each value one that cannot be read as an option (no leading ``-``) and that converts as
    click converts it (a path Typer refuses, present but unreadable, is not plain); at least
    one path. None for any other (Typer answers: its usage errors,
    ``--help``)."""
    from pathlib import Path

    values, options, positional = {}, {}, None
    for name, kind, names, negative, default in parameters:
        values[name] = _default(kind, default)
        if kind == "words":
            positional, values[name] = name, []
            continue
        for option in names.split(","):
            options[option] = (name, kind, True)
        for option in filter(None, negative.split(",")):
            options[option] = (name, kind, False)
    if positional is None:
        return None
    index = 0
    while index < len(words):
        word = words[index]
        index += 1
        if word == "-" or not word.startswith("-"):
            values[positional].append(word)
            continue
        given, equals, value = word.partition("=") if word.startswith("--") else (word, "", "")
        if given not in options:
            return None
        name, kind, positive = options[given]
        if kind in ("flag", "switch"):
            if equals:
                return None
            values[name] = positive
            continue
        if not equals:
            if index >= len(words):
                return None
            value = words[index]
            index += 1
        if value.startswith("-"):
            return None
        try:
            if kind in ("text", "texts"):
                read = value
            elif kind in ("path", "paths"):
                if not _typer_path(value):
                    return None
                read = Path(value)
            elif kind == "float":
                read = float(value)
                if read - read != 0:  # NaN or infinite: Typer's usage error (cli._finite_numbers)
                    return None
            else:
                from urdftool.numbers import in_int64

                read = int(value)  # (past 4,300 digits a ValueError: Typer's usage error)
                if kind.startswith("int>=") and read < int(kind[5:]) or not in_int64(read):
                    return None  # (past an int64: Typer's usage error, cli._bounded_integers)
        except ValueError:
            return None
        if kind in ("texts", "paths"):
            values[name].append(read)
        else:
            values[name] = read
    return values if values[positional] else None


def _typer_path(value: str) -> bool:
    """Whether Typer's path parameters take ``value`` as it is: absent, or present and
    readable (else Typer's usage error: "Path '...' is not readable.")."""
    try:
        os.stat(value)
    except (OSError, ValueError):
        return True
    return os.access(value, os.R_OK)


def commands_digest() -> str:
    """A digest of the command modules (``urdftool/cli/*.py``) the help texts come from."""
    import zlib

    folder = os.path.join(os.path.dirname(os.path.abspath(__file__)), "cli")
    digest = 0
    for name in sorted(n for n in os.listdir(folder) if n.endswith(".py")):
        with open(os.path.join(folder, name), "rb") as handle:
            digest = zlib.crc32(handle.read(), zlib.crc32(name.encode(), digest))
    return f"{digest:08x}"


def _exit_with(stdout: str, stderr: str, code: int) -> None:
    """Print ``stdout`` and ``stderr`` and exit with ``code`` (:func:`urdftool.streams.run`
    ends it quietly when the reader of standard output left, ``| head``, as click does)."""
    sys.stderr.write(stderr)
    sys.stdout.write(stdout)
    raise SystemExit(code)


if __name__ == "__main__":
    main()
