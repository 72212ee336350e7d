"""Exceptions. One base class; narrow subclasses carry the data a reporter needs."""

from __future__ import annotations

import functools
import os
import re
from dataclasses import dataclass


class UrdftoolError(Exception):
    """Base class of every error urdftool raises on purpose.

    asked: whose the error is, which decides how every command ends on it
    (``cli._common.fail_at``, the one reader). True: the question's. The command line asked
    the robot for what it does not have, or not in the form the command needs: a name it lacks,
    a tip not below its base, a limb or chain that no joint moves, a limb or D-H chain through
    a joint the computation does not take, a file of values or a D-H table that cannot be
    read or does not fit the robot. Another base, tip, name or file answers it; the robot is
    not at fault. A usage error: one line, exit 2. False (the default): the robot's. It
    cannot be computed as the command takes it whatever the command line says (a model
    refuses it, a mimic loop, an origin past what can be computed, a support link with no
    geometry): the error at its line, exit 1, as ``check``'s findings. Set by the raiser,
    the only one that knows whether a name came from the user."""

    asked = False


class UsageError(UrdftoolError):
    """The command line asked for something impossible (exit code 2)."""

    asked = True


class OptionError(UsageError, TypeError, ValueError):
    """An option given to urdftool's Python API of a kind or value the command line and the
    settings refuse; ``option`` names it. A TypeError and a ValueError too, as Python's
    callers expect of a wrong argument (raised by :mod:`urdftool.description.inputs`' guard)."""

    def __init__(self, option: str, message: str):
        super().__init__(message)
        self.option = option


class SettingsError(UrdftoolError):
    """A settings file, or a setting passed to the API, is malformed or names a path it may
    not."""


class TargetError(UrdftoolError):
    """A path to check does not exist or holds no robot description."""


class LoadError(UrdftoolError):
    """A robot description could not be loaded.

    kind: why, one of 'read', 'too-large', 'empty', 'binary', 'syntax', 'entity', 'root',
        'xacro', 'arg' (an undefined xacro argument, named by ``subject``), 'io', 'package'
        (named by ``subject``), 'sandbox', 'outside' or 'link'
    message: what went wrong, for people
    location: the :class:`~urdftool.diagnostics.Location` of the problem
    certain: False when it may not hold after a package's build (an included file missing from
        the source tree whose package's install rules could not be read)
    close: for 'package', the packages found whose names are close to ``subject`` (a misspelt
        or stale name, most likely)
    whatever_args: True when it fails whatever values the xacro arguments have (a macro call
        under no condition giving a parameter the macro lacks)
    declared: for 'package', True when the package.xml of the file's package declares it as a
        dependency (:attr:`PackageNotFound.declared_by`): installed wherever that package is
        built, a question of the workspace, not of the file
    undefined: for 'xacro', True when it fails on a name the file uses and does not define (a
        property, a macro, a property to forward), which a robot including it may define
    repeated: the parts of the message other findings say word for word (for 'package', where
        it was looked for: :attr:`PackageNotFound.repeated`; an available list), which
        ``message`` carries too (a :class:`Said`)
    """

    def __init__(self, kind: str, message: str, location, subject: str | None = None,
                 certain: bool = True, close: tuple = (), whatever_args: bool = False,
                 declared: bool = False, undefined: bool = False, repeated: tuple = ()):
        self.kind = kind
        # (a Said: a message built on it with + keeps them, an f-string raises)
        self.message = Said(message, repeated) if repeated else message
        self.location = location
        self.subject = subject
        self.certain = certain
        self.close = tuple(close)
        self.whatever_args = whatever_args
        self.declared = declared
        self.undefined = undefined
        self.repeated = tuple(repeated)
        super().__init__(message)


