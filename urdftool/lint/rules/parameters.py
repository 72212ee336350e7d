"""U630-U633: controller parameters against the controllers' own definitions.

What each class reads is data extracted from the controllers' sources (see
:mod:`urdftool.description.controller_parameters`): ros2_controllers' generate_parameter_library
files per ROS 2 distribution, and what ROS 1's ros_controllers read. A finding holds in every
distribution that has the class: a parameter renamed in a later one (``i_clamp`` before
``i_clamp_max``) is nobody's mistake.
"""

from __future__ import annotations

import functools
import math
import re

from urdftool.description import controller_parameters as schema
from urdftool.description.controllers import Controller, controller_files, controllers
from urdftool.description.documents import YamlMap
from urdftool.errors import available, shown_word
from urdftool.lint.catalogue import Severity, rule
from urdftool.lint.rules.controllers import if_started, label

_FAILS = "it fails to configure"


@functools.lru_cache(maxsize=256)
def _ros2(class_name: str) -> dict:
    return schema.ros2_schemas(class_name)


def _schemas(controller: Controller) -> dict:
    """Distribution -> Schema of what the controller's class reads ({} when not known, or when
    its block was written for another implementation of that class name)."""
    if controller.layout == "ros2":
        found = _ros2(controller.type)
    elif controller.layout == "ros1":
        ros1 = schema.ros1_schema(controller.type)
        found = {ros1.distribution: ros1} if ros1 else {}
    else:
        return {}
    return {} if schema.another_implementation(found, controller.own) else found


def _leaves(controller: Controller):
    """(dotted name, value, line) of each parameter its own block (ROS 1: its mapping) sets."""
    for name, value, holder, key in schema.flatten(controller.own):
        line = holder.lines.get(key) if isinstance(holder, YamlMap) else None
        yield name, value, line or controller.block_line or controller.line


def _judged(robot):
    """(controller, schemas, severity, condition, name, value, line) of each parameter a
    controller whose class is known sets, with how bad a defect in it is (see if_started)."""
    for controller in controllers(robot):
        schemas = _schemas(controller)
        severity, condition = if_started(robot, controller, _FAILS) if schemas else (None, "")
        if severity is None:
            continue
        for name, value, line in _leaves(controller):
            yield controller, schemas, severity, condition, name, value, line


def _known(schemas: dict, name: str) -> list:
    """The parameter ``name`` is, in each distribution that has it."""
    return [p for p in (s.find(name) for s in schemas.values()) if p is not None]


def _ros(controller: Controller) -> int:
    return 2 if controller.layout == "ros2" else 1


# --- U630 ------------------------------------------------------------------------------------

@rule("U630", "controller-parameter-type", Severity.ERROR)
def controller_parameter_type(robot):
    """A controller parameter's value has another type than the controller declares.

    ROS 2 declares each parameter with a type and refuses another ("parameter 'wheel_radius'
    has invalid type: expected [double] got [integer]"): the controller fails to configure. A
    list written as one name (``joints: head_joint``), a number in quotes (``update_rate:
    "50"``), an integer for a double (``wheel_separation: 1``) or a list of integers for a list
    of doubles are the usual slips. ROS 1 converts an integer to a double, nothing else.
    Types are ros2_controllers' per ROS 2 distribution (a finding holds in every distribution
    that has the class) and those ROS 1's ros_controllers read. The controller manager's
    ``update_rate`` (an integer) is checked too.

    A list mixing types (``[0.1, 0, 0.1]``) in a ROS 2 parameter file is an error whatever
    reads it: ROS 2's parser refuses the whole file ("Sequence should be of same type").
    Otherwise an error when the controller is started, and a warning saying "if it is
    started" while that is not known.

    Bad: ``joints: head_joint``; ``update_rate: "50"``; ``wheel_radius: 1``
    Good: ``joints: [head_joint]``; ``update_rate: 50``; ``wheel_radius: 1.0``
    """
    for read in controller_files(robot):
        if read.file.ros2:
            yield from _mixed_lists(read)
            yield from _manager_types(read)
    for controller, schemas, severity, condition, name, value, line in _judged(robot):
        known = _known(schemas, name)
        problems = [schema.type_problem(p, value, _ros(controller)) for p in known]
        if known and all(problems):
            yield controller.file.at(line), (
                f"{label(controller)}: {name} must be {problems[0]}; {_write(name, value, known[0])}"
                f"; {condition}"), None, severity


