"""Findings and their order (urdftool/diagnostics.py)."""

from __future__ import annotations

from urdftool.diagnostics import Finding, Location, Severity, distinct_sorted


def test_findings_that_differ_only_in_their_call_site_sort_the_same_in_every_order():
    def at(site_line):
        return Finding("U022", "x", Severity.INFO, "same", Location(
            "arm.xacro", 7, (Location("robot.urdf.xacro", site_line),), column=3))

    findings = [at(9), at(4), at(12)]
    assert [f.location.via[0].line for f in sorted(findings, key=Finding.sort_key)] == [4, 9, 12]
    assert sorted(reversed(findings), key=Finding.sort_key) == \
        sorted(findings, key=Finding.sort_key)


def test_findings_distinct_and_sorted_as_a_set_of_them_sorted():
    import random

    chance = random.Random(19)
    made = [Finding(chance.choice(["U101", "U311"]), "x",
                    chance.choice([Severity.ERROR, Severity.WARNING]), chance.choice("ab"),
                    Location(chance.choice(["a.urdf", "b.urdf"]), chance.choice([None, 1, 2]),
                             column=chance.choice([None, 3])))
            for _ in range(300)]
    found = distinct_sorted(made)
    assert len(found) == len(set(found)) == len(set(made)) < len(made)
    assert found == sorted(found, key=Finding.sort_key) and set(found) == set(made)
    # findings of one key that differ (here in severity only) keep the order given
    one, other = made[0], Finding(made[0].code, "x", Severity.INFO, made[0].message,
                                  made[0].location)
    assert distinct_sorted([other, one, other]) == [other, one]


def test_every_count_of_lines_is_the_one_owners():
    """A line is what :func:`diagnostics.lines_of` says (CR LF, LF, CR), wherever a message, a
    finding, an edit or a reader numbers one: no code counts LF itself (a file whose lines end
    with CR alone was line 1 in four messages), finds a line's start by LF, numbers lines by
    PyYAML's count (which ends a line at NEL and LINE SEPARATOR too), or matches the start of
    a line with ``^`` under re.M (LF only: a CR-only ROS 2 parameter file was read as ROS 1).
    A reader that emulates another program's line ends says whose on that line or the one
    before it (``line ends: ...``); the output layer writes its own LF lines."""
    import re
    from pathlib import Path

    import urdftool

    root = Path(urdftool.__file__).parent
    owners = {root / "diagnostics.py", root / "description" / "yaml_limits.py"}
    wrong = re.compile(r"""\.count\(b?["']\\n["']|\.rfind\(b?["']\\n["']|mark\.line\b"""
                       r"""|\bre\.M\b|\bre\.MULTILINE\b|\(\?m\)|enumerate\([^)]*(splitlines\(|split\(b?["']\\n)""")
    found = []
    for path in sorted(root.rglob("*.py")):
        if path in owners or "report" in path.relative_to(root).parts:
            continue
        lines = path.read_text(encoding="utf-8").split("\n")
        for number, line in enumerate(lines, 1):
            said = "line ends:" in line or (number > 1 and "line ends:" in lines[number - 2])
            if wrong.search(line) and not said:
                found.append(f"{path.relative_to(root)}:{number}: {line.strip()}")
    assert not found, "lines counted by another rule than diagnostics.lines_of:\n" + \
        "\n".join(found)


def test_line_at_and_its_index_agree_on_every_offset_of_str_and_bytes():
    from urdftool.diagnostics import LineNumbers, line_at, line_end, line_start, lines_between, \
        lines_of

    import random

    draw = random.Random(16)
    for _ in range(400):
        text = "".join(draw.choice("ab\r\n\u2028\x85") for _ in range(draw.randint(0, 14)))
        data = text.replace("\u2028", "x").replace("\x85", "y").encode()
        for sample in (text, data):
            numbers, lines = LineNumbers(sample), lines_of(text if sample is text else
                                                          data.decode(), keepends=True)
            starts = [sum(map(len, lines[:i])) for i in range(len(lines))]
            for offset in range(len(sample) + 1):
                assert line_at(sample, offset) == numbers(offset)
                line = numbers(offset)
                if sample[offset - 1:offset + 1] not in ("\r\n", b"\r\n"):
                    assert lines_between(sample, 0, offset) + 1 == line
                if offset < len(sample) and sample[offset:offset + 1] not in ("\n", b"\n"):
                    assert starts[line - 1] == line_start(sample, offset)
                    assert starts[line - 1] + len(lines[line - 1]) == line_end(sample, offset)
    assert [line_at("a\rb\r\nc\nd\u2028e", i) for i in (0, 2, 5, 7, 9)] == [1, 2, 3, 4, 4]


