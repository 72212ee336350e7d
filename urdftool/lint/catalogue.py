"""The rule catalogue: what a rule is, the families, and the catalogue built from family modules.

A rule is one function that yields ``(where, message)``, or ``(where, message, fix)`` when it
can say how to remove the finding (a :class:`~urdftool.diagnostics.Fix`, built with
:mod:`urdftool.lint.fixes`): ``where`` is an lxml element of the robot, a
:class:`~urdftool.diagnostics.Location` in another file, or None for the file as a whole.
The engine, not the rule, stamps the code, name, severity and location. The rule's docstring is
its documentation: a first-line summary, then why it matters, then examples (the pages of docs/rules/ and
``urdftool rules CODE`` are generated from it).

A rule's severity is for a defect that holds in every configuration the robot's consumers can
run (docs/certainty.md). A finding that holds only in some (a controller a launch file may or
may not start, a ROS version that may read the element) names the condition in its message and
is reported lower: yielded as ``(where, message, fix, severity)``, or with its message wrapped in
:class:`Conditional` (a warning unless it says otherwise); never above the rule's own severity.

``rule()`` marks a check with its code, name and severity and registers nothing. Codes that the
engine or the runner report themselves are ``declare()``d as module-level constants.
:meth:`Catalogue.from_modules` collects both from an explicit list of family modules
(``urdftool.lint.rules.FAMILY_MODULES``), in source order, and refuses a malformed, taken or
misordered code and a repeated name.

Families: U0xx loading (U02x the URDF vocabulary), U1xx kinematic tree, U2xx joints, U3xx inertials, U4xx geometry and
meshes, U5xx transmissions and ros2_control, U6xx controllers and Gazebo, U7xx joint spec table,
U8xx SRDF and collisions, U9xx urdftool itself (U92x-U98x: simulator portability, one decade per
target: what that program refuses or silently changes; they run only for the targets asked for,
``check --target NAME``, and each of their findings names its target).
"""

from __future__ import annotations

import functools
import inspect
import re
from collections.abc import Callable  # (not typing's: a check does not import it)

from urdftool.diagnostics import Finding, Fix, Location, Severity
from urdftool.errors import Said, UnknownRule  # (Said: the rules take it from here)
from urdftool.records import Frozen
from urdftool.simulators import SIMULATORS

__all__ = ["Rule", "Severity", "FAMILIES", "rule", "declare", "Catalogue", "UnknownRule",
           "Conditional", "ReadersTake", "Refused", "UrdfdomAlone", "UrdfdomDrops", "weighed",
           "NOT_LOADED"]

FAMILIES = {
    "U0": "loading and the URDF vocabulary",
    "U1": "kinematic tree",
    "U2": "joints",
    "U3": "inertials",
    "U4": "geometry and meshes",
    "U5": "transmissions and ros2_control",
    "U6": "controllers and Gazebo",
    "U7": "joint spec table",
    "U8": "SRDF and collisions",
    "U9": "urdftool",
}
# Simulator portability: one decade of codes per target (``check --target NAME``). A code in one
# of these decades is that target's: it runs only when the target is asked for, and its findings
# carry the target's name (:attr:`Finding.target`).
TARGET_DECADES = {"U92": "mujoco", "U93": "pybullet", "U94": "drake", "U95": "gz",
                  "U96": "gazebo", "U97": "isaac", "U98": "pinocchio"}
_CODE = re.compile(r"U\d{3}")
# who fails when urdfdom refuses a robot, as a finding of it says so (U023, U108, U405): the
# tools that load URDF through urdfdom (Gazebo through sdformat's urdfdom)
NOT_LOADED = "robot_state_publisher, RViz, MoveIt and Gazebo (sdformat) do not load it"
_RANK = {Severity.INFO: 0, Severity.WARNING: 1, Severity.ERROR: 2}


class Conditional(Said):
    """A finding's message when the defect holds only in some configurations the robot's
    consumers can run; the text names the condition ("if controller 'x' is started ...").
    Reported at ``severity`` (a warning unless said), or at the rule's own when that is lower.
    ``repeated``: as a :class:`~urdftool.errors.Said`'s, with those of ``text``."""

    severity: Severity

    def __new__(cls, text: str, severity: Severity = Severity.WARNING, repeated: tuple = ()):
        made = super().__new__(cls, text, tuple(repeated) + getattr(text, "repeated", ()))
        made.severity = Severity(severity)
        return made


