"""One escaping function per output kind: what text taken from the files checked becomes in
each kind of output urdftool writes.

Every name in a robot file (links, joints, materials, frames, the robot, SRDF groups, controllers,
YAML keys), every file and folder name, every message that quotes one, and every word of the
command line is the attacker's text. Only the templates of the renderers are ours. Each output
kind has exactly one function here, and every renderer and every message that quotes such text
goes through the function of the kind it writes:

============================  ==================  =============================================
output kind                   function            what it guards against
============================  ==================  =============================================
terminal text (stdout,        :func:`text`        a line break or carriage return starting a
stderr: reports, tables,                          line of its own (``::error``, a fake verdict),
messages, progress, logs)                         terminal escape sequences (CSI, OSC 8 links,
                                                  OSC 52 clipboard), C1 controls, bidi
                                                  overrides; a line starting with ``::`` (a
                                                  GitHub workflow command, blanks before it too)
rich console markup           :func:`markup`      :func:`text`, and ``[bold]``-style markup
GitHub workflow commands      :func:`workflow`    a line break ending the command, ``%``, and in
                                                  a property ``:`` and ``,``
Markdown (pull-request        :func:`markdown`    headings, images, links, raw HTML, mentions,
comments, job summaries;                          table cells: the text is a code span
rdjson's messages, which
reviewdog posts as review
comments)
XML (JUnit; lxml writes it)   :func:`xml`         characters XML 1.0 cannot hold; line breaks
                                                  that would start a line in a CI page; on a
                              :func:`write_xml`   stream whose encoding lacks a character, a
                                                  backslash escape changing the data
SVG / HTML written by hand    :func:`svg`         markup (``<img onerror>``, ``<script>``) and
                                                  characters XML cannot hold
CSV cells                     :func:`csv_cell`    line breaks (a row of their own) and formulas
                                                  a spreadsheet would run (``=``, ``+``, ``-``,
                                                  ``@``)
Graphviz DOT                  :func:`dot`         a quoted ID ended early, DOT's own escapes
                                                  and character entities, two names made one
                                                  ID (one to one)
YAML documents                :func:`yaml_text`   a scalar folded or broken onto a line of its
                                                  own; non-printable characters
editor notifications          :func:`notification` a line break or control character (some
(the language server's                            clients print it in a terminal), and the
``window/showMessage``)                           link grammar of VS Code's notifications:
                                                  ``[text](command:...)`` runs the command
                                                  when clicked
SARIF message text           :func:`sarif_text`  SARIF's own grammar inside the JSON string:
                                                  ``[text](0)`` an embedded link, ``{0}`` a
                                                  placeholder, ``\\[`` a bracket
JSON (json, sarif, gitlab,    the encoder:        nothing to escape: the data stays exact (but
rdjson, json-lines, LSP)      ``json_output``     the message texts above), the bytes are
                                                  ASCII (``\\uXXXX``); a name's
                              (``paired``: LSP)   undecodable byte (a lone surrogate) is U+FFFD
                                                  and its two hex digits, one to one
                                                  (``json_output.named``; SARIF's URIs ``%FF``)
============================  ==================  =============================================

tests/report/test_escape.py holds each function to its kind; tests/integration/
test_forged_output.py runs every command in every format on names carrying every payload, and
tests/report/test_escape.py's scan finds output written past these functions.
"""

from __future__ import annotations

import io
import re

# Characters that move the cursor, end a line, change the terminal's state or reorder text
# (Unicode categories Cc, Cf, Cs, Zl, Zp), and U+FFFE and U+FFFF, the two characters besides
# those that XML 1.0 cannot hold (a file named with one made lxml refuse the JUnit report): a
# name in a robot file that holds one could forge report lines ("::error ...", "no problems
# found"), hide text, or make a report unwritable.
_UNPRINTABLE = re.compile(
    "[\x00-\x1f\x7f-\x9f\xad\u0600-\u0605\u061c\u06dd\u070f\u0890\u0891\u08e2\u180e"
    "\u200b-\u200f\u2028-\u202e\u2060-\u2064\u2066-\u206f\ud800-\udfff\ufeff"
    "\ufff9-\ufffb\ufffe\uffff\U000110bd\U000110cd\U00013430-\U0001343f\U0001bca0-\U0001bca3"
    "\U0001d173-\U0001d17a\U000e0001\U000e0020-\U000e007f]")
_SHORT = {"\n": "\\n", "\r": "\\r", "\t": "\\t"}


def _escaped(match) -> str:
    char = match.group()
    code = ord(char)
    return _SHORT.get(char) or (f"\\x{code:02x}" if code < 0x100 else
                                f"\\u{code:04x}" if code < 0x10000 else f"\\U{code:08x}")


