"""``--format text``: findings grouped by file, with the macro call chain and a summary.

The lines are built once as styled spans. On a terminal (or with FORCE_COLOR) rich renders them
in colour; anywhere else (CI logs, pipes, files) they are written as plain text, which is what
rich would write there too, without paying for importing it.

Text is for people, so it says each thing once (the machine formats keep every finding):

- findings of one rule that say the same thing about different names (24 transmissions whose
  interface lacks ``hardware_interface/``; nine parameters of a camera plugin, each its own
  tag, ``<updateRate>``, ``<distortionK1>``...) are one line, the first of them, followed by how
  many there are and where (:func:`groups`); the figures of what they name may differ (six
  links "has mass 0.59 kg but zero inertia", each its own mass): a figure that differs is
  written as the range of the group's (``0.0649 to 0.864 kg``), so the one line is true of
  each. A message that names nothing keeps its figures apart: they are what it says;
- a long "available links: ..." list, where a missing package was looked for with how to
  pass it, and the evidence a rule gives for what it assumed (U640: why the robot is ROS 2),
  are written in full the first time in a file's report, and later findings refer to it
  (:func:`_once`; each is a part of the message its finding names,
  :attr:`~urdftool.diagnostics.Finding.repeated`, never words read back from the message);
- notes (severity info: explanations such as "its inertia is taken from its convex hull", not
  problems) are shown only when asked for (``check --notes``, ``notes = true`` in the
  settings); the summary line counts the ones it left out.
"""

from __future__ import annotations

import functools
import os
import re
from typing import Callable

from urdftool.diagnostics import Severity, display_path
from urdftool.errors import LISTED, first_listed, fitting
from urdftool.report.escape import text as escaped
from urdftool.report.summary import STYLES, Summary, counted, lines_of, tallies, via_text

Line = list[tuple[str, str]]  # (text, rich style or "")
Notes = bool | Callable[[object], bool]  # for all results, or per result

# a name in quotes, an absolute path or an XML tag written without attributes (``<updateRate>``,
# ``</cx>``): what differs between findings that say the same thing. Each branch starts with
# its character (the path's "/" then looks behind it for the space or "(" before): the search
# jumps from quote to slash to "<" instead of trying the look-behind at every character of every
# message (10,000 findings' messages: a quarter of the time).
_NAME = re.compile(r"'[^'\s]*'|/(?<=[\s(]/)[^\s)]*|</?[A-Za-z_][\w:.\-]*>")
_LONG_LIST = 60  # [characters] a list of names shorter than this (all shown) is written every time
# a figure: a number standing alone (not part of a word, a name, a unit's power like m^3 or a
# version like 1.2.3): (?<![\w.+\-^/])[-+]?\d+..., written to start with its first character
# ([-+\d], the character before it looked at behind that), so that the search skips from sign
# or digit to the next instead of trying the look-behind at every character (10,000 findings'
# messages: half of the time); the same matches
_FIGURE = re.compile(r"[-+\d](?<![\w.+\-^/][-+\d])(?:(?<=[-+])\d+|(?<=\d)\d*)"
                     r"(?:\.\d+)?(?:e[-+]?\d+)?(?![\w.]\w|\w)")


def lines(results, quiet: bool = False, notes: Notes = True) -> list[Line]:
    """The report as lines of (text, style) spans; names, paths and messages come from the
    files checked, so each line is terminal text (urdftool.report.escape.text: one finding,
    one line, none a workflow command).

    notes: whether findings of severity info are shown, for every result or per result
    """
    out: list[Line] = []
    hidden, unseen = 0, 0  # (notes not shown; fixes among them)
    noted = []  # the notes shown
    for result in results:
        shown = _shown(result, notes)
        noted += [f for f in shown if f.severity is Severity.INFO]
        if len(shown) < len(result.findings):
            kept = {id(f) for f in shown}
            left = [f for f in result.findings if id(f) not in kept]
            hidden, unseen = hidden + len(left), unseen + sum(f.fix is not None for f in left)
        if not shown:
            continue
        out.append([(display_path(result.path), "bold underline")])
        listed: dict = {}  # each long list of names -> where it was written in full
        for group, message, named in _in_file_order(shown):
            out.extend(_group_lines(group, message, listed, named))
        if not quiet:
            out.append([])
    if quiet:
        return [_escaped(line) for line in out]
    out.append(_summary(results, hidden, noted))
    fixable = [f.fix.safe for result in results for f in result.findings if f.fix is not None]
    if fixable:
        safe, unsafe = fixable.count(True), fixable.count(False)
        parts = [f"[*] {safe} fixable with --fix"] if safe else []
        parts += [f"[~] {unsafe} {'more' if safe else 'fixable'} with --unsafe-fixes"] \
            if unsafe else []
        parts += [f"{unseen} of them in notes not shown"] if unseen else []
        out.append([("; ".join(parts), "")])
    return [_escaped(line) for line in out]


