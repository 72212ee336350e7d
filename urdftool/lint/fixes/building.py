"""Building the edits that remove a finding: what to change, where it was written.

A rule builds the fix of a finding with the helpers here, from the robot element it reports.
The edit lands in the file where that element was written, at its start tag
(:mod:`.tags`), at the literal that produced the value. Text spans are replaced; the XML is
never re-serialised, so formatting, comments and attribute order stay as they were. What a fix
writes as elements must be exactly one well-formed element (:func:`insert_before`,
:func:`append_child`): a name from the robot written unescaped into it is refused.

When the value came from an expression or a macro argument (``${...}``, ``$(arg ...)``) there is
no edit: the helper returns :class:`Unfixable`, whose reason says where the value came from, and
the rule adds it to its message (:func:`offer`).
"""

from __future__ import annotations

import re
from xml.parsers import expat

from urdftool.description.files import kind_of
from urdftool.description.xml import attribute
from urdftool.diagnostics import Edit, Fix, line_start
from urdftool.lint.fixes.tags import EXPRESSION, Unfixable, local_name, source, source_tag


def set_attribute(robot, element, name: str, value: str) -> list[Edit] | Unfixable:
    """Edits giving ``element``'s attribute ``name`` the value ``value``: the literal replaced,
    or the attribute added after the last one; Unfixable when the value came from an
    expression."""
    found = source_tag(robot, element)
    if isinstance(found, Unfixable):
        return found
    text, tag = found
    if name in tag.attributes:
        _, (start, end), raw = tag.attributes[name]
        if EXPRESSION.search(raw):
            line, _ = text.position(start)
            return Unfixable(_origin(robot, element, name, raw, f"{text.file}:{line}"))
        return [text.edit(start, end, attribute(value))]
    if element.get(name) is not None:
        return Unfixable(f"{name} is not written at {text.file}:{tag.line} (set by xacro)")
    closing = text.data.rfind(b"/>" if tag.self_closing else b">", tag.start, tag.end)
    at = closing
    while at > tag.start and text.data[at - 1:at].isspace():
        at -= 1
    return [text.edit(at, at, f' {name}="{attribute(value)}"')]


_ARGUMENT = re.compile(r"\$\{\s*([A-Za-z_]\w*)\s*\}")


def _origin(robot, element, name: str, raw: str, where: str) -> str:
    """Where an attribute value written as an expression came from: the macro argument of the
    call that produced the element when the expression is one (``${axis}``), else the
    expression itself."""
    argument = _ARGUMENT.fullmatch(raw.strip())
    location = robot.locations.get(element)
    if argument and location is not None:
        for site in location.via:
            text = source(robot, site.file)
            calls = [t for t in (text.on_line(site.line) if text else ())
                     if t.name.startswith("xacro:") and argument.group(1) in t.attributes]
            if len(calls) == 1:
                value = calls[0].attributes[argument.group(1)][2]
                return (f"{name} is the macro argument {argument.group(1)}=\"{value}\" of the "
                        f"call at {site}; change it there")
    return (f"{name} comes from the expression \"{raw}\" at {where}; change it there or where "
            "its parts are defined")


def swap_attributes(robot, element, first: str, second: str,
                    default: str | None = None) -> list[Edit] | Unfixable:
    """Edits exchanging the values of two attributes of ``element`` (``default``: the value an
    absent one stands for)."""
    values = [element.get(name, default) for name in (first, second)]
    if None in values:
        return Unfixable(f"{first} or {second} is missing")
    edits = []
    for name, value in ((first, values[1]), (second, values[0])):
        found = set_attribute(robot, element, name, value)
        if isinstance(found, Unfixable):
            return found
        edits.extend(found)
    return edits


def _not_one_element(xml: tuple[str, ...]) -> Unfixable | None:
    """Unfixable when a fragment a fix would write is not exactly one well-formed element: a
    name from the robot written into it without :func:`~urdftool.description.xml.attribute`
    would break the file or add an element of the attacker's (``"/><link name="x``)."""
    for fragment in xml:
        parser, depth, tops = expat.ParserCreate(), [0], [0]

        def start(name, attributes, depth=depth, tops=tops):
            tops[0] += depth[0] == 1  # a child of <_>: an element of the fragment's top level
            depth[0] += 1

        def end(name, depth=depth):
            depth[0] -= 1

        parser.StartElementHandler, parser.EndElementHandler = start, end
        try:
            parser.Parse(f"<_>{fragment}</_>", True)
        except expat.ExpatError:
            tops[0] = 0
        if tops[0] != 1:
            return Unfixable("the element it would write is not well formed (a name in it?)")
    return None


