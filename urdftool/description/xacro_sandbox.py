"""A safer evaluator for xacro's ``${...}`` and ``$(eval ...)``, installed over xacro's own.

xacro's own ``safe_eval`` only rejects names starting with ``__`` in the outermost code object:
names inside a lambda or comprehension are not looked at, attributes such as ``gi_frame`` and
``f_back`` walk from a generator to xacro's own frames (and from there to ``os``), ``vars`` and
``type`` hand out class dictionaries, and ``"{0.__globals__}".format(f)`` reads attributes
without any name in the code at all. ``$(eval ...)`` is worse: a plain ``eval`` with every
Python built-in (``exec``, ``open``). This module replaces both for the length of one expansion:

- the expression is parsed and every node checked: no names or attributes starting with ``_``,
  no attributes that reach frames, code or generators (``gi_frame``, ``f_back``, ``co_code`` ...),
  no assignment to attributes or items;
- every attribute access is rewritten into a call to a guard that re-checks the attribute at run
  time (``format``/``format_map`` of strings get a formatter that applies the same check to
  ``{0.attr}`` fields);
- memory is bounded while the expression runs, not only at its end. Every value the expression
  makes (results of calls, operators, subscripts and attributes, list/tuple/set/dict displays,
  comprehension items, lambda results, f-string fields) is charged its *weight* to a budget of
  MAX_WORK per expression, and every comprehension step costs one. The weight of a value is about
  what printing it takes: characters of strings, items of containers, with every reference to a
  shared part counted again (``[s] * 1000`` weighs a thousand ``s``), measured only up to what is
  left of the budget. Operations whose output can be much larger than their input (``*``,
  ``**``, ``<<``, ``%``, ``str.format``, ``ljust``/``center``/``zfill``, ``expandtabs``,
  ``replace``, ``join``, ``translate``, ``int.to_bytes``, ``math.factorial``/``comb``/``perm``,
  ``sum``, ``round``) are checked before they run; calls to built-ins are charged the weight of
  their arguments (``str`` of a structure prints all of it), and built-ins handed to ``map``,
  ``sorted`` and the like are wrapped so their calls are charged too;
- ``vars`` is gone, ``type`` only answers ``type(x)``, ``range`` is bounded, and names of Python
  built-ins that run code or open files (``exec``, ``open``) are refused by name.

Anything refused raises :class:`SandboxViolation`, a load error of kind 'sandbox'.
"""

from __future__ import annotations

import ast
import functools
import math
import operator
import re
import string
import types

MAX_SEQUENCE = 1_000_000  # [items or characters] one value may hold
MAX_INT_BITS = 100_000  # [bits] of an integer one expression may build
MAX_RANGE = 1_000_000  # [items] of a range()
MAX_WORK = 2_000_000  # [items + characters + steps] one expression may build and walk in all
MAX_NESTING = 250  # [levels] of nested containers in one value

_FORBIDDEN_ATTRIBUTES = frozenset({
    "gi_frame", "gi_code", "gi_yieldfrom", "gi_running", "gi_suspended",
    "cr_frame", "cr_code", "cr_await", "cr_origin", "ag_frame", "ag_code", "ag_await",
    "f_back", "f_globals", "f_locals", "f_builtins", "f_code", "f_trace",
    "tb_frame", "tb_next", "func_globals", "func_code", "im_func", "im_self",
    "mro", "format_field", "get_field", "vformat",
})
# Names an expression might reach for to run code, import, or touch files; none is in xacro's
# symbol table, so using one is an attack (kind 'sandbox'), not a typo (kind 'xacro').
_DANGEROUS_NAMES = frozenset({
    "exec", "eval", "compile", "open", "getattr", "setattr", "delattr", "globals", "locals",
    "vars", "breakpoint", "memoryview", "super", "importlib", "os", "sys", "subprocess",
})


class SandboxViolation(Exception):
    """An expression tried something the sandbox refuses; the message says what."""


def check_name(name: str, what: str = "attribute") -> None:
    """Raise SandboxViolation for names that lead out of the expression language."""
    if name.startswith("_") or name.startswith(("co_", "f_", "gi_", "cr_", "ag_", "tb_")) \
            or name in _FORBIDDEN_ATTRIBUTES:
        raise SandboxViolation(f"{what} '{name}' is not allowed in xacro expressions")


