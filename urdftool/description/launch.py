"""Launch files read without running them: what each one declares, starts, loads and includes.

Readers, one per form, all giving the same :class:`LaunchFile`:

- ROS 1 XML (``.launch``, ``.launch.xml``): ``<arg>`` (``default=`` may be given at launch,
  ``value=`` may not), ``<include file>`` with its ``<arg>``\\s, ``<group>``, ``<node pkg type
  args>`` with its ``<param>``/``<rosparam>``/``<remap>`` children, ``<remap from to>`` beside
  nodes (for the nodes after it in its scope, those of included files too), ``<param name
  command|textfile>`` (``robot_description`` from xacro with its arguments), ``<rosparam
  command="load" file subst_value>``, and ``if``/``unless`` on each; substitutions ``$(arg)``,
  ``$(find)`` (of a package named there or by an argument, ``$(find $(arg pkg))``),
  ``$(optenv)``/``$(env)``, ``$(dirname)``.
- ROS 2 XML and YAML (``.launch.xml``, ``.launch.yaml``): the same elements with ``exec``,
  ``<let>`` (one holding ``$(command 'xacro ...')`` builds the robot where a ``<param>`` takes
  it by ``$(var ...)``), ``<param from>``, ``<executable cmd>``, a node's ``<remap>`` (YAML's
  ``remap:`` list) and ``<set_remap>``; ``$(var)``,
  ``$(find-pkg-share)``, ``$(find-exec)`` (the program's name), ``$(command '...')``.
- ROS 2 Python (``.launch.py``): by static analysis of its syntax tree,
  :mod:`urdftool.description.launch_python` (:func:`~urdftool.description.launch_configs.read_launch`
  picks the reader).

A launch file is a stranger's program: it is parsed, never executed, imported or evaluated.
Files over :data:`MAX_LAUNCH_SIZE` are not read, nesting and the number of actions are bounded,
and every path a launch file names is resolved later, only inside the repository
(:mod:`urdftool.description.launch_configs`). What a reader cannot tell (``$(eval ...)``, a
value computed in Python) is kept as unknown, never guessed.
"""

from __future__ import annotations

import re
from pathlib import Path

from urdftool.diagnostics import AT_LINE_START
from urdftool.description.documents import read_text, yaml_of, YamlMap
from urdftool.errors import described
from urdftool.records import Frozen, NEW, Record

MAX_LAUNCH_SIZE = 512 * 1024  # [bytes]
MAX_ACTIONS = 5000  # per file
MAX_SUBSTITUTION_DEPTH = 8
MAX_TEXT = 16 * 1024  # [characters] a resolved value may have
LAUNCH_SUFFIXES = (".launch", ".launch.xml", ".launch.py", ".launch.yaml", ".launch.yml")


# --- values: text with substitutions ----------------------------------------------------------

class Value(Frozen):
    """Text as a launch file writes it: literal parts and substitutions.

    parts: each a ``str``, or a tuple: ``("arg", name, default Value or None)``, ``("find",
        package)`` (the package's name, a ``str``, or a Value when a launch argument names it:
        ``$(find $(arg pkg))``, ``FindPackageShare(LaunchConfiguration("pkg"))``), ``("env",
        name, default Value or None)``, ``("dirname",)``, ``("command", Value)``, ``("unknown",
        text)``
    text: as written, for messages
    """

    parts: tuple
    text: str

    __slots__ = ("parts", "text")

    def __init__(self, parts: tuple, text: str) -> None:
        set_field = object.__setattr__
        set_field(self, "parts", parts)
        set_field(self, "text", text)

    @property
    def literal(self) -> str | None:
        """The text when it holds no substitution."""
        return self.parts[0] if len(self.parts) == 1 and isinstance(self.parts[0], str) else \
            ("" if not self.parts else None)

    def names(self) -> set[str]:
        """The launch arguments it reads."""
        found = set()
        for part in self.parts:
            if isinstance(part, tuple) and part[0] == "arg":
                found.add(part[1])
                if part[2] is not None:
                    found |= part[2].names()
            elif isinstance(part, tuple) and part[0] in ("command", "find") \
                    and isinstance(part[1], Value):
                found |= part[1].names()
        return found


