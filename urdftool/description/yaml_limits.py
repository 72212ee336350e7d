"""Limits on YAML written by a stranger: how deep it nests and how far its aliases expand.

PyYAML composes and constructs nested collections recursively, so a document nested 50,000 levels
deep ends in a RecursionError that carries no line. An alias repeats its anchor without copying
it, so ten lines can stand for a billion items (or a long string repeated thousands of times)
once the data is printed or walked, and a chain of aliases (``c1: &c1 [*c0]``, ``c2: &c2
[*c1]``...) builds data a thousand levels deep from text two levels deep, which every walker of
the data recurses into. :class:`DepthLimit` stops composing at the line where the text's
nesting passes MAX_DEPTH, and refuses a composed document whose aliases make it deeper than
MAX_DEPTH or larger than MAX_EXPANSION beyond its text (:func:`expansion_problem`), each as a
YAML error (:class:`LimitError`) at its line: every loader built on it reads within them.

It is also the one guard of constructing values: PyYAML's constructors raise Python's own
errors for values YAML's grammar lets through (``2001-02-30`` is a timestamp to YAML 1.1 and
no date; ``!!float junk``, ``!!bool maybe``, ``!!timestamp x``; a decimal integer past the
digits Python converts), which no reader catches: every such error is a ConstructorError at the
value's line (:func:`unconstructable`). A loader reading as ROS 2's parameter parser does
(``lenient``: rcl_yaml_param_parser types a plain scalar itself, as a boolean, an integer, a
double or else a string, reads no dates and ignores every tag but ``!!str``) reads such a
value as its text instead and notes why in ``unconstructed``: what PyYAML cannot construct is
then a warning of the readers that use PyYAML, not an error of the file.
"""

from __future__ import annotations

import re

import yaml

from urdftool.diagnostics import LineNumbers, line_at
from urdftool.numbers import NumberRefused, double_problem, long_integer, too_long

MAX_DEPTH = 200  # [levels] of nested collections; real configuration files use about ten
MAX_EXPANSION = 1_000_000  # [nodes + characters] aliases may add to what the text holds


# PyYAML and libyaml (YAML 1.1) end a line at NEL, LINE SEPARATOR and PARAGRAPH SEPARATOR too,
# which no Location, editor or language server protocol does: a mark's line after one is not
# the line of the file (CR LF, LF and CR they count as every Location does)
_OTHER_BREAKS = re.compile("[\x85\u2028\u2029]")


def _other_breaks(text: str) -> bool:
    """Whether ``text`` holds one of those line ends (none in ASCII text: known at no cost)."""
    return not text.isascii() and _OTHER_BREAKS.search(text) is not None


def line_of(mark, text: str) -> int:
    """The 1-based line of a YAML ``mark`` (an error's, a node's) in ``text``, the text the
    loader read, as every Location numbers lines (:func:`urdftool.diagnostics.line_at`)."""
    return line_at(text, mark.index) if _other_breaks(text) else mark.line + 1


