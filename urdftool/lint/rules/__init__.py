"""The rule catalogue.

A rule is one function that yields ``(where, message)``: ``where`` is an lxml element of the
robot, a :class:`~urdftool.diagnostics.Location` in another file, or None for the file as a whole.
The engine, not the rule, stamps the code, name, severity and location. The rule's docstring is
its documentation: a first-line summary, then why it matters, then examples (the README table and
``urdftool rules CODE`` are generated from it).

Families: U0xx loading, U1xx kinematic tree, U2xx joints, U3xx inertials, U4xx geometry and
meshes, U5xx transmissions and ros2_control, U6xx controllers and Gazebo, U7xx joint spec table,
U8xx SRDF and collisions, U9xx urdftool itself.
"""

from __future__ import annotations

import difflib
import importlib
import inspect
import pkgutil
from dataclasses import dataclass
from typing import Callable

from urdftool.diagnostics import Finding, Location, Severity

__all__ = ["Rule", "REGISTRY", "Severity", "rule", "declare", "all_rules", "find_rule",
           "registered", "matches", "FAMILIES"]

FAMILIES = {
    "U0": "loading",
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


@dataclass(frozen=True)
class Rule:
    code: str
    name: str
    severity: Severity
    check: Callable | None
    doc: str

    @property
    def summary(self) -> str:
        return self.doc.strip().splitlines()[0].strip() if self.doc.strip() else self.name

    @property
    def family(self) -> str:
        return FAMILIES[self.code[:2]]

    def finding(self, message: str, location: Location) -> Finding:
        """A finding of this rule at ``location``."""
        return Finding(self.code, self.name, self.severity, message, location)


REGISTRY: dict[str, Rule] = {}


def _register(code: str, name: str, severity: Severity, check, doc: str | None) -> Rule:
    if code in REGISTRY:
        raise ValueError(f"rule code {code} registered twice")
    if code[:2] not in FAMILIES or len(code) != 4 or not code[1:].isdigit():
        raise ValueError(f"rule code {code} is not of the form U<family><nn>")
    registered = Rule(code, name, Severity(severity), check, inspect.cleandoc(doc or ""))
    REGISTRY[code] = registered
    return registered


def rule(code: str, name: str, severity: Severity):
    """Register a check: a generator function taking the robot and yielding (where, message)."""

    def decorate(function):
        _register(code, name, severity, function, function.__doc__)
        return function

    return decorate


def declare(code: str, name: str, severity: Severity, doc: str) -> None:
    """Register a code that the loader or a command reports itself (no check function)."""
    _register(code, name, severity, None, doc)


def rule_modules() -> list[str]:
    """Every public module of this package: each holds one family's rules."""
    return sorted(m.name for m in pkgutil.iter_modules(__path__) if not m.name.startswith("_"))


_loaded = False


def all_rules() -> list[Rule]:
    """Every registered rule, sorted by code."""
    global _loaded
    if not _loaded:
        for module in rule_modules():
            importlib.import_module(f"{__name__}.{module}")
        importlib.import_module("urdftool.lint.engine")  # declares U900
        _loaded = True
    return [REGISTRY[code] for code in sorted(REGISTRY)]


def registered(code: str) -> Rule:
    """The rule of an exact code, the catalogue loaded first when the code is not yet known
    (codes the loader, the engine and the workers report themselves)."""
    if code not in REGISTRY:
        all_rules()
    return REGISTRY[code]


def matches(code: str, selector: str) -> bool:
    """Whether a selector (a code, a code prefix such as ``U2``, or a rule name) picks ``code``."""
    selector = selector.strip()
    rule = REGISTRY.get(code)
    return code.startswith(selector.upper()) or (rule is not None and rule.name == selector)


def find_rule(wanted: str) -> Rule:
    """A rule by code (any case) or name; a UsageError listing the valid ones otherwise."""
    from urdftool.errors import UsageError

    rules = all_rules()
    for candidate in rules:
        if wanted.upper() == candidate.code or wanted == candidate.name:
            return candidate
    prefixed = [r for r in rules if r.code.startswith(wanted.upper())]
    if prefixed:  # a family or part of one: U6, U60
        listed = ", ".join(f"{r.code} {r.name}" for r in prefixed)
        raise UsageError(f"no rule '{wanted}'; the rules starting with {wanted.upper()} are: {listed}")
    by_word = {r.code: r for r in rules} | {r.name: r for r in rules}
    close = dict.fromkeys(by_word[word] for word in
                          difflib.get_close_matches(wanted, list(by_word), n=3, cutoff=0.6))
    hint = ("; did you mean " + " or ".join(f"{r.code} {r.name}" for r in close) + "?") if close else "."
    raise UsageError(f"no rule '{wanted}'{hint} `urdftool rules` lists all {len(rules)} rules")