def literal(text: str) -> Value:
    return Value((text,) if text else (), text)


def unknown(text: str) -> Value:
    return Value((("unknown", text),), text)


def concat(values, text: str | None = None) -> Value:
    """The values one after the other (adjacent literals joined); an item that is no Value is
    unknown: a launch file may pass anything where launch takes a substitution (``None``, a
    dict, a condition in ``Command([...])``: every rule asking of the launch files crashed on
    it)."""
    values = [value if isinstance(value, Value) else unknown("?") for value in values]
    parts: list = []
    for value in values:
        for part in value.parts:
            if isinstance(part, str) and parts and isinstance(parts[-1], str):
                parts[-1] += part
            else:
                parts.append(part)
    return Value(tuple(parts), text if text is not None else "".join(v.text for v in values))


def substituted(text: str | None) -> Value | None:
    """``text`` with its ``$(...)`` substitutions (ROS 1 and ROS 2 spellings), nested ones too."""
    if text is None:
        return None
    return Value(tuple(_substitutions(text, 0)), text)


_FIND = ("find", "find-pkg-share", "find-pkg-prefix")


def _substitutions(text: str, depth: int) -> list:
    parts: list = []
    index = 0
    while index < len(text):
        start = text.find("$(", index)
        if start < 0:
            parts.append(text[index:])
            break
        if start > index:
            parts.append(text[index:start])
        end = _closing(text, start + 2)
        if end is None:
            parts.append(("unknown", text[start:]))
            break
        parts.append(_substitution(text[start + 2:end], text[start:end + 1], depth))
        index = end + 1
    merged: list = []  # adjacent texts as one (a substitution may give text: $(find-exec x))
    for part in parts:
        if isinstance(part, str) and merged and isinstance(merged[-1], str):
            merged[-1] += part
        elif part != "":
            merged.append(part)
    return merged


def _closing(text: str, index: int) -> int | None:
    """The index of the ``)`` closing a ``$(`` whose content starts at ``index``."""
    close = text.find(")", index)
    if close < 0:
        return None
    inner = text[index:close]
    if "(" not in inner and "'" not in inner and '"' not in inner:  # (no nesting, no quote)
        return close
    depth, quote = 1, None
    for position in range(index, len(text)):
        char = text[position]
        if quote:
            if char == quote:
                quote = None
        elif char in "'\"" and depth == 1 and text[position - 1] in " (":
            quote = char
        elif char == "(":
            depth += 1
        elif char == ")":
            depth -= 1
            if depth == 0:
                return position
    return None


def _substitution(inner: str, written: str, depth: int):
    kind, _, rest = inner.strip().partition(" ")
    words = _words(rest)
    if depth >= MAX_SUBSTITUTION_DEPTH:
        return ("unknown", written)
    if kind in ("arg", "var") and len(words) == 1 and "$(" not in words[0]:
        return ("arg", words[0], None)
    if kind in _FIND and len(words) >= 1 and "$(" not in words[0]:
        return ("find", words[0]) if len(words) == 1 else ("unknown", written)
    if kind in _FIND and "$(" in rest:  # $(find $(arg pkg)), a launch argument names it
        package = Value(tuple(_substitutions(rest.strip(), depth + 1)), rest.strip())
        if any(isinstance(p, str) and any(c.isspace() for c in p) for p in package.parts):
            return ("unknown", written)  # more than one word
        return ("find", package)
    if kind == "find-exec" and len(words) == 1 and "$(" not in words[0]:
        return words[0]  # the program's path: named by the program (``$(find-exec xacro)``)
    if kind in ("env", "optenv") and words and "$(" not in words[0]:
        default = substituted(" ".join(words[1:])) if len(words) > 1 or kind == "optenv" else None
        return ("env", words[0], default)
    if kind == "dirname":
        return ("dirname",)
    if kind == "command":
        return ("command", Value(tuple(_substitutions(rest.strip().strip("'\""), depth + 1)), rest))
    return ("unknown", written)


def _words(text: str) -> list[str]:
    """Words split at spaces outside quotes, quotes removed."""
    if "'" not in text and '"' not in text:
        return text.split()  # (at what str.isspace says is a space, as below)
    words, current, quote = [], "", None
    for char in text:
        if quote:
            if char == quote:
                quote = None
            else:
                current += char
        elif char in "'\"":
            quote = char
        elif char.isspace():
            if current:
                words.append(current)
            current = ""
        else:
            current += char
    if current:
        words.append(current)
    return words