def _mixed_lists(read):
    seen = set()
    for block in read.blocks:
        for name, value, holder, key in schema.flatten(block.params):
            if isinstance(value, list) and schema.ros_type(value) == "mixed_array" and id(value) not in seen:
                seen.add(id(value))
                kinds = sorted({schema.ros_type(v) for v in value})
                yield read.file.at(holder.lines.get(key)), (
                    f"{name} mixes {' and '.join(kinds)} values in one list: ROS 2's parameter parser "
                    "refuses the whole file (\"Sequence should be of same type\"), so no node gets "
                    "its parameters from it; write every number with a decimal point "
                    f"({_doubles(value)})")


def _doubles(value: list) -> str:
    return "[" + ", ".join(f"{float(v)!r}" if isinstance(v, int) and not isinstance(v, bool) else str(v)
                           for v in value) + "]"


def _manager_types(read):
    """The controller manager's own parameters (update_rate, ...): it reads them as it starts."""
    schemas = schema.manager_schemas()
    for block in read.blocks:
        if block.name != "controller_manager":
            continue
        for name, value in block.params.items():
            if isinstance(value, dict):
                continue  # a controller's declaration (NAME: {type: ...}) or a group
            known = _known(schemas, str(name))
            problems = [schema.type_problem(p, value) for p in known]
            if known and all(problems):
                yield read.file.at(block.params.lines.get(name)), (
                    f"controller_manager: {name} must be {problems[0]}; "
                    f"{_write(str(name), value, known[0])} (the controller manager refuses to start)")


def _write(name: str, value, parameter) -> str:
    """How to write ``value`` with the parameter's type."""
    expected = parameter.type
    short = name.rsplit(".", 1)[-1]
    if expected.endswith("_array") and not isinstance(value, list):
        return f"write {short}: [{shown_word(str(value))}]"
    if expected == "double" and isinstance(value, int) and not isinstance(value, bool):
        return f"write {short}: {float(value)!r}"
    if expected == "double_array" and isinstance(value, list):
        return f"write {short}: {_doubles(value)}"
    if isinstance(value, str) and _plain_is(value.strip(), expected):
        return f"write {short}: {value.strip()} without quotes"
    return f"give it {schema._shown(expected.split('_fixed_')[0])}"


def _plain_is(text: str, expected: str) -> bool:
    """Whether ``text`` written plain (without quotes) is a value of the type ``expected``
    (``int``, ``double``, ``bool``) to the readers: only then is a string that holds it one
    written in quotes (``update_rate: "50"``); a word (``junk``) is no number however written."""
    if expected == "bool":
        return text.lower() in ("true", "false", "yes", "no", "on", "off")
    if expected == "int":
        return re.fullmatch(r"[-+]?[0-9]{1,18}", text) is not None
    if expected == "double":
        try:
            return math.isfinite(float(text))
        except ValueError:
            return False
    return False


# --- U631 ------------------------------------------------------------------------------------

