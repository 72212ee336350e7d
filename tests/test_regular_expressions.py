"""Every regular expression of urdftool runs in time linear in what it reads.

Session 31 found a dozen module-level patterns over a file's bytes whose backtracking was
quadratic or cubic in them: ``<parameters>\\s*([^<]*?)\\s*</parameters>`` took 24 s of a check
for a 3 KB part file anywhere in the repository holding ``<parameters>``, 3,000 spaces and a
tag; a comment of ``<xacro:arg default="x"`` and 20,000 ``name='a'`` 40 s. Each was one
instance of one class: a lazy or greedy repeat followed by another over the same characters,
or a stretch looked for from every opener to the end of the file when none closes it. The
guard is this test: each pattern is pumped with strings built from its own parse (a witness of
each run of its items repeated, after a witness of what comes before it, before a byte that
fails it) and its cost must grow no faster than the string, as it is called: from every
position (``search``, ``findall``, ``finditer``, ``sub``, ``split``) or from one
(``match``, ``fullmatch``)."""

from __future__ import annotations

import ast
import importlib
import pkgutil
import re
import time
from pathlib import Path
from re import _constants as C
from re import _parser as P

import pytest

import urdftool

pytestmark = pytest.mark.xdist_group("timing")

_ALPHABET = " a0<>'\"=\n-./_:"
_CANDIDATES = _ALPHABET + "bxyzAZ9\t!#$%&()*+,;?@[]^`{|}~"
_SCANS = {"search", "findall", "finditer", "sub", "subn", "split"}
_ANCHORED = {"match", "fullmatch"}


def _in_class(items, code: int) -> bool:
    negate, hit = False, False
    for op, av in items:
        if op is C.NEGATE:
            negate = True
        elif op is C.LITERAL:
            hit = hit or av == code
        elif op is C.RANGE:
            hit = hit or av[0] <= code <= av[1]
        elif op is C.CATEGORY:
            char, name = chr(code), str(av)
            found = (char.isdigit() if "DIGIT" in name else char.isspace() if "SPACE" in name
                     else char.isalnum() or char == "_" if "WORD" in name else False)
            hit = hit or (found != ("NOT" in name))
    return hit != negate


def _witness(items, depth: int = 0) -> str:
    """A short string the items match (best effort: lookarounds and references ignored)."""
    out = []
    for op, av in items:
        if depth > 20:
            break
        if op is C.LITERAL:
            out.append(chr(av))
        elif op is C.NOT_LITERAL:
            out.append("b" if av == ord("a") else "a")
        elif op is C.ANY:
            out.append("a")
        elif op is C.IN:
            out.append(next((c for c in _CANDIDATES if _in_class(av, ord(c))), "a"))
        elif op in (C.MAX_REPEAT, C.MIN_REPEAT, C.POSSESSIVE_REPEAT):
            low, high, body = av
            out.append(_witness(body, depth + 1) * max(low, 1 if high else 0))
        elif op is C.SUBPATTERN:
            out.append(_witness(av[-1], depth + 1))
        elif op is C.ATOMIC_GROUP:
            out.append(_witness(av, depth + 1))
        elif op is C.BRANCH:
            out.append(_witness(av[1][0], depth + 1))
        elif op is C.GROUPREF:
            out.append("'")
    return "".join(out)


def _flat(items) -> list:
    """The items in order, groups opened; a run of literal characters one item (a list)."""
    seq: list = []
    for op, av in items:
        for item in _flat(av[-1]) if op is C.SUBPATTERN else [(op, av)]:
            if item[0] is C.LITERAL and seq and isinstance(seq[-1], list):
                seq[-1].append(item)
            else:
                seq.append([item] if item[0] is C.LITERAL else item)
    return seq


def _items(seq) -> list:
    return [item for unit in seq for item in (unit if isinstance(unit, list) else [unit])]