class PackageNotFound(UrdftoolError):
    """A ROS package named by ``$(find)`` or ``package://`` is nowhere on the search path.

    ``unchecked`` says what is not checked for want of it: the robot (a ``$(find)``: it is
    not expanded) or a mesh (``package://``: the robot is checked without it). ``declared_by``:
    the package whose package.xml declares it as a dependency (installed wherever that package
    is built, a question of the workspace, not of the file naming it), or None; ``manifest``:
    the file that package's manifest is (``package.xml``, or rosbuild's ``manifest.xml``, whose
    dependencies are ``<depend package="NAME"/>``). ``repeated``:
    the part of its message from "; looked in: " to its end (where it looked, how to pass it),
    which every file or mesh naming the package says again, ``("searched", text, name)``
    (:attr:`urdftool.diagnostics.Finding.repeated`)."""

    ROBOT = "the robot is not expanded, so not checked"

    def __init__(self, name: str, searched: list[str], declared_by: str | None = None,
                 undeclared_by: str | None = None, close: tuple = (), unchecked: str = ROBOT,
                 manifest: str = "package.xml"):
        self.name = name
        self.manifest = manifest
        self.searched = searched
        self.declared_by = declared_by
        self.close = tuple(close)  # the packages found whose names are close to this one
        self.unchecked = unchecked
        # (a search path of 8,000 entries was a 240 KB message for every mesh)
        where = first_listed(searched, len(searched), "places") if searched \
            else "nowhere (no search path)"
        hint = ("did you mean " + " or ".join(f"'{other}'" for other in self.close) + "? "
                if self.close else "")
        if declared_by:
            said = (f"package '{name}' not found: the {manifest} of '{declared_by}' declares "
                    f"it as a dependency, which is not installed here: {unchecked} (nothing in "
                    "it is known to be wrong)")
            searched = (f"; looked in: {where}. Pass --package {name}=PATH, set "
                        "ROS_PACKAGE_PATH or AMENT_PREFIX_PATH, or install the dependencies "
                        "(rosdep install --from-paths . --ignore-src)")
        elif undeclared_by:
            tag = f'<depend package="{name}"/>' if manifest == "manifest.xml" else \
                f"<exec_depend>{name}</exec_depend>"
            said = (f"package '{name}' not found, and the {manifest} of '{undeclared_by}' does "
                    f"not declare it, so rosdep would not install it: {hint}if it is another "
                    f"repository's, add {tag}; not installed here, {unchecked}")
            searched = (f"; looked in: {where}. Pass --package {name}=PATH or set "
                        "ROS_PACKAGE_PATH or AMENT_PREFIX_PATH")
        else:
            said = f"package '{name}' not found; {hint}{unchecked}"
            searched = f"; looked in: {where}. Pass --package {name}=PATH or set ROS_PACKAGE_PATH"
        super().__init__(said + searched)
        self.repeated = (("searched", searched, name),)

    def declared(self, owner: str | None, declares: bool = True,
                 unchecked: str | None = None, manifest: str = "package.xml") -> "PackageNotFound":
        """The same error, said of a package that ``owner``'s ``manifest`` (package.xml, or
        rosbuild's manifest.xml) depends on, or (not ``declares``) does not (no owner: said of
        a file in no ROS package, whose folders hold no package.xml or only one that is not a
        ROS package manifest: no dependency to add is advised), and of ``unchecked``."""
        return PackageNotFound(self.name, self.searched, owner if declares else None,
                               None if declares else owner, self.close,
                               unchecked or self.unchecked, manifest)

LISTED = 12  # items a list in a message or a report shows; more are counted
MAX_SIMILAR_NAME = 128  # [characters] longer names are neither looked up nor suggested
MAX_SIMILAR_CANDIDATES = 5000  # names compared with one that is not known
_SHOWN_NAME = 64  # [characters] of a name listed among the available ones