def _in_file_order(shown: list) -> list[tuple[list, str, list | None]]:
    """The lines ``shown`` (findings in line order) is written in, each (its findings, the
    message it says, the names :func:`_apart` read or None), in the order of their first
    findings: the lines a group is split into (each its own figures, :func:`_foldable`) stand
    among the others where they are in the file, not one group's after another's (PAROL6's
    U515: every min, then every max)."""
    order = {id(finding): index for index, finding in enumerate(shown)}
    lines = [(group, message, named if group is part else None)
             for whole, alike in _grouped(shown)
             for part, named in _apart(whole)
             for group, message in _foldable(part, alike)]
    return sorted(lines, key=lambda line: order[id(line[0][0])])


def _shown(result, notes: Notes) -> list:
    """The findings of ``result`` the report shows: its notes only where ``notes`` says (but
    a note saying why the file was not checked, which the exit code counts)."""
    if notes(result) if callable(notes) else notes:
        return result.findings
    kept = {id(f) for f in result.not_checked_by}
    return [f for f in result.findings if f.severity is not Severity.INFO or id(f) in kept]


def _summary(results, hidden: int, noted: list) -> Line:
    """The last line: the files checked and their findings by severity, each with the lines
    of the files it is on when fewer (:meth:`Summary.counts`: a macro line in many robots is
    one line to change); the notes the report shows (``noted``), and how many it left out
    (``hidden``)."""
    summary = Summary.of(results)
    infos = summary.infos - hidden
    style = "bold red" if summary.errors else ("yellow" if summary.warnings else "bold green")
    counts = tallies([(summary.errors, summary.error_lines, "error"),
                      (summary.warnings, summary.warning_lines, "warning"),
                      (infos, lines_of(noted), "note")])
    counts = counts if infos or not hidden else counts[:2]
    verdict = ", ".join(counts) if summary.errors or summary.warnings or infos \
        else "no problems found" if summary.files else "nothing to check"
    if hidden:
        verdict += f" ({counted(hidden, 'note')} not shown: --notes shows them)"
    unexpanded = sum(1 for result in results if result.unexpanded)
    checked = f"{counted(summary.files - unexpanded, 'file')} checked"
    if unexpanded:  # (a package they need is not installed: U006, and the run exits 2)
        needs = "it needs" if unexpanded == 1 else "they need"
        checked += f", {unexpanded} not (a package {needs} is not installed)"
    return [(f"{checked}: {verdict}", style)]


def groups(findings) -> list[list]:
    """The findings in groups that say the same thing in one file: one rule, severity, target
    and kind of fix, and the same message once the names in quotes, the absolute paths and the
    tags in angle brackets are set aside. Each group is in the order of its first finding; a
    finding alone is a group of one."""
    return [group for group, _ in _grouped(findings)]


