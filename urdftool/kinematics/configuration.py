"""Joint configurations: which values a robot takes, parsed from words, files or drawn at random.

A *variable* is one number the user sets: the angle [rad] of a revolute or continuous joint, the
travel [m] of a prismatic joint, or one coordinate of a floating (``NAME.x``, ``.y``, ``.z``,
``.roll``, ``.pitch``, ``.yaw``) or planar (``NAME.x``, ``.y``, ``.yaw``) joint. Mimic joints are
not variables: they follow the joint they mimic.
"""

from __future__ import annotations

import csv
import io
import json
import math
import re
from dataclasses import dataclass
from typing import Collection

import numpy as np

from urdftool.diagnostics import lines_of
from urdftool.errors import ConfigError, MimicError, available, listed, shown_word
from urdftool.description.urdf import ANGULAR, VARIABLE
from urdftool.description.values import number, parse_numbers

FLOATING_COORDINATES = ("x", "y", "z", "roll", "pitch", "yaw")
PLANAR_COORDINATES = ("x", "y", "yaw")
_ANGULAR = {*ANGULAR, "roll", "pitch", "yaw"}
_RANDOM_SPAN = {"x": 1.0, "y": 1.0, "z": 1.0}  # [m] drawn for unbounded floating positions


@dataclass(frozen=True)
class Variable:
    """One settable coordinate: ``kind`` is revolute, continuous, prismatic, or a floating or
    planar coordinate name (x, y, z, roll, pitch, yaw); limits in [rad] or [m], inf when none."""

    name: str
    joint: str
    kind: str
    lower: float
    upper: float

    @property
    def angular(self) -> bool:
        return self.kind in _ANGULAR

    @property
    def default(self) -> float:
        """0, or mid-range when 0 is outside the limits (as MoveIt does)."""
        if self.lower <= 0.0 <= self.upper:
            return 0.0
        return 0.5 * (self.lower + self.upper)


@dataclass
class Configurations:
    """Values ``[rows, variables]`` for ``variables``; warnings about values outside limits."""

    variables: list[Variable]
    values: np.ndarray
    warnings: list[str]


def variables_of(robot, floating_root: str | None = None) -> list[Variable]:
    """The robot's variables in document order; ``floating_root`` adds a free root joint first."""
    result = []
    if floating_root:
        result += _coordinates(floating_root, FLOATING_COORDINATES)
    for name, joint in robot.joints.items():
        kind = joint.get("type")
        if joint.find("mimic") is not None or kind not in VARIABLE:
            continue
        if kind == "floating":
            result += _coordinates(name, FLOATING_COORDINATES)
        elif kind == "planar":
            result += _coordinates(name, PLANAR_COORDINATES)
        else:
            lower, upper = -math.inf, math.inf
            limit = joint.find("limit")
            if kind != "continuous" and limit is not None:
                lower = _number(limit.get("lower"), 0.0)
                upper = _number(limit.get("upper"), 0.0)
            result.append(Variable(name, name, kind, lower, upper))
    return result


def mimics_of(robot) -> dict[str, str]:
    """Mimic joint -> the joint it follows (not variables: setting one is an error)."""
    return {name: joint.find("mimic").get("joint") for name, joint in robot.joints.items()
            if joint.find("mimic") is not None}


def mimic_source(robot, name: str, variable_names: Collection[str], seen=(),
                 known: dict | None = None):
    """(variable, multiplier, offset): joint ``name``'s value as ``multiplier * variable +
    offset``, following chains of mimic joints; ConfigError (with ``element``) when a joint has
    no value: a mimic cycle, or a mimic of a joint that does not exist. ``known``: the sources
    found so far, shared by a caller that asks for every joint (filled in here). Walked in a
    loop, each joint's source kept: a chain of 3,000 mimic joints raised RecursionError in every
    command that poses the robot, and asking for each joint walked the chain again (cubic with
    the tuple of joints seen: check, fk, ik, dynamics stopped at the time budget)."""
    known = {} if known is None else known
    steps, visited = [], set(seen)  # (joint, multiplier, offset) from ``name`` on
    while name not in variable_names and name not in known:
        element = robot.joints.get(name)
        mimic = element.find("mimic") if element is not None else None
        if mimic is None or name in visited:
            raise MimicError(f"joint '{name}' has no value (a mimic cycle?)", element)
        visited.add(name)
        master = mimic.get("joint")
        if master not in robot.joints:
            raise MimicError(f"joint '{name}' mimics unknown joint '{master}'; "
                             + available("joints", master or "", robot.joints), mimic)
        steps.append((name, _attribute(mimic, "multiplier", 1.0),
                      _attribute(mimic, "offset", 0.0)))
        name = master
    variable, multiplier, offset = known.get(name) or (name, 1.0, 0.0)
    for joint, step_multiplier, step_offset in reversed(steps):  # the recursion's products
        multiplier, offset = step_multiplier * multiplier, step_multiplier * offset + step_offset
        known[joint] = variable, multiplier, offset
    return variable, multiplier, offset


