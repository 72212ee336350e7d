"""The README rules table is generated from the rule docstrings and must be current."""

import pytest

from conftest import ROOT
from urdftool.lint import rules
from urdftool.docs import with_table
from urdftool.lint.rules import Severity, all_rules


def test_readme_rules_table_is_current():
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    assert text == with_table(text), "README rules table is stale: run python -m urdftool.docs README.md"


def test_every_rule_is_documented():
    for rule in all_rules():
        assert rule.doc and rule.summary.endswith("."), f"{rule.code} needs a docstring summary"
        assert rule.name == rule.name.lower() and " " not in rule.name


def test_registry_is_sorted_and_unique(monkeypatch):
    codes = [r.code for r in all_rules()]
    names = [r.name for r in all_rules()]
    assert codes == sorted(set(codes))
    assert len(names) == len(set(names))
    # all_rules() lists a dict by sorted key, so uniqueness of codes rests on registration
    monkeypatch.setattr(rules, "REGISTRY", dict(rules.REGISTRY))
    for code in ("U204", "U2040", "X204", "U2x4"):  # taken, too long, no U, not digits
        with pytest.raises(ValueError):
            rules.declare(code, "some-name", Severity.ERROR, "Summary.")
