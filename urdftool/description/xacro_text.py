"""A robot file's text read without expanding it: the files it includes, the tags of its top
level, the macros it defines and calls. Classifying the files of a folder (which are robots,
which are parts: :mod:`urdftool.lint.targets`) and judging a file that does not expand
(:mod:`urdftool.lint.rules.loading`) ask the same questions; the answers are decided here, once.
Files are read through :func:`head`: regular files under the size limit, inside their
repository, links followed."""

from __future__ import annotations

import os
import re
from pathlib import Path

from urdftool.description.files import DEFAULT_MAX_FILE_SIZE, inside, read_regular, real_path
from urdftool.description.packages import PackageResolver, containment_root
from urdftool.description.urdf import is_xacro, is_xacro_element

# What a fragment of a robot defined elsewhere holds besides definitions (X.gazebo.xacro): the
# blocks that extend links and joints written by the robot that includes it, and a top-level
# <plugin> (legacy Gazebo's and Webots'; a Clearpath platform macro file writes one beside its
# macro: a library all the same)
PART_BLOCKS = frozenset({"gazebo", "transmission", "ros2_control", "webots", "plugin"})
# [^<>]: a tag ends before the next "<", so no character is scanned from two starts (linear time
# on files made of "<xacro:include " repeated).
# Pre-2019 xacro wrote <include> without the prefix (ros-naoqi/nao_robot's nao_robot_v4.urdf.xacro).
INCLUDE = re.compile(rb"<(?:xacro:)?include\s[^<>]*?filename\s*=\s*[\"']([^\"'<>]+)[\"']", re.S)
# $(optenv VAR default): xacro takes the default when VAR is unset (Clearpath's
# $(optenv HUSKY_URDF_EXTRAS empty.urdf)); $(arg NAME): the argument's default in the same file
_OPTENV = re.compile(r"\$\(optenv\s+\S+\s+([^)$\s]+)\)")
_ARG_USE = re.compile(r"\$\(arg\s+([^)\s]+)\)")
ARG_DEFAULT = re.compile(  # the first name (atomic: each later one tried again was quadratic)
    rb"<xacro:arg\s(?>[^<>]*?name\s*=\s*[\"']([^\"'<>]+)[\"'])[^<>]*?default\s*=\s*[\"']([^\"'<>]*)[\"']",
    re.S)
CHUNK = 64 * 1024
FIND = re.compile(r"\$\(find\s+([^)\s]+)\)")
DEFINITIONS = {"property", "arg", "include", "macro", "material"}
# xacro's own elements: everything else in its namespace is a macro call
XACRO_DIRECTIVES = DEFINITIONS | {"if", "unless", "insert_block", "element", "attribute",
                                   "call", "load_yaml"}


def resolved_path(path: Path) -> Path:
    try:
        return Path(real_path(path))
    except (OSError, ValueError):  # NUL in a name
        return path.absolute()


def stays_inside(path: Path) -> bool:
    """Whether ``path``, links followed, stays in the repository holding it (as named)."""
    return inside(path, containment_root(Path(os.path.abspath(path)).parent))


def head(path: Path, limit: int = DEFAULT_MAX_FILE_SIZE) -> bytes | None:
    """A file's bytes; None, without opening it, for a link leading outside the repository, a
    file over ``limit`` [bytes] or anything else :func:`~urdftool.description.files.read_regular` refuses."""
    if not stays_inside(path):
        return None
    try:
        return read_regular(path, limit, as_="target")
    except (OSError, ValueError):
        return None


def stream(data: bytes, target) -> str:
    """Feed ``data`` to an lxml parser ``target`` as a stream of start and end tags, no tree
    kept, stopping at the first answer (raised as _Answered): memory stays small whatever the
    file holds. An unparsable file answers 'robot', so that the parse error is reported."""
    from lxml import etree

    parser = etree.XMLParser(target=target, resolve_entities=False, no_network=True,
                             load_dtd=False, recover=True)
    try:
        for offset in range(0, len(data) or 1, CHUNK):
            parser.feed(data[offset:offset + CHUNK])
        parser.close()
    except _Answered as answered:
        return answered.args[0]
    except etree.LxmlError:
        return "robot"
    return target.default()


