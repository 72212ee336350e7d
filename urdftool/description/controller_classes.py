"""The controller classes of ros_control (ROS 1) and ros2_control (ROS 2), as plain data.

Each entry is one class a controller manager can load, as its package's pluginlib XML exports
it, with what the class reads: the parameters naming the URDF joints it commands (or reads),
the parameters it cannot configure without, and the command interface it claims. ``source``
is the repository and the plugin XML the class is exported by (ros2_controllers and
ros_controllers at their rolling/noetic-devel branches).

A class is looked up for the ROS version of the file it is declared in (ROS 2: the file has
``ros__parameters``). A package that is in neither table is a vendor's (franka_example_
controllers, ur_controllers, ...): nothing is known about it, so its ``joint``/``joints`` are not
taken for URDF joints without evidence.
"""

from __future__ import annotations


from urdftool.records import Frozen, NEW

ROS2_REPO = "ros-controls/ros2_controllers"
ROS1_REPO = "ros-controls/ros_controllers"


class ControllerClass(Frozen):
    """One controller class.

    name: ``package/Class`` as written in ``type:``
    ros: 1 or 2
    joints: parameter -> "list" or "name": the parameters naming URDF joints, and whether each
        holds a list or a single name ("any": either, as ROS 1's diff_drive_controller reads)
    required: parameters the class refuses to configure without
    commands: the command interface it claims on its joints: a fixed name, or "@PARAM" for the
        parameter holding the interface name(s); None when it commands none or varies per joint
    state: it only reads (a broadcaster or state controller)
    source: repository and plugin XML exporting it
    """

    name: str
    ros: int
    joints: dict
    required: tuple[str, ...]
    commands: str | None
    state: bool
    source: str

    __slots__ = ("name", "ros", "joints", "required", "commands", "state", "source")

    def __init__(self, name: str, ros: int, joints: dict = NEW, required: tuple[str, ...] = (),
                 commands: str | None = None, state: bool = False, source: str = "") -> None:
        set_field = object.__setattr__
        set_field(self, "name", name)
        set_field(self, "ros", ros)
        set_field(self, "joints", {} if joints is NEW else joints)
        set_field(self, "required", required)
        set_field(self, "commands", commands)
        set_field(self, "state", state)
        set_field(self, "source", source)

    @property
    def package(self) -> str:
        return self.name.split("/")[0]


def _ros2(name, path, joints=None, required=(), commands=None, state=False):
    return ControllerClass(name, 2, joints or {}, tuple(required), commands, state,
                           f"{ROS2_REPO}: {path}")


def _ros1(name, path, joints=None, required=(), commands=None, state=False):
    return ControllerClass(name, 1, joints or {}, tuple(required), commands, state,
                           f"{ROS1_REPO}: {path}")


_LIST = {"joints": "list"}
_ONE = {"joint": "name"}

