"""``urdftool.terminal``: the command-line words every robot command reads."""

from __future__ import annotations

import pytest

from urdftool.errors import UsageError
from urdftool.terminal import pairs


def test_pairs_split_at_the_first_separator_by_default():
    # a xacro argument's value may hold '=' (a launch-style "k=v" string)
    assert pairs(["prefix=a=b"], "--arg") == {"prefix": "a=b"}


def test_pairs_split_at_the_last_separator_when_the_name_may_hold_it():
    # a joint named 'gain=2' and its value
    assert pairs(["gain=2=0.5", " elbow=1"], "--q", strip=True, last=True) == {
        "gain=2": "0.5", "elbow": "1"}


@pytest.mark.parametrize("last", [False, True])
@pytest.mark.parametrize("word", ["elbow", "=1"])
def test_a_pair_without_name_or_separator_is_a_usage_error(word, last):
    with pytest.raises(UsageError, match="--q must be NAME=VALUE"):
        pairs([word], "--q", last=last)
