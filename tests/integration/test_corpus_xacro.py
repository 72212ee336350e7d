"""Real robots expand exactly as with plain xacro: every corpus xacro file that xacro 2.1.1
expands gives the same elements through urdftool's sandboxed expander (robots from the shared
``corpus_run``), without reading a file outside the repository and its packages."""

from __future__ import annotations

import csv
import re
import xml.dom.minidom
from pathlib import Path

import pytest

from conftest import CORPUS, corpus_args, entry_id
from urdftool.description.load import load
from urdftool.description.packages import PackageResolver


def _corpus_xacro_rows() -> list[tuple[str, str]]:
    """(path, xacro_args as written in CHECKS.tsv) of the xacro files plain xacro expands."""
    if not CORPUS.is_dir():
        return []
    with open(CORPUS / "CHECKS.tsv", newline="") as handle:
        rows = list(csv.DictReader(handle, delimiter="\t"))
    return [(row["path"], row["xacro_args"]) for row in rows
            if row["kind"] == "xacro" and row["xacro_2.1.1_with_find_resolved"].startswith("ok")]


def _plain_xacro(path, args):
    """What real xacro produces, with $(find) resolved like urdftool does."""
    import xacro
    from xacro import substitution_args

    resolver = PackageResolver(start=path.parent)
    saved = substitution_args._eval_find
    substitution_args._eval_find = lambda package: str(resolver.find(package))
    try:
        xacro.init_stacks(str(path))
        xacro.all_includes = []
        doc = xml.dom.minidom.parseString(path.read_bytes())
        xacro.process_doc(doc, mappings=dict(args), verbosity=0)
    finally:
        substitution_args._eval_find = saved
        xacro.init_stacks(None)
        xacro.substitution_args_context.clear()
    return doc.documentElement


def _signature_dom(node):
    items = []
    for element in node.getElementsByTagName("*"):
        attributes = sorted((k, v) for k, v in element.attributes.items()
                            if not k.startswith("xmlns"))
        text = "".join(c.data for c in element.childNodes if c.nodeType == c.TEXT_NODE).strip()
        items.append((element.tagName.split(":")[-1], tuple(attributes), text))
    return items


def _signature_lxml(root):
    from lxml import etree

    items = []
    for element in root.iter(etree.Element):
        if element is root:
            continue
        attributes = sorted((etree.QName(k).localname if k.startswith("{") else k, v)
                            for k, v in element.attrib.items())
        items.append((etree.QName(element).localname, tuple(attributes),
                      (element.text or "").strip()))
    return items


ENVIRONMENT = re.compile(r"\$\((?:env|optenv)\s")


@pytest.mark.parametrize("relative, args", _corpus_xacro_rows() or [("none", "")])
def test_corpus_xacro_expands_as_with_plain_xacro(relative, args, corpus_run):
    _, result = corpus_run[entry_id((relative, corpus_args(args)))]
    robot = result.robot
    assert robot is not None, [f"{f.location} {f.code} {f.message}" for f in result.findings]
    path = CORPUS / relative
    assert _signature_lxml(robot.root) == _signature_dom(_plain_xacro(path, corpus_args(args)))
    # The shared run reads like `urdftool check` (environment allowed). Under --no-env the
    # expansion is the same when nothing was read from outside and no $(env)/$(optenv) is used.
    assert not [note for note in robot.notes if note.kind == "outside-file"]
    assert not [f for f in robot.files if ENVIRONMENT.search(Path(f).read_text(errors="replace"))]


def test_corpus_has_the_46_expanding_xacro_files(corpus):
    assert len(_corpus_xacro_rows()) == 46


def test_found_packages_are_allowed_roots(corpus):
    relative, args = next(row for row in _corpus_xacro_rows() if row[0].startswith("ur_gazebo"))
    robot = load(corpus / relative, xacro_args=corpus_args(args), allow_env=False)
    assert not [note for note in robot.notes if note.kind == "outside-file"]
    assert any("ur_description" in f for f in robot.files)
