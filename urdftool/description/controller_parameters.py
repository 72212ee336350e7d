"""What each controller class reads, per ROS distribution, and what a value must be to pass.

The facts are data, extracted from the controllers' own sources and committed:

- ``urdftool/data/ros2_controllers.json``: ros2_controllers' generate_parameter_library files
  (name, type, default, read_only, validation) per class and ROS 2 distribution, the parameters
  every controller has (``update_rate``, ...) and the controller manager's, each with its
  repository, path and commit (``scripts/extract_controller_parameters.py``; Apache-2.0, the
  notice is in the file);
- ``urdftool/data/ros_controllers.json``: what ROS 1's ros_controllers read and refuse to start
  without, each fact with the source line it was read from
  (``scripts/extract_ros1_controller_parameters.py``).

This module reads them and answers: which parameters a class has in a distribution, whether
a name is one of them (``gains.elbow.p`` is ``gains.__map_joints.p``), what type ROS gives a
YAML value, whether a value has the declared type and passes the declared validation. It
judges nothing: that is the rules' business.
"""

from __future__ import annotations

import functools
import math
import re

from urdftool.description import data
from urdftool.errors import shown_word
from urdftool.numbers import INT64, in_int64
from urdftool.records import Frozen, NEW

# Distributions past their end of life: what only they have is reported as such.
END_OF_LIFE = ("foxy", "galactic", "iron")
MISSING = object()


class Parameter(Frozen):
    """One parameter of a class in one distribution.

    name: dotted, as generate_parameter_library writes it (``gains.__map_joints.p``: a key per
        entry of ``joints``)
    type: bool, int, double, string, their ``_array`` forms, ``none`` (any value or subtree), or
        ``string_or_array`` (ROS 1: one name or a list)
    default: the value it takes when not given; MISSING when it has none (it must be given)
    validation: {validator: [arguments]} (generate_parameter_library's names: gt_eq, one_of, ...)
    source: repository, path and commit it was read from
    """

    name: str
    type: str
    default: object
    read_only: bool
    validation: dict
    source: str

    __slots__ = ("name", "type", "default", "read_only", "validation", "source")

    def __init__(self, name: str, type: str, default: object = MISSING, read_only: bool = False,
                 validation: dict = NEW, source: str = "") -> None:
        set_field = object.__setattr__
        set_field(self, "name", name)
        set_field(self, "type", type)
        set_field(self, "default", default)
        set_field(self, "read_only", read_only)
        set_field(self, "validation", {} if validation is NEW else validation)
        set_field(self, "source", source)

    @property
    def required(self) -> bool:
        """Whether the class refuses to configure without it: no default, or a default its own
        validation refuses (``joints: []`` with ``size_gt: [0]``)."""
        if self.type == "none":
            return False  # a subtree of anything
        if self.default is MISSING:
            return True
        return bool(self.validation) and bool(validation_problems(self, self.default))


class Schema(Frozen):
    """The parameters of one class (or of every controller, or of the controller manager) in
    one distribution."""

    distribution: str
    parameters: dict  # name -> Parameter
    complete: bool  # whether every parameter it reads is listed (ROS 1: only required ones)

    __slots__ = ("distribution", "parameters", "complete")

    def __init__(self, distribution: str, parameters: dict, complete: bool = True) -> None:
        set_field = object.__setattr__
        set_field(self, "distribution", distribution)
        set_field(self, "parameters", parameters)
        set_field(self, "complete", complete)

    def find(self, name: str) -> Parameter | None:
        """The parameter a dotted ``name`` is (matching ``__map_X`` segments and ``none``
        subtrees), or None."""
        if name in self.parameters:
            return self.parameters[name]
        parts = name.split(".")
        for pattern, parameter in self.parameters.items():
            if _matches(pattern.split("."), parts, parameter.type == "none"):
                return parameter
        return None

    def is_group(self, name: str) -> bool:
        """Whether ``name`` is a namespace of parameters (``constraints``), not one."""
        parts = name.split(".")
        return any(_matches(p.split(".")[:len(parts)], parts, False)
                   for p in self.parameters if len(p.split(".")) > len(parts))