# --- conditions ---------------------------------------------------------------------------------

class Condition(Frozen):
    """When an action runs: ``kind`` "if"/"unless" (``value`` true or false), "equals" /
    "differs" (``value`` against ``other``), or "unknown" (a Python test, an expression;
    ``value`` holds the arguments it reads, ``text`` what was written)."""

    kind: str
    value: Value
    text: str
    other: Value | None

    __slots__ = ("kind", "value", "text", "other")

    def __init__(self, kind: str, value: Value, text: str, other: Value | None = None) -> None:
        set_field = object.__setattr__
        set_field(self, "kind", kind)
        set_field(self, "value", value)
        set_field(self, "text", text)
        set_field(self, "other", other)


# --- actions ------------------------------------------------------------------------------------

class Arg(Frozen):
    """A launch argument: ``fixed`` when the file sets it (ROS 1 ``value=``, ``<let>``,
    SetLaunchConfiguration), else it may be given at launch and ``default`` is used otherwise
    (None: required)."""

    name: str
    default: Value | None
    fixed: bool
    when: tuple
    line: int | None

    __slots__ = ("name", "default", "fixed", "when", "line")

    def __init__(self, name: str, default: Value | None, fixed: bool, when: tuple = (),
                 line: int | None = None) -> None:
        set_field = object.__setattr__
        set_field(self, "name", name)
        set_field(self, "default", default)
        set_field(self, "fixed", fixed)
        set_field(self, "when", when)
        set_field(self, "line", line)


class Include(Frozen):
    """Another launch file included, with the arguments given to it (``every``: ROS 1's
    ``pass_all_args``) and the remaps of its scope (:class:`Remap`), which hold for the nodes
    it starts."""

    path: Value
    args: tuple  # ((name, Value), ...)
    when: tuple
    line: int | None
    every: bool
    remaps: tuple  # Remap

    __slots__ = ("path", "args", "when", "line", "every", "remaps")

    def __init__(self, path: Value, args: tuple, when: tuple = (), line: int | None = None,
                 every: bool = False, remaps: tuple = ()) -> None:
        set_field = object.__setattr__
        set_field(self, "path", path)
        set_field(self, "args", args)
        set_field(self, "when", when)
        set_field(self, "line", line)
        set_field(self, "every", every)
        set_field(self, "remaps", remaps)


class ParamFile(Frozen):
    """A parameter file loaded (``<rosparam command="load">``, a node's parameter file, a
    spawner's ``--param-file``); ``substitute``: its ``$(arg)``/``$(var)`` are replaced
    (``subst_value``, ``allow_substs``)."""

    path: Value
    substitute: bool
    when: tuple
    line: int | None

    __slots__ = ("path", "substitute", "when", "line")

    def __init__(self, path: Value, substitute: bool = False, when: tuple = (),
                 line: int | None = None) -> None:
        set_field = object.__setattr__
        set_field(self, "path", path)
        set_field(self, "substitute", substitute)
        set_field(self, "when", when)
        set_field(self, "line", line)


class Remap(Frozen):
    """A name remapped for a node: ROS 1's ``<remap from to>`` (a node's child, or beside
    nodes: then for every node after it in its scope, included files' too), ROS 2's
    ``remappings=[(from, to)]``, ``<remap>``/``<set_remap>``, YAML's ``remap: [{from, to}]``.
    ``when``: its own conditions (those of its scope are the node's)."""

    source: Value
    target: Value
    when: tuple
    line: int | None

    __slots__ = ("source", "target", "when", "line")

    def __init__(self, source: Value, target: Value, when: tuple = (),
                 line: int | None = None) -> None:
        set_field = object.__setattr__
        set_field(self, "source", source)
        set_field(self, "target", target)
        set_field(self, "when", when)
        set_field(self, "line", line)