class Taken(Said):
    """A finding's message when urdfdom (check_urdf, robot_state_publisher) parses the shape
    the finding is about, though it refuses others under the same code (a joint's ``name=""``
    where one without the attribute is refused; a loop of joints beside the tree, where one
    with no root is refused): the finding is the rule's as it is, and the commands that pose a
    robot do not refuse it as urdfdom's refusal (:attr:`~urdftool.diagnostics.Finding.
    urdfdom_takes`, asked by :func:`urdftool.lint.engine.urdfdom_refusals`). Checked against
    the real check_urdf by tests/integration/test_parity.py's table of shapes."""


class ReadersTake(Said):
    """A finding's message when the shape it is about is a defect for some consumers of the
    robot's file and other readers of URDF take it: ``takers``, the kinds of
    :class:`~urdftool.description.readers.Reader` that do ('drake', 'browser') -> who the
    defect is for on a file that reader reads, as the condition names it ("Gazebo or MuJoCo",
    "a simulator"). The rule says only that; the engine, in one place
    (:func:`urdftool.lint.engine.as_read`), decides from who reads the robot
    (:func:`~urdftool.description.readers.other_reader`) whether the finding is the rule's as
    it is (a file ROS or nobody known reads, or one read by a reader that does not take it) or
    a warning naming the condition, "if WHO loads it (why the reader reads it): ...".
    ``repeated``: as a :class:`~urdftool.errors.Said`'s."""

    takers: dict

    def __new__(cls, text: str, takers: dict, repeated: tuple = ()):
        made = super().__new__(cls, text, tuple(repeated) + getattr(text, "repeated", ()))
        made.takers = dict(takers)
        return made


class UrdfdomAlone(ReadersTake):
    """A :class:`ReadersTake` message when it is urdfdom that refuses the shape and other
    readers of URDF take it (``takers``: their kinds, 'drake', 'browser'): Drake's world frame
    as a joint's parent, a revolute joint without ``<limit>``. On a file such a reader reads,
    the engine makes it a :class:`Refused` warning, "if urdfdom loads it ..."."""

    def __new__(cls, text: str, takers, repeated: tuple = ()):
        return super().__new__(cls, text, dict.fromkeys(takers, "urdfdom"), repeated)


class UrdfdomDrops(ReadersTake, Taken):
    """A :class:`ReadersTake` message when urdfdom takes the robot but drops what the shape
    is about (and more) while other readers of URDF (``takers``) read it whole: a visual's
    ``<material>`` without a name, at which urdfdom stops reading the link. Its finding is no
    refusal (:class:`Taken`); on a file such a reader reads, a warning naming the condition,
    "if urdfdom loads it ..."."""

    def __new__(cls, text: str, takers, repeated: tuple = ()):
        return ReadersTake.__new__(cls, text, dict.fromkeys(takers, "urdfdom"), repeated)


class Refused(Conditional):
    """A :class:`Conditional` message whose finding is urdfdom's refusal all the same: a shape
    urdfdom refuses in a file its robot's readers (Drake, a web page) take, a warning naming
    the condition that still counts as the refusal it is
    (:attr:`~urdftool.diagnostics.Finding.urdfdom_refuses`, asked by
    :func:`urdftool.lint.engine.urdfdom_refusals`): the commands that pose a robot refuse it
    as urdfdom does. The opposite of :class:`Taken`. Made by the engine from a rule's
    :class:`UrdfdomAlone`, never by a rule."""


def weighed(message: str, certain: bool = True, workspace: bool = False,
            repeated: tuple = ()) -> str:
    """A file or package not found, as a finding's message at the severity what is known of it
    decides (the one rule of U005, U006, U407, U408): a **note** when it is the workspace's
    question, not the file's (``workspace``: a package the package.xml declares as a
    dependency, a folder kept empty for files a tool puts there later); a **warning** when it
    may not hold (not ``certain``: a package's build may put the file there, its install rules
    not read; a package not installed here); else the rule's own. ``repeated``: as a
    :class:`~urdftool.errors.Said`'s."""
    if workspace:
        return Conditional(message, Severity.INFO, repeated)
    if not certain:
        return Conditional(message, repeated=repeated)
    return Said(message, repeated) if repeated else message