class DepthLimit:
    """Mixin for a yaml Loader: collections nested deeper than MAX_DEPTH are a ComposerError;
    a value PyYAML cannot construct (an integer longer than Python converts, a date that is
    none, ``!!float junk``) a ConstructorError at its line, not the Python error its
    constructor raised (a traceback wherever YAML errors are caught); with ``lenient``, read as
    ROS 2's parameter parser reads it (:meth:`construct_object`)."""

    _depth = 0
    _numbers = None  # the LineNumbers of the text read, when PyYAML's lines are not its lines
    # a ROS 2 parameter file: a value PyYAML cannot construct is read as its text, (line, why)
    # in ``unconstructed``
    lenient = False
    unconstructed: list | tuple = ()
    aliased: int | None = None  # lenient: the line of the first alias (ROS 2 refuses every one)
    any_integer = False  # a launch file's: an integer past a double is text to its readers

    def file_line(self, mark) -> int:
        """The 1-based line of ``mark`` in the text this loader reads (:func:`line_of`)."""
        numbers = self._numbers
        if numbers is None:
            text = getattr(self, "buffer", "")  # a loader of a string holds it whole
            numbers = self._numbers = LineNumbers(text) if _other_breaks(text) else False
        return numbers(mark.index) if numbers else mark.line + 1

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if hasattr(cls, "add_constructor"):  # a loader: its own table (PyYAML copies it)
            cls.add_constructor("tag:yaml.org,2002:int", _bounded_int)

    def construct_object(self, node, deep=False):
        """PyYAML's, with what its constructors raise of Python's own (ValueError, KeyError,
        AttributeError...) a ConstructorError at ``node`` (:func:`unconstructable`). With
        ``lenient``, a scalar PyYAML cannot construct is its text, and a collection whose tag
        it cannot construct the plain list or mapping, as ROS 2's parser reads them (it never
        constructs a tag but ``!!str``); each noted in ``unconstructed``."""
        deep_before = self.deep_construct
        try:
            return super().construct_object(node, deep)
        except (ValueError, TypeError, KeyError, AttributeError, IndexError, OverflowError) as error:
            problem = unconstructable(node, error)
        except yaml.constructor.ConstructorError as error:
            if not self.lenient or getattr(error, "kept", False):
                raise
            problem = error
        if not self.lenient or not (isinstance(node, yaml.ScalarNode) or node.tag not in _PLAIN):
            raise problem from None
        self.recursive_objects.pop(node, None)  # (PyYAML's bookkeeping of the node it left)
        self.deep_construct = deep_before
        if isinstance(self.unconstructed, tuple):
            self.unconstructed = []
        self.unconstructed.append((self.file_line(node.start_mark), _said(problem)))
        if isinstance(node, yaml.ScalarNode):
            self.constructed_objects[node] = node.value
            return node.value
        node.tag = _PLAIN[type(node)]  # (an alias of it is the same node: read the same way)
        try:
            return self.construct_object(node, deep)
        except yaml.constructor.ConstructorError as error:
            error.kept = True  # (what fails as a plain collection is the file's error)
            raise

    def compose_document(self):
        node = super().compose_document()
        text = getattr(self, "buffer", "")  # a loader of a string holds it whole
        problem = expansion_problem(node, len(text))
        if problem:
            raise LimitError(None, None, *problem)
        return node

    def compose_node(self, parent, index):
        if self.lenient and self.aliased is None and self.check_event(yaml.events.AliasEvent):
            self.aliased = self.file_line(self.peek_event().start_mark)
        if self._depth >= MAX_DEPTH:
            mark = self.peek_event().start_mark
            raise LimitError(
                None, None, f"collections nested deeper than {MAX_DEPTH} levels (configuration files need a "
                "few)", mark)
        self._depth += 1
        try:
            return super().compose_node(parent, index)
        finally:
            self._depth -= 1


_PLAIN = {yaml.SequenceNode: "tag:yaml.org,2002:seq", yaml.MappingNode: "tag:yaml.org,2002:map"}
_KINDS = {"int": "an integer", "float": "a float", "bool": "a boolean", "timestamp": "a date",
          "binary": "binary (base64)", "null": "null", "str": "a string", "seq": "a list",
          "map": "a mapping", "set": "a set", "omap": "an ordered mapping", "pairs": "pairs"}


_COLLECTIONS = {"sequence": "a sequence", "mapping": "a mapping"}


def unconstructable(node, error: Exception):
    """The ConstructorError, at ``node``, of a value PyYAML's constructor of its tag raised
    ``error`` for (a Python error, not a YAML one): what was written, what YAML 1.1 makes of it
    (its tag) and why it cannot be that."""
    if isinstance(error, NumberRefused):  # (its words say what it is and why)
        return yaml.constructor.ConstructorError(None, None, str(error), node.start_mark)
    from urdftool.errors import shown_word

    tag = node.tag
    what = _KINDS.get(tag.rsplit(":", 1)[-1], tag) if tag.startswith("tag:yaml.org,2002:") else tag
    written = f"'{shown_word(node.value)}'" if isinstance(node, yaml.ScalarNode) else \
        _COLLECTIONS.get(node.id, node.id)
    why = str(error) if isinstance(error, (ValueError, OverflowError)) and str(error) else \
        f"no {what.split(' ', 1)[-1]} YAML 1.1 knows"
    return yaml.constructor.ConstructorError(
        None, None, f"{written} cannot be constructed as {what} ({tag}): {why}", node.start_mark)