class Start(Frozen):
    """A node or process started: ``package``/``executable`` (a process: empty package,
    ``executable`` its command line), its argument words, the parameter files given to it, the
    names remapped for it (:class:`Remap`, those of its scope first)."""

    package: Value
    executable: Value
    arguments: tuple  # Values, each one or more words once resolved
    files: tuple  # ParamFile
    when: tuple
    line: int | None
    remaps: tuple  # Remap

    __slots__ = ("package", "executable", "arguments", "files", "when", "line", "remaps")

    def __init__(self, package: Value, executable: Value, arguments: tuple, files: tuple = (),
                 when: tuple = (), line: int | None = None, remaps: tuple = ()) -> None:
        set_field = object.__setattr__
        set_field(self, "package", package)
        set_field(self, "executable", executable)
        set_field(self, "arguments", arguments)
        set_field(self, "files", files)
        set_field(self, "when", when)
        set_field(self, "line", line)
        set_field(self, "remaps", remaps)


class Description(Frozen):
    """A robot (or semantic) description made from a file: ``command`` a command line (xacro's,
    or ``cat``; the file and its ``name:=value`` arguments are read from it once resolved), or
    ``file`` with ``args`` given apart: run through xacro when ``xacro`` (xacro.process_file's
    mappings, MoveItConfigsBuilder), else read as it is (``textfile=``, Python's ``open``).
    ``complete``: every argument given is in ``args`` (False when a mapping was not read).
    ``replaced``: for a file read as it is, the texts the launch file replaces in it before
    loading it (None for one not known without running it): a template it fills.
    ``published``: the conditions under which the description reaches a controller manager (the
    robot_state_publisher or ros2_control_node given it), when they are more than ``when``'s
    (a description given to those under a condition and to MoveIt unconditionally); else None."""

    command: Value | None
    file: Value | None
    args: tuple  # ((name, Value), ...)
    when: tuple
    line: int | None
    parameter: str  # the parameter it is loaded into, as written ("" when not said)
    xacro: bool  # for ``file``: run through xacro
    complete: bool
    replaced: tuple
    published: tuple | None

    __slots__ = ("command", "file", "args", "when", "line", "parameter", "xacro", "complete",
                 "replaced", "published")

    def __init__(self, command: Value | None = None, file: Value | None = None, args: tuple = (),
                 when: tuple = (), line: int | None = None, parameter: str = "",
                 xacro: bool = False, complete: bool = True, replaced: tuple = (),
                 published: tuple | None = None) -> None:
        set_field = object.__setattr__
        set_field(self, "command", command)
        set_field(self, "file", file)
        set_field(self, "args", args)
        set_field(self, "when", when)
        set_field(self, "line", line)
        set_field(self, "parameter", parameter)
        set_field(self, "xacro", xacro)
        set_field(self, "complete", complete)
        set_field(self, "replaced", replaced)
        set_field(self, "published", published)


class LaunchFile(Record):
    """One launch file, read. ``form``: "ros1", "ros2-xml", "ros2-yaml" or "ros2-python";
    ``actions``: Arg, Include, ParamFile, Start and Description, in the order written;
    ``problem``: why it could not be read (then it has no actions)."""

    path: Path
    display: str
    form: str
    actions: list
    problem: str | None
    problem_line: int | None  # the line the problem is at, when the parser said
    test: bool  # a launch test (:func:`is_launch_test`), read from its entry point

    __slots__ = ("path", "display", "form", "actions", "problem", "problem_line", "test")

    def __init__(self, path: Path, display: str, form: str, actions: list = NEW,
                 problem: str | None = None, problem_line: int | None = None,
                 test: bool = False) -> None:
        self.path = path
        self.display = display
        self.form = form
        self.actions = [] if actions is NEW else actions
        self.problem = problem
        self.problem_line = problem_line
        self.test = test

    @property
    def ros(self) -> int:
        return 1 if self.form == "ros1" else 2

    @property
    def named(self) -> str:
        """What it is and where, as a finding names it (:func:`named`)."""
        return named(self.display, self.test)


def named(display: str, test: bool = False, read: bool = True) -> str:
    """A source of launch evidence as a finding names it: what it is, then where ("launch
    file launch/robot.launch.py", "launch test test/robot.py"), and "(not read)" when it could
    not be read (:func:`was_read`). The one describing function: a launch test shows how a
    robot file is built, never what a deployment starts, so a reader must be told which of the
    two said it."""
    return f"{'launch test' if test else 'launch file'} {display}" + ("" if read else " (not read)")


