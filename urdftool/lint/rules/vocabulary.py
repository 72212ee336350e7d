"""U02x: the URDF vocabulary. Misspelt elements and attributes, and content urdfdom ignores.

urdfdom asks for each element and attribute it knows by name and never looks at the rest: an
``<orgin>`` leaves the joint at the identity, an ``uper`` leaves the limit at 0, both without a
word. The names it reads, where, and which it requires are the data of
:data:`urdftool.description.urdf.VOCABULARY` (with their sources). Namespaced content
(``drake:``, ``xacro:``) and the blocks other programs read (``<gazebo>``, ``<transmission>``,
``<ros2_control>``, ``<sensor>``, ``<mujoco>``: :data:`~urdftool.description.urdf.EXTENSIONS`)
are left alone, except for the parts of transmissions and ros2_control whose names are known,
where a close misspelling is reported. The numbers it reads are read by its own grammar, whose
white space is narrower than XML's and other loaders' (U023).
"""

from __future__ import annotations

import re

from urdftool.description.urdf import (EXTENSION_VOCABULARY, EXTENSIONS, NUMBERS, VOCABULARY,
                                       Place, is_namespaced, is_xacro, version_problem, where_valid)
from urdftool.description.values import parse_numbers, urdfdom_refuses, urdfdom_spelling
from urdftool.description.xml import child_list
from urdftool.lint.catalogue import NOT_LOADED, Conditional, Severity, rule

CUTOFF = 0.75  # difflib ratio from which a name is taken for a misspelling of a known one


def _close(name: str, valid) -> list[str]:
    """The known names ``name`` is a misspelling of. A known name with a word added before or
    after it (``gear_velocity``, ``velocity_max``) is a tool's own extension written on
    purpose, not a misspelling of ``velocity``, and a word of a known name (``mimic`` beside
    ros2_control's ``is_mimic``) is another version's name for it: neither is close."""
    from urdftool.errors import close_names  # only for an unknown name

    valid = list(dict.fromkeys(valid))
    same_case = [v for v in valid if v.lower() == name.lower()]
    def words(text: str) -> set[str]:
        return set(text.lower().replace("-", "_").split("_"))

    return same_case or [v for v in close_names(name, valid, n=3, cutoff=CUTOFF)
                         if not (len(words(name)) > 1 and v.lower() in words(name))
                         and not (len(words(v)) > 1 and name.lower() in words(v))]


class _Unknown:
    """One unknown name: ``element`` holds it (the unknown element itself, or the element with
    the unknown ``attribute``); ``close`` the known names it is close to; ``why``: when known
    but read nowhere here, the reason."""

    __slots__ = ("element", "attribute", "place", "close", "why", "extension", "elsewhere")

    def __init__(self, element, attribute, place, close, why=None, extension=False,
                 elsewhere=False):
        self.element, self.attribute, self.place = element, attribute, place
        self.close, self.why, self.extension = close, why, extension
        self.elsewhere = elsewhere  # another program reads it: ``why`` says which

    @property
    def name(self) -> str:
        return self.attribute if self.attribute is not None else self.element.tag

    @property
    def holder(self) -> str:
        parent = self.element if self.attribute is not None else self.element.getparent()
        return parent.tag if parent is not None else "?"


def _unknowns(robot) -> list[_Unknown]:
    return robot.memo(_unknowns, lambda: _walk(robot.root, "robot", VOCABULARY["robot"], [],
                                               robot.listed(), _alike(robot)))


# A robot of this many top-level elements or more has its links and joints walked once per
# shape (:meth:`~urdftool.description.robot.Robot.shapes`): a generated or exported robot of
# thousands of links repeats a few.
ALIKE = 256