def local_name(tag) -> str:
    """A tag's name without namespace or prefix (lxml in recover mode keeps an undeclared
    ``xacro:`` prefix in the name)."""
    return tag.rpartition("}")[2].rpartition(":")[2] if isinstance(tag, str) else ""


class _Answered(Exception):
    """The question is answered (its answer is the argument): stop reading."""


def uncommented(data: bytes) -> bytes:
    """``data`` without its XML comments: an include commented out is no include
    (ipa320/cob_common's ur10_arm.urdf.xacro). Linear: a comment left open ends the text."""
    parts, start = [], 0
    while (opening := data.find(b"<!--", start)) >= 0:
        parts.append(data[start:opening])
        closing = data.find(b"-->", opening + 4)
        if closing < 0:
            return b"".join(parts)
        start = closing + 3
    return b"".join(parts) + data[start:] if parts else data


def included_files(path: Path, data: bytes, resolver: PackageResolver):
    """The files ``data`` (of ``path``) includes, resolved. An include through ``$(arg NAME)``
    takes the argument's default written in the file, and ``$(optenv VAR default)`` its default,
    as xacro does when nobody gives the argument or sets the variable (Clearpath's
    ``<xacro:arg name="urdf_extras" default="$(optenv HUSKY_URDF_EXTRAS empty.urdf)"/>``)."""
    defaults = arg_defaults(data)
    for match in INCLUDE.finditer(data):
        found = resolved_spec(path, match.group(1).decode("utf-8", "replace"), defaults,
                               resolver)
        if found is not None:
            yield found


def arg_defaults(data: bytes) -> dict[str, str]:
    """The defaults of the ``<xacro:arg>`` written in ``data`` (none looked for when nothing
    in it uses ``$(arg``)."""
    if b"$(arg" not in data:
        return {}
    return {name.decode("utf-8", "replace"): value.decode("utf-8", "replace")
            for name, value in ARG_DEFAULT.findall(data)}


def unnamed_arguments(sources, args: dict[str, str]) -> dict[str, list[str]]:
    """The xacro arguments of ``args`` that no file of ``sources`` (the bytes of every file
    expanded, :attr:`Robot.sources`) names, each with the arguments the files declare whose
    names are close: an argument is read by ``$(arg NAME)``, ``arg('NAME')`` in ``$(eval)`` or
    declared by ``<xacro:arg name="NAME">``, all of which write its name, so one whose name
    is in no file changes nothing (xacro takes it without a word: ``lenght:=2`` for
    ``length``)."""
    from urdftool.errors import close_names

    texts = [data.decode("utf-8", "replace") for data in sources.values()]
    unnamed = [name for name in args
               if not any(re.search(rf"(?<![\w-]){re.escape(name)}(?![\w-])", text)
                          for text in texts)]
    if not unnamed:
        return {}
    declared = declared_arguments(sources)
    return {name: close_names(name, declared) for name in unnamed}


def declared_arguments(sources) -> list[str]:
    """The names of the ``<xacro:arg>`` the files of ``sources`` declare, sorted."""
    return sorted({name.decode("utf-8", "replace") for data in sources.values()
                   for name, _ in ARG_DEFAULT.findall(data)})


def run_argument_warnings(arguments: list, given: dict[str, str], whose: str) -> list[str]:
    """A warning for each xacro argument of ``given`` that no robot's files name, with the
    names any of them declares close to it, from what each check kept of its robot's text
    (``arguments``: per robot, ``[named, declared]`` of ``given``, as
    ``lint.options.FileResult.arguments``). The one wording of the robot commands (one robot,
    :func:`argument_warnings`) and of check (every robot of the run)."""
    from urdftool.errors import close_names, listed

    named = {name for each, _ in arguments for name in each}
    declared = sorted({name for _, each in arguments for name in each})
    warnings = []
    for name in given:
        if name not in named:
            close = close_names(name, declared)
            hint = f"; did you mean {listed(close)}?" if close else ""
            warnings.append(f"xacro argument '{name}' ({name}:={given[name]}) is named by no "
                            f"file of {whose} (no <xacro:arg name=\"{name}\">, no $(arg {name})"
                            f"): it changes nothing{hint}")
    return warnings


