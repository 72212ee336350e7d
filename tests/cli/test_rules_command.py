"""``urdftool rules``: the catalogue and each rule's documentation."""

from __future__ import annotations

from urdftool.lint.rules import CATALOGUE


def test_list_has_every_rule(run_cli):
    result = run_cli("rules")
    assert result.exit_code == 0
    for rule in CATALOGUE:
        assert rule.code in result.stdout and rule.name in result.stdout
    assert "``" not in result.stdout


def test_by_code_or_name_prints_the_docstring(run_cli):
    by_code, by_name = run_cli("rules", "u204"), run_cli("rules", "inverted-limits")
    assert by_code.exit_code == 0 and by_code.stdout == by_name.stdout
    assert by_code.stdout.startswith("U204 inverted-limits (error) joints")
    assert "Bad: `<limit lower=\"1.57\"" in by_code.stdout and "Good:" in by_code.stdout
    assert "``" not in by_code.stdout  # reST literals read as Markdown ones in a terminal


def test_unknown_suggests_the_close_one(run_cli):
    result = run_cli("rules", "inverted-limit")
    assert result.exit_code == 2
    assert "no rule 'inverted-limit'; did you mean U204 inverted-limits?" in result.stderr
    assert "U001" not in result.stderr  # not the whole catalogue


def test_unknown_without_a_close_one_points_at_the_list(run_cli):
    result = run_cli("rules", "U999")
    assert result.exit_code == 2
    assert "no rule 'U999'. `urdftool rules` lists all" in result.stderr


def test_family_prefix_lists_that_family(run_cli):
    result = run_cli("rules", "u7")
    assert result.exit_code == 2
    listed = [r for r in CATALOGUE if r.code.startswith("U7")]
    assert all(f"{r.code} {r.name}" in result.stderr for r in listed)
    assert "U604" not in result.stderr
