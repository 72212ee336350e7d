"""Mutations of real robot descriptions for the fuzz harness (hypothesis strategies).

A case is a seed robot (a real file, so its includes, packages and YAML resolve) and the bytes
that replace it: the seed with elements deleted, duplicated or moved, attributes and numbers
corrupted, xacro expressions and entities injected, or its bytes truncated or flipped; or its
``<mesh>`` elements pointed at files outside the repository, at files that are not meshes, at
the crafted meshes of tests/fuzz/meshes/ (lying headers, bad indices, NaN vertices, flat or
empty meshes, COLLADA with entities, glTF buffers outside the folder), or given odd scales.
"""

from __future__ import annotations

import csv
import os
from dataclasses import dataclass, field
from pathlib import Path

from hypothesis import strategies as st
from lxml import etree

ROOT = Path(__file__).resolve().parents[2]
CORPUS = Path(os.environ.get("URDFTOOL_CORPUS", ROOT.parent / "shared" / "corpus"))
if not CORPUS.is_dir():
    CORPUS = Path("/work/shared/corpus")


@dataclass(frozen=True)
class Seed:
    path: Path
    args: dict = field(default_factory=dict, hash=False, compare=False)

    def __repr__(self):
        return f"Seed({self.path})"


def seeds(max_bytes: int | None = None) -> list[Seed]:
    """Real robots: the bundled ones, and the corpus files that load (with their xacro args)."""
    found = [Seed(p) for p in sorted((ROOT / "robots").glob("*/*.urdf.xacro"))]
    table = CORPUS / "CHECKS.tsv"
    if table.is_file():
        with open(table, newline="") as handle:
            for row in csv.DictReader(handle, delimiter="\t"):
                if row["kind"] == "xacro" and not row["xacro_2.1.1_with_find_resolved"].startswith("ok"):
                    continue
                pairs = (w.partition(":=") for w in row["xacro_args"].split())
                args = {n: v.replace("<corpus>", str(CORPUS)) for n, _, v in pairs}
                found.append(Seed(CORPUS / row["path"], args))
    if max_bytes:
        found = [s for s in found if s.path.stat().st_size <= max_bytes]
    return found


# numbers at a float's edges, where Python's arithmetic raises or rounds to 0 or infinity:
# cubed (a sphere's volume), squared twice (a tensor), summed (a bound); 1e103 and 5e-324
# found U309-U316 crashing (numbers.power, solids.computed)
EDGE_NUMBERS = ["1e103", "-1e103", "1e155", "1e200", "1.7e308", "-1.7e308", "5e-324", "1e-108",
                "1e-200", "-0.0", "2.2250738585072014e-308"]

NASTY_VALUES = [
    "", " ", "nan", "-nan", "inf", "-inf", "1e309", "-0", "0x10", "1_000", "abc", "1 2", "1 2 3 4",
    "1,2,3", "  1   2   3  ", "1e-400", "9" * 400, "\u00e9\u4e2d", "\t\n", "&amp;", "<", "]]>",
    "${x}", "${1/0}", "${undefined_property}", "${'a' * 10**8}", "${10**10**10}",
    "${().__class__}", "${(lambda: 0).__globals__}", "$(find no_such_pkg)", "$(env HOME)",
    "$(optenv URDFTOOL_NOPE default)", "$(arg nope)", "$(cwd)", "${xacro.load_yaml('/etc/passwd')}",
    "package://no_such_pkg/mesh.stl", "file:///etc/passwd", "a" * 70000, "continuous", "fixed",
    "floating", "planar", "prismatic", "revolute", "base_link", "true", "false",
]
NASTY_TAGS = ["link", "joint", "robot", "xacro:macro", "xacro:include", "xacro:property",
              "xacro:if", "xacro:insert_block", "xacro:call", "xacro:element", "xacro:attribute",
              "xacro:arg", "gazebo", "transmission", "mimic", "limit", "origin", "axis",
              "parent", "child", "inertial", "visual", "collision", "geometry", "mesh",
              "xacro:no_such_macro", "a.b", "x-y"]
