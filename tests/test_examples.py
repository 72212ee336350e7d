"""Every example of command output in README.md and docs/ prints what it shows (tests/examples.py
runs them; `make examples` rewrites those whose output changed on purpose)."""

from __future__ import annotations

import pytest

import examples
from conftest import ROOT

EXAMPLES = examples.examples()


@pytest.mark.integration
@pytest.mark.parametrize("example", EXAMPLES, ids=[e.name for e in EXAMPLES])
def test_the_example_prints_what_it_shows(example, tmp_path):
    printed = examples.outputs(example, examples.workspace(tmp_path))
    problem = examples.report(example, printed)
    assert problem is None, problem


def test_the_readme_has_examples_and_each_runs_urdftool():
    assert any(e.file == "README.md" for e in EXAMPLES)
    for example in EXAMPLES:
        assert example.runs, f"{example.name}: a console block without a $ command"
        for step in example.runs:
            assert step.command.startswith("urdftool "), f"{example.name}: {step.command}"
        assert example.change is None or example.change in examples.CHANGES, example.name


@pytest.mark.parametrize(("expected", "printed", "cost", "rewritten"), [
    (["a", "b"], ["a", "b"], 0, ["a", "b"]),
    (["a", "...", "z"], ["a", "b", "c", "z"], 0, ["a", "...", "z"]),
    (["a", "...", "z"], ["a", "z"], 0, ["a", "...", "z"]),
    (["took … s", "x"], ["took 0.31 s", "x"], 0, ["took … s", "x"]),
    (["took … s", "x"], ["took 0.31 s", "y"], 1, ["took … s", "y"]),
    (["a", "...", "z"], ["a", "b", "y"], 1, ["a", "...", "y"]),
    (["a", "gone", "b"], ["a", "b", "new"], 2, ["a", "b", "new"]),
    ([], ["a"], 1, ["a"]),
])
def test_marks_match_and_survive_a_rewrite(expected, printed, cost, rewritten):
    assert examples.align(expected, printed) == (cost, rewritten)


def test_a_rewrite_replaces_only_what_changed(tmp_path):
    doc = tmp_path / "README.md"
    (tmp_path / "docs").mkdir()
    doc.write_text("Intro.\n\n```console\n$ urdftool rules \\\n    U204\nU204 inverted-limits …\n"
                   "...\nnot printed\n```\n\nEnd.\n")
    for name in examples.COPIED:
        (tmp_path / name).mkdir(parents=True, exist_ok=True)
    (example,) = examples.examples(tmp_path)
    assert [run.command for run in example.runs] == ["urdftool rules U204"]
    assert examples.update(tmp_path) == ["README.md:3"]
    text = doc.read_text()
    assert text.startswith("Intro.\n\n```console\n$ urdftool rules \\\n    U204\n"
                           "U204 inverted-limits …\n...\n")
    assert "not printed" not in text and text.endswith("```\n\nEnd.\n")
    assert examples.update(tmp_path) == []  # now it matches


def test_the_marks_are_documented_where_examples_are():
    index = (ROOT / "docs" / "README.md").read_text(encoding="utf-8")
    assert f"`{examples.ANY_LINES}`" in index and f"`{examples.ANY_TEXT}`" in index


@pytest.mark.integration
def test_the_python_api_examples_run(tmp_path, monkeypatch, capsys):
    """docs/python-api.md's examples, run as written in a copy of the checkout."""
    import re

    text = (ROOT / "docs" / "python-api.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert blocks
    monkeypatch.chdir(examples.workspace(tmp_path))
    for number, block in enumerate(blocks):
        exec(compile(block, f"docs/python-api.md, example {number + 1}", "exec"), {})
    assert "robots/diffbot/wheel.xacro:" in capsys.readouterr().out
