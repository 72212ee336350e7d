"""Untrusted XML: entities, DTDs, bombs, deep nesting, huge values, odd names, odd files.

Each input goes through both the plain-URDF parser and the xacro path, and must end in a
located finding (or load), never a traceback, never reading a file it was not asked to read.
"""

from __future__ import annotations

import os

import pytest

from urdftool.lint.engine import CheckOptions, load_and_check

pytestmark = pytest.mark.worker  # budgets and deaths: run_cli's commands in the forked worker

XACRO_NS = ' xmlns:xacro="http://www.ros.org/wiki/xacro"'
LAUGHS = ('<!DOCTYPE robot [<!ENTITY lol "lol">'
          + "".join(f'<!ENTITY lol{i} "{("&lol%s;" % (i - 1 if i > 1 else "")) * 10}">'
                    for i in range(1, 10))
          + ']>\n<robot name="r"><link name="&lol9;"/></robot>\n')
QUADRATIC = ('<!DOCTYPE robot [<!ENTITY a "' + "x" * 100_000 + '">]>\n<robot name="r"><link name="'
             + "&a;" * 10_000 + '"/></robot>\n')
INPUTS = {
    "billion laughs": (LAUGHS, "U009"),
    "quadratic blowup": (QUADRATIC, "U009"),
    "external entity": ('<!DOCTYPE robot [<!ENTITY s SYSTEM "file:///etc/passwd">]>\n'
                        '<robot name="r"><link name="&s;"/></robot>\n', "U009"),
    "parameter entity": ('<!DOCTYPE robot [<!ENTITY % p SYSTEM "file:///etc/passwd"> %p;]>\n'
                         '<robot name="r"><link name="a"/></robot>\n', "U009"),
    "external DTD": ('<!DOCTYPE robot SYSTEM "file:///etc/passwd">\n'
                     '<robot name="r"><link name="a"/></robot>\n', "U009"),
    "network DTD": ('<!DOCTYPE robot PUBLIC "-//x//y" "http://127.0.0.1:9/x.dtd">\n'
                    '<robot name="r"><link name="a"/></robot>\n', "U009"),
    "undefined entity": ('<robot name="r"><link name="&nope;"/></robot>\n', "U001"),
    "deep nesting": ('<robot name="r">' + "<link>" * 100_000 + "</link>" * 100_000 + "</robot>\n",
                     "U001"),
    "huge attribute": ('<robot name="r"><link name="' + "a" * 8_000_000 + '"/></robot>\n', None),
    "long line": ('<robot name="r">' + '<link name="a"/>' * 50_000 + "</robot>\n", "U101"),
    "three-part name": ('<robot name="r"><a:b:c/><link name="a"/></robot>\n', None),
    "undeclared prefix": ('<robot name="r"><gz:plugin/><link name="a"/></robot>\n', None),
    "bad encoding": ('<?xml version="1.0" encoding="no-such-encoding"?>\n'
                     '<robot name="r"/>\n', "U001"),
    "latin-1 bytes": ('<robot name="r"><link name="caf\udce9"/></robot>\n', "U001"),
}


def _write(tmp_path, name, text, xacro):
    if xacro:
        text = text.replace('<robot name="r"', f'<robot name="r"{XACRO_NS}', 1)
    path = tmp_path / (name.replace(" ", "_") + (".urdf.xacro" if xacro else ".urdf"))
    path.write_bytes(text.encode("utf-8", "surrogateescape"))
    return path


@pytest.mark.parametrize("xacro", [False, True], ids=["urdf", "xacro"])
@pytest.mark.parametrize("name", sorted(INPUTS))
def test_untrusted_input_ends_in_a_finding(tmp_path, name, xacro):
    text, code = INPUTS[name]
    result = load_and_check(str(_write(tmp_path, name, text, xacro)), CheckOptions(allow_env=False))
    codes = {f.code for f in result.findings}
    assert "U900" not in codes, result.findings
    if code is not None:
        assert code in codes, result.findings
    if result.robot is None:
        assert any(f.line is not None for f in result.findings), result.findings
    leaked = [f for f in result.findings if "root:" in f.message]
    assert not leaked
    if result.robot is not None:
        assert "root:x:0" not in result.robot.urdf


def test_entity_bomb_is_refused_at_its_declaration(tmp_path):
    result = load_and_check(str(_write(tmp_path, "laughs", LAUGHS, False)), CheckOptions())
    assert [(f.code, f.line) for f in result.findings] == [("U009", 1)]


def test_included_file_over_the_size_limit(tmp_path):
    (tmp_path / "big.xacro").write_text(f'<robot{XACRO_NS}>' + " " * 5000 + "</robot>")
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(f'<robot name="r"{XACRO_NS}>\n<xacro:include filename="big.xacro"/>\n</robot>')
    result = load_and_check(str(path), CheckOptions(max_file_size=1000))
    assert [(f.code, f.line) for f in result.findings] == [("U005", 2)]
    assert "over the limit" in result.findings[0].message


def test_unreadable_include_is_a_located_finding(tmp_path):
    if os.geteuid() == 0:
        pytest.skip("root reads everything")
    (tmp_path / "secret.xacro").write_text(f"<robot{XACRO_NS}/>")
    (tmp_path / "secret.xacro").chmod(0)
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(f'<robot name="r"{XACRO_NS}>\n<xacro:include filename="secret.xacro"/>\n</robot>')
    result = load_and_check(str(path), CheckOptions())
    assert [(f.code, f.line) for f in result.findings] == [("U005", 2)]


def test_folder_as_include_is_a_located_finding(tmp_path):
    (tmp_path / "sub").mkdir()
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(f'<robot name="r"{XACRO_NS}>\n<xacro:include filename="sub"/>\n</robot>')
    result = load_and_check(str(path), CheckOptions())
    assert [(f.code, f.line) for f in result.findings] == [("U005", 2)]


def test_fifo_input_is_not_read(tmp_path):
    fifo = tmp_path / "pipe.urdf"
    os.mkfifo(fifo)
    result = load_and_check(str(fifo), CheckOptions())
    assert [f.code for f in result.findings] == ["U001"]


def test_odd_files_in_a_folder_do_not_break_the_walk(run_cli, tmp_path):
    (tmp_path / "r.urdf.xacro").write_bytes(
        f'<robot name="r"{XACRO_NS}>\n<xacro:include filename="a\0b"/>\n</robot>'.encode())
    (tmp_path / "loop.xacro").symlink_to(tmp_path / "loop.xacro")
    os.mkfifo(tmp_path / "pipe.urdf")
    (tmp_path / "caf\u00e9 bot.urdf").write_text('<robot name="r"><link name="a"/></robot>')
    result = run_cli("check", "--timeout", "20", tmp_path)
    assert result.exit_code == 1, result.output
    assert "Traceback" not in result.output and "U900" not in result.output
    assert "pipe.urdf: error U001 cannot read file: not a regular file" in result.output
    assert "loop.xacro: error U001" in result.output  # an unreadable file is reported, not skipped
    # a NUL byte makes r.urdf.xacro binary, not an include-only library: checked, not skipped
    assert "r.urdf.xacro:1: error U003" in result.output
    assert "4 files checked" in result.output  # and the FIFO, the loop, the robot with an odd name


def test_symlink_loop_input_is_a_finding(tmp_path):
    loop = tmp_path / "loop.urdf"
    loop.symlink_to(loop)
    result = load_and_check(str(loop), CheckOptions())
    assert [f.code for f in result.findings] == ["U001"]