def _private_name(name: str) -> bool:
    """A name (not an attribute) an expression may not use: a dunder like ``__import__`` or
    ``__builtins__``. One leading underscore is a plain xacro property (``_ixx`` in HEBI's
    end_effector.xacro, ``_tmp_`` in Shadow's hand): names reach only the symbol table, where
    nothing else starts with an underscore; attributes (``x._y``) stay refused."""
    return name.startswith("__")


class _Validator(ast.NodeVisitor):
    def visit_Name(self, node):
        if _private_name(node.id):
            raise SandboxViolation(f"name '{node.id}' is not allowed in xacro expressions")

    def visit_Attribute(self, node):
        check_name(node.attr)
        self._refuse_store(node, f"attribute '{node.attr}'")
        self.generic_visit(node)

    def visit_Subscript(self, node):
        self._refuse_store(node, "an item")
        self.generic_visit(node)

    @staticmethod
    def _refuse_store(node, what):
        if not isinstance(node.ctx, ast.Load):
            raise SandboxViolation(f"assigning to {what} is not allowed in xacro expressions")

    def visit_keyword(self, node):
        if node.arg is not None and _private_name(node.arg):
            raise SandboxViolation(f"keyword '{node.arg}' is not allowed in xacro expressions")
        self.generic_visit(node)

    def visit_arg(self, node):
        if _private_name(node.arg):
            raise SandboxViolation(f"parameter '{node.arg}' is not allowed in xacro expressions")

    def visit_Constant(self, node):
        if isinstance(node.value, str) and ("{" in node.value):
            _check_format_fields(node.value)


# --- the rewrite: every operation that makes a value goes through a guard ----------------------

def _guard_call_node(name: str, node, *args) -> ast.Call:
    return ast.copy_location(ast.Call(ast.Name(name, ast.Load()), list(args), []), node)


class _Guard(ast.NodeTransformer):
    def visit_Attribute(self, node):
        self.generic_visit(node)
        return _guard_call_node("__urdftool_attr__", node, node.value, ast.Constant(node.attr))

    def visit_BinOp(self, node):
        self.generic_visit(node)
        return _guard_call_node("__urdftool_binop__", node, node.left, node.right,
                                ast.Constant(type(node.op).__name__))

    def visit_Call(self, node):
        self.generic_visit(node)
        return ast.copy_location(ast.Call(ast.Name("__urdftool_call__", ast.Load()),
                                          [node.func, *node.args], node.keywords), node)

    def visit_Subscript(self, node):
        self.generic_visit(node)
        return _guard_call_node("__urdftool_item__", node, node.value, _slices(node.slice))

    def visit_Lambda(self, node):
        self.generic_visit(node)
        node.body = _charge(node.body, "a lambda's result")
        return _charge(node, "a lambda")

    def visit_UnaryOp(self, node):
        self.generic_visit(node)
        return _charge(node, "the result of an operator")

    def _display(self, node, what):
        self.generic_visit(node)
        if isinstance(getattr(node, "ctx", ast.Load()), ast.Load):
            return _charge(node, what)
        return node

    def visit_List(self, node):
        return self._display(node, "a list")

    def visit_Tuple(self, node):
        return self._display(node, "a tuple")

    def visit_Set(self, node):
        return self._display(node, "a set")

    def visit_Dict(self, node):
        return self._display(node, "a dict")

    def visit_comprehension(self, node):
        self.generic_visit(node)
        node.iter = _guard_call_node("__urdftool_iter__", node.iter, node.iter)
        return node

    def visit_ListComp(self, node):
        self.generic_visit(node)
        node.elt = _charge(node.elt, "a comprehension item")
        return node

    visit_SetComp = visit_ListComp

    def visit_GeneratorExp(self, node):
        return _charge(self.visit_ListComp(node), "a generator")

    def visit_DictComp(self, node):
        self.generic_visit(node)
        node.key = _charge(node.key, "a comprehension key")
        node.value = _charge(node.value, "a comprehension item")
        return node

    def visit_FormattedValue(self, node):
        self.generic_visit(node)
        spec = node.format_spec if node.format_spec is not None else ast.Constant("")
        value = _guard_call_node("__urdftool_format__", node, node.value,
                                 ast.Constant(node.conversion), spec)
        return ast.copy_location(ast.FormattedValue(value, -1, None), node)


