"""The generated documentation (urdftool/docs.py): a page per rule, the index, the targets table;
current in the checkout, and the generator the only source of docs/rules/."""

from __future__ import annotations

import re
import shutil

import pytest

from conftest import ROOT
from urdftool import docs
from urdftool.lint.catalogue import Catalogue
from urdftool.lint.rules import CATALOGUE
from urdftool.records import replace


def test_the_generated_docs_are_current():
    changed = docs.stale(ROOT)
    assert not changed, (f"generated documentation out of date: run `{docs.COMMAND}` "
                         f"(python -m urdftool.docs); stale: {', '.join(changed)}")


def test_every_rule_has_a_page_and_a_row_in_the_index():
    index = (ROOT / docs.INDEX).read_text(encoding="utf-8")
    for rule in CATALOGUE:
        page = (ROOT / "docs" / "rules" / f"{rule.code}.md").read_text(encoding="utf-8")
        assert page.splitlines()[2] == f"# {rule.code} {rule.name}"
        assert f"| {rule.severity.value} |" in page
        assert f"[{rule.code}]({rule.code}.md) | {rule.name} |" in index


@pytest.fixture
def copy(tmp_path):
    """A checkout's documentation and cases, copied: the generator writes there."""
    for name in ("docs", "tests/cases"):
        shutil.copytree(ROOT / name, tmp_path / name, symlinks=True)
    return tmp_path


def test_a_changed_docstring_makes_its_page_stale_and_make_docs_rewrites_it(copy, monkeypatch):
    changed = [replace(r, written="Changed.\n\nWhy.") if r.code == "U204" else r
               for r in CATALOGUE]
    monkeypatch.setattr(docs, "CATALOGUE", Catalogue(changed))
    assert docs.stale(copy) == ["docs/rules/U204.md", docs.INDEX]
    assert docs.write(copy) == ["docs/rules/U204.md", docs.INDEX]
    assert docs.stale(copy) == []
    assert "Changed." in (copy / "docs/rules/U204.md").read_text()


def test_a_missing_page_a_leftover_page_and_a_changed_case_are_stale(copy):
    (copy / "docs/rules/U204.md").unlink()
    (copy / "docs/rules/U999.md").write_text("a rule that no longer exists")
    (copy / "docs/rules/notes.md").write_text("written by hand")
    case = copy / "tests/cases/U206_axis_not_unit.urdf"
    case.write_text(case.read_text() + "<!-- changed -->\n")
    assert docs.stale(copy) == ["docs/rules/U204.md", "docs/rules/U206.md",
                                "remove docs/rules/U999.md", "remove docs/rules/notes.md"]
    changed = docs.write(copy)
    assert "remove docs/rules/U999.md" in changed and not (copy / "docs/rules/U999.md").exists()
    assert (copy / "docs/rules/notes.md").exists()  # a page a person wrote: left, and still stale
    assert docs.stale(copy) == ["remove docs/rules/notes.md"]


def test_the_check_command_names_the_command_that_regenerates(copy, monkeypatch, capsys):
    (copy / "docs/rules/U204.md").write_text("edited by hand")
    monkeypatch.setattr(docs, "checkout", lambda: copy)
    assert docs.main(["--check"]) == 1
    out = capsys.readouterr().out
    assert "stale: docs/rules/U204.md" in out and "make docs" in out
    assert docs.main([]) == 0 and docs.main(["--check"]) == 0


def test_prose_escapes_tags_and_links_codes_but_leaves_code_spans():
    text = docs._markdown_text("reads <visual> meshes, see U414 and U999.\n"
                               "Bad: ``<axis xyz='0 0 2'/>`` U204\nGood: x", link="")
    assert "reads &lt;visual> meshes, see [U414](U414.md) and U999." in text
    assert "\n\n**Bad:** ``<axis xyz='0 0 2'/>`` [U204](U204.md)\n\n**Good:** x" in text


def test_case_files_are_shown_except_links_binaries_and_long_lines():
    page = (ROOT / "docs/rules/U017.md").read_text()
    assert "a symbolic link to" in page  # never followed
    assert "not shown" in (ROOT / "docs/rules/U003.md").read_text()  # binary
    long_line = (ROOT / "docs/rules/U933.md").read_text()
    assert re.search(r"… \(\d+ characters\)", long_line)


# ---- the hand-written pages: size, links, index -------------------------------------------------

README_LIMIT = 15_000  # [bytes]: what it is, the two commands, the five things, links


def test_the_readme_stays_short():
    size = len((ROOT / "README.md").read_bytes())
    assert size <= README_LIMIT, (f"README.md is {size} bytes, over {README_LIMIT}: move the "
                                  "detail into a page under docs/ and link it")


def _pages():
    return [ROOT / "README.md", ROOT / "CHANGELOG.md", *sorted((ROOT / "docs").rglob("*.md"))]


def _slug(heading: str) -> str:
    """GitHub's anchor of a heading: lower case, punctuation but ``-`` and ``_`` dropped, spaces
    made ``-``."""
    text = re.sub(r"`|\*\*|\[([^]]*)\]\([^)]*\)", r"\1", heading.strip()).lower()
    return re.sub(r"[^\w\- ]", "", text).replace(" ", "-")


def _anchors(path) -> set[str]:
    text = re.sub(r"```.*?```", "", path.read_text(encoding="utf-8"), flags=re.S)
    anchors, seen = set(), {}
    for heading in re.findall(r"^#{1,6} (.+)$", text, re.M):
        slug = _slug(heading)
        anchors.add(slug if slug not in seen else f"{slug}-{seen[slug]}")
        seen[slug] = seen.get(slug, 0) + 1
    return anchors | set(re.findall(r'<a id="([^"]+)"', text))


def test_every_relative_link_and_anchor_resolves():
    broken = []
    for page in _pages():
        text = re.sub(r"```.*?```", "", page.read_text(encoding="utf-8"), flags=re.S)
        for target in re.findall(r"\]\(([^)\s]+)\)", text):
            if re.match(r"[a-z]+:", target):
                continue  # an address elsewhere
            path, _, anchor = target.partition("#")
            resolved = (page.parent / path).resolve() if path else page
            if not resolved.is_relative_to(ROOT.resolve()):  # found here, absent in a clone
                broken.append(f"{page.relative_to(ROOT)}: {target} (outside the repository)")
            elif not resolved.exists():
                broken.append(f"{page.relative_to(ROOT)}: {target} (no such file)")
            elif anchor and resolved.suffix == ".md" and anchor not in _anchors(resolved):
                broken.append(f"{page.relative_to(ROOT)}: {target} (no such heading)")
    assert not broken, "\n".join(broken)


def test_every_page_is_in_the_index():
    """docs/README.md lists every page under docs/ (the rule pages through their own index)."""
    index = (ROOT / "docs" / "README.md").read_text(encoding="utf-8")
    linked = set(re.findall(r"\]\(([^)#\s]+)", index))
    missing = [p.relative_to(ROOT / "docs").as_posix() for p in (ROOT / "docs").glob("*.md")
               if p.name != "README.md" and p.relative_to(ROOT / "docs").as_posix() not in linked]
    assert not missing, f"pages not linked from docs/README.md: {missing}"
