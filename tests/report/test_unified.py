"""``check --diff``'s unified diff (urdftool.report.unified)."""

from __future__ import annotations

import difflib
import random
import re

from urdftool.report import unified as module
from urdftool.report.unified import unified


def _patched(old: bytes, diff: str) -> bytes:
    """``old`` with the hunks of ``diff`` applied, as ``patch`` reads them (LF lines)."""
    lines = old.decode().split("\n")
    lines = [line + "\n" for line in lines[:-1]] + ([lines[-1]] if lines[-1] else [])
    out, at, rows, index = [], 0, diff.split("\n")[2:], 0
    while index < len(rows) and rows[index].startswith("@@"):
        start, length = re.match(r"@@ -(\d+)(?:,(\d+))?", rows[index]).groups()
        start = int(start) - (length != "0")  # (an empty range names the line before it)
        out, at, index = out + lines[at:start], start, index + 1
        while index < len(rows) and rows[index][:1] in (" ", "-", "+", "\\"):
            row, index = rows[index], index + 1
            ending = "" if index < len(rows) and rows[index].startswith("\\") else "\n"
            if row[0] in " -":
                at += 1
            if row[0] in " +":
                out.append(lines[at - 1] if row[0] == " " else row[1:] + ending)
    return "".join(out + lines[at:]).encode()


def test_a_diff_from_the_edits_spans_is_the_edits_and_compares_only_the_lines_they_touch(
        monkeypatch):
    """A robot of 4,000 joints, each with the same axis fixed, took 84 s to diff (1,000: 10 s):
    difflib over the whole file, quadratic where lines repeat. From the edits' spans, only the
    lines they touch are compared: every drawn diff applied gives the file after the edits,
    and difflib is asked about a few lines at a time."""
    rng = random.Random(5)
    words = ["<a/>", "<b/>", "  <c x='1'/>", "", "<d>", "</d>"]
    for _ in range(1500):
        data = ("\n".join(rng.choice(words) for _ in range(rng.randrange(1, 30)))
                + "\n").encode()
        spans, pieces, at = [], [], 0
        for start in sorted(rng.sample(range(len(data)), min(len(data), rng.randrange(1, 6)))):
            if start < at:
                continue
            end = min(len(data), start + rng.choice([0, 0, 1, 3]))
            text = rng.choice([b"", b"X", b"\n<new/>\n", b"<a/>\n"])
            pieces += [data[at:start], text]
            spans.append((start, end, len(text)))
            at = end
        after = b"".join(pieces) + data[at:]
        diff = unified({"f": (data, after)}, {"f": spans})
        assert _patched(data, diff) == after, (data, spans, diff)
        if not diff:
            assert after == data
    lines = "".join(f'  <joint name="j{i}">\n    <axis xyz="0 0 2"/>\n  </joint>\n'
                    for i in range(3000)).encode()
    spans = [(m.start(1), m.end(1), 1) for m in re.finditer(rb'xyz="0 0 (2)"', lines)]
    after = lines.replace(b'xyz="0 0 2"', b'xyz="0 0 1"')
    compared = []
    real = difflib.SequenceMatcher.get_opcodes
    monkeypatch.setattr(module.difflib.SequenceMatcher, "get_opcodes",
                        lambda self: compared.append(len(self.a)) or real(self))
    diff = unified({"f": (lines, after)}, {"f": spans})
    assert diff.count("\n-    <axis") == 3000 and max(compared) == 1


def test_the_hunks_are_difflibs_unified_diff_given_its_matcher():
    """``_unified`` is difflib.unified_diff's loop over a matcher given to it (unified_diff
    takes none: it would compare the whole files, the quadratic cost the edits' spans avoid):
    the same text, hunk ranges included, for any two files."""
    rng = random.Random(7)
    words = ["<a/>\n", "<b/>\n", "\n", "<c x='1'/>\n", "<d>", "\r\n"]
    for _ in range(2000):
        old, new = ([rng.choice(words) for _ in range(rng.randrange(0, 25))] for _ in "ab")
        matcher = difflib.SequenceMatcher(None, old, new)
        assert list(module._unified(old, new, "a/f", "b/f", matcher)) == \
            list(difflib.unified_diff(old, new, "a/f", "b/f"))


def test_a_diff_splits_lines_as_a_patch_does_a_crlf_or_cr_only_file_too():
    """A patch's lines end at line feeds (``git apply``, ``patch``): a CR LF file's lines keep
    their CR, and a CR-only file is one line, as ``diff -u`` shows it; the diff drawn from the
    edits' spans, applied, gives the file after the edits."""
    for end in (b"\n", b"\r\n", b"\r"):
        data = end.join([b"<robot>", b"  <a x='1'/>", b"  <b/>", b"</robot>", b""])
        at = data.index(b"1")
        after = data[:at] + b"2" + data[at + 1:]
        diff = unified({"f": (data, after)}, {"f": [(at, at + 1, 1)]})
        assert _patched(data, diff) == after, diff
        assert diff.count("\n-") == 1 and ("@@ -1 +1 @@" in diff) is (end == b"\r")