def _sequences(items):
    """The pattern's sequence of items, and the sequences with each alternative, or a
    repeat's or atomic group's body, written in place of it (``re`` takes an alternation's
    common prefix out of it: ``<!--.*?-->|<\\?.*?\\?>`` is ``<`` before the alternation)."""
    seq = _flat(items)
    yield seq
    for at, unit in enumerate(seq):
        if isinstance(unit, list):
            continue
        op, av = unit
        bodies = (av[1] if op is C.BRANCH else [av[2]] if op in (
            C.MAX_REPEAT, C.MIN_REPEAT, C.POSSESSIVE_REPEAT) else [av] if op is C.ATOMIC_GROUP
            else [])
        for body in bodies:
            for inner in _sequences(body):
                yield seq[:at] + inner + seq[at + 1:]


def _probes(pattern: re.Pattern):
    source = pattern.pattern
    text = source if isinstance(source, str) else source.decode("latin-1")
    parsed = P.parse(text, pattern.flags & ~(re.ASCII if isinstance(source, bytes) else 0))
    seen = set()
    for seq in _sequences(list(parsed)):
        for a in range(len(seq) + 1):
            prefix = _witness(_items(seq[:a]))
            for b in range(a + 1, min(len(seq), a + 8) + 1):
                pump = _witness(_items(seq[a:b]))
                for extra in ("", " ", "a"):
                    for suffix in ("", "\x00", "<"):
                        key = (prefix, pump + extra, suffix)
                        if pump + extra and key not in seen:
                            seen.add(key)
                            yield key
    for char in _ALPHABET:
        yield "", char, ""


def _cost(pattern: re.Pattern, anchored: bool, probe: tuple, times: int) -> float:
    prefix, pump, suffix = probe
    subject = prefix + pump * times + suffix
    if isinstance(pattern.pattern, bytes):
        subject = subject.encode("latin-1", "replace")
    start = time.perf_counter()
    if anchored:
        pattern.match(subject)
    else:
        for _ in pattern.finditer(subject):
            pass
    return time.perf_counter() - start