def _alike(robot) -> dict | None:
    """Element -> its shape, of the robot's top-level elements whose shape says all the walk
    reads of them (no ``<axis rpy>``, whose value :func:`_zero` reads, no namespace declared:
    an ``xmlns=""`` and an ``xmlns="..."`` are one shape); None below :data:`ALIKE` elements
    or where the loader did not scan the file."""
    children = child_list(robot.root)
    if len(children) < ALIKE:
        return None
    shapes = robot.shapes(children)
    if shapes is None:
        return None
    found, told = {}, {}  # (each distinct shape judged once: a robot repeats a few)
    for child, shape in zip(children, shapes):
        telling = told.get(shape)
        if telling is None:
            telling = told[shape] = b"xmlns" not in shape and \
                not (b"rpy=" in shape and _AXIS_RPY.search(shape))
        if telling:
            found[child] = shape
    return found


_AXIS_RPY = re.compile(rb"<axis\b[^<>]*\srpy=")


def _skipped(tag) -> bool:
    return not isinstance(tag, str) or is_namespaced(tag) or is_xacro(tag)


def _walk(element, key: str, place: Place, found: list, listed: dict,
          alike: dict | None = None) -> list[_Unknown]:
    """Append the unknowns of ``element`` and below to ``found``, in document order; return it.
    Calls, not nested generators, and leaves not iterated: a 10,000-link robot has 190,000
    elements. Each element's attributes are first compared as a whole with the names known
    there (one set operation; the names one by one only when some is not known), and a known
    child that is a leaf is judged in its parent's loop, without a call of its own. Each
    element's children are grouped by tag as they are met, into ``listed`` (:meth:`~urdftool.
    description.robot.Robot.listed`), for the families that group them, but a ``<geometry>``'s
    (its shape is read as its first element). ``alike``: see :func:`_walk_children`."""
    keys = element.keys()
    if keys and not _KNOWN[key].issuperset(keys):
        _unknown_attributes(element, key, place, keys, found)
    if len(element):
        _walk_children(element, key, place, found, listed, alike)
    return found


def _unknown_attributes(element, key: str, place: Place, keys, found: list) -> None:
    """Append the unknown attributes among ``keys`` (``element``'s, in order) to ``found``."""
    known = place.attributes
    for attribute in keys:
        if attribute in known or is_namespaced(attribute):
            continue
        if key == "axis" and attribute == "rpy" and _zero(element.get(attribute)):
            continue  # misleads nobody: the axis is where its author meant it
        if attribute in place.elsewhere:
            found.append(_Unknown(element, attribute, key, [], place.elsewhere[attribute],
                                  elsewhere=True))
        elif attribute in place.ignored:
            found.append(_Unknown(element, attribute, key, [], place.ignored[attribute]))
        else:
            found.append(_Unknown(element, attribute, key, _close(attribute, place.names())))


def _walk_children(element, key: str, place: Place, found: list, listed: dict,
                   alike: dict | None = None) -> None:
    """Append the unknowns below ``element`` (which has children) to ``found``, in order (its
    children grouped in ``listed``: see :func:`_walk`). ``alike``: child -> its shape
    (:func:`_alike`), of children walked once per shape: a known child of a shape found
    clean is clean, and is not walked (nor its children grouped)."""
    children, shapes, clean = place.children, 0, set()
    if key != "geometry":
        known_children = _KNOWN_CHILDREN[key]
        groups = {}  # (as _by_tag groups them; an element grouped already keeps its groups)
        if element not in listed:
            listed[element] = groups
    else:
        known_children, groups = {}, {}
    for child in child_list(element):
        tag = child.tag
        group = groups.get(tag)
        if group is not None:
            group.append(child)
        elif isinstance(tag, str):  # not a comment, processing instruction or entity
            groups[tag] = [child]
        entry = known_children.get(tag)
        if entry is not None:  # a known element (not a shape): most are; as _walk(child, ...)
            name, child_place, child_known = entry
            if alike is not None:  # a link, joint or material like one found clean: clean
                shape, before = alike.get(child), len(found)
                if shape in clean:
                    continue
            keys = child.keys()
            if keys and not child_known.issuperset(keys):
                _unknown_attributes(child, name, child_place, keys, found)
            if len(child):
                _walk_children(child, name, child_place, found, listed)
            if alike is not None and shape is not None and len(found) == before:
                clean.add(shape)
            continue
        if tag not in children and _skipped(tag):  # (a name the place knows is plain)
            continue
        if key == "geometry":
            shapes += 1
            if shapes == 1 and tag not in children:
                continue  # an unknown shape is U401's
            if shapes > 1:
                found.append(_Unknown(child, None, key, [], "urdfdom reads only the first "
                                      "shape of <geometry>; give each shape its own "
                                      "<visual>/<collision>"))
                continue
        if tag in children:
            name = children[tag]
            _walk(child, name, VOCABULARY[name], found, listed)
        elif key == "robot" and tag in EXTENSIONS:
            found.extend(_extension(child, tag))
        elif tag in place.extensions:
            continue
        elif tag in place.ignored:
            found.append(_Unknown(child, None, key, [], place.ignored[tag]))
        else:
            close = [] if _metadata(child, key) else _close(tag, place.names())
            found.append(_Unknown(child, None, key, close))


