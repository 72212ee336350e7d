"""Run rules over robots: select, stamp, and never let one rule's crash end the run; what went
wrong around the rules as findings too: a load error's kind -> U0xx, a crash -> U900, a piece of
work the pool stopped (:class:`urdftool.lint.pool.Stop`) -> U015, U018 or U900."""

from __future__ import annotations

from contextlib import nullcontext
from pathlib import Path

from urdftool import budget as budgets
from urdftool.diagnostics import Finding, Location, display_path, distinct_sorted
from urdftool.errors import LoadError, Said, described, missing_extra
from urdftool.lint.catalogue import Conditional, ReadersTake, Refused, Rule, Taken, UrdfdomAlone, \
    weighed
from urdftool.lint.options import CheckOptions, FileResult, Selection
from urdftool.lint.parts import judged
from urdftool.lint.rules import CATALOGUE
from urdftool.lint import suppressions

TYPE_CHECKING = False  # (typing.TYPE_CHECKING: typing is not imported by a check)
if TYPE_CHECKING:
    from urdftool.lint.pool import Stop

__all__ = ["CheckOptions", "FileResult", "Selection", "check_robot", "load_and_check",
           "reader_crashes", "stop_finding"]

# What the loader's errors (LoadError.kind) and notes (LoadNote.kind) are reported as. The loader
# knows no rule code and names no option: the hints on what to pass are added here.
LOAD_CODES = {"read": "U001", "syntax": "U001", "empty": "U002", "binary": "U003", "root": "U004",
              "xacro": "U005", "arg": "U005", "io": "U005", "package": "U006",
              "too-large": "U008", "entity": "U009", "outside": "U014", "sandbox": "U016",
              "link": "U017"}
NOTE_CODES = {"xacro-in-urdf": "U007", "xacro-warning": "U010", "outside-file": "U013",
              "late-declaration": "U001", "double-hyphen": "U001",
              "root-namespace": "U004"}
# The errors for what urdfdom's parser (check_urdf, robot_state_publisher) refuses: the file does
# not parse, is not a <robot> of a version it reads, its tree, joint types, limits or joint
# numbers are broken, or a top-level material's name is given twice (U405, its other findings
# urdfdom takes). urdftool's other errors are on files urdfdom accepts (it is stricter there).
# tests/integration/test_parity.py holds this set to check_urdf's verdicts.
URDFDOM_REFUSES = frozenset({"U001", "U002", "U003", "U004", "U011", "U012",
                             "U101", "U102", "U103", "U104", "U105", "U106", "U108", "U109",
                             "U110", "U201", "U202", "U203", "U207", "U208", "U213",
                             "U023", "U405"})
# ... and what the commands that pose a robot (fk, render...) refuse besides: a link with two
# parent joints (U107), which urdfdom hangs under the joint whose name sorts last, Pinocchio
# too or refuses the robot ("Model does not have any body named a"), by the joints' names, and
# urdftool's kinematics and yourdfpy under neither (they stopped at it in their own words)
POSING_REFUSES = URDFDOM_REFUSES | {"U107"}
# ... but not a finding its rule says urdfdom takes (Finding.urdfdom_takes, from a
# lint.catalogue.Taken message): an empty <robot name=""> (U011; check_urdf prints "robot name
# is: "), a joint's name="" or an only link's missing or empty name (U103), a loop beside the
# tree (U109; check_urdf drops its links), which every command refused before as if urdfdom had
_HINTS = {"too-large": lambda subject: " (raise it with --max-file-size)",
          "arg": lambda subject: f"; pass it as {subject}:=VALUE (or --arg {subject}=VALUE)"}

def stamp(rule: Rule, where, message: str, robot, fix=None, severity=None) -> Finding:
    """A finding for ``rule`` at ``where`` (element, Location or None), with its fix if any and
    its severity when lower than the rule's (a condition the rule cannot decide)."""
    location = where if isinstance(where, Location) else robot.locate(where)
    return rule.finding(message, location, fix, severity)


def stamp_all(rule: Rule, yielded: list, robot) -> list[Finding]:
    """:func:`stamp` of each (where, message, [fix, severity]) a rule yielded, in order: the
    elements located together (:meth:`~urdftool.description.robot.Robot.locate_all`), a plain
    message (a str without fix or severity) made into its finding here, as
    :meth:`~urdftool.lint.catalogue.Rule.finding` makes it (10,000 findings on a large
    robot: a call less for each)."""
    locations = robot.locate_all([where for where, _, _ in yielded])
    code, name, severity, target = rule.code, rule.name, rule.severity, rule.target
    found = []
    for (_, message, rest), location in zip(yielded, locations):
        if not rest and type(message) is str:
            found.append(Finding(code, name, severity, message, location, None, target, False))
        else:
            found.append(rule.finding(message, location, *rest))
    return found


