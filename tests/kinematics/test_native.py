"""Pinocchio's URDF parser is called quietly: urdfdom's console messages become the error's."""

from __future__ import annotations

import pytest

from urdftool.description.load import load
from urdftool.errors import ModelBuildError
from urdftool.kinematics.native import build_model, urdfdom_messages

NO_LIMIT = """<robot name="r"><link name="a"/><link name="b"/>
<joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint>
</robot>"""


def test_urdfdom_refusal_is_an_error_with_its_reasons_and_nothing_on_fd_2(tmp_path, capfd):
    path = tmp_path / "r.urdf"
    path.write_text(NO_LIMIT)
    robot = load(str(path))
    with pytest.raises(ModelBuildError, match="does not specify limits") as caught:
        build_model(robot)
    assert caught.value.robot is robot and caught.value.element is robot.root
    assert "urdf_parser" not in str(caught.value)  # no C++ source positions
    out, err = capfd.readouterr()
    assert err == "" and out == ""


def test_urdfdom_messages_drop_source_positions():
    text = ("Error:   Joint [j] is of type REVOLUTE but it does not specify limits\n"
            "         at line 607 in /project/urdfdom/urdf_parser/src/joint.cpp\n")
    assert urdfdom_messages(text) == ["Joint [j] is of type REVOLUTE but it does not specify limits"]
