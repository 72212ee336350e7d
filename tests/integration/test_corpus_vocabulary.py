"""The vocabulary rules (U020-U022) on the public corpus: every finding is listed here with why
it is right, and nothing else is found. The findings come from the shared ``corpus_run``."""

from __future__ import annotations

import os
from collections import Counter

import pytest

from conftest import CORPUS, corpus_entry_points

pytestmark = pytest.mark.skipif(not corpus_entry_points(), reason="corpus not available")

INERTIA = ("urdfdom's parseInertial reads ixx ixy ixz iyy iyz izz (the upper triangle of the "
           "symmetric tensor); the lower-triangle copies are never read")
DYNAMICS = ("urdfdom's parseJointDynamics reads damping and friction only; Franka's elasticity "
            "and friction model parameters are not read by urdfdom, KDL or MoveIt")
COLLISION_MATERIAL = ("urdfdom's parseCollision reads origin and geometry (and name); a "
                      "<material> is read only by parseVisual")
BOX_SCALE = "urdfdom's parseBox reads size only; scale is a <mesh> attribute"

# (entry point, file the finding is in, code, message up to its first ':') -> (count, why)
EXPECTED = {
    ("darwin_description/urdf/darwin.urdf", "darwin_description/urdf/darwin.urdf", "U022",
     "<box> attribute 'scale' has no effect"): (2, BOX_SCALE),
    ("darwin_description/urdf/darwin.urdf", "darwin_description/urdf/darwin.urdf", "U022",
     "<inertia> attributes 'iyx', 'izx', 'izy' have no effect"): (24, INERTIA),
    ("robotis_op_description/robots/robotis_op.urdf", "robotis_op_description/robots/robotis_op.urdf",
     "U022", "<box> attribute 'scale' has no effect"): (2, BOX_SCALE),
    ("example-robot-data/robots/bolt_description/robots/bolt.urdf",
     "example-robot-data/robots/bolt_description/robots/bolt.urdf", "U022",
     "<material> in <collision> has no effect"): (9, COLLISION_MATERIAL),
    ("example-robot-data/robots/solo_description/robots/solo.urdf",
     "example-robot-data/robots/solo_description/robots/solo.urdf", "U022",
     "<material> in <collision> has no effect"): (13, COLLISION_MATERIAL),
    ("example-robot-data/robots/solo_description/robots/solo12.urdf",
     "example-robot-data/robots/solo_description/robots/solo12.urdf", "U022",
     "<material> in <collision> has no effect"): (17, COLLISION_MATERIAL),
    ("op3_description/urdf/robotis_op3.urdf.xacro", "op3_description/urdf/robotis_op3.visuals.xacro",
     "U022", "<material> in <collision> has no effect"): (21, COLLISION_MATERIAL),
    **{(entry, "franka_description/robots/common/franka_arm.xacro", "U022",
        "<dynamics> attributes 'D', 'K', 'mu_coulomb', 'mu_viscous' have no effect"): (14, DYNAMICS)
       for entry in ("franka_description/robots/dual_panda/dual_panda_example.urdf.xacro",
                     "franka_description/robots/fr3/fr3.urdf.xacro",
                     "franka_description/robots/panda/panda.urdf.xacro")},
    ("franka_gazebo/test/launch/panda-gazebo.urdf", "franka_gazebo/test/launch/panda-gazebo.urdf",
     "U022", "<dynamics> attributes 'D', 'K', 'mu_coulomb', 'mu_viscous' have no effect"):
        (7, DYNAMICS),
    ("franka_gazebo/test/launch/panda-gazebo.urdf", "franka_gazebo/test/launch/panda-gazebo.urdf",
     "U022", "<limit> attribute 'acceleration' has no effect"):
        (7, "urdfdom's parseJointLimits reads lower, upper, effort and velocity; URDF has no "
            "acceleration limit (MoveIt takes it from joint_limits.yaml)"),
}


def test_every_vocabulary_finding_on_the_corpus_is_listed_and_true(corpus_run):
    found = Counter()
    for (path, _), result in corpus_run.values():
        for finding in result.findings:
            if finding.code.startswith("U02"):
                # real paths on both sides: the corpus may be reached through a link
                shown = os.path.relpath(os.path.realpath(finding.file), os.path.realpath(CORPUS))
                found[(path, shown, finding.code, finding.message.split(":")[0])] += 1
    assert dict(found) == {key: count for key, (count, _) in EXPECTED.items()}
