"""Companion documents read with their lines: YAML (controllers, the joint spec) and SRDF.

Reading only: which files a robot has is :mod:`urdftool.description.companions`' business, and
what is wrong in them the rules' (U6xx-U8xx live in :mod:`urdftool.lint.rules`).
"""

from __future__ import annotations

import functools
import re
from pathlib import Path

from urdftool.diagnostics import Location, display_path, line_at, lines_of
from urdftool.errors import shown_word
from urdftool.description.files import TooLarge, read_regular
from urdftool.description.xml import XmlProblem, entity_uses, merge_conflict, start_tag_lines, \
    tinyxml2_comments
from urdftool.records import Record

MAX_SIZE = 16 * 1024 * 1024


# --- YAML that remembers where each key and item was written -------------------------------

class YamlMap(dict):
    """A YAML mapping; ``line`` is where it starts, ``lines[key]`` where each key is (1-based)."""

    line: int = 0
    lines: dict


class YamlList(list):
    """A YAML sequence; ``line`` is where it starts, ``lines[i]`` where each item is (1-based)."""

    line: int = 0
    lines: list


@functools.lru_cache(maxsize=None)
def _loader():
    """The YAML loader class (PyYAML is imported on first use: a run served from the result
    cache reads no YAML): PyYAML's Python reader, scanner and parser (:func:`_fast_loader`
    reads with libyaml's, and answers with this one whenever it fails)."""
    import yaml

    from urdftool.description.yaml_limits import DepthLimit

    class _Loader(DepthLimit, yaml.SafeLoader):
        """SafeLoader keeping line numbers; unknown tags (``!degrees 90``) load as their plain value;
        nesting past yaml_limits.MAX_DEPTH is a YAML error at its line.

        merge_repeated: a key written twice in one mapping, both times holding a mapping, holds
        both merged (the later value wins key by key), as ROS 2's parameter parser reads a
        parameter file (rcl_yaml_param_parser adds each node-name block and each nested parameter
        name to what it has: two ``/**:`` blocks both apply). Off, the later value replaces the
        earlier one, as PyYAML (and so rosparam, ROS 1) does."""

        merge_repeated = False

        def construct_yaml_map(self, node):
            if not isinstance(node, yaml.MappingNode):  # (``!!map abc``: PyYAML's words)
                raise yaml.constructor.ConstructorError(
                    None, None, f"expected a mapping node, but found {node.id}", node.start_mark)
            merges = self._merged(node)
            data = YamlMap()
            data.line, data.lines = self.file_line(node.start_mark), {}
            yield data
            owned: set[int] = set()  # the maps this mapping's merges made (merged in place)
            for key_node, value_node in node.value:
                key = "<<" if key_node.tag == _MERGE and not merges else \
                    self.construct_object(key_node, deep=True)
                try:
                    hash(key)
                except TypeError:
                    key = str(key)
                value = self.construct_object(value_node, deep=True)
                if self.merge_repeated and isinstance(data.get(key), YamlMap) and isinstance(value, YamlMap):
                    data[key] = merged(data[key], value, owned)  # keeps the line it was first written at
                    continue
                data[key] = value
                data.lines[key] = self.file_line(key_node.start_mark)

        def _merged(self, node) -> bool:
            """Merge keys (``<<: *defaults``) flattened into ``node`` as PyYAML does (the keys
            merged first, the mapping's own after them, so they win); True. A merge of what is no
            mapping (``<<: 5``) is PyYAML's error; read leniently (ROS 2's parser knows no merge:
            ``<<`` is a name to it) the mapping keeps ``<<`` as a key, noted, and False."""
            if not any(key.tag == _MERGE for key, _ in node.value):
                return True
            written = list(node.value)
            try:
                self.flatten_mapping(node)
                return True
            except yaml.constructor.ConstructorError as error:
                if not self.lenient:
                    raise
                node.value = written  # (flatten_mapping removed merge keys as it went)
                if isinstance(self.unconstructed, tuple):
                    self.unconstructed = []
                self.unconstructed.append((self.file_line(error.problem_mark),
                                           f"{error.problem} ({error.context})"))
                return False

        def construct_yaml_seq(self, node):
            if not isinstance(node, yaml.SequenceNode):  # (``!!seq abc``: PyYAML's words)
                raise yaml.constructor.ConstructorError(
                    None, None, f"expected a sequence node, but found {node.id}", node.start_mark)
            data = YamlList()
            data.line = self.file_line(node.start_mark)
            data.lines = [self.file_line(item.start_mark) for item in node.value]
            yield data
            data.extend(self.construct_object(item, deep=True) for item in node.value)

        def construct_unknown(self, suffix, node):
            if isinstance(node, yaml.ScalarNode):
                return self.construct_scalar(node)
            if isinstance(node, yaml.SequenceNode):  # (the generator itself: PyYAML fills
                return self.construct_yaml_seq(node)  # it; its first item alone was empty)
            return self.construct_yaml_map(node)

        rosparam = False  # a ROS 1 parameter file: rosparam's tags are its (rosparam_angle)

        def construct_angle(self, node):
            if not self.rosparam:  # (a ROS 2 parameter file, a launch file: no such tag)
                return self.construct_unknown(node.tag, node)
            text = self.construct_scalar(node)
            try:
                made = rosparam_angle(node.tag, text)
            except ValueError as error:
                raise yaml.constructor.ConstructorError(None, None, (
                    f"{error} (rosparam's {node.tag} makes no number of it: roslaunch refuses "
                    "the file, setting none of its parameters)"), node.start_mark) from None
            return text if made is None else made

    _Loader.add_constructor("tag:yaml.org,2002:map", _Loader.construct_yaml_map)
    _Loader.add_constructor("tag:yaml.org,2002:seq", _Loader.construct_yaml_seq)
    _Loader.add_multi_constructor("!", _Loader.construct_unknown)
    for tag in ("!degrees", "!radians"):  # rosparam's own (its plain deg(N) and rad(EXPR),
        # which ROS 2's readers take as text, stay text: which ROS reads the file is not known)
        _Loader.add_constructor(tag, _Loader.construct_angle)
    return _Loader