def insert_before(robot, element, *xml: str) -> list[Edit] | Unfixable:
    """An edit writing the elements ``xml`` just before ``element``'s start tag, each on a line
    of its own with the same indentation when ``element`` starts its line; Unfixable when one
    is not exactly one well-formed element."""
    found = _not_one_element(xml) or source_tag(robot, element)
    if isinstance(found, Unfixable):
        return found
    text, tag = found
    indent = text.data[line_start(text.data, tag.start):tag.start]
    separator = text.newline + indent.decode("utf-8") if not indent.strip() else " "
    return [text.edit(tag.start, tag.start, "".join(part + separator for part in xml))]


def append_child(robot, element, xml: str) -> list[Edit] | Unfixable:
    """An edit writing ``xml`` (lines of an element) as the last child of ``element``, indented
    one step (two spaces) deeper than ``element`` when its end tag starts a line; Unfixable when
    it is not exactly one well-formed element."""
    found = _not_one_element((xml,)) or source_tag(robot, element)
    if isinstance(found, Unfixable):
        return found
    text, tag = found
    if tag.close_name is None:
        return Unfixable(f"<{tag.name}> at {text.file}:{tag.line} is empty-element tag")
    close = tag.close_name[0] - 2
    start = line_start(text.data, close)
    before = text.data[start:close]
    if before.strip():
        return [text.edit(close, close, xml)]
    indent = before.decode("utf-8") + "  "
    lines = "".join(indent + line + text.newline for line in xml.split("\n"))
    return [text.edit(start, start, lines)]


def rename_attribute(robot, element, old: str, new: str) -> list[Edit] | Unfixable:
    """Edits renaming attribute ``old`` of ``element`` to ``new`` where it was written."""
    found = source_tag(robot, element)
    if isinstance(found, Unfixable):
        return found
    text, tag = found
    if old not in tag.attributes:
        return Unfixable(f"attribute {old} is not written at {text.file}:{tag.line}")
    start, end = tag.attributes[old][0]
    return [text.edit(start, end, new)]


def rename_element(robot, element, new: str) -> list[Edit] | Unfixable:
    """Edits renaming ``element`` to ``new`` in its start tag and its end tag."""
    found = source_tag(robot, element)
    if isinstance(found, Unfixable):
        return found
    text, tag = found
    if ":" in tag.name:
        return Unfixable(f"<{tag.name}> at {text.file}:{tag.line} is not a plain element")
    edits = [text.edit(*tag.name_span, new)]
    if tag.close_name is not None:
        edits.append(text.edit(*tag.close_name, new))
    return edits


def _plain_text(robot, element):
    """(source, tag, text, offset of the text) of an element holding plain literal text;
    Unfixable when its text is absent, holds elements or an expression."""
    found = source_tag(robot, element)
    if isinstance(found, Unfixable):
        return found
    text, tag = found
    value = text.data[tag.end:tag.close_name[0] - 2] if tag.close_name is not None else b""
    decoded = value.decode("utf-8", errors="replace")
    if not decoded.strip() or "<" in decoded or EXPRESSION.search(decoded):
        return Unfixable(f"the text of <{tag.name}> at {text.file}:{tag.line} is not a plain "
                         "literal")
    return text, tag, decoded, tag.end + len(value) - len(value.lstrip())


def element_to_attribute(robot, element) -> list[Edit] | Unfixable:
    """Edits turning ``<parent><name>text</name></parent>`` into ``<parent name="text">``: the
    attribute set on the parent, the element deleted."""
    found = _plain_text(robot, element)
    if isinstance(found, Unfixable):
        return found
    text, tag, value, _ = found
    end = text.data.find(b">", tag.close_name[1]) + 1
    attribute = set_attribute(robot, element.getparent(), local_name(element.tag), value.strip())
    if isinstance(attribute, Unfixable):
        return attribute
    parent = source_tag(robot, element.getparent())
    if not isinstance(parent, Unfixable) and parent[0] is text and parent[1].close_name:
        holder = parent[1]
        close_end = text.data.find(b">", holder.close_name[1]) + 1
        rest = text.data[holder.end:tag.start] + text.data[end:holder.close_name[0] - 2]
        if not rest.strip():  # nothing else inside: the parent becomes an empty-element tag
            return attribute + [text.edit(holder.end - 1, close_end, "/>")]
    return attribute + [text.edit(tag.start, end, "")]


