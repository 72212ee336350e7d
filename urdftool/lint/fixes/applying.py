"""Applying fixes: byte edits on the files, checked against what is there now.

:func:`plan` gathers the fixes of checked files (safe ones, or all with ``unsafe``), refuses
edits of files outside the checked robot's containment root, edits whose text is no longer
what was read and edits that overlap, and gives the new contents; :func:`write` writes them
atomically through :mod:`urdftool.description.files`; :func:`apply` repeats until nothing
more is fixed.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

from urdftool.description.files import kind_of
from urdftool.diagnostics import Edit, Fix
from urdftool.errors import UsageError, listed
from urdftool.lint.fixes.building import inertial_edits
from urdftool.lint.fixes.tags import Unfixable


@dataclass
class Plan:
    """What applying the fixes would do.

    changed: file (as findings name it) -> (bytes now, bytes after)
    spans: file -> (start, end, length written) of each edit, in the file's order (what a
        diff of the file compares: :func:`urdftool.report.unified.unified`)
    applied: the fixes taken; skipped: (fix, why) of those left out
    """

    changed: dict[str, tuple[bytes, bytes]] = field(default_factory=dict)
    spans: dict[str, list[tuple[int, int, int]]] = field(default_factory=dict)
    applied: list[Fix] = field(default_factory=list)
    skipped: list[tuple[Fix, str]] = field(default_factory=list)


def plan(results, unsafe: bool = False, read=None) -> Plan:
    """The fixes of ``results`` (FileResults) that apply: safe ones, unsafe ones too with
    ``unsafe``. A fix is taken whole or not at all; it is left out when one of its edits is
    outside the checked robot's containment root, when the file no longer holds the text
    the edit replaces, or when it overlaps an edit already taken."""
    from urdftool.description.files import read_regular
    from urdftool.description.packages import containment_root

    candidates, sites = [], {}
    for checked in results:
        if checked is None or checked.path == "-":
            continue
        root = containment_root(os.path.dirname(os.path.abspath(checked.path)))
        for finding in checked.findings:
            if finding.fix is not None and (finding.fix.safe or unsafe):
                candidates.append((finding.fix, root))
                sites[id(finding.fix)] = finding.location.via
    return _take(candidates, read or read_regular, sites)


def _take(candidates, read, sites: dict | None = None) -> Plan:
    """The plan of ``candidates``: (fix, containment root) pairs, in order; ``sites``: id of a
    fix -> the macro call sites of its finding's element (:func:`_disputed`)."""
    from urdftool.description.files import inside

    result = Plan()
    current: dict[str, bytes] = {}
    taken: dict[str, _Taken] = {}
    disputed = _disputed([fix for fix, _ in candidates], sites)
    created: dict[str, bytes] = {}
    skipped: set[int] = set()  # (ids, as the skipped were told apart; the applied by value)
    applied: set[Fix] = set()
    for fix, root in candidates:
        if fix in applied or id(fix) in skipped:
            continue
        why = disputed.get(id(fix)) or _refusal(fix, root, current, taken, read, inside) \
            or _creation_refusal(fix, root, created, inside)
        if why:
            skipped.add(id(fix))
            result.skipped.append((fix, why))
            continue
        for edit in fix.edits:
            taken.setdefault(edit.file, _Taken()).add(edit)
        applied.add(fix)
        result.applied.append(fix)
    for file, edits in taken.items():
        data = current[file]
        # in the file's order; of insertions at one point, the first taken ends up first
        pieces, at, spans = [], 0, []
        for edit in sorted(edits.order, key=lambda e: (e.start, e.end, edits.index[e])):
            written = edit.text.encode("utf-8")
            pieces += (data[at:edit.start], written)
            spans.append((edit.start, edit.end, len(written)))
            at = edit.end
        result.changed[file] = (data, b"".join(pieces) + data[at:])
        result.spans[file] = spans
    for file, data in created.items():
        result.changed[file] = (b"", data)
    return result