INJECTIONS = [
    b'<!DOCTYPE robot [<!ENTITY e SYSTEM "file:///etc/passwd">]>\n',
    b'<!DOCTYPE robot [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">]>\n',
    b'<!DOCTYPE robot SYSTEM "http://127.0.0.1:9/evil.dtd">\n',
    b'<!DOCTYPE robot [<!ENTITY % p SYSTEM "file:///etc/passwd"> %p;]>\n',
    b'<?xml-stylesheet href="file:///etc/passwd"?>\n',
]


MESHES = Path(__file__).resolve().parent / "meshes"
OUTSIDE_MESHES = ["../../../../../../../../etc/passwd", "file:///etc/passwd", "/etc/passwd",
                  "file:///dev/zero", "file:///proc/self/environ", "../../../../../../../tmp/x.stl",
                  "file://", "package://", "package://../../etc/passwd", "http://127.0.0.1:9/x.stl",
                  "", ".", "..", "meshes", "mesh.stl\x00"]
SCALES = ["0 0 0", "1 1", "nan nan nan", "-1 -1 -1", "1e30 1e30 1e30", "1e-30 1e-30 1e-30",
          "1 0 1", "inf 1 1", "abc", "0.001 0.001 0.001", "1000 1000 1000"]


def _elements(root):
    return [e for e in root.iter() if isinstance(e.tag, str)]


@st.composite
def tree_mutation(draw, data: bytes) -> bytes:
    """Parse the seed (no entities, no network) and change its element tree."""
    parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False,
                             remove_comments=False, huge_tree=False)
    root = etree.fromstring(data, parser)
    for _ in range(draw(st.integers(1, 4))):
        elements = _elements(root)
        target = elements[draw(st.integers(0, len(elements) - 1))]
        kind = draw(st.sampled_from(["delete", "duplicate", "move", "attribute", "number",
                                     "retag", "text", "drop_attribute", "nest"]))
        parent = target.getparent()
        if kind == "delete" and parent is not None:
            parent.remove(target)
        elif kind == "duplicate" and parent is not None:
            parent.insert(parent.index(target), _copy(target))
        elif kind == "move" and parent is not None:
            others = _elements(root)
            destination = others[draw(st.integers(0, len(others) - 1))]
            if target not in destination.iterancestors() and destination is not target:
                parent.remove(target)
                destination.insert(draw(st.integers(0, len(destination))), target)
        elif kind == "attribute":
            names = list(target.attrib) or ["name"]
            name = draw(st.sampled_from(names + ["name", "type", "xyz", "value", "filename",
                                                 "params", "link", "joint"]))
            value = draw(st.sampled_from(NASTY_VALUES) | st.text(max_size=20))
            target.set(name, _xml_safe(value))
        elif kind == "number" and target.attrib:
            name = draw(st.sampled_from(sorted(target.attrib)))
            words = target.get(name).split() or ["0"]
            index = draw(st.integers(0, len(words) - 1))
            words[index] = draw(st.sampled_from(["-1", "0", "1e30", "-1e30", "nan", "1.5.2",
                                                 "--1", "1e", "+", str(draw(st.floats()))])
                                | st.sampled_from(EDGE_NUMBERS))
            target.set(name, " ".join(words))
        elif kind == "retag":
            tag = draw(st.sampled_from(NASTY_TAGS))
            if tag.startswith("xacro:"):
                tag = "{http://www.ros.org/wiki/xacro}" + tag[6:]
            target.tag = tag
        elif kind == "text":
            target.text = _xml_safe(draw(st.sampled_from(NASTY_VALUES)))
        elif kind == "drop_attribute" and target.attrib:
            del target.attrib[draw(st.sampled_from(sorted(target.attrib)))]
        elif kind == "nest":
            depth = draw(st.integers(1, 3000))
            inner = target
            for _ in range(depth):
                inner = etree.SubElement(inner, "link")
    return etree.tostring(root, xml_declaration=True, encoding="utf-8")


def _copy(element):
    import copy

    return copy.deepcopy(element)


