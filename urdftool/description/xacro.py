"""Expand xacro in-process, keeping the source location of every element.

The ``xacro`` package is used as it is; a few of its module functions are wrapped for the length
of one expansion:

- ``parse`` reads each file through a minidom builder that stamps every element with a hidden
  ``xmlns:``-prefixed attribute holding ``file-index:line`` (xacro copies attributes when it clones
  macro bodies, and ``check_attrs`` ignores ``xmlns:`` names, so the stamp survives expansion);
- ``handle_macro_call`` lifts the stamp off the call and records it as a call site, and
  ``eval_all`` appends the active call sites to the elements a macro body produces;
- ``substitution_args._eval_find`` resolves ``$(find pkg)`` through :class:`PackageResolver`;
- ``get_include_files`` expands an include's glob pattern (``robots/*.xacro``) itself
  (:func:`_expand_pattern`): where the pattern may look is decided before anything is listed,
  and no folder outside the repository and the packages is listed, nor named in a message;
- ``safe_eval`` and ``substitution_args._eval`` (``$(eval ...)``) go through
  :mod:`xacro_sandbox`, whose ``env``/``optenv``/``find`` are the session's own.

The expander is ROS 2's xacro. A robot whose package builds with catkin (ROS 1) is expanded as
ROS 1's xacro up to Melodic (1.13) read it: the seven xacro tags without the ``xacro:`` prefix
(:data:`ROS1_TAGS`; an ``<include>`` only when it holds no element, as Gazebo's ``<include><uri>``
does) and macro calls without it are xacro's (:func:`_prefix_ros1_tags`), each file that relies on
it named in a warning: xacro since Noetic (1.14) and ROS 2's leave those tags in the output.
When that reading fails and Noetic's succeeds, the robot is Noetic's expansion and Melodic's
failure a warning (:func:`expand`).

When xacro raises, the element being processed is recovered from the traceback's frames, so the
diagnostic points at the line that failed and not just at the file.
"""

from __future__ import annotations

import builtins
import contextlib
import errno
import io
import fnmatch
import math
import os
import re
import sys
import xml.dom
import xml.dom.minidom
from dataclasses import dataclass
from pathlib import Path
from xml.dom.expatbuilder import ExpatBuilderNS
from xml.parsers import expat

from lxml import etree

from urdftool import budget
from urdftool.diagnostics import LineNumbers, Location, display_path, lines_of
from urdftool.errors import PackageNotFound
from urdftool.description import files
from urdftool.errors import available
from urdftool.description import xacro_sandbox
from urdftool.description.xml import MAX_DEPTH, XmlProblem, entity_message, \
    external_dtd_message, malformed, too_deep_message
from urdftool.records import NEW, Record

STAMP = "xmlns:urdftool-loc"
_STAMP_PREFIX = "urn:loc:"
_STAMP_LOCAL = STAMP.split(":", 1)[-1]  # (its local name, as minidom's Attr finds it)
MAX_MACRO_DEPTH = 100
MAX_ELEMENTS = 100_000  # elements xacro may evaluate in one expansion (macro bombs)
MAX_MACRO_CALLS = 20_000  # macro calls in one expansion
MAX_OUTPUT_DEPTH = 1000  # element nesting of the expanded document
MAX_TEXT = 64 * 1024 * 1024  # [characters] all substitutions of one expansion may produce
MAX_MESSAGES = 1024 * 1024  # [characters] of xacro's warnings kept
MAX_PATTERN_ENTRIES = 20_000  # folder entries one include pattern may look at
_MAGIC = re.compile(r"[*?[]")  # what makes xacro glob an include's filename
_UNSTAMPED = {"xacro:macro"}  # its attributes are copied onto the caller's parent
# xacro's tags that ROS 1's xacro up to Melodic (1.13) also read without the xacro: prefix (its
# deprecation message lists them); its macro calls too (handle_macro_call)
ROS1_TAGS = ("include", "property", "macro", "arg", "if", "unless", "insert_block")


@dataclass
class XacroFailure(Exception):
    """xacro stopped; ``kind`` is 'xacro', 'arg' (an undefined argument, named by ``subject``),
    'syntax', 'entity', 'package' (named by ``subject``), 'io', 'sandbox', 'outside' (a file
    outside the allowed roots, refused) or 'link' (a symbolic link in the repository leading
    outside it, not followed): the kinds of :class:`~urdftool.errors.LoadError`."""

    kind: str
    message: str
    location: Location
    subject: str | None = None
    certain: bool = True  # False: may not hold after the package's build (a file it installs)
    close: tuple = ()  # 'package': the packages found whose names are close to ``subject``
    melodic: bool = False  # read as ROS 1's xacro up to Melodic, relying on unprefixed tags
    # fails whatever values the xacro arguments have (a macro call under no condition giving a
    # parameter the macro lacks: xacro checks the names before any value)
    whatever_args: bool = False
    # 'package': the package.xml of the file's package declares it as a dependency
    declared: bool = False
    # 'xacro': it fails on a name the file uses and does not define (a property, a macro, a
    # property to forward), which a robot including it may define (:func:`_on_undefined`)
    undefined: bool = False
    # the parts of the message other findings say again ('package': PackageNotFound.repeated;
    # 'xacro': the names available, where a name is not known: urdftool.errors.available)
    repeated: tuple = ()


class Expansion(Record):
    """The expanded URDF with the source location of each element."""

    root: etree._Element
    locations: dict[etree._Element, Location]
    files: list[str]
    warnings: list[tuple[Location, str]]
    outside: list[tuple[Location, str]]

    __slots__ = ("root", "locations", "files", "warnings", "outside")

    def __init__(self, root: etree._Element, locations: dict[etree._Element, Location],
                 files: list[str], warnings: list[tuple[Location, str]] = NEW,
                 outside: list[tuple[Location, str]] = NEW) -> None:
        self.root = root
        self.locations = locations
        self.files = files
        self.warnings = [] if warnings is NEW else warnings
        self.outside = [] if outside is NEW else outside


class _Session:
    """State of one expansion: the files read and how to resolve packages and environment."""

    def __init__(self, resolver, allow_env: bool, read_file, roots=()):
        self.resolver = resolver
        self.allow_env = allow_env
        self.read_file = read_file
        self.roots = [files.real_path(root) for root in roots]
        self.paths: list[str] = []  # only ever appended to: an index names one file
        self.shown_paths: dict[int, str] = {}
        self.locations: dict[str, Location] = {}  # stamp -> where it was written
        self.places: dict[str, Location] = {}  # one part of a stamp -> its place
        self.call_sites: list[str] = []
        self.warnings: list[tuple[Location, str]] = []
        self.detached: dict[int, str] = {}  # macro-call node id -> the stamp lifted off it
        self.outside: list[tuple[Location, str]] = []
        self.elements = 0
        self.macro_calls = 0
        self.text = 0
        self.ros1_tags = False  # read unprefixed xacro tags as ROS 1's xacro up to Melodic did
        self.unprefixed: dict[int, tuple[str, str, int]] = {}  # file index -> (stamp, tag, count)
        self.renamed_tags = False  # one of xacro's own tags was read without its prefix

    def allow_root(self, folder) -> None:
        self.roots.append(files.real_path(folder))

    def within_roots(self, filename: str) -> bool:
        """Whether ``filename``, links followed, is in an allowed root (or there are none)."""
        real = files.real_path(filename)
        return not self.roots or any(
            real == root or real.startswith(root.rstrip(os.sep) + os.sep) for root in self.roots)

    def check_inside(self, filename: str, what: str) -> None:
        """Record (or, without environment access, refuse) a file outside the allowed roots."""
        if self.within_roots(filename):
            return
        where = self.current_location()
        shown = ", ".join(display_path(root) for root in self.roots)
        if not self.allow_env:
            raise _Outside(f"{what} '{display_path(filename)}' is outside the repository and the "
                           f"packages it uses ({shown}); refused under --no-env")
        self.outside.append((where, f"{what} '{display_path(filename)}' is outside the "
                                    f"repository and the packages it uses ({shown})"))

    def current_location(self) -> Location:
        return _failure_location(self, None, self.paths[0], frame=sys._getframe(1))

    def shown(self, index: int) -> str:
        """``paths[index]`` as the user reads it, worked out once (this runs for every element)."""
        if index not in self.shown_paths:
            self.shown_paths[index] = display_path(self.paths[index])
        return self.shown_paths[index]

    def file_index(self, path: str) -> int:
        self.paths.append(path)
        return len(self.paths) - 1

    def location(self, stamp: str) -> Location:
        """Where the element stamped ``stamp`` was written; worked out once per stamp (an
        element of a macro is reached again at every call)."""
        found = self.locations.get(stamp)
        if found is None:
            found = self.locations[stamp] = self._location(stamp)
        return found

    def _location(self, stamp: str) -> Location:
        places = [self._place(part) for part in stamp[len(_STAMP_PREFIX):].split(";")]
        if len(places) == 1:
            return places[0]
        return Location(places[0].file, places[0].line, tuple(places[1:]), places[0].column)

    def _place(self, part: str) -> Location:
        """One ``file-index:line[:column]`` of a stamp; a call site is in many stamps."""
        found = self.places.get(part)
        if found is None:
            index, line, column = (part.split(":") + [""])[:3]
            found = self.places[part] = Location(self.shown(int(index)), int(line),
                                                 column=int(column) if column else None)
        return found


