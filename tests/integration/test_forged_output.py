"""Issue 29, class 7: no name from a robot file forges output, in any command or format.

Every command of the Typer app runs with every format its module declares, every option that
writes a file, and the modes that print other things, on a repository whose link, joint,
material, frame, robot, SRDF group, controller, file and folder names carry line breaks,
carriage returns, GitHub workflow commands, Markdown headings, images, links and tables, HTML,
rich markup, emoji codes, terminal escape sequences (CSI, OSC 8, OSC 52), C1 controls and bidi
overrides (tests/fuzz/forge.py). What each printed and wrote is judged by its kind: a raw
control character, a line GitHub reads as a workflow command, Markdown outside code, a JUnit or
SVG document that does not parse or holds an element that is not ours, rich markup that was
interpreted, a CSV cell holding a line break or a formula. A new command, format or output
option is tried as soon as it exists, or the coverage test names it.
"""

from __future__ import annotations

import pytest

from conftest import one_piece_here
from tests.fuzz import forge


@pytest.fixture(scope="module")
def hostile_repository(tmp_path_factory, analysis_imported):
    """The repository of hostile names; the commands' libraries imported before the first
    command runs, so that each command's budgeted worker, forked from this process, does not
    import them again (100 commands: 13.3 -> 7.0 s of CPU)."""
    return forge.repository(tmp_path_factory.mktemp("hostile"))


def test_every_command_format_and_output_option_is_tried(hostile_repository):
    assert forge.uncovered(forge.invocations(hostile_repository)) == []


PARTS = 4  # the invocations in four tests, which the suite's workers share (one took 26 s)


@pytest.mark.parametrize("part", range(PARTS))
def test_no_name_forges_output_in_any_command_or_format(hostile_repository, part, monkeypatch):
    one_piece_here(monkeypatch)  # each command in this process, as under its guardian outside
    # the tests (not in a worker forked from the test's: 100 forks, 7 s of CPU in children)
    repo = hostile_repository
    found = []
    for run in forge.invocations(repo)[part::PARTS]:
        for path in run.writes:
            path.unlink(missing_ok=True)
        code, stdout, stderr = forge.run_in_process(run.argv, repo.root)
        where = "urdftool " + " ".join(word[:12] for word in run.argv[:3])
        if code not in (0, 1, 2) or "Traceback (most recent call last)" in stderr:
            found.append(f"{where}: exit {code}: {stderr[-300:]}")
        found += forge.judge(run.kind, stdout, stderr, where)
        for path in [*run.writes, *run.checks]:
            found += [f"{where}: {problem}" for problem in forge.file_written(path)]
        for path in run.checks:
            found += [f"{where}: {problem}" for problem in forge.names_kept(path, repo.names)]
    assert found == [], "\n".join(found)


def test_the_judge_finds_each_kind_of_forgery():
    """The judge itself can fail: one sample of each forgery it must see."""
    assert forge.terminal("ok\n  ::error::x\n", "t")
    assert forge.terminal("\u3000::add-mask::x", "t")
    assert forge.terminal("a\x1b[31mb", "t")
    assert forge.terminal("a\u202eb", "t")
    assert forge.terminal("RICHMARK", "t")  # [bold red] was eaten by rich
    assert not forge.terminal("[bold red]RICHMARK[/]", "t")
    assert forge.terminal("::error file=a,line=1,title=x::m\n::add-mask::x", "t", github=True)
    assert not forge.terminal("::error file=a,line=1,title=U1 x::m", "t", github=True)
    assert forge.markdown("### ours\n\n# HEADING\n", "m")
    assert forge.markdown("- ![IMAGE](x)\n", "m")
    assert forge.markdown("- <img src=x onerror=1>\n", "m")
    assert forge.markdown("| a | b |\n|---|---|\n| `x|y` | z |\n", "m")
    assert not forge.markdown("| a | b |\n|---|---|\n| `x\\|y` | z |\n", "m")
    assert forge.markdown("- FORGED\n", "m")
    assert not forge.markdown("- `FORGED`\n", "m")
    assert forge.xml_document(b"<svg><script>x</script></svg>", "s", forge.SVG_ELEMENTS)
    assert forge.xml_document(b"<svg><text>a", "s", forge.SVG_ELEMENTS)
    assert forge.xml_document(b"<testsuites><testsuite><testcase><failure>a\n::error::x"
                              b"</failure></testcase></testsuite></testsuites>", "j",
                              forge.JUNIT_ELEMENTS)
    assert forge.unpaired('{"a": "x\\udcff"}', "j")
    assert not forge.unpaired('{"a": "x\\ud83d\\ude00 \\\\udcff"}', "j")
    assert forge.csv_text('a,b\n"x\n::error::y",1\n', "c")
    assert forge.csv_text("a,b\n=cmd(),1\n", "c")
    assert not forge.csv_text("a,b\n-1.5,1\n", "c")
    assert forge.dot('digraph "r" {\n  rankdir=TB;\n  node [];\n  edge [];\n  "a\n::error::x";\n}\n',
                     "d")