# Per place of the vocabulary: the attribute names known there (a set, compared with each
# element's at once), and each known child tag -> (its place's name, place, known attributes)
_KNOWN = {key: frozenset(place.attributes) for key, place in VOCABULARY.items()}
_KNOWN_CHILDREN = {key: {tag: (name, VOCABULARY[name], _KNOWN[name])
                         for tag, name in place.children.items()}
                   for key, place in VOCABULARY.items()}


def _metadata(element, key: str) -> bool:
    """Whether an element named like an attribute of its holder holds what that attribute
    cannot: ``<version>2025-09-17_13-38-40</version>`` in ``<robot>`` (kroshu's KUKA robots) is
    a build stamp, not a slip for ``version="1.0"``, so no effect (U022) rather than a
    misspelling whose fix would make urdfdom refuse the robot."""
    return key == "robot" and element.tag == "version" and \
        version_problem(element.text or "") is not None


def _zero(text) -> bool:
    values, problem = parse_numbers(text, 3)
    return not problem and not any(values)


def _extension(element, key: str):
    known = EXTENSION_VOCABULARY.get(key)
    if known is None:
        return
    for attribute in element.attrib:
        if not is_namespaced(attribute) and attribute not in known:
            close = _close(attribute, known)
            if close:
                yield _Unknown(element, attribute, key, close, extension=True)
    for child in element:
        if _skipped(child.tag):
            continue
        if child.tag in known:
            yield from _extension(child, f"{key}/{child.tag}")
            continue
        close = _close(child.tag, known)
        if close:
            yield _Unknown(child, None, key, close, extension=True)


def _attributes(key: str) -> tuple[str, ...]:
    place = VOCABULARY.get(key)
    return place.attributes if place is not None else ()


def _suggestion(unknown: _Unknown) -> str:
    close = unknown.close
    if unknown.attribute is None:
        as_attribute = [name for name in close if name in _attributes(unknown.place)]
        if as_attribute and as_attribute[0] == unknown.name:
            text = (unknown.element.text or "").strip() or "..."
            return (f"urdfdom reads {unknown.name} as an attribute: "
                    f"<{unknown.holder} {unknown.name}=\"{text}\"/>")
    elif unknown.attribute in close and unknown.attribute not in _attributes(unknown.place):
        return (f"urdfdom reads {unknown.attribute} as an element: "
                f"<{unknown.attribute} .../> inside <{unknown.holder}>")
    shown = " or ".join(f"'{name}'" for name in close)
    return f"did you mean {shown}?"


def _what(unknown: _Unknown) -> str:
    if unknown.attribute is not None:
        return f"<{unknown.holder}> attribute '{unknown.attribute}'"
    return f"<{unknown.name}> in <{unknown.holder}>"