# rosparam's module's names (ROS 1, ros_comm's tools/rosparam/src/rosparam/__init__.py, Noetic):
# the globals a ``!radians`` expression is evaluated with, besides Python's builtins
_ROSPARAM_NAMES = frozenset((
    "Binary", "GLOBALNS", "NAME", "NS", "OptionParser", "RosParamException",
    "RosParamIOException", "base64", "construct_angle_degrees", "construct_angle_radians",
    "construct_yaml_binary", "delete_param", "dump_params", "get_param", "get_param_server",
    "get_ros_namespace", "list_params", "load_file", "load_str", "make_caller_id",
    "make_global_ns", "math", "ns_join", "os", "pattern", "print_function", "print_params", "re",
    "represent_foo", "represent_xml_binary", "rosgraph", "script_resolve_name", "set_param",
    "set_param_raw", "socket", "sys", "upload_params", "yaml", "yamlmain"))


def rosparam_angle(tag: str, text: str) -> float | None:
    """The value rosparam (ROS 1) makes of ``text`` under ``tag`` (``!degrees``, ``!radians``),
    in [rad], as its constructors do: ``float(N) * pi / 180`` (``deg(N)`` too);
    ``float(eval(EXPR))`` with ``pi`` replaced by ``math.pi`` (``rad(EXPR)`` too). ROS 2's
    MoveIt reads the file with launch_param_builder's tags: ``float(text)``, in degrees or
    radians alike. A value neither makes a number of raises ValueError in rosparam's words (or
    Python's, which roslaunch prints: "file ... contains invalid YAML"): every reader refuses
    the file (PyYAML's own knows no such tag). None for what one of them reads and the other
    not (``!radians inf``: ROS 2 only), and for an expression past numbers, ``pi`` and
    arithmetic (a call, a name rosparam's module holds, a power too large to compute):
    rosparam evaluates any Python; urdftool none."""
    import math

    if tag == "!degrees":
        written = text.strip()[4:-1] if text.startswith("deg(") else text
        try:
            return float(written) * math.pi / 180.0
        except ValueError:
            raise ValueError(f"invalid degree value: {shown_word(text)}") from None
    value = text.strip()
    expression = value.replace("pi", "math.pi")
    if expression.startswith("rad("):
        expression = expression[4:-1]
    import ast

    try:
        tree = ast.parse(expression, mode="eval")
    except SyntaxError:  # (no number float() reads is a syntax error to Python)
        raise ValueError(f"invalid radian expression: {shown_word(value)}") from None
    except (ValueError, RecursionError, MemoryError):  # (an integer past this Python's
        return None  # digits, not past Noetic's; nesting past this parser's depth)
    try:
        made = _arithmetic(tree.body)
        return None if made is None else float(made)
    except RecursionError:  # (a chain of 100,000 terms)
        return None
    except (ArithmeticError, TypeError, ValueError, NameError, AttributeError) as error:
        try:
            float(text)  # (launch_param_builder's reading: ROS 2's MoveIt takes it)
            return None
        except ValueError:
            raise ValueError(f"!radians {shown_word(value)}: {shown_word(str(error))}") from None