def _matches(pattern: list[str], parts: list[str], subtree: bool) -> bool:
    if len(parts) < len(pattern) or (len(parts) > len(pattern) and not subtree):
        return False
    return all(p == q or p.startswith("__map_") for p, q in zip(pattern, parts))


# --- the data files ------------------------------------------------------------------------

def _data(name: str) -> dict:
    # (a check reads the schemas of the classes its controllers name: a few of 69)
    return data.load(name, "schemas" if name == "ros2_controllers.json" else None)


def _parameter(name: str, facts: dict, source: str) -> Parameter:
    default = facts.get("default", MISSING)
    return Parameter(name, facts["type"], _from_json(default), bool(facts.get("read_only")),
                     facts.get("validation", {}), source)


def _from_json(value):
    if value in ("inf", "-inf"):
        return float(value)
    if isinstance(value, list):
        return [_from_json(v) for v in value]
    return value


@functools.lru_cache(maxsize=None)
def _ros2_schema(ident: str) -> dict:
    data = _data("ros2_controllers.json")
    entry = data["schemas"][ident]
    source = data["sources"][entry["source"]]
    first = entry["distributions"][0]
    where = (f"{source['repository']} {source['refs'][first]['ref']}:{entry['path']} "
             f"({source['refs'][first]['commit'][:12]})")
    return {name: _parameter(name, facts, where) for name, facts in entry["parameters"].items()}


def ros2_schemas(class_name: str) -> dict[str, Schema]:
    """Distribution -> the parameters ``class_name`` reads there (its own and every
    controller's), for the distributions whose sources declare them; empty when the class is
    not one of ros2_controllers' or none of its distributions declares its parameters."""
    data = _data("ros2_controllers.json")
    found, per_distribution = {}, data["classes"].get(class_name, {})
    for distribution in data["distributions"]:  # oldest first
        idents = per_distribution.get(distribution)
        if not idents:
            continue
        merged = dict(common_ros2(distribution))
        for ident in idents:
            merged.update(_ros2_schema(ident))
        found[distribution] = Schema(distribution, merged)
    return found


def ros2_class_distributions(class_name: str) -> list[str]:
    """The ROS 2 distributions whose ros2_controllers export ``class_name`` (empty: none)."""
    return list(_data("ros2_controllers.json")["classes"].get(class_name, {}))


def ros2_classes() -> list[str]:
    """Every class ros2_controllers exports in some distribution."""
    return list(_data("ros2_controllers.json")["classes"])


def ros2_distributions() -> list[str]:
    return list(_data("ros2_controllers.json")["distributions"])


# Parameters of every ROS 2 node, and what the controller manager and the spawner read from a
# controller's own block (``type``, ``params_file``, ``fallback_controllers``: controller_manager
# and spawner of humble and later).
NODE_PARAMETERS = {"use_sim_time": "bool", "type": "string", "params_file": "string_or_array",
                   "fallback_controllers": "string_array", "qos_overrides": "none"}


def common_ros2(distribution: str) -> dict[str, Parameter]:
    """The parameters every controller reads in ``distribution`` (ControllerInterfaceBase's,
    and the node's own)."""
    data = _data("ros2_controllers.json")
    found = {name: Parameter(name, kind, None, source="ROS 2 nodes, controller_manager")
             for name, kind in NODE_PARAMETERS.items()}
    ident = data["controller"].get(distribution)
    if ident:
        found.update(_ros2_schema(ident))
    return found


def manager_schemas() -> dict[str, Schema]:
    """Distribution -> the controller manager's parameters (update_rate, ...)."""
    data = _data("ros2_controllers.json")
    return {d: Schema(d, _ros2_schema(ident), complete=ident.split("@")[0].endswith(".yaml"))
            for d, ident in data["controller_manager"].items()}


