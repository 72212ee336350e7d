"""SRDF ``<disable_collisions>``: read them with their lines, write them as MoveIt does, and say
which entries a fresh matrix shows to be stale."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from lxml import etree

from urdftool.numbers import number
from urdftool.diagnostics import Location
from urdftool.description.documents import SRDF_READ_AS, read_srdf
from urdftool.description.files import kind_of, read_regular
from urdftool.description.urdf import is_xacro
from urdftool.description.xml import attribute
from urdftool.errors import SrdfError, available
from urdftool.collision.matrix import Matrix
from urdftool.collision.pairs import TOUCHING  # [m]: overlapping less than this touches
from urdftool.kinematics.tree import pair_key

AUTOMATIC = ("Adjacent", "Default", "Always", "Never")


@dataclass
class Disabled:
    """A pair of links whose collisions the SRDF disables, why, and where it says so."""

    link1: str
    link2: str
    reason: str
    location: Location


@dataclass
class Stale:
    """An SRDF entry (or a missing one) the matrix disagrees with."""

    location: Location
    message: str


def _document(path: Path):
    """The SRDF as ``check`` reads it (:func:`urdftool.description.documents.read_srdf`: each
    element's ``sourceline`` is its start tag); SrdfError saying where when it cannot be used."""
    document = read_srdf(path)
    if document.problem:
        where = f"{document.display}:{document.line}" if document.line else document.display
        raise SrdfError(f"{where}: {document.problem}", location=document.at(document.line))
    return document


def read(path: Path) -> tuple[list[Disabled], Location]:
    """The disable_collisions entries and where ``<robot>`` starts."""
    document = _document(path)
    entries = [Disabled(el.get("link1", ""), el.get("link2", ""), el.get("reason", ""),
                        document.at(el.sourceline))
               for el in document.root.iter("disable_collisions")]
    return entries, document.at(document.root.sourceline)


def allowed_pairs(entries: list[Disabled]) -> dict[tuple[str, str], str]:
    return {pair_key(e.link1, e.link2): e.reason or "disabled" for e in entries}


def entries_of(matrix: Matrix) -> list[tuple[str, str, str]]:
    """Disabled pairs sorted as MoveIt's SRDF writer sorts them: by (link1, link2)."""
    return [(p.link1, p.link2, p.reason) for p in matrix.pairs if p.disabled]


REWRITES = frozenset({SRDF_READ_AS})  # what an SRDF's update may replace: a file read so only


def check_update(path: Path) -> None:
    """Raise, before the matrix is computed, what writing the update at ``path`` would: an
    existing file that is not an SRDF (:func:`_to_update`), or a file the command read as
    anything but an SRDF (an include of the robot: :func:`~urdftool.description.files.
    check_write`)."""
    from urdftool.description.files import check_write

    if kind_of(path, follow=False) == "file":
        _to_update(path)
    check_write(path, REWRITES)


def _to_update(existing: Path):
    """The SRDF at ``existing`` (:func:`_document`), refused when its root holds a ``<link>``,
    a ``<joint>`` or a xacro element (a robot description, which a merge would rewrite), or
    when srdfdom reads it otherwise than XML does (a caution: ``--`` in a comment, an entity
    used), which a merge would write as srdfdom reads it."""
    document = _document(existing)
    if document.caution:  # (its tree is srdfdom's reading, not the file's: written back, the
        # comments' hyphens would be blanks and the entities their characters; expat, which
        # finds the root's bytes, refuses it)
        raise SrdfError(f"{document.display}:{document.line}: not updated: {document.caution}",
                        location=document.at(document.line))
    described = next((child for child in document.root if child.tag in ("link", "joint")
                       or is_xacro(child.tag)), None)
    if described is not None:  # merged into, a robot description lost its formatting
        tag = etree.QName(described).localname
        tag = f"{described.prefix}:{tag}" if described.prefix else tag
        raise SrdfError(f"{document.display}:{described.sourceline}: <{tag}> is not "
                        "an SRDF element: this is a robot description, not an SRDF; give the "
                        "SRDF's file name", location=document.at(described.sourceline))
    return document


def render(matrix: Matrix, robot_name: str, existing: Path | None = None) -> str:
    """SRDF text: a new document, or ``existing`` with its disable_collisions replaced (entries
    with other reasons, such as 'User', are kept) and everything else untouched."""
    new = entries_of(matrix)
    if existing is None:
        lines = ['<?xml version="1.0" ?>', f'<robot name="{attribute(robot_name)}">']
        lines += [f'    <disable_collisions link1="{attribute(a)}" link2="{attribute(b)}" '
                  f'reason="{r}" />' for a, b, r in new]
        return "\n".join([*lines, "</robot>", ""])
    root = _to_update(existing).root
    old = list(root.iter("disable_collisions"))
    computed = {(a, b) for a, b, _ in new}
    kept = [(*pair_key(e.get("link1", ""), e.get("link2", "")), e.get("reason", ""))
            for e in old if e.get("reason") not in AUTOMATIC
            and pair_key(e.get("link1", ""), e.get("link2", "")) not in computed]
    merged = sorted([*new, *kept], key=lambda e: (e[0].encode(), e[1].encode()))
    indent = _indent(root)
    if old:
        parent, index = old[0].getparent(), old[0].getparent().index(old[0])
        last_tail = old[-1].tail if old[-1].tail and not old[-1].tail.strip() else indent
        for element in old:
            _remove(element)
    else:
        parent, index, last_tail = root, len(root), "\n"
        if len(root):
            root[-1].tail = indent
        else:
            root.text = indent
    for offset, (a, b, reason) in enumerate(merged):
        element = etree.Element("disable_collisions", link1=a, link2=b, reason=reason)
        element.tail = indent if offset < len(merged) - 1 else last_tail
        parent.insert(index + offset, element)
    data = read_regular(existing, as_=SRDF_READ_AS)
    start, end = _root_span(data)
    return (data[:start].decode("utf-8", "replace")
            + etree.tostring(root, encoding="unicode", with_tail=False)
            + data[end:].decode("utf-8", "replace"))


def updated(matrix: Matrix, robot_name: str, path: Path) -> str:
    """The SRDF text to write at ``path``: merged into what is there when it is a regular file
    (see render), else a new document; a link planted at ``path`` is not read."""
    existing = path if kind_of(path, follow=False) == "file" else None
    return render(matrix, robot_name, existing)


def _root_span(data: bytes) -> tuple[int, int]:
    """Byte offsets where the root element starts and just after it ends, so that the prolog
    (declaration, comments) and whatever follows are kept byte for byte."""
    from xml.parsers import expat

    parser = expat.ParserCreate()
    span, depth = [0, len(data)], [0]

    def on_start(name, attributes):
        if depth[0] == 0:
            span[0] = parser.CurrentByteIndex
        depth[0] += 1

    def on_end(name):
        depth[0] -= 1
        if depth[0] == 0:
            span[1] = data.index(b">", parser.CurrentByteIndex) + 1

    parser.StartElementHandler, parser.EndElementHandler = on_start, on_end
    parser.Parse(data, True)
    return span[0], span[1]


def _indent(root) -> str:
    """The whitespace that starts a line of ``<robot>``'s children, without blank lines."""
    space = root.text if root.text and not root.text.strip() else "\n    "
    return "\n" + space.rsplit("\n", 1)[-1]


def _remove(element) -> None:
    """Remove an element, keeping the whitespace and comments around it in place."""
    parent, previous = element.getparent(), element.getprevious()
    if element.tail and element.tail.strip():
        if previous is not None:
            previous.tail = (previous.tail or "") + element.tail
        else:
            parent.text = (parent.text or "") + element.tail
    parent.remove(element)


def stale(matrix: Matrix, entries: list[Disabled], robot_links, root: Location) -> list[Stale]:
    """Entries naming links that do not exist, Never pairs that collided, and pairs the matrix
    disables as Adjacent, Default or Always that the SRDF leaves enabled."""
    problems = []
    disabled = set()
    for entry in entries:
        missing = [name for name in (entry.link1, entry.link2) if name not in robot_links]
        for name in missing:
            problems.append(Stale(entry.location, f"disable_collisions names link '{name}', "
                                  "which does not exist; " + available("links", name,
                                                                       robot_links)))
        if missing:
            continue
        pair = pair_key(entry.link1, entry.link2)
        disabled.add(pair)
        found = matrix.pair(*pair)
        if entry.reason == "Never" and found is not None and found.collisions:
            problems.append(Stale(entry.location, f"{pair[0]} and {pair[1]} are disabled as "
                                  f"Never but collided in {found.collisions} of "
                                  f"{found.samples} samples; remove the entry"))
    for pair in matrix.pairs:
        if pair.reason in ("Adjacent", "Default", "Always") and \
                (pair.link1, pair.link2) not in disabled:
            what = {"Adjacent": "are adjacent", "Default": "collide in the default pose",
                    "Always": f"collide in {number(100 * pair.fraction, places=0)}% of samples"
                    }[pair.reason]
            problems.append(Stale(root, f"{pair.link1} and {pair.link2} {what} but are not "
                                  f"disabled; add <disable_collisions link1=\"{pair.link1}\" "
                                  f"link2=\"{pair.link2}\" reason=\"{pair.reason}\"/>"))
    return problems


# --- the SRDF's poses checked once each ---------------------------------------------------------

# Reasons under which a disabled pair may touch: joined by a joint, in contact in the default
# pose, in contact nearly always. Any other reason ("Never", "User", none) claims it does not.
MAY_TOUCH = ("Adjacent", "Default", "Always")


@dataclass
class Overlap:
    """Two links in contact at some of the SRDF's poses: the deepest ``depth`` [m] and the poses
    as (label, group_state element or None for the default configuration). ``depth`` is None
    where non-convex meshes are in contact, whose depth is not known; ``depth_at_most`` is then
    their convex hulls' (and None when not even that is known: a flat mesh)."""

    link1: str
    link2: str
    depth: float | None = 0.0
    depth_at_most: float | None = 0.0
    poses: list = field(default_factory=list)
    adjacent: bool = False  # joined by a joint (MoveIt's "Adjacent"): contact is expected there


def named_poses(scene, srdf_root) -> list[tuple[str, object, object]]:
    """(label, configuration, element): the default configuration (0, or mid-range where 0 is
    outside the limits; element None), then each ``<group_state>`` over it. Values the scene
    cannot take (multi-variable joints such as a floating root, unknown names, text) are left
    out; a state with none left is skipped."""
    from urdftool.errors import UrdftoolError
    from urdftool.kinematics import configuration

    poses = [("the default configuration", scene.default(), None)]
    names = {variable.name for variable in scene.variables}
    for state in srdf_root.iterfind("group_state"):
        values = {j.get("name"): j.get("value", "") for j in state.iterfind("joint")
                  if j.get("name") in names and len(j.get("value", "").split()) == 1}
        if not values:
            continue
        try:
            chosen = configuration.from_words(scene.variables, values, False, scene.kinematics.mimics)
        except UrdftoolError:
            continue
        poses.append((f"group state '{state.get('name')}' of '{state.get('group')}'",
                      chosen.values[0], state))
    return poses


def overlaps(robot, srdf_root) -> dict[tuple[str, str], Overlap]:
    """Pairs of links that overlap by more than :data:`TOUCHING` at the default configuration
    or at a group state of the SRDF (adjacent ones marked so): one FCL check of every pair per
    pose, as in :func:`urdftool.collision.matrix.default_collisions`, the depth of a mesh's
    contact from the convex hulls (:meth:`~urdftool.collision.pairs.PairChecker.exact`).
    Surfaces that only touch (a lift on its base, meshes exported to share a face, non-convex
    meshes whose hulls overlap by no more) are not reported."""
    from urdftool.collision.matrix import Scene, default_collisions

    scene = Scene(robot, 0.0)
    found: dict[tuple[str, str], Overlap] = {}
    index = {pair: i for i, pair in enumerate(scene.pairs)}
    for label, q, element in named_poses(scene, srdf_root):
        parts = None
        for pair in sorted(default_collisions(scene, q)):
            if parts is None:  # every part placed once for the pairs at this pose (as pose.py)
                scene.checker.place(parts := scene.checker.part_poses(scene.at(q)))
            depth, bound = scene.checker.exact(None, index[pair], contacts=True,
                                               part_poses=parts, placed=True,
                                               touching_first=True)[2:]
            overlap = found.setdefault(pair, Overlap(*pair, adjacent=pair in scene.adjacent))
            overlap.depth = None if None in (overlap.depth, depth) else max(overlap.depth, depth)
            overlap.depth_at_most = None if None in (overlap.depth_at_most, bound) else \
                max(overlap.depth_at_most, bound)
            overlap.poses.append((label, element))
    return {pair: overlap for pair, overlap in found.items()
            if overlap.depth_at_most is None or overlap.depth_at_most > TOUCHING}