def _coordinates(joint: str, names) -> list[Variable]:
    return [Variable(f"{joint}.{c}", joint, c, -math.inf, math.inf) for c in names]


def _attribute(element, name: str, default: float) -> float:
    value = number(element, name, default)
    return default if value is None else value


def _number(text, default: float) -> float:
    values, _ = parse_numbers(text, 1)
    return default if values is None or not math.isfinite(values[0]) else values[0]


def defaults(variables: list[Variable]) -> np.ndarray:
    return np.array([v.default for v in variables], dtype=float)


def assignments(variables: list[Variable], values: dict[str, str], degrees: bool = False,
                mimics: dict[str, str] | None = None) -> dict[str, float]:
    """``{variable: value}`` from ``{name: text}`` (e.g. parsed ``NAME=VALUE`` words).

    Values are in [rad] or [m] (or per second, per second squared); with ``degrees`` angular
    variables are given in degrees. A continuous joint takes one value like any other.
    """
    index = {v.name: i for i, v in enumerate(variables)}
    result = {}
    for name, text in values.items():
        column = _column(index, name, mimics)
        value = _to_float(text, f"value '{text}' for joint '{name}' is not a number")
        result[name] = _scaled(value, variables[column], degrees)
    return result


def from_words(variables: list[Variable], values: dict[str, str], degrees: bool = False,
               mimics: dict[str, str] | None = None,
               default: float | None = None) -> Configurations:
    """One configuration from ``{name: text}``; unnamed variables take ``default``, or when
    None their own default (0, or mid-range when 0 is outside the limits)."""
    index = {v.name: i for i, v in enumerate(variables)}
    row = defaults(variables) if default is None else np.full(len(variables), float(default))
    for name, value in assignments(variables, values, degrees, mimics).items():
        row[index[name]] = value
    row = row[None, :]
    placeable(variables, row)
    return Configurations(variables, row, limit_warnings(variables, row))


def configurations(model, q: dict[str, str] | None = None, degrees: bool = False,
                   q_file: str | None = None, count: int | None = None,
                   seed=0) -> Configurations:
    """The configurations of ``model`` (urdftool.kinematics.fk.KinematicModel) to compute: read
    from ``q_file``, else ``count`` random ones drawn from ``seed``, else one from ``q``."""
    if q_file:
        return from_file(model.variables, q_file, degrees, model.mimics)
    if count is not None:
        return random(model.variables, count, seed)
    return from_words(model.variables, q or {}, degrees, model.mimics)


@dataclass
class JointValues:
    """Positions ``q`` (every variable named, and each other whose default is not 0: mid-range,
    as every command poses it; the others absent, at 0), velocities ``v`` and accelerations
    ``a`` (None when not given), and warnings about positions given outside limits."""

    q: dict[str, float]
    v: dict[str, float] | None
    a: dict[str, float] | None
    warnings: list[str]