class _StampingBuilder(ExpatBuilderNS):
    def __init__(self, index: int):
        super().__init__()
        self._index = index
        self._depth = 0

    def start_doctype_decl_handler(self, name, system_id, public_id, has_internal_subset):
        if system_id or public_id:
            raise XmlProblem("entity", external_dtd_message(system_id or public_id),
                             self._parser.CurrentLineNumber)
        super().start_doctype_decl_handler(name, system_id, public_id, has_internal_subset)

    def end_element_handler(self, name):
        self._depth -= 1
        super().end_element_handler(name)

    def install(self, parser):
        super().install(parser)

        def refuse_entity(name, *rest):
            raise XmlProblem("entity", entity_message(name), parser.CurrentLineNumber)

        parser.EntityDeclHandler = refuse_entity
        parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)

    def start_element_handler(self, name, attributes):
        line, column = self._parser.CurrentLineNumber, self._parser.CurrentColumnNumber + 1
        self._depth += 1
        if self._depth > MAX_DEPTH:
            raise XmlProblem("syntax", too_deep_message(), line)
        super().start_element_handler(name, attributes)
        node = self.curNode
        # An included file's root is replaced by its content, and xacro copies its xmlns:
        # attributes onto the include's parent, so only the top file's root is stamped.
        is_root = node.parentNode is self.document
        if (not is_root or self._index == 0) and node.tagName not in _UNSTAMPED:
            stamp = f"{_STAMP_PREFIX}{self._index}:{line}:{column}"
            if node.getAttributeNode(STAMP) is not None:
                node.setAttribute(STAMP, stamp)
                return
            # the attribute setAttribute makes, its local name given: minidom's own (parsed
            # with namespaces) have theirs, and one without it is asked by an AttributeError
            # each time it is stored, cloned with a macro's body or unlinked
            attribute = xml.dom.minidom.Attr(STAMP, localName=_STAMP_LOCAL)
            attribute.value = stamp
            attribute.ownerDocument = node.ownerDocument
            node.setAttributeNode(attribute)


def _parse_stamped(session: _Session, path: str, data: bytes) -> xml.dom.minidom.Document:
    builder = _StampingBuilder(session.file_index(path))
    try:
        doc = builder.parseString(data)
        if session.ros1_tags:
            _prefix_ros1_tags(session, doc)
        return doc
    except expat.ExpatError as error:
        problem = malformed(data, expat.ErrorString(error.code), error.lineno, error.offset + 1)
    except XmlProblem as refused:
        problem = refused
    except (LookupError, ValueError) as error:  # an unknown encoding= in the declaration
        problem = malformed(data, str(error), 1)
    raise XacroFailure(problem.kind, problem.message, Location(display_path(path), problem.line))


def _prefix_ros1_tags(session: _Session, doc) -> None:
    """Rename the unprefixed xacro tags of a parsed file as ROS 1's xacro up to Melodic read
    them (``<include>`` only without child elements, its is_include), and record where."""
    for element in list(doc.getElementsByTagName("*")):
        tag = element.tagName
        if tag not in ROS1_TAGS or tag == "include" and any(
                child.nodeType == xml.dom.Node.ELEMENT_NODE for child in element.childNodes):
            continue
        stamp = element.getAttribute(STAMP)
        _record_unprefixed(session, stamp, f"<{tag}>")
        session.renamed_tags = True
        element.tagName = element.nodeName = f"xacro:{tag}"
        if element.tagName in _UNSTAMPED and stamp:
            element.removeAttribute(STAMP)


def _record_unprefixed(session: _Session, stamp: str, what: str) -> None:
    if not stamp:
        return
    index = int(stamp[len(_STAMP_PREFIX):].split(":", 1)[0])
    first, shown, count = session.unprefixed.get(index, (stamp, what, 0))
    session.unprefixed[index] = (first, shown, count + 1)


def _unprefixed_warnings(session: _Session) -> list[tuple[Location, str]]:
    """One warning per file that relies on ROS 1's unprefixed xacro tags."""
    found = []
    for first, what, count in session.unprefixed.values():
        more = f" (and {count - 1} more in this file)" if count > 1 else ""
        found.append((session.location(first.split(";")[0]), (
            f"{what} without the xacro: prefix{more}: read here as ROS 1's xacro up to Melodic "
            "(1.13) read it, with a deprecation warning, since the package builds with catkin; "
            "xacro since Noetic (1.14) and ROS 2's xacro leave it in the output, and the robot "
            "loses what it does there. Prefix it: <xacro:...>")))
    return found


def _melodic_only(session: _Session) -> bool:
    """Whether a failure may be Melodic's reading alone: it read an element named as a macro
    without the xacro: prefix as a call (Gazebo's ``<camera>`` in a macro ``camera``). A file
    written with xacro's own tags unprefixed (``<property>``) is Melodic's: Noetic's xacro
    would leave them in the output, and that is no expansion of it."""
    return bool(session.unprefixed) and not session.renamed_tags


def _reads_ros1_tags(path: Path) -> bool:
    """Whether the file's package builds with catkin (ROS 1), so its consumers may run a
    xacro that reads unprefixed tags."""
    from urdftool.description.ros_version import package_build_tool

    found = package_build_tool(str(path))
    return found is not None and found[0] == 1


def _xacro():
    """The xacro library (imported where first used: a robot without xacro never pays for it,
    nor for the command line module its ``__init__`` imports)."""
    import xacro

    return xacro