@rule("U020", "misspelt-element", Severity.ERROR)
def misspelt_element(robot):
    """An element urdfdom does not know, spelt close to one it reads there.

    urdfdom asks for its elements by name and ignores the rest without a word: the joint keeps
    an identity origin, the link no inertia. Known blocks of other readers (``<gazebo>``,
    ``<sensor>``, namespaced ``drake:`` tags) are left alone; in ``<transmission>`` and
    ``<ros2_control>`` only their known names are compared.

    Fix (safe): the element renamed, when exactly one known name is close; an element written
    for an attribute of its parent becomes that attribute.

    Bad: ``<joint ...><orgin xyz="0 0 1"/>``, ``<dynamics><damping>100</damping></dynamics>``
    Good: ``<origin xyz="0 0 1"/>``, ``<dynamics damping="100"/>``
    """
    for unknown in _unknowns(robot):
        if unknown.attribute is None and unknown.close:
            message = (f"unknown element {_what(unknown)}, which {_reader(unknown)} ignores; "
                       f"{_suggestion(unknown)}")
            yield _renamed(robot, unknown, message)


@rule("U021", "misspelt-attribute", Severity.ERROR)
def misspelt_attribute(robot):
    """An attribute urdfdom does not know, spelt close to one it reads there.

    urdfdom then uses that attribute's default (``upper`` 0, ``multiplier`` 1) silently.

    Fix (safe): the attribute renamed, when exactly one known name is close and the element
    does not already have it.

    Bad: ``<limit lower="-1" uper="1" effort="1" velocity="1"/>``
    Good: ``<limit lower="-1" upper="1" effort="1" velocity="1"/>``
    """
    for unknown in _unknowns(robot):
        if unknown.attribute is not None and unknown.close:
            message = (f"unknown {_what(unknown)}, which {_reader(unknown)} ignores; "
                       f"{_suggestion(unknown)}")
            yield _renamed(robot, unknown, message)


def _renamed(robot, unknown: _Unknown, message: str):
    """The finding, with the rename to the one close name as its fix (when the name is one of
    the same kind: an element for an element, an attribute for an attribute)."""
    from urdftool.lint.fixes import element_to_attribute, offer, rename_attribute, rename_element

    if unknown.attribute is None and unknown.close == [unknown.name] and \
            unknown.name in _attributes(unknown.place) and \
            unknown.element.getparent().get(unknown.name) is None:
        return offer(unknown.element, message, f"write <{unknown.name}> as an attribute",
                     element_to_attribute(robot, unknown.element))
    kind = _attributes(unknown.place) if unknown.attribute is not None else _children(unknown)
    close = [name for name in unknown.close if name in kind]
    if len(close) != 1 or len(unknown.close) != 1 or \
            (unknown.attribute is not None and close[0] in unknown.element.attrib):
        return unknown.element, message
    if unknown.attribute is not None:
        edits = rename_attribute(robot, unknown.element, unknown.attribute, close[0])
    else:
        edits = rename_element(robot, unknown.element, close[0])
    return offer(unknown.element, message, f"rename {unknown.name} to {close[0]}", edits)


def _children(unknown: _Unknown) -> tuple[str, ...]:
    place = VOCABULARY.get(unknown.place)
    if place is not None:
        return tuple(place.children)
    return EXTENSION_VOCABULARY.get(unknown.place, ())