def ros1_schema(class_name: str) -> Schema | None:
    """What ROS 1's ``class_name`` reads (the parameters it needs and their types), or None."""
    data = _data("ros_controllers.json")
    entry = data["classes"].get(class_name)
    if entry is None:
        return None
    source = data["source"]
    parameters = {}
    for name, facts in entry.items():
        where = (f"{source['repository']} {source['ref']}:{facts['path']}:{facts['line']} "
                 f"({source['commit'][:12]})")
        parameters[name] = _parameter(name, facts, where)
    return Schema("noetic", parameters, complete=False)


# --- values as ROS reads them ----------------------------------------------------------------

# PyYAML reads these plain scalars as numbers: a str that matches one was written in quotes.
_YAML_INT = re.compile(r"[-+]?(0|[1-9][0-9_]*)")
_YAML_FLOAT = re.compile(r"[-+]?([0-9][0-9_]*)?\.[0-9_]*([eE][-+][0-9]+)?|[-+]?\.(inf|Inf|INF)|\.(nan|NaN|NAN)")
# rcl_yaml_param_parser reads a plain scalar as a number where C's strtol/strtod would: "8e-3"
# is a double for ROS 2 but a string for PyYAML; written in quotes it is a string for both.
# Which it was is not kept, so such a string's type is not known.
_C_NUMBER = re.compile(r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?|[-+]?0[xX][0-9a-fA-F]+")
_RCL_BOOL_ONLY = {"y", "Y", "n", "N"}  # plain y/n: booleans to rcl, strings to PyYAML


def ros_type(value, ros: int = 2) -> str | None:
    """The parameter type ROS gives a value read from YAML: bool, int, double, string, their
    ``_array`` forms, ``map`` (a namespace), ``mixed_array`` (a list of different types: ROS 2's
    parser refuses the file), ``empty_array``; None when it cannot be told (a string PyYAML read
    that ROS 2 may read as a number or a boolean, a null)."""
    if isinstance(value, bool):
        return "bool"
    if isinstance(value, int):
        return "int" if ros == 1 or in_int64(value) else "double"  # (rcl: strtoll's ERANGE,
        # then strtod; past a double PyYAML's reading refuses it: yaml_limits)
    if isinstance(value, float):
        return "double"
    if isinstance(value, str):
        if ros == 2 and (value in _RCL_BOOL_ONLY or (_C_NUMBER.fullmatch(value.strip())
                                                     and not _quoted_number(value))):
            return None
        return "string"
    if isinstance(value, dict):
        return "map"
    if isinstance(value, list):
        kinds = {ros_type(item, ros) for item in value}
        if not value:
            return "empty_array"
        if None in kinds or "map" in kinds or any(k.endswith("array") for k in kinds if k):
            return None
        if len(kinds) == 1:
            return f"{kinds.pop()}_array"
        return "mixed_array"
    return None


def _quoted_number(text: str) -> bool:
    """Whether PyYAML would have read ``text`` as a number had it been written plain: then,
    being a string, it was written in quotes."""
    return bool(_YAML_INT.fullmatch(text) or _YAML_FLOAT.fullmatch(text))


def type_problem(parameter: Parameter, value, ros: int = 2) -> str | None:
    """What is wrong with the type of ``value`` for ``parameter`` (None: nothing known wrong).

    ROS 2 declares each parameter with its type and refuses another one ("expected [double]
    got [integer]"); ROS 1's getParam converts an int to a double but nothing else."""
    expected = parameter.type.split("_fixed_")[0]
    given = ros_type(value, ros)
    if given in (None, "mixed_array") or expected == "none" or (given == "empty_array"
                                                                and expected.endswith("_array")):
        return None  # not known; a mixed list is the file's problem (ROS 2 refuses the file)
    if expected == "string_or_array":
        return None if given in ("string", "string_array") else f"a name or a list of names, not {_shown(given)}"
    if given == expected:
        return None
    if ros == 1 and expected == "double" and given == "int":
        return None
    if ros == 1 and expected == "double_array" and given in ("int_array", "mixed_array"):
        return None
    return f"{_shown(expected)}, not {_shown(given)}{_past_int64(value, ros)}"


def _past_int64(value, ros: int) -> str:
    """Why ROS 2 reads the integers of ``value`` as doubles, when it does: they are past int64
    (rcl_yaml_param_parser's strtoll refuses them and strtod reads them); else nothing."""
    items = value if isinstance(value, list) else [value]
    past = [item for item in items if isinstance(item, int) and not isinstance(item, bool)
            and not in_int64(item)]
    if ros != 2 or not past:
        return ""
    return (f" ({shown_word(str(past[0]))} is past int64, {INT64[0]} to {INT64[1]}, which ROS 2 "
            "reads as a double)")


_SHOWN = {"bool": "a boolean", "int": "an integer", "double": "a double", "string": "a string",
          "map": "a group of parameters", "mixed_array": "a list mixing types",
          "empty_array": "an empty list"}


def _shown(kind: str) -> str:
    if kind in _SHOWN:
        return _SHOWN[kind]
    if kind.endswith("_array"):
        return f"a list of {_SHOWN.get(kind[:-6], kind[:-6])[2:].lstrip('n ')}s"
    return kind


# --- generate_parameter_library's validators --------------------------------------------------

def validation_problems(parameter: Parameter, value) -> list[str]:
    """What ``value`` breaks of the parameter's validation (generate_parameter_library's
    built-in validators; a project's own, ``pkg::function``, is not evaluated)."""
    problems = []
    for name, arguments in parameter.validation.items():
        check = _VALIDATORS.get(name)
        if check is None:
            continue
        try:
            problem = check(value, *arguments)
        except (TypeError, ValueError, IndexError):
            problem = None  # a value of the wrong type: type_problem says so
        if problem:
            problems.append(problem)
    return problems


def _number(value) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise TypeError(value)
    return float(value)


def _elements(value) -> list:
    if not isinstance(value, list):
        raise TypeError(value)
    return value


def _bound(op, word):
    def check(value, limit=None, *_):
        if limit is None:
            return None
        if isinstance(value, list):
            bad = [v for v in value if not op(_number(v), float(limit))]
            return f"every element must be {word} {limit:g}" if bad else None
        return None if op(_number(value), float(limit)) else f"must be {word} {limit:g}"
    return check


def _bounds(value, low, high, *_):
    number = _number(value)
    return None if low <= number <= high else f"must be between {low:g} and {high:g}"


def _element_bounds(value, low, high, *_):
    bad = [v for v in _elements(value) if not low <= _number(v) <= high]
    return f"every element must be between {low:g} and {high:g}" if bad else None


def _lower_element_bounds(value, low, *_):
    bad = [v for v in _elements(value) if _number(v) < low]
    return f"every element must be at least {low:g}" if bad else None


def _upper_element_bounds(value, high, *_):
    bad = [v for v in _elements(value) if _number(v) > high]
    return f"every element must be at most {high:g}" if bad else None


def _one_of(value, choices=(), *_):
    if isinstance(value, (list, dict)):
        raise TypeError(value)
    return None if value in choices else f"must be one of {', '.join(map(str, choices))}"


def _subset_of(value, choices=(), *_):
    bad = [v for v in _elements(value) if v not in choices]
    return (f"must hold only {', '.join(map(str, choices))} ({', '.join(map(str, bad))} "
            f"{'is' if len(bad) == 1 else 'are'} not one)") if bad else None


def _size(op, word):
    def check(value, size=None, *_):
        if size is None or not isinstance(value, (list, str)):
            return None
        return None if op(len(value), int(size)) else f"must have {word} {int(size)} entries"
    return check


def _not_empty(value, *_):
    return "must not be empty" if isinstance(value, (list, str)) and not value else None


def _unique(value, *_):
    seen, repeated = set(), []
    for item in _elements(value):
        if item in seen and item not in repeated:
            repeated.append(item)
        seen.add(item)
    return f"must not list {', '.join(map(str, repeated))} more than once" if repeated else None


_VALIDATORS = {
    "gt": _bound(lambda a, b: a > b, "above"),
    "gt_eq": _bound(lambda a, b: a >= b, "at least"),
    "lt": _bound(lambda a, b: a < b, "below"),
    "lt_eq": _bound(lambda a, b: a <= b, "at most"),
    "bounds": _bounds,
    "element_bounds": _element_bounds,
    "lower_element_bounds": _lower_element_bounds,
    "upper_element_bounds": _upper_element_bounds,
    "one_of": _one_of,
    "subset_of": _subset_of,
    "fixed_size": _size(lambda a, b: a == b, "exactly"),
    "size_gt": _size(lambda a, b: a > b, "more than"),
    "size_lt": _size(lambda a, b: a < b, "fewer than"),
    "not_empty": _not_empty,
    "unique": _unique,
}


def flatten(params, prefix: str = "", depth: int = 0) -> list[tuple[str, object, object]]:
    """(dotted name, value, the mapping holding it, key) of each leaf of a parameter mapping:
    ROS 2 names a parameter by the path of keys to it."""
    found = []
    if not isinstance(params, dict) or depth > 12:
        return found
    for key, value in params.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict) and value:
            found.extend(flatten(value, f"{name}.", depth + 1))
        else:
            found.append((name, value, params, key))
    return found