def joint_values(robot, q: dict[str, str], v: dict[str, str] | None = None,
                 a: dict[str, str] | None = None, degrees: bool = False,
                 floating_root: str | None = None,
                 variables: list[Variable] | None = None) -> JointValues:
    """Positions, velocities and accelerations of ``robot``'s joints from ``{name: text}``;
    a bad one raises ConfigError whose ``argument`` is 'q', 'v' or 'a'. A joint not named in
    ``q`` takes its default, as in :func:`from_words`: 0, or mid-range when 0 is outside its
    limits (dynamics computed G(q) at 0 there, a pose fk, collisions and render never draw).
    ``floating_root``: a free root joint of that name, whose coordinates are variables too.
    ``variables``: those of the model the values are for, when not the robot's (a robot's own
    free base held fixed has none: physics.dynamics.build)."""
    if variables is None:
        variables = variables_of(robot, floating_root)
    mimics = mimics_of(robot)
    parsed = []
    for argument, words in (("q", q), ("v", v), ("a", a)):
        try:
            parsed.append(assignments(variables, words, degrees, mimics)
                          if words or argument == "q" else None)
            if argument != "q" and parsed[-1]:
                _squarable(parsed[-1], {"v": "velocity", "a": "acceleration"}[argument])
        except ConfigError as error:
            error.argument = argument
            raise
    given = [variable for variable in variables if variable.name in parsed[0]]
    row = np.array([[parsed[0][variable.name] for variable in given]])
    warnings = limit_warnings(given, row)
    parsed[0] = {**{variable.name: variable.default for variable in variables
                    if variable.default != 0.0}, **parsed[0]}
    try:
        placed = [variable for variable in variables if variable.name in parsed[0]]
        placeable(placed, np.array([[parsed[0][variable.name] for variable in placed]]))
    except ConfigError as error:
        error.argument = "q"
        raise
    return JointValues(*parsed, warnings)


def _squarable(values: dict[str, float], what: str) -> None:
    """ConfigError for a joint velocity or acceleration past :data:`~urdftool.numbers.
    SQUARABLE`: the dynamics squares velocities (C(q, v)) and multiplies accelerations by
    M(q); a --v of 1e308 rad/s gave numpy's overflow warnings and torques of inf N m."""
    from urdftool.numbers import SQUARABLE, number as number_text

    far = [f"joint '{name}' {what} {number_text(value)}" for name, value in values.items()
           if not abs(value) <= SQUARABLE]
    if far:
        raise ConfigError(f"{', '.join(far)}: past what the dynamics computes with (at most "
                          f"{number_text(SQUARABLE)} each)")


def from_file(variables: list[Variable], path: str, degrees: bool = False,
              mimics: dict[str, str] | None = None) -> Configurations:
    """Configurations from a CSV (header = names) or JSON (a list of {name: value}) file: a
    regular file up to the size limit (urdftool.description.files.read_regular) that is not a
    link leading out of its repository, else ConfigError."""
    index = {v.name: i for i, v in enumerate(variables)}

    def check(names):
        for name in names:
            _column(index, name, mimics, where=f"{path}: header")

    names, table = read_table(path, "q-file", "joint", check)
    columns = [index[name] for name in names]
    if degrees:
        table *= np.array([math.pi / 180.0 if degrees and variables[c].angular else 1.0
                           for c in columns])
    if columns == list(range(len(variables))):  # every variable, in order: the table is it
        values = table
    else:  # (one copy of the table at a time: 12,000 rows of 300 joints are 29 MB)
        values = np.tile(defaults(variables), (len(table), 1))
        values[:, columns] = table
    del table
    try:
        placeable(variables, values)
    except ConfigError as error:  # (the file's, not --q's: "--q: joint 'knee' = 1e+308")
        raise ConfigError(str(error), path) from None
    return Configurations(variables, values, limit_warnings(variables, values))


def read_table(path: str, what: str, named: str, check=None) -> tuple[list[str], np.ndarray]:
    """(column names, values ``[rows, columns]``) of a CSV file (header = names; lines that start
    with ``#`` are comments) or a JSON file
    (a list of objects {name: value}) of numbers, read with :func:`read_bytes`; ``what`` names
    the file, ``named`` what its columns are ("joint"), ``check(names)`` may refuse the header
    before the values are read. ConfigError, located, for anything wrong: a column named twice
    (a CSV header, a JSON object's key) too, for every file of numbers (either value would be
    a guess; ``json`` and ``csv.DictReader`` take the last). The values are converted
    :data:`ROWS_PER_CHUNK` rows at a time into the table, a row's cells split as it is reached:
    every cell of the file held as a string at once was 433 MB for a 16 MB file (12,000 rows
    of 300 joints); a JSON file is decoded an element of its list at a time
    (:func:`_json_rows`)."""
    data = read_bytes(path, what)
    is_json = path.endswith(".json") or _visible_start(data) in ("[", "{")
    if is_json:
        names, count, rows = _json_rows(data, path, named)
    else:
        text, data = data.decode("utf-8-sig"), None  # (the text alone held: checked UTF-8)
        names, count, rows = _csv_rows(text, path, what, named)
    twice = named_twice(names)
    if twice is not None:
        raise ConfigError(f"{named} '{shown_word(twice)}' is named twice in the header",
                          f"{path}: header")
    if check is not None:
        check(names)
    table = np.empty((count, len(names)))
    chunk, done = [], 0
    for row in rows():
        chunk.append(row)
        if len(chunk) == ROWS_PER_CHUNK:
            table[done:done + len(chunk)] = _floats(chunk, names, path, named, done, is_json)
            done, chunk = done + len(chunk), []
    if chunk:
        table[done:] = _floats(chunk, names, path, named, done, is_json)
    return names, table