@rule("U631", "controller-parameter-invalid", Severity.ERROR)
def controller_parameter_invalid(robot):
    """A controller parameter's value is outside what the controller accepts.

    ros2_controllers validates parameters as they are declared (generate_parameter_library's
    ``gt``, ``gt_eq``, ``bounds``, ``one_of``, ``subset_of``, ``size_gt``, ``size_lt``,
    ``fixed_size``, ``not_empty``, ``unique``, ...) and the controller fails to configure
    ("Invalid value set during initialization for parameter 'interpolation_method': ...").
    Checked against each ROS 2 distribution that has the class: a finding holds in all of
    them. An error when the controller is started; a warning saying "if it is started" while
    that is not known.

    Bad: ``interpolation_method: spline``; ``command_interfaces: [position, position]``;
    ``wheel_separation: 0.0``
    Good: ``interpolation_method: splines``; ``command_interfaces: [position]``;
    ``wheel_separation: 0.35``
    """
    for controller, schemas, severity, condition, name, value, line in _judged(robot):
        ros = _ros(controller)
        known = [p for p in _known(schemas, name) if schema.type_problem(p, value, ros) is None]
        problems = [schema.validation_problems(p, value) for p in known]
        if known and all(problems):
            shown = f"[{', '.join(map(str, value))}]" if isinstance(value, list) else value
            yield controller.file.at(line), (
                f"{label(controller)}: {name} is {shown!s}, but it {'; it '.join(problems[0])}"
                f"; {condition}"), None, severity


# --- U632 ------------------------------------------------------------------------------------

@rule("U632", "controller-unknown-parameter", Severity.WARNING)
def controller_unknown_parameter(robot):
    """A controller's block sets a parameter its class does not read in any ROS 2 distribution.

    ROS 2 controllers accept parameters they do not declare without a word, so a misspelt one
    (``state_interface`` for ``state_interfaces``, ``wheel_seperation``) is silently ignored
    and the default (or nothing) is used. Checked for ros2_controllers' classes, against the
    parameters each distribution's definition lists, those of every controller
    (``update_rate``, ``is_async``, ...) and of every node (``use_sim_time``); a parameter
    known to any distribution is not reported. Parameters set for every node (a ``/**``
    block) are not checked.

    Bad: ``state_publish_rat: 50``
    Good: ``state_publish_rate: 50.0`` (Humble; later distributions dropped it)
    """
    for controller in controllers(robot):
        if controller.layout != "ros2":
            continue
        schemas = _schemas(controller)
        if not schemas or not all(s.complete for s in schemas.values()):
            continue
        reported = set()
        for name, value, line in _leaves(controller):
            if _known(schemas, name):
                continue
            unknown = _unknown_prefix(schemas, name)
            if unknown is None or unknown in reported:
                continue  # a group holding a value its own way (a list of mappings)
            reported.add(unknown)
            names = sorted({_shown_name(n) for s in schemas.values() for n in s.parameters})
            what = f"'{unknown}'" + (f" (nor anything under it: {name}, ...)" if unknown != name else "")
            yield controller.file.at(_line_of(controller.own, unknown) or line), (
                f"{label(controller)} does not read {what} in any ROS 2 distribution, so it is "
                "ignored; " + _suggest(unknown, names))


def _line_of(params, name: str) -> int | None:
    """Where the key at dotted ``name`` is written in nested ``params``."""
    *heads, last = name.split(".")
    node = params
    for part in heads:
        node = node.get(part) if isinstance(node, dict) else None
    return node.lines.get(last) if isinstance(node, YamlMap) else None


def _unknown_prefix(schemas: dict, name: str) -> str | None:
    """The shortest head of dotted ``name`` that no distribution reads or groups under (None:
    every head is a group some distribution has)."""
    parts = name.split(".")
    for size in range(1, len(parts) + 1):
        head = ".".join(parts[:size])
        if not (_known(schemas, head) or any(s.is_group(head) for s in schemas.values())):
            return head
    return None


def _shown_name(name: str) -> str:
    return ".".join("<joint>" if part == "__map_joints" else f"<{part[6:]}>" if part.startswith("__map_")
                    else part for part in name.split("."))


def _suggest(name: str, names: list[str]) -> str:
    from urdftool.errors import close_names

    close = close_names(name, names, n=1, cutoff=0.75)
    if close:
        return f"did you mean '{close[0]}'?"
    listed = available("parameters", name, sorted({n.split(".")[0] for n in names}))
    readers = _readers(name)
    if not readers:
        return listed
    more = f" and {len(readers) - 2} more" if len(readers) > 2 else ""
    return f"'{name}' is a parameter of {', '.join(readers[:2])}{more}, not of this class; " + \
        listed