def _stamped_before(rule: Rule, yielded: list, robot) -> tuple[list[Finding], Exception | None]:
    """(the findings of what a rule yielded before it failed, each stamped as it came; the
    error stamping one raised, which came first, or None)."""
    found = []
    for where, message, rest in yielded:
        try:
            found.append(stamp(rule, where, message, robot, *rest))
        except MemoryError:
            raise
        except Exception as error:
            return found, error
    return found, None


def _failure(rule: Rule, error: Exception, robot) -> Finding:
    """The finding for a rule that raised ``error``: what a lint-only install did not run
    (U902), else a crash (U900); ``error`` raised again when it is the memory budget's."""
    _raise_if_out_of_memory(error)  # (a library not mapped under the memory budget, too)
    advice = missing_extra(error) if isinstance(error, ImportError) else None
    if advice is None:
        return _crash(f"rule {rule.code} ({rule.name})", error, robot.locate(None))
    return CATALOGUE.get("U902").finding(
        f"rule {rule.code} ({rule.name}) did not run: it {advice}", robot.locate(None))


def _raise_if_out_of_memory(error: Exception) -> None:
    """Raise ``error`` again when it is the memory budget's doing though not a MemoryError
    (:func:`urdftool.lint.pool.out_of_memory`): the pool stops the piece (U018), where a U900
    built at the memory ceiling is the next allocation refused, or a segmentation fault."""
    from urdftool.lint.pool import out_of_memory  # (imported wherever a budget applies)

    if out_of_memory(error):
        raise error


def _crash(what: str, error: BaseException, location: Location) -> Finding:
    """U900 for a crash in urdftool itself, naming the code line that raised."""
    import traceback  # only for a crash

    frame = traceback.extract_tb(error.__traceback__)[-1] if error.__traceback__ else None
    where = f" [{Path(frame.filename).name}:{frame.lineno}]" if frame else ""
    return CATALOGUE.get("U900").finding(
        f"{what} crashed: {described(error)}{where}", location)


def reader_crashes() -> list[Finding]:
    """U900 for each crash of a reader of the user's files outside a rule since the last call
    (:func:`urdftool.description.crashes.drained`: a launch file read while finding targets or
    for a rule), at the file it was reading and naming the reader; one the memory budget did
    is raised again (the pool stops it: U018)."""
    from urdftool.description.crashes import drained

    found = []
    for crash in drained():
        _raise_if_out_of_memory(crash.error)
        found.append(_crash(crash.reader, crash.error, Location(display_path(crash.path))))
    return found


def load_error_message(error: LoadError) -> str:
    """The message of a load error as reported, with the hint on how to get past it."""
    hint = _HINTS.get(error.kind)
    return error.message + (hint(error.subject) if hint else "")


def load_error_findings(error: LoadError) -> list[Finding]:
    """A file that did not load, as findings: one, of the rule its kind maps to; a warning
    when it may not hold after a package's build (``error.certain``: an included file that
    package's install rules, not read, may put there); a note for a package the file's
    package.xml declares as a dependency (U006). A package not installed here leaves the robot
    not checked (:attr:`~urdftool.diagnostics.Finding.not_checked`)."""
    rule = CATALOGUE.get(LOAD_CODES[error.kind])
    unexpanded = error.kind == "package"
    # a dependency the package.xml declares: installed wherever the package is built, a
    # question of the workspace, not a defect of the file (a note; the run still exits 2)
    return [rule.finding(weighed(load_error_message(error), error.certain,
                                 unexpanded and error.declared), error.location,
                         not_checked=unexpanded)]  # (the message carries error.repeated)


def note_findings(robot) -> list[Finding]:
    """What the loader noticed without stopping (``robot.notes``), as findings."""
    findings = []
    for note in robot.notes:
        message = note.message
        if note.cause is not None and load_error_message(note.cause) != note.cause.message:
            message = message.replace(note.cause.message, load_error_message(note.cause), 1)
        if note.severity is not None:
            message = Conditional(message, note.severity)
        findings.append(CATALOGUE.get(NOTE_CODES[note.kind]).finding(
            message, note.location, repeated=note.cause.repeated if note.cause else ()))
    return findings


