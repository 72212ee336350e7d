"""U619-U629: what the robot's launch files start together, and those that could not be read.

Read from the launch files without running them (:mod:`urdftool.description.runtime`): a
finding here is an error when a launch file always does what it says, a warning naming the
condition when it does so only under an argument or condition (docs/certainty.md).
"""

from __future__ import annotations

from urdftool.description.companions import parameter_files
from urdftool.description.runtime import runtime, together, unread_describing
from urdftool.diagnostics import Location
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
                   "(ROS 1's controller manager lets only one controller claim a joint, whatever "
                   "its interface)")
            message = (f"{label(controller)} and {label(other)} both command "
                       f"{', '.join(joints)} {how}; the second to start is refused (resource "
                       "conflict): start one --inactive (ROS 2) or --stopped (ROS 1), or give "
                       "them different joints")
            if state == "certain":
                yield controller.file.at(line), f"{where} starts both active together: " + message
            else:
                yield controller.file.at(line), Conditional(f"if {where}, active: " + message)


@rule("U620", "launch-file-not-read", Severity.INFO)
def launch_file_not_read(robot):
    """A launch file that names the robot file could not be read, or a file it names is not.

    Launch files are read, never run (docs/launch.md): one that is not well-formed, not valid
    Python (or too deep for Python's own parser), over the size limit or left with a merge
    conflict tells nothing, so the controller YAML it loads, the controllers it starts, the
    xacro arguments it builds the robot with and the SRDF it gives MoveIt are not known, and
    are not checked: companions that only it names are not found. A note at the launch file
    (where the parser stopped, when it said), saying why; the robot is checked as if the file
    were not there. Launch tests are left out (a test is not a deployment). A parameter file
    or launch file one names by a path leading outside the repository (itself or through a
    link) is not read either: a note at the line naming it, for a launch file that describes
    the robot.

    Bad: ``launch/robot.launch.py`` loading ``config/ctrl.yaml`` and holding ``x = a.b.b...``
    100,000 attributes long (``RecursionError`` in ``ast``); ``<rosparam
    file="$(dirname)/../../other/ctrl.yaml"/>`` leading out of the repository
    Good: a launch file Python's parser reads, naming files inside the repository
    """
    if robot.path == "-":
        return
    for display, problem, line in unread_describing(robot.path):
        yield Location(display, line), (
            f"this launch file names the robot and could not be read ({problem}): the "
            "controllers, parameter files and xacro arguments it gives the robot are not known, "
            "and not checked")
    for display, line, written in runtime(robot).outside():
        yield Location(display, line), (
            f"this launch file names '{written}', which leads outside the repository: not read, "
            "so the controllers, parameters and launch files it holds are not known, and not "
            "checked")