@rule("U022", "no-effect", Severity.WARNING)
def no_effect(robot):
    """Content that urdfdom reads nothing from, and that is no misspelling of what it reads.

    It looks meaningful and changes nothing: an ``rpy`` on an ``<axis>`` does not turn the
    axis, a ``<material>`` in a ``<collision>`` colours nothing. Where a name is valid elsewhere
    the message says where. An attribute another program is known to read (``dont_collapse``
    on a ``<joint>``: Isaac Gym's and Isaac Sim's importers keep the fixed joint) is written
    for it on purpose: a **note** saying which. An element named as a macro whose file has
    ``<xacro:macro name="...">`` as its root element calls none (xacro inserts that root's
    children at the include and defines no macro): the message says so (Quori's
    ``<quori_kinematics/>``).

    Bad: ``<axis xyz="0 0 1" rpy="0 1.57 0"/>``, ``<collision><material name="red"/>...``
    Good: ``<axis xyz="1 0 0"/>`` (turn the joint frame with ``<origin rpy>`` instead)
    """
    unread: dict = {}  # element -> its unknown attributes without a close name, in order
    for unknown in _unknowns(robot):
        if unknown.close or unknown.extension:
            continue
        if unknown.elsewhere:  # meant for another program: a note, saying which
            yield unknown.element, (f"{_what(unknown)} has no effect on urdfdom and the tools "
                                    f"that load URDF through it; {unknown.why}"), None, \
                Severity.INFO
        elif unknown.why:
            yield unknown.element, f"{_what(unknown)} has no effect: {unknown.why}"
        elif unknown.attribute is not None:
            unread.setdefault(unknown.element, []).append(unknown.attribute)
        else:
            places = [p for p in where_valid(unknown.name) if p != unknown.place]
            tags = dict.fromkeys(f"<{_tag(p)}>" for p in places)  # a visual's and a global <material>
            hint = ("; urdfdom reads it only in " + ", ".join(tags) if places
                    else _read_elsewhere(unknown) or _macro_file_root(robot, unknown.name))
            yield unknown.element, f"{_what(unknown)} has no effect: {_unread(1)}{hint}"
    for element, names in unread.items():
        listed = ", ".join(f"'{name}'" for name in names)
        noun = "attribute" if len(names) == 1 else "attributes"
        read = _attributes(_key(element))  # <geometry> reads none (ros2_jazzy_p3at's name=)
        reads = f"it reads {', '.join(read)}" if read else f"URDF gives <{element.tag}> no attributes"
        yield element, (f"<{element.tag}> {noun} {listed} {'has' if len(names) == 1 else 'have'} "
                        f"no effect: {_unread(len(names))}; {reads}")


def _macro_file_root(robot, name: str) -> str:
    """Why an element named as a macro calls none, when a file the robot was built from has
    ``<xacro:macro name="NAME">`` as its root element (Quori's quori_kinematics.xacro, called
    ``<quori_kinematics/>``): xacro inserts an included file's root's children at the include,
    so the macro's body is in the robot already and no macro of that name is ever defined; ""
    otherwise."""
    import os

    wanted = re.compile(rb"<xacro:macro\s[^<>]*?\bname\s*=\s*[\"']" + re.escape(name.encode())
                        + rb"[\"']")
    for path, data in robot.sources.items():
        start = _first_element(data)
        if start is not None and wanted.match(data, start):
            return (f"; it calls no macro: {os.path.basename(path)}'s root element is "
                    f"<xacro:macro name=\"{name}\">, whose body xacro inserts where the file is "
                    "included (a file's root is never defined as a macro): remove the element, "
                    "or wrap the macro in a <robot> root and call it <xacro:" + name + "/>")
    return ""


def _first_element(data: bytes) -> int | None:
    """Where the first element of an XML file starts, past white space, the declaration,
    processing instructions and comments (each skipped by a search: linear in the file, where
    one regular expression matching them all backtracked for minutes on a generated URDF of
    many comments); None when the file has none."""
    at = 0
    while True:
        while at < len(data) and data[at:at + 1].isspace():
            at += 1
        if data.startswith(b"<!--", at):
            end = data.find(b"-->", at + 4)
            at = end + 3 if end >= 0 else len(data)
        elif data.startswith(b"<?", at) or data.startswith(b"<!", at):
            end = data.find(b">", at)
            at = end + 1 if end >= 0 else len(data)
        else:
            return at if data.startswith(b"<", at) else None


def _read_elsewhere(unknown) -> str:
    """Where another program reads an element misplaced here (mallard_urdf's thruster macro
    writes freefloating_gazebo's <buoyancy> after its link, at the top level), or ""."""
    readers = [(place, entry.extensions[unknown.name]) for place, entry in VOCABULARY.items()
               if place != unknown.place and unknown.name in entry.extensions]
    return "".join(f"; {reader} reads it only inside <{_tag(place)}>" for place, reader in readers)


def _unread(count: int) -> str:
    it = "it" if count == 1 else "them"
    return (f"urdfdom does not read {it}, nor do the tools that load URDF through it (KDL, "
            "robot_state_publisher, MoveIt)")


def _key(element) -> str:
    """The vocabulary place of an element of the robot (its tag, or material_global)."""
    if element.tag == "material" and element.getparent() is not None \
            and element.getparent().tag == "robot":
        return "material_global"
    return element.tag