def close_names(wanted: str, names, n: int = 3, cutoff: float = 0.6) -> list[str]:
    """``difflib.get_close_matches`` bounded before the work: the one similarity search of
    urdftool (a test holds it so). A ratio costs the product of the two lengths, and a robot
    file can hold a 6 MB name (8 s of `check` on one): nothing is suggested for a name over
    MAX_SIMILAR_NAME characters, longer candidates are skipped, and at most
    MAX_SIMILAR_CANDIDATES are compared. A name of the same words in another order
    (``gripper_finger_l_link`` for ``gripper_finger_link_l``) comes first: difflib's ratio may
    rank the other finger's name above it. A name difflib finds close is suggested only when
    it has the same words (:func:`same_words`): 'torso_lift_joint' is no suggestion for
    'wheel_left_joint' (ratio 0.62, two words of three differ). Each search is made once per
    process (:func:`_close_names`): a check of the corpus asked 185 times, 33 of them
    different (``iyx`` among an inertia's attributes, a Gazebo plugin's ``alwaysOn``)."""
    if len(wanted) > MAX_SIMILAR_NAME:
        return []
    candidates = tuple(name for name in names
                       if len(name) <= MAX_SIMILAR_NAME)[:MAX_SIMILAR_CANDIDATES]
    return list(_close_names(wanted, candidates, n, cutoff))


@functools.lru_cache(maxsize=128)
def _close_names(wanted: str, candidates: tuple[str, ...], n: int,
                 cutoff: float) -> tuple[str, ...]:
    """:func:`close_names` of bounded ``candidates``, as a tuple (an answer kept is never
    changed by a caller)."""
    import difflib

    words = sorted(wanted.split("_"))
    reordered = [name for name in candidates
                 if name != wanted and "_" in name and sorted(name.split("_")) == words]
    close = [name for name in difflib.get_close_matches(wanted, candidates, n=n + 5, cutoff=cutoff)
             if same_words(wanted, name)]
    # then a close name holding every word of a name of three or more, and one more (Gazebo's
    # depthImageCameraInfoTopicName for depthImageInfoTopicName, before depthImageTopicName;
    # not joint1_mimic for joint1, whose joint_1 difflib ranks first)
    mine = _words(wanted)
    fuller = [] if len(mine) < 3 else [
        name for name, words in ((name, _words(name)) for name in close if name not in reordered)
        if len(words - mine) == 1 and mine <= words]
    return tuple((reordered + fuller + [name for name in close
                                        if name not in reordered and name not in fuller])[:n])


def same_words(wanted: str, name: str) -> bool:
    """Whether ``name`` may be what was meant by ``wanted``, word by word: the same letters and
    digits once case and separators are dropped (``FRHAA``, ``FR_HAA``; ``link2``,
    ``link_02``), or every word of one found in the other, in any order, each the same word,
    a near miss (difflib's ratio 0.75 or more: ``Join``/``Joint``, ``Rollert``/``Roller``; not
    of a word of two letters, an acronym a letter more makes another: ``ur``/``mur``, which
    suggested ``mur_desciption`` for ``ur_description``) or its initial (``l``/``left``),
    digits equal as numbers. So a word added or dropped is a
    suggestion (``gazebo_HEAD_JOINT1_Link``, ``arm_left_1_joint`` for ``arm_1_joint``) and a
    word replaced is not (``wrist_3_joint``/``hand_3_joint``, ``ur_description``/
    ``sr_description``, ``arm_0_link``/``arm_6_link``). Chosen on 60 suggestions of the real
    sweep judged by hand: 24 useful and 3 misleading kept, of 28 and 32 (difflib's ratio
    alone: 22 and 8 at 0.75). A name that drops words must keep one that is not a kind
    (:data:`KIND_WORDS`) or a number: ``joint1`` names no part, and is no suggestion for
    ``finger_joint1`` (a gripper's joint on an arm without one); ``interfaces`` stays for
    ``state_interfaces`` (joint_state_broadcaster's parameter of that meaning). Of the sweep's
    48 suggestions dropping a word, the misleading one went, no useful one
    (``gazebo_CHEST_JOINT0_Link``'s ``CHEST_JOINT0_Link`` stays). An initial stands for a
    word in its own place only (``g_base``, ``gripper_base``): the ``r`` of
    ``r_gripper_aft_link`` is no ``roll`` of ``gripper_roll_link``."""
    mine, theirs = _pieces(wanted), _pieces(name)
    if "".join(mine) == "".join(theirs):
        return True
    left, unmatched = list(enumerate(theirs)), 0
    for place, word in enumerate(mine):
        match = next((i for i, (_, other) in enumerate(left) if other == word), None)
        if match is None:  # an initial stands for the word in its own place only
            match = next((i for i, (at, other) in enumerate(left) if _alike(word, other)
                          and (min(len(word), len(other)) > 1 or at == place)), None)
        if match is None:
            unmatched += 1
        else:
            left.pop(match)
    if unmatched == 0:
        return True
    return not left and any(word.isalpha() and word not in KIND_WORDS for word in theirs)