def test_line_numbers_without_cr_are_those_of_the_three_line_ends():
    """A text without CR is counted by LF alone (memchr's speed, session 16): the same lines as
    the CR LF | LF | CR definition gives, checked on every offset of random mixes of both."""
    import random
    import re

    from urdftool import diagnostics

    ends = {str: re.compile("\r\n|\n|\r"), bytes: re.compile(b"\r\n|\n|\r")}

    def at(text, offset):
        found = len(ends[type(text)].findall(text, 0, offset))
        return found + 1 - (0 < offset < len(text) and text[offset - 1:offset + 1] in ("\r\n", b"\r\n"))

    rng = random.Random(16)
    for _ in range(3000):
        text = "".join(rng.choice("ab\r\n\u2028 ") for _ in range(rng.randint(0, 10)))
        if rng.random() < 0.5:
            text = text.replace("\r", "")
        for sample in (text, text.encode()):
            pattern = ends[type(sample)]
            assert diagnostics.line_ends(sample) == [e.end() - 1 for e in pattern.finditer(sample)]
            for start in range(len(sample) + 1):
                assert diagnostics.line_at(sample, start) == at(sample, start), (sample, start)
                for end in range(start, len(sample) + 1):
                    assert diagnostics.lines_between(sample, start, end) == \
                        len(pattern.findall(sample, start, end))
        assert diagnostics.lines_of(text) == (ends[str].split(text) if text else [])


def test_a_path_is_displayed_as_relpath_below_the_working_directory_says(tmp_path, monkeypatch):
    """display_path: below the working directory, the path relative to it (as ``os.path.
    relpath`` makes it, without its steps), else the absolute path; a folder named "..x"
    below it is shown absolute, as relpath's answer starting with ".." was."""
    import os

    from urdftool.diagnostics import display_path

    def relpath_rule(text):
        absolute = os.path.abspath(text)
        relative = os.path.relpath(absolute)
        return absolute if relative.startswith("..") else relative

    (tmp_path / "a" / "..b" / "c").mkdir(parents=True)
    texts = ["", ".", "..", "a", "a/", "a/../b", "/", "//", "//x", "///x", "..b", "a/..b/c",
             "./a/./b//c", str(tmp_path), str(tmp_path) + "x", str(tmp_path / "a"), "../a",
             "a/../../x", "..."]
    for folder in ("/", tmp_path, tmp_path / "a", tmp_path / "a" / "..b"):
        monkeypatch.chdir(folder)
        assert [display_path(t) for t in texts] == [relpath_rule(t) for t in texts], folder
    assert display_path("-") == "-" and display_path("<stdin>") == "<stdin>"
    monkeypatch.chdir(tmp_path)
    assert display_path(tmp_path / "a" / "f.launch") == os.path.join("a", "f.launch")


def test_a_patchs_lines_end_at_line_feeds_only():
    """``feeds_only``: the lines of a patch (report.unified's diff), numbered by the same owner
    as every line: a CR stays in its line, a CR-only text is one line."""
    from urdftool.diagnostics import LineNumbers, lines_of

    text = "a\r\nb\rc\nd"
    assert lines_of(text, keepends=True, feeds_only=True) == ["a\r\n", "b\rc\n", "d"]
    assert lines_of(text, keepends=True) == ["a\r\n", "b\r", "c\n", "d"]
    numbers = LineNumbers(text.encode(), feeds_only=True)
    assert [numbers(offset) for offset in range(len(text))] == [1, 1, 1, 2, 2, 2, 2, 3]
    assert [numbers.start(line) for line in (1, 2, 3)] == [0, 3, 7]
    assert [LineNumbers(text).start(line) for line in (1, 2, 3, 4)] == [0, 3, 5, 7]