def _arithmetic(node):
    """The value of an expression of constants, ``math``'s constants and arithmetic, as Python
    computes it (raising as it raises); None for anything else, or a power past 10,000 bits."""
    import ast
    import builtins
    import math
    import operator

    if isinstance(node, ast.Constant):
        return node.value
    if isinstance(node, ast.Name):
        if node.id.startswith("__") or node.id in _ROSPARAM_NAMES or hasattr(builtins, node.id):
            return None
        raise NameError(f"name '{node.id}' is not defined")
    if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and \
            node.value.id == "math":
        found = getattr(math, node.attr)  # (AttributeError as Python's: math has no 'pipe')
        return found if isinstance(found, float) else None
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        operand = _arithmetic(node.operand)
        return None if operand is None else (-operand if isinstance(node.op, ast.USub)
                                             else +operand)
    operators = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul,
                 ast.Div: operator.truediv, ast.FloorDiv: operator.floordiv,
                 ast.Mod: operator.mod, ast.Pow: operator.pow}
    if isinstance(node, ast.BinOp) and type(node.op) in operators:
        left, right = _arithmetic(node.left), _arithmetic(node.right)
        if left is None or right is None:
            return None
        if isinstance(node.op, ast.Pow) and isinstance(left, int) and isinstance(right, int) \
                and abs(left) > 1 and right * max(abs(left), 2).bit_length() > 10_000:
            return None
        if any(isinstance(side, int) and side.bit_length() > 10_000 for side in (left, right)):
            return None
        return operators[type(node.op)](left, right)
    return None


_MERGE = "tag:yaml.org,2002:merge"


# A text holding one of these characters is read by PyYAML alone: each begins a case where
# libyaml's parser takes what PyYAML's refuses (a tab between tokens, a block scalar's header
# followed by a comment, a ``?`` in a flow scalar, a tag followed by nothing) or reads it
# otherwise (``!`` alone, a byte order mark or a Unicode line break within the text). Without
# them, what libyaml reads whole PyYAML reads alike (the same data, types and lines), and what
# PyYAML refuses libyaml refuses too: 13,033 YAML files (the sweep repositories, the corpus, the
# tests, an SDK's; 8,540 without them) and 315,884 random texts of YAML's pieces (session 13)
_LIBYAML_DIFFERS = re.compile("[\t\ufeff\u2028\u2029\x85!|>?]")


@functools.lru_cache(maxsize=None)
def _fast_loader():
    """:func:`_loader`'s class reading its events from libyaml's parser (``yaml._yaml.
    CParser``, C) instead of PyYAML's Python reader, scanner and parser (7.5 M of the 667 M
    instructions of r2d2's check, for its 22-line controller file); composing (with
    :class:`~urdftool.description.yaml_limits.DepthLimit`'s limits, one event at a time:
    libyaml's parser keeps its own stack, never C's) and constructing stay Python's, the same
    tables. Used only for a
    document it reads whole: any error, and :func:`read_yaml` reads the text again with
    :func:`_loader`, whose messages and marks findings quote. None without libyaml."""
    try:
        from yaml._yaml import CParser
    except ImportError:
        return None
    from yaml.composer import Composer
    from yaml.constructor import SafeConstructor
    from yaml.resolver import Resolver

    class _FastLoader(_loader()):
        def __init__(self, text: str):
            events = CParser(text)
            self.check_event, self.peek_event, self.get_event = \
                events.check_event, events.peek_event, events.get_event
            self.buffer = text + "\0"  # (as PyYAML's reader holds it: DepthLimit's bound)
            Composer.__init__(self)
            SafeConstructor.__init__(self)
            Resolver.__init__(self)

        def dispose(self):
            pass

    return _FastLoader