# what a name's words say of its kind, not which part it is
KIND_WORDS = frozenset(("link", "joint", "frame", "group", "controller", "transmission",
                        "trans"))


def renamed(wanted: str, names) -> list[str]:
    """The names that are ``wanted`` with its first word replaced by other words, its other
    words (two or more pieces, one of them a number) ending the name: victor.urdf's
    transmissions name ``iiwa_joint_7``, written before the arms took their prefixes, where the
    joints are ``victor_left_arm_joint_7`` and ``victor_right_arm_joint_7`` (difflib's ratio
    0.57: not close). In the order given."""
    if len(wanted) > MAX_SIMILAR_NAME:
        return []
    mine = _pieces(wanted)
    first = _WORD.findall(wanted)[:1]
    rest = mine[len(_pieces(first[0])):] if first else []
    if len(rest) < 2 or not any(piece.isdigit() for piece in rest):
        return []
    found = []
    for name in list(names)[:MAX_SIMILAR_CANDIDATES]:
        theirs = _pieces(name) if len(name) <= MAX_SIMILAR_NAME else []
        if len(theirs) > len(rest) and theirs[-len(rest):] == rest and \
                theirs[:len(theirs) - len(rest)] != mine[:len(mine) - len(rest)]:
            found.append(name)
    return found


_PIECE = re.compile(r"[a-z]+|[0-9]+")


def _pieces(name: str) -> list[str]:
    """The words of a name (:func:`_words`) in order, letters and digits apart, numbers without
    leading zeros."""
    found = []
    for word in _WORD.findall(name):
        for piece in _PIECE.findall(word.lower()):
            found.append((piece.lstrip("0") or "0") if piece.isdigit() else piece)
    return found


def _alike(one: str, two: str) -> bool:
    """Two words that are not equal, one a near miss or the initial of the other."""
    import difflib

    if not (one.isalpha() and two.isalpha()):
        return False
    if min(len(one), len(two)) == 1:
        return one[0] == two[0]
    if min(len(one), len(two)) == 2:  # an acronym: a letter more makes another (ur, mur)
        return False
    return difflib.SequenceMatcher(None, one, two).ratio() >= 0.75


def _words(name: str) -> set[str]:
    """The words of a name, lower case: split at ``_``, ``-``, ``.`` and camelCase humps."""
    return {word.lower() for word in _WORD.findall(name)}


_WORD = re.compile(r"[A-Z]?[a-z0-9]+|[A-Z]+(?![a-z])")


def similarity(one: str, two: str) -> float:
    """difflib's ratio of two names, 0.0 when either is over MAX_SIMILAR_NAME characters (see
    :func:`close_names`)."""
    import difflib

    if len(one) > MAX_SIMILAR_NAME or len(two) > MAX_SIMILAR_NAME:
        return 0.0
    return difflib.SequenceMatcher(None, one, two).ratio()


def shown_word(name: str) -> str:
    """A name or value a message quotes from an input (a robot, a file of numbers), cut to
    64 characters with its length said: a 10 MB cell is not repeated whole."""
    return name if len(name) <= _SHOWN_NAME else f"{name[:_SHOWN_NAME]}... ({len(name)} characters)"