class Rule(Frozen):
    """A rule: its code, name and severity, its check (None: reported by the engine or the
    runner) and its documentation as written (``written``: a docstring, indented as in its
    source; :attr:`doc` is it cleaned, when asked)."""

    code: str
    name: str
    severity: Severity
    check: Callable | None
    written: str

    __slots__ = ("code", "name", "severity", "check", "written")

    def __init__(self, code: str, name: str, severity: Severity, check: Callable | None,
                 written: str) -> None:
        set_field = object.__setattr__
        set_field(self, "code", code)
        set_field(self, "name", name)
        set_field(self, "severity", severity)
        set_field(self, "check", check)
        set_field(self, "written", written)

    @property
    def doc(self) -> str:
        """The documentation, its indentation removed (``inspect.cleandoc``): cleaned when a
        report or a page asks, not as the rules are imported (1.8 ms of every check, for 200
        docstrings no check reads)."""
        return _cleaned(self.written)

    @property
    def summary(self) -> str:
        return self.doc.strip().splitlines()[0].strip() if self.doc.strip() else self.name

    @property
    def family(self) -> str:
        target = self.target
        if target is not None:
            return f"simulator portability: {SIMULATORS[target].title}"
        return FAMILIES[self.code[:2]]

    @property
    def target(self) -> str | None:
        """The target (``check --target``) this rule is about, or None for a rule of every run."""
        return TARGET_DECADES.get(self.code[:3])

    def finding(self, message: str, location: Location, fix: Fix | None = None,
                severity: Severity | None = None, not_checked: bool = False,
                repeated: tuple = ()) -> Finding:
        """A finding of this rule at ``location``, with the fix that would remove it if any;
        ``severity`` lowers the rule's for a finding that holds only under a condition (it is
        never raised: ValueError); a :class:`Conditional` message is reported at its own
        severity when that is below the rule's; a :class:`Taken` message makes a finding
        urdfdom parses all the same, a :class:`Refused` one a finding below an error that is
        urdfdom's refusal all the same. ``not_checked``: the finding says its file's
        robot was not checked (:attr:`~urdftool.diagnostics.Finding.not_checked`).
        ``repeated``: the parts of the message others say word for word
        (:attr:`~urdftool.diagnostics.Finding.repeated`), with those of a
        :class:`~urdftool.errors.Said` message."""
        if severity is None and type(message) is str:  # most findings: as the rule says
            return Finding(self.code, self.name, self.severity, message, location, fix,
                           self.target, not_checked, repeated)
        repeated = tuple(dict.fromkeys(tuple(repeated) + getattr(message, "repeated", ())))
        if severity is not None and _RANK[Severity(severity)] > _RANK[self.severity]:
            raise ValueError(f"{self.code}'s severity is {self.severity.value}; a finding of it "
                             f"cannot be more severe ({Severity(severity).value})")
        if severity is None and isinstance(message, Conditional):
            severity = min(self.severity, message.severity, key=_RANK.__getitem__)
        return Finding(self.code, self.name, Severity(severity or self.severity), str(message),
                       location, fix, self.target, not_checked, repeated,
                       isinstance(message, Taken), isinstance(message, Refused))


def rule(code: str, name: str, severity: Severity):
    """Mark a check: a generator function taking the robot and yielding (where, message).

    The function gets a ``rule`` attribute and is returned unchanged; nothing is registered."""

    def decorate(function):
        function.rule = Rule(code, name, Severity(severity), function, function.__doc__ or "")
        return function

    return decorate


def declare(code: str, name: str, severity: Severity, doc: str) -> Rule:
    """A code that the engine or the runner reports itself (no check function): keep the
    returned value as a module-level constant of a family module."""
    return Rule(code, name, Severity(severity), None, doc or "")


@functools.lru_cache(maxsize=None)
def _cleaned(written: str) -> str:
    return inspect.cleandoc(written)


