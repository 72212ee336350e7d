"""physics.frames: a joint's axis as urdfdom reads it."""

from __future__ import annotations

from lxml import etree

from urdftool.physics.frames import axis


def test_axis_is_the_first_axis_child_past_comments_and_other_children():
    joint = etree.fromstring('<joint><!-- the axis --><limit/><axis xyz="0 0 2"/>'
                             '<axis xyz="1 0 0"/><mimic><axis xyz="0 1 0"/></mimic></joint>')
    assert axis(joint) == (0.0, 0.0, 1.0)


def test_axis_absent_is_x_and_zero_or_malformed_is_none():
    assert axis(etree.fromstring('<joint><parent link="a"/></joint>')) == (1.0, 0.0, 0.0)
    assert axis(etree.fromstring('<joint><axis xyz="0 0 0"/></joint>')) is None
    assert axis(etree.fromstring('<joint><axis xyz="0 one 0"/></joint>')) is None
