"""The JSON writer of every JSON format and analysis command."""

from __future__ import annotations

import io
import json
import math

import pytest

from urdftool.report.json_output import RECORD, WIDTH, dumps, write_json


def test_a_value_that_fits_stays_on_one_line_and_a_long_one_has_an_item_a_line():
    long = "x" * WIDTH
    text = dumps({"short": [1, 2.5], "long": [long, {"a": None}], "empty": {}})
    assert text == ('{\n  "short": [1, 2.5],\n  "long": [\n    "' + long + '",\n    {"a": null}\n'
                    '  ],\n  "empty": {}\n}')


def test_dumps_reads_back_as_what_json_reads_including_keys_json_converts():
    document = {"diagnostics": [{"message": "m" * 200, "via": [], "line": 3}] * 3, 1.5: [],
                True: None, 2: (1, 2), "nested": [[["deep" * 30]]]}
    assert json.loads(dumps(document)) == json.loads(json.dumps(document))
    assert all(len(line) <= WIDTH or '"m' in line or '"deep' in line
               for line in dumps(document).splitlines())


def test_write_json_ends_with_a_newline():
    stream = io.StringIO()
    write_json({"a": [1, 2.5]}, stream)
    assert stream.getvalue() == '{"a": [1, 2.5]}\n'


def test_json_is_always_json_a_float_not_finite_is_null():
    """session 9: `inertia -f json` of a robot declaring mass="inf" wrote `Infinity` and `NaN`
    (no JSON reader but Python's takes them); every JSON urdftool writes goes through
    json_output, which writes them null, one line (json-lines) too."""
    from urdftool.report.json_output import line

    stream = io.StringIO()
    write_json({"d": math.inf, "rows": [(1.0, math.nan)], "n": -math.inf}, stream)
    strict = {"parse_constant": lambda word: pytest.fail(word)}
    assert json.loads(stream.getvalue(), **strict) == {"d": None, "rows": [[1.0, None]], "n": None}
    assert json.loads(line({"x": [math.nan, 2.0]}), **strict) == {"x": [None, 2.0]}
    assert json.loads(dumps({"name": "NaN", "v": 1e308}), **strict) == {"name": "NaN", "v": 1e308}


def test_an_object_in_a_list_is_a_line_of_its_own_up_to_a_record_long():
    record = {"message": "m" * (WIDTH * 2), "line": 1}
    huge = {"message": "m" * RECORD}
    lines = dumps({"diagnostics": [record, huge]}).splitlines()
    assert lines[2] == "    " + json.dumps(record) + ","
    assert lines[3] == "    {"


def test_the_least_length_is_never_more_than_the_length():
    from urdftool.report.json_output import _least_length

    for value in ([], [1], [1, 22, "abc"], {}, {"a": 1}, {"a": [1, {"bb": "c"}], 2: None},
                  ["é" * 5, [[]], {"": ""}]):
        assert _least_length(value, 10 ** 6) <= len(json.dumps(value))


def test_paired_spells_a_lone_surrogate_as_every_json_document_does_and_keeps_the_length_true():
    # session 13: the language server's messages, written by pygls's json.dumps; session 21:
    # spelt as json_output.named spells it (U+FFFD and the byte's hex digits), the
    # Content-Length made the new body's
    from urdftool.report.json_output import paired

    value = {"a": "x\udcff \U0001F600 \ud800", "b": "\\udcff", "c": "\\\udcff",
             "d": "\ud83d\\ude00", "e": "\ufffd"}
    data = json.dumps(value).encode()
    assert json.loads(paired(data)) == {
        "a": "x\ufffdFF \U0001F600 \ufffdED\ufffdA0\ufffd80", "b": "\\udcff",
        "c": "\\\ufffdFF", "d": "\ufffdED\ufffdA0\ufffdBD\\ude00",
        "e": "\ufffdEF\ufffdBF\ufffdBD"}
    framed = paired(b"Content-Length: %d\r\nContent-Type: x\r\n\r\n" % len(data) + data)
    head, body = framed.split(b"\r\n\r\n")
    assert head == b"Content-Length: %d\r\nContent-Type: x" % len(body)
    assert paired(b'{"a": "plain"}') == b'{"a": "plain"}'


def test_named_is_one_to_one_and_name_bytes_gives_the_name_back():
    import os

    from urdftool.report.json_output import name_bytes, named

    names = ["bad\udcff.urdf", "bad\udcfe.urdf", "bad\ufffd.urdf", "bad\ufffdFF.urdf",
             "bad\ufffdff.urdf", "bad.urdf", "b\u00e9\U0001F600", "\udcc3.urdf"]
    spelt = [named(name) for name in names]
    assert len(set(spelt)) == len(names) and named("bad.urdf") == "bad.urdf"
    assert [os.fsdecode(name_bytes(text)) for text in spelt] == names


def test_no_zero_is_signed_and_a_string_is_left_as_it_is():
    """-0.0 (atan2's pitch of a level frame) is written 0.0, in both writers; the same text in a
    string stays, and -0.05 is a number of its own."""
    from urdftool.report.json_output import line

    data = {"rpy": [0.0, -0.0, -0.05], "name": "j -0.0", "nested": [{"q": -0.0}]}
    for text in (dumps(data), line(data)):
        assert "-0.0," not in text and "-0.0]" not in text and "-0.0}" not in text
        back = json.loads(text)
        assert back["rpy"] == [0.0, 0.0, -0.05] and math.copysign(1, back["rpy"][1]) == 1
        assert back["name"] == "j -0.0" and math.copysign(1, back["nested"][0]["q"]) == 1


def test_a_signed_zero_is_found_as_the_pattern_finds_it():
    import random

    from urdftool.report.json_output import _NEGATIVE_ZERO, _signed_zero

    parts = ["-0.0", "0.0", "-", "0", ".", "a", "_", " ", ",", "[", "1", "-0.05", "e", "\u00e9", "\u0661"]
    chance = random.Random(19)
    texts = ["".join(chance.choice(parts) for _ in range(chance.randint(0, 8)))
             for _ in range(3000)]
    assert sum(_signed_zero(t) for t in texts) > 100
    assert all(_signed_zero(t) == (_NEGATIVE_ZERO.search(t) is not None) for t in texts)


@pytest.mark.parametrize("items", [
    [], [1], [1, 2, 3], ["a" * 40, "b" * 40], ["a" * 40, "b" * 60],
    [{"x": [0.5] * 30}, {"y": -0.0}, {"z": math.inf}, {"\udcff": "\ufffd"}],
    [{"frame": f"l{k}", "position": [0.1 * k, -0.0, 1e-300]} for k in range(50)],
    [[{"deep": [[-0.0, math.nan]] * 40}] * 3, "short"]])
def test_a_list_written_member_by_member_is_the_list_written_whole(items):
    """write_json_list (fk's documents, as they are computed) writes what write_json writes of
    the whole list, a short list on one line, each member cleaned as the list would be."""
    from urdftool.report.json_output import write_json_list

    whole, streamed = io.StringIO(), io.StringIO()
    write_json(items, whole)
    write_json_list(iter(items), streamed)
    assert streamed.getvalue() == whole.getvalue()