def expand(path: Path, data: bytes, *, args: dict[str, str], resolver, allow_env: bool = True,
           read_file=None, roots=()) -> Expansion:
    """Expand the xacro document ``data`` read from ``path``; raises XacroFailure.

    roots: folders included and YAML files may be in; others are reported (refused when
    ``allow_env`` is false). Empty means anywhere. Folders of packages found are added.

    A catkin package's file is read as ROS 1's xacro up to Melodic read it (unprefixed tags
    and macro calls are xacro's). When xacro fails so, having read an element named as a macro
    as its call (and none of xacro's own tags unprefixed: :func:`_melodic_only`), and
    succeeds as Noetic's (1.14) and ROS 2's read the file, the robot is that expansion and
    Melodic's failure a warning: it depends on the ROS 1 distribution (curiosity_mars_rover's
    ``<camera name="camera">`` in the body of its macro ``camera``, for Noetic).
    """
    ros1 = _reads_ros1_tags(path)
    try:
        return _expand(path, data, args, resolver, allow_env, read_file, roots, ros1)
    except XacroFailure as error:
        if not error.melodic:
            raise
        failure = error
    try:
        expansion = _expand(path, data, args, resolver, allow_env, read_file, roots, False)
    except XacroFailure:
        raise failure from None
    expansion.warnings.insert(0, (failure.location, (
        f"ROS 1's xacro up to Melodic (1.13) fails here: {failure.message}, reading tags "
        "without the xacro: prefix as xacro's (the package builds with catkin); xacro since "
        "Noetic (1.14) and ROS 2's leave them in the output and expand the file, which is "
        "checked so: prefix xacro's tags (<xacro:...>) and rename what is not xacro's")))
    return expansion


def _expand(path: Path, data: bytes, args: dict[str, str], resolver, allow_env: bool,
            read_file, roots, ros1_tags: bool) -> Expansion:
    """One expansion (:func:`expand`), ``ros1_tags``: as ROS 1's xacro up to Melodic."""
    xacro = _xacro()
    from xacro import substitution_args

    read_file = read_file or files.read_regular
    session = _Session(resolver, allow_env, read_file, roots)
    session.ros1_tags = ros1_tags
    doc = _parse_stamped(session, str(path), data)
    stderr = _BoundedText(session)
    originals = {
        (xacro, "parse"): xacro.parse,
        (xacro, "handle_macro_call"): xacro.handle_macro_call,
        (xacro, "eval_all"): xacro.eval_all,
        (xacro, "check_attrs"): xacro.check_attrs,
        (substitution_args, "_eval_find"): substitution_args._eval_find,
        (substitution_args, "_eval_env"): substitution_args._eval_env,
        (substitution_args, "_eval_optenv"): substitution_args._eval_optenv,
        (xacro, "safe_eval"): xacro.safe_eval,
        (xacro, "eval_text"): xacro.eval_text,
        (xacro, "eval_extension"): xacro.eval_extension,
        (xacro, "get_include_files"): xacro.get_include_files,
        (xacro, "replace_node"): xacro.replace_node,
        (xacro, "remove_previous_comments"): xacro.remove_previous_comments,
        (substitution_args, "_eval"): substitution_args._eval,
    }
    replacements = _replacements(session, originals, xacro, substitution_args)
    saved_limit = sys.getrecursionlimit()
    saved_constructors = _yaml_constructors()
    saved_symbols = xacro_sandbox.harden_symbols(xacro._global_symbols)
    try:
        for (module, name), function in replacements.items():
            setattr(module, name, function)
        xacro.open = _yaml_opener(session)  # load_yaml's open(); shadows the builtin in xacro
        sys.setrecursionlimit(max(saved_limit, 20000))
        xacro.init_stacks(str(path))
        xacro.all_includes = []
        with contextlib.redirect_stderr(stderr):
            xacro.process_doc(doc, mappings=dict(args), verbosity=1)
        root, locations = _to_lxml(session, doc, Location(display_path(path), 1))
    except XacroFailure as failure:
        failure.melodic = _melodic_only(session)
        raise
    except RecursionError:
        where = _failure_location(session, sys.exc_info()[2], path)
        raise XacroFailure("xacro", "expansion nested too deeply (recursive macro or include?)",
                           where) from None
    except MemoryError:
        raise  # reported where expansion was (urdftool.budget), as over the memory budget
    except Exception as error:  # xacro raises many kinds; each becomes a located finding
        if _caused_by(error, MemoryError):
            raise MemoryError(str(error)) from None
        failure = _as_failure(session, error, path, doc)
        failure.melodic = _melodic_only(session)
        raise failure from None
    finally:
        for (module, name), function in originals.items():
            setattr(module, name, function)
        del xacro.open
        xacro_sandbox.restore_symbols(saved_symbols)
        _restore_yaml_constructors(saved_constructors)
        sys.setrecursionlimit(saved_limit)
        xacro.init_stacks(None)
        xacro.substitution_args_context.clear()
    budget.working_at(None)
    warnings = (session.warnings + _unprefixed_warnings(session)
                + [(_written_use(session, where, message), message) for where, message in
                   _warnings(stderr.getvalue(), display_path(path), stderr.places)])
    return Expansion(root, locations, list(dict.fromkeys(session.paths)), warnings,
                     session.outside)


def _yaml_opener(session: _Session):
    """``open`` for xacro.load_yaml: allowed roots, regular files, the size limit, UTF-8."""

    def open_yaml(filename, *args, **kwargs):
        if not os.path.basename(str(filename)).strip():  # ('' is the macro's folder to xacro)
            raise _Unreadable(errno.EISDIR, "load_yaml was given no file name" + (
                f" ('{display_path(filename)}', a folder: a file name or argument left empty?)"
                if str(filename).strip() else ""))
        spec, filename = filename, _installed(session, filename)
        session.check_inside(filename, "YAML file")
        try:
            data = session.read_file(filename, "yaml")
        except OSError as error:
            unsure = _unsure(session, filename, error, "YAML file")
            if unsure:
                raise unsure from None
            raise _Unreadable(error.errno, _not_read(
                error, filename, f"YAML file '{display_path(spec)}'",
                written=display_path(spec))) from None
        session.paths.append(filename)
        text = data.decode("utf-8", errors="replace")
        xacro_sandbox.refuse_yaml_bomb(text, display_path(filename))
        return io.StringIO(text)

    return open_yaml




class _BoundedText(io.StringIO):
    """xacro's stderr: keeps the first MAX_MESSAGES characters (``xacro.warning`` in a loop),
    and where the expansion was when each piece was written (``places``: offset -> Location):
    xacro's own warnings (a deprecation: ``load_yaml()`` without ``xacro.``) say no line."""

    def __init__(self, session=None):
        super().__init__()
        self.session, self.places = session, {}

    def write(self, text):
        room = MAX_MESSAGES - self.tell()
        if room > 0:
            if self.session is not None and self.session.paths and text.strip():
                where = _failure_location(self.session, None, self.session.paths[0],
                                          frame=sys._getframe(1))
                if where.line is not None:
                    self.places[self.tell()] = where
            super().write(text[:room])
        return len(text)


def _yaml_constructors():
    """yaml.SafeLoader's own constructor table, to restore after the expansion without xacro's
    unit tags: xacro.load_yaml adds ``!degrees`` and the like to every later safe_load,
    evaluated with whatever ``xacro.safe_eval`` is at the time (xacro's own, outside)."""
    import xacro
    import yaml

    own = yaml.SafeLoader.__dict__.get("yaml_constructors")
    units = {unit.value.tag for unit in xacro.ConstructUnits}
    return None if own is None else {tag: make for tag, make in own.items() if tag not in units}


def _restore_yaml_constructors(saved) -> None:
    import yaml

    if saved is not None:
        yaml.SafeLoader.yaml_constructors = saved
    elif "yaml_constructors" in yaml.SafeLoader.__dict__:
        del yaml.SafeLoader.yaml_constructors