# rows of a file of numbers converted at a time: their cells as strings (300 joints: some 4 MB)
ROWS_PER_CHUNK = 256


def _floats(rows: list, names: list[str], path: str, named: str, before: int,
            any_json: bool) -> np.ndarray:
    """The values ``[rows, names]`` of ``rows`` (cells: CSV's strings, JSON's values), the
    rows after the first ``before`` of the file: in one conversion, else the careful reader's
    answer, which says what is wrong and where."""
    block = _vectorised(rows, len(names), any_json)
    return block if block is not None else _located_floats(rows, names, path, named, before)


def _vectorised(rows: list, width: int, any_json: bool):
    """``rows`` as floats ``[rows, width]`` in one conversion (numpy reads a string as
    ``float`` does), or None for the careful reader: a value that is no finite number, a JSON
    ``true`` (numpy's 1.0)."""
    try:
        cells = [cell for row in rows for cell in row]
        if any_json:
            cells = [float(cell) if cell.__class__ is not bool else None for cell in cells]
        block = np.array(cells, dtype=float).reshape(len(rows), width)
    except (ValueError, TypeError):
        return None
    return block if np.all(np.isfinite(block)) else None


def named_twice(names):
    """The first of ``names`` given again, or None; in one pass (a search of the names before
    each was quadratic: a header of 100,000 columns took the command's 60 s)."""
    seen: set = set()
    return next((name for name in names if name in seen or seen.add(name)), None)


def read_bytes(path: str, what: str) -> bytes:
    """The bytes of a file of numbers the user names (``what``: "q-file"): a regular file up to
    the size limit that is not a link leading out of its repository, else ConfigError; UTF-8
    (checked a piece at a time, the text not made), a byte-order mark left out when decoded
    (it was read as part of the first column's name, "unknown joint '\\ufeffhead_pan'", and
    JSON refused it)."""
    from urdftool.description.files import read_regular
    from urdftool.description.packages import link_out

    leads = link_out(path)
    if leads:
        raise ConfigError(f"cannot read {what}: it is a symbolic link leading outside the "
                          f"repository ({leads[1]}); not followed", path)
    try:  # a byte-order mark (Excel's "CSV UTF-8") marks the encoding: not the first name's
        data = read_regular(path)
    except OSError as error:
        raise ConfigError(f"cannot read {what}: {error.strerror}", path) from None
    try:
        for _ in _decoded(data):
            pass
    except UnicodeDecodeError:
        try:
            data.decode("utf-8-sig")  # (the error as the whole text's: where it is in the file)
        except UnicodeDecodeError as error:
            raise ConfigError(f"cannot read {what}: {error}", path) from None
    return data


# [bytes] of a file of numbers decoded at a time (a JSON element longer is read whole)
DECODED_AT_ONCE = 1 << 18


def _decoded(data: bytes, at_once: int | None = None):
    """The text of UTF-8 ``data`` (a byte-order mark left out), a piece of about ``at_once``
    (:data:`DECODED_AT_ONCE`) bytes at a time."""
    import codecs

    at_once = at_once or DECODED_AT_ONCE
    decoder = codecs.getincrementaldecoder("utf-8-sig")()
    for start in range(0, len(data), at_once):
        yield decoder.decode(data[start:start + at_once], start + at_once >= len(data))


def _visible_start(data: bytes) -> str:
    """The first character of ``data``'s text that is not white space ('' for none)."""
    for piece in _decoded(data, 1 << 12):
        piece = piece.lstrip()
        if piece:
            return piece[0]
    return ""


