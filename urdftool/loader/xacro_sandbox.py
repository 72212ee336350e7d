"""A safer evaluator for xacro's ``${...}`` expressions, installed over ``xacro.safe_eval``.

xacro's own ``safe_eval`` only rejects names starting with ``__`` in the outermost code object:
names inside a lambda or comprehension are not looked at, attributes such as ``gi_frame`` and
``f_back`` walk from a generator to xacro's own frames (and from there to ``os``), ``vars`` and
``type`` hand out class dictionaries, and ``"{0.__globals__}".format(f)`` reads attributes
without any name in the code at all. This module replaces it for the length of one expansion:

- the expression is parsed and every node checked: no names or attributes starting with ``_``,
  no attributes that reach frames, code or generators (``gi_frame``, ``f_back``, ``co_code`` ...);
- every attribute access, ``**``, ``*``, ``+`` and ``<<`` is rewritten into a call to a guard
  that re-checks the attribute at run time (``format``/``format_map`` of strings get a formatter
  that applies the same check to ``{0.attr}`` fields) and refuses results over a size limit;
- ``vars`` is gone, ``type`` only answers ``type(x)``, ``range`` is bounded.

Anything refused raises :class:`SandboxViolation`, which the loader reports as U016.
"""

from __future__ import annotations

import ast
import string

MAX_SEQUENCE = 1_000_000  # [items or characters] one expression may build
MAX_INT_BITS = 100_000  # [bits] of an integer one expression may build
MAX_RANGE = 1_000_000  # [items] of a range()

_FORBIDDEN_ATTRIBUTES = frozenset({
    "gi_frame", "gi_code", "gi_yieldfrom", "gi_running", "gi_suspended",
    "cr_frame", "cr_code", "cr_await", "cr_origin", "ag_frame", "ag_code", "ag_await",
    "f_back", "f_globals", "f_locals", "f_builtins", "f_code", "f_trace",
    "tb_frame", "tb_next", "func_globals", "func_code", "im_func", "im_self",
    "mro", "format_field", "get_field", "vformat",
})


class SandboxViolation(Exception):
    """An expression tried something the sandbox refuses; the message says what."""


def check_name(name: str, what: str = "attribute") -> None:
    """Raise SandboxViolation for names that lead out of the expression language."""
    if name.startswith("_") or name.startswith(("co_", "f_", "gi_", "cr_", "ag_", "tb_")) \
            or name in _FORBIDDEN_ATTRIBUTES:
        raise SandboxViolation(f"{what} '{name}' is not allowed in xacro expressions")


class _Validator(ast.NodeVisitor):
    def visit_Name(self, node):
        if node.id.startswith("_"):
            raise SandboxViolation(f"name '{node.id}' is not allowed in xacro expressions")

    def visit_Attribute(self, node):
        check_name(node.attr)
        self.generic_visit(node)

    def visit_keyword(self, node):
        if node.arg is not None and node.arg.startswith("_"):
            raise SandboxViolation(f"keyword '{node.arg}' is not allowed in xacro expressions")
        self.generic_visit(node)

    def visit_arg(self, node):
        if node.arg.startswith("_"):
            raise SandboxViolation(f"parameter '{node.arg}' is not allowed in xacro expressions")

    def visit_Constant(self, node):
        if isinstance(node.value, str) and ("{" in node.value):
            _check_format_fields(node.value)


_GUARD_NAMES = {"attr": "__urdftool_attr__", ast.Pow: "__urdftool_pow__",
                ast.Mult: "__urdftool_mul__", ast.Add: "__urdftool_add__",
                ast.LShift: "__urdftool_lshift__"}


class _Guard(ast.NodeTransformer):
    def visit_Attribute(self, node):
        self.generic_visit(node)
        return ast.copy_location(ast.Call(
            func=ast.Name(_GUARD_NAMES["attr"], ast.Load()),
            args=[node.value, ast.Constant(node.attr)], keywords=[]), node)

    def visit_BinOp(self, node):
        self.generic_visit(node)
        guard = _GUARD_NAMES.get(type(node.op))
        if guard is None:
            return node
        return ast.copy_location(ast.Call(func=ast.Name(guard, ast.Load()),
                                          args=[node.left, node.right], keywords=[]), node)


def _check_format_fields(text: str) -> None:
    """Refuse ``{0.__class__}``-style fields in a string that may be used as a format."""
    try:
        fields = list(string.Formatter().parse(text))
    except ValueError:
        return  # not a valid format string: str.format would refuse it too
    import _string

    for _, field_name, spec, _ in fields:
        if field_name:
            try:
                _, rest = _string.formatter_field_name_split(field_name)
                for is_attribute, key in rest:
                    if is_attribute:
                        check_name(key)
                    elif isinstance(key, str) and key.startswith("_"):
                        check_name(key, "key")
            except ValueError:
                pass
        if spec and "{" in spec:
            _check_format_fields(spec)


class _SafeFormatter(string.Formatter):
    def get_field(self, field_name, args, kwargs):
        _check_format_fields("{" + field_name + "}")
        return super().get_field(field_name, args, kwargs)


_FORMATTER = _SafeFormatter()


def _guard_attr(obj, name):
    check_name(name)
    value = getattr(obj, name)
    if name in ("format", "format_map") and (isinstance(obj, str) or obj is str):
        if obj is str:
            return (lambda text, *a, **k: _FORMATTER.vformat(text, a, k)) if name == "format" \
                else (lambda text, mapping: _FORMATTER.vformat(text, (), mapping))
        if name == "format":
            return lambda *a, **k: _FORMATTER.vformat(obj, a, k)
        return lambda mapping: _FORMATTER.vformat(obj, (), mapping)
    return value