def _xml_safe(text: str) -> str:
    return "".join(c for c in text if c in "\t\n\r" or (" " <= c <= "\ud7ff")
                   or ("\ue000" <= c <= "\ufffd"))


@st.composite
def byte_mutation(draw, data: bytes) -> bytes:
    kind = draw(st.sampled_from(["truncate", "flip", "insert", "inject", "expression"]))
    if kind == "truncate":
        return data[:draw(st.integers(0, len(data)))]
    if kind == "flip":
        buffer = bytearray(data)
        for _ in range(draw(st.integers(1, 8))):
            buffer[draw(st.integers(0, len(buffer) - 1))] = draw(st.integers(0, 255))
        return bytes(buffer)
    if kind == "insert":
        at = draw(st.integers(0, len(data)))
        return data[:at] + draw(st.binary(max_size=16) | st.sampled_from(
            [b"<", b">", b"&", b"\"", b"${", b"}", b"$(", b"<!--", b"]]>", b"\xff\xfe", b"\x00"]
        )) + data[at:]
    if kind == "inject":
        injection = draw(st.sampled_from(INJECTIONS))
        if data.startswith(b"<?xml"):
            end = data.find(b"?>") + 2
            return data[:end] + b"\n" + injection + data[end:]
        return injection + data
    at = data.find(b'"', draw(st.integers(0, len(data))))
    if at < 0:
        return data
    expression = draw(st.sampled_from([v for v in NASTY_VALUES if "$" in v]))
    return data[:at + 1] + _xml_safe(expression).replace("'", "&apos;").encode() + data[at + 1:]


@st.composite
def mesh_mutation(draw, data: bytes, seed_path: Path) -> bytes:
    """Point ``<mesh>`` elements (existing ones, or one added to a link) at hostile files."""
    parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False)
    root = etree.fromstring(data, parser)
    meshes = [e for e in root.iter("mesh")]
    links = [e for e in root.iter("link")]
    if links and (not meshes or draw(st.booleans())):
        link = links[draw(st.integers(0, len(links) - 1))]
        holder = etree.SubElement(link, draw(st.sampled_from(["collision", "visual"])))
        meshes.append(etree.SubElement(etree.SubElement(holder, "geometry"), "mesh",
                                       filename="x.stl"))
        if draw(st.booleans()) and link.find("inertial") is None:  # the inertia rules read it
            inertial = etree.SubElement(link, "inertial")
            etree.SubElement(inertial, "mass", value="1")
            etree.SubElement(inertial, "inertia", ixx="1", iyy="1", izz="1", ixy="0", ixz="0",
                             iyz="0")
    crafted = sorted(p.name for p in MESHES.iterdir())
    inside = ROOT in seed_path.resolve().parents  # relative paths to MESHES stay in the repo
    for mesh in meshes:
        kind = draw(st.sampled_from(["crafted", "outside", "scale"] if inside
                                    else ["outside", "scale"]))
        if kind == "crafted":
            target = MESHES / draw(st.sampled_from(crafted))
            mesh.set("filename", os.path.relpath(target, seed_path.parent))
        elif kind == "outside":
            mesh.set("filename", _xml_safe(draw(st.sampled_from(OUTSIDE_MESHES))))
        if kind == "scale" or draw(st.integers(0, 3)) == 0:
            mesh.set("scale", draw(st.sampled_from(SCALES)))
    return etree.tostring(root, xml_declaration=True, encoding="utf-8")


def mutant(seed_list: list[Seed]):
    """A strategy for (seed, mutated bytes)."""

    @st.composite
    def build(draw):
        kind = draw(st.sampled_from(["tree", "bytes", "mesh"]))
        pool = seed_list
        if kind == "mesh" and draw(st.booleans()):  # the crafted meshes only reach own robots
            pool = [s for s in seed_list if ROOT in s.path.resolve().parents] or seed_list
        seed = draw(st.sampled_from(pool))
        data = seed.path.read_bytes()
        strategy = {"tree": tree_mutation, "bytes": byte_mutation}.get(kind)
        mutated = draw(strategy(data) if strategy else mesh_mutation(data, seed.path))
        return seed, mutated

    return build()