def argument_warnings(sources, args: dict[str, str], whose: str) -> list[str]:
    """A warning for each xacro argument of ``args`` (``--arg NAME=VALUE``, ``NAME:=VALUE``)
    that no file of ``sources`` names (:func:`unnamed_arguments`), with the declared names
    close to it: xacro takes it and it changes nothing (``--arg lenght=2`` computed the
    defaults without a word). ``whose``: what the files are, as the warning says it ("the
    robot", "the 3 robots checked"). The robot commands' warning; check's is
    :func:`run_argument_warnings`, in the same words."""
    unnamed = unnamed_arguments(sources, args)
    return run_argument_warnings([[[name for name in args if name not in unnamed],
                                   declared_arguments(sources)]], args, whose)


def resolved_spec(path: Path, spec: str, defaults: dict[str, str],
                   resolver: PackageResolver) -> Path | None:
    """The file ``spec``, written in ``path``, names, or None when it needs what is only
    known when expanding."""
    spec = _ARG_USE.sub(lambda m: defaults.get(m.group(1), m.group(0)), spec)
    spec = _OPTENV.sub(lambda m: m.group(1), spec)
    find = FIND.search(spec)
    if find:
        try:
            spec = spec.replace(find.group(0), str(resolver.find(find.group(1))))
        except Exception:
            return None
    if "$" in spec or "\0" in spec:
        return None
    return resolved_path(resolver.locate(path.parent / spec).path)  # as xacro finds it


class MacroUse:
    """lxml parser target for a xacro file: answers 'content' at anything outside its macro
    definitions and extension blocks that is neither a definition nor a macro call (a
    ``<link>``, any element of its own; ``xacro:call``, ``insert_block``, ``element``, whose
    result is not known here), looking inside ``xacro:if``/``unless``; at the end 'calls'.
    Meanwhile it notes the macros called there (``calls``) and, for each macro it defines,
    whether its body writes a ``<link>`` or ``<joint>`` (or something not known here) and the
    macros it calls (``macros``: name -> [makes links, calls])."""

    _UNKNOWN = {"call", "insert_block", "element"}

    def __init__(self):
        self.depth, self.skipped = 0, None  # depth of a block whose inside says nothing
        self.macro, self.calls, self.macros = None, set(), {}

    def start(self, tag, attributes):
        self.depth += 1
        if self.depth == 1 or self.skipped is not None:
            return
        name, xacro = local_name(tag), is_xacro(tag)
        if name == "macro":
            if self.macro is None:  # (a definition inside one is read as part of its body)
                self.macro = (self.depth, self.macros.setdefault(
                    attributes.get("name", ""), [False, set()]))
            return
        if self.macro is not None:  # a body: what the macro writes
            entry = self.macro[1]
            if not xacro and name in PART_BLOCKS:  # (a transmission's <joint> names one)
                self.skipped = self.depth
            elif not xacro and name in ("link", "joint") or xacro and name in self._UNKNOWN:
                entry[0] = True
            elif xacro and name not in XACRO_DIRECTIVES:
                entry[1].add(name)
            return
        if xacro and name in ("if", "unless"):
            return  # what it holds is read as the top level
        if xacro and name not in XACRO_DIRECTIVES:  # a call: its children are its blocks
            self.calls.add(name)
        elif not (name in DEFINITIONS or not xacro and name in PART_BLOCKS) or \
                xacro and name in self._UNKNOWN:
            raise _Answered("content")
        self.skipped = self.depth

    def end(self, tag):
        if self.skipped == self.depth:
            self.skipped = None
        elif self.macro is not None and self.macro[0] == self.depth:
            self.macro = None
        self.depth -= 1

    def close(self):
        return None

    def default(self) -> str:
        return "calls"