def superlinear(pattern: re.Pattern, anchored: bool = False, short: int = 2_000,
                floor: float = 0.0003):
    """The first probe whose cost grows faster than its length (4 and 16 times the string:
    each more than 8 times the time), or that costs a quarter of a second at 2,000 characters; None."""
    for probe in _probes(pattern):
        times = max(1, short // len(probe[1]))
        spent = _cost(pattern, anchored, probe, times)
        if spent < floor:
            continue
        spent = min(spent, *(_cost(pattern, anchored, probe, times) for _ in range(2)))
        if spent < floor:
            continue
        if spent > 0.25:
            return probe, times, spent
        longer = min(_cost(pattern, anchored, probe, 4 * times) for _ in range(3))
        if longer > 8 * spent and longer > 4 * floor:  # once more: a pause is not a cost
            longest = min(_cost(pattern, anchored, probe, 16 * times) for _ in range(2))
            if longest > 8 * longer:
                return probe, 16 * times, longest
    return None


def _literal_parts(node) -> list:
    """The pattern a call is given when it is written as literals joined by ``+``, a name
    (``re.escape(name)``) standing for what is not written (``rb"<macro\\s[^<>]*?name=" +
    re.escape(name) + rb"..."``); none when no part is written."""
    if isinstance(node, ast.Constant) and isinstance(node.value, (str, bytes)):
        return [node.value]
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
        left, right = _literal_parts(node.left), _literal_parts(node.right)
        if len(left) == 1 and len(right) == 1 and type(left[0]) is type(right[0]):
            return [left[0] + right[0]]
        if left and not right and not _is_literal(node.right):  # + re.escape(name): a name
            return [left[0] + type(left[0])("name")] if isinstance(left[0], str) else \
                [left[0] + b"name"]
        if right and not left and not _is_literal(node.left):
            return [("name" if isinstance(right[0], str) else b"name") + right[0]]
    return []


def _is_literal(node) -> bool:
    return isinstance(node, ast.Constant) or isinstance(node, ast.BinOp) and \
        _is_literal(node.left) and _is_literal(node.right)


def _patterns() -> dict[str, tuple[re.Pattern, bool]]:
    """Every module-level pattern of urdftool: name -> (pattern, called only anchored)."""
    found: dict[int, tuple[str, re.Pattern]] = {}
    calls: dict[int, set[str]] = {}
    literals: list[tuple] = []
    for info in pkgutil.walk_packages(urdftool.__path__, "urdftool."):
        module = importlib.import_module(info.name)
        names = vars(module)
        for name, value in names.items():
            members = value if isinstance(value, (tuple, list)) else [value]
            for at, member in enumerate(members):
                if isinstance(member, re.Pattern):
                    where = name if member is value else f"{name}[{at}]"
                    found.setdefault(id(member), (f"{info.name}.{where}", member))
        tree = ast.parse(Path(module.__file__).read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and \
                    isinstance(names.get(node.value.id), re.Pattern):
                calls.setdefault(id(names[node.value.id]), set()).add(node.attr)
            # a literal pattern written where it is used (re.search("...", text), a function's
            # own re.compile("..." + name): its literal parts)
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and \
                    isinstance(node.func.value, ast.Name) and node.func.value.id == "re" and \
                    node.func.attr in _SCANS | _ANCHORED | {"compile"} and node.args:
                for part in _literal_parts(node.args[0]):
                    flags = re.S if "DOTALL" in ast.unparse(node) or "re.S" in ast.unparse(node) \
                        else 0
                    literals.append((f"{info.name}:{node.lineno}", part, flags, node.func.attr))
    known = {pattern.pattern for _, pattern in found.values()}
    for name, part, flags, called in literals:
        if part not in known:  # (a module's own pattern, written where it is named)
            pattern = re.compile(part, flags)
            found.setdefault(id(pattern), (name, pattern))
            calls.setdefault(id(pattern), set()).add(called if called != "compile" else "search")
    return {name: (pattern, bool(calls.get(key)) and calls[key] <= _ANCHORED)
            for key, (name, pattern) in found.items()}


_ALL = _patterns()


def test_the_guard_finds_the_patterns_session_31_closed():
    """The pumps find each class the test closes (the patterns as they were)."""
    before = [rb"<parameters>\s*([^<]*?)\s*</parameters>",
              rb"<xacro:arg\s[^<>]*?name\s*=\s*[\"']([^\"'<>]+)[\"'][^<>]*?default\s*=\s*"
              rb"[\"']([^\"'<>]*)[\"']",
              rb"<export\b[^>]*>(.*?)</export>",
              rb"<!--.*?-->|<\?.*?\?>",
              r"<!--\s*urdftool:\s*(ignore-file|ignore)\b(.*?)-->",
              rb"(?<![a-z0-9_#.])[-+]?[0-9]*\.?[0-9]+e\+?0*[1-9][0-9]{2}",
              r"\s*[ |+]*(?:Exception Group )?Traceback \(most recent call last\):",
              rb"(\\+)u(d[89ab][0-9a-f]{2}|fffd)"]
    for source in before:
        assert superlinear(re.compile(source, re.S)) is not None, source
    assert superlinear(re.compile(r"^(\s*)<!--\s*urdftool:\s*ignore\s+(.*?)\s*-->\s*$"),
                       anchored=True) is not None


@pytest.mark.parametrize("name", sorted(_ALL))
def test_every_pattern_is_linear_in_what_it_reads(name):
    pattern, anchored = _ALL[name]
    found = superlinear(pattern, anchored)
    if found is not None:  # measured again: a busy machine's pause is not a pattern's cost
        found = superlinear(pattern, anchored)
    assert found is None, f"{name} ({'match' if anchored else 'search'}): {found!r}"