class Catalogue:
    """Every rule, by code. ``declared`` keeps the order the rules were given in; ``rules`` is
    sorted by code.

    later: functions importing (and returning) the family modules whose rules all run only
    for a target
    (:data:`TARGET_DECADES`), imported, and their rules joined to the others, when first asked
    for: every question but :meth:`running` without a target asks for them (the portability
    family's import was 4.1 M of r2d2's 642 M instructions, for rules a check without a
    target never runs)."""

    def __init__(self, rules, later: tuple = ()):
        self._later = tuple(later)
        self._join(rules)
        self._always = self._rules  # (the rules every check runs: not the later ones, joined)

    def _join(self, rules) -> None:
        self._declared = tuple(rules)
        self._by_code: dict[str, Rule] = {}
        names: dict[str, str] = {}
        for item in self._declared:
            if not _CODE.fullmatch(item.code) or item.code[:2] not in FAMILIES:
                raise ValueError(f"rule code {item.code} is not of the form U<family><nn>")
            if item.code in self._by_code:
                raise ValueError(f"rule code {item.code} declared twice")
            if item.name in names:
                raise ValueError(f"rule name {item.name} declared twice "
                                 f"({names[item.name]} and {item.code})")
            self._by_code[item.code] = item
            names[item.name] = item.code
        self._rules = tuple(self._by_code[code] for code in sorted(self._by_code))

    def _whole(self) -> Catalogue:
        """This catalogue with the rules of its ``later`` modules joined (imported once)."""
        if self._later:
            modules = [imported() for imported in self._later]
            self._later = ()
            self._join((*self._declared, *Catalogue.from_modules(modules)._declared))
        return self

    @property
    def declared(self) -> tuple[Rule, ...]:
        return self._whole()._declared

    @property
    def rules(self) -> tuple[Rule, ...]:
        return self._whole()._rules

    def running(self, targets: bool) -> tuple[Rule, ...]:
        """The rules a check may run, sorted by code: with no ``targets`` asked for, none of
        the ``later`` families' (their rules run only for a target), which stay unimported,
        nor, once they were imported, asked (each robot asked each of them and was refused)."""
        return self.rules if targets else self._always

    @classmethod
    def from_modules(cls, modules, later: tuple = ()) -> Catalogue:
        """The rules of ``modules``, each module's in source order: its ``rule()``-marked
        functions and its module-level ``Rule`` constants, counting only functions defined in
        that module and each constant once. A module whose codes are not ascending, or that
        declares a code below the previous module's, is refused. ``later``: functions
        importing the modules read so when first asked for (:class:`Catalogue`)."""
        found: list[Rule] = []
        seen: set[int] = set()
        for module in modules:
            codes, name = [], module.__name__
            for value in vars(module).values():
                if isinstance(value, Rule):
                    item = value
                elif callable(value) and getattr(value, "__module__", None) == name and \
                        isinstance(getattr(value, "rule", None), Rule):  # (imported: not asked)
                    item = value.rule
                else:
                    continue
                if id(item) in seen:
                    continue
                seen.add(id(item))
                found.append(item)
                codes.append(item.code)
            if codes != sorted(codes):
                raise ValueError(f"{module.__name__}: rule codes out of order: {', '.join(codes)}")
        return cls(found, later)

    def __iter__(self):
        return iter(self.rules)

    def __len__(self) -> int:
        return len(self.rules)

    def __contains__(self, code: str) -> bool:
        return code in self._by_code or code in self._whole()._by_code

    def get(self, code: str) -> Rule:
        """The rule of an exact code (KeyError when there is none)."""
        found = self._by_code.get(code)
        return found if found is not None else self._whole()._by_code[code]

    def matches(self, code: str, selector: str) -> bool:
        """Whether a selector (a code, a code prefix such as ``U2``, or a rule name) picks
        ``code``."""
        selector = selector.strip()
        found = self._by_code.get(code)
        if found is None and self._later:
            found = self._whole()._by_code.get(code)
        return code.startswith(selector.upper()) or (found is not None and found.name == selector)

    def check_selector(self, selector: str) -> None:
        """:class:`UnknownRule` unless ``selector`` (a code, a code prefix or a rule name, as
        ``--select`` and ``--ignore`` take them) picks at least one rule: a misspelt selector
        would otherwise select nothing, or ignore nothing, without a word. The ``later``
        families are imported only for a selector that picks none of the others (``--ignore
        U103`` imported the portability family, and each robot then asked its rules: 14 M
        instructions of a check of the corpus)."""
        wanted = selector.strip()
        if any(self.matches(item.code, wanted) for item in self._always) or \
                any(self.matches(item.code, wanted) for item in self.rules):
            return
        self.find(wanted)  # raises, with the close names

    def find(self, wanted: str) -> Rule:
        """A rule by code (any case) or name; :class:`UnknownRule` listing the close ones
        otherwise (a word without a character but blanks too: every code starts with it, and
        ``urdftool rules ''`` answered with all of them as "the rules starting with  are")."""
        rules = self.rules
        if not wanted.strip():
            raise UnknownRule(f"no rule '{wanted}': give a code (U204) or a name "
                              f"(inverted-limits); `urdftool rules` lists all {len(rules)} rules")
        for candidate in rules:
            if wanted.upper() == candidate.code or wanted == candidate.name:
                return candidate
        prefixed = [r for r in rules if r.code.startswith(wanted.upper())]
        if prefixed:  # a family or part of one: U6, U60
            listed = ", ".join(f"{r.code} {r.name}" for r in prefixed)
            raise UnknownRule(
                f"no rule '{wanted}'; the rules starting with {wanted.upper()} are: {listed}")
        from urdftool.errors import close_names  # only for a name that is no rule's

        by_word = {r.code: r for r in rules} | {r.name: r for r in rules}
        close = dict.fromkeys(by_word[word] for word in
                              close_names(wanted, list(by_word), n=3, cutoff=0.6))
        hint = ("; did you mean " + " or ".join(f"{r.code} {r.name}" for r in close) + "?"
                if close else ".")
        raise UnknownRule(f"no rule '{wanted}'{hint} `urdftool rules` lists all {len(rules)} rules")