def _grouped(findings) -> list[tuple[list, bool]]:
    """:func:`groups`, each with whether its findings surely give the same figures, known
    without finding them (:func:`_foldable` then need not look): no message gives a value in
    double quotes, and the messages are one text once their names are set aside. A figure
    outside a name neither reaches into one nor starts right after a path, and the character
    of a name it looks at beside it (a quote, a slash, an angle bracket) reads as the ``'`` left
    in the name's place, so such messages have the same figures outside their names, in the
    same order."""
    found: dict[tuple, list] = {}  # key -> [group, its first message without names, alike]
    unnamed: dict[str, str] = {}  # a message without its names -> without its figures too
    for finding in findings:
        fix = None if finding.fix is None else finding.fix.safe
        message = finding.message
        said = unnamed_message = _NAME.sub("''", message)
        if said != message:  # it names what it is about: that thing's figures may differ
            figures_aside = unnamed.get(said)  # (10,000 findings may say one thing)
            if figures_aside is None:
                figures_aside = unnamed[said] = _without_figures(said)
            said = figures_aside
        key = (finding.location.file, finding.code, finding.severity, finding.target, fix, said)
        entry = found.get(key)
        if entry is None:
            found[key] = [[finding], unnamed_message, '"' not in message]
        else:
            entry[0].append(finding)
            if entry[2] and (unnamed_message != entry[1] or '"' in message):
                entry[2] = False
    return [(group, alike) for group, _, alike in found.values()]


def _without_figures(said: str) -> str:
    """``said`` with each figure outside the values it gives in double quotes written ``#``."""
    if '"' not in said:  # (no value: every figure)
        return _FIGURE.sub("#", said)
    return _FIGURE.sub(lambda m: "#" if not _in_value(said, m.start()) else m.group(), said)


def _in_value(message: str, index: int) -> bool:
    """Whether ``index`` is inside a value the message gives in double quotes (``write
    xyz="0.57735 0.57735 0.57735"``): what to write, never a figure to fold into a range."""
    return message.count('"', 0, index) % 2 == 1


def _figures(message: str) -> list:
    """The figures of a message outside the names it quotes and the values it gives in double
    quotes: (start, end, text) each."""
    named = [m.span() for m in _NAME.finditer(message)]
    quoted = '"' in message  # (without, no figure is in a value)
    found = []
    for m in _FIGURE.finditer(message):  # (a loop: 10,000 findings' messages)
        start = m.start()
        for a, b in named:
            if a <= start < b:
                break
        else:
            if not (quoted and _in_value(message, start)):
                found.append((start, m.end(), m.group()))
    return found


def _apart(group: list, named: list | None = None) -> list[tuple[list, list | None]]:
    """``group`` as the groups of its lines by what its findings name: one, unless they name
    different things at several places of their message and one of those places is a kind
    they fall into, which a line naming the others at one place (:func:`_also`) would hide,
    saying something false of some: a tag not going one to one with the names that differ
    most (the element they are in: "<pose> in <link>" and "<ambient>, <diffuse>... in
    <material>"; a link's <visual> and <collision>), or any such name where a tag differs most
    (the plugin its tags are of). Then a group for each kind, each split so again. Places going
    one to one stay one line (a tag and the one suggested for it), and so do names where no
    tag differs (a transmission and its joint, a link and its mesh: "also" names the first, as
    before tags were names). The kinds are read in the first findings of a long group, as
    :func:`_also` reads the names. Each group comes with the names of its first findings
    (``named``: read once, and said by :func:`_also`); None for a finding alone."""
    if len(group) == 1:
        return [(group, None)]
    if named is None:
        named = [_names(finding.message) for finding in group[:_NAMES_READ]]
    first = named[0]
    if len(first) < 2 or any(len(names) != len(first) for names in named):
        return [(group, named)]  # (one name, or messages naming another count of things)
    ways = [len({names[i] for names in named}) for i in range(len(first))]
    most = ways.index(max(ways))
    kinds = [i for i, count in enumerate(ways) if count > 1 and i != most
             and "<" in (first[i][0], first[most][0])
             and not _one_to_one([(names[most], names[i]) for names in named])]
    shapes = _shapes(named, ways)
    if not kinds and not shapes:
        return [(group, named)]
    parts: dict[tuple, tuple[list, list]] = {}  # key -> (findings, the names of the first)
    for index, finding in enumerate(group):
        names = named[index] if index < len(named) else _names(finding.message)
        key = () if len(names) != len(first) else (
            *(names[i] for i in kinds), *(_shape(names, at, i) for at, i in shapes))
        part = parts.setdefault(key, ([], []))
        part[0].append(finding)
        if len(part[1]) < _NAMES_READ:
            part[1].append(names)
    if len(parts) == 1:
        return [(group, named)]
    return [split for part, names in parts.values() for split in _apart(part, names)]