def reached(includes: list, resolver_for, limit: int, also=None):
    """(bytes, whether its own includes could all be followed) of each file reached from
    ``includes`` through the includes of each (once; bytes None for a file missing, refused
    or binary, whose includes are not known). ``also(path, text, resolver, included)``: more
    files a file names, followed as its includes; nothing is followed without
    ``resolver_for``."""
    seen, pending = set(), list(includes)
    while pending:
        target = pending.pop()
        if target in seen:
            continue
        seen.add(target)
        data = head(target, limit)
        if data is None or b"\0" in data:
            yield None, False
            continue
        complete = True
        if resolver_for:
            written = uncommented(data)
            resolver = resolver_for(target)
            followed = list(included_files(target, written, resolver))
            complete = len(INCLUDE.findall(written)) <= len(followed)
            pending.extend(followed + (also(target, written, resolver, followed) if also else []))
        yield data, complete


def writes_no_links(path, packages, limit: int = DEFAULT_MAX_FILE_SIZE) -> bool:
    """Whether the xacro file ``path`` is a part whose top level writes no link: only
    definitions, extension blocks and calls of macros, defined in it and the files it includes,
    that write none (:func:`calls_make_links`). ``packages``: the check's ``--package``
    paths."""
    path = Path(path)
    written = _xacro_source(path, limit)
    if written is None:
        return False

    def resolver_for(file: Path) -> PackageResolver:
        return PackageResolver(packages, start=file.parent)

    includes = list(included_files(path, written, resolver_for(path)))
    unfollowed = len(INCLUDE.findall(written)) > len(includes)
    return not calls_make_links(written, includes, unfollowed, resolver_for, limit)


def nameless_robot(path, limit: int = DEFAULT_MAX_FILE_SIZE, own_links: bool = True) -> bool:
    """Whether the ``.xacro`` file ``path`` has a ``<robot>`` root without a name: what a file
    written for xacro to include looks like (xacro keeps only the includer's root, so its name
    is not needed), and what urdfdom refuses loaded alone. ``own_links`` False: and it writes
    no ``<link>`` or ``<joint>`` of its own outside macro definitions (its links, if any, come
    from the macros it calls: bluerov2's actuators.xacro)."""
    written = _xacro_source(Path(path), limit)
    root = _ROBOT_TAG.search(written) if written is not None else None
    if root is None or _NAME_ATTRIBUTE.search(root.group(0)) is not None:
        return False
    return own_links or _OWN_LINK.search(without_macro_bodies(written)) is None


_ROBOT_TAG = re.compile(rb"<robot\b[^<>]*>")
_NAME_ATTRIBUTE = re.compile(rb"\sname\s*=")
_OWN_LINK = re.compile(rb"<(?:link|joint)\b")
MACRO_START = re.compile(rb"<(?:xacro:)?macro\s")  # a macro definition's opening tag
_MACRO_END = re.compile(rb"</(?:xacro:)?macro\s*>")


def without_macro_bodies(data: bytes) -> bytes:
    """``data`` without its macro definitions, each from ``<xacro:macro`` to the first
    ``</xacro:macro>`` after it (the same bytes, not searched, when it has no ``macro`` at all,
    as most robots). What ``re.sub`` of ``<macro .*?</macro>`` removes, in time linear in
    ``data``: that expression looked for a closing tag from every opening one, to the end of
    the file for each when none followed (a comment of 20,000 ``<macro `` took 6 s); an
    opening tag with no closing tag after it has none after any later one either."""
    if b"macro" not in data:
        return data
    kept, at = [], 0
    while (start := MACRO_START.search(data, at)) is not None:
        end = _MACRO_END.search(data, start.end())
        if end is None:
            break
        kept.append(data[at:start.start()])
        at = end.end()
    kept.append(data[at:])
    return b"".join(kept)


def macro_library(path, limit: int = DEFAULT_MAX_FILE_SIZE) -> bool:
    """Whether the xacro file ``path`` is a library of macros: it defines one or more, and its
    own top level calls none and writes nothing but definitions, includes and extension blocks
    (talos' sensors/xtion_pro_live.urdf.xacro). Written to be included: run alone, its own text
    makes no robot (what a file it includes writes at its top level is not known here when
    that file is not)."""
    written = _xacro_source(Path(path), limit)
    use = MacroUse()
    return written is not None and stream(written, use) == "calls" and not use.calls and \
        bool(use.macros)


