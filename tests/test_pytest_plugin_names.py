"""``pytest --urdftool`` on robot files with a stranger's names (docs/attacks.md, session 8):
pytest prints a node ID at the start of a line (``-v``, ``--collect-only``, the short
summary) and writes it into ``--junitxml``. A robot file named ``::error::forged.urdf`` made a
GitHub workflow command of pytest's line, one holding a line break started a line of its own,
an escape sequence reached the terminal, and an undecodable byte ended pytest's JUnit writer
with a traceback. The plugin's node IDs and names go through the terminal-text escaper."""

from __future__ import annotations

import os
import re
import xml.dom.minidom

import pytest

pytest_plugins = ["pytester"]

ROBOT = '<robot name="g"><link name="a"/></robot>\n'
NAMES = ["::error::forged.urdf", "nl\n::warning::x.urdf", "esc\x1b[2J.urdf", "bidi\u202e.urdf",
         "a::b[1].urdf"]  # (pytest read what follows "::" as names, "[" as parameters: the
# item's ID a ValueError that interrupted the session's collection)


# -v prints each node ID where its line starts, -rA again in the short summary: one pytest run
# shows both (each a pytest of its own cost 2 s of CPU)
@pytest.mark.parametrize("options", [["-v", "-rA"], ["--collect-only"]])
def test_robot_file_names_print_no_command_and_no_control(pytester, options):
    for name in NAMES:
        (pytester.path / name).write_text(ROBOT)
    (pytester.path / os.fsdecode(b"inv\xff.urdf")).write_text(ROBOT)
    junit = pytester.path.parent / "junit.xml"
    result = pytester.runpytest_subprocess("--urdftool", "-p", "no:cacheprovider",
                                           "-p", "no:xdist", f"--junitxml={junit}", *options)
    out = "\n".join(result.outlines + result.errlines)
    assert "Traceback" not in out and "INTERNALERROR" not in out, out
    assert not [line for line in result.outlines if re.match(r"\s*::", line)], out
    assert not re.search("[\x00-\x08\x0b-\x1f\x7f\u202e]", out), out
    if "--collect-only" not in options:
        document = xml.dom.minidom.parse(str(junit))  # written whole, and parses
        assert len(document.getElementsByTagName("testcase")) == 6
