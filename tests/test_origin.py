"""Where urdftool came from (urdftool/origin.py): the install commands it prints work from that
source, and every rule link of every output (SARIF, rdjson, the language server) is the rule's
generated page: in this checkout by default, the git host's page of it at the installed commit,
or the address URDFTOOL_DOCS_URL gives."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from conftest import ROOT
from rule_links import assert_rule_page, page_of
from urdftool import origin
from urdftool.diagnostics import Finding, Location, Severity
from urdftool.lint.engine import FileResult
from urdftool.lint.rules import CATALOGUE
from urdftool.origin import Origin


@pytest.fixture
def came_from(monkeypatch):
    """Pretend urdftool came from somewhere else."""
    monkeypatch.delenv(origin.DOCS_URL_VARIABLE, raising=False)

    def pretend(where: Origin):
        monkeypatch.setattr(origin, "origin", lambda: where)

    return pretend


def _findings():
    return [FileResult("a.urdf", [Finding(rule.code, rule.name, rule.severity, "m",
                                          Location("a.urdf", 1)) for rule in CATALOGUE])]


def _links(monkeypatch) -> dict[str, list[tuple[str, str | None]]]:
    """(code, link) of every rule in each output that links rule pages."""
    from pygls.workspace.position_codec import PositionCodec

    from urdftool import server
    from urdftool.report import rdjson_format, sarif_format

    results = _findings()
    sarif = sarif_format.as_dict(results)["runs"][0]["tool"]["driver"]["rules"]
    rdjson = rdjson_format.as_dict(results)["diagnostics"]
    by_path = server.diagnostics_by_path([f for r in results for f in r.findings],
                                         lambda path: "<robot/>\n", PositionCodec())
    diagnostics = [d for shown in by_path.values() for d, _ in shown]
    hover = [rule.code for rule in CATALOGUE]
    return {
        "sarif": [(r["id"], r.get("helpUri")) for r in sarif],
        "rdjson": [(d["code"]["value"], d["code"].get("url")) for d in rdjson],
        "lsp diagnostics": [(d.code, d.code_description and d.code_description.href)
                            for d in diagnostics],
        "lsp hover": [(code, _markdown_link(server.rule_markdown(CATALOGUE.get(code))))
                      for code in hover],
    }


def _markdown_link(markdown: str) -> str | None:
    return markdown.rsplit("](", 1)[1].rstrip(")") if "](" in markdown else None


@pytest.mark.parametrize("where", ["checkout", "github", "gitlab", "setting"])
def test_every_rule_link_of_every_output_is_a_generated_page(came_from, monkeypatch, where):
    if where == "github":
        came_from(Origin(url="https://github.com/you/urdftool.git", commit="0123abc"))
    elif where == "gitlab":
        came_from(Origin(url="https://gitlab.com/team/tools/urdftool", commit="v0.1.0"))
    elif where == "setting":
        monkeypatch.setenv(origin.DOCS_URL_VARIABLE, "https://docs.example.org/urdftool/docs/rules")
    links = _links(monkeypatch)
    for output, pairs in links.items():
        assert len({code for code, _ in pairs}) == len(CATALOGUE), output
        for code, url in pairs:
            assert_rule_page(url, code)
    first = links["sarif"][0][1]
    assert first == {
        "checkout": (ROOT / "docs" / "rules" / "U001.md").as_uri(),
        "github": "https://github.com/you/urdftool/blob/0123abc/docs/rules/U001.md",
        "gitlab": "https://gitlab.com/team/tools/urdftool/-/blob/v0.1.0/docs/rules/U001.md",
        "setting": "https://docs.example.org/urdftool/docs/rules/U001.md",
    }[where]


@pytest.mark.parametrize("where", [Origin(), Origin(url="https://git.example.com/you/urdftool",
                                                   commit="0123abc")])
def test_no_link_rather_than_a_dead_one(came_from, where):
    """Nothing says where the pages are (a wheel of unknown origin, an unknown git host): the
    outputs carry no link, and SARIF stays valid for code scanning."""
    came_from(where)
    from urdftool.report import rdjson_format, sarif_format

    results = _findings()
    log = sarif_format.as_dict(results)
    assert "informationUri" not in log["runs"][0]["tool"]["driver"]
    assert all("helpUri" not in rule for rule in log["runs"][0]["tool"]["driver"]["rules"])
    import sarif_schema

    sarif_schema.validate(json.loads(json.dumps(log)))
    rdjson = rdjson_format.as_dict(results)
    assert "url" not in rdjson["source"]
    assert all("url" not in d["code"] for d in rdjson["diagnostics"])


def test_the_setting_must_be_an_address(came_from, monkeypatch):
    came_from(Origin())
    for value in ("javascript:alert(1)", "docs/rules", "https://", " ",
                  "https://x.org/\x1b]8;;evil\x07", 'https://x.org/a"b', "https://x.org/<x>",
                  "https://x.org/a\u202eb", "https://x.org/a b"):
        monkeypatch.setenv(origin.DOCS_URL_VARIABLE, value)
        assert origin.rule_url("U204") is None, value
    monkeypatch.setenv(origin.DOCS_URL_VARIABLE, "file:///srv/urdftool/docs/rules/")
    assert origin.rule_url("U204") == "file:///srv/urdftool/docs/rules/U204.md"


def test_this_checkout_is_where_the_tests_run_from():
    """The default the other tests rely on: the tests run urdftool from this checkout."""
    assert origin.origin().folder == ROOT
    assert page_of(origin.docs_index_url()) == ROOT / "docs" / "rules" / "README.md"


@pytest.mark.parametrize(("where", "expected"), [
    (Origin(folder=Path("/src/urdftool"), editable=True),
     "pip install -e '/src/urdftool[analysis]'"),
    (Origin(folder=Path("/src/my tools/urdftool")),
     "pip install '/src/my tools/urdftool[analysis]'"),
    (Origin(url="https://github.com/you/urdftool", commit="0123abc"),
     "pip install 'urdftool[analysis] @ git+https://github.com/you/urdftool@0123abc'"),
    (Origin(), "pip install '/path/to/urdftool[analysis]'  (in a clone of the urdftool repository)"),
])
def test_install_commands_name_the_source_urdftool_came_from(came_from, where, expected):
    came_from(where)
    assert origin.install_command("analysis") == expected


def test_origin_reads_pips_record(monkeypatch, tmp_path):
    """direct_url.json (PEP 610) as pip writes it for a git URL and for a folder."""
    import importlib.metadata

    records = {"git": {"url": "https://github.com/you/urdftool", "vcs_info": {
        "vcs": "git", "commit_id": "0123abc", "requested_revision": "v0.1.0"}},
        "folder": {"url": tmp_path.as_uri(), "dir_info": {}}}
    (tmp_path / "pyproject.toml").write_text("")

    class Distribution:
        def __init__(self, record):
            self.record = record

        def read_text(self, name):
            return json.dumps(self.record) if name == "direct_url.json" else None

    monkeypatch.setattr(origin.Path, "is_file", lambda self: self == tmp_path / "pyproject.toml")
    for kind, expected in (("git", Origin(url="https://github.com/you/urdftool", commit="0123abc")),
                           ("folder", Origin(folder=tmp_path))):
        monkeypatch.setattr(importlib.metadata, "distribution",
                            lambda name, record=records[kind]: Distribution(record))
        origin.origin.cache_clear()
        try:
            assert origin.origin() == expected
        finally:
            origin.origin.cache_clear()