def check_robot(robot, selection: Selection = Selection()) -> list[Finding]:
    """Run every selected rule over a loaded robot; a crashing rule becomes U900. On a part of
    a robot defined elsewhere, what it cannot be right about alone is a note
    (:func:`~urdftool.lint.parts.judged`).

    Inline ``<!-- urdftool: ignore ... -->`` comments then filter the findings (see
    :mod:`urdftool.lint.suppressions`); unused ones become U901.
    """
    if selection.targets:
        robot.targets = target_versions(selection.targets)
    allows = selection.allowing()
    findings = [f for f in note_findings(robot) if allows(f.code)]
    findings += judged(robot, _run_rules(robot, allows, bool(selection.targets)))
    findings = suppressions.apply(findings, robot.sources, allows, CATALOGUE)
    return distinct_sorted(findings)


def as_read(robot, message: ReadersTake) -> str:
    """A rule's :class:`~urdftool.lint.catalogue.ReadersTake` message as the robot's readers
    make it, the one place this is decided for every rule: on a robot another reader reads
    (:func:`~urdftool.description.readers.other_reader`) that takes the shape, a warning
    naming the condition, "if WHO loads it (WHO reads it and why; nothing says ROS runs it)"
    (a :class:`~urdftool.lint.catalogue.Refused` one, still urdfdom's refusal, for an
    :class:`~urdftool.lint.catalogue.UrdfdomAlone`); else the rule's message as it is (what
    urdfdom refuses, or what a simulator refuses, is an error for every file it may read:
    docs/certainty.md)."""
    from urdftool.description.readers import other_reader  # (asked of a marked shape only)

    reader = other_reader(robot)
    if reader is None or reader.kind not in message.takers:
        if isinstance(message, Taken):  # (urdfdom takes the robot all the same: no refusal)
            return Taken(str(message), message.repeated)
        return Said(str(message), message.repeated) if message.repeated else str(message)
    why = f" ({reader.why})"
    said = Refused if isinstance(message, UrdfdomAlone) else Conditional
    return said(f"if {message.takers[reader.kind]} loads it" + why + ": " + message,
                repeated=(("why", why, ""),))


def _run_rules(robot, allows, targets: bool = True) -> list[Finding]:
    findings = []
    for rule in CATALOGUE.running(targets):  # (without targets, no target's family imported)
        if rule.check is None or not allows(rule.code):
            continue
        yielded = []  # (where, message, [fix, severity]): stamped together once the rule ends
        try:
            for where, message, *rest in rule.check(robot):
                if isinstance(message, ReadersTake):
                    message = as_read(robot, message)
                yielded.append((where, message, rest))
            if yielded:  # (most rules find nothing)
                findings += stamp_all(rule, yielded, robot)
        except MemoryError:
            raise  # over the memory budget: the pool stops it (U018)
        except Exception as error:  # a bug in a rule must not hide the other findings; a
            # lint-only install says what did not run, and why. What came before the error is
            # stamped as it came, and a finding that cannot be is the failure (it came first).
            stamped, failed = _stamped_before(rule, yielded, robot)
            findings += stamped
            findings.append(_failure(rule, failed or error, robot))
    return findings


def target_versions(targets) -> dict:
    """``NAME`` / ``NAME@VERSION`` words as name -> version tuple (None: the newest known)."""
    from urdftool.simulators import parse_target

    found = {}
    for word in targets:
        target = parse_target(word)
        found[target.name] = target.version
    return found


def urdfdom_refusals(robot, codes=URDFDOM_REFUSES) -> list[Finding]:
    """Why urdfdom (check_urdf, robot_state_publisher) would refuse a loaded robot: the errors
    of :data:`URDFDOM_REFUSES` (or of ``codes``: :data:`POSING_REFUSES`), located, sorted;
    empty when it would parse it; a finding its rule says urdfdom takes
    (:attr:`~urdftool.diagnostics.Finding.urdfdom_takes`) is not one, and a warning on a file
    another reader takes that urdfdom refuses all the same
    (:attr:`~urdftool.diagnostics.Finding.urdfdom_refuses`) is. Inline suppressions do not
    apply: they cannot make urdfdom accept a file."""
    found = _run_rules(robot, codes.__contains__)
    return sorted({f for f in found if f.urdfdom_refuses
                   or f.severity.value == "error" and not f.urdfdom_takes},
                  key=Finding.sort_key)


