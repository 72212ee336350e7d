"""The URDF vocabulary: joint types and geometry shapes, as urdfdom defines them.

Every module that asks "is this joint movable?" or "is this a shape?" reads these names, so a
rule, the kinematics and the collision checker never disagree about what a joint or shape is.
"""

from __future__ import annotations

# urdf::Joint types in the order urdfdom's parser lists them (joint.cpp, parseJoint).
JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")
MOVING = ("revolute", "continuous", "prismatic")  # one variable along or about one axis
LIMITED = ("revolute", "prismatic")  # urdfdom requires a <limit>
AXIS = MOVING + ("planar",)  # an <axis> is read (the planar joint's normal)
VARIABLE = MOVING + ("floating", "planar")  # the child link moves: every type but fixed
ANGULAR = ("revolute", "continuous")  # the variable is an angle in [rad]
UNITS = {"revolute": "rad", "prismatic": "m"}  # of the <limit> lower/upper of a LIMITED joint
# a joint's degrees of freedom: how many numbers its velocity is (Pinocchio's nv, Drake's DOF)
DEGREES = {**dict.fromkeys(MOVING, 1), "fixed": 0, "floating": 6, "planar": 3}

# <geometry> children and the attributes each needs: (attribute, how many numbers; None: text).
SHAPES = ("box", "cylinder", "sphere", "mesh")
SHAPE_ATTRIBUTES = {"box": (("size", 3),), "cylinder": (("radius", 1), ("length", 1)),
                    "sphere": (("radius", 1),), "mesh": (("filename", None),)}
ROUND = ("cylinder", "sphere")  # the shapes with a radius

# ---------------------------------------------------------------------------------------------
# The vocabulary: every element and attribute urdfdom reads, where, and which it requires.
#
# Sources (the first that reads a name is cited in ``source``):
#   urdfdom  urdf_parser/src/model.cpp (parseURDF), link.cpp (parseLink, parseInertial,
#            parseVisual, parseCollision, parseGeometry, parseMaterial, parse<Shape>), joint.cpp
#            (parseJoint, parseJointLimits/Dynamics/Safety/Calibration/Mimic), pose.cpp
#            (parsePose), sensor_parser.cpp (<sensor>)
#   spec     the URDF XML pages of the ROS wiki (urdf/XML/robot, link, joint, ...)
#   xsd      urdfdom's xsd/urdf.xsd (names it lists that urdfdom does not read: link type,
#            collision verbose, calibration reference_position, origin quat_xyzw)
# ---------------------------------------------------------------------------------------------


class Place:
    """What urdfdom reads of an element at one place in the tree.

    attributes: the attributes read there; required: those it refuses the element without
    children: child tag -> the name of its :data:`VOCABULARY` entry
    ignored: known names urdfdom reads nothing from here, with why (a warning: no effect)
    extensions: child elements urdfdom skips here that another program reads (left alone)
    elsewhere: attributes urdfdom skips here that another program reads, with who (a note)
    source: where the names come from
    """

    __slots__ = ("attributes", "required", "children", "ignored", "extensions", "elsewhere",
                 "source")

    def __init__(self, attributes=(), required=(), children=None, ignored=None, source="",
                 extensions=None, elsewhere=None):
        self.extensions = dict(extensions or {})
        self.elsewhere = dict(elsewhere or {})
        self.attributes = tuple(attributes)
        self.required = tuple(required)
        self.children = dict(children or {})
        self.ignored = dict(ignored or {})
        self.source = source

    def names(self) -> tuple[str, ...]:
        """Every name valid at this place, children and attributes."""
        return (*self.children, *self.attributes)


# Elements inside a <link> that urdfdom skips and another program reads: left alone.
LINK_EXTENSIONS = {
    "contact": "PyBullet (lateral_friction, rolling_friction, restitution, ...)",
    "self_filter": "robot_self_filter (ROS 1)",
    "collision_checking": "arm_navigation collision checking (ROS 1)",
    "buoyancy": "freefloating_gazebo's fluid plugin (ROS 1; origin, compensation, limit, damping)",
}

