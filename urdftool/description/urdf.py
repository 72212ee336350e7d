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

# <geometry> children and the attributes each needs: (attribute, how many numbers; None: text).
SHAPES = ("box", "cylinder", "sphere", "mesh")
SHAPE_ATTRIBUTES = {"box": (("size", 3),), "cylinder": (("radius", 1), ("length", 1)),
                    "sphere": (("radius", 1),), "mesh": (("filename", None),)}
ROUND = ("cylinder", "sphere")  # the shapes with a radius
