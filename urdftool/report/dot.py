"""The kinematic tree as a Graphviz DOT graph: links as boxes, joints as labelled edges, both
coloured by the worst finding ``check`` reports at them."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

from urdftool.description.urdf import UNITS
from urdftool.diagnostics import Severity
from urdftool.errors import DotMissing
from urdftool.report.escape import dot as _quote

COLOURS = {  # severity -> (outline, fill)
    Severity.ERROR: ("#c62828", "#ffcdd2"),
    Severity.WARNING: ("#ef6c00", "#ffe0b2"),
}
_RANK = {Severity.ERROR: 0, Severity.WARNING: 1, Severity.INFO: 2}
RENDERED = (".svg", ".png", ".pdf")


def dot_missing_advice(missing: DotMissing, output: Path) -> str:
    """What happened to ``output`` when Graphviz is missing (``missing`` names the DOT file
    written instead), and how to render it."""
    import shlex

    command = shlex.join(["dot", f"-T{output.suffix[1:]}", str(missing), "-o", str(output)])
    return (f"Graphviz's 'dot' program is not installed, so {output} was not rendered; "
            f"wrote the DOT source to {missing} instead. Install Graphviz (apt install "
            f"graphviz, brew install graphviz) or render it with `{command}`.")


def findings_by_element(robot, findings) -> dict[tuple[str, str], list]:
    """(``link``/``joint``, name) -> findings located at that element or inside it."""
    owner = {}
    for tag in ("link", "joint"):
        for element in robot.children(tag):
            for inner in element.iter():
                owner.setdefault(robot.locate(inner), (tag, element.get("name", "")))
    found: dict[tuple[str, str], list] = {}
    for finding in findings:
        key = owner.get(finding.location)
        if key is not None:
            found.setdefault(key, []).append(finding)
    return found


def to_dot(robot, findings=()) -> str:
    """DOT source for ``robot``'s tree; ``findings`` (from check) colour links and joints.

    A link takes the worst severity of the findings at it and at the joint that moves it. The
    links beside the tree (:func:`urdftool.kinematics.tree.beside_the_tree`, the one owner
    every command leaves them out by) and the joints between them are drawn dashed and grey,
    labelled so: urdfdom's model, and every other command, leaves them out (they were drawn as
    links of the tree, while the command's warning said they were left out). A robot of
    several roots (a link no joint reaches: urdfdom refuses it) has each root labelled
    ``(root 2 of 2)``: they were drawn as any link, the parts apart, and only a tooltip said
    which was a root (a PNG has none).
    """
    from urdftool.kinematics.tree import beside_the_tree, roots

    beside = set(beside_the_tree(robot))
    several = roots(robot)
    several = {name: i for i, name in enumerate(several, 1)} if len(several) > 1 else {}
    marked = findings_by_element(robot, findings)
    for joint in robot.children("joint"):
        child = joint.find("child")
        if child is not None and ("joint", joint.get("name", "")) in marked:
            marked.setdefault(("link", child.get("link", "")), []).extend(
                marked[("joint", joint.get("name", ""))])
    lines = [f"digraph {_quote(robot.name or 'robot')} {{",
             "  rankdir=TB;",
             '  node [shape=box, style="rounded,filled", fillcolor="#ffffff", '
             'fontname="Helvetica", fontsize=11];',
             '  edge [fontname="Helvetica", fontsize=9];']
    for name in robot.links:
        attributes = _colour(marked.get(("link", name)), "color", "fillcolor")
        if name in beside:
            attributes = {**BESIDE, **attributes, "label": (name, "(beside the tree)"),
                          "tooltip": (BESIDE_TOOLTIP, *attributes.get("tooltip", ()))}
        elif name in several:  # (no tree: each root and what hangs from it drawn apart)
            attributes = {**attributes, "label": (name, f"(root {several[name]} of "
                                                        f"{len(several)})"),
                          "tooltip": (SEVERAL_ROOTS, *attributes.get("tooltip", ()))}
        lines.append(f"  {_quote(name)}{_attributes(attributes)};")
    missing = []  # links joints name that the robot does not have: drawn as missing
    for joint in robot.children("joint"):
        for end in (joint.find("parent"), joint.find("child")):
            name = end.get("link") if end is not None else None
            if name and name not in robot.links and name not in missing:
                missing.append(name)
                attributes = {**MISSING, "label": (name, "(missing)"),
                              "tooltip": f"no link named '{name}'"}
                lines.append(f"  {_quote(name)}{_attributes(attributes)};")
    for joint in robot.children("joint"):
        parent, child = joint.find("parent"), joint.find("child")
        if parent is None or child is None or not parent.get("link") or not child.get("link"):
            continue
        attributes = {"label": joint_label(joint),
                      **_colour(marked.get(("joint", joint.get("name", ""))), "color",
                                "fontcolor")}
        if child.get("link") in beside:  # (its parent too: beside, or the tree would reach it)
            attributes = {"style": "dashed", "color": BESIDE["color"],
                          "fontcolor": BESIDE["fontcolor"], **attributes}
        lines.append(f"  {_quote(parent.get('link'))} -> {_quote(child.get('link'))}"
                     f"{_attributes(attributes)};")
    lines.append("}")
    return "\n".join(lines) + "\n"


MISSING = {"style": "dashed", "color": "#c62828", "fontcolor": "#c62828"}  # a link not defined
BESIDE = {"style": "rounded,dashed,filled", "color": "#757575", "fontcolor": "#757575"}
SEVERAL_ROOTS = ("a root: no joint has it as its child, and the robot has several, which "
                 "urdfdom refuses (a robot is one tree): a joint is missing between them")
BESIDE_TOOLTIP = ("beside the tree: no joint from the root reaches it, so urdfdom's model "
                  "(and every other urdftool command) leaves it out")


def joint_label(joint) -> tuple[str, str]:
    """The label's lines: ``name``, then the type and, for limited joints, ``[lower, upper]
    unit``."""
    kind = joint.get("type", "?")
    second = kind
    limit = joint.find("limit")
    if kind in UNITS and limit is not None:
        lower, upper = _short(limit.get("lower", "0")), _short(limit.get("upper", "0"))
        second += f" [{lower}, {upper}] {UNITS[kind]}"
    return joint.get("name", "?"), second


def _short(text: str) -> str:
    """A limit with 4 significant digits; as written when it is not a number."""
    try:
        from urdftool.numbers import number

        return number(float(text))
    except ValueError:
        return text


def _colour(findings, line_key: str, fill_key: str) -> dict:
    if not findings:
        return {}
    worst = min((f.severity for f in findings), key=_RANK.__getitem__)
    if worst not in COLOURS:
        return {}
    outline, fill = COLOURS[worst]
    tooltip = tuple(f"{f.code} {f.message}" for f in findings)
    fill_value = fill if fill_key == "fillcolor" else outline
    return {line_key: outline, fill_key: fill_value, "penwidth": "2", "tooltip": tooltip}


def _attributes(attributes: dict) -> str:
    if not attributes:
        return ""
    return " [" + ", ".join(f"{key}={_quote(*value) if isinstance(value, tuple) else _quote(value)}"
                            for key, value in attributes.items()) + "]"


def write(dot: str, output: Path) -> Path:
    """Write ``dot`` to ``output``: as is for ``.dot``/``.gv``, rendered by Graphviz's ``dot``
    for ``.svg``/``.png``/``.pdf``. Returns the file written; raises DotMissing (after writing
    the DOT beside ``output``) when ``dot`` is not installed, ValueError for other suffixes.
    Written with :func:`urdftool.description.files.write_file`: a link planted at the path is replaced,
    never followed (``dot`` renders to a pipe, not to the path)."""
    from urdftool.description.files import write_file

    suffix = output.suffix.lower()
    if suffix in (".dot", ".gv"):
        write_file(output, dot)
        return output
    if suffix not in RENDERED:
        raise ValueError(f"cannot write '{output.name}': use .dot, .gv, {', '.join(RENDERED)}")
    program = shutil.which("dot")
    if program is None:
        fallback = output.with_suffix(".dot")
        write_file(fallback, dot)
        raise DotMissing(str(fallback))
    done = subprocess.run([program, f"-T{suffix[1:]}"], input=dot.encode(),
                          capture_output=True, check=False)
    if done.returncode != 0:
        from urdftool.guardian import ended

        said = done.stderr.decode(errors="replace").strip()  # (killed: the signal that ended it)
        raise ValueError("dot failed: " + (said if said and done.returncode > 0
                                           else ended(done.returncode)))
    write_file(output, done.stdout)
    return output
