"""The loaded robot: the URDF element tree, where each element was written, and accessors."""

from __future__ import annotations

import os
from functools import cached_property
from pathlib import Path

from urdftool.diagnostics import Location, Severity
from urdftool.description.inputs import CompanionPaths, MeshLimits
from urdftool.description.packages import PackageResolver
from urdftool.description.xml import child_list
from urdftool.records import Frozen, NEW, Record

TYPE_CHECKING = False  # (typing.TYPE_CHECKING: typing is not imported by a check)
if TYPE_CHECKING:  # the annotations' names, never evaluated
    from collections.abc import Callable, Mapping
    from typing import TypeVar

    T = TypeVar("T")

_UNSET = object()  # (what Robot.memo has not computed)


class LoadNote(Frozen):
    """Something the loader noticed that did not stop it.

    kind: 'xacro-in-urdf' (a file not named .xacro that needs xacro; ``cause`` is the
        :class:`~urdftool.errors.LoadError` when xacro could not expand it), 'xacro-warning'
        (xacro printed a warning), 'outside-file' (xacro read a file outside the repository)
        'late-declaration' (white space before a URDF's XML declaration, which urdfdom
        reads and standard XML parsers refuse), 'double-hyphen' (``--`` inside a
        comment, likewise) or 'root-namespace' (a ``<robot>`` in a default
        XML namespace, which urdfdom reads by its elements' names as written)
    severity: lower than the rule's when what it notices holds only in some configurations
    """

    kind: str
    location: Location
    message: str
    cause: Exception | None
    severity: Severity | None

    __slots__ = ("kind", "location", "message", "cause", "severity")

    def __init__(self, kind: str, location: Location, message: str, cause: Exception | None = None,
                 severity: Severity | None = None) -> None:
        set_field = object.__setattr__
        set_field(self, "kind", kind)
        set_field(self, "location", location)
        set_field(self, "message", message)
        set_field(self, "cause", cause)
        set_field(self, "severity", severity)