def is_finite_number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def required(class_name: str, ros: int, params=None) -> dict[str, Parameter]:
    """Name -> the parameter, of those ``class_name`` refuses to configure without in every
    distribution that declares its parameters (ROS 2), or in ROS 1's ros_controllers; names
    with ``__map_X`` stand for one per entry of X. None when ``params`` (the controller's own)
    were written for another implementation of that class name."""
    if ros == 1:
        found = ros1_schema(class_name)
        return {n: p for n, p in found.parameters.items() if p.required} if found else {}
    schemas = ros2_schemas(class_name)
    if another_implementation(schemas, params):
        return {}
    names = [{n for n, p in s.parameters.items() if p.required} for s in schemas.values()]
    common = set.intersection(*names) if names else set()
    newest = list(schemas.values())[-1].parameters if schemas else {}
    return {n: newest[n] for n in sorted(common)}


def expand(name: str, params) -> list[str]:
    """The dotted names ``name`` stands for in ``params``: ``gains.__map_joints.p`` is
    ``gains.<j>.p`` for each name ``j`` of ``params['joints']`` (none when it lists none)."""
    names = [""]
    for part in name.split("."):
        if part.startswith("__map_"):
            keys = lookup(params, part[6:])
            keys = [keys] if isinstance(keys, str) else keys if isinstance(keys, list) else []
            names = [f"{n}{k}." for n in names for k in keys if isinstance(k, str)]
        else:
            names = [f"{n}{part}." for n in names]
    return [n[:-1] for n in names]


def lookup(params, name: str, default=None):
    """The value at dotted ``name`` in nested ``params``, or ``default``."""
    node = params
    for part in name.split("."):
        if not isinstance(node, dict) or part not in node:
            return default
        node = node[part]
    return node


def another_implementation(schemas: dict, params) -> bool:
    """Whether ``params`` were written for another implementation of the class name (a
    vendor's ``mecanum_drive_controller`` before ros2_controllers had one, a fork): most of
    the parameters they set (at least 4) are read by none of the distributions' definitions,
    so none of what those definitions say applies."""
    names = [name for name, *_ in flatten(params) if name.split(".")[0] not in NODE_PARAMETERS]
    if len(names) < 4 or not schemas:
        return False
    unknown = [n for n in names if not any(s.find(n) or s.is_group(n) for s in schemas.values())]
    return 2 * len(unknown) > len(names)