def _replacements(session: _Session, originals, xacro, substitution_args):
    original_macro_call = originals[(xacro, "handle_macro_call")]
    original_eval_all = originals[(xacro, "eval_all")]
    original_check_attrs = originals[(xacro, "check_attrs")]
    original_eval_text = originals[(xacro, "eval_text")]
    original_eval_extension = originals[(xacro, "eval_extension")]
    splicer = _Splicer()

    def parse(inp, filename=None):
        if inp is not None:
            return xml.dom.minidom.parseString(inp) if isinstance(inp, str) else inp
        stack = [files.real_path(f) for f in xacro.filestack[:-1] if f]
        if files.real_path(filename) in stack:
            chain = " -> ".join(display_path(f) for f in [*xacro.filestack])
            raise xacro.XacroException(f"include cycle: {chain}")
        _refuse_link_out(session, filename)
        session.check_inside(filename, "included file")
        try:
            data = session.read_file(filename)
        except OSError as error:
            xacro.filestack.pop()
            # an OSError still (xacro skips an optional include by it), said once, plainly
            raise xacro.XacroException(exc=_unread_include(
                session, filename, error, xacro.filestack[-1] if xacro.filestack else None)
            ) from error
        return _parse_stamped(session, filename, data)

    def handle_macro_call(node, macros, symbols):
        if not node.tagName.startswith("xacro:"):
            if not (session.ros1_tags and _is_macro(xacro, node.tagName, macros, symbols)):
                return False  # xacro asks this of every element; only xacro: tags are calls
            _record_unprefixed(session, node.getAttribute(STAMP), f"macro call <{node.tagName}>")
            node.tagName = node.nodeName = f"xacro:{node.tagName}"
        call_site = node.getAttribute(STAMP) if node.hasAttribute(STAMP) else None
        if call_site:
            node.removeAttribute(STAMP)
            session.detached[id(node)] = call_site
        session.macro_calls += 1
        if session.macro_calls > MAX_MACRO_CALLS:
            raise xacro_sandbox.SandboxViolation(
                f"expansion made over {MAX_MACRO_CALLS} macro calls (a macro bomb?)")
        if len(xacro.macrostack) >= MAX_MACRO_DEPTH:
            raise xacro.XacroException(
                f"macro calls nested deeper than {MAX_MACRO_DEPTH}: recursive macro "
                f"'{node.tagName}' without a terminating condition?")
        if call_site:
            session.call_sites.append(call_site[len(_STAMP_PREFIX):].split(";")[0])
        try:
            handled = original_macro_call(node, macros, symbols)
        finally:
            if call_site:
                session.call_sites.pop()
        # Kept only while an error propagates: a freed node's id may be reused.
        session.detached.pop(id(node), None)
        return handled

    def eval_all(node, macros, symbols):
        session.elements += 1
        if session.elements > MAX_ELEMENTS:
            raise xacro_sandbox.SandboxViolation(
                f"expansion produced over {MAX_ELEMENTS} elements (a macro bomb?)")
        stamp = node.getAttribute(STAMP) if node.nodeType == xml.dom.Node.ELEMENT_NODE else ""
        if stamp:
            if session.call_sites and ";" not in stamp:
                stamp = ";".join([stamp, *reversed(session.call_sites)])
                node.setAttribute(STAMP, stamp)
            # where a time or memory budget (urdftool.budget) finds the expansion if it stops
            budget.working_at(session.location(stamp))
        return original_eval_all(node, macros, symbols)

    def check_attrs(tag, required, optional):
        # xacro prints unknown attributes of its own tags without a line; report them located
        # and hand xacro the tag without them (it reads only the known ones).
        extra = [name for name in tag.attributes.keys()
                 if name not in (*required, *optional) and not name.startswith("xmlns:")]
        if extra:
            stamp = _nearest_stamp(tag)
            where = session.location(stamp) if stamp else Location(display_path(session.paths[0]))
            session.warnings.append((where, f"<{tag.tagName}> has unknown attribute(s) "
                                            f"{', '.join(extra)}; xacro ignores them (known: "
                                            f"{', '.join([*required, *optional])})"))
            for name in extra:
                tag.removeAttribute(name)
        return original_check_attrs(tag, required, optional)

    def eval_text(text, symbols):
        if text.startswith(_STAMP_PREFIX):  # a location stamp: nothing to substitute, no lexing
            return text
        # Without a '$', xacro's lexer finds one text token and returns the text as it is.
        result = original_eval_text(text, symbols) if "$" in text else text
        return charge_text(result, "substitution") if isinstance(result, str) else result

    def charge_text(result, what: str):
        if isinstance(result, str):
            size = len(result)
        else:
            size = xacro_sandbox.weight(result, MAX_TEXT)
        session.text += size
        if size > xacro_sandbox.MAX_SEQUENCE or session.text > MAX_TEXT:
            raise xacro_sandbox.SandboxViolation(
                f"{what} produced {size} characters (limits: "
                f"{xacro_sandbox.MAX_SEQUENCE} per value, {MAX_TEXT} in all)")
        return result

    def safe_eval(expression, symbols, locals=None):
        return charge_text(xacro_sandbox.safe_eval(expression, symbols, locals), "expression")

    def eval_extension(text):
        return charge_text(original_eval_extension(text), "substitution")

    def get_include_files(filename_spec, symbols):
        # xacro's own, but a pattern is expanded by _expand_pattern instead of glob.glob
        try:
            spec = xacro.abs_filename_spec(xacro.eval_text(filename_spec, symbols))
        except xacro.XacroException as error:
            if error.exc and isinstance(error.exc, NameError) and symbols is None:
                raise xacro.XacroException(
                    "variable filename is supported with in-order option only") from None
            raise
        filenames = [_installed(session, spec)]
        if _MAGIC.search(spec):
            filenames = _expand_pattern(session, _installed(session, spec))
            if not filenames:
                xacro.warning(xacro.include_no_matches_msg.format(spec))
        for filename in filenames:
            xacro.all_includes.append(filename)
            yield filename

    def eval_substitution(expression, context):
        args = context.setdefault("arg", {})
        functions = dict(_EVAL_CONSTANTS)
        functions.update(
            arg=lambda name: substitution_args.convert_value(
                substitution_args._eval_arg(name, args=args), "auto"),
            dirname=lambda: substitution_args._eval_dirname(context.get("filename")),
            env=eval_env, optenv=eval_optenv, find=eval_find)
        return xacro_sandbox.eval_substitution(expression, functions, args)

    def eval_find(package):
        try:
            found = session.resolver.find(package)
        except PackageNotFound as error:
            from urdftool.description.packages import declaring_package

            owner, declares, manifest = declaring_package(
                xacro.filestack[-1] if xacro.filestack else None, package)
            raise _PackageFailure(error.declared(owner, declares, manifest=manifest) if owner
                                  else error) from None
        session.allow_root(found)
        return str(found)

    def eval_env(name):
        if not session.allow_env:
            raise substitution_args.SubstitutionException(
                f"$(env {name}) is disabled by --no-env")
        value = files.environ(name)  # as xacro's own, recorded
        if value is None:
            raise substitution_args.SubstitutionException(
                f"environment variable '{name}' is not set")
        return value

    def eval_optenv(name, default=""):
        if not session.allow_env:  # the robot as an environment without NAME makes it: the
            return default  # default, the environment never read (an error was a false one)
        value = files.environ(name)  # recorded
        return default if value is None else value

    return {
        (xacro, "parse"): parse,
        (xacro, "handle_macro_call"): handle_macro_call,
        (xacro, "eval_all"): eval_all,
        (xacro, "check_attrs"): check_attrs,
        (xacro, "eval_text"): eval_text,
        (xacro, "eval_extension"): eval_extension,
        (xacro, "get_include_files"): get_include_files,
        (xacro, "safe_eval"): safe_eval,
        (xacro, "replace_node"): splicer,
        (xacro, "remove_previous_comments"): splicer.remove_previous_comments,
        (substitution_args, "_eval"): eval_substitution,
        (substitution_args, "_eval_find"): eval_find,
        (substitution_args, "_eval_env"): eval_env,
        (substitution_args, "_eval_optenv"): eval_optenv,
    }