_POSE = "origin"
VOCABULARY: dict[str, Place] = {
    "robot": Place(("name", "version"), ("name",),
                   {"link": "link", "joint": "joint", "material": "material_global"},
                   source="urdfdom model.cpp parseURDF; version: urdfdom >= 1.0, spec robot"),
    "link": Place(("name", "type"), ("name",),
                  {"inertial": "inertial", "visual": "visual", "collision": "collision"},
                  extensions=LINK_EXTENSIONS,
                  source="urdfdom link.cpp parseLink; type: xsd (PR2)"),
    "inertial": Place((), (), {"origin": _POSE, "mass": "mass", "inertia": "inertia"},
                      source="urdfdom link.cpp parseInertial"),
    "origin": Place(("xyz", "rpy", "quat_xyzw"), (),
                    source="urdfdom pose.cpp parsePose; quat_xyzw: xsd"),
    "mass": Place(("value",), ("value",), source="urdfdom link.cpp parseInertial"),
    "inertia": Place(("ixx", "ixy", "ixz", "iyy", "iyz", "izz"),
                     ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"),
                     source="urdfdom link.cpp parseInertial"),
    "visual": Place(("name", "group"), (),
                    {"origin": _POSE, "geometry": "geometry", "material": "material"},
                    source="urdfdom link.cpp parseVisual; name: urdfdom >= 1.0; group: urdfdom < 1.0"),
    "collision": Place(("name", "group"), (),
                       {"origin": _POSE, "geometry": "geometry", "verbose": "verbose"},
                       ignored={"material": "urdfdom reads <material> only in <visual>; a "
                                            "collision has no colour"},
                       source="urdfdom link.cpp parseCollision; verbose: xsd"),
    "verbose": Place(("value",), source="xsd collision"),
    "geometry": Place((), (), {shape: shape for shape in SHAPES},
                      source="urdfdom link.cpp parseGeometry"),
    "box": Place(("size",), ("size",), source="urdfdom link.cpp parseBox"),
    "cylinder": Place(("radius", "length"), ("radius", "length"),
                      source="urdfdom link.cpp parseCylinder"),
    "sphere": Place(("radius",), ("radius",), source="urdfdom link.cpp parseSphere"),
    "mesh": Place(("filename", "scale"), ("filename",), source="urdfdom link.cpp parseMesh"),
    "material": Place(("name",), ("name",), {"color": "color", "texture": "texture"},
                      source="urdfdom link.cpp parseVisual, parseMaterial"),
    "material_global": Place(("name",), ("name",), {"color": "color", "texture": "texture"},
                             source="urdfdom model.cpp parseURDF, link.cpp parseMaterial"),
    "color": Place(("rgba",), ("rgba",), source="urdfdom link.cpp parseMaterial"),
    "texture": Place(("filename",), (), source="urdfdom link.cpp parseMaterial"),
    "joint": Place(("name", "type"), ("name", "type"),
                   {"origin": _POSE, "parent": "parent", "child": "child", "axis": "axis",
                    "calibration": "calibration", "dynamics": "dynamics", "limit": "limit",
                    "safety_controller": "safety_controller", "mimic": "mimic"},
                   elsewhere={"dont_collapse": (
                       "Isaac Gym's and Isaac Sim's URDF importers read it: a fixed joint so "
                       "marked is kept, not merged into its parent (a foot or sensor frame)")},
                   source="urdfdom joint.cpp parseJoint; dont_collapse: Isaac Sim URDF "
                          "importer"),
    "parent": Place(("link",), ("link",), source="urdfdom joint.cpp parseJoint"),
    "child": Place(("link",), ("link",), source="urdfdom joint.cpp parseJoint"),
    "axis": Place(("xyz",), (), ignored={
        "rpy": "urdfdom reads only xyz of <axis>: the axis is a direction in the joint frame; "
               "rotate the frame with the joint's <origin rpy>"},
                  source="urdfdom joint.cpp parseJoint"),
    "calibration": Place(("rising", "falling", "reference_position"), (),
                         source="urdfdom joint.cpp parseJointCalibration; reference_position: xsd"),
    "dynamics": Place(("damping", "friction"), (), source="urdfdom joint.cpp parseJointDynamics"),
    "limit": Place(("lower", "upper", "effort", "velocity"), ("effort", "velocity"),
                   source="urdfdom joint.cpp parseJointLimits"),
    "safety_controller": Place(("soft_lower_limit", "soft_upper_limit", "k_position",
                                "k_velocity"), ("k_velocity",),
                               source="urdfdom joint.cpp parseJointSafety"),
    "mimic": Place(("joint", "multiplier", "offset"), ("joint",),
                   source="urdfdom joint.cpp parseJointMimic"),
}