def _creation_refusal(fix: Fix, root, created: dict, inside) -> str | None:
    """Why the files ``fix`` creates cannot be made (outside the root, there already, the source
    does not convert); None: they are made, into ``created`` (file -> bytes)."""
    for derived in fix.creates:
        if derived.file in created:
            continue
        if not inside(derived.file, root) or not inside(derived.source, root):
            return f"{derived.file} is outside the repository ({root})"
        if kind_of(derived.file, follow=False):
            return f"{derived.file} exists already"
        from urdftool.description.meshes import converted
        from urdftool.errors import MeshProblem

        try:
            created[derived.file] = converted(derived.source, derived.how)
        except MeshProblem as problem:
            return str(problem)
    return None


def inertia_rewrite(robot, results) -> tuple[Plan, list[tuple[str, str]]]:
    """``urdftool inertia --write``: the edits giving each link of ``results`` (LinkInertia
    with a computed inertial) that inertial, in the files the robot was written in; and (link,
    why) for the links whose inertial cannot be edited (values from expressions)."""
    from urdftool.description.files import read_regular
    from urdftool.description.packages import containment_root

    root = containment_root(robot.base_dir)
    candidates, unfixable = [], []
    for result in results:
        edits = inertial_edits(robot, robot.links[result.link], result.computed)
        if isinstance(edits, Unfixable):
            unfixable.append((result.link, edits.reason))
        else:
            fix = Fix(f"link '{result.link}' inertial from its geometry", tuple(edits), False)
            candidates.append((fix, root))
    changes = _take(candidates, read_regular)
    unfixable.extend((fix.description, why) for fix, why in changes.skipped)
    return changes, unfixable


def _overlap(one: Edit, other: Edit) -> bool:
    """Whether two different edits touch the same text. Insertions at one point do not: they
    are written one after the other."""
    if one == other:
        return False
    if one.start == one.end and other.start == other.end:
        return False
    if one.start == one.end:
        return other.start < one.start < other.end
    if other.start == other.end:
        return one.start < other.start < one.end
    return one.start < other.end and other.start < one.end


def _disputed(candidates: list[Fix], sites: dict | None = None) -> dict[int, str]:
    """Fixes (by id) whose edits overlap a different edit of another fix made for another
    element: a literal in a macro that serves several elements needing different values. None
    of them is taken. ``sites`` (id of a fix -> its element's macro call sites): two fixes of
    one element (the same call sites: U023's spacing and U206's unit axis of one ``xyz``) are
    no dispute; the first is taken, the other waits for the next pass (:func:`_refusal`:
    it overlaps), whose check reads the text the first wrote. Without ``sites`` every overlap
    is one."""
    spans: dict[str, list[tuple[Edit, int]]] = {}
    for fix in candidates:
        for edit in fix.edits:
            spans.setdefault(edit.file, []).append((edit, id(fix)))
    disputed: dict[int, str] = {}
    for edits in spans.values():
        edits.sort(key=lambda pair: (pair[0].start, pair[0].end))
        for index, (edit, owner) in enumerate(edits):
            for later in range(index + 1, len(edits)):  # (no copy of the rest of the list)
                other, second = edits[later]
                if other.start > edit.end:
                    break
                if owner != second and _overlap(edit, other) and (
                        sites is None or sites.get(owner) != sites.get(second)):
                    why = (f"the text at {edit.file}:{edit.line} would need different values "
                           "for different elements (a macro used more than once?)")
                    disputed[owner] = disputed[second] = why
    return disputed