def _charge(node, what: str):
    return _guard_call_node("__urdftool_charge__", node, node, ast.Constant(what))


def _slices(node):
    """A subscript's index as an ordinary expression (``a:b`` becomes ``slice(a, b)``)."""
    if isinstance(node, ast.Slice):
        parts = [part or ast.Constant(None) for part in (node.lower, node.upper, node.step)]
        return _guard_call_node("__urdftool_slice__", node, *parts)
    if isinstance(node, ast.Tuple) and any(isinstance(e, ast.Slice) for e in node.elts):
        return ast.copy_location(ast.Tuple([_slices(e) for e in node.elts], ast.Load()), node)
    return node


# --- format strings ------------------------------------------------------------------------------

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


_DIGITS = re.compile(r"\d+")


def _check_width(spec, what: str) -> None:
    """Refuse a format spec (``0200000000d``) or a width whose number is over MAX_SEQUENCE."""
    runs = [spec] if isinstance(spec, int) else _DIGITS.findall(spec)
    for run in runs:
        number = run if isinstance(run, int) else \
            (int(run.lstrip("0") or "0") if len(run.lstrip("0")) <= 9 else MAX_SEQUENCE + 1)
        if number > MAX_SEQUENCE:
            raise SandboxViolation(f"{what} {number} is over the limit of {MAX_SEQUENCE} "
                                   "characters")


# a key never closed runs to the end: Python refuses it there ("incomplete format key"), after
# the specifications before it, and from each '%(' to the end was quadratic in them
_PERCENT = re.compile(r"%(?:\([^)]*(?:\)|\Z))?[#0 +-]*(\*|\d+)?(?:\.(\*|\d+))?")


def _check_percent_format(text, values) -> None:
    """Refuse ``'%02000000000d' % 0`` and ``'%*d' % (10**9, 0)`` before they allocate."""
    if isinstance(text, bytes):
        text = text.decode("latin-1")
    starred = False
    for match in _PERCENT.finditer(text):
        for group in match.groups():
            if group == "*":
                starred = True
            elif group:
                _check_width(group, "'%' format width")
    if starred:
        for value in values if isinstance(values, tuple) else (values,):
            if isinstance(value, int):
                _check_width(abs(value), "'%*' format width")


class _SafeFormatter(string.Formatter):
    def get_field(self, field_name, args, kwargs):
        _check_format_fields("{" + field_name + "}")
        return super().get_field(field_name, args, kwargs)

    def format_field(self, value, format_spec):
        return _format_field(value, format_spec, "a formatted field")


def _format_field(value, spec: str, what: str) -> str:
    _check_width(spec, "format width")
    _charge_weight(value, what)
    return _charge_weight(format(value, spec), what)


_FORMATTER = _SafeFormatter()


def _guard_format(value, conversion, spec):
    """An f-string field: ``{value!conversion:spec}``."""
    if conversion != -1:
        _charge_weight(value, "an f-string field")
        value = {ord("s"): str, ord("r"): repr, ord("a"): ascii}[conversion](value)
    return _format_field(value, spec, "an f-string field")


# --- the budget and the weight of values ---------------------------------------------------------

class _Budget:
    __slots__ = ("left",)

    def __init__(self):
        self.left = MAX_WORK


_CONTAINERS = (list, tuple, dict, set, frozenset)
_OBJECT_WEIGHT = 32  # a function, generator or other object: about its size in pointers, and
#                      about the length of its repr
_budgets: list[_Budget] = []
_IDLE = _Budget()  # for guarded code run outside any expression (a lambda kept in a property)


def _budget() -> _Budget:
    return _budgets[-1] if _budgets else _IDLE


def weight(value, limit: int = MAX_WORK) -> int:
    """About how many characters printing ``value`` takes: characters of strings, two per item
    of a container, every reference to a shared part counted again. Stops counting past
    ``limit`` (the result is then over ``limit``); refuses values nested deeper than
    MAX_NESTING."""
    seen: dict[int, int] = {}
    return _weigh(value, limit, seen, 0)