def was_read(launch: LaunchFile | None) -> bool:
    """Whether reading a launch file or launch test told what it does: parsed (or read in
    part, with actions). The one test of "could not be read" for every reader of launch files
    and tests: what one that was not read does is unknown
    (:func:`urdftool.description.runtime.unread_naming`), never nothing."""
    return launch is not None and (launch.problem is None or bool(launch.actions))


def is_launch_file(path: Path, root: Path) -> bool:
    """A launch file by its name: ``*.launch``, ``*.launch.xml|py|yaml``, or a ``.py``,
    ``.xml`` or ``.yaml`` in a ``launch`` folder below ``root``."""
    name = path.name
    if name.endswith(LAUNCH_SUFFIXES):
        return True
    try:
        folders = path.parent.relative_to(root).parts
    except ValueError:
        return False
    return is_launch_name(name, bool(folders) and folders[-1] == "launch")


def is_launch_name(name: str, in_launch_folder: bool) -> bool:
    """:func:`is_launch_file` of a file named ``name``, in a ``launch`` folder below the root
    or not (a walk's listing: no path made)."""
    return name.endswith(LAUNCH_SUFFIXES) or in_launch_folder and \
        name.endswith((".py", ".xml", ".yaml", ".yml")) and not name.startswith(("__", "test_"))


# launch_testing's entry point: ``launch_test FILE`` and CMake's ``add_launch_test`` run it
LAUNCH_TEST_ENTRY = "generate_test_description"
_TEST_FOLDERS = ("test", "tests")
# (at the start of a line as Python ends them, CR LF, LF or CR: a Location's; a multi-line
# ``^`` starts one after LF only)
_DEFINES_TEST = re.compile(AT_LINE_START + rf"(?:async\s+)?def\s+{LAUNCH_TEST_ENTRY}\s*\(")
_DEFINES_LAUNCH = re.compile(AT_LINE_START + r"(?:async\s+)?def\s+generate_launch_description\s*\(")


def may_be_launch_test(path: Path, root: Path) -> bool:
    """A Python file that may be a launch test, by its name: in a ``test`` or ``tests`` folder
    below ``root``, or named ``test_*.py``, ``*_test.py`` or ``*.test.py``; read, it is one
    when :func:`is_launch_test` says so."""
    name = path.name
    if not name.endswith(".py"):
        return False
    if name.startswith("test_") or name.endswith(("_test.py", ".test.py")):
        return True
    try:
        folders = path.parent.relative_to(root).parts
    except ValueError:
        return False
    return any(folder in _TEST_FOLDERS for folder in folders)


def is_launch_test(text: str) -> bool:
    """Whether a Python file's text is a launch test: it defines launch_testing's
    ``generate_test_description`` (and not ``generate_launch_description``: then ``ros2
    launch`` runs it, a launch file). The one decision of what a launch test is. A launch test
    shows how a robot file is built (its robot description), never what a deployment starts:
    its controllers and nodes run for the test alone
    (:func:`~urdftool.description.launch_configs.launch_index` keeps it apart)."""
    # (the name looked for first: a pattern starting at any line start is tried at every
    # character, 3 M instructions over a repository's launch files that never name it)
    return LAUNCH_TEST_ENTRY in text and bool(_DEFINES_TEST.search(text)) and \
        not _DEFINES_LAUNCH.search(text)


def read_launch_text(path: Path) -> LaunchFile | str:
    """An XML or YAML launch file read (never run); the text of a Python one, for
    :mod:`urdftool.description.launch_python`. A file that cannot be read or parsed has a
    ``problem`` and no actions."""
    if path.name.endswith((".yaml", ".yml")):
        return _read_yaml_launch(path)
    document = read_text(path, MAX_LAUNCH_SIZE)
    if document.text is None:
        form = "ros2-python" if path.name.endswith(".py") else "ros1"
        return LaunchFile(path, document.display, form, problem=document.problem,
                          problem_line=document.line)
    if path.name.endswith(".py"):
        return document.text
    return _read_xml_launch(path, document.display, document.text)


# --- XML (ROS 1 and ROS 2) ----------------------------------------------------------------------