# ``{name}`` with no ``$`` before it: xacro leaves it as written (a substitution's "$" forgotten);
# in a value, any ``{expression}`` (``{-2*pi}``)
_BARE_SUBSTITUTION = re.compile(r"(?<!\$)\{([A-Za-z_]\w*)\}")
BARE_EXPRESSION = re.compile(r"(?<!\$)\{([^{}$]+)\}")


def bare_substitution(text: str, pattern: re.Pattern = _BARE_SUBSTITUTION) -> str | None:
    """Why ``text`` holds a ``{...}`` that ``pattern`` finds with no ``$`` before it (xacro
    leaves it as written), or None."""
    bare = pattern.search(text)
    return (f"'{bare.group(0)}' is a xacro substitution without its '$' "
            f"(${{{bare.group(1)}}}), which xacro leaves as written") if bare else None


def available(kind: str, wanted: str, names, *more: tuple[str, object]) -> str:
    """``Did you mean 'x'? Available links: a, b, ...`` for a name that does not exist. A name
    holding ``{x}`` without its ``$`` is said to: xacro left ``{x}`` as written, and the closest
    name (one leg's of four, for ``{name}_hip``) would mislead. ``more``: (kind, names) of
    other kinds the name may be of, each listed after the first (``<gazebo reference>`` names a
    link or a joint: "available links: ...; available joints: ..."), the closest name looked
    for among them all."""
    # (unnamed elements are another rule's business)
    kinds = [(one, sorted({name for name in some if name})) for one, some in ((kind, names), *more)]
    every = sorted({name for _, some in kinds for name in some})
    bare = bare_substitution(wanted)
    # a name written with white space at an end, which readers keep: shown alike unquoted
    spaced = None if bare else next((name for name in every if name != wanted
                                     and name.strip() == wanted.strip()), None)
    close = [] if bare or spaced else close_names(wanted, every, n=1)
    hint = f"did you mean '{close[0]}'? " if close else ""
    if spaced is not None:
        hint = (f"did you mean '{spaced}'? the two differ only in white space, which URDF "
                "readers keep (names are compared as written); ")
    if bare:
        hint = bare + "; "
    quote = any(name != name.strip() for name in every)
    lists = [(one, some, f"available {one}: {listed(some, quote=quote) or '(none)'}")
             for one, some in kinds]
    return Said(hint + "; ".join(written for _, _, written in lists),
                tuple(("available", written, f"{len(some)} {one}") for one, some, written in lists))


# Whether a Said formatted into a plain str raises (:class:`Said`): the test suite sets
# URDFTOOL_STRICT_MESSAGES (its cases, commands and workers, and a sweep drafted with it), where
# a wrapper that drops the parts fails; a user's run never fails on them (the report then
# writes that list again, as for a plain str).
STRICT_MESSAGES = bool(os.environ.get("URDFTOOL_STRICT_MESSAGES"))


class Said(str):
    """A message holding parts that other findings of one report say word for word
    (:attr:`~urdftool.diagnostics.Finding.repeated`: ``(kind, text, detail)`` each), such as
    the list :func:`available` writes (``available``, the list as written, how many and what
    it lists: ``31 links``). A message built on it with ``+`` (``"...; " + available(...)``)
    keeps them. An f-string or ``format`` would make a plain str without them, silently: under
    :data:`STRICT_MESSAGES` (the test suite's) it raises TypeError instead (a wrapper writes
    ``"if ...: " + message``, or ``str(message)`` where it means to drop them), and so does
    ``"%s" % said``. A str method (``join``, ``replace``) still drops them:
    tests/lint/test_cases.py holds every case's findings to carry the parts their messages
    say."""

    repeated: tuple

    def __new__(cls, text: str, repeated: tuple = ()):
        made = super().__new__(cls, text)
        made.repeated = tuple(repeated)
        return made

    def __format__(self, spec: str) -> str:
        if STRICT_MESSAGES:
            raise TypeError("a Said formatted into a str loses its repeated parts: build the "
                            "message with + (or quote str(said) to drop them on purpose)")
        return format(str(self), spec)

    def __rmod__(self, other):
        if STRICT_MESSAGES:
            raise TypeError("a Said formatted with % loses its repeated parts: build the "
                            "message with +")
        return NotImplemented

    def __add__(self, other: str) -> Said:
        return Said(str.__add__(self, other), self.repeated + getattr(other, "repeated", ()))

    def __radd__(self, other: str) -> Said:
        return Said(str.__add__(other, self), getattr(other, "repeated", ()) + self.repeated)

    def __getitem__(self, key) -> Said:
        """A piece (``message[len(label) + 2:]``), with the parts it still holds whole."""
        piece = str.__getitem__(self, key)
        return Said(piece, tuple(part for part in self.repeated if part[1] in piece))