class Robot(Record):
    """A robot description ready for rules and analysis.

    path: the file the user named (``-`` for stdin)
    root: the ``<robot>`` element of the URDF (after xacro expansion)
    locations: where each element was written; see :meth:`locate`
    files: every file read to build it (the input first, then includes)
    from_xacro: whether the input went through xacro
    notes: what the loader noticed that did not stop it, in the order it noticed
    sources: the bytes of every file read to build it, as loaded (the input's ``data`` when
        given), by the name findings give it: suppressions are read from these, not from disk
    companion_paths: companion files the user named (the rest are discovered)
    mesh_limits: how large a mesh may be loaded
    xacro_args: the xacro arguments it was checked with (the rest took their defaults)
    targets: the simulators the robot is checked for (``check --target``): name -> the version
        whose behaviour to predict (a tuple of numbers), or None for the newest known
    rebuild: ``rebuild(args)`` loads the same file again as it was loaded (its packages,
        environment and limits) with these xacro arguments given too (raises LoadError); None
        where the checking engine did not load it
    """

    path: str
    display: str
    root: object  # the lxml <robot> element
    locations: Mapping  # element -> Location (a dict, or made when asked)
    resolver: PackageResolver
    files: list[str]
    from_xacro: bool
    notes: list[LoadNote]
    sources: dict[str, bytes]
    companion_paths: CompanionPaths
    mesh_limits: MeshLimits
    xacro_args: Mapping
    targets: dict
    rebuild: Callable | None
    _memo: dict
    _groups: dict

    __slots__ = ("path", "display", "root", "locations", "resolver", "files", "from_xacro",
                 "notes", "sources", "companion_paths", "mesh_limits", "xacro_args", "targets",
                 "rebuild", "_memo", "_groups")
    _compared = ("path", "display", "root", "locations", "resolver", "files", "from_xacro",
                 "notes", "sources", "companion_paths", "mesh_limits", "xacro_args", "targets")
    _shown = ("path", "display", "root", "locations", "resolver", "files", "from_xacro", "notes",
              "sources", "companion_paths", "mesh_limits", "xacro_args", "targets")
    _made = ("_memo", "_groups")

    def __init__(self, path: str, display: str, root: object, locations: Mapping,
                 resolver: PackageResolver, files: list[str] = NEW, from_xacro: bool = False,
                 notes: list[LoadNote] = NEW, sources: dict[str, bytes] = NEW,
                 companion_paths: CompanionPaths = NEW, mesh_limits: MeshLimits = NEW,
                 xacro_args: Mapping = NEW, targets: dict = NEW,
                 rebuild: Callable | None = None) -> None:
        self.path = path
        self.display = display
        self.root = root
        self.locations = locations
        self.resolver = resolver
        self.files = [] if files is NEW else files
        self.from_xacro = from_xacro
        self.notes = [] if notes is NEW else notes
        self.sources = {} if sources is NEW else sources
        self.companion_paths = CompanionPaths() if companion_paths is NEW else companion_paths
        self.mesh_limits = MeshLimits() if mesh_limits is NEW else mesh_limits
        self.xacro_args = {} if xacro_args is NEW else xacro_args
        self.targets = {} if targets is NEW else targets
        self.rebuild = rebuild
        self._memo = {}
        self._groups = {}

    def memo(self, key, compute: Callable[[], T]) -> T:
        """``compute()`` once per robot for ``key`` (by convention the function that asks), then
        the same value: what several rules derive from a robot (its companions, mesh outcomes,
        link solids) is built once. Looked up once when known (35,000 asks on the corpus, each
        key hashed twice, a mesh's with its limits' hash in Python)."""
        found = self._memo.get(key, _UNSET)
        if found is _UNSET:
            found = self._memo[key] = compute()
        return found

    def memoized(self, key) -> bool:
        """Whether :meth:`memo` has computed ``key`` (a result cache lists what it was built
        from only when it was)."""
        return key in self._memo

    def memo_for(self, kind, key, compute: Callable[[], T]) -> T:
        """``compute()`` once per robot, ``kind`` and ``key`` (a link, say), then the same
        value, as :meth:`memo` keyed by ``(kind, key)`` but with one dict per kind: no key
        tuple is made for each of a 10,000-link robot's links. ``compute`` may not return None."""
        known = self._memo.get(kind)
        if known is None:
            known = self._memo[kind] = {}
        found = known.get(key)
        if found is None:
            found = known[key] = compute()
        return found

    def locate(self, element) -> Location:
        """Where ``element`` was written; the file itself when it has no element."""
        if element is None:
            return Location(self.display, None)
        while element is not None:
            location = self.locations.get(element)
            if location is not None:
                return location
            element = element.getparent()
        return Location(self.display, None)

    def locate_all(self, places: list) -> list[Location]:
        """:meth:`locate` of each of ``places`` (elements, None), a :class:`Location` among them
        kept as it is: the findings of one rule are located together, in one call to the
        locations where the loader scanned the file (10,000 findings on a large robot)."""
        bulk = getattr(self.locations, "get_all", None)
        if bulk is None:
            return [place if isinstance(place, Location) else self.locate(place)
                    for place in places]
        elements = [place for place in places if place is not None and not
                    isinstance(place, Location)]
        found = iter(bulk(elements))
        located = []
        for place in places:
            if place is None or isinstance(place, Location):
                located.append(place if place is not None else Location(self.display, None))
                continue
            location = next(found)
            located.append(location if location is not None else self.locate(place))
        return located

    @property
    def base_dir(self) -> Path:
        """The folder holding the file as named (a link is not followed, so that companions and
        relative paths are looked for where the link is, never where it leads); made once per
        robot (every mesh and package question asks: 160 times on the corpus)."""
        if self.path == "-":
            return Path.cwd()
        return self.memo(Robot.base_dir, lambda: Path(os.path.abspath(self.path)).parent)

    @property
    def name(self) -> str:
        return self.root.get("name", "")

    def children(self, tag: str) -> list:
        """Direct children of ``<robot>`` with this tag, in document order (a new list: the
        children are grouped by tag once per robot, as every rule asks)."""
        return list(self.grouped(self.root).get(tag, ()))

    def grouped(self, element) -> dict[str, list]:
        """The element children of ``element`` (one of this robot's) by tag, each list in
        document order; grouped once per robot and element. Rules ask each joint for its
        limit, axis, origin, parent and child about fifteen times: one pass over its children
        replaces as many walks of lxml siblings, which add up on a robot of thousands of joints.
        The dict is shared: read it, never change it."""
        groups = self._groups.get(element)
        if groups is None:
            groups = self._groups[element] = _by_tag(child_list(element))
        return groups

    def listed(self) -> dict:
        """Where a walk that lists the children of the robot's elements anyway (the vocabulary
        rules') leaves the groups of each element it lists (element -> what :meth:`grouped`
        gives, made as :func:`_by_tag` makes it, from :func:`~urdftool.description.xml.
        child_list` of it as it was when loaded), built as it meets each child: :meth:`grouped`
        then finds them, rather than listing the children again (a proxy object looked up for
        each) and reading their tags again. A walk leaves alone an element grouped already."""
        return self._groups

    def shapes(self, elements: list) -> list | None:
        """For ``elements``, siblings in document order: the markup of each but the last as
        written (from its start tag to the next one's), every attribute value left out, as
        bytes; None where the loader did not scan the file (xacro's output, a document not
        plain enough: :meth:`~urdftool.description.xml._StartOffsets.shapes`). Two elements of
        one shape have the same tags, attribute names and nesting."""
        shapes = getattr(self.locations, "shapes", None)
        return shapes(elements) if shapes is not None else None

    def child(self, element, tag: str):
        """The first direct child of ``element`` with this tag, or None
        (:func:`~urdftool.description.xml.first_child`, remembered: see :meth:`grouped`)."""
        found = self.grouped(element).get(tag)
        return found[0] if found else None

    def ends(self) -> dict:
        """Joint -> {"parent": (element, link it names), "child": (element, link)}, in document
        order; read once per robot (the tree rules, the inertial rules and the rigid bodies of
        the solids all ask). A missing ``<parent>`` or ``<child>`` is (None, None)."""
        return self.memo(Robot.ends, self._read_ends)

    def _read_ends(self) -> dict:
        found, named = {}, set()
        for joint in self.children("joint"):  # (a loop, not comprehensions: 10,000 joints)
            groups = self.grouped(joint)
            parents, children = groups.get("parent"), groups.get("child")
            parent, child = parents[0] if parents else None, children[0] if children else None
            link = child.get("link") if child is not None else None
            found[joint] = {"parent": (parent, parent.get("link") if parent is not None else None),
                            "child": (child, link)}
            if children:
                named.add(link)
                for other in children[1:]:  # (one <child> in all but broken joints)
                    named.add(other.get("link"))
        self._memo[Robot.hanging] = named
        return found

    def hanging(self) -> set:
        """The link (or None) named by every ``<child>`` of every joint, the first of a joint
        and any after it: the links that hang from a joint; read with :meth:`ends`."""
        self.ends()
        return self._memo[Robot.hanging]

    def names(self) -> dict:
        """Element -> its ``name`` attribute (None without one) of every link and joint (the
        ``<robot>``'s children), read once per robot: the rules of several families look
        each link up by name and name it in their messages, 10,000 times on a large robot."""
        return self.memo(Robot.names, self._read_names)

    def kinds(self) -> dict:
        """Joint element -> its ``type`` attribute (None without one) of every joint, read
        once per robot with :meth:`names`: the joint, inertia and solid rules, the tree of
        fixed bodies and the wheels each ask every joint."""
        self.names()
        return self._memo[Robot.kinds]

    def _read_names(self) -> dict:
        found, kinds = {}, {}
        groups = self.grouped(self.root)
        for element in groups.get("link", ()):
            found[element] = element.get("name")
        for element in groups.get("joint", ()):
            found[element] = element.get("name")
            kinds[element] = element.get("type")
        self._memo[Robot.kinds] = kinds
        return found

    @cached_property
    def links(self) -> dict[str, object]:
        """Link elements by name; the first of duplicates wins. A link without a ``name``
        attribute is the link named ``''``, as urdfdom reads it (it logs "No name given for the
        link." and goes on: alone it is the root, beside another link a second one)."""
        return _by_name(self.grouped(self.root).get("link", ()), self.names(), "")

    @cached_property
    def joints(self) -> dict[str, object]:
        """Joint elements by name; the first of duplicates wins."""
        return _by_name(self.grouped(self.root).get("joint", ()), self.names())

    @cached_property
    def urdf(self) -> str:
        """The expanded URDF as text, for yourdfpy, Pinocchio and ``urdftool xacro``."""
        from lxml import etree

        return etree.tostring(self.root, encoding="unicode", pretty_print=False)

    def resolve_uri(self, uri: str) -> Path:
        """A mesh URI as a path; raises PackageNotFound for an unknown package."""
        return self.resolver.resolve_uri(uri, self.base_dir)


def _by_tag(children: list) -> dict[str, list]:
    grouped: dict[str, list] = {}
    for child in children:  # (child_list's: one list from lxml, not its iterator)
        tag = child.tag
        group = grouped.get(tag)
        if group is not None:
            group.append(child)
        elif isinstance(tag, str):  # not a comment, processing instruction or entity
            grouped[tag] = [child]  # (no list made and dropped for each child, as setdefault)
    return grouped


def _by_name(elements, names: dict, unnamed: str | None = None) -> dict:
    """``unnamed``: the name an element without the attribute goes by (None: left out)."""
    found: dict = {}
    for element in elements:  # (their names as read once: Robot.names)
        name = names[element]
        if name is None:
            name = unnamed
        if name is not None and name not in found:
            found[name] = element
    return found