_ROS2_XML = re.compile(r"\bexec\s*=|\$\(var\s|\$\(find-pkg-|<let\b")


def _read_xml_launch(path: Path, display: str, text: str) -> LaunchFile:
    from urdftool.description.xml import XmlProblem, parse

    form = "ros2-xml" if _ROS2_XML.search(text) else "ros1"
    launch = LaunchFile(path, display, form)
    try:
        root, positions = parse(text.encode())
    except XmlProblem as error:
        # what it is: empty, not well-formed, or well-formed and refused (an entity declared,
        # an external DTD, nested too deep, binary), each said as itself (all were "not
        # well-formed XML")
        launch.problem = "empty" if error.kind == "empty" else (  # (its message says <robot>)
            f"not well-formed XML: {error.message.removeprefix('malformed XML: ')}"
            if error.message.startswith("malformed XML: ") else f"not read: {error.message}"
        ) + (f" (line {error.line})" if error.line and error.kind != "empty" else "")
        launch.problem_line = error.line
        return launch
    except (ValueError, SyntaxError) as error:  # lxml's XMLSyntaxError is one
        launch.problem = f"not well-formed XML: {error}"
        return launch
    except Exception as error:  # noqa: BLE001 - a stranger's file must not stop the check
        launch.problem = f"not read: {described(error)}"
        return launch
    if root.tag != "launch":
        launch.problem = f"root element is <{root.tag}>, not <launch>"
        launch.problem_line = positions[root][0] if root in positions else root.sourceline
        return launch

    def line(element) -> int | None:
        position = positions.get(element)
        return position[0] if position else element.sourceline

    _xml_children(root, (), launch, line, 0, [])
    return launch


# roslaunch's commonest expression, read (never evaluated) as the comparison it writes:
# if="$(eval arg('arm') == 'gen3')" (ros_kortex's launch files choose a default by it)
_EVAL_COMPARE = re.compile(r"""\s*\$\(eval\s+arg\(\s*(["'])(\w+)\1\s*\)\s*(==|!=)\s*(["'])([^"'$]*)\4\s*\)\s*""")


def _when(element) -> tuple:
    found = []
    for key in ("if", "unless"):
        value = element.get(key)
        if value is None:
            continue
        compared = _EVAL_COMPARE.fullmatch(value)
        if compared:
            equals = (compared.group(3) == "==") == (key == "if")
            found.append(Condition("equals" if equals else "differs",
                                   substituted(f"$(arg {compared.group(2)})"), f'{key}="{value}"',
                                   substituted(compared.group(5))))
        else:
            found.append(Condition(key, substituted(value), f'{key}="{value}"'))
    return tuple(found)


def _xml_remap(element, when: tuple, line) -> Remap | None:
    source, target = element.get("from"), element.get("to")
    if not source or target is None:
        return None
    return Remap(substituted(source), substituted(target), when, line(element))


def _xml_children(parent, when: tuple, launch: LaunchFile, line, depth: int, remaps: list) -> None:
    """The actions of ``parent``'s children; ``remaps``: those of the scope so far (a
    ``<remap>`` beside nodes holds for the nodes after it in its scope, a group's own ending
    with it)."""
    for element in parent:
        if not isinstance(element.tag, str) or len(launch.actions) >= MAX_ACTIONS or depth > 64:
            continue
        own = when + _when(element)
        tag = element.tag
        if tag == "arg" and element.get("name"):
            fixed = element.get("value") is not None
            default = element.get("value") if fixed else element.get("default")
            launch.actions.append(Arg(element.get("name"), substituted(default), fixed, own,
                                      line(element)))
        elif tag == "let" and element.get("name"):
            launch.actions.append(Arg(element.get("name"), substituted(element.get("value", "")),
                                      True, own, line(element)))
        elif tag == "include" and element.get("file"):
            args = tuple((a.get("name"), substituted(a.get("value", a.get("default", ""))))
                         for a in element if a.tag == "arg" and a.get("name"))
            every = (element.get("pass_all_args") or "").strip().lower() in ("true", "1")
            launch.actions.append(Include(substituted(element.get("file")), args, own, line(element),
                                          every, tuple(remaps)))
        elif tag == "group":
            _xml_children(element, own, launch, line, depth + 1, list(remaps))
        elif tag in ("remap", "set_remap"):
            remap = _xml_remap(element, _when(element), line)
            if remap is not None:
                remaps.append(remap)
        elif tag == "node" and element.get("pkg"):
            _xml_node(element, own, launch, line, remaps)
        elif tag == "executable" and element.get("cmd"):
            launch.actions.append(Start(literal(""), substituted(element.get("cmd")), (), (), own,
                                        line(element)))
        elif tag == "param":
            _xml_param(element, own, launch, line)
        elif tag == "rosparam":
            loaded = _rosparam(element, own, line)
            if loaded is not None:
                launch.actions.append(loaded)