def _tag(place: str) -> str:
    return "robot" if place == "robot" else place.split("_global")[0]


def _reader(unknown: _Unknown) -> str:
    if unknown.extension:
        return "ros2_control" if unknown.place.startswith("ros2_control") else \
            "the transmission parser"
    return "urdfdom"


@rule("U023", "number-white-space", Severity.ERROR)
def number_white_space(robot):
    """A number written with white space urdfdom refuses: after a scalar, or a tab inside a vector.

    urdfdom reads a single number (a mass, a limit, a radius) only when nothing follows it, not
    even a space (``value="2 "``: "mass [2 ] is not a float"), and splits a vector (``xyz``,
    ``rpy``, ``size``, ``scale``, ``rgba``) at spaces only, so that a tab, line break or carriage
    return after a number leaves a part that is no number ("Unable to parse component"). In a
    joint it then refuses the robot: robot_state_publisher, RViz, MoveIt and Gazebo (through
    sdformat) do not load it. In a link it logs an error and reads no more of the link: an
    ``<inertial>`` so written leaves the link without mass (0 to KDL and Pinocchio), visuals
    and collisions. A colour so written is dropped. PyBullet reads a vector with a tab or line
    break between its numbers as ``0 0 0``. MuJoCo and yourdfpy read every such spelling as
    meant. In a joint it is an error, as every other robot urdfdom refuses is (the parser
    ROS's tools share; ``urdftool tree`` fails as check_urdf does); in a link or a colour a
    warning: urdfdom loads the robot without the part. White space before a number, and spaces
    around a vector's numbers, every reader takes.

    A tab or line break written raw in an attribute is a space to the XML parsers that
    normalise attributes (lxml, expat: xacro's output has none) and stays what it is to
    TinyXML2 (urdfdom, PyBullet): a URDF's own bytes are judged. ``&#9;`` is a tab to all.

    Fix (safe): the numbers written with one space between them and none around.

    Bad: ``<mass value="2 "/>``, ``<origin xyz="0.1&#9;0 0"/>``
    Good: ``<mass value="2"/>``, ``<origin xyz="0.1 0 0"/>``
    """
    sources = [data for data in robot.sources.values() if data]
    if robot.sources and not any(map(_suspect, sources)) and \
            (robot.from_xacro or not any(map(_raw_line_break, sources))):
        return  # (nothing written so, as in nearly every robot: no walk)
    raw = None if robot.from_xacro else _raw_spaced(robot)
    for element in robot.root.iter(*NUMBERS):
        fields = NUMBERS[element.tag]
        for attribute, count in fields:
            text = element.get(attribute)
            if text is None:
                continue
            part = urdfdom_refuses(text, count)
            if raw and text in raw and (count > 1 or part is not None) and \
                    _written_there(element, raw[text]):
                # (as written: a tab or line break lxml reads as a space, quoted as it is)
                written, again = _as_written(robot, element, attribute, count)
                if part is None or again is not None:
                    text, part = written, again
            if part is None or _place(element) != element.tag:
                continue
            from urdftool.lint.fixes import offer, set_attribute  # (only for a finding: 4 M)
            where, message, fix = offer(
                element, _refused(element, attribute, text, part, count),
                "write the numbers with one space between them",
                set_attribute(robot, element, attribute, urdfdom_spelling(text)))
            yield where, message if _refuses_robot(element) else \
                Conditional(message, Severity.WARNING), fix


def _suspect(data: bytes) -> bool:
    """Whether ``data`` (a file read) holds what every spelling U023 finds is written with, a
    xacro's too (in a property's value or a literal): white space before a quote, a character
    reference (``&#9;``), a tab or a carriage return. Byte searches, not a pattern: a 5 MB
    robot is searched in a few ms, where the walk of its 10,000 links' numbers costs 0.2 s. A
    two-byte needle is looked for only in a text holding its rarer byte (a one-byte search is
    memchr's, 0.1 instructions a byte; a two-byte one 4: the star's 5.4 MB hold no "&" and no
    "'", and three searches of 20 M instructions each went)."""
    return b"\t" in data or b"\r" in data or any(
        rare in data and any(needle in data for needle in needles) for rare, needles in _SUSPECT)


