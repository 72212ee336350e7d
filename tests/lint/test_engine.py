"""The engine: selection, stamping, and a crashing rule or loader as U900, never a traceback."""

from __future__ import annotations

from conftest import CASES
from urdftool.lint import engine
from urdftool.lint.engine import CheckOptions, Selection, check_file
from urdftool.lint.rules import REGISTRY, Rule, Severity, all_rules

ROBOT = CASES / "U204_inverted_limits.urdf"


def test_a_crashing_rule_is_u900_and_the_other_rules_still_run(monkeypatch):
    def broken(robot):
        yield robot.root, "about to fail"
        raise ZeroDivisionError("boom")

    all_rules()  # load the catalogue before replacing one entry
    original = REGISTRY["U204"]
    monkeypatch.setitem(REGISTRY, "U204", Rule("U204", original.name, original.severity, broken,
                                              original.doc))
    monkeypatch.setattr(engine, "all_rules", lambda: [REGISTRY[c] for c in sorted(REGISTRY)])
    findings = check_file(str(ROBOT), CheckOptions()).findings
    crash = [f for f in findings if f.code == "U900"]
    assert len(crash) == 1
    assert "rule U204 (inverted-limits) crashed: ZeroDivisionError: boom" in crash[0].message
    assert crash[0].file.endswith("U204_inverted_limits.urdf")
    assert any(f.code == "U204" and f.message == "about to fail" for f in findings)


def test_a_crashing_loader_is_u900_naming_the_file(monkeypatch):
    import urdftool.description.load

    def explode(*args, **kwargs):
        raise RecursionError("deep")

    monkeypatch.setattr(urdftool.description.load, "load", explode)
    [finding] = check_file(str(ROBOT), CheckOptions()).findings
    assert finding.code == "U900" and finding.severity is Severity.ERROR
    assert finding.message.startswith("loading crashed: RecursionError: deep")


def test_load_failures_are_reported_whatever_the_selection():
    result = check_file(str(CASES / "U001_malformed_xml.urdf"),
                        CheckOptions(selection=Selection(ignore=("U0",))))
    assert [f.code for f in result.findings] == ["U001"]


def test_selection_by_code_prefix_and_name():
    assert Selection(select=("U2",)).allows("U204")
    assert not Selection(select=("U2",)).allows("U101")
    assert not Selection(ignore=("inverted-limits",)).allows("U204")
    assert Selection(ignore=("inverted-limits",)).allows("U205")