def _xml_node(element, when, launch, line, remaps: list) -> None:
    files, remaps = [], list(remaps)
    for child in element:
        if not isinstance(child.tag, str):
            continue
        if child.tag == "remap":
            remap = _xml_remap(child, _when(child), line)
            if remap is not None:
                remaps.append(remap)
        elif child.tag == "rosparam":
            loaded = _rosparam(child, when + _when(child), line)
            if loaded is not None:
                files.append(loaded)
        elif child.tag == "param" and child.get("from"):
            files.append(ParamFile(substituted(child.get("from")), True, when + _when(child),
                                   line(child)))
        elif child.tag == "param":
            _xml_param(child, when + _when(child), launch, line)
    executable = element.get("type") or element.get("exec") or ""
    arguments = (substituted(element.get("args")),) if element.get("args") else ()
    launch.actions.append(Start(substituted(element.get("pkg")), substituted(executable),
                                arguments, tuple(files), when, line(element), tuple(remaps)))


_LET_VALUE = re.compile(r"\$\((?:var|arg)\s+([\w/-]+)\)")


def _xml_param(element, when, launch, line) -> None:
    """A ``<param>`` holding a description: ``command=`` (xacro) or ``textfile=`` (a URDF)."""
    command, textfile = element.get("command"), element.get("textfile")
    name = element.get("name") or ""
    held = _held(command, launch) if command else None
    if held is not None:
        launch.actions.append(Description(held, None, (), when, line(element), name))
    elif command and ("xacro" in command or ".urdf" in command):
        launch.actions.append(Description(substituted(command), None, (), when, line(element), name))
    elif textfile:
        launch.actions.append(Description(None, substituted(textfile), (), when, line(element), name))
    value = element.get("value") or ""
    held = _LET_VALUE.fullmatch(value.strip())
    if held:  # value="$(var robot_description)", a <let> above holding the command (Kassow's)
        value = next((a.default.text for a in reversed(launch.actions) if isinstance(a, Arg)
                      and a.fixed and a.name == held.group(1) and a.default is not None), value)
    if value.startswith("$(command") and "xacro" in value:  # ROS 2 XML: value="$(command 'xacro ...')"
        launch.actions.append(Description(substituted(value), None, (), when, line(element), name))


def _held(command: str, launch: LaunchFile) -> Value | None:
    """The command an argument above holds when ``command`` is only that argument and its value
    (set, or its default) runs xacro or names a URDF: ``<arg name="cmd" default="$(find
    xacro)/xacro .../drone4.xacro main_camera:=$(arg main_camera)"/>`` then ``<param
    command="$(arg cmd)"/>`` (COEX Clover's spawn_drone.launch). roslaunch substitutes the
    argument, then splits the command into words, so the command read is the value written
    there (a value given at launch for ``cmd`` itself is not followed); None otherwise."""
    held = _LET_VALUE.fullmatch(command.strip())
    value = next((a.default for a in reversed(launch.actions) if isinstance(a, Arg)
                  and held and a.name == held.group(1) and a.default is not None), None)
    return value if value is not None and ("xacro" in value.text or ".urdf" in value.text) \
        else None


def _rosparam(element, when, line) -> ParamFile | None:
    command = element.get("command", "load")
    if command != "load" or not element.get("file"):
        return None
    substitute = (element.get("subst_value") or "").strip().lower() in ("true", "1")
    return ParamFile(substituted(element.get("file")), substitute, when, line(element))


# --- YAML (ROS 2) -------------------------------------------------------------------------------