# (a byte every needle after it holds, the needles): the spellings U023 finds are written with
_SUSPECT = ((b"&", (b"&#",)), (b"'", (b" '", b"\n'")), (b'"', (b' "', b'\n"')))


def _raw_line_break(data: bytes) -> bool:
    """Whether a URDF's bytes hold a line break inside a value of number characters (a vector
    written across lines, which lxml reads as a space and TinyXML2 keeps), looked for only
    where some line does not end a tag (a 5 MB robot whose every line ends one: two counts)."""
    # line ends: LF only; a file holding a CR is searched whatever this says (_SUSPECT)
    return data.count(b"\n") != data.count(b">\n") and _RAW_SPACED.search(data) is not None


# A quoted value of number characters holding a tab, line feed or carriage return as written:
# lxml reads each as a space (attribute-value normalisation), TinyXML2 keeps it. The characters
# before the first of those are taken without one (possessive: never given back), so a value
# without any fails where it ends, not after trying each of its characters again (the search
# of the corpus's URDFs cost 37 M instructions, 21 M so; the same matches).
_RAW_SPACED = re.compile(rb"""=[ \t\r\n]*(?:"([-+0-9.eE ]*+[\t\r\n][-+0-9.eE \t\r\n]*+)"|"""
                         rb"""'([-+0-9.eE ]*+[\t\r\n][-+0-9.eE \t\r\n]*+)')""")


def _raw_spaced(robot) -> dict[str, list[tuple[int, int]]]:
    """The values (as lxml reads them) written with a raw tab or line break in the robot's
    file, read from its bytes, each with the lines from its first to its start tag's '>' (where
    lxml's ``sourceline`` puts an element, LF only: a CR-only file is line 1 to it); empty for
    nearly every robot."""
    found: dict[str, list[tuple[int, int]]] = {}
    for data in robot.sources.values():
        if data is None:
            continue
        line, counted, tag_end, tag_line = 1, 0, -1, 1
        for match in _RAW_SPACED.finditer(data):
            # line ends: libxml2's (LF only), as lxml's sourceline they are compared with
            line += data.count(b"\n", counted, match.start())
            counted = match.start()
            if match.start() > tag_end:  # (values of one tag share its end: found once)
                tag_end = _tag_end(data, match.end())
                # line ends: libxml2's, as above
                tag_line = line + data.count(b"\n", match.start(), tag_end)
            raw = match.group(1) if match.group(1) is not None else match.group(2)
            value = raw.decode().replace("\r\n", " ").translate(_NORMALISED)
            found.setdefault(value, []).append((line, tag_line))
    return found


def _tag_end(data: bytes, start: int) -> int:
    """Where the '>' ending the start tag that holds ``start`` is (quoted values skipped: XML
    allows a raw '>' in one), or the first '<' outside a tag's values (no start tag holds
    ``start``: a comment's or a text's look-alike, not followed past the next markup); the end
    of ``data`` where neither is. Byte searches from quote to quote, never a pattern that could
    backtrack: linear in what is looked at."""
    at = start
    while True:
        found = _TAG_END.search(data, at)
        if found is None:
            return len(data)
        if found.group() != b"\"" and found.group() != b"'":
            return found.start()
        close = data.find(found.group(), found.end())
        close = len(data) if close < 0 else close
        markup = data.find(b"<", found.end(), close)  # (no value of a start tag holds a '<')
        if markup >= 0 or close == len(data):
            return markup if markup >= 0 else close
        at = close + 1


_TAG_END = re.compile(rb"[<>\"']")


def _written_there(element, spans: list[tuple[int, int]]) -> bool:
    """Whether ``element``'s start tag may hold a value written over one of ``spans`` (its
    first line to its tag's '>'): lxml's line of the element (that '>') is within it. An
    integer comparison per element: one look at the tag then confirms it (a robot repeats its
    values, 20,000 origins ``0 0 0`` beside one written across lines)."""
    end = element.sourceline
    return end is not None and any(first <= end <= last for first, last in spans)