def listed(names, quote: bool = True) -> str:
    """Names of an input said in a message: the first 12, each cut by :func:`shown_word`, then
    how many in all. A message said once per name of the same list (the multiple-roots
    finding at each of 10,000 roots, naming every root) repeated the list whole each time: a
    check's output grew as the square of the input (54 MB of JSON for 2,500 roots).
    ``quote``: each in single quotes."""
    names = list(names)
    return first_listed([f"'{shown_word(name)}'" if quote else shown_word(name)
                         for name in names[:LISTED]], len(names))


def first_listed(shown: list[str], count: int, unit: str = "", width: int | None = None) -> str:
    """A list of ``count`` items as a message or a report says it: the first :data:`LISTED` of
    ``shown`` (the items as written), then how many in all when there are more: ``a, b, ...
    (31 in all)``; ``unit`` names them in the count (``(8000 places in all)``). The one way
    every list is cut (:func:`listed` for names of an input). ``width`` [characters]: fewer
    items when they are long, those written within it (:data:`LISTED_LEAST` at least): twelve
    meshes each named with its ``package://`` path made one line of 1,900 characters (a
    macro's missing package on 43 links of AgiBot's G1)."""
    most = LISTED if width is None else fitting(shown, width)
    counted = f"{count} {unit}" if unit else str(count)
    return ", ".join(shown[:most]) + (f", ... ({counted} in all)" if count > most else "")


LISTED_LEAST = 3  # items a list cut to a width still shows


def fitting(shown: list[str], width: int) -> int:
    """How many of the first :data:`LISTED` of ``shown`` are written within ``width``
    characters (", " between them), :data:`LISTED_LEAST` at least."""
    used = most = 0
    for item in shown[:LISTED]:
        used += len(item) + 2 * (most > 0)
        if used > width and most >= LISTED_LEAST:
            break
        most += 1
    return most


class OverLimit(UrdftoolError):
    """An input over a size limit checked before the work it would cost (``what`` is over
    ``limit``; ``value`` is how much it is): the work is not started. The command line says
    which option raises the limit."""

    def __init__(self, what: str, value: int, limit: int, unit: str):
        self.what, self.value, self.limit, self.unit = what, value, limit, unit
        super().__init__(f"{what}: {value} {unit}, over the limit of {limit}; not computed")


# --- Errors of the analyses (one hierarchy; each is re-exported by the module that raises it,
# so ``except fk.FKError`` keeps working) ---------------------------------------------------


class LocatedError(UrdftoolError):
    """An error about a place in a robot description.

    element: the robot's XML element it is about (``Robot.locate`` gives file and line), or None
    location: a :class:`~urdftool.diagnostics.Location` when known without the robot, or None
    """

    element = None
    location = None

    def __init__(self, message: str, element=None, location=None, asked: bool = False):
        super().__init__(message)
        self.element = element
        self.location = location
        if asked:  # (the class's own value otherwise: a ConfigError is always the question's)
            self.asked = True