def _shapes(named: list[tuple], ways: list[int]) -> list[tuple[int, int]]:
    """The places (at, i) where each finding's name at ``i`` holds its name at ``at``, the
    first place their names differ (a mesh named after its link: 'package://p/meshes/
    base_link.STL' of link 'base_link'), and the rest of it is not one for all: the line
    naming the others after ``at`` (:func:`_also`) would show one pattern of several (nine
    meshes of OpenLoong's whose package is written twice, 'package://loong_control/
    loong_control/...', behind one simply missing)."""
    differ = [i for i, count in enumerate(ways) if count > 1]
    if not differ or named[0][differ[0]][0] != "'":
        return []
    at = differ[0]
    found = []
    for i in differ[1:]:
        if named[0][i][0] == "<":
            continue  # (a tag: a kind, which the caller splits by)
        held = [names for names in named if len(names[at]) > 4 and names[at][1:-1] in names[i]]
        if len(held) == len(named) and len({_shape(names, at, i) for names in held}) > 1:
            found.append((at, i))
    return found


def _shape(names: tuple, at: int, i: int) -> str:
    """The name at ``i`` with the name at ``at`` taken out of it (``{}`` in its place)."""
    return names[i].replace(names[at][1:-1], "{}")


def _one_to_one(pairs: list[tuple]) -> bool:
    """Whether the pairs' first and second items go one to one (each first with one second,
    each second with one first)."""
    return len(set(pairs)) == len({a for a, _ in pairs}) == len({b for _, b in pairs})


def _foldable(group: list, alike: bool) -> list[tuple[list, str]]:
    """``group`` as the lines it is written in, each (its findings, the message it says): one,
    whose differing figure is written as the group's range (:func:`_ranged`), when one figure
    at most differs and it stands alone; else one line per message once the names are set
    aside (each true as written, its names said by :func:`_also`). ``alike``: the group's
    figures are surely the same (:func:`_grouped`: 10,000 findings of one line, no figure
    looked for). Two figures differing read as nonsense folded ("min -1.2 to 2.89 is above max
    -1.48 to 2.49", five joints each its own), and so did a figure of a vector ("centre of
    mass (0.065 -0.133 to 0.133 -0.056)") or of a number written with thousands ("33 to
    35,333 to 368 kg/m^3", 33,333 and 35,368)."""
    message = group[0].message
    if alike or len(group) == 1:
        return [(group, message)]
    mine = _figures(message)
    others = [_figures(f.message) for f in group[1:]]
    if any(len(figures) != len(mine) for figures in others):
        return [(group, message)]  # (written as the first says it)
    differ = [i for i in range(len(mine)) if any(f[i][2] != mine[i][2] for f in others)]
    if len(differ) <= 1 and not any(_joined(message, mine, i) or _a_line(message, mine, i)
                                    for i in differ):
        return [(group, _ranged(message, mine, others, differ))]
    parts: dict[str, list] = {}
    for finding in group:
        parts.setdefault(_NAME.sub("''", finding.message), []).append(finding)
    return [(part, part[0].message) for part in parts.values()]


def _joined(message: str, figures: list, index: int) -> bool:
    """Whether the figure ``figures[index]`` of ``message`` is one of several written as one
    value: a vector's coordinates (a space between), a number's groups of thousands (a
    comma)."""
    start, end, _ = figures[index]
    before = index > 0 and figures[index - 1][1] + 1 == start and \
        message[start - 1] in " ,"
    after = index + 1 < len(figures) and figures[index + 1][0] == end + 1 and \
        message[end] in " ,"
    return before or after


def _a_line(message: str, figures: list, index: int) -> bool:
    """Whether the figure ``figures[index]`` of ``message`` is a line of a file it names
    (``macro.xacro:49``): lines 49 and 137 are two places, not a range ("first at
    macro.xacro:49 to 137" read as one element written across 88 lines)."""
    start = figures[index][0]
    return start > 1 and message[start - 1] == ":" and not message[start - 2].isspace()