# How the cyclic garbage collector runs around each check: (a context manager factory around a
# whole check, one around its rules). Python's own collection unless the program installs its
# own: ``urdftool/__main__.py``, the one door for speed tricks, does for the command line.
COLLECTION = (nullcontext, nullcontext)
# Where the robot of the latest check is kept once its result is made (None: nowhere; it is
# freed when its caller drops the result). A program that ends without freeing its objects
# (``os._exit``) installs a list (``urdftool/__main__.py`` does for a check): the last robot
# checked then lives until the end, and its objects (a 10,000-link robot's elements, tree and
# everything the rules built for it: 0.14 s) are not freed one by one; each check frees the
# robot before it first, so no more robots are alive at once than without the slot.
LATEST: list | None = None


def load_and_check(path: str, options: CheckOptions, data: bytes | None = None) -> FileResult:
    """Load and check one file with ``options`` as they are (no settings file is looked for:
    the public ``urdftool.check_file`` finds them, then calls this); ``data``: its content,
    when not to be read from ``path``. Load failures are findings too."""
    if LATEST:
        LATEST.clear()  # (before this check builds its robot: a memory budget sees one)
    with COLLECTION[0]():
        result = _recorded(path, options, data)
    if LATEST is not None:
        LATEST.append(result.robot)
    return result


def _recorded(path: str, options: CheckOptions, data: bytes | None) -> FileResult:
    """Load and check, everything read, searched and resolved noted in the result's record
    (:mod:`urdftool.description.record`): the loader, discovery and every rule read through
    the one door, so the record is complete; the result cache and the language server read it."""
    from urdftool.description.record import recording

    with recording() as record:
        result = _load_and_check(path, options, data)
    crashed = reader_crashes()  # (loading or its rules read on as if the file said nothing)
    if crashed:
        result.findings = distinct_sorted(result.findings + crashed)
    result.record = record
    return result


def _as_launched(robot, findings: list[Finding], options: CheckOptions, build) -> list[Finding]:
    """``findings`` of ``robot``, built with its own argument defaults, when every launch
    file of its repository builds it with other values
    (:func:`~urdftool.description.runtime.built_otherwise`): an error that the first such build
    (its arguments all known) does not have holds only for a plain ``xacro FILE``, so it is a
    warning saying so (autonomous_excavator's launch files build its xacro with
    ``use_nominal_extrinsics:=true``, which makes the camera frame a joint hangs from; with
    the default ``false`` the joint names a link that does not exist, U105). An error that
    build has too is an error; so is every one when no launch file builds the robot otherwise,
    or that build fails. ``build(args)`` loads the robot with those arguments."""
    from urdftool.description.runtime import built_otherwise
    from urdftool.diagnostics import Severity

    if not any(f.severity == Severity.ERROR for f in findings):
        return findings
    launched = next((made for made, _ in built_otherwise(robot)
                     if made.args and all(v is not None for v in made.args.values())), None)
    if launched is None:
        return findings
    try:
        other = build(dict(launched.args))
    except LoadError:
        return findings
    other.companion_paths, other.mesh_limits = robot.companion_paths, robot.mesh_limits
    other.xacro_args = dict(launched.args)
    other.rebuild = lambda more: build({**launched.args, **more})  # (as robot's: rules ask it)
    there = {(f.code, f.file, f.line) for f in check_robot(other, options.selection)}
    condition = (f"; that is the build with the robot's own argument defaults (a plain xacro "
                 f"of the file): {launched.named} builds it with {launched.shown_args()}, "
                 "which does not have it (--arg NAME=VALUE checks a build)")
    return distinct_sorted([
        Finding(f.code, f.name, Severity.WARNING, f.message + condition, f.location, f.fix,
                f.target, f.not_checked, f.repeated, f.urdfdom_takes,
                f.urdfdom_refuses or (f.code in URDFDOM_REFUSES and not f.urdfdom_takes))
        if f.severity == Severity.ERROR and (f.code, f.file, f.line) not in there else f
        for f in findings])