def prefix_text(robot, element, prefix: str) -> list[Edit] | Unfixable:
    """An edit writing ``prefix`` before the text of ``element`` (after leading blanks)."""
    found = _plain_text(robot, element)
    if isinstance(found, Unfixable):
        return found
    text, _, _, at = found
    return [text.edit(at, at, prefix)]


def inertial_edits(robot, link, body) -> list[Edit] | Unfixable:
    """Edits making ``link``'s ``<inertial>`` say ``body`` (mass [kg], com [m] and inertia
    [kg m^2] about the com in link axes): mass, origin (at the com, rpy zero) and the six
    terms; a whole block written when the link has none."""
    from urdftool.physics.inertia_compare import inertial_numbers

    mass, com, terms = inertial_numbers(body)
    inertial = link.find("inertial")
    if inertial is None:
        return _new_inertial(robot, link, mass, com, terms)
    edits = []
    mass_element, inertia = inertial.find("mass"), inertial.find("inertia")  # (read once)
    if mass_element is not None and mass_element.get("value") is not None:
        declared = float(mass_element.get("value", "nan") or "nan")
        if not abs(declared - float(body.mass)) <= 1e-9 * max(abs(declared), 1.0):
            edits.append(set_attribute(robot, mass_element, "value", mass))
    origin = inertial.find("origin")
    if origin is not None:
        edits.append(set_attribute(robot, origin, "xyz", com))
        if origin.get("rpy") is not None:
            edits.append(set_attribute(robot, origin, "rpy", "0 0 0"))
    elif com != "0 0 0":  # as written: round-off is 0
        first = next((c for c in inertial if isinstance(c.tag, str)), None)
        if first is None:
            return Unfixable("its <inertial> is empty")
        edits.append(insert_before(robot, first, f'<origin xyz="{com}" rpy="0 0 0"/>'))
    if inertia is None:
        return Unfixable("its <inertial> has no <inertia>")
    for name, value in terms.items():
        edits.append(set_attribute(robot, inertia, name, value))
    unfixable = next((e for e in edits if isinstance(e, Unfixable)), None)
    return unfixable or [edit for group in edits for edit in group]


def _new_inertial(robot, link, mass: str, com: str, terms: dict) -> list[Edit] | Unfixable:
    """An edit writing a whole ``<inertial>`` as the link's first child."""
    block = (f'<inertial><origin xyz="{com}" rpy="0 0 0"/><mass value="{mass}"/><inertia '
             + " ".join(f'{name}="{value}"' for name, value in terms.items()) + "/></inertial>")
    first = next((c for c in link if isinstance(c.tag, str)), None)
    if first is not None:
        return insert_before(robot, first, block)
    found = source_tag(robot, link)
    if isinstance(found, Unfixable):
        return found
    text, tag = found
    if not tag.self_closing:
        return Unfixable(f"<link> at {text.file}:{tag.line} holds no element to write it before")
    closing = text.data.rfind(b"/>", tag.start, tag.end)
    return [text.edit(closing, tag.end, f"><{block[1:]}</link>")]


def offer(where, message: str, description: str, edits, safe: bool = True, creates=()):
    """What a rule yields for a finding with a possible fix: ``(where, message, fix)``; when
    ``edits`` is :class:`Unfixable`, the message with why there is no fix; None: no fix.
    creates: the :class:`~urdftool.diagnostics.Derived` files the fix writes too."""
    if edits is None:
        return where, message, None
    if isinstance(edits, Unfixable):
        return where, message + f" (no automatic fix: {edits.reason})", None
    return where, message, Fix(description, tuple(edits), safe, tuple(creates))


def converted_mesh(robot, mesh, source, suffix: str):
    """(edits, creates) pointing ``mesh``'s filename at ``source`` converted to ``suffix``
    (``.obj``, ``.stl``), beside it: the file is written when the fix is applied, unless it is
    there already. Unfixable when the filename comes from an expression or has no
    extension to replace."""
    from pathlib import Path

    from urdftool.diagnostics import Derived, display_path

    filename = mesh.get("filename") or ""
    old_suffix = Path(filename.split("?")[0]).suffix
    if not old_suffix or not filename.endswith(old_suffix):
        return Unfixable(f"mesh '{filename}' has no extension to replace"), ()
    edits = set_attribute(robot, mesh, "filename", filename[:-len(old_suffix)] + suffix)
    target = Path(source).with_suffix(suffix)
    if isinstance(edits, Unfixable) or kind_of(target):
        return edits, ()
    return edits, (Derived(display_path(target), display_path(source), suffix[1:]),)