class _Splicer:
    """xacro's ``xmlutils.replace_node(node, by, content_only)`` (``node`` replaced by ``by``, or
    by its children), done as one splice of the parent's children where minidom's
    ``insertBefore`` looks each inserted node's place up from the first child (``list.index``,
    a comparison per sibling) and ``removeChild`` the node's: a robot's macro calls one after
    another cost the square of their number (19,000 flat calls: 20 s; a macro calling itself
    twice 11 deep, 4,096 links: 20 s). The place is looked for from where the last splice in
    that parent ended (xacro expands in document order), and from the first child only when
    it is not there (a few places before it first). The same tree as minidom makes: the nodes,
    their order, parent and sibling links; a fragment's children inserted, each node taken
    from where it was."""

    def __init__(self):
        self.hint: dict[int, tuple[object, int]] = {}  # id(parent) -> (parent, index)

    def __call__(self, node, by, content_only: bool = False) -> None:
        parent = node.parentNode
        new = []
        for doc in [] if by is None else by if isinstance(by, list) else [by]:
            new.extend(tuple(doc.childNodes) if content_only else (doc,))
        flat = []
        for child in new:
            fragment = child.nodeType == child.DOCUMENT_FRAGMENT_NODE
            flat.extend(tuple(child.childNodes) if fragment else (child,))
        for child in flat:
            if child.nodeType not in parent._child_node_types:
                raise xml.dom.HierarchyRequestErr(f"{child!r} cannot be child of {parent!r}")
            if child.parentNode is not None:
                child.parentNode.removeChild(child)  # (a macro's body, an include: small)
        siblings = parent.childNodes
        index = self._place(parent, siblings, node)
        siblings[index:index + 1] = flat
        previous = siblings[index - 1] if index else None
        for child in flat:
            child.parentNode, child.previousSibling = parent, previous
            if previous is not None:
                previous.nextSibling = child
            previous = child
        end = index + len(flat)
        after = siblings[end] if end < len(siblings) else None
        if previous is not None:
            previous.nextSibling = after
        if after is not None:
            after.previousSibling = previous
        node.parentNode = node.previousSibling = node.nextSibling = None
        xml.dom.minidom._clear_id_cache(parent)
        self.hint[id(parent)] = (parent, end)

    def insert_before(self, child, ref) -> None:
        """minidom's ``ref.parentNode.insertBefore(child, ref)`` by splices: ``child`` taken
        from where it was, put before ``ref``."""
        if child.parentNode is not None:
            self(child, None)
        parent = ref.parentNode
        siblings = parent.childNodes
        index = self._place(parent, siblings, ref)
        siblings[index:index] = [child]
        previous = siblings[index - 1] if index else None
        child.parentNode, child.previousSibling, child.nextSibling = parent, previous, ref
        ref.previousSibling = child
        if previous is not None:
            previous.nextSibling = child
        xml.dom.minidom._clear_id_cache(parent)

    def remove_previous_comments(self, node) -> None:
        """xacro's ``remove_previous_comments(node)`` (the comments just before a xacro element
        dropped, and its one blank text node moved after the element to stop the next call
        there), its removals and its move done by splices: minidom's looked the blank's old and
        new places up from the first child, once each per macro call."""
        import xacro

        after = node.nextSibling
        previous = node.previousSibling
        while previous:
            text = previous.nodeType == xml.dom.Node.TEXT_NODE
            # line ends: xacro's own (a blank of at most one LF is skipped, as xacro counts it)
            if text and previous.data.isspace() and previous.data.count("\n") <= 1:
                previous = previous.previousSibling
            if previous and previous.nodeType == xml.dom.Node.COMMENT_NODE:
                comment = previous
                previous = previous.previousSibling
                self(comment, None)
            else:
                if after and xacro._empty_text_node is not after:
                    self.insert_before(xacro._empty_text_node, after)
                return

    def _place(self, parent, siblings, node) -> int:
        known, start = self.hint.get(id(parent), (None, 0))
        if known is parent:
            try:  # (a few before it too: the blank moved just before a call, its comments)
                return siblings.index(node, max(start - 16, 0))
            except ValueError:
                pass
        return siblings.index(node)


# What $(eval ...) offers besides arg, dirname, env, optenv and find: xacro's substitution_args
# names (math, true/false) and the built-ins it meant to allow, with ${}'s common ones.
_EVAL_CONSTANTS = {
    **{name: value for name, value in vars(math).items() if not name.startswith("_")},
    "true": True, "false": False, "True": True, "False": False,
    **{name: getattr(builtins, name) for name in (
        "list", "dict", "map", "str", "float", "int", "len", "bool", "min", "max", "round", "abs")},
}


def _is_macro(xacro, name: str, macros, symbols) -> bool:
    """Whether ``name`` calls a macro defined so far (ROS 1's xacro up to Melodic called macros
    without the xacro: prefix)."""
    try:
        xacro.resolve_macro(name, macros, symbols)
    except (KeyError, TypeError, AttributeError):
        return False
    return True


def _refuse_link_out(session: _Session, filename: str) -> None:
    """XacroFailure 'link' when ``filename``, as named, is in the input's repository but a
    symbolic link on the way leads outside it: not followed, whatever ``--no-env`` says."""
    from urdftool.description.packages import containment_root

    root = containment_root(os.path.dirname(os.path.abspath(session.paths[0])))
    named = os.path.abspath(filename)
    lexically_inside = any(named.startswith(base.rstrip(os.sep) + os.sep)
                           for base in (str(root), files.real_path(root)))
    if lexically_inside and not files.inside(filename, root):
        raise XacroFailure("link", (
            f"included file '{display_path(filename)}' is a symbolic link leading outside "
            f"the repository ({display_path(root)}); not followed"), session.current_location())


def _written_from_elsewhere(session: _Session, filename: str, including: str | None) -> str:
    """Advice for an include xacro could not open beside the file including it when the path
    as written is there from a folder above (inside the repository): written for a tool run
    from that folder (Upkie's ``xacro/utils/box_inertia.xacro``, for xacrodoc run from the
    repository root by its Makefile), which reads it: the failure is then not certain (a
    warning when checked). "" otherwise."""
    from urdftool.description.packages import containment_root, written_from_above

    if not including:
        return ""
    base = os.path.dirname(os.path.abspath(including))
    named = os.path.abspath(filename)
    if not named.startswith(base + os.sep):
        return ""  # an absolute or upward path: written as meant
    written = named[len(base) + 1:]
    folder = written_from_above(base, written, above=True)
    if folder is None:
        return ""
    where = "the repository's root" if folder == os.fspath(containment_root(Path(base))) \
        else f"'{display_path(folder)}'"
    return (f" (xacro reads an include beside the file including it; '{written}' is there "
            f"from {where}, as a tool run from that folder reads it: write the path from the "
            "including file, or $(find PKG)/...)")


class _Unreadable(OSError):
    """A file xacro could not read, said as its message (an OSError says "[Errno 2] REASON:
    'PATH'")."""

    def __str__(self) -> str:
        return self.strerror


class _Unsure(_Unreadable):
    """A file below a package missing from the source tree, whose package's install rules
    could not be read: it may exist after the build (a load error that is not certain)."""


def _not_read(error: OSError, filename: str, subject: str, where: str = "",
              written: str = "") -> str:
    """What reading ``filename`` met, said of ``subject`` (``xacro:include 'SPEC'``): "SUBJECT
    not found WHERE (looked at PATH)" for a file missing, the place left out when ``written``
    (the path as the file writes it) already says it; else "SUBJECT: REASON: PATH"."""
    shown = display_path(filename)
    if error.errno != errno.ENOENT:
        return f"{subject}: {error.strerror}" + ("" if written == shown else f": {shown}")
    return f"{subject} not found{where}" + ("" if written == shown else f" (looked at {shown})")