def merged(first, second, owned: set[int] | None = None):
    """``second`` merged into a copy of ``first`` when both are mappings (recursively, the
    later value winning key by key; lines kept from where each key was first written); else
    ``second``. Neither is changed: an alias may share them.

    owned: the ids of maps earlier calls with this set made, which no one else holds: merged
    into in place, not copied again, so that a key written 20,000 times (``/**:`` blocks, each
    adding a parameter) costs each block's size, not the size of all before it each time."""
    if not (isinstance(first, YamlMap) and isinstance(second, YamlMap)):
        return second
    if owned is not None and id(first) in owned:
        result = first
    else:
        result = YamlMap(first)
        result.line, result.lines = first.line, dict(first.lines)
        if owned is not None:
            owned.add(id(result))
    for key, value in second.items():
        result[key] = merged(result[key], value, owned) if key in result else value
        result.lines.setdefault(key, second.lines.get(key, second.line))
    return result


# A ROS 2 parameter file: some node's parameters are under ``ros__parameters:``, at the start
# of a line as YAML ends them (line ends: libyaml's and PyYAML's, CR LF, LF, CR, NEL, LINE and
# PARAGRAPH SEPARATOR: ``^`` under re.M starts a line after LF only, and a file whose lines end
# with CR was read as ROS 1). Each "ros__parameters" found is matched from its line's start.
_ROS2_PARAMETERS = re.compile(r"[ \t]*(?:-[ \t]+)?[\"']?ros__parameters[\"']?[ \t]*:")
_YAML_LINE_ENDS = "\r\n\x85\u2028\u2029"


def is_ros2_parameters(text: str) -> bool:
    """Whether ``text`` is a ROS 2 parameter file (it has a ``ros__parameters:`` key)."""
    at, before, start, tried = text.find("ros__parameters"), 0, 0, -1
    while at >= 0:  # (each line end looked for once, each line's start matched once: linear)
        start = max(start, max(text.rfind(end, before, at) for end in _YAML_LINE_ENDS) + 1)
        if start != tried:
            if _ROS2_PARAMETERS.match(text, start):
                return True
            tried = start
        before, at = at, text.find("ros__parameters", at + 1)
    return False



class CompanionFile(Record):
    """A parsed companion: ``data`` (YAML: YamlMap/YamlList/scalar; SRDF: the ``<robot>``
    element), or None with ``problem`` at ``line``."""

    path: Path
    display: str
    data: object
    problem: str | None
    line: int | None
    ros2: bool  # a ROS 2 parameter file (YAML with ros__parameters), read as ROS 2 does
    text: str | None  # an SRDF's text as read, for the fixes that edit it
    # an SRDF that srdfdom reads but parsers following the XML standard refuse, a ROS 2
    # parameter file ROS 2's parser reads but PyYAML cannot: why, at ``line``
    caution: str | None
    # YAML: how its launch files load it: True with substitution (subst_value, allow_substs:
    # its $(arg)/$(var) are replaced, by ``substitutions`` where known), False as written (a
    # $(arg) stays as it is), None when no launch file tells
    substituted: bool | None

    __slots__ = ("path", "display", "data", "problem", "line", "ros2", "text", "caution",
                 "substituted")

    def __init__(self, path: Path, display: str, data: object = None, problem: str | None = None,
                 line: int | None = None, ros2: bool = False, text: str | None = None,
                 caution: str | None = None, substituted: bool | None = None) -> None:
        self.path = path
        self.display = display
        self.data = data
        self.problem = problem
        self.line = line
        self.ros2 = ros2
        self.text = text
        self.caution = caution
        self.substituted = substituted

    @property
    def root(self):
        return self.data

    def at(self, line: int | None) -> Location:
        return Location(self.display, line)


YamlFile = SrdfFile = CompanionFile