def _size(value) -> int | None:
    if isinstance(value, (str, bytes, list, tuple)):
        return len(value)
    return None


def _refuse_large(value, what: str):
    size = _size(value)
    if size is not None and size > MAX_SEQUENCE:
        raise SandboxViolation(f"{what} would build {size} items (limit {MAX_SEQUENCE})")
    if isinstance(value, int) and value.bit_length() > MAX_INT_BITS:
        raise SandboxViolation(f"{what} would build an integer over {MAX_INT_BITS} bits")
    return value


def _guard_pow(base, exponent):
    if isinstance(base, int) and isinstance(exponent, int) and exponent > 0 and abs(base) > 1:
        if exponent * abs(base).bit_length() > MAX_INT_BITS:
            raise SandboxViolation(f"{base} ** {exponent} is too large "
                                   f"(integers are limited to {MAX_INT_BITS} bits)")
    return base ** exponent


def _guard_mul(left, right):
    for sequence, count in ((left, right), (right, left)):
        size = _size(sequence)
        if size is not None and isinstance(count, int) and size * count > MAX_SEQUENCE:
            raise SandboxViolation(f"repeating {size} items {count} times is over the limit of "
                                   f"{MAX_SEQUENCE}")
    if isinstance(left, int) and isinstance(right, int) \
            and left.bit_length() + right.bit_length() > MAX_INT_BITS:
        raise SandboxViolation(f"product is over {MAX_INT_BITS} bits")
    return left * right


def _guard_add(left, right):
    if _size(left) is not None and _size(right) is not None \
            and _size(left) + _size(right) > MAX_SEQUENCE:
        raise SandboxViolation(f"concatenation is over the limit of {MAX_SEQUENCE} items")
    return left + right


def _guard_lshift(left, right):
    if isinstance(left, int) and isinstance(right, int) \
            and right + left.bit_length() > MAX_INT_BITS:
        raise SandboxViolation(f"{left} << {right} is over {MAX_INT_BITS} bits")
    return left << right


_GUARDS = {
    _GUARD_NAMES["attr"]: _guard_attr,
    _GUARD_NAMES[ast.Pow]: _guard_pow,
    _GUARD_NAMES[ast.Mult]: _guard_mul,
    _GUARD_NAMES[ast.Add]: _guard_add,
    _GUARD_NAMES[ast.LShift]: _guard_lshift,
}


def compile_expression(expression: str):
    """Parse, check and guard ``expression``; the code object to evaluate."""
    tree = ast.parse(expression.strip(), "<expression>", "eval")
    _Validator().visit(tree)
    tree = ast.fix_missing_locations(_Guard().visit(tree))
    return compile(tree, "<expression>", "eval")


def safe_eval(expression, symbols, locals=None):
    """Drop-in replacement for ``xacro.safe_eval``."""
    code = compile_expression(expression)
    dict.__setitem__(symbols, "__builtins__", _GUARDS)
    return _refuse_large(eval(code, symbols, locals), "expression")


def refuse_yaml_bomb(text: str) -> None:
    """Refuse YAML whose aliases expand past MAX_SEQUENCE nodes ("billion laughs" in YAML:
    ``b: &b [*a, *a, ...]``); xacro would print it in full."""
    import yaml

    try:
        documents = list(yaml.compose_all(text, Loader=yaml.SafeLoader))
    except yaml.YAMLError:
        return  # xacro's own load reports it
    sizes: dict[int, int] = {}

    def size(node) -> int:
        known = sizes.get(id(node))
        if known is not None:
            return known
        sizes[id(node)] = 1  # a recursive alias counts once
        total = 1
        if isinstance(node, yaml.SequenceNode):
            total += sum(size(child) for child in node.value)
        elif isinstance(node, yaml.MappingNode):
            total += sum(size(key) + size(value) for key, value in node.value)
        sizes[id(node)] = total
        return total

    for document in documents:
        if document is not None and size(document) > MAX_SEQUENCE:
            raise SandboxViolation(f"YAML aliases expand to over {MAX_SEQUENCE} nodes "
                                   "(a YAML bomb?)")


def _bounded(make_range):
    """``make_range`` (xacro's range, perhaps wrapped in a deprecation warning), bounded."""

    def bounded_range(*args):
        result = make_range(*args)
        if len(result) > MAX_RANGE:
            raise SandboxViolation(f"range of {len(result)} items is over the limit of {MAX_RANGE}")
        return result

    return bounded_range


def _one_argument_type(value):
    return type(value)


def harden_symbols(symbols: dict) -> dict:
    """Replace the dangerous entries of xacro's global symbols in place; returns the originals."""
    saved = {}
    python = symbols.get("python")
    targets = [(symbols, "range", _bounded)]
    if python is not None:
        targets += [(python, "range", _bounded), (python, "type", lambda _: _one_argument_type),
                    (python, "vars", None)]
    for table, name, make in targets:
        if dict.__contains__(table, name):
            original = dict.__getitem__(table, name)
            saved[(id(table), name)] = (table, name, original)
            replacement = make(original) if make else None
            if replacement is None:
                dict.__delitem__(table, name)
            else:
                dict.__setitem__(table, name, replacement)
    return saved


def restore_symbols(saved: dict) -> None:
    for table, name, value in saved.values():
        dict.__setitem__(table, name, value)