def _read_yaml_launch(path: Path) -> LaunchFile:
    text = read_text(path, MAX_LAUNCH_SIZE)  # (the size every launch file is read at: a YAML
    # one was read up to 16 MiB)
    launch = LaunchFile(path, text.display, "ros2-yaml")
    document = yaml_of(text, parameters=False) if text.text is not None else text
    if document.problem:  # not read, or not YAML: each said as itself
        launch.problem = document.problem if text.text is None else \
            f"not valid YAML: {document.problem.removeprefix('not valid YAML: ')}"
        launch.problem_line = document.line
        return launch
    data = document.data
    entries = data.get("launch") if isinstance(data, dict) else None
    if not isinstance(entries, list):
        launch.problem = "no top-level 'launch:' list"
        return launch
    _yaml_entries(entries, (), launch, 0)
    return launch


def _yaml_when(entry) -> tuple:
    found = []
    for key in ("if", "unless"):
        if isinstance(entry.get(key), str):
            found.append(Condition(key, substituted(entry[key]), f"{key}: {entry[key]}"))
    return tuple(found)


def _yaml_line(mapping, key=None) -> int | None:
    if isinstance(mapping, YamlMap):
        return mapping.lines.get(key, mapping.line) if key is not None else mapping.line
    return None


def _text(value) -> Value | None:
    if isinstance(value, (str, int, float, bool)):
        return substituted(str(value).lower() if isinstance(value, bool) else str(value))
    return None


def _yaml_entries(entries, when: tuple, launch: LaunchFile, depth: int) -> None:
    if depth > 32:
        return
    for item in entries:
        if not isinstance(item, dict) or len(launch.actions) >= MAX_ACTIONS:
            continue
        for kind, entry in item.items():
            if not isinstance(entry, dict):
                continue
            own = when + _yaml_when(entry)
            at = _yaml_line(item, kind)
            if kind in ("arg", "let") and isinstance(entry.get("name"), str):
                value = entry.get("value" if kind == "let" else "default")
                launch.actions.append(Arg(entry["name"], _text(value), kind == "let", own, at))
            elif kind == "include" and _text(entry.get("file")) is not None:
                args = entry.get("arg") if isinstance(entry.get("arg"), list) else []
                pairs = tuple((a["name"], _text(a.get("value")) or literal(""))
                              for a in args if isinstance(a, dict) and isinstance(a.get("name"), str))
                launch.actions.append(Include(_text(entry["file"]), pairs, own, at))
            elif kind == "group" and isinstance(entry.get("children"), list):
                _yaml_entries(entry["children"], own, launch, depth + 1)
            elif kind == "node" and _text(entry.get("pkg")) is not None:
                files, params = [], entry.get("param") if isinstance(entry.get("param"), list) else []
                for param in params:
                    if isinstance(param, dict) and _text(param.get("from")) is not None:
                        files.append(ParamFile(_text(param["from"]), True, own, _yaml_line(param)))
                    elif isinstance(param, dict) and isinstance(param.get("value"), str) \
                            and "xacro" in param["value"] and "$(command" in param["value"]:
                        launch.actions.append(Description(_text(param["value"]), None, (), own,
                                                          _yaml_line(param)))
                arguments = (_text(entry["args"]),) if _text(entry.get("args")) is not None else ()
                remaps = entry.get("remap") if isinstance(entry.get("remap"), list) else []
                remaps = tuple(Remap(_text(r["from"]), _text(r["to"]), _yaml_when(r), _yaml_line(r))
                               for r in remaps if isinstance(r, dict) and _text(r.get("from"))
                               is not None and _text(r.get("to")) is not None)
                launch.actions.append(Start(_text(entry["pkg"]), _text(entry.get("exec")) or literal(""),
                                            arguments, tuple(files), own, at, remaps))
            elif kind == "executable" and _text(entry.get("cmd")) is not None:
                launch.actions.append(Start(literal(""), _text(entry["cmd"]), (), (), own, at))


__all__ = ["Arg", "Condition", "Description", "Include", "LaunchFile", "ParamFile", "Remap",
           "Start", "Value", "concat", "is_launch_file", "is_launch_name", "literal", "named",
           "read_launch_text", "substituted", "unknown", "was_read"]