@dataclass(frozen=True)
class MeshProblem(LocatedError):
    """Why a mesh cannot be used.

    kind: ``package`` (unknown package), ``outside`` (escapes the root), ``missing``,
    ``format`` (not a mesh extension), ``too-large`` (bytes or triangles), ``corrupt``
    message: what a user should read, naming the file and the fix
    certain: False when the problem may not hold after the package's build (a file missing
    from the source tree whose package's install rules could not be read)
    declared: for ``package``, True when the robot's package.xml declares the package as a
    dependency (:attr:`PackageNotFound.declared_by`): the workspace's, not the file's
    kept_empty: for ``missing``, True when the file's folder holds only placeholders, kept
    empty in the repository for files put there later (a tool, a download, a build step):
    the repository leaves it for a tool to put there, as a declared dependency is left to the
    workspace
    repeated: for ``package``, the parts of the message every mesh of that package says again
    (:attr:`PackageNotFound.repeated`)
    """

    kind: str
    message: str
    certain: bool = True
    declared: bool = False
    kept_empty: bool = False
    repeated: tuple = ()

    def __str__(self) -> str:
        return self.message

    def quoting(self, uri: str, written: str) -> str:
        """The message with the mesh quoted as ``written`` in the user's file (a xacro's
        ``file://$(find pkg)/meshes/a.stl``), ``uri`` (what the robot, expanded, names: the
        message's quote) kept as detail: a message quoting only the expanded absolute path
        named what no file of the user says."""
        quoted = f"mesh '{uri}'"
        if written == uri or not self.message.startswith(quoted):
            return self.message
        return mesh_quoted(uri, written) + self.message[len(quoted):]


def mesh_quoted(uri: str, written: str) -> str:
    """A mesh as a message names it: ``mesh 'WRITTEN'``, as the user's file writes it (a
    xacro's ``file://$(find pkg)/meshes/a.stl``), with ``uri`` (what the robot, expanded,
    names) as detail when they differ."""
    return f"mesh '{uri}'" if written == uri else f"mesh '{written}' (expanded: '{uri}')"


def _exception_state_settable(frozen):
    """``frozen``'s __setattr__ (a frozen dataclass's, which refuses every name) letting
    Python set the state every exception carries: contextlib's ``@contextmanager`` sets
    ``__traceback__`` on the exception leaving its block, ``add_note`` sets ``__notes__``.
    Refused, a MeshProblem raised through such a block became a FrozenInstanceError."""
    allowed = frozenset({"__traceback__", "__cause__", "__context__", "__suppress_context__",
                         "__notes__"})
    refusing = frozen.__setattr__

    def __setattr__(self, name, value):
        if name in allowed:
            BaseException.__setattr__(self, name, value)
        else:
            refusing(self, name, value)

    frozen.__setattr__ = __setattr__
    return frozen


_exception_state_settable(MeshProblem)


class SrdfError(LocatedError):
    """The SRDF cannot be read; the message says where and why."""


class ConfigError(LocatedError):
    """A configuration that cannot be used; ``where`` is a file (and row) when it came from one,
    ``argument`` which of several inputs it came from (the parameter: q, v or a of the dynamics;
    q, xyz, orientation, frame_q or targets of inverse kinematics), when known. The message names no
    command-line option: the command adds it. Always the question's (``asked``): values given
    by the user."""

    asked = True

    def __init__(self, message: str, where: str | None = None):
        super().__init__(f"{where}: " + message if where else message)
        self.where = where
        self.argument: str | None = None


class MimicError(LocatedError):
    """A mimic joint whose value cannot be resolved; ``element`` is where."""


class TreeError(LocatedError):
    """The joints do not form one tree (no root, several roots, a cycle); ``element`` is where."""


class FKError(LocatedError):
    """The model cannot be built or asked for what it lacks; ``element`` locates it when known."""


class DHError(LocatedError):
    """A chain that cannot be written in D-H form, or a table that cannot be read; ``where`` is
    the table file (and row) when it came from one; ``asked``: the question's (a chain the
    user chose; a table the user gave, every error with a ``where``), see
    :class:`UrdftoolError`."""

    def __init__(self, message: str, element=None, where: str | None = None,
                 asked: bool = False):
        super().__init__(message, element, asked=asked or where is not None)
        self.where = where