def _weigh(value, limit, seen, depth) -> int:
    kind = type(value)
    if kind is str or kind is bytes:
        return len(value) or 1
    if kind is int:
        return 1 + value.bit_length() // 8
    if kind is float or kind is bool or value is None:
        return 1
    if isinstance(value, (str, bytes, bytearray)):
        return len(value) or 1
    if isinstance(value, int):
        return 1 + value.bit_length() // 8
    if not isinstance(value, _CONTAINERS):
        return 1 if isinstance(value, (float, complex)) else _OBJECT_WEIGHT
    known = seen.get(id(value))
    if known is not None:
        return known
    if depth > MAX_NESTING:
        raise SandboxViolation(f"a value is nested deeper than {MAX_NESTING} levels")
    seen[id(value)] = 1  # a container holding itself prints as [...]
    if isinstance(value, dict):
        items = [part for pair in dict.items(value) for part in pair]
    elif isinstance(value, list):
        items = list.__iter__(value)
    else:
        items = value
    total = 1
    for item in items:
        total += 1 + _weigh(item, limit, seen, depth + 1)
        if total > limit:
            return total  # not remembered: an unfinished count
    seen[id(value)] = total
    return total


def _charge_weight(value, what: str):
    """Charge ``value``'s weight to the running expression's budget; returns ``value``."""
    budget = _budget()
    budget.left -= weight(value, max(budget.left, 0))
    if budget.left < 0:
        raise SandboxViolation(f"{what} would take the expression over its limit of {MAX_WORK} "
                               "items and characters in all")
    return value


def _charge_steps(count: int, what: str) -> None:
    budget = _budget()
    budget.left -= count
    if budget.left < 0:
        raise SandboxViolation(f"{what} would take the expression over its limit of {MAX_WORK} "
                               "items, characters and steps in all")


def _refuse_large(value, what: str):
    if weight(value, MAX_SEQUENCE) > MAX_SEQUENCE:
        raise SandboxViolation(f"{what} would build over {MAX_SEQUENCE} items and characters")
    if isinstance(value, int) and value.bit_length() > MAX_INT_BITS:
        raise SandboxViolation(f"{what} would build an integer over {MAX_INT_BITS} bits")
    return value


# --- guards --------------------------------------------------------------------------------------

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
    return _charge_weight(value, f"attribute '{name}'")


def _guard_item(obj, key):
    return _charge_weight(obj[key], "an item")


def _size(value) -> int | None:
    if isinstance(value, (str, bytes, list, tuple)):
        return len(value)
    return None


def _check_pow(base, exponent):
    if isinstance(base, int) and isinstance(exponent, int) and exponent > 0 and abs(base) > 1:
        if exponent * abs(base).bit_length() > MAX_INT_BITS:
            raise SandboxViolation(f"{base} ** {exponent} is too large "
                                   f"(integers are limited to {MAX_INT_BITS} bits)")