def printable(value, keep: str = "") -> str:
    """``value`` with every control, format, separator or lone surrogate character written as
    a Python escape (``\\n``, ``\\x1b``, ``\\u202e``), except those in ``keep``: what every
    kind below starts from."""
    value = str(value)
    if value.isascii() and value.isprintable():  # the characters escaped in ASCII are C0 and
        return value  # DEL, exactly what isprintable refuses there: most text, at C speed
    return _UNPRINTABLE.sub(lambda m: m.group() if m.group() in keep else _escaped(m), value)


def text(value, keep: str = "") -> str:
    """Terminal text: :func:`printable`, and a ``:`` that would start the line (after blanks,
    which GitHub's runner strips) written ``\\x3a``, so that no line of output is a workflow
    command. Idempotent: a line already escaped comes back as it is. ``keep``: characters left
    as they are (a file's own tabs, in lines copied from it)."""
    value = printable(value, keep)
    stripped = value.lstrip()
    if stripped.startswith(":"):
        at = len(value) - len(stripped)
        value = value[:at] + "\\x3a" + value[at + 1:]
    return value


def lines(block: str, keep: str = "") -> str:
    """A block of terminal text (lines a renderer built, or a message) with :func:`text`
    applied to each line: whatever a value in it held, each of its lines stays one line that
    starts as the renderer wrote it. ``"\\r"`` in ``keep`` keeps a carriage return that ends
    a line only (a CR LF file's lines in a diff, which ``git apply`` matches by their bytes: the
    terminal goes back to a line's start and then on to the next, hiding nothing); any other
    stays escaped, where going back would let the rest of the line overwrite what it shows."""
    if "\r" not in keep:
        return "\n".join(text(line, keep) for line in block.split("\n"))
    keep = keep.replace("\r", "")
    return "\n".join(text(line[:-1], keep) + "\r" if line.endswith("\r") else text(line, keep)
                     for line in block.split("\n"))


class Lines:
    """A text stream for terminal text written by a library (rich off a terminal): every line
    written through it goes through :func:`text` (the last guard of :func:`lines`) without the
    blanks rich pads a table's last column with (an empty status cell: trailing spaces in a
    log, a diff, a golden file), and it is no terminal (rich writes no escape sequence of its
    own to it)."""

    def __init__(self, stream):
        self.stream, self._pending = stream, ""

    def write(self, data: str) -> int:
        *done, self._pending = (self._pending + data).split("\n")
        if done:
            self.stream.write("".join(text(line).rstrip(" ") + "\n" for line in done))
        return len(data)

    def flush(self) -> None:
        if self._pending:
            self.stream.write(text(self._pending))
            self._pending = ""
        self.stream.flush()

    def isatty(self) -> bool:
        return False


def markup(value) -> str:
    """Rich console markup: :func:`text`, with ``[`` of anything rich would read as a tag
    escaped (consoles are made with ``emoji=False``: ``:thumbs_up:`` stays text)."""
    from rich.markup import escape

    return escape(text(value))


def workflow(value, property: bool = False) -> str:
    """GitHub Actions workflow-command data (``property``: a property value, ``file=...``): a
    line break is ``%0A`` (the annotation goes on, the command cannot end), every other control
    character is written as an escape."""
    data = printable(value, keep="\r\n").replace("%", "%25").replace("\r", "%0D") \
        .replace("\n", "%0A")
    return data.replace(":", "%3A").replace(",", "%2C") if property else data


def markdown(value) -> str:
    """GitHub-flavoured Markdown: the text as a code span, so that nothing in it is a heading,
    image, link, HTML, mention or emphasis; control characters escaped (a line break cannot
    start a block), ``|`` escaped (GFM splits table cells before reading code spans)."""
    body = printable(value).replace("|", "\\|")
    fence = "`" * (max(map(len, re.findall("`+", body)), default=0) + 1)
    if not body.strip(" ") or body[0] in "` " or body[-1] in "` ":
        body = f" {body} "  # CommonMark strips one space on each side
    return f"{fence}{body}{fence}"


def xml(value) -> str:
    """Text or an attribute value for lxml to write (it escapes ``<``, ``&`` and quotes): no
    character XML 1.0 cannot hold, no line break of the value's own, and, as :func:`text`, no
    ``:`` starting it (CI pages show a JUnit failure's text line by line)."""
    return text(value)


def xml_document(document: str, root) -> str:
    """An XML document copied from the files checked (``urdftool xacro``'s output, ``root`` its
    lxml tree) for a terminal or a log, its data exact: a character :func:`printable` escapes
    is written as a character reference, and a line (of a comment or text) starting with ``:``
    starts with ``&#58;``. Left as it is where no reference can stand: when an element or
    attribute name holds such a character."""
    document = _LINE_COLON.sub(r"\1&#58;", document)
    if document.isascii() and "\r" not in document:
        return document
    for element in root.iter():
        names = [element.tag, *element.attrib] if isinstance(element.tag, str) else []
        if any(_UNPRINTABLE.search(name) for name in names):
            return document
    return _UNPRINTABLE.sub(lambda m: m.group() if m.group() in "\n\t" else
                            f"&#x{ord(m.group()):x};", document)