CLASSES: tuple[ControllerClass, ...] = (
    # --- ROS 2: ros2_controllers ---------------------------------------------------------
    _ros2("ackermann_steering_controller/AckermannSteeringController",
          "ackermann_steering_controller/ackermann_steering_controller.xml",
          {"rear_wheels_names": "list", "front_wheels_names": "list"}),
    _ros2("admittance_controller/AdmittanceController",
          "admittance_controller/admittance_controller.xml", _LIST,
          ("joints", "command_interfaces", "state_interfaces"), "@command_interfaces"),
    _ros2("bicycle_steering_controller/BicycleSteeringController",
          "bicycle_steering_controller/bicycle_steering_controller.xml",
          {"rear_wheels_names": "list", "front_wheels_names": "list"}),
    _ros2("diff_drive_controller/DiffDriveController",
          "diff_drive_controller/diff_drive_plugin.xml",
          {"left_wheel_names": "list", "right_wheel_names": "list"},
          ("left_wheel_names", "right_wheel_names", "wheel_separation", "wheel_radius"),
          "velocity"),
    _ros2("effort_controllers/GripperActionController",
          "gripper_controllers/gripper_action_controller_plugin.xml", _ONE, ("joint",), "effort"),
    _ros2("effort_controllers/JointGroupEffortController",
          "effort_controllers/effort_controllers_plugins.xml", _LIST, ("joints",), "effort"),
    _ros2("force_torque_sensor_broadcaster/ForceTorqueSensorBroadcaster",
          "force_torque_sensor_broadcaster/force_torque_sensor_broadcaster.xml", state=True),
    _ros2("forward_command_controller/ForwardCommandController",
          "forward_command_controller/forward_command_plugin.xml", _LIST,
          ("joints", "interface_name"), "@interface_name"),
    _ros2("forward_command_controller/MultiInterfaceForwardCommandController",
          "forward_command_controller/forward_command_plugin.xml", _ONE,
          ("joint", "interface_names"), "@interface_names"),
    _ros2("gpio_controllers/GpioCommandController",
          "gpio_controllers/gpio_controllers_plugin.xml"),
    _ros2("imu_sensor_broadcaster/IMUSensorBroadcaster",
          "imu_sensor_broadcaster/imu_sensor_broadcaster.xml", state=True),
    _ros2("joint_state_broadcaster/JointStateBroadcaster",
          "joint_state_broadcaster/joint_state_plugin.xml", _LIST, state=True),
    # Foxy's name of the joint state broadcaster (ros2_controllers foxy branch)
    _ros2("joint_state_controller/JointStateController",
          "joint_state_controller/joint_state_plugin.xml (foxy)", _LIST, state=True),
    _ros2("joint_trajectory_controller/JointTrajectoryController",
          "joint_trajectory_controller/joint_trajectory_plugin.xml", _LIST,
          ("joints", "command_interfaces", "state_interfaces"), "@command_interfaces"),
    _ros2("mecanum_drive_controller/MecanumDriveController",
          "mecanum_drive_controller/mecanum_drive_controller.xml"),
    _ros2("parallel_gripper_action_controller/GripperActionController",
          "parallel_gripper_controller/parallel_gripper_action_controller.xml", _ONE, ("joint",),
          "position"),
    _ros2("pid_controller/PidController", "pid_controller/pid_controller.xml"),
    _ros2("pose_broadcaster/PoseBroadcaster", "pose_broadcaster/pose_broadcaster.xml",
          state=True),
    _ros2("position_controllers/GripperActionController",
          "gripper_controllers/gripper_action_controller_plugin.xml", _ONE, ("joint",), "position"),
    _ros2("position_controllers/JointGroupPositionController",
          "position_controllers/position_controllers_plugins.xml", _LIST, ("joints",), "position"),
    _ros2("range_sensor_broadcaster/RangeSensorBroadcaster",
          "range_sensor_broadcaster/range_sensor_broadcaster.xml", state=True),
    _ros2("tricycle_controller/TricycleController", "tricycle_controller/tricycle_controller.xml",
          {"traction_joint_name": "name", "steering_joint_name": "name"},
          ("traction_joint_name", "steering_joint_name")),
    _ros2("tricycle_steering_controller/TricycleSteeringController",
          "tricycle_steering_controller/tricycle_steering_controller.xml",
          {"rear_wheels_names": "list", "front_wheels_names": "list"}),
    _ros2("velocity_controllers/JointGroupVelocityController",
          "velocity_controllers/velocity_controllers_plugins.xml", _LIST, ("joints",), "velocity"),
    # --- ROS 1: ros_controllers ----------------------------------------------------------
    _ros1("ackermann_steering_controller/AckermannSteeringController",
          "ackermann_steering_controller/ackermann_steering_controller_plugins.xml",
          {"rear_wheel": "name", "front_steer": "name"}, ("rear_wheel", "front_steer")),
    _ros1("diff_drive_controller/DiffDriveController",
          "diff_drive_controller/diff_drive_controller_plugins.xml",
          {"left_wheel": "any", "right_wheel": "any"}, ("left_wheel", "right_wheel"), "velocity"),
    _ros1("effort_controllers/GripperActionController",
          "gripper_action_controller/ros_control_plugins.xml", _ONE, ("joint",), "effort"),
    _ros1("effort_controllers/JointEffortController",
          "effort_controllers/effort_controllers_plugins.xml", _ONE, ("joint",), "effort"),
    _ros1("effort_controllers/JointGroupEffortController",
          "effort_controllers/effort_controllers_plugins.xml", _LIST, ("joints",), "effort"),
    _ros1("effort_controllers/JointGroupPositionController",
          "effort_controllers/effort_controllers_plugins.xml", _LIST, ("joints",), "effort"),
    _ros1("effort_controllers/JointPositionController",
          "effort_controllers/effort_controllers_plugins.xml", _ONE, ("joint",), "effort"),
    _ros1("effort_controllers/JointTrajectoryController",
          "joint_trajectory_controller/ros_control_plugins.xml", _LIST, ("joints",), "effort"),
    _ros1("effort_controllers/JointVelocityController",
          "effort_controllers/effort_controllers_plugins.xml", _ONE, ("joint",), "effort"),
    _ros1("force_torque_sensor_controller/ForceTorqueSensorController",
          "force_torque_sensor_controller/force_torque_sensor_controller_plugins.xml", state=True),
    _ros1("four_wheel_steering_controller/FourWheelSteeringController",
          "four_wheel_steering_controller/four_wheel_steering_controller_plugins.xml",
          {"front_wheel": "any", "rear_wheel": "any", "front_steering": "any",
           "rear_steering": "any"}),
    _ros1("imu_sensor_controller/ImuSensorController",
          "imu_sensor_controller/imu_sensor_controller_plugins.xml", state=True),
    _ros1("joint_state_controller/JointStateController",
          "joint_state_controller/joint_state_plugin.xml", state=True),
    _ros1("pos_vel_acc_controllers/JointTrajectoryController",
          "joint_trajectory_controller/ros_control_plugins.xml", _LIST, ("joints",), "position"),
    _ros1("pos_vel_controllers/JointTrajectoryController",
          "joint_trajectory_controller/ros_control_plugins.xml", _LIST, ("joints",), "position"),
    _ros1("position_controllers/GripperActionController",
          "gripper_action_controller/ros_control_plugins.xml", _ONE, ("joint",), "position"),
    _ros1("position_controllers/JointGroupPositionController",
          "position_controllers/position_controllers_plugins.xml", _LIST, ("joints",), "position"),
    _ros1("position_controllers/JointPositionController",
          "position_controllers/position_controllers_plugins.xml", _ONE, ("joint",), "position"),
    _ros1("position_controllers/JointTrajectoryController",
          "joint_trajectory_controller/ros_control_plugins.xml", _LIST, ("joints",), "position"),
    _ros1("velocity_controllers/JointGroupVelocityController",
          "velocity_controllers/velocity_controllers_plugins.xml", _LIST, ("joints",), "velocity"),
    _ros1("velocity_controllers/JointPositionController",
          "velocity_controllers/velocity_controllers_plugins.xml", _ONE, ("joint",), "velocity"),
    _ros1("velocity_controllers/JointTrajectoryController",
          "joint_trajectory_controller/ros_control_plugins.xml", _LIST, ("joints",), "velocity"),
    _ros1("velocity_controllers/JointVelocityController",
          "velocity_controllers/velocity_controllers_plugins.xml", _ONE, ("joint",), "velocity"),
)