class ModelBuildError(LocatedError):
    """Pinocchio's URDF parser (urdfdom) refuses the robot; the message gives urdfdom's reasons.
    The command line reports the linter's located findings instead, when it has some."""
class IKError(LocatedError):
    """A chain or target that inverse kinematics cannot work with (a limb without a moving
    joint, a target file that cannot be read); ``where`` is the target file (and row) when it
    came from one. A link name the robot does not have is an :class:`UnknownLink`;
    ``asked``: the question's (a limb the user chose), see :class:`UrdftoolError`."""

    def __init__(self, message: str, element=None, where: str | None = None,
                 asked: bool = False):
        super().__init__(f"{where}: " + message if where else message, element, asked=asked)
        self.where = where


class DynamicsError(LocatedError):
    """The robot cannot be turned into a dynamic model (Pinocchio's reason, made readable)."""


class SceneError(LocatedError):
    """The robot cannot be built into a scene to draw (yourdfpy's reason, made readable)."""


class DotMissing(UrdftoolError):
    """The ``dot`` program is not installed; the DOT file was written instead (the message is
    its path)."""


class UnknownName(UrdftoolError, ValueError):
    """A name asked for (a link, a rule) that does not exist; the message lists the close and
    the valid ones. Always the question's (``asked``)."""

    asked = True


class UnknownLink(UnknownName):
    """A link asked for by name that the robot does not have; the message lists the others."""

    def __init__(self, wanted: str, names, beside: bool = False):
        what = ("is beside the tree (no joint from the root reaches it: urdfdom drops it, and "
                "no command poses it)") if beside else "does not exist"
        super().__init__(f"link '{wanted}' {what}; " + available("links", wanted, names))
        self.wanted = wanted

    @classmethod
    def unless_among(cls, wanted, names, beside=()) -> None:
        """Raise for the first of ``wanted`` (link names asked for: a command line's) that is
        not among ``names`` (a robot's links, as its model has them), saying so of one of
        ``beside`` (links of the robot its model leaves out:
        ``kinematics.tree.beside_the_tree``): the one check of every command that names
        links, made before any work that might not look at them (diff's reach of a chain is
        computed only when the robots differ: an unknown link named there was "equivalent")."""
        for name in wanted:
            if name not in names:
                raise cls(name, names, name in beside)


class UnknownRule(UnknownName):
    """No rule has the code or name asked for; the message lists the close ones."""


class PlotError(UrdftoolError, ValueError):
    """A picture cannot be written in the asked format; the caller names the option."""


def described(error: BaseException) -> str:
    """An exception as a message says it: ``Name: text``, the one way urdftool quotes an error
    it did not make. Its name once when its text already starts with it (pycollada's said
    "DaeMalformedError: DaeMalformedError: XML Parsing Error..."), alone when it has no text
    (a MemoryError said "MemoryError: " and nothing)."""
    name, text = type(error).__name__, str(error)
    return text if text.startswith(f"{name}:") else f"{name}: {text}" if text else name


# The libraries only the analysis commands and a few rules need, by import name; they come
# with urdftool's ``analysis`` extra (a lint-only install has none of them).
ANALYSIS_MODULES = {"pinocchio": "pin", "fcl": "python-fcl", "yourdfpy": "yourdfpy",
                    "PIL": "pillow"}


def missing_extra(error: BaseException) -> str | None:
    """For an ImportError of an analysis library, what to install; None for any other error."""
    name = getattr(error, "name", None) or ""
    top = name.split(".")[0]
    if not isinstance(error, ImportError) or top not in ANALYSIS_MODULES:
        return None
    from urdftool.origin import install_command

    return (f"needs {ANALYSIS_MODULES[top]}, which a lint-only install leaves out: "
            f"{install_command('analysis')}")


# What a check refuses before checking anything, said in one line (exit 2 on the command line,
# a one-line failure of a pytest item): a usage error, a broken settings file, a path holding
# no robot, a name (rule, link) that does not exist.
REFUSALS = (UsageError, SettingsError, TargetError, UnknownName)