def write_xml(stream, document: str) -> None:
    """Write an XML document to a text stream: where the stream's encoding cannot hold a
    character (an ASCII or Latin-1 locale), it is written as a character reference, which
    an XML reader reads back as that character, not as the backslash escape the stream writes
    for terminal text (a link ``b\\xe9`` is another link). A name of an element or attribute
    cannot hold a reference: one holding such a character is written as XML allows nothing
    better."""
    errors = getattr(stream, "errors", None)
    if errors != "backslashreplace" or not isinstance(stream, io.TextIOWrapper):
        stream.write(document)  # UTF-8 (everything fits), or no encoding (a StringIO)
        return
    stream.reconfigure(errors="xmlcharrefreplace")
    try:
        stream.write(document)
        stream.flush()
    finally:
        stream.reconfigure(errors=errors)

_LINE_COLON = re.compile(r"(?m)^([^\S\n]*):")


def svg(value) -> str:
    """Text or a double-quoted attribute value in SVG (or HTML) written by hand."""
    from html import escape

    return escape(printable(value), quote=True)


_FORMULA = ("=", "+", "-", "@")


# VS Code's link in a notification (vs/base/common/linkedText.ts: ``[label](href)`` of an
# http(s), command or file URI, opened with allowCommands): what makes text a link is "](",
# a label's bracket closed right before the link's
_NOTIFICATION_LINK = re.compile(r"\]\(")


def notification(value) -> str:
    """A message an editor shows as a notification (the language server's
    ``window/showMessage``): :func:`text` (one line; clients such as Neovim print it in a
    terminal), and no link: VS Code makes ``[label](command:ID)`` in a notification a link
    that runs the command when clicked (its renderer opens it with ``allowCommands``), so a
    settings key or a file name of the repository written so was one click from a command;
    ``](`` is written ``] (``, which no link grammar reads as one."""
    return _NOTIFICATION_LINK.sub("] (", text(value))


def sarif_text(value) -> str:
    """A SARIF plain text message (a result's, a related location's): the text exact for a SARIF
    viewer. SARIF reads ``[text](id)`` as an embedded link (3.11.6: to a related location or a
    URI; ``\\[``, ``\\]`` and ``\\\\`` are a bracket and a backslash) and ``{0}`` as a placeholder
    (3.11.5: ``{{`` and ``}}`` are braces), so each is escaped as SARIF says: a link named
    ``[click](0)`` stays text, a name holding ``{0}`` or a backslash stays what it was. The JSON
    encoder escapes the rest."""
    return value.replace("\\", "\\\\").replace("[", "\\[").replace("]", "\\]") \
        .replace("{", "{{").replace("}", "}}")


def csv_cell(value) -> str:
    """A text cell of CSV (csv.writer quotes it): no line break, and a leading ``'`` before
    what a spreadsheet would run as a formula."""
    cell = printable(value)
    return "'" + cell if cell.startswith(_FORMULA) else cell


def dot(*lines) -> str:
    """A Graphviz double-quoted ID or label; each argument is a line of the label (DOT's
    ``\\n``), escaped so that neither its quotes nor DOT's escapes (``\\N``, ``\\l``) nor its
    character entities (``&#x1b;``, ``&#x202e;``: Graphviz draws a quoted string's entities as
    the characters, and writes them into SVG as such) act: ``&`` is ``&amp;``. A DOT ID is a
    node's identity, so the escape is one to one: a backslash of the name is written twice
    before :func:`printable` writes its escapes (the link ``a\\nb``, with a backslash, and ``a``
    line feed ``b`` were one node: two roots drawn as one chain)."""
    return '"' + "\\n".join(printable(str(line).replace("\\", "\\\\")).replace("\\", "\\\\")
                            .replace('"', '\\"').replace("&", "&amp;")
                            for line in lines) + '"'


def yaml_text(data) -> str:
    """``data`` as a YAML document (block style, keys in order): a string that holds anything
    :func:`printable` escapes, or that a plain scalar could not carry on one line, is written
    double-quoted with YAML's own escapes; no scalar is folded onto a line of its own. The data
    stays exact (``yaml.safe_load`` gives it back)."""
    import yaml

    class Dumper(yaml.SafeDumper):
        pass

    def string(dumper, value):
        style = '"' if printable(value) != value else None
        return dumper.represent_scalar("tag:yaml.org,2002:str", value, style=style)

    Dumper.add_representer(str, string)
    return yaml.dump(data, Dumper=Dumper, sort_keys=False, width=float("inf"))


__all__ = ["Lines", "csv_cell", "dot", "lines", "markdown", "markup", "notification",
           "printable", "sarif_text", "svg", "text", "workflow", "write_xml", "xml", "yaml_text"]