def _csv_rows(text: str, path: str, what: str, named: str):
    """(names, number of rows, rows): the header's names, and a function that gives the cells
    of each row in turn (a second pass over ``text``: what is held is a row's); every row's
    width judged first, a row of another width said at its line."""
    if '"' in text:
        def records():  # newline="": a line break inside a quoted cell is the cell's, as csv
            # reads it
            reader = csv.reader(io.StringIO(text, newline=""))
            before = 0
            try:
                for row in reader:  # a row's number: the line it starts on (a quoted cell may
                    yield before + 1, row  # hold line breaks), as every Location numbers them
                    before = reader.line_num
            except csv.Error as error:
                raise ConfigError(f"{what} is not CSV: {error}", path) from None
    else:  # no quoting: splitting is csv's answer, ten times faster
        lines = lines_of(text)

        def records():
            for number, line in enumerate(lines, start=1):
                yield number, line.split(",") if line else []

    def numbered():  # blank lines and comment lines (# first) are skipped; the others keep
        # their numbers
        for number, line in records():
            if line and any(cell.strip() for cell in line) and \
                    not line[0].lstrip().startswith("#"):
                yield number, line

    header, count = None, 0
    for line_number, line in numbered():
        if header is None:
            header = line
            names = [cell.strip() for cell in header]
            continue
        if len(line) != len(names):
            raise ConfigError(f"row has {len(line)} values but the header names {len(names)} "
                              f"{named}s", f"{path}:{line_number}")
        count += 1
    if header is None:
        raise ConfigError(f"empty {what}: expected a header of {named} names", path)
    if not count:
        raise ConfigError(f"{what} has a header but no rows", path)

    def rows():
        body = numbered()
        next(body)  # (the header)
        return (line for _, line in body)

    return names, count, rows


def _json_rows(data: bytes, path: str, named: str):
    """(names, number of rows, rows) of a JSON file of numbers (``data``, checked UTF-8), as
    :func:`_csv_rows`: read twice (:func:`_json_values`), its list an element at a time, once
    to know its names and rows and refuse what is wrong, then for the values, a row's listed as
    it is reached. The whole document made at once as ``json`` reads it, every row a dict of
    floats, and its text: reading a 13.5 MB file (3,000 rows of 300 joints) allocated 64.6 MB
    at the peak, now 25.4 MB (its bytes, the table, a piece of text, a chunk of rows). Refused
    as the whole document read at once was (``json``'s words and line, in the same order)."""
    names, first, short, count, listed_rows, not_object = {}, {}, None, 0, False, None
    try:
        for listed_rows, row in _json_values(data):
            count += 1
            if not isinstance(row, dict):
                not_object = not_object or count  # (said once the whole file is read)
            elif not_object is None:
                if count == 1:
                    first = row
                elif len(row) < len(first) and short is None:
                    short = (count, [name for name in first if name not in row])
                names.update(dict.fromkeys(row))  # (in the order first named)
    except _Twice as error:
        raise ConfigError(f"{named} '{error.args[0]}' is given twice in one object", path) from None
    except json.JSONDecodeError as error:
        raise ConfigError(f"invalid JSON: {error.msg}", f"{path}:{error.lineno}") from None
    except RecursionError:  # 10^5 [[
        raise ConfigError("invalid JSON: lists nested too deep for any configuration",
                          path) from None
    if not count or not listed_rows and not_object:  # ([], or one value that is no object)
        raise ConfigError(f"expected a JSON list of objects {{{named} name: value}}", path)
    if not_object:
        raise ConfigError(f"expected an object {{{named} name: value}}",
                          f"{path}: row {not_object}")
    if len(names) > len(first):  # a name the first row lacks: it is the first short one
        short = (1, [name for name in names if name not in first])
    if short is not None:
        raise ConfigError(f"row lacks {listed(short[1], quote=False)} (every row must name "
                          f"the same {named}s)", f"{path}: row {short[0]}")
    names = list(names)
    return names, count, lambda: ([row[name] for name in names]
                                  for _, row in _json_values(data))


