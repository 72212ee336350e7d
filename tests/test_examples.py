"""Every example of command output in README.md and docs/ prints what it shows (tests/examples.py
runs them; `make examples` rewrites those whose output changed on purpose)."""

from __future__ import annotations

import pytest

import examples
from conftest import ROOT

EXAMPLES = examples.examples()


@pytest.fixture(scope="module")
def pristine(tmp_path_factory):
    """The scratch checkout made once (copying, ``git add`` and commit: 0.8 s of CPU); each
    example runs in a copy of it of its own (0.2 s), which it may change."""
    return examples.workspace(tmp_path_factory.mktemp("pristine"))


def workspace(pristine, folder):
    import subprocess

    subprocess.run(["cp", "-a", f"{pristine}/.", str(folder)], check=True)
    return folder


@pytest.mark.integration
@pytest.mark.parametrize("example", EXAMPLES, ids=[e.name for e in EXAMPLES])
def test_the_example_prints_what_it_shows(example, pristine, tmp_path):
    printed = examples.outputs(example, workspace(pristine, tmp_path))
    problem = examples.report(example, printed)
    assert problem is None, problem
    # an example shows the robot as it can be: no joint posed outside its limits
    outside = [line for lines in printed for line in lines if "outside its limits" in line]
    assert not outside, outside


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
def test_the_python_api_examples_run(pristine, tmp_path, monkeypatch, capsys):
    """docs/python-api.md's examples, run as written in a copy of the checkout."""
    import re

    text = (ROOT / "docs" / "python-api.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert blocks
    monkeypatch.chdir(workspace(pristine, tmp_path))
    for number, block in enumerate(blocks):
        exec(compile(block, f"docs/python-api.md, example {number + 1}", "exec"), {})
    assert "robots/diffbot/wheel.xacro:" in capsys.readouterr().out


def _documented_command_lines():
    """Every ``urdftool ...`` line of a code block in README.md and docs/ (shell, console, YAML,
    make), continuation lines joined, comments and pipes cut off."""
    import re
    import shlex

    for page in examples.sources():
        text = page.read_text(encoding="utf-8")
        for block in re.findall(r"```\w*\n(.*?)```", text, re.S):
            for line in block.replace("\\\n", " ").splitlines():
                line = line.strip().removeprefix("$ ").removeprefix("- ").removeprefix("run: ")
                if line.startswith("urdftool "):
                    words = shlex.split(line, comments=True)
                    for stop in ("|", ">", "||", ">>", "&&"):
                        words = words[:words.index(stop)] if stop in words else words
                    yield page.relative_to(ROOT).as_posix(), words


def test_every_documented_command_line_parses():
    """The commands the pages show but do not run (placeholder files, CI recipes) still name
    commands and options that exist: an option renamed fails here, not on a reader."""
    import typer.main

    from urdftool.cli import app

    group = typer.main.get_command(app)
    context = type(group.make_context("urdftool", ["--help"], resilient_parsing=True))
    problems, count = [], 0
    for page, words in _documented_command_lines():
        parent = context(group, info_name="urdftool")
        command = group.get_command(parent, words[1])
        try:
            assert command is not None, f"no command {words[1]!r}"
            command.make_context(words[1], words[2:], parent=parent)
            count += 1
        except Exception as error:  # click's usage errors, or the assertion
            problems.append(f"{page}: {' '.join(words)}: {error}")
    assert not problems, "\n".join(problems)
    assert count >= 30
