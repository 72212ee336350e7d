"""Numbers read in bulk against ``np.fromstring``, the reader they stand in for: generated
lists, hostile texts, every COLLADA index list of the corpus, and COLLADA documents read both
ways."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import CORPUS
from urdftool.description import collada, number_lists
from urdftool.description.collada import ColladaProblem, read_collada

WHITE = " \t\n\r\x0b\x0c"
EXAMPLES = settings(max_examples=300, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])


def _fromstring(text: str):
    """What the reader read before: the numbers, or None where numpy refuses the text."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            return np.fromstring(text, dtype=np.int64, sep=" ")
        except (ValueError, DeprecationWarning):
            return None


def _same_as_numpy(text: str, stride: int = 1, offset: int = 0) -> None:
    found = number_lists.whole_numbers(text, stride, offset)
    expected = _fromstring(text) if text.strip(WHITE) else np.zeros(0, dtype=np.int64)
    if found is None:
        return
    assert expected is not None, f"read {text[:60]!r}, which numpy refuses"
    count, column = found
    assert count == len(expected)
    assert column.dtype == np.int64
    assert column.tobytes() == expected[offset::stride].tobytes()


words = st.text(alphabet="0123456789", min_size=1, max_size=16)
white = st.text(alphabet=WHITE, max_size=3)


@EXAMPLES
@given(white, st.lists(st.tuples(words, white.filter(bool)), max_size=60), st.integers(1, 4),
       st.data())
def test_plain_lists_read_as_numpy_reads_them(lead, pairs, stride, data):
    text = lead + "".join(word + after for word, after in pairs)
    offset = data.draw(st.integers(0, stride - 1))
    # plain (ASCII digits, at most sixteen, and C white space): read here, not left to numpy
    assert number_lists.whole_numbers(text, stride, offset) is not None
    _same_as_numpy(text, stride, offset)


@EXAMPLES
@given(st.text(alphabet="0123456789 \t\n-+.eEx\x00\u0661\u00a0\x1c", max_size=80),
       st.integers(1, 3))
def test_any_text_is_read_as_numpy_reads_it_or_left_to_numpy(text, stride):
    _same_as_numpy(text, stride, stride - 1)


@pytest.mark.parametrize("text", ["-1 2", "+1", "1.5", "1e3", "0x10", "1,2", "1 a", "\u0661",
                                  "\u00a02", "1\x1c2", "1\x002", "1" * 17, "2 " + "9" * 20])
def test_what_is_not_plain_is_left_to_numpy(text):
    assert number_lists.whole_numbers(text) is None


@pytest.mark.parametrize("text", ["", " ", "\n\t ", "0", "007", "9" * 16, "1\x0b2\x0c3\r4"])
def test_edges_read_as_numpy_reads_them(text):
    assert number_lists.whole_numbers(text) is not None
    _same_as_numpy(text)


def test_long_lists_with_every_length():
    rng = np.random.default_rng(29)
    values = rng.integers(0, 10 ** rng.integers(1, 17, 50_000))
    text = " ".join(map(str, values))
    for stride, offset in ((1, 0), (3, 0), (3, 2), (5, 4)):
        count, column = number_lists.whole_numbers(text, stride, offset)
        assert count == len(values) and np.array_equal(column, values[offset::stride])


def test_corpus_index_lists_read_as_numpy_reads_them():
    from lxml import etree

    files = sorted(CORPUS.rglob("*.dae"))
    if not files:
        pytest.skip("no corpus")
    read = 0
    for path in files:
        root = etree.parse(str(path), collada.parser()).getroot()
        for element in root.iter("{*}p", "{*}vcount"):
            text = element.text or ""
            if len(text) >= number_lists.BULK:
                assert number_lists.whole_numbers(text) is not None
                for stride in (1, 2, 3):
                    _same_as_numpy(text, stride, stride - 1)
                read += 1
    assert read > 50


def _document(p: str, stride: int = 1, kind: str = "triangles", vcount: str = "") -> bytes:
    inputs = "".join(f'<input semantic="{"VERTEX" if i == 0 else "NORMAL"}" '
                     f'source="#{"v" if i == 0 else "n"}" offset="{i}"/>' for i in range(stride))
    positions = " ".join(f"{i} {i % 7} {i % 3}" for i in range(200))
    extra = f"<vcount>{vcount}</vcount>" if vcount else ""
    return (f'<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema"><library_geometries>'
            f'<geometry id="g"><mesh><source id="pos"><float_array id="a" count="600">'
            f'{positions}</float_array><technique_common><accessor source="#a" count="200" '
            f'stride="3"><param name="X"/><param name="Y"/><param name="Z"/></accessor>'
            f'</technique_common></source><source id="n"><float_array id="na" count="3">0 0 1'
            f'</float_array><technique_common><accessor source="#na" count="1" stride="3">'
            f'<param name="X"/><param name="Y"/><param name="Z"/></accessor></technique_common>'
            f'</source><vertices id="v"><input semantic="POSITION" source="#pos"/></vertices>'
            f'<{kind}>{inputs}{extra}<p>{p}</p></{kind}></mesh></geometry></library_geometries>'
            f'<library_visual_scenes><visual_scene id="s"><node><instance_geometry url="#g"/>'
            f'</node></visual_scene></library_visual_scenes></COLLADA>').encode()


def _both_ways(data: bytes, monkeypatch):
    """read_collada's result or problem, with the bulk reader and without it."""
    outcomes = []
    for bulk in (0, 10 ** 9):
        monkeypatch.setattr(number_lists, "BULK", bulk)
        try:
            vertices, faces = read_collada(data, max_triangles=10 ** 6)
            outcomes.append((vertices.tobytes(), faces.tobytes(), faces.dtype))
        except ColladaProblem as problem:
            outcomes.append(str(problem))
    return outcomes


@pytest.mark.parametrize("stride", [1, 2, 3])
def test_collada_reads_a_long_index_list_the_same_both_ways(stride, monkeypatch):
    rng = np.random.default_rng(stride)  # the other inputs' indices are never used
    p = "\n".join(" ".join(map(str, row)) for row in rng.integers(0, 200, (2000, 3 * stride)))
    with_bulk, without = _both_ways(_document(p, stride), monkeypatch)
    assert with_bulk == without and not isinstance(with_bulk, str)


def test_collada_reads_a_long_polylist_the_same_both_ways(monkeypatch):
    rng = np.random.default_rng(4)
    counts = rng.integers(3, 7, 1500)
    p = " ".join(f"{i} 0" for i in rng.integers(0, 200, int(counts.sum())))
    data = _document(p, 2, "polylist", " ".join(map(str, counts)))
    with_bulk, without = _both_ways(data, monkeypatch)
    assert with_bulk == without and not isinstance(with_bulk, str)


@pytest.mark.parametrize("p", ["0 1 2 " * 2000 + "3 -4 5", "0 1 2 " * 2000 + "3 4",
                               "0 1 2 " * 2000 + "3 4 x", "0 1 2 " * 2000 + "3 4 500",
                               "0 1 2 " * 2000 + "3 4 " + "9" * 20])
def test_collada_refuses_a_long_bad_index_list_the_same_both_ways(p, monkeypatch):
    with_bulk, without = _both_ways(_document(p), monkeypatch)
    assert with_bulk == without and isinstance(with_bulk, str)