class _Text:
    """The text of a JSON document read a piece at a time from its bytes (:func:`_decoded`):
    ``text[at:]`` is what is not yet read, ``lines`` the line breaks before ``text``."""

    def __init__(self, data: bytes) -> None:
        self.pieces = _decoded(data)
        self.text, self.at, self.lines, self.ended = "", 0, 0, False

    def more(self) -> bool:
        """Whether more text was added (at least as much as is held: a long element is read
        again a bounded number of times); False at the end."""
        added, size, held = [], 0, len(self.text) - self.at
        while not self.ended and size < max(held, 1):
            piece = next(self.pieces, None)
            if piece is None:
                self.ended = True
            else:
                added.append(piece)
                size += len(piece)
        if not added:
            return False
        # line ends: json's (LF only, as JSONDecodeError.lineno counts them in the whole text)
        self.lines += self.text.count("\n", 0, self.at)
        self.text, self.at = self.text[self.at:] + "".join(added), 0
        return True

    def skip_space(self) -> str:
        """The next character after JSON's white space ('' at the end), not taken."""
        while True:
            self.at = _SPACE(self.text, self.at).end()
            if self.at < len(self.text) or not self.more():
                return self.text[self.at:self.at + 1]

    def value(self, decode):
        """The JSON value that starts here, taken. What fails before the end of the text
        (a value cut by a piece's end, or not), or ends within a few characters of it (a
        number whose exponent may follow), is read again with more text: the answer and
        the error are those of the whole text."""
        while True:
            try:
                value, end = decode(self.text, self.at)
            except (ValueError, RecursionError) as error:
                if self.more():
                    continue
                if isinstance(error, json.JSONDecodeError):
                    raise self.error(error.msg, error.pos) from None
                raise
            if end + _LOOKAHEAD >= len(self.text) and self.more():
                continue
            self.at = end
            return value

    def error(self, message: str, at: int, line: int | None = None) -> json.JSONDecodeError:
        """json's error ``message`` at ``at`` in the text, its line counted from the file's
        start (or ``line``)."""
        made = json.JSONDecodeError(message, self.text, at)
        made.lineno = self.line(at) if line is None else line
        return made

    def line(self, at: int) -> int:
        """The line of the file that ``at`` in the text is on (line ends: json's, LF only)."""
        return self.lines + self.text.count("\n", 0, at) + 1


_SPACE = re.compile(r"[ \t\n\r]*").match  # (JSON's white space, as json.decoder's)
_LOOKAHEAD = 3  # [characters] that may extend a number read to the end of the text: 'e-5'


def _json_values(data: bytes):
    """(whether the document is a list, each value) of the JSON document ``data``: each
    element of its list, read a piece of text at a time, or the one value it is otherwise;
    json.JSONDecodeError (ValueError, RecursionError) as json.loads raises it of the whole
    text. The list's brackets, commas and white space are read here as json's scanner reads
    them (CPython's _json.c, _parse_array_unicode), its elements and any other value by it."""
    # (every number kept as written, converted to a float with the rest: an integer past
    # Python's 4,300 digits was json's ValueError, one past a double float()'s
    # OverflowError; as written, each is "not finite" at its row)
    decode = json.JSONDecoder(object_pairs_hook=_once_each, parse_int=_Number,
                              parse_float=_Number).raw_decode
    text = _Text(data)
    text.more()
    if text.text.startswith("\ufeff"):  # (a second mark: json.loads refuses it so)
        raise text.error("Unexpected UTF-8 BOM (decode using utf-8-sig)", 0)
    if text.skip_space() != "[":
        while text.more():
            pass
        yield False, text.value(decode)
    else:
        text.at += 1
        if text.skip_space() == "]":
            text.at += 1
        else:
            while True:
                yield True, text.value(decode)
                after = text.skip_space()
                text.at += 1
                if after == "]":
                    break
                if after != ",":
                    raise text.error("Expecting ',' delimiter", text.at - 1)
                comma = (text.text, text.at - 1, text.lines)  # (its line counted if said)
                if text.skip_space() == "]" and _TRAILING_COMMA is not None:
                    raise text.error(_TRAILING_COMMA, text.at,  # (line ends: json's)
                                     comma[2] + comma[0].count("\n", 0, comma[1]) + 1)
    if text.skip_space():
        raise text.error("Extra data", text.at)


