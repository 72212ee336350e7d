"""The class methods and regular expressions a check compiles, kept compiled
(``urdftool.kept_code``) and given back by the door (``urdftool/__main__.py``): used for the
very texts and patterns they were made from and nothing else, by the Python that made them
only, with the same findings."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from conftest import ROOT, walked

# made in one process (collect), used in another (the door's kept_code); prints what the
# second compiled
PROGRAM = '''
import dataclasses, marshal, re, sys
from urdftool import __main__ as door

SOURCE = """
@dataclasses.dataclass(frozen=True)
class Kept:
    a: int
    b: str = "x"
"""
OTHER = SOURCE.replace("Kept", "Other").replace("b: str", "c: str")
PATTERN, FLAGS = r"(?P<word>ab+)c|(d)", re.I

if sys.argv[1] == "make":
    from urdftool import kept_code

    # python -m urdftool.kept_code, its workload these two
    kept_code.check_robots = lambda: (re.compile(PATTERN, FLAGS),
                                      exec(SOURCE, {"dataclasses": dataclasses}))
    door.KEPT_CODE = sys.argv[2]
    if sys.argv[3] != "this":
        door.kept_code_header = lambda: ("another Python",)
    kept_code.main()
    raise SystemExit(0)

if sys.argv[1] == "corrupt":  # bytes of the file in turn inverted: nothing else changes
    import builtins
    import random
    whole = open(sys.argv[2], "rb").read()
    head = 8 + int.from_bytes(whole[:8], "little")  # the length, header and checksum
    positions = range(len(whole)) if sys.argv[3] == "every" else sorted(  # or every byte of the
        {*range(head), len(whole) - 1,  # head, the last and a seeded sample of the forms
         *random.Random(int(sys.argv[3])).sample(range(head, len(whole)), 64)})
    real = dataclasses.exec if hasattr(dataclasses, "exec") else None, re._compile

    def outcome():
        re.purge()
        space = {"dataclasses": dataclasses}
        exec(SOURCE, space)
        kept = space["Kept"]
        return ([m.group(0) for m in re.compile(PATTERN, FLAGS).finditer("xABBc d")],
                repr(kept(1)), kept(1) == kept(1, "x"))

    expected, changed = outcome(), []
    for at in positions:
        with open(sys.argv[2], "wb") as handle:
            handle.write(whole[:at] + bytes([whole[at] ^ 0xFF]) + whole[at + 1:])
        try:
            door.kept_code(sys.argv[2])
            got = outcome()
        except Exception as error:
            got = repr(error)
        finally:
            vars(dataclasses).pop("exec", None)
            re._compile = real[1]
        if got != expected:
            changed.append((at, got))
    print(len(positions), "bytes,", len(changed), "changed", changed[:3])
    raise SystemExit(0)

door.kept_code(sys.argv[2])
compiled, parsed = [], []
sys.addaudithook(lambda event, args: event == "compile" and compiled.append(args[1]))
real = re._compiler._code
re._compiler._code = lambda *a: parsed.append(1) or real(*a)
re.purge()
kept = re.compile(PATTERN, FLAGS)
print("pattern parsed", len(parsed), kept.groupindex, kept.groups, kept.flags,
      [m.group(0) for m in kept.finditer("xABBc d")])
re.compile(PATTERN + "e", FLAGS)
print("other pattern parsed", len(parsed))
space = {"dataclasses": dataclasses}
exec(compile(SOURCE, "<test>", "exec"), space)
kept_class = space["Kept"]
print("class compiled", len(compiled) - 1, repr(kept_class(1)), kept_class(1) == kept_class(1, "x"))
try:
    space["Kept"](1).a = 2
except dataclasses.FrozenInstanceError:
    print("frozen")
before = len(compiled)
exec(compile(OTHER, "<test>", "exec"), space)
print("other class compiled", len(compiled) - before - 1 > 0)
'''


def _run(*words: str) -> str:
    done = subprocess.run([sys.executable, "-c", PROGRAM, *words], capture_output=True,
                          text=True, cwd=ROOT, timeout=120)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_kept_forms_serve_the_texts_and_patterns_they_were_made_from_and_no_other(tmp_path):
    kept = str(tmp_path / "kept.marshal")
    _run("make", kept, "this")
    lines = _run("use", kept).splitlines()
    assert lines == ["pattern parsed 0 {'word': 1} 2 34 ['ABBc', 'd']",
                     "other pattern parsed 1",
                     "class compiled 0 Kept(a=1, b='x') True", "frozen",
                     "other class compiled True"]


def test_another_pythons_kept_forms_are_not_used(tmp_path):
    kept = str(tmp_path / "kept.marshal")
    _run("make", kept, "another")
    lines = _run("use", kept).splitlines()
    assert lines[0].startswith("pattern parsed 1 ") and lines[2].startswith("class compiled ")
    assert lines[2] != "class compiled 0 Kept(a=1, b='x') True"


def test_a_corrupt_kept_file_costs_the_saving_and_changes_nothing(tmp_path):
    """A byte of the file inverted (every byte of its length, header and checksum, the last,
    and a seeded sample of the code objects' and patterns' bytes): the door uses no form of
    it, and nothing raises or compiles differently. Every byte in turn: the slow test below."""
    kept = str(tmp_path / "kept.marshal")
    _run("make", kept, "this")
    counted, _, changed = _run("corrupt", kept, "20261130").partition(" bytes, ")
    assert int(counted) > 100 and changed.startswith("0 changed"), changed


@pytest.mark.slow  # generated breadth (5,000 bytes, 5 s of CPU): make fuzz runs it
def test_every_byte_of_a_kept_file_corrupt_costs_the_saving_and_changes_nothing(tmp_path):
    """Every byte of the file in turn inverted (header, checksum, a code object, a pattern's
    code): the door uses no form of it, and nothing raises or compiles differently."""
    kept = str(tmp_path / "kept.marshal")
    _run("make", kept, "this")
    counted, _, changed = _run("corrupt", kept, "every").partition(" bytes, ")
    assert int(counted) > 500 and changed.startswith("0 changed"), changed


def test_a_check_finds_the_same_with_and_without_the_kept_forms(tmp_path):
    """robots/ and a broken case, through the door, with the file ``python -m
    urdftool.kept_code`` writes and with the door's kept_code patched out."""
    kept = tmp_path / "kept.marshal"
    program = ("import sys; sys.argv = ['urdftool', *sys.argv[1:]]; "
               "import urdftool.__main__ as door; {}; door.main()")
    made = subprocess.run([sys.executable, "-c", "import sys, urdftool.__main__ as door; "
                           f"door.KEPT_CODE = {str(kept)!r}; "
                           "from urdftool import kept_code; kept_code.main()"],
                          capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert made.returncode == 0 and kept.stat().st_size, made.stderr
    words = ["check", "--no-cache", "--format", "json", "robots",
             "tests/cases/U005_xacro_error/robot.urdf.xacro"]
    runs = [subprocess.run([sys.executable, "-c", program.format(patch), *words],
                           capture_output=True, text=True, cwd=ROOT, timeout=300,
                           env={**os.environ, "COLUMNS": "100"})
            for patch in (f"door.KEPT_CODE = {str(kept)!r}", "door.kept_code = lambda: None")]
    assert runs[0].returncode == runs[1].returncode == 1
    assert (runs[0].stdout, runs[0].stderr) == (runs[1].stdout, runs[1].stderr)
    assert '"U005"' in runs[0].stdout


def test_the_kept_file_is_read_in_place_not_copied_into_memory(tmp_path, monkeypatch):
    """The forms are checksummed and unmarshalled from the mapped file: reading the file whole
    first (then slicing the forms out of it) copied it twice, a page fault per page of each
    copy (r2d2's check: 7,506 -> 7,338 page faults)."""
    import io

    from urdftool import __main__ as door

    source = "x = 1\n"
    path = tmp_path / "kept.marshal"
    path.write_bytes(door.kept_code_file({source: compile(source, "<string>", "exec")}, {}))

    class Unread(io.FileIO):
        def read(self, *args):
            raise AssertionError("the kept file was read whole")

        readall = readinto = read

    monkeypatch.setattr(door, "open", lambda name, mode="r": Unread(name, "r"), raising=False)
    forms = door._kept_forms(str(path))
    assert forms is not None and list(forms[0]) == [source] and forms[1] == {}


def test_every_dataclass_has_a_docstring():
    """dataclasses writes a docstring for a class without one from ``inspect.signature`` of it,
    at every import (eight such classes cost a check of r2d2 2.4 M instructions): each class
    says what it is instead."""
    import ast

    def is_dataclass(decorator) -> bool:
        target = decorator.func if isinstance(decorator, ast.Call) else decorator
        return getattr(target, "id", getattr(target, "attr", None)) == "dataclass"

    bare = [f"{path.relative_to(ROOT)}:{node.lineno} {node.name}"
            for path in sorted((ROOT / "urdftool").rglob("*.py"))
            for node in walked(path.read_text(encoding="utf-8"))
            if isinstance(node, ast.ClassDef) and any(map(is_dataclass, node.decorator_list))
            and ast.get_docstring(node) is None]
    assert not bare, bare
