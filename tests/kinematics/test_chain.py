"""The limb as a reduced Pinocchio model (urdftool.kinematics.chain)."""

from __future__ import annotations

import numpy as np
import pytest

from urdftool.description.load import load
from urdftool.kinematics import configuration as config
from urdftool.kinematics import ik
from urdftool.kinematics.chain import build_chain
from urdftool.kinematics.fk import forward_kinematics

# two legs whose joints are named as their child links, as ANYmal's are (LF_HAA is a link and a
# joint): URDF allows it, and Pinocchio's buildReducedModel raised "Several frames match the
# filter" for it, so ik and workspace failed with a traceback on such robots
SAME_NAMES = b"""<robot name="same_names">
  <link name="base"/>
  <link name="LF_HAA"/><link name="LF_KFE"/><link name="LF_FOOT"/>
  <link name="RF_HAA"/><link name="RF_KFE"/>
  <joint name="LF_HAA" type="revolute"><parent link="base"/><child link="LF_HAA"/>
    <origin xyz="0.3 0.1 0"/><axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="LF_KFE" type="revolute"><parent link="LF_HAA"/><child link="LF_KFE"/>
    <origin xyz="0 0.05 -0.2"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="LF_FOOT" type="fixed"><parent link="LF_KFE"/><child link="LF_FOOT"/>
    <origin xyz="0 0 -0.25"/></joint>
  <joint name="RF_HAA" type="revolute"><parent link="base"/><child link="RF_HAA"/>
    <origin xyz="0.3 -0.1 0"/><axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="RF_KFE" type="revolute"><parent link="RF_HAA"/><child link="RF_KFE"/>
    <origin xyz="0 -0.05 -0.2"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
</robot>"""


def test_a_limb_whose_joints_are_named_as_links_is_built_and_solved(tmp_path):
    path = tmp_path / "robot.urdf"
    path.write_bytes(SAME_NAMES)
    chain = build_chain(load(path), "base", "LF_FOOT")  # the other leg's joints are locked
    assert chain.joints == ["LF_HAA", "LF_KFE"]
    assert [variable.name for variable in chain.variables] == ["LF_HAA", "LF_KFE"]
    names = {frame.name for frame in chain.model.frames}
    assert {"LF_HAA", "RF_HAA", "RF_KFE", "LF_FOOT"} <= names and not any(
        "\x1f" in name for name in names)
    row = config.from_words(chain.kinematics.variables,
                            {"LF_HAA": "0.4", "LF_KFE": "-1.1"}).values[0]
    configurations = config.Configurations(chain.kinematics.variables, row[None, :], [])
    pose = forward_kinematics(chain.kinematics, configurations, ["LF_FOOT"],
                              "base").matrices[0, 0]
    solution = ik.solve(chain, ik.Target(pose[:3, 3], pose[:3, :3]), ik.seeds(chain, 4, 0))
    assert solution.solved, solution.reason
    assert np.allclose(solution.x, [0.4, -1.1], atol=1e-6)


def test_a_limb_beside_a_fixed_joint_named_as_its_link_is_built(tmp_path):
    """Locking the left leg, whose fixed joint LF_FOOT is its link's name and holds a link of
    its own (Baxter's left_hand, which holds its camera): buildReducedModel raised "Several frames match the filter" for the right arm's
    ik and workspace, a traceback."""
    path = tmp_path / "robot.urdf"
    path.write_bytes(SAME_NAMES.replace(b"</robot>", b'<link name="LF_SENSOR"/><joint '
                                        b'name="LF_SENSOR" type="fixed"><parent link="LF_FOOT"/>'
                                        b'<child link="LF_SENSOR"/></joint></robot>'))
    chain = build_chain(load(path), "base", "RF_KFE")
    assert chain.joints == ["RF_HAA", "RF_KFE"]
    names = [frame.name for frame in chain.model.frames]
    assert names.count("LF_FOOT") == 2 and not any("\x1f" in name for name in names)


def test_a_limb_whose_pinocchio_data_cannot_fit_is_refused_before_allocating(tmp_path,
                                                                            monkeypatch):
    # ik and workspace on a 999-joint limb ran out of a 2 GiB budget (U018, "raise the budget
    # with --max-memory": to 60 GiB); dynamics said why, before allocating; now both do
    import resource

    from conftest import synthetic_robot
    from urdftool.errors import IKError

    robot = load(str(synthetic_robot(tmp_path, 301)))
    monkeypatch.setattr(resource, "getrlimit", lambda _: (1024 ** 3, resource.RLIM_INFINITY))
    with pytest.raises(IKError, match="300 joint variables from 'l0' to 'l300'.*cube of the"):
        build_chain(robot, None, "l300")
    assert build_chain(robot, "l290", "l300").tip == "l300"  # a sub-chain fits


def test_a_limb_variable_of_no_range_is_held(tmp_path):
    """double_pendulum_simple's joints are written ``<limit lower="0" upper="0">``: its
    workspace of 2,000 samples was one point, said as a reach of 0.3 m with no word of it."""
    path = tmp_path / "robot.urdf"
    path.write_bytes(SAME_NAMES.replace(b'lower="-2" upper="2"', b'lower="0.5" upper="0.5"'))
    chain = build_chain(load(str(path)), "base", "LF_FOOT")
    assert chain.held == ["LF_KFE"]
    path.write_bytes(SAME_NAMES)
    assert build_chain(load(str(path)), "base", "LF_FOOT").held == []