def _check_mul(left, right):
    for sequence, count in ((left, right), (right, left)):
        size = _size(sequence)
        if size and isinstance(count, int) and count > 0:
            if size * count > MAX_SEQUENCE:
                raise SandboxViolation(f"repeating {size} items {count} times is over the limit "
                                       f"of {MAX_SEQUENCE}")
            if count > 1 and weight(sequence, MAX_WORK // count + 1) * count > _budget().left:
                raise SandboxViolation(f"repeating {size} items {count} times would take the "
                                       f"expression over its limit of {MAX_WORK} items and "
                                       "characters in all")
    if isinstance(left, int) and isinstance(right, int) \
            and left.bit_length() + right.bit_length() > MAX_INT_BITS:
        raise SandboxViolation(f"product is over {MAX_INT_BITS} bits")


def _check_add(left, right):
    if _size(left) is not None and _size(right) is not None \
            and _size(left) + _size(right) > MAX_SEQUENCE:
        raise SandboxViolation(f"concatenation is over the limit of {MAX_SEQUENCE} items")


def _check_lshift(left, right):
    if isinstance(left, int) and isinstance(right, int) \
            and right + left.bit_length() > MAX_INT_BITS:
        raise SandboxViolation(f"{left} << {right} is over {MAX_INT_BITS} bits")


def _check_mod(left, right):
    if isinstance(left, (str, bytes)):
        _check_percent_format(left, right)
        _charge_weight(right, "values formatted with '%'")


_BINARY = {
    "Add": (operator.add, _check_add), "Sub": (operator.sub, None),
    "Mult": (operator.mul, _check_mul), "MatMult": (operator.matmul, None),
    "Div": (operator.truediv, None), "FloorDiv": (operator.floordiv, None),
    "Mod": (operator.mod, _check_mod), "Pow": (operator.pow, _check_pow),
    "LShift": (operator.lshift, _check_lshift), "RShift": (operator.rshift, None),
    "BitOr": (operator.or_, None), "BitXor": (operator.xor, None),
    "BitAnd": (operator.and_, None),
}


def _guard_binop(left, right, name):
    compute, check = _BINARY[name]
    if check is not None:
        check(left, right)
    result = compute(left, right)
    if isinstance(result, int) and result.bit_length() > MAX_INT_BITS:
        raise SandboxViolation(f"an integer over {MAX_INT_BITS} bits")
    return _charge_weight(result, f"the result of '{_SYMBOLS[name]}'")


_SYMBOLS = {"Add": "+", "Sub": "-", "Mult": "*", "MatMult": "@", "Div": "/", "FloorDiv": "//",
            "Mod": "%", "Pow": "**", "LShift": "<<", "RShift": ">>", "BitOr": "|",
            "BitXor": "^", "BitAnd": "&"}


def _guard_iter(iterable):
    """A comprehension's iterable, each step charged."""
    for item in iterable:
        _charge_steps(1, "a comprehension")
        yield item


def _guard_charge(value, what):
    return _charge_weight(value, what)


# --- calls ---------------------------------------------------------------------------------------

def _is_expression_function(func) -> bool:
    """A lambda written in an expression: its body is guarded already."""
    return type(func) is types.FunctionType and func.__code__.co_filename == "<expression>"


def _method(func, args):
    """(self, name, other arguments) for a built-in method, bound or taken from its class;
    else (None, None, args)."""
    kind = type(func)
    if kind is types.BuiltinMethodType:
        owner = func.__self__
        if not isinstance(owner, (types.ModuleType, type)) and owner is not None:
            return owner, func.__name__, args
    elif kind is types.MethodDescriptorType and args:
        return args[0], func.__name__, args[1:]
    return None, None, args


def _argument(args, kwargs, index, name, default=None):
    if len(args) > index:
        return args[index]
    return kwargs.get(name, default)


def _check_text_method(text, name, args, kwargs):
    """Refuse str/bytes methods whose result would be over MAX_SEQUENCE, before they run."""
    length = len(text)
    if name in ("ljust", "rjust", "center", "zfill"):
        width = _argument(args, kwargs, 0, "width", 0)
        if isinstance(width, int):
            _check_width(width, f"{name}() width")
    elif name == "expandtabs":
        tabsize = _argument(args, kwargs, 0, "tabsize", 8)
        if isinstance(tabsize, int) and tabsize > 0:
            _check_width(length + text.count("\t" if isinstance(text, str) else b"\t") * tabsize,
                         "expandtabs() result of")
    elif name == "replace" and len(args) >= 2:
        old, new = args[0], args[1]
        if isinstance(old, (str, bytes)) and isinstance(new, (str, bytes)):
            count = length + 1 if not old else text.count(old)
            limit = args[2] if len(args) > 2 and isinstance(args[2], int) and args[2] >= 0 \
                else count
            _check_width(length + min(count, limit) * max(len(new) - len(old), 0),
                         "replace() result of")
    elif name == "translate" and args:
        table = args[0]
        values = dict.values(table) if isinstance(table, dict) else \
            table if isinstance(table, (list, tuple, str, bytes)) else None
        if values is None:
            raise SandboxViolation("translate() takes a dict, list or string table here")
        longest = max((len(v) for v in values if isinstance(v, (str, bytes))), default=1)
        _check_width(length * max(longest, 1), "translate() result of")
    elif name == "join" and args:
        parts = list(args[0])
        pieces = sum(len(p) for p in parts if isinstance(p, (str, bytes)))
        _check_width(pieces + length * max(len(parts) - 1, 0), "join() result of")
        return (parts,)
    return None


def _check_int_method(number, name, args, kwargs):
    if name == "to_bytes":
        length = _argument(args, kwargs, 0, "length", 1)
        if isinstance(length, int):
            _check_width(length, "to_bytes() length")


def _bits(value) -> int:
    return abs(value).bit_length() if isinstance(value, int) else 0


def _check_factorial(n, *rest):
    if isinstance(n, int) and n > 1 and n * n.bit_length() > MAX_INT_BITS:
        raise SandboxViolation(f"factorial({n}) is over {MAX_INT_BITS} bits")


def _check_choose(n, k=None):
    """comb(n, k) and perm(n, k) have at most k * log2(n) bits."""
    if isinstance(n, int) and n > 1:
        k = n if k is None else k
        if isinstance(k, int) and min(k, n) * n.bit_length() > MAX_INT_BITS:
            raise SandboxViolation(f"comb/perm of {n} and {k} may be over {MAX_INT_BITS} bits")


def _check_lcm(*numbers):
    if sum(_bits(n) for n in numbers) > MAX_INT_BITS:
        raise SandboxViolation(f"lcm() of these numbers may be over {MAX_INT_BITS} bits")


def _check_round(number, ndigits=None):
    if isinstance(number, int) and isinstance(ndigits, int) and -ndigits > MAX_INT_BITS // 3:
        raise SandboxViolation(f"round() to {ndigits} digits builds a number over "
                               f"{MAX_INT_BITS} bits")


def _check_type(*args, **kwargs):
    """``type`` itself is reachable as ``python.type(python.type(1))``: no new classes."""
    if len(args) != 1 or kwargs:
        raise SandboxViolation("type() with more than one argument (a new class) is not allowed "
                               "in xacro expressions")


def _check_range(*args):
    """``range`` itself is reachable as ``python.type(python.range(1))``."""
    size = len(range(*args))
    if size > MAX_RANGE:
        raise SandboxViolation(f"range of {size} items is over the limit of {MAX_RANGE}")


def _check_bytes(source=None, *rest):
    """``bytes(10**9)`` (``python.type(b'')``) allocates that many zeros."""
    if isinstance(source, int):
        _check_width(source, "bytes() length")


def _guarded_sum(iterable, /, start=0):
    """``sum`` with each addition guarded (``sum(lists, [])`` is quadratic)."""
    return functools.reduce(lambda a, b: _guard_binop(a, b, "Add"), iterable, start)


def _guarded_prod(iterable, /, *, start=1):
    """``math.prod`` with each product guarded (ints and repeated sequences)."""
    return functools.reduce(lambda a, b: _guard_binop(a, b, "Mult"), iterable, start)


_CHECKS = {math.factorial: _check_factorial, math.comb: _check_choose, math.perm: _check_choose,
           math.lcm: _check_lcm, round: _check_round, type: _check_type, range: _check_range,
           bytes: _check_bytes, bytearray: _check_bytes}
_REPLACED = {sum: _guarded_sum, math.prod: _guarded_prod}
_MUTABLE = (list, dict, set, bytearray)
_NAMED = (types.BuiltinFunctionType, types.FunctionType, types.MethodDescriptorType, type)


def _guard_call(func, /, *args, **kwargs):
    if _is_expression_function(func):
        return func(*args, **kwargs)
    if _hashable(func):
        func = _REPLACED.get(func, func)
        check = _CHECKS.get(func)
        if check is not None:
            check(*args, **kwargs)
    owner, name, rest = _method(func, args)
    if isinstance(owner, (str, bytes)):
        replaced_args = _check_text_method(owner, name, rest, kwargs)
        if replaced_args is not None:
            args = (*args[:len(args) - len(rest)], *replaced_args)
    elif type(owner) is int:
        _check_int_method(owner, name, rest, kwargs)
    shown = func.__name__ if isinstance(func, _NAMED) else type(func).__name__
    _charge_weight((args, kwargs), f"the arguments of {shown}()")
    if owner is not None and not isinstance(owner, _MUTABLE):
        _charge_weight(owner, f"{shown}()")
    if func not in _NOT_WRAPPED:
        args = tuple(_wrapped(a) for a in args)
        kwargs = {k: _wrapped(v) for k, v in kwargs.items()}
    before = len(owner) if isinstance(owner, _MUTABLE) else None
    result = func(*args, **kwargs)
    if before is not None:
        _charge_steps(max(len(owner) - before, 0), f"{shown}()")
    return _charge_weight(result, f"the result of {shown}()")


def _hashable(value) -> bool:
    try:
        hash(value)
    except TypeError:
        return False
    return True


def _wrapped(value):
    """A built-in (or xacro) function passed to another one, with its calls guarded."""
    if callable(value) and not _is_expression_function(value) \
            and not isinstance(value, (dict, list)):
        return lambda *a, **k: _guard_call(value, *a, **k)
    return value


_GUARDS = {
    "__urdftool_attr__": _guard_attr,
    "__urdftool_binop__": _guard_binop,
    "__urdftool_call__": _guard_call,
    "__urdftool_item__": _guard_item,
    "__urdftool_iter__": _guard_iter,
    "__urdftool_charge__": _guard_charge,
    "__urdftool_format__": _guard_format,
    "__urdftool_slice__": slice,
}


@functools.lru_cache(maxsize=4096)
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
    _budgets.append(_Budget())
    try:
        result = eval(code, symbols, locals)
    except NameError as error:
        if getattr(error, "name", None) in _DANGEROUS_NAMES:
            raise SandboxViolation(f"'{error.name}' is a Python built-in that xacro expressions "
                                   "may not use (no code execution, no files)") from None
        raise
    finally:
        _budgets.pop()
    return _refuse_large(result, "expression")


def eval_substitution(expression: str, functions: dict, args: dict):
    """``$(eval expression)``: the sandbox with xacro's substitution functions (``arg``,
    ``env``, ``find`` ... in ``functions``) and the xacro arguments readable by name."""
    if "__" in expression:  # xacro refuses these too
        raise SandboxViolation("$(eval ...) may not contain double underscore expressions")
    from xacro.substitution_args import convert_value

    return str(safe_eval(expression, functions, _ArgumentNames(args, functions, convert_value)))


class _ArgumentNames:
    """The local names of ``$(eval)``: its functions first, then the xacro arguments (as xacro's
    ``_DictWrapper``), never a name starting with ``_`` (those are the guards)."""

    def __init__(self, args, functions, convert):
        self._args, self._functions, self._convert = args, functions, convert

    def __getitem__(self, key):
        if key.startswith("_"):
            raise KeyError(key)
        if key in self._functions:
            return self._functions[key]
        return self._convert(self._args[key], "auto")


def refuse_yaml_bomb(text: str, filename: str = "YAML file") -> None:
    """Refuse YAML past yaml_limits' limits: nested too deeply, or whose aliases expand past
    MAX_EXPANSION nodes and characters ("billion laughs" in YAML: ``b: &b [*a, *a, ...]``) or
    nest past MAX_DEPTH; xacro would print it in full, and PyYAML would recurse until the
    stack runs out."""
    import yaml

    from urdftool.description.yaml_limits import BoundedLoader, LimitError, line_of

    try:
        for _ in yaml.compose_all(text, Loader=BoundedLoader):
            pass
    except LimitError as error:
        raise SandboxViolation(f"{filename}:{line_of(error.problem_mark, text)}: {error.problem}") \
            from None
    except yaml.YAMLError:
        return  # xacro's own load reports it


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


_NOT_WRAPPED = (isinstance, issubclass, type, _one_argument_type)  # they take classes as such


def _literal_tokenize(tokenize):
    """xacro.tokenize with ``sep`` taken as characters, not as part of a regular expression
    (``sep='a](a*)*['`` would make a catastrophically backtracking one)."""

    def literal_tokenize(s, sep=",; ", skip_empty=True):
        results = re.split("[" + re.escape(sep) + "]", s)
        return [item for item in results if item] if skip_empty else results

    return literal_tokenize


def harden_symbols(symbols: dict) -> list:
    """Replace the dangerous entries of xacro's global symbols in place; returns what
    :func:`restore_symbols` needs to put back every table as it was (an expression may also
    change the shared namespaces, ``python.update(...)``, which must not reach the next file)."""
    python = symbols.get("python")
    namespace = symbols.get("xacro")
    tables = [symbols, *(t for t in (python, symbols.get("math"), namespace) if t is not None)]
    saved = [(table, dict(table)) for table in tables]
    targets = [(symbols, "range", _bounded)]
    if python is not None:
        targets += [(python, "range", _bounded), (python, "type", lambda _: _one_argument_type),
                    (python, "vars", None)]
    if namespace is not None:
        targets.append((namespace, "tokenize", _literal_tokenize))
    for table, name, make in targets:
        if dict.__contains__(table, name):
            replacement = make(dict.__getitem__(table, name)) if make else None
            if replacement is None:
                dict.__delitem__(table, name)
            else:
                dict.__setitem__(table, name, replacement)
    return saved


def restore_symbols(saved: list) -> None:
    for table, content in saved:
        dict.clear(table)
        dict.update(table, content)