def _load_and_check(path: str, options: CheckOptions, data: bytes | None) -> FileResult:
    from urdftool.description.load import load

    xacro_args, built = dict(options.xacro_args or {}), []

    def build(given: dict):
        return load(path, xacro_args={**given, **xacro_args}, packages=options.packages,
                    allow_env=options.allow_env, max_file_size=options.max_file_size)

    try:
        try:
            robot = load(path, xacro_args=xacro_args, packages=options.packages,
                         allow_env=options.allow_env, max_file_size=options.max_file_size, data=data)
        except LoadError as error:
            if data is not None:
                raise
            if error.kind == "arg" and error.subject and error.subject not in xacro_args:
                from urdftool.lint.rules.loading import required_argument

                robot, given, built = required_argument(path, error, build)
                if robot is None:
                    return FileResult(path, built)
            elif error.kind in ("xacro", "io") and not xacro_args:
                from urdftool.lint.rules.loading import failing_defaults

                robot, given, built = failing_defaults(path, error, build)
                if robot is None and built:
                    return FileResult(path, built)
                if robot is None:
                    return _part_noted(path, error, options)
            elif error.kind == "package" and not xacro_args:
                return _part_noted(path, error, options)
            else:
                raise
            xacro_args = {**given, **xacro_args}
    except LoadError as error:
        # A file that cannot be loaded is never silently passed, whatever the selection.
        return FileResult(path, load_error_findings(error))
    except MemoryError:
        raise  # over the memory budget: the pool stops it where loading was (U018)
    except Exception as error:  # a loader bug (RecursionError too): a finding, not a traceback
        _raise_if_out_of_memory(error)
        shown = display_path(path) if path != "-" else "<stdin>"
        return FileResult(path, [_crash("loading", error, Location(shown))])
    robot.companion_paths, robot.mesh_limits = options.companions, options.mesh_limits
    robot.xacro_args = xacro_args
    robot.rebuild = lambda more: load(path, xacro_args={**xacro_args, **more}, data=data,
                                      packages=options.packages, allow_env=options.allow_env,
                                      max_file_size=options.max_file_size)
    with COLLECTION[1]():
        findings = check_robot(robot, options.selection)
        if not options.xacro_args and data is None:
            findings = _as_launched(robot, findings, options, build)
    if built and options.selection.allows(built[0].code):
        findings = sorted(set(findings) | set(built), key=Finding.sort_key)
    return FileResult(path, findings, robot, companions=_companion_lines(robot),
                      arguments=_arguments(robot, options.xacro_args))


def _arguments(robot, given) -> list | None:
    """:attr:`FileResult.arguments`: of ``given`` (the xacro arguments of the check), those
    the robot's files name, and those they declare; None without any given (nothing read)."""
    if not given:
        return None
    from urdftool.description.xacro_text import declared_arguments, unnamed_arguments

    unnamed = unnamed_arguments(robot.sources, given)
    return [sorted(name for name in given if name not in unnamed),
            declared_arguments(robot.sources)]


def _part_noted(path: str, error: LoadError, options: CheckOptions) -> FileResult:
    """The file's result when the load ``error`` is a note on a part of a robot defined
    elsewhere (:func:`~urdftool.lint.rules.loading.part_note`); else ``error`` raised again."""
    from urdftool.lint.rules.loading import part_note

    noted = part_note(path, error, options.packages, options.max_file_size)
    if not noted:
        raise error
    return FileResult(path, noted)


def _companion_lines(robot) -> list[str]:
    from urdftool.description.companions import companions

    try:
        return companions(robot).describe()
    except Exception as error:  # noqa: BLE001 - the rules already reported what broke
        return [f"companions not found: {described(error)}"]


def stop_finding(path: str, stop: Stop, doing: str) -> Finding:
    """The finding for work on ``path`` that ``stop`` ended; ``doing``: what it was, e.g.
    'checking'. Located where the work was, when known."""
    shown = display_path(path) if path != "-" else "<stdin>"
    where = stop.where or Location(shown)
    if path == "-" and where.file.endswith("stdin.xacro"):
        where = Location(shown, where.line, where.via)
    if stop.kind == "time":
        return _finding("U015", where, f"{doing} took longer than {stop.budget.seconds:g} s and "
                                       "was stopped (raise the budget with --timeout)")
    if stop.kind == "memory":
        limit = stop.budget.memory
        needed = (f"needed more than {budgets.format_memory(limit)} of memory"
                  if limit else "ran out of memory")
        return _finding("U018", where, f"{doing} {needed} and was stopped"
                                       + (" (raise the budget with --max-memory)" if limit else ""))
    detail = stop.detail.strip().splitlines()[-1] if stop.detail.strip() else stop.kind
    if stop.kind == "died" and stop.budget.memory:  # C libraries may exit when malloc fails
        detail += (f"; it may have run out of its {budgets.format_memory(stop.budget.memory)} "
                   "of memory (--max-memory)")
    return _finding("U900", where, f"internal error: {detail}")


def _finding(code: str, where: Location, message: str) -> Finding:
    return CATALOGUE.get(code).finding(message, where)
