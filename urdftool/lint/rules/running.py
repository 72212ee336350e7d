"""U619-U629: what the robot's launch files start together.

Read from the launch files without running them (:mod:`urdftool.description.runtime`): a
finding here is an error when a launch file always does what it says, a warning naming the
condition when it does so only under an argument or condition (docs/certainty.md).
"""

from __future__ import annotations

from urdftool.description.companions import parameter_files
from urdftool.description.runtime import together
from urdftool.lint.catalogue import Conditional, Severity, rule
from urdftool.lint.rules.controllers import label, shared_commands


@rule("U619", "controllers-started-together", Severity.ERROR)
def controllers_started_together(robot):
    """Two controllers a launch file starts active together command the same joint.

    The controller manager gives each command interface to one controller: the second of the
    two is refused ("Resource conflict"; ROS 1's controller manager refuses two controllers
    claiming one joint whatever their interfaces, ROS 2's two claiming the same interface of
    it), and the launch fails or runs without it. An error when a launch file of the robot as
    checked starts both, active, unconditionally; a warning naming the condition when it does
    so only under an argument or condition. Two controllers a file offers as alternatives and
    no launch file starts together are U610's note, or nothing.

    Bad: ``spawner joint_state_broadcaster arm_controller arm_position_controller`` with both
    on ``joints: [shoulder, elbow]``
    Good: ``spawner arm_position_controller --inactive`` (switch to it when needed)
    """
    named = parameter_files(robot)
    for ros1 in (True, False):
        for controller, other, line, joints in shared_commands(robot, by_interface=not ros1):
            if (controller.ros == 1) != ros1:
                continue
            state, where = together(robot, other, controller, named)
            if state not in ("certain", "conditional"):
                continue
            how = ("through the same interfaces" if not ros1 else
                   "(ROS 1's controller manager lets one controller claim a joint)")
            message = (f"{label(controller)} and {label(other)} both command "
                       f"{', '.join(joints)} {how}; the second to start is refused (resource "
                       "conflict): start one --inactive (ROS 2) or --stopped (ROS 1), or give "
                       "them different joints")
            if state == "certain":
                yield controller.file.at(line), f"{where} starts both active together: {message}"
            else:
                yield controller.file.at(line), Conditional(f"if {where}, active: {message}")