def _unread_include(session: _Session, filename: str, error: OSError,
                    including: str | None) -> _Unreadable:
    """The error of an include xacro could not read (``filename``, included by ``including``),
    as a reader reads it: the include as written (the ``filename`` of the ``xacro:include``
    being done), what reading met and where it looked (:func:`_not_read`), and why when it is
    known; an :class:`_Unsure` when the file may be there where it is built (its package's
    install rules, ``$(cwd)``, a tool run from a folder above)."""
    spec = _spec_included()
    subject = f"xacro:include '{spec}'" if spec else "included file"
    unsure = _unsure(session, filename, error, subject) or _from_cwd(
        session, filename, error, including, subject)
    if unsure:
        return unsure
    if "package:/" in filename:  # package://: a path by now, its // made one /
        from urdftool.description.packages import find_form

        instead = f"'{find_form(spec)}'" if spec.startswith("package://") else "$(find PKG)/..."
        return _Unreadable(error.errno, f"{subject}: xacro:include does not resolve package:// "
                                        f"URIs; write {instead}")
    said = _not_read(error, filename, subject, written=spec)
    hint = _written_from_elsewhere(session, filename, including)
    if hint:  # a tool run from that folder reads it (upkie's xacrodoc): not certain
        return _Unsure(error.errno, said + hint)
    empty = _empty_arguments(spec) if error.errno == errno.ENOENT else []
    if empty:  # a path with nothing where it names an argument: say which
        said += (f"; the include's filename names argument '{empty[0]}', which is empty "
                 f"here: pass {empty[0]}:=VALUE")
    elif spec.startswith("/") and error.errno == errno.ENOENT:  # uned_crazyflie_ros_pkg's
        said += ("; the include names an absolute path, there only on the machine it was "
                 "written on: name the file relative to this one, or $(find PKG)/...")
    return _Unreadable(error.errno, said)


def _spec_included() -> str:
    """The filename, as written, of the include xacro is doing ("" when none): the innermost
    ``xacro.process_include``'s ``filename_spec``, read from the frames that called."""
    frame = sys._getframe(1)
    while frame is not None:
        if frame.f_code.co_name == "process_include":
            value = frame.f_locals.get("filename_spec")
            return value if isinstance(value, str) else ""
        frame = frame.f_back
    return ""


def _from_cwd(session: _Session, filename: str, error: OSError,
              including: str | None, subject: str) -> _Unsure | None:
    """``error`` as not certain when the include was written with ``$(cwd)`` (the folder xacro
    runs from, here urdftool's) and the path after it is there from a folder above the
    including file: the robot is built from that folder (ridgeback-baxter's
    ``$(cwd)/src/baxter/...``, for xacro run from its catkin workspace). None otherwise."""
    here = os.getcwd()
    if not including or not filename.startswith(here + os.sep):
        return None
    try:
        if b"$(cwd)" not in session.read_file(including):
            return None
    except OSError:
        return None
    from urdftool.description.packages import written_from_above

    folder = written_from_above(os.path.dirname(os.path.abspath(including)),
                                filename[len(here) + 1:], skip=here)
    if folder is None:
        return None
    return _Unsure(error.errno, f"{_not_read(error, filename, subject)}: written with $(cwd), "
                                f"the folder xacro runs from; it is there when xacro runs from "
                                f"'{display_path(folder)}'")


def _unsure(session: _Session, filename: str, error: OSError, subject: str) -> _Unsure | None:
    """``error`` reading ``filename`` (``subject``: what it is) as not certain, when the
    package's build may install the file (its install rules could not be read); None when it
    is certainly missing."""
    doubt = session.resolver.locate(filename).doubt if session.resolver else None
    if not doubt:
        return None
    return _Unsure(error.errno, f"{_not_read(error, filename, subject, ' in the source tree')}; "
                                f"{doubt}")


def _installed(session: _Session, spec: str) -> str:
    """``spec`` (a file, or an include pattern) where the source tree has it: a path below a
    package ``$(find)`` resolved names the installed ``share/NAME``, which the package's build
    may fill from other folders (:meth:`PackageResolver.locate`); for a pattern, the folder
    before its first wildcard is looked for so."""
    if session.resolver is None:
        return spec
    parts = spec.split("/")
    first = next((i for i, part in enumerate(parts) if _MAGIC.search(part)), len(parts))
    base = "/".join(parts[:first])
    if not base:
        return spec
    found = os.fspath(session.resolver.locate(base).path)
    return spec if found == base else "/".join([found, *parts[first:]])


def _expand_pattern(session: _Session, spec: str) -> list[str]:
    """The files an include's glob pattern names, as ``sorted(glob.glob(spec))`` finds them
    (``*``, ``?``, ``[...]`` in any part; a name starting with ``.`` only for a part that does;
    ``**`` is ``*``), decided before anything is listed: the folder before the first wildcard
    must be in the repository or a package used (:meth:`_Session.check_inside`: refused under
    --no-env, else a warning), not reached through a link in the repository leading outside
    it, and no ``..`` may follow a wildcard. The walk never enters a linked folder that leads
    outside the allowed roots, looks at MAX_PATTERN_ENTRIES entries at most, and no message
    names what it found outside (a matched link leading out is refused when it is read,
    without saying where it leads)."""
    parts = spec.split("/")
    first = next(i for i, part in enumerate(parts) if _MAGIC.search(part))
    if ".." in parts[first:]:
        raise xacro_sandbox.SandboxViolation(
            f"include pattern '{spec}' climbs ('..') after a wildcard; not expanded")
    base = "/".join(parts[:first]) or ("/" if spec.startswith("/") else ".")
    _refuse_link_out(session, base)
    session.check_inside(base, "include pattern folder")
    anywhere = not session.within_roots(base)  # --allow-env, outside: already reported
    folders, seen = [base if first else ""], 0
    for index, part in enumerate(parts[first:], start=first):
        last = index == len(parts) - 1
        found = []
        for folder in folders:
            here = folder or "."
            if not _MAGIC.search(part):
                candidate = os.path.join(folder, part) if folder else part
                if files.kind_of(candidate, follow=False) if last else \
                        files.kind_of(candidate) == "folder":
                    found.append(candidate)
                continue
            entries = files.listing(here)  # (name, kind as lstat says), sorted; recorded
            seen += len(entries)
            if seen > MAX_PATTERN_ENTRIES:
                raise xacro_sandbox.SandboxViolation(
                    f"include pattern '{spec}' looked at over {MAX_PATTERN_ENTRIES} files; "
                    "not expanded")
            for name, kind in entries:
                if name.startswith(".") and not part.startswith("."):
                    continue
                if not fnmatch.fnmatchcase(name, part):
                    continue
                path = os.path.join(folder, name) if folder else name
                is_dir = kind == "folder" or kind == "link" and files.kind_of(path) == "folder"
                if not last and not (is_dir and (
                        anywhere or kind != "link" or session.within_roots(path))):
                    continue  # a file, or a linked folder leading out: never listed
                found.append(path)
        folders = found
    return sorted(folders)


class _Outside(Exception):
    """A file outside the allowed roots, refused."""


class _PackageFailure(Exception):
    def __init__(self, error: PackageNotFound):
        super().__init__(str(error))
        self.error = error