class _Taken:
    """The edits taken in one file: in the order taken, as a set, and by their spans (sorted by
    start and end: taken edits do not overlap, so their ends rise with their starts), so that
    whether an edit is taken or overlaps one costs its neighbours, not every edit taken before
    it (``check --diff`` of 4,000 joints, each with two fixes: 437 s; 1,000: 25 s)."""

    def __init__(self):
        self.order: list[Edit] = []
        self.index: dict[Edit, int] = {}
        self.spans: list[tuple[int, int]] = []
        self.at: list[Edit] = []  # (the edit of each span)

    def __contains__(self, edit: Edit) -> bool:
        return edit in self.index

    def add(self, edit: Edit) -> None:
        if edit not in self.index:
            import bisect

            self.index[edit] = len(self.order)
            self.order.append(edit)
            place = bisect.bisect_right(self.spans, (edit.start, edit.end))
            self.spans.insert(place, (edit.start, edit.end))
            self.at.insert(place, edit)

    def overlapped(self, edit: Edit) -> bool:
        """Whether ``edit`` overlaps an edit taken (:func:`_overlap` of each that may)."""
        import bisect

        place = bisect.bisect_left(self.spans, (edit.start, -1))
        if place and _overlap(edit, self.at[place - 1]):  # (the latest end before it)
            return True
        for other, (start, _) in zip(self.at[place:], self.spans[place:]):
            if start > edit.end:
                return False
            if _overlap(edit, other):
                return True
        return False


def _refusal(fix: Fix, root, current, taken, read, inside) -> str | None:
    """Why the edits of ``fix`` cannot be taken; None: take it. A fix whose edits are all
    taken already (another finding's fix making the same edits under another description: a
    macro's literal serving two elements) is taken too: its finding is fixed, and the files it
    creates are made (:func:`_creation_refusal`)."""
    if all(edit in taken.get(edit.file, ()) for edit in fix.edits):
        return None  # (each was read and compared when first taken)
    for edit in fix.edits:
        if not inside(edit.file, root):
            return f"{edit.file} is outside the repository ({root})"
        if edit.file not in current:
            try:
                current[edit.file] = read(edit.file)
            except OSError as error:
                return f"{edit.file} cannot be read: {error.strerror}"
        data = current[edit.file]
        if data[edit.start:edit.end].decode("utf-8", errors="replace") != edit.old:
            return f"{edit.file} changed since it was checked"
        if edit.file in taken and taken[edit.file].overlapped(edit):
            return f"it overlaps another fix in {edit.file}"
    return None


MAX_PASSES = 10  # a fix can make another finding (an unused suppression) and its fix appear


def apply(results, recheck, unsafe: bool = False):
    """Apply fixes and check again until nothing more is fixed (at most MAX_PASSES times).

    recheck: ``() -> results`` checks the same targets again
    Returns (the results of the last check, fixes applied, files changed, skipped fixes).
    """
    applied, changed, skipped = 0, set(), []
    for _ in range(MAX_PASSES):
        changes = plan(results, unsafe=unsafe)
        skipped = changes.skipped
        if not changes.changed:
            break
        write(changes, changed)
        applied += len(changes.applied)
        changed.update(changes.changed)
        results = recheck()
    return results, applied, changed, skipped


def write(changes: Plan, written: set | frozenset = frozenset()) -> None:
    """Write the changed files, each atomically (a temporary file replaces it). When one
    cannot be written (a full disk, a read-only folder), the UsageError says which files were
    written before it (``written``: by earlier passes; then this one's), whose fixes stand,
    and that the rest were not: a run fixing two files said only "cannot write 'b.urdf'", and
    'a.urdf' was changed without a word."""
    from urdftool.description.files import write_file

    done = list(dict.fromkeys(written))
    files = list(changes.changed.items())
    for index, (file, (_, after)) in enumerate(files):
        try:
            write_file(file, after, rewrites=True)  # the fixes: meant
        except UsageError as error:
            if not done:
                raise
            left = len(files) - index - 1
            raise UsageError(f"{error}; fixed before it: {listed(done)}"
                             f"{f'; {left} other file(s) not written' if left else ''}") \
                from None
        if file not in done:
            done.append(file)