_SUBSTITUTION = re.compile(r"\$\((?:arg|var)\s+([A-Za-z0-9_./-]+)\s*\)")


def read_yaml(path: Path, as_: str = "companion YAML", substituted: bool | None = None,
              substitutions: dict[str, str] | None = None, parameters: bool = True) -> YamlFile:
    """Parse one YAML file; a syntax error becomes ``problem`` at the line YAML reports.
    as_: what it is read as, for the record (:mod:`.record`).

    parameters: whether it is read as parameters, numbers computed with (False: a launch file,
    a settings file, whose readers take any integer as text). A ROS 2 parameter file (with
    ``ros__parameters``) holding a value PyYAML cannot construct, or an integer past a double,
    is then read as ROS 2's parser reads it, with a ``caution`` at ``line``
    (:func:`_unconstructed`); in any other file such a value is its ``problem``.

    substituted, substitutions: how launch files load it (see ``CompanionFile.substituted``):
    with substitution, each ``$(arg NAME)``/``$(var NAME)`` whose NAME ``substitutions`` holds
    is replaced in the text before it is parsed, as roslaunch and ROS 2's ``allow_substs`` do
    (a value holding a line break is not: lines stay where they were written)."""
    result = YamlFile(path, display_path(path), substituted=substituted)
    text = _read_text(path, result, as_)
    if text is None:
        return result
    return _parsed_yaml(result, text, substituted, substitutions, parameters)


def yaml_of(document: CompanionFile, parameters: bool = True) -> YamlFile:
    """The YAML of a text file read (:func:`read_text`, its ``text`` not None), parsed as
    :func:`read_yaml` parses a file (``parameters`` as there): what a reader that tells a file
    it could not read from one it could not parse asks (a YAML launch file)."""
    return _parsed_yaml(YamlFile(document.path, document.display), document.text, None, None,
                        parameters)


def _parsed_yaml(result: YamlFile, text: str, substituted, substitutions,
                 parameters: bool) -> YamlFile:
    if substituted and substitutions:
        text = _SUBSTITUTION.sub(lambda m: substitutions[m.group(1)]
                                 if "\n" not in substitutions.get(m.group(1), "\n") else m.group(0), text)
    import yaml

    result.ros2 = is_ros2_parameters(text)
    fast = _fast_loader() if _LIBYAML_DIFFERS.search(text) is None else None
    if fast is not None:
        try:
            loader = fast(text)
            loader.merge_repeated = result.ros2
            loader.lenient, loader.any_integer = result.ros2 and parameters, not parameters
            loader.rosparam = parameters and not result.ros2
            result.data = loader.get_single_data()
            _as_ros2_reads(result, loader)
            return result
        except Exception:  # (libyaml's error, or a limit's: PyYAML's reading says it)
            result.data = None
    try:
        loader = _loader()(text)  # (PyYAML's reader refuses a control character here)
    except yaml.reader.ReaderError as error:
        result.line = line_at(text, error.position)
        result.problem = f"unacceptable character #x{error.character:04x}: {error.reason}"
        return result
    loader.merge_repeated = result.ros2
    loader.lenient, loader.any_integer = result.ros2 and parameters, not parameters
    loader.rosparam = parameters and not result.ros2
    try:
        result.data = loader.get_single_data()
        _as_ros2_reads(result, loader)
    except yaml.MarkedYAMLError as error:
        result.line = _error_line(error, text)
        result.problem = f"{error.problem or error}" + (f" ({error.context})" if error.context else "")
    except (yaml.YAMLError, RecursionError) as error:
        result.problem = f"not valid YAML: {error}"
    finally:
        loader.dispose()
    return result