def _as_failure(session: _Session, error: Exception, path: Path, doc=None) -> XacroFailure:
    where = _failure_location(session, error.__traceback__, path)
    cause = error
    while cause is not None and not isinstance(cause, (_PackageFailure, _Outside,
                                                       xacro_sandbox.SandboxViolation)):
        cause = getattr(cause, "exc", None) or cause.__context__
    if isinstance(cause, _PackageFailure):
        # a package not installed here: the environment's (a dependency declared, another
        # repository's, or a misspelt name: the message says which it seems), never certain
        return XacroFailure("package", str(cause.error), where, subject=cause.error.name,
                            certain=False, close=cause.error.close,
                            declared=cause.error.declared_by is not None,
                            repeated=cause.error.repeated)
    if isinstance(cause, _Outside):
        return XacroFailure("outside", str(cause), where)
    if isinstance(cause, xacro_sandbox.SandboxViolation):
        return XacroFailure("sandbox", str(cause), where)
    if _caused_by(error, _Unsure):
        return XacroFailure("io", " ".join(str(error).split()), where, certain=False)
    message = _said(" ".join(str(error).split())) or type(error).__name__
    argument = None
    if message.startswith("Undefined substitution argument"):  # the caller says how to pass it
        # "Undefined substitution argument NAME[ when evaluating expression '...']"
        argument = message[len("Undefined substitution argument"):].split()[0]
    if "when evaluating expression" not in message and isinstance(error, (NameError, TypeError)):
        message = f"{type(error).__name__}: {message}"
    undefined = _undefined_name(error)
    if undefined:
        message += "; " + available("properties", undefined, _visible_properties(error))
    lacking = _UNDEFINED_PARAMETERS.fullmatch(message)
    if lacking:  # xacro names the parameters, not what they lack
        names = [name.strip() for name in lacking.group(1).split(",") if name.strip()]
        message += (f": the macro called here{_called_macro_name(error)} has "
                    f"{', '.join(names)} without a default, and the "
                    f"call gives {'it' if len(names) == 1 else 'them'} no value; pass "
                    f"{names[0] if names else 'it'}=\"...\"")
    later = ""
    if message.startswith("unknown macro name: xacro:") and doc is not None:
        later = _defined_later(session, doc, message.split("xacro:", 1)[1].strip())
        message += later
    if later and session.ros1_tags:  # a catkin package: ROS 1 up to Lunar may expand it
        message += ("; not certain for a catkin package: ROS 1's xacro up to Lunar (Kinetic's) "
                    "expands it in that order by default")
        return XacroFailure("xacro", str(message), where, certain=False,
                            repeated=getattr(message, "repeated", ()))
    invalid = _INVALID_PARAMETER.fullmatch(message)
    if invalid:  # xacro names the attribute, not what the macro takes
        message += (f"; the macro called here{_called_macro_name(error)} takes no parameter of "
                    "that name: ") + available(
            "parameters", invalid.group(1), _called_macro_params(error))
    return XacroFailure("arg" if argument else "xacro", str(message), where, subject=argument,
                        whatever_args=bool(invalid) and not _under_condition(error.__traceback__),
                        undefined=not argument and _on_undefined(error),
                        repeated=getattr(message, "repeated", ()))  # (an available list's)


# what xacro says when a macro, or a property to forward, is not defined (its own words, never
# the file's: read from the exception it raised, not from the message a name may be part of)
_UNDEFINED_SAID = ("unknown macro name", "Undefined property to forward")


def _on_undefined(error: Exception) -> bool:
    """Whether xacro failed on a name the file uses and does not define: a property or a name
    of an expression (a NameError, xacro's or Python's), a macro, a property to forward. Read
    from the exceptions xacro raised (each wrapping the next), where the loading rules read
    the message's words before (a file named 'x is not defined.xacro' was such a failure)."""
    import xacro

    cause = error
    while cause is not None:
        if isinstance(cause, NameError):
            return True
        if isinstance(cause, xacro.XacroException) and cause.args and \
                isinstance(cause.args[0], str) and cause.args[0].startswith(_UNDEFINED_SAID):
            return True
        cause = getattr(cause, "exc", None) or cause.__context__
    return False


_ARGUMENT_USE = re.compile(r"\$\(arg\s+([^\s)]+)\)")


def _empty_arguments(spec: str) -> list[str]:
    """The xacro arguments an include's filename ``spec`` names (``$(arg NAME)``, as written)
    whose value is empty: Interbotix's locobot built without ``arm_model`` includes
    ``arms/.urdf.xacro``, which xacro reports only as not found."""
    arguments = _xacro().substitution_args_context.get("arg") or {}
    return [name for name in dict.fromkeys(_ARGUMENT_USE.findall(spec))
            if arguments.get(name) == ""]


_CONDITIONS = ("xacro:if", "xacro:unless", "if", "unless")


def _under_condition(traceback) -> bool:
    """Whether an element xacro was working on when it raised, or one holding it (the calls
    of the macros it is in, each a frame), is an ``xacro:if``/``xacro:unless``: whether other
    argument values could leave the failing element unexpanded."""
    while traceback is not None:
        for name in ("node", "elt"):
            node = traceback.tb_frame.f_locals.get(name)
            while isinstance(node, xml.dom.Node):
                if node.nodeType == xml.dom.Node.ELEMENT_NODE and node.tagName in _CONDITIONS:
                    return True
                node = node.parentNode
        traceback = traceback.tb_next
    return False


_UNDEFINED_PARAMETERS = re.compile(r"Undefined parameters \[(.*)\]")
_INVALID_PARAMETER = re.compile(r'Invalid parameter "(.*)"')


def _called_macro_name(error: Exception) -> str:
    """`` ('NAME')``, the name of the macro a call failed in (xacro's
    ``XacroException(..., macro=m)``: its definition, ``m.body``, says it), or "" when unknown:
    the line points at the call, and a file calling many macros there (one per line, or a
    call spread over lines) left the reader to find which."""
    cause = error
    while cause is not None:
        for macro in getattr(cause, "macros", None) or ():
            body = getattr(macro, "body", None)
            name = body.getAttribute("name") if hasattr(body, "getAttribute") else ""
            return f" ('{name}')" if isinstance(name, str) and name else ""
        cause = getattr(cause, "exc", None) or cause.__context__
    return ""


def _called_macro_params(error: Exception) -> list[str]:
    """The parameter names of the macro a call gave an attribute it lacks (xacro's
    ``XacroException(..., macro=m)``, innermost first)."""
    cause = error
    while cause is not None:
        for macro in getattr(cause, "macros", None) or ():
            return [name for name in getattr(macro, "params", ()) if isinstance(name, str)]
        cause = getattr(cause, "exc", None) or cause.__context__
    return []


def _defined_later(session: _Session, doc, name: str) -> str:
    """Where a macro used before its definition is defined further on, with why that fails."""
    for element in doc.getElementsByTagName("xacro:macro"):
        if element.getAttribute("name") == name:  # unstamped (_UNSTAMPED): its body is
            body = [e.getAttribute(STAMP) for e in element.getElementsByTagName("*")
                    if e.hasAttribute(STAMP)]
            where = session.location(body[0].split(";")[0]) if body else None
            at = f" (its body begins at {where.file}:{where.line})" if where and where.line else ""
            return (f"; it is defined further on{at}: xacro expands in document order since "
                    "Melodic (1.13), and only the legacy order (xacro up to Lunar, or Melodic's "
                    "--legacy) read every definition first. Move the definition (or its include) above the first use")
    return ""


def _caused_by(error: BaseException, kind: type) -> bool:
    """Whether ``error`` is, or wraps (xacro's ``exc``, or as context), an error of ``kind``."""
    while error is not None and not isinstance(error, kind):
        error = getattr(error, "exc", None) or error.__context__
    return error is not None


def _undefined_name(error: Exception) -> str | None:
    """The property name of a NameError that xacro wrapped, if that is what failed."""
    cause = error
    while cause is not None and not isinstance(cause, NameError):
        cause = getattr(cause, "exc", None) or cause.__context__
    return getattr(cause, "name", None) if cause is not None else None


def _visible_properties(error: Exception) -> set[str]:
    """Property names defined where the expression failed (xacro's symbol tables in the
    traceback), without xacro's own built-in symbols."""
    import xacro

    names: set[str] = set()
    traceback = error.__traceback__
    while traceback is not None:
        table = traceback.tb_frame.f_locals.get("symbols")
        while isinstance(table, xacro.Table):
            names.update(k for k in table if not k.startswith(("*", "_")))
            table = table.parent
        traceback = traceback.tb_next
    return names - set(xacro._global_symbols)