_NORMALISED = str.maketrans("\t\r\n", "   ")


def _as_written(robot, element, attribute: str, count: int) -> tuple[str, str | None]:
    """(the value as written, :func:`urdfdom_refuses` of it) where ``element``'s start tag is
    found; (its value, None) otherwise."""
    from urdftool.lint.fixes.tags import Unfixable, source_tag

    found = source_tag(robot, element)
    if isinstance(found, Unfixable) or attribute not in found[1].attributes:
        return element.get(attribute), None
    written = found[1].attributes[attribute][2].replace("\r\n", "\n")
    return written, urdfdom_refuses(written, count)


def _place(element) -> str | None:
    """The :data:`VOCABULARY` place of ``element`` (None outside what urdfdom reads)."""
    path = [element.tag, *(ancestor.tag for ancestor in element.iterancestors())][::-1]
    if path[0] != "robot":
        return None
    key = "robot"
    for tag in path[1:]:
        key = VOCABULARY[key].children.get(tag)
        if key is None:
            return None
    return key


def _holder(element):
    """The joint, link or material ``element`` is a number of (None: none of them)."""
    return next((a for a in (element, *element.iterancestors())
                 if a.tag in ("joint", "link", "material")), None)


def _refuses_robot(element) -> bool:
    """Whether urdfdom refuses the whole robot for a number of ``element`` it cannot read (a
    joint's); in a link it stops reading the link, in a material it drops the colour."""
    holder = _holder(element)
    return holder is None or holder.tag == "joint"


def _refused(element, attribute: str, text: str, part: str, count: int) -> str:
    """U023's message: the text, why urdfdom refuses it, what each consumer then does (urdfdom
    6.0's check_urdf and Pinocchio 4.1, measured: a joint's number refuses the robot; a link's
    inertial, visual or collision ends urdfdom's reading of the link there, with an error on
    its log; a colour is dropped)."""
    said = f"<{element.tag} {attribute}=\"{_shown(text)}\">"
    if count == 1:
        why = "urdfdom reads a number only when nothing follows it, not even white space,"
    else:
        why = f"urdfdom splits a vector at spaces only, so \"{_shown(part)}\" is no number to it,"
    ancestors = [element, *element.iterancestors()]
    holder = _holder(element)
    if holder is None or holder.tag == "joint":
        effect = f"and refuses the robot: {NOT_LOADED}"
    elif element.tag == "color":
        effect = ("and drops the colour (an error on its log): RViz and Gazebo (sdformat) draw "
                  "the visual without it")
    else:
        part_of = next(a for a in ancestors if a.getparent() is holder)
        lost = _LOST.get(part_of.tag, f"this <{part_of.tag}>")
        effect = (f"and reads no more of the link from this <{part_of.tag}> on (an error on its "
                  "log): robot_state_publisher, RViz, MoveIt and Gazebo (sdformat) get the link "
                  f"without {lost}")
    if count > 1 and any(c in "\t\n\r\f\v" for c in text.strip(" \t\n\r\f\v")):
        effect += ", and PyBullet reads the vector as zeros"
    where = f"{holder.tag} '{holder.get('name')}': " if holder is not None else ""
    return f"{where}{said}: {why} {effect}; write \"{urdfdom_spelling(text)}\""


# What a link loses where urdfdom stops reading it, by the element it stopped at: it reads the
# first <inertial>, then the visuals, then the collisions (urdfdom link.cpp parseLink)
_LOST = {"inertial": "its mass (0 to KDL and Pinocchio), visuals and collisions",
         "visual": "this visual and the visuals and collisions after it",
         "collision": "this collision and the collisions after it"}


def _shown(text: str) -> str:
    """A text as the message quotes it: a tab, line feed or carriage return as its escape
    (the finding's line in any format, the text report's escaping aside)."""
    return text.translate(_ESCAPES)


_ESCAPES = str.maketrans({"\t": "\\t", "\n": "\\n", "\r": "\\r"})