def _as_ros2_reads(result: YamlFile, loader) -> None:
    """The caution of a ROS 2 parameter file that ROS 2's parser and PyYAML read apart
    (:class:`~urdftool.description.yaml_limits.DepthLimit`'s ``lenient``), at the first place:
    a value PyYAML cannot construct (read as ROS 2 reads it: the node loads the file, a launch
    file loading it with PyYAML fails), an alias (rcl_yaml_param_parser refuses every one: the
    node fails, a launch file loading it with PyYAML reads it). Whether the file loads depends
    on what reads it: a warning, never the file's error."""
    said = []
    found = loader.unconstructed
    if found:
        line, why = found[0]
        more = f" (and {len(found) - 1} more such values)" if len(found) > 1 else ""
        said.append((line, (
            f"{why}{more}: ROS 2's parameter parser reads it as written (no dates, no tag but "
            "!!str, a number past its types as text), so the file loads as a node's parameter "
            "file, but a launch file or tool loading it with PyYAML (yaml.safe_load) fails")))
    if loader.aliased is not None:
        said.append((loader.aliased, (
            f"an alias (*name) on line {loader.aliased}: ROS 2's parameter parser refuses "
            "every alias (\"Will not support aliasing\"), so a node given this file as its "
            "parameter file fails to start; only a launch file loading it with PyYAML reads it")))
    if said:
        said.sort()
        result.line = said[0][0]
        result.caution = "; and ".join(text for _, text in said)


def _error_line(error, text: str) -> int | None:
    """The line (1-based) to report a YAML syntax error at: where an unclosed bracket or quote
    opened when PyYAML's context says so, or when it only noticed at the end of the file; never
    past the file's last non-blank line (PyYAML puts the end of the stream on the line after
    the final newline)."""
    from urdftool.description.yaml_limits import line_of

    problem, context = error.problem_mark, error.context_mark
    at_end = problem is not None and problem.index >= len(text.rstrip())
    opened = (error.context or "").startswith(("while parsing a flow", "while scanning a quoted"))
    mark = problem or context
    if context is not None and (opened or at_end) and context.index < len(text.rstrip()):
        mark = context
    if mark is None:
        return None
    last = max(1, len(lines_of(text.rstrip())))
    return min(line_of(mark, text), last)


# what an SRDF is read as (the record's kind): a rewrite is meant of a file read so only
# (``collisions --write-srdf`` updates an SRDF, never an include named in its place)
SRDF_READ_AS = "companion SRDF"


def read_srdf(path: Path, as_: str = SRDF_READ_AS) -> SrdfFile:
    """Parse one SRDF; a syntax error becomes ``problem`` at its line."""
    result = SrdfFile(path, display_path(path))
    text = _read_text(path, result, as_)
    if text is None:
        return result
    from lxml import etree

    parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False)
    result.text = text
    read, result.caution, result.line = _entities_kept(text)
    try:
        result.data = etree.fromstring(read.encode(), parser)
    except etree.XMLSyntaxError as error:
        conflict = merge_conflict(text.encode())
        result.problem, result.line = (conflict.message, conflict.line) if conflict else \
            (f"not well-formed XML: {error.msg}", _xml_error_line(error, text))
        comments = None if conflict else tinyxml2_comments(read.encode())
        if comments is None:
            return result
        try:  # as srdfdom's TinyXML2 reads it
            result.data = etree.fromstring(comments[0], parser)
        except etree.XMLSyntaxError:
            return result
        result.problem, result.line = None, comments[1]
        result.caution = (result.caution + "; and " if result.caution else "") + (
            "not well-formed XML, '--' inside a comment: srdfdom reads it (TinyXML2 ends a "
            "comment at the first '-->'), so MoveIt does when its launch file loads the SRDF "
            "as text (ROS 1's textfile=, a Python launch file reading it), but xacro refuses "
            "it, and MoveItConfigsBuilder passes every SRDF through xacro; write the comment "
            "without '--'")
    _start_tag_lines(result.data, text)
    _trimmed(result.data)
    if result.data.tag != "robot":
        result.problem, result.line = (f"root element is <{result.data.tag}>, not <robot>",
                                       result.data.sourceline)
        result.data = None
    return result