def _said(message: str) -> str:
    """xacro's message for an exception its substitution arguments raise, as a reader reads it:
    xacro writes ``f"{type(e)}: {e}"`` and then ``e`` again ("<class 'xacro.substitution_args.
    SubstitutionException'>: Unknown substitution command [x]. ... Unknown substitution command
    [x]. ..."); the class by its name, the text once."""
    match = _CLASS_SAID.match(message)
    if match is None:
        return message
    said = match.group(2)
    half = (len(said) - 1) // 2
    if said[half:half + 1] == " " and said[:half] == said[half + 1:]:
        said = said[:half]
    return f"{match.group(1)}: {said}"


_CLASS_SAID = re.compile(r"<class '(?:[\w.]+\.)?(\w+)'>: (.*)", re.S)


def _failure_location(session: _Session, traceback, path, frame=None) -> Location:
    """The innermost element xacro was working on when it raised, from the traceback frames
    (or, given ``frame``, from the frames of the stack that called it)."""
    frames = []
    while traceback is not None:
        frames.append(traceback.tb_frame)
        traceback = traceback.tb_next
    frames.reverse()
    while frame is not None:
        frames.append(frame)
        frame = frame.f_back
    for frame in frames:
        for name in ("node", "elt"):
            node = frame.f_locals.get(name)
            stamp = _nearest_stamp(node, session.detached)
            if stamp:
                return session.location(stamp)
        call_site = frame.f_locals.get("call_site")
        if isinstance(call_site, str) and call_site.startswith(_STAMP_PREFIX):
            return session.location(call_site)
    return Location(display_path(session.paths[-1] if session.paths else path), None)


def _nearest_stamp(node, detached: dict[int, str] | None = None) -> str | None:
    while isinstance(node, xml.dom.Node):
        if detached and id(node) in detached:
            return detached[id(node)]
        if node.nodeType == xml.dom.Node.ELEMENT_NODE and node.hasAttribute(STAMP):
            return node.getAttribute(STAMP)
        node = node.parentNode
    return None


def _to_lxml(session: _Session, doc, root_location: Location):
    """Copy the expanded minidom document into lxml, moving the stamps into a location map."""
    locations: dict[etree._Element, Location] = {}
    source = doc.documentElement

    def build(node, parent, depth=0):
        if depth > MAX_OUTPUT_DEPTH:
            raise xacro_sandbox.SandboxViolation(
                f"expanded elements are nested deeper than {MAX_OUTPUT_DEPTH} levels")
        stamp = node.getAttribute(STAMP) if node.hasAttribute(STAMP) else None
        element = _make_element(parent, node)
        if stamp:
            locations[element] = session.location(stamp)
        elif parent is not None and parent in locations:
            locations[element] = locations[parent]
        else:
            locations[element] = root_location
        last = None
        texts = 0  # text nodes before the first child (lxml joins them; minidom does not)
        for child in node.childNodes:
            if child.nodeType == xml.dom.Node.ELEMENT_NODE:
                last = build(child, element, depth + 1)
            elif child.nodeType in (xml.dom.Node.TEXT_NODE, xml.dom.Node.CDATA_SECTION_NODE):
                if last is None:
                    element.text = (element.text or "") + child.data
                    texts += 1
                else:
                    last.tail = (last.tail or "") + child.data
            elif child.nodeType == xml.dom.Node.COMMENT_NODE:
                comment = etree.Comment(child.data.replace("--", "- -"))
                element.append(comment)
                last = comment
        if last is None and texts > 1 and not (element.text or "").strip():
            # content that all expanded away (an <xacro:if> that was false): the blank xacro
            # prints for it, so that `urdftool xacro` writes what ROS xacro writes
            element.text = "\n" + "  " * depth
        return element

    root = build(source, None)
    # the comments around the root element (a title above <robot>) stay where they were
    for node in doc.childNodes:
        if node is source:
            break
        if node.nodeType == xml.dom.Node.COMMENT_NODE:
            root.addprevious(etree.Comment(node.data.replace("--", "- -")))
    for node in reversed(doc.childNodes):
        if node is source:
            break
        if node.nodeType == xml.dom.Node.COMMENT_NODE:
            root.addnext(etree.Comment(node.data.replace("--", "- -")))
    return root, locations


def _make_element(parent, node):
    """An lxml element for a minidom element, namespaces kept where they were declared."""
    nsmap = {}
    tag = _qualified(node, nsmap)
    attributes = {}
    for attribute in node.attributes.values():  # item(i) lists the names on every call
        if attribute.name == STAMP or attribute.name.startswith("xmlns"):
            continue
        attributes[_qualified(attribute, nsmap)] = attribute.value
    if parent is None:
        return etree.Element(tag, attributes, nsmap=nsmap or None)
    return etree.SubElement(parent, tag, attributes, nsmap=nsmap or None)


def _qualified(node, nsmap: dict) -> str:
    name = node.nodeName
    if ":" not in name:
        return name
    prefix, local = name.split(":", 1)
    uri = node.namespaceURI or f"urn:undeclared:{prefix}"
    nsmap[prefix] = uri
    return f"{{{uri}}}{local}"


_DEPRECATED_USE = re.compile(r"Using (\w+)\(\) directly is deprecated")


def _written_use(session: _Session, where: Location, message: str) -> Location:
    """Where a deprecated name xacro warns about (``load_yaml()`` without ``xacro.``) is
    written: a property's value is evaluated where it is first used, so the element being
    expanded may be a line below its property. The nearest use at or before ``where``'s line
    in its file, else ``where``."""
    named = _DEPRECATED_USE.search(message)
    if named is None or where.line is None:
        return where
    use = re.compile(rf"(?<![\w.]){re.escape(named.group(1))}\s*\(".encode())
    for index, path in enumerate(session.paths):
        if session.shown(index) != where.file:
            continue
        try:
            data = session.read_file(path, "xacro")
        except OSError:
            return where
        line_of = LineNumbers(data)
        lines = [line_of(m.start()) for m in use.finditer(data)]
        before = [line for line in lines if line <= where.line]
        return Location(where.file, max(before), where.via) if before else where
    return where


def _warnings(text: str, top: str, places: dict | None = None) -> list[tuple[Location, str]]:
    """xacro's warnings (written to stderr) as (location, message) pairs: at the element the
    expansion was at when xacro wrote the warning (``places``, offset -> Location), else in
    the file xacro's context lines name, without a line. Only what xacro says is a warning
    (or an error): ``xacro.warning()`` writes "warning: " before it when stderr is no
    terminal; ``xacro.message()`` writes the author's own words without it (dvrk_model's
    "Using instrument 400006: Large Needle Driver"), which are not a warning."""
    found = []
    current: list[str] = []
    where, at = top, None
    offset, marks = 0, sorted((places or {}).items())
    for raw in lines_of(text, keepends=True):
        start, offset = offset, offset + len(raw)
        line = raw.strip()
        if not line:
            continue
        if line.startswith(("when processing file:", "in file:", "included from:",
                            "when instantiating macro:", "instantiated from:")):
            if line.startswith(("when processing file:", "in file:")):
                where = display_path(line.split(":", 1)[1].strip())
            continue
        if current:
            found.append((at or Location(where, None), " ".join(current)))
            current = []
        if not line.lower().startswith(("warning:", "error:")):
            continue  # xacro.message() (<xacro:message>): what its author prints, no warning
        # the place of the write that began this line: the last one at or before it
        at = next((place for mark, place in reversed(marks) if mark <= start), None) \
            if marks else None
        # the finding says it is a warning: "warning ... warning: ..." said it twice
        current.append(line[len("warning:"):].lstrip() if line.lower().startswith("warning:")
                       else line)
    if current:
        found.append((at or Location(where, None), " ".join(current)))
    return found