def _readers(name: str) -> list[str]:
    """The ros2_controllers classes that read parameter ``name`` in some distribution (a
    parameter carried over from another controller: the forward command controllers'
    ``interface_name`` given to JointTrajectoryController)."""
    return [kind for kind in schema.ros2_classes() if _known(_ros2(kind), name)]


# --- U633 ------------------------------------------------------------------------------------

@rule("U633", "parameters-outside-ros-parameters", Severity.ERROR)
def parameters_outside_ros_parameters(robot):
    """A ROS 2 parameter file holds values outside any ``ros__parameters`` block.

    In a ROS 2 parameter file every value is under ``NODE: ros__parameters:``. ROS 2's parser
    refuses a file with a value before ``ros__parameters`` ("Cannot have a value before
    ros__parameters at line N"), so no node of the launch gets its parameters from it: a
    controller block written the ROS 1 way (``head_controller: joints: [...]``) next to the
    controller manager's ``ros__parameters`` breaks the whole file. An error: it holds for
    whatever is started.

    Parameters written inside the controller manager's declaration of a controller
    (``controller_manager: ros__parameters: arm_controller: {type: ..., joints: [...]}``) are
    the controller manager's, not the controller's: nothing reads them (a warning).

    Bad: ``head_controller:`` / ``  joints: [head_joint]`` beside ``controller_manager:`` /
    ``  ros__parameters:``
    Good: ``head_controller:`` / ``  ros__parameters:`` / ``    joints: [head_joint]``
    """
    for read in controller_files(robot):
        if not read.file.ros2 or not isinstance(read.file.data, YamlMap):
            continue
        for key, line in _outside(read.file.data, ()):
            node = "/".join(map(str, key[:-1])) or key[-1]
            yield read.file.at(line), (
                f"'{'.'.join(map(str, key))}' is a value outside any ros__parameters block: ROS 2's "
                "parameter parser refuses the whole file (\"Cannot have a value before "
                f"ros__parameters\"), so no node gets its parameters from it; put it under "
                f"'{node}: ros__parameters:'")
        for block in read.blocks:
            if block.name != "controller_manager":
                continue
            for name, declared in block.params.items():
                if isinstance(declared, YamlMap) and isinstance(declared.get("type"), str):
                    extra = [k for k in declared if k not in _MANAGER_KEYS]
                    if extra:
                        yield read.file.at(declared.lines.get(extra[0])), (
                            f"controller_manager's declaration of '{name}' holds {', '.join(map(str, extra))}: "
                            "the controller manager reads only type, params_file and "
                            f"fallback_controllers there, and '{name}' reads its parameters from "
                            f"'{name}: ros__parameters:'; move them there"), None, Severity.WARNING


_MANAGER_KEYS = ("type", "params_file", "fallback_controllers")


def _outside(node, path, depth=0):
    """(key path, line) of the first value of each branch that reaches a value before any
    ros__parameters (rcl's parser stops at the first; each branch is a node's mistake)."""
    if depth > 12:
        return
    for key, value in node.items():
        if key == "ros__parameters":
            continue
        if isinstance(value, YamlMap) and _has_parameters_block(value, depth + 1):
            yield from _outside(value, (*path, key), depth + 1)
            continue
        first = _first_value(node, key, (*path, key), depth + 1)
        if first is not None:
            yield first


def _has_parameters_block(node, depth) -> bool:
    return depth <= 12 and isinstance(node, YamlMap) and (
        "ros__parameters" in node or any(_has_parameters_block(v, depth + 1) for v in node.values()))


def _first_value(holder, key, path, depth):
    value = holder[key]
    if value is None or depth > 12:
        return None
    if not isinstance(value, YamlMap):
        return path, holder.lines.get(key)
    for inner in value:
        found = _first_value(value, inner, (*path, inner), depth + 1)
        if found is not None:
            return found
    return None