def _ranged(message: str, mine: list, others: list, differ: list) -> str:
    """``message`` with each figure of ``mine`` (:func:`_figures`) whose index is in ``differ``
    written as the range of it and the ``others``' there (``0.0649 to 0.864``)."""
    for index in reversed(differ):
        start, end, text = mine[index]
        texts = [text] + [figures[index][2] for figures in others]
        low, high = min(texts, key=float), max(texts, key=float)
        message = f"{message[:start]}{low} to {high}{message[end:]}"
    return message


def _group_lines(group: list, message: str, listed: dict, named: list | None) -> list[Line]:
    """The lines of ``group``, which says ``message``; ``named``: the names of its first
    findings when :func:`_apart` read them (else None)."""
    first = group[0]
    location, severity = first.location, first.severity.value
    line = [(f"  {location}: ", ""), (severity, STYLES[severity]), (" ", ""), *_marker(first),
            (first.code, "bold"), (f" {_once(message, location, listed, first.repeated)} ", ""),
            (f"({first.name}, {first.target})" if first.target else f"({first.name})", "dim")]
    if len(group) > 1:
        places = _places(group)
        line.append((f" [{len(group)} times{f': {places}' if places else ' on this line'}"
                     f"{_also(group, named)}]", ""))
    out = [line]
    calls = list(dict.fromkeys(f.location.via for f in group))
    if calls == [()]:
        return out
    if len(calls) == 1:  # a macro's: its call sites (10,000 findings may have none)
        return out + [[(f"      {text}", "dim")] for text in via_text(location)]
    # the level of the call chains (innermost first) where the findings differ most
    depth = max(len(via) for via in calls)
    sites = max((list(dict.fromkeys(str(via[level]) for via in calls if len(via) > level))
                 for level in range(depth)), key=len)
    return out + [[(f"      expanded from {counted(len(sites), 'macro call')} at "
                    f"{_listed(_same_file_once(sorted(sites, key=_site_order)))}", "dim")]]


def _site_order(site: str) -> tuple:
    """A call site (``FILE:LINE``) in reading order: by file, then line (``92, 93, 94``, not
    the order of the names the findings were sorted by)."""
    file, _, line = site.rpartition(":")
    return (file, int(line), "") if file and line.isdigit() else (site, 0, site)


def _same_file_once(sites: list[str]) -> list[str]:
    """Call sites (``FILE:LINE``) with a file written once for its run of sites: ``a.xacro:28,
    52, 76, b.xacro:28`` (a robot named by an absolute path repeated it 21 times on a line)."""
    shown, previous = [], None
    for site in sites:
        file, _, line = site.rpartition(":")
        if file and line.isdigit() and file == previous:
            shown.append(line)
        else:
            shown.append(site)
        previous = file if line.isdigit() else None
    return shown


def _places(group: list) -> str:
    """Where the findings of a group are (lines of one file), each place once, with how many
    findings it holds when several (a macro line expanded by several calls); '' when they are
    all on the line the group's line names ("2 times: line 162 (2x)" said it twice)."""
    counts: dict[str, int] = {}
    for finding in group:
        place = str(finding.location.line or "?")
        counts[place] = counts.get(place, 0) + 1
    if len(counts) == 1:
        return ""
    places = [place if n == 1 else f"{place} ({n}x)" for place, n in counts.items()]
    return ("line " if len(places) == 1 else "lines ") + _listed(places)


_NAMES_READ = 1000  # findings of a group whose names are looked at (10,000 may say one thing)


@functools.lru_cache(maxsize=2 * _NAMES_READ)
def _names(message: str) -> tuple[str, ...]:
    """The names ``message`` says (:data:`_NAME`), in order; kept for the messages read last
    (:func:`_apart` and then :func:`_also` read those of a group's first findings)."""
    return tuple(_NAME.findall(message))


ALSO_WIDTH = 200  # [characters] of the names an "also" list shows (fewer when long: errors.fitting)