def _trailing_comma() -> str | None:
    """What json says of a list's comma before its ']' when it says so at the comma (Python
    3.13: "Illegal trailing comma before end of array"); None when it expects a value at the
    ']' (3.11, 3.12), as :meth:`_Text.value` then finds."""
    try:
        json.loads("[0,]")
    except json.JSONDecodeError as error:
        return error.msg if error.pos == 2 else None
    return None


_TRAILING_COMMA = _trailing_comma()


class _Number(str):
    """A JSON number as written (``float`` reads it as the CSV reader reads a cell)."""

    __slots__ = ()


def _json_text(value) -> str:
    """A JSON value as written, its numbers as they were (:class:`_Number`: ``json.dumps``
    wrote ``[1]`` as ``["1"]``)."""
    if isinstance(value, _Number):
        return str(value)
    if isinstance(value, list):
        return "[" + ", ".join(map(_json_text, value)) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{json.dumps(k)}: {_json_text(v)}" for k, v in value.items()) + "}"
    return json.dumps(value)


class _Twice(Exception):
    """A JSON object giving a key twice (its key)."""


def _once_each(pairs: list) -> dict:
    """A JSON object as a dict, each key given once (:class:`_Twice` otherwise)."""
    found = dict(pairs)
    if len(found) != len(pairs):
        seen = set()
        raise _Twice(next(key for key, _ in pairs if key in seen or seen.add(key)))
    return found


def _located_floats(rows, names, path, named: str, before: int = 0) -> np.ndarray:
    """``rows`` as floats, each checked: ConfigError at the first that is no finite number,
    located by its row of the file (``before``: the rows of the file before ``rows``)."""
    table = np.empty((len(rows), len(names)))
    for number, row in enumerate(rows, start=1):
        for column, cell in enumerate(row):
            where = f"{path}: row {before + number}"
            written = cell if isinstance(cell, str) else _json_text(cell)  # (JSON's words)
            message = (f"value '{shown_word(written)}' for {named} "
                       f"'{shown_word(names[column])}' is not a number")
            if isinstance(cell, bool) or not isinstance(cell, (int, float, str)):
                raise ConfigError(message, where)
            table[number - 1, column] = _to_float(str(cell), message, where)
    return table


def _column(index: dict, name: str, mimics: dict | None, where: str | None = None) -> int:
    if name in index:
        return index[name]
    if mimics and name in mimics:
        raise ConfigError(_set_instead(name, index, mimics), where)
    raise ConfigError(f"unknown joint '{shown_word(name)}'; " + available("joints", name, index),
                      where)


def _set_instead(name: str, index: dict, mimics: dict) -> str:
    """What to set in place of mimic joint ``name``: the joint its chain of mimics ends at (a
    mimic of a mimic named its leader, itself a mimic that was refused in turn)."""
    path = [name]
    while path[-1] in mimics and path[-1] not in index:
        if mimics[path[-1]] in path:
            return (f"joint '{name}' mimics '{mimics[name]}', in a cycle of mimic joints: no "
                    "joint sets it")
        path.append(mimics[path[-1]])
    said = f"joint '{name}' mimics '{path[1]}'"
    if len(path) == 3:
        said += f", which mimics '{path[2]}'"
    elif len(path) > 3:
        said += f", which follows '{path[-1]}' through {len(path) - 3} more mimic joint(s)"
    if path[-1] not in index:
        return f"{said}; '{path[-1]}' takes no value"
    return f"{said}: set '{path[-1]}' instead"


def _to_float(text: str, message: str, where: str | None = None) -> float:
    try:
        value = float(text)
    except ValueError:
        raise ConfigError(message, where) from None
    if not math.isfinite(value):
        raise ConfigError(message.replace("is not a number", "is not finite"), where)
    return value


def _scaled(value: float, variable: Variable, degrees: bool) -> float:
    return math.radians(value) if degrees and variable.angular else value


def limit_warnings(variables: list[Variable], values: np.ndarray) -> list[str]:
    """One warning per variable that has values outside its limits (still computed)."""
    lower = np.array([v.lower for v in variables])
    upper = np.array([v.upper for v in variables])
    outside = (values < lower - 1e-12) | (values > upper + 1e-12)
    warnings = []
    for column in np.flatnonzero(outside.any(axis=0)):
        rows = np.flatnonzero(outside[:, column])
        variable = variables[column]
        first = f"{values[rows[0], column]:g}"
        where = "" if len(values) == 1 else (
            f" in {len(rows)} row(s), first row {rows[0] + 1}")
        warnings.append(f"joint '{variable.name}' = {first} is outside its limits "
                        f"[{variable.lower:g}, {variable.upper:g}]{where}; computed anyway")
    return warnings


