"""urdftool's own data files, read as the checks read them."""

from __future__ import annotations

import json

import pytest

from urdftool.description import data


@pytest.mark.parametrize("name, table", [("ros2_controllers.json", "schemas"),
                                         ("ros2_controllers.json", "classes"),
                                         ("gazebo_plugins.json", "plugins")])
def test_a_lazy_table_reads_as_the_whole_file_decoded(name, table):
    """Every entry of a table read lazily (its text decoded when first asked) and the rest
    of the file are what decoding the file whole gives, in its order; an entry not asked is
    not decoded."""
    text = (data.FOLDER / name).read_text(encoding="utf-8")
    whole, lazy = json.loads(text), data._with_lazy_table(text, table)
    assert isinstance(lazy[table], data.Table)
    assert {k: v for k, v in lazy.items() if k != table} == \
        {k: v for k, v in whole.items() if k != table}
    first, *_ = whole[table]
    assert first in lazy[table] and "no such entry" not in lazy[table]
    assert lazy[table][first] == whole[table][first] and len(lazy[table]._decoded) == 1
    assert list(lazy[table]) == list(whole[table]) and len(lazy[table]) == len(whole[table])
    assert lazy[table] == whole[table]
    with pytest.raises(KeyError):
        lazy[table]["no such entry"]


@pytest.mark.parametrize("text", ['{\n  "t": {"a": 1}\n}\n', '{"t": {"a": 1}}',
                                  '{\n  "u": {\n    "a": 1\n  }\n}\n'])
def test_a_file_not_laid_out_as_the_scripts_write_it_is_decoded_whole(text):
    assert data._with_lazy_table(text, "t") is None


def test_a_lazy_table_keeps_the_last_of_a_key_written_twice_as_json_does():
    text = '{\n  "t": {\n    "a": 1,\n    "b": {"c": [1,\n 2]},\n    "a": 3\n  },\n  "u": 4\n}\n'
    lazy = data._with_lazy_table(text, "t")
    assert dict(lazy["t"]) == json.loads(text)["t"] == {"a": 3, "b": {"c": [1, 2]}}
    assert lazy["u"] == 4 and list(lazy["t"]) == ["a", "b"]