def _also(group: list, named: list | None = None) -> str:
    """The other names a group's line is about, where its findings name different things
    (three joints of one macro line, each its own limit): "; also 'b', 'c'". The names
    compared are the first place their findings' names differ, in the first findings of a
    long group, and with each the names in quotes or the tag it gives at the other places
    that differ (one to one: :func:`_apart` split the others), as the line says the first's:
    "also 'b' ('b.stl')" on a line of "link 'a' <visual>: mesh 'a.stl' not found", "also
    <contact_coefficients> (<collision>)" on a line of "<joint_properties> in <joint>" (a
    closing tag, an absolute path are not). A name in quotes that another place's name holds
    in one pattern for all is said by that one alone (a mesh named after its link, a
    transmission after its joint): "also 'package://p/meshes/b.stl'", not the link's name,
    where the reader needs the mesh. ``named``: those names when read already
    (:func:`_apart`)."""
    if named is None:
        named = [_names(finding.message) for finding in group[:_NAMES_READ]]
    first = named[0]
    if any(len(names) != len(first) for names in named):
        return ""  # (messages naming another count of things)
    differ = [i for i in range(len(first)) if any(names[i] != first[i] for names in named)]
    if not differ:
        return ""  # (the same names)
    quoted = [i for i in differ if first[i][0] == "'"]
    held = {i for i in quoted if any(_holds(named, h, i) and not (
        _holds(named, i, h) and (len(first[i]), -i) > (len(first[h]), -h))
        for h in quoted if h != i)}  # (of two that hold each other, the longer, else the first)
    differ = [i for i in differ if i not in held]
    at, with_it = differ[0], [i for i in differ[1:] if first[i][:2] != "</" and first[i][0] in "<'"]
    places = (at, *with_it)

    def said(folders: list[str]) -> list[str]:
        mine = _in_folders(first, places, folders)  # (a link's second mesh is another's)
        return [names[0] + (f" ({', '.join(names[1:])})" if with_it else "") for names in
                dict.fromkeys(_in_folders(names, places, folders) for names in named)
                if names != mine]

    others = said([""] * len(places))
    if fitting(others, ALSO_WIDTH) < len(others):  # (cut: the folder they share said once)
        others = said([_shared_folder([names[i] for names in named]) for i in places])
    if len(group) > _NAMES_READ:  # (how many in all is not known)
        return f"; also {', '.join(others[:fitting(others, ALSO_WIDTH)])}, ..."
    return f"; also {first_listed(others, len(others), width=ALSO_WIDTH)}"


_SHARED_FOLDER = 16  # [characters] a folder the names of an "also" list share, said once


def _shared_folder(names: list[str]) -> str:
    """The folder the quoted paths ``names`` are all in (``'package://ur_description/meshes/
    ur10/visual/``) when it is longer than :data:`_SHARED_FOLDER` characters, else "": an
    "also" list too long for its width writes it ``...`` (:func:`_in_folders`), the group's
    first message giving it in full (Shadow's arm named six meshes of one package folder, its
    45 characters each time: three within the list's width, then "... (6 in all)")."""
    if not all(name[:1] == "'" and "/" in name for name in names):
        return ""
    shared = os.path.commonprefix(names)
    shared = shared[:shared.rfind("/") + 1]
    return shared if len(shared) > _SHARED_FOLDER else ""


def _in_folders(names: tuple, places: tuple, folders: list[str]) -> tuple:
    """The names at ``places`` of ``names``, each with the folder of its place (``folders``,
    :func:`_shared_folder`) written ``...``."""
    return tuple("'..." + names[i][len(folder) - 1:] if folder else names[i]
                 for i, folder in zip(places, folders))