def _said(error) -> str:
    """A YAML error's words (its problem, and its context when it has one)."""
    problem = getattr(error, "problem", None) or str(error)
    context = getattr(error, "context", None)
    return f"{problem} ({context})" if context else problem


def _bounded_int(loader, node) -> int:
    """PyYAML's integer, refusing a decimal longer than Python converts (its conversion is
    quadratic; in bases 2, 8 and 16 any length is linear), and, unless the loader's
    ``any_integer``, one past what a double holds (no parameter holds it, nothing computes
    with it: ``float()`` of it raised OverflowError in every rule reading numbers): each a
    :class:`~urdftool.numbers.NumberRefused` the guard makes a YAML error at its line."""
    value = loader.construct_scalar(node)
    bare = value.replace("_", "").lstrip("+-")
    if not bare.startswith("0") and long_integer(bare) is not None:  # (0x, 0b, 0...: bases
        raise too_long(len(value))  # 16, 2 and 8)
    number = yaml.constructor.SafeConstructor.construct_yaml_int(loader, node)
    problem = None if loader.any_integer else double_problem(number)
    if problem is not None:
        raise problem
    return number


class BoundedLoader(DepthLimit, yaml.SafeLoader):
    """yaml.SafeLoader with the depth limit."""


class OnceLoader(BoundedLoader):
    """:class:`BoundedLoader` refusing a key written twice in one mapping (a located YAML
    error), for files of numbers a command computes from, where either value would be a
    guess (PyYAML keeps the last). Keys a merge (``<<``) brings may be overridden, as YAML
    means."""

    def construct_mapping(self, node, deep=False):
        if isinstance(node, yaml.MappingNode):
            seen = set()
            for key_node, _ in node.value:
                if key_node.tag == "tag:yaml.org,2002:merge":
                    continue
                key = self.construct_object(key_node, deep=True)
                try:
                    twice = key in seen
                    seen.add(key)
                except TypeError:  # an unhashable key: PyYAML's own error says so
                    continue
                if twice:
                    raise yaml.constructor.ConstructorError(
                        "while constructing a mapping", node.start_mark,
                        f"the key '{key}' is written twice", key_node.start_mark)
        return super().construct_mapping(node, deep)


def expansion_problem(node, text_length: int) -> tuple[str, object] | None:
    """(message, mark) when ``node`` (a composed document) expands, with its aliases, to
    more than MAX_EXPANSION nodes and characters beyond ``text_length``, or nests deeper than
    MAX_DEPTH through them; else None. The mark is the innermost collection's over a limit by
    itself. Walked without recursion, each node once (a node its own descendant counts once)."""
    if node is None:
        return None
    limit = MAX_EXPANSION + text_length
    sizes: dict[int, tuple[int, int]] = {}  # id -> (size, depth); (1, 0) while being walked
    stack = [(node, False)]
    while stack:
        current, done = stack.pop()
        if isinstance(current, yaml.ScalarNode):
            sizes[id(current)] = (1 + len(current.value), 0)
            continue
        children = current.value if isinstance(current, yaml.SequenceNode) else \
            [part for pair in current.value for part in pair]
        if not done:
            if id(current) in sizes:
                continue
            sizes[id(current)] = (1, 0)
            stack.append((current, True))
            stack.extend((child, False) for child in children if id(child) not in sizes)
            continue
        size, depth = 1, 0
        for child in children:
            child_size, child_depth = sizes[id(child)]
            size += child_size
            depth = max(depth, child_depth)
        if size > limit:
            return (f"YAML aliases expand to over {limit} nodes and characters (a YAML bomb?)",
                    current.start_mark)
        if depth + 1 > MAX_DEPTH:
            return f"YAML aliases nest collections deeper than {MAX_DEPTH} levels", current.start_mark
        sizes[id(current)] = (size, depth + 1)
    return None


class LimitError(yaml.composer.ComposerError):
    """A document past one of the limits: too deep, or its aliases too large or too deep."""
