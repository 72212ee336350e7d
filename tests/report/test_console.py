"""Helpers shared by the command renderers: fixed-point numbers and the JSON writer."""

from __future__ import annotations

import io
import json
import math

from urdftool.report.console import fixed
from urdftool.report.json_output import write_json


def test_fixed_drops_the_minus_of_a_rounded_zero():
    assert fixed(-1e-9) == "0.000000"
    assert fixed(-0.5) == "-0.500000"
    assert fixed(1.23456789, 3) == "1.235"


def test_write_json_indents_and_ends_with_a_newline():
    stream = io.StringIO()
    write_json({"a": [1, 2.5]}, stream)
    assert stream.getvalue() == json.dumps({"a": [1, 2.5]}, indent=2) + "\n"


def test_write_json_finite_writes_null_for_infinite_and_nan():
    stream = io.StringIO()
    write_json({"d": math.inf, "rows": [(1.0, math.nan)], "n": -math.inf}, stream, finite=True)
    assert json.loads(stream.getvalue()) == {"d": None, "rows": [[1.0, None]], "n": None}
    assert "Infinity" not in stream.getvalue()