def _holds(named: list[tuple], holder: int, i: int) -> bool:
    """Whether the name at ``i`` is read from the name at ``holder`` in one pattern for all,
    as the group's line shows it for its first finding: each finding's name at ``holder``
    holds its name at ``i`` (of two characters or more: :func:`_shape`), or its name at ``i``
    holds the part of its name at ``holder`` that differs among them (three characters or
    more: 'package://p/meshes/{}.STL' written for 'package://q/meshes/{}.STL')."""
    if all(len(names[i]) > 3 and names[i][1:-1] in names[holder] for names in named) and \
            len({_shape(names, i, holder) for names in named}) == 1:
        return True
    written = [names[holder] for names in named]
    start = len(os.path.commonprefix(written))
    end = len(os.path.commonprefix([name[start:][::-1] for name in written]))
    parts = [name[start:len(name) - end] for name in written]
    return all(len(part) > 2 and part in names[i] for part, names in zip(parts, named)) and \
        len({names[i].replace(part, "{}", 1) for part, names in zip(parts, named)}) == 1


def _listed(items: list[str]) -> str:
    """Places or names on a grouped line, cut as every list is (``errors.first_listed``)."""
    return first_listed(items, len(items))


def _once(message: str, location, listed: dict, repeated: tuple = ()) -> str:
    """``message`` with each part its finding says other findings repeat (``repeated``,
    :attr:`~urdftool.diagnostics.Finding.repeated`: a long "available ..." list, the "looked
    in: ..." of a missing package, the evidence for what a rule assumed) that it repeats from
    an earlier finding of the same report replaced by a reference to where it was written in
    full."""
    def first(key: str):
        """Where ``key`` was written before (None: nowhere, and it is written here)."""
        if key not in listed:
            listed[key] = location
            return None
        where = listed[key]
        return f"line {where.line}" if where.file == location.file and \
            where.line is not None else str(where)

    for kind, part, detail in repeated:  # (Finding.repeated: the parts others say again)
        if part not in message:
            continue
        if kind == "available":  # (urdftool.errors.available: "available links: a, b, ...",
            count, what = detail.split(" ", 1)  # detail "31 links": how many, what they are)
            cut = int(count) > LISTED  # (the list shows the first LISTED, then the count)
            if not cut and len(part) - len(f"available {what}: ") < _LONG_LIST:
                continue  # (a short list: written every time)
            at = first(part)
            if at is not None:
                message = message.replace(part, f"available {what}: " + (
                    f"the {count} listed at {at}" if cut else f"as listed at {at}"), 1)
        elif kind in _SAID_AGAIN:
            at = first(part)
            if at is not None:
                message = message.replace(part, _SAID_AGAIN[kind].format(at=at, detail=detail), 1)
    return message


# what a part of a message that other findings repeat (Finding.repeated) becomes after the
# first: the evidence for what a rule assumed (U640's ROS version), where a package not found
# was looked for and how to pass it (each mesh and file of a missing package says it again)
_SAID_AGAIN = {"why": " (as said at {at})",
               "searched": "; looked in the places listed at {at}; pass --package "
                           "{detail}=PATH as said there"}


def _escaped(line: Line) -> Line:
    """The line with each span escaped as terminal text; one look at the whole line first
    (escaping is per character, so a line that needs none is kept as it is: 10,000 findings
    are 60,000 spans)."""
    whole = "".join([text for text, _ in line])
    if escaped(whole) == whole:
        return line
    return [(escaped(text), style) for text, style in line]


def _marker(finding) -> Line:
    """``[*]`` before the code of a finding that ``--fix`` removes, ``[~]`` for one only
    ``--unsafe-fixes`` removes (as ruff marks them)."""
    if finding.fix is None:
        return []
    return [("[*] " if finding.fix.safe else "[~] ", "bold cyan")]


def render(results, stream, quiet: bool = False, notes: Notes = True) -> None:
    report = lines(results, quiet, notes)
    if not _colour(stream):
        stream.write("".join("".join(text for text, _ in line) + "\n" for line in report))
        return
    from rich.text import Text

    from urdftool.report.console import plain_console

    # emoji=False, highlight=False, Text spans: messages are printed exactly as written
    console = plain_console(stream)
    for line in report:
        console.print(Text.assemble(*line))


def _colour(stream) -> bool:
    if os.environ.get("NO_COLOR"):
        return False
    if os.environ.get("FORCE_COLOR"):
        return True
    return hasattr(stream, "isatty") and stream.isatty()