# MoveIt's controller managers drive FollowJointTrajectory and GripperCommand action servers
# (and, MoveIt 2 from Jazzy, ParallelGripperCommand: moveit_simple_controller_manager.cpp of
# moveit/moveit2 main); their ``joints`` are URDF joints.
MOVEIT_TYPES = ("FollowJointTrajectory", "GripperCommand", "ParallelGripperCommand")


def action_served(name: str) -> tuple[str, str] | None:
    """(MoveIt controller type, action name under the controller) that a class of
    ros_controllers or ros2_controllers serves, or None: the trajectory controllers serve
    ``follow_joint_trajectory`` (control_msgs/FollowJointTrajectory), the gripper action
    controllers ``gripper_cmd`` (control_msgs/GripperCommand; ROS 2's parallel gripper
    controller control_msgs/ParallelGripperCommand)."""
    if not known_package(name):
        return None
    short = name.split("/")[-1]
    if short == "JointTrajectoryController":
        return "FollowJointTrajectory", "follow_joint_trajectory"
    if short == "GripperActionController":
        kind = "ParallelGripperCommand" if name.startswith("parallel_gripper") else "GripperCommand"
        return kind, "gripper_cmd"
    return None

# What replaces a class in the other ROS version (name in ROS x -> the class ROS y has).
COUNTERPARTS = {
    (1, "effort_controllers/JointEffortController"): "effort_controllers/JointGroupEffortController",
    (1, "effort_controllers/JointTrajectoryController"):
        "joint_trajectory_controller/JointTrajectoryController (command_interfaces: [effort])",
    (1, "joint_state_controller/JointStateController"): "joint_state_broadcaster/JointStateBroadcaster",
    (1, "position_controllers/JointPositionController"): "position_controllers/JointGroupPositionController",
    (1, "position_controllers/JointTrajectoryController"):
        "joint_trajectory_controller/JointTrajectoryController (command_interfaces: [position])",
    (1, "velocity_controllers/JointTrajectoryController"):
        "joint_trajectory_controller/JointTrajectoryController (command_interfaces: [velocity])",
    (1, "velocity_controllers/JointVelocityController"): "velocity_controllers/JointGroupVelocityController",
    (2, "joint_state_broadcaster/JointStateBroadcaster"): "joint_state_controller/JointStateController",
    (2, "joint_state_controller/JointStateController"): "joint_state_broadcaster/JointStateBroadcaster",
    (2, "joint_trajectory_controller/JointTrajectoryController"):
        "position_controllers/JointTrajectoryController (or velocity_/effort_controllers/...)",
}

_BY_VERSION = {ros: {c.name: c for c in CLASSES if c.ros == ros} for ros in (1, 2)}
PACKAGES = {ros: {c.package for c in CLASSES if c.ros == ros} for ros in (1, 2)}


def lookup(name: str, ros: int) -> ControllerClass | None:
    """The class ``name`` for ROS ``ros`` (1 or 2), or None when that ROS has no such class."""
    return _BY_VERSION[ros].get(name)


def known_package(name: str) -> bool:
    """Whether the package of ``package/Class`` is one of ros_controllers or ros2_controllers."""
    package = name.split("/")[0]
    return package in PACKAGES[1] or package in PACKAGES[2]


def classes(ros: int) -> dict[str, ControllerClass]:
    """Every class of ROS ``ros``, by name."""
    return _BY_VERSION[ros]