def random_stream(seed):
    """numpy's generator of ``seed`` (an integer 0 or more, a sequence of them, or None), the
    one maker of every random stream a command draws from (``--seed`` of fk, ik, dynamics,
    workspace, collisions, diff). UsageError for a seed numpy refuses (a negative one): the
    message numpy gives is a traceback's."""
    from urdftool.errors import UsageError

    try:
        return np.random.default_rng(seed)
    except (ValueError, TypeError):
        given = seed[0] if isinstance(seed, (list, tuple)) else seed  # (a block's stream)
        raise UsageError(f"--seed must be an integer, 0 or more, not {given}") from None


def within(generator, lower, upper, size: tuple[int, int]) -> np.ndarray:
    """Values drawn uniformly between ``lower`` and ``upper`` (per column), ``size`` of them: the
    one uniform draw between joint limits (a scan holds it). Limits written the wrong way round
    are a range all the same (numpy refuses them); limits past
    :data:`~urdftool.numbers.MAX_COORDINATE` are drawn within it, as every value given is
    (:func:`placeable`): a prismatic joint of limits +-1e200 placed its link at 1e199 (a
    workspace "max reach inf m"), and numpy's uniform raised "Range exceeds valid bounds" for
    a span past the largest float."""
    from urdftool.numbers import MAX_COORDINATE

    if math.prod(size) > np.iinfo(np.intp).max // 8:  # numpy's ValueError ("array is too
        # big"), a traceback of --random, --samples, --seeds of 10^18, where 10^10 ran out of
        # the memory budget: no memory holds it either
        raise MemoryError(f"{size[0]:,} draws of {size[1]} values: past any memory")
    low = np.clip(np.minimum(lower, upper), -MAX_COORDINATE, MAX_COORDINATE)
    high = np.clip(np.maximum(lower, upper), -MAX_COORDINATE, MAX_COORDINATE)
    return generator.uniform(low, high, size=size)


def placeable(variables: list[Variable], values: np.ndarray) -> None:
    """ConfigError for the first joint value past :data:`~urdftool.numbers.MAX_COORDINATE`
    ([m] or [rad]; a default too: mid-range of limits at 1e200): a link placed there is past
    what urdftool computes with (every pose below it rounded to nothing or squared to inf),
    whichever command poses it: the one check of the values given (:func:`from_words`,
    :func:`from_file`, :func:`joint_values`), as :func:`within` is of the values drawn."""
    from urdftool.numbers import MAX_COORDINATE, number as number_text

    with np.errstate(invalid="ignore"):
        far = np.argwhere(~(np.abs(values) < MAX_COORDINATE))
    if len(far):
        row, column = far[0]
        where = "" if len(values) == 1 else f" (row {row + 1})"
        if values[row, column] == variables[column].default != 0.0:
            where += " (its default, the middle of its limits)"
        raise ConfigError(f"joint '{variables[column].name}' = {number_text(values[row, column])}"
                          f"{where} is past the {number_text(MAX_COORDINATE)} (m or rad) "
                          "urdftool places a link within")


def random(variables: list[Variable], count: int, seed=None,
           hold: Collection[str] = ()) -> Configurations:
    """``count`` configurations drawn uniformly within the limits (continuous: [-pi, pi]).

    seed: anything ``numpy.random.default_rng`` takes; a sequence such as ``[seed, block]``
        gives independent streams for blocks drawn apart (e.g. in worker processes)
    hold: names of variables kept at their default instead of drawn
    """
    generator = random_stream(seed)
    lower, upper = [], []
    for v in variables:
        if v.name in hold:
            lower.append(v.default)
            upper.append(v.default)
        elif math.isfinite(v.lower) and math.isfinite(v.upper):
            lower.append(v.lower)
            upper.append(v.upper)
        else:
            span = _RANDOM_SPAN.get(v.kind, math.pi)
            lower.append(-span)
            upper.append(span)
    values = within(generator, lower, upper, (count, len(variables)))
    return Configurations(variables, values, [])