def _entities_kept(text: str) -> tuple[str, str | None, int | None]:
    """(the SRDF as srdfdom reads it, why it differs, the line of the first difference): an
    entity the file declares and uses (``<!ENTITY g "head">``, ``<group name="&g;">``) is
    expanded by libxml2 (lxml) and kept as those characters by srdfdom's TinyXML2, which skips
    the DOCTYPE (measured through urdfdom 6.0's check_urdf, the same TinyXML2: ``<link
    name="&g;">`` is the link ``&g;``); each such reference is then written as its characters
    (``&amp;g;``: lines unchanged), so that no name is checked that MoveIt does not read.
    (text, None, None) for nearly every SRDF."""
    data = text.encode()
    uses = entity_uses(data)
    if not uses:
        return text, None, None
    pieces, at = [], 0
    for written, offset in uses:
        pieces += [data[at:offset], b"&amp;", written[1:]]
        at = offset + len(written)
    read = b"".join([*pieces, data[at:]]).decode()
    return read, (f"declares the entity '{uses[0][0].decode()}' and uses it: srdfdom (TinyXML2) "
                  "expands no entity, so MoveIt reads the characters as written when its "
                  "launch file loads the SRDF as text (ROS 1's textfile=, a Python launch file "
                  "reading it), the entity's text when it passes through xacro "
                  "(MoveItConfigsBuilder); the SRDF is checked as srdfdom reads it; write the "
                  "text in place of each entity"), line_at(data, uses[0][1])


# What srdfdom reads of an attribute untrimmed: a joint property's value, a collision pair's
# reason; every name it trims (boost::trim, src/model.cpp), so `<group name="arm ">` is "arm"
_UNTRIMMED = frozenset({"value", "reason"})
_BLANKS = " \t\n\r\f\v"  # (C's isspace, as boost::trim's default locale has it)


def _trimmed(root) -> None:
    """The names of an SRDF's elements as srdfdom reads them: without the white space around
    them (``<group name="arm ">`` is the group "arm" that MoveIt knows, not another one)."""
    for element in root.iter():
        for name, value in element.attrib.items():
            if name not in _UNTRIMMED and value != value.strip(_BLANKS):
                element.set(name, value.strip(_BLANKS))


def _xml_error_line(error, text: str) -> int | None:
    """libxml2's line, except that an element left open is reported where it opened ("Premature
    end of data in tag group line 2"), not on the line after the end of the file."""
    opened = re.search(r"Premature end of data in tag \S+ line (\d+)", error.msg or "")
    line = int(opened.group(1)) if opened else error.lineno
    return min(line, max(1, len(lines_of(text.rstrip())))) if line else line


# The largest line lxml's sourceline setter takes (libxml2's unsigned short); lxml reads larger
# lines itself (XML_PARSE_BIG_LINES). An SRDF of 100,000 entries crashed 61 rules with
# "OverflowError: value too large to convert to unsigned short" (a crash of each rule).
_MOST_SOURCELINE = 65535


def _start_tag_lines(root, text: str) -> None:
    """Give each element the line of its ``<`` (lxml keeps the line of the closing ``>``),
    where lxml can hold it: past line 65,535 an element keeps lxml's own line, its ``>``'s
    (the same line unless the start tag is written across lines)."""
    from lxml import etree

    elements = list(root.iter(etree.Element))
    try:
        lines = start_tag_lines(text.encode())
    except XmlProblem:  # libxml2 accepted what expat refuses (an entity): keep lxml's lines
        return
    if len(lines) == len(elements):
        for element, line in zip(elements, lines):
            if line <= _MOST_SOURCELINE:
                element.sourceline = line


def read_text(path: Path, limit: int = MAX_SIZE, as_: str = "launch file") -> CompanionFile:
    """One text file (a launch file) read as companions are: ``text`` when it is a regular file
    of at most ``limit`` bytes in UTF-8, else ``problem`` says why."""
    result = CompanionFile(path, display_path(path))
    result.text = _read_text(path, result, as_, limit)
    return result


def _read_text(path: Path, result, as_: str, limit: int = MAX_SIZE) -> str | None:
    """The file's text when it is a regular file of at most ``limit`` bytes in UTF-8; else None
    and ``result.problem`` says why (nothing is read from a FIFO or a device), at
    ``result.line`` where a byte is not UTF-8."""
    try:
        data = read_regular(path, limit, as_)
    except TooLarge:
        result.problem = f"larger than {limit} bytes; not read"
        return None
    except OSError as error:
        result.problem = f"cannot be read: {error.strerror}"
        return None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as error:  # (Python's words named a position in bytes)
        result.line = line_at(data, error.start)
        result.problem = (f"not UTF-8 text: byte 0x{data[error.start]:02x} on line "
                          f"{result.line} ({error.reason})")
    return None
