"""A loaded robot written back as URDF text (``urdftool xacro``)."""

from __future__ import annotations


def expanded_urdf(robot) -> str:
    """The robot's (expanded) document, indented by two spaces, with an XML declaration."""
    from lxml import etree

    etree.indent(robot.root, space="  ")
    text = etree.tostring(robot.root, encoding="unicode", xml_declaration=False)
    return f'<?xml version="1.0" ?>\n{text}\n'
