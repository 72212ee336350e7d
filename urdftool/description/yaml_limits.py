"""Limits on YAML written by a stranger: how deep it nests and how far its aliases expand.

PyYAML composes and constructs nested collections recursively, so a document nested 50,000 levels
deep ends in a RecursionError that carries no line. An alias repeats its anchor without copying
it, so ten lines can stand for a billion items (or a long string repeated thousands of times)
once the data is printed or walked. :class:`DepthLimit` stops composing at the line where the
nesting passes MAX_DEPTH, as a YAML error with that line; :func:`expansion_problem` measures what
the aliases expand to.
"""

from __future__ import annotations

import yaml

MAX_DEPTH = 200  # [levels] of nested collections; real configuration files use about ten
MAX_EXPANSION = 1_000_000  # [nodes + characters] aliases may add to what the text holds


class DepthLimit:
    """Mixin for a yaml Loader: collections nested deeper than MAX_DEPTH are a ComposerError;
    an integer longer than Python converts (4,300 digits) a ConstructorError at its line, not
    the ValueError ``int()`` raises (a traceback wherever YAML errors are caught)."""

    _depth = 0

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if hasattr(cls, "add_constructor"):  # a loader: its own table (PyYAML copies it)
            cls.add_constructor("tag:yaml.org,2002:int", _bounded_int)

    def compose_node(self, parent, index):
        if self._depth >= MAX_DEPTH:
            mark = self.peek_event().start_mark
            raise yaml.composer.ComposerError(
                None, None, f"collections nested deeper than {MAX_DEPTH} levels (configuration files need a "
                "few)", mark)
        self._depth += 1
        try:
            return super().compose_node(parent, index)
        finally:
            self._depth -= 1


def _bounded_int(loader, node) -> int:
    try:
        return yaml.constructor.SafeConstructor.construct_yaml_int(loader, node)
    except ValueError:  # past sys.get_int_max_str_digits(): its conversion is quadratic
        raise yaml.constructor.ConstructorError(
            None, None, f"an integer of {len(node.value):,} characters, longer than any number "
            "a configuration holds", node.start_mark) from None


class BoundedLoader(DepthLimit, yaml.SafeLoader):
    """yaml.SafeLoader with the depth limit."""


def expansion_problem(node, text_length: int) -> tuple[int, str] | None:
    """(line, message) when ``node`` (a composed document) expands, with its aliases, to more
    than MAX_EXPANSION nodes and characters beyond ``text_length``; else None. The line is the
    innermost collection that is over the limit by itself."""
    limit = MAX_EXPANSION + text_length
    sizes: dict[int, int] = {}

    def size(node) -> int:
        known = sizes.get(id(node))
        if known is not None:
            return known
        sizes[id(node)] = 1  # a recursive alias counts once
        total = 1
        if isinstance(node, yaml.ScalarNode):
            total += len(node.value)
        else:
            children = node.value if isinstance(node, yaml.SequenceNode) else \
                [part for pair in node.value for part in pair]
            for child in children:
                total += size(child)
                if total > limit:
                    raise _TooLarge(node)
        sizes[id(node)] = total
        return total

    try:
        size(node)
    except _TooLarge as found:
        return (found.node.start_mark.line + 1,
                f"YAML aliases expand to over {limit} nodes and characters (a YAML bomb?)")
    return None


class _TooLarge(Exception):
    def __init__(self, node):
        super().__init__()
        self.node = node