def _xacro_source(path: Path, limit: int) -> bytes | None:
    """The text of a ``.xacro`` file without its comments, read through :func:`head`; None for
    another file, one not read, or a binary one."""
    data = head(path, limit) if path.name.endswith(".xacro") else None
    return None if data is None or b"\0" in data else uncommented(data)


def calls_make_links(data: bytes, includes: list, unfollowed: bool, resolver_for,
                     limit: int) -> bool:
    """Whether a xacro file makes links through what its top level holds: True unless that is
    only definitions, extension blocks and calls of macros that the file and the files it
    includes (followed) define, none of which writes a ``<link>`` or ``<joint>`` or calls one
    that does (talos' left_arm.transmissions.urdf.xacro: transmissions through macro calls,
    a part for a robot that defines its ``name``). Anything not known (an include not
    followed, a macro defined nowhere here, an included file with content of its own) counts
    as links: the file is then checked."""
    use = MacroUse()
    if unfollowed or stream(data, use) != "calls":
        return True
    macros = use.macros
    for included, complete in reached(includes, resolver_for, limit):
        table = MacroUse()
        if included is None or not complete or stream(included, table) != "calls" or \
                table.calls:
            return True  # not known, or an include writing or calling at its top level
        for name, (links, calls) in table.macros.items():
            entry = macros.setdefault(name, [False, set()])
            entry[0] = entry[0] or links
            entry[1] |= calls
    called, pending = set(), list(use.calls)
    while pending:
        name = pending.pop()
        if name in called:
            continue
        called.add(name)
        entry = macros.get(name)
        if entry is None or entry[0]:
            return True
        pending.extend(entry[1])
    return False


def dropped_under(robot, element, wanted: str) -> str | None:
    """How the xacro source of ``element`` (of the expanded ``robot``) writes its ``<wanted>``
    only under ``xacro:if``/``xacro:unless`` conditions on arguments or properties, false as
    the robot was expanded (``its <plugin> is under <xacro:if value="$(arg sim_mode)"> (line
    15) of ros2_control.xacro, false then``), or None. A constant condition is not one: no
    build gives it."""
    location = robot.locate(element)
    data = robot.sources.get(location.file) if location is not None and location.line is not None else None
    found = [(written, line) for written, line in (
        condition_dropping(data, location.line, local_name(element.tag), wanted) if data else ())
        if "$(arg" in written or "${" in written]
    if not found:
        return None
    under = " or ".join(f"<{written}> (line {line})" for written, line in found[:3])
    return (f"its <{wanted}> is under {under} of {location.file}, "
            f"{'false' if len(found) == 1 else 'each false'} then")


def condition_dropping(data: bytes, line: int, tag: str, wanted: str) -> list[tuple[str, int]]:
    """Where the xacro source ``data`` writes a ``wanted`` element inside the ``tag`` element
    whose start tag is on ``line``, but only under an ``xacro:if``/``xacro:unless``: each such
    condition's start tag as written (``xacro:if value="$(arg sim_mode)"``) and its line, in
    document order; empty when the source holds none so (or does not parse). An element the
    expanded robot lacks there was then left out by the arguments or properties it was
    expanded with, not forgotten."""
    from urdftool.description.xml import XmlProblem, parse

    try:
        root, positions = parse(data)
    except (XmlProblem, ValueError, SyntaxError):
        return []
    found = []
    for element in root.iter(tag, f"{{*}}{tag}"):
        position = positions.get(element)
        if position is None or position[0] != line or local_name(element.tag) != tag:
            continue
        for condition in element.iter():
            if condition is element or not is_xacro_element(condition) or \
                    local_name(condition.tag) not in ("if", "unless"):
                continue
            if any(local_name(inner.tag) == wanted for inner in condition.iter()
                   if inner is not condition):
                words = " ".join(f'{name}="{value}"' for name, value in condition.attrib.items())
                found.append((f"xacro:{local_name(condition.tag)} {words}".strip(),
                              positions.get(condition, (line,))[0]))
        break
    return found