# The numbers urdfdom reads, by VOCABULARY place: (attribute, count). A count of 1 is a scalar,
# read by urdf::strToDouble of the whole text; 3 and 4 are a Vector3 (pose.h) and a Color
# (color.h), split at spaces and each part read so (values.urdfdom_refuses holds the grammar).
NUMBERS: dict[str, tuple[tuple[str, int], ...]] = {
    "origin": (("xyz", 3), ("rpy", 3)),
    "axis": (("xyz", 3),),
    "limit": (("lower", 1), ("upper", 1), ("effort", 1), ("velocity", 1)),
    "dynamics": (("damping", 1), ("friction", 1)),
    "mimic": (("multiplier", 1), ("offset", 1)),
    "calibration": (("rising", 1), ("falling", 1)),
    "safety_controller": (("soft_lower_limit", 1), ("soft_upper_limit", 1), ("k_position", 1),
                          ("k_velocity", 1)),
    "mass": (("value", 1),),
    "inertia": tuple((name, 1) for name in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")),
    "box": (("size", 3),),
    "cylinder": (("radius", 1), ("length", 1)),
    "sphere": (("radius", 1),),
    "mesh": (("scale", 3),),
    "color": (("rgba", 4),),
}
# a <joint>'s children that hold numbers, in the order the joint rules read them
JOINT_NUMBER_PLACES = ("origin", "axis", "limit", "dynamics", "mimic", "calibration",
                       "safety_controller")

# Blocks at the top level that urdfdom skips and other programs read. Their content is theirs:
# only what ``EXTENSION_VOCABULARY`` knows of one is checked (for misspellings, never for
# "no effect", since the reader may take more than is listed).
EXTENSIONS = {
    "gazebo": "Gazebo (gazebo_ros, gz-sim): any content, passed to SDFormat",
    "transmission": "ros_control / ros2_control transmissions (ROS 1, PR2 and ros2_control forms)",
    "ros2_control": "ros2_control hardware description",
    "sensor": "urdfdom sensor_parser (camera, ray) and ROS 2 sensors",
    "mujoco": "MuJoCo's URDF compiler options (<mujoco><compiler .../></mujoco>)",
    "plugin": "legacy Gazebo / Webots plugins at the top level",
    "webots": "Webots' urdf2webots extensions",
}
# element path inside an extension block -> the children and attributes known there
EXTENSION_VOCABULARY: dict[str, tuple[str, ...]] = {
    # transmission_interface (ROS 1) TransmissionParser; ros2_control transmission parser
    "transmission": ("name", "type", "joint", "actuator", "plugin", "leftActuator",
                     "rightActuator", "flexJoint", "rollJoint", "gap_joint", "passive_joint",
                     "use_simulated_gripper_joint", "mechanicalReduction", "compensator",
                     "simulated_actuated_joint", "param"),
    "transmission/joint": ("name", "hardwareInterface", "role", "mechanicalReduction",
                           "mechanical_reduction", "offset", "state_interface",
                           "command_interface"),
    "transmission/actuator": ("name", "hardwareInterface", "role", "mechanicalReduction",
                              "mechanical_reduction", "offset", "motorTorqueConstant",
                              "pulsesPerRevolution"),
    # ros2_control's hardware_interface component_parser
    "ros2_control": ("name", "type", "is_async", "rw_rate", "hardware", "joint", "sensor", "gpio",
                     "transmission"),
    "ros2_control/hardware": ("plugin", "param", "classType"),
    "ros2_control/joint": ("name", "is_mimic", "command_interface", "state_interface", "param"),
    "ros2_control/sensor": ("name", "state_interface", "param", "command_interface"),
    "ros2_control/gpio": ("name", "command_interface", "state_interface", "param"),
}



def version_problem(text: str) -> str | None:
    """Why ``text`` is no ``<robot version>`` urdfdom reads (MAJOR.MINOR, 1.0 to 1.2), or None."""
    from urdftool.errors import shown_word
    from urdftool.numbers import is_decimal

    major, dot, minor = text.strip().partition(".")
    if not dot or not is_decimal(major) or not is_decimal(minor):  # ('1².0': int() raised)
        return f"version '{shown_word(text)}' is not of the form MAJOR.MINOR (e.g. 1.0)"
    if max(len(major), len(minor)) > 9 or not (1, 0) <= (int(major), int(minor)) <= (1, 2):
        return f"URDF version {shown_word(text)} is not supported (urdfdom reads 1.0 to 1.2)"
    return None


# A robot file by its name: .urdf or .xacro, in any letter case (the SolidWorks exporter writes
# NAME.URDF: poppy-project/poppy-humanoid's Poppy_Humanoid.URDF). One owner for every walk.
ROBOT_SUFFIXES = (".urdf", ".xacro")
ROBOT_GLOB = "|".join("*" + "".join(f"[{c.lower()}{c.upper()}]" if c.isalpha() else c for c in s)
                      for s in ROBOT_SUFFIXES)  # the same as a listing's pattern


def is_robot_name(name: str) -> bool:
    """Whether a file named ``name`` is a robot description by its name (:data:`ROBOT_GLOB`)."""
    return name.lower().endswith(ROBOT_SUFFIXES)


def is_urdf_name(name: str) -> bool:
    """Whether ``name`` says the file is URDF, read as written (``.urdf``, any case)."""
    return name.lower().endswith(".urdf")


def is_xacro(tag) -> bool:
    """Whether an element tag (lxml: ``{uri}local``, or a raw ``xacro:`` name) is xacro's, where
    only the tag is known (a parser target's): by the URIs the real sweep binds ``xacro:`` to
    (``http://www.ros.org/wiki/xacro``, ``http://ros.org/wiki/xacro``, ``http://wiki.ros.org/xacro``,
    ``.../xacro/#interface``, ``...#xacro``). With the element at hand, :func:`is_xacro_element`
    asks its prefix too, as xacro does."""
    return isinstance(tag, str) and (tag.startswith(("xacro:", "{urn:undeclared:xacro}"))
                                     or "/xacro}" in tag or "xacro/#interface}" in tag
                                     or "#xacro}" in tag)


def is_xacro_element(element) -> bool:
    """Whether an lxml element is xacro's. xacro reads tag names as written (minidom), so
    ``xacro:if`` is its tag whatever URI the document binds the prefix to:
    ``http://wiki.ros.org/xacro`` (672 files of the real sweep, mycobot_ros2's among them),
    ``.../xacro/#interface``, Gazebo's old ``playerstage`` schema; the prefix decides."""
    return is_xacro(element.tag) or getattr(element, "prefix", None) == "xacro"


def is_namespaced(name) -> bool:
    """Whether an lxml tag or attribute name has a namespace (``drake:``, ``xacro:``, ...):
    such names belong to another reader, never to urdfdom."""
    return isinstance(name, str) and (name.startswith("{") or ":" in name)


def where_valid(name: str) -> list[str]:
    """The vocabulary places where ``name`` is a child element."""
    return [place for place, entry in VOCABULARY.items() if name in entry.children]
