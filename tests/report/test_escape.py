"""urdftool.report.escape: one escaping function per output kind, each held to its kind; and a
scan of the sources that finds output written past them (a renderer printing for itself, an
escaper of another library, a console that is not one of the guarded ones)."""

from __future__ import annotations

import ast
import csv
import io
import json
from pathlib import Path

import pytest
import yaml
from lxml import etree

from conftest import parsed, walked
from urdftool.report import escape

URDFTOOL = Path(escape.__file__).resolve().parent.parent
HOSTILE = ("j\n::error file=a.urdf,line=1::pwned\r\n## All checks passed\x1b[2J\x1b]8;;https://e"
           "\x1b\\l\x1b]8;;\x1b\\\x9b31m\u202eevil\u2066\u2028|a|`b`<img src=x onerror=1>"
           "[bold]x[/]:thumbs_up:\t=cmd()")


def _one_line_without_controls(text: str) -> bool:
    import unicodedata

    return not any(unicodedata.category(c) in ("Cc", "Cf", "Cs", "Zl", "Zp") for c in text)


def test_text_is_one_line_with_nothing_a_terminal_or_a_runner_acts_on():
    shown = escape.text(HOSTILE)
    assert _one_line_without_controls(shown)
    assert shown.startswith("j\\n::error file=a.urdf,line=1::pwned\\r\\n## All checks passed\\x1b")
    for name in ("::error::x", "  ::warning::x", "\u3000::add-mask::x", ":x"):
        assert not escape.text(name).lstrip().startswith(":"), name
    assert escape.text("  ::x") == "  \\x3a:x"
    assert escape.text(escape.text(HOSTILE)) == escape.text(HOSTILE)  # idempotent
    assert escape.text("naïve 机器人 a::b") == "naïve 机器人 a::b"


def test_lines_keeps_a_renderers_lines_and_guards_each():
    block = "first\n" + "::error::x\n  \x1b[31mred\n"
    assert escape.lines(block) == "first\n\\x3a:error::x\n  \\x1b[31mred\n"
    assert escape.lines("\t<link/>\n\t::x\x1b", keep="\t") == "\t<link/>\n\t\\x3a:x\\x1b"


def test_lines_keeps_a_carriage_return_that_ends_a_line_only_when_asked():
    """``check --diff`` of a CR LF file: each line's CR was written ``\\r``, so no line of the
    diff matched the file and ``git apply`` refused it; a CR anywhere else still hides the
    start of its line on a terminal, and stays escaped."""
    block = "-a\r\n+b\r\n c\rd::error::x\r\n\r"
    assert escape.lines(block, "\t\r") == "-a\r\n+b\r\n c\\rd::error::x\r\n\r"
    assert escape.lines(block, "\t") == "-a\\r\n+b\\r\n c\\rd::error::x\\r\n\\r"
    assert escape.lines("\r::error::x\r", "\r") == "\\r::error::x\r"


def test_the_lines_stream_guards_every_line_a_library_writes():
    out = io.StringIO()
    stream = escape.Lines(out)
    stream.write("a\n::er")
    stream.write("ror::x\x1b\nlast")
    stream.flush()
    assert out.getvalue() == "a\n\\x3a:error::x\\x1b\nlast" and not stream.isatty()


def test_the_lines_stream_drops_the_blanks_rich_pads_a_last_column_with():
    from urdftool.report.console import plain_console
    from rich.table import Table

    out = io.StringIO()
    table = Table("link", "status", box=None)
    table.add_row("l_foot_link", "")  # collisions' "Closest pairs apart": no status
    table.add_row("body_link", "disabled (User)")
    plain_console(out).print(table)
    assert [line.split() for line in out.getvalue().splitlines()] == [
        ["link", "status"], ["l_foot_link"], ["body_link", "disabled", "(User)"]]
    assert not any(line.endswith(" ") for line in out.getvalue().splitlines())


def test_markup_is_printed_by_rich_as_written():
    from rich.console import Console

    out = io.StringIO()
    Console(file=out, width=1000, emoji=False).print(escape.markup("[bold red]x[/] [link=u]y"))
    assert out.getvalue() == "[bold red]x[/] [link=u]y\n"


def test_workflow_data_and_properties_cannot_end_the_command():
    data = escape.workflow(HOSTILE)
    assert "\n" not in data and "\r" not in data and "%0A" in data and "\x1b" not in data
    assert escape.workflow("50%") == "50%25"
    assert escape.workflow("a:b,c\n", property=True) == "a%3Ab%2Cc%0A"


def test_markdown_is_a_code_span_whatever_it_holds():
    from markdown_it import MarkdownIt

    for value in (HOSTILE, "`", "``x``", " a ", "", "# h", "![i](u)", "<script>"):
        span = escape.markdown(value)
        [block] = [t for t in MarkdownIt("commonmark").enable("table").parse(f"- {span}\n")
                   if t.type == "inline"]
        assert [child.type for child in block.children] == ["code_inline"], value
        assert "\n" not in span
    cell = MarkdownIt("commonmark").enable("table").parse(
        f"| a | b |\n|---|---|\n| {escape.markdown('x|y')} | z |\n")
    assert sum(t.type == "td_open" for t in cell) == 2


def test_xml_and_svg_values_make_documents_that_parse_and_say_the_same():
    element = etree.Element("failure", message=escape.xml(HOSTILE))
    element.text = escape.xml(HOSTILE)
    parsed = etree.fromstring(etree.tostring(element))
    assert parsed.get("message") == parsed.text == escape.text(HOSTILE)
    svg = f'<svg><text a="{escape.svg(HOSTILE)}">{escape.svg(HOSTILE)}</text></svg>'
    root = etree.fromstring(svg.encode())
    assert [e.tag for e in root.iter()] == ["svg", "text"]
    assert root[0].text == root[0].get("a") == escape.printable(HOSTILE)


@pytest.mark.parametrize("char", ["\x00", "\x1f", "\ud800", "\udcff", "\ufffe", "\uffff"])
def test_every_character_xml_cannot_hold_is_escaped_for_xml_and_svg(char):
    """A file named with U+FFFE or U+FFFF (valid UTF-8, outside XML 1.0's characters) ended
    ``check -f junit`` with lxml's ValueError traceback and no report."""
    element = etree.Element("failure", message=escape.xml(f"a{char}.urdf"))
    element.text = escape.xml(char)
    assert etree.fromstring(etree.tostring(element)).get("message") == \
        escape.text(f"a{char}.urdf") != f"a{char}.urdf"
    etree.fromstring(f'<svg><text a="{escape.svg(char)}">{escape.svg(char)}</text></svg>')


def test_xml_documents_keep_their_data_and_lose_their_forged_lines():
    root = etree.fromstring('<r a="x&#10;y">\n::error::x\n<!--\n ::c -->\u202e\x85</r>'.encode())
    document = etree.tostring(root, encoding="unicode")
    safe = escape.xml_document(document, root)
    assert not any(line.lstrip().startswith(":") for line in safe.split("\n"))
    assert _one_line_without_controls(safe.replace("\n", ""))
    again = etree.fromstring(safe.encode())
    assert again.text == root.text and again.get("a") == root.get("a")


def test_csv_cells_hold_no_line_break_and_run_no_formula():
    out = io.StringIO()
    csv.writer(out, lineterminator="\n").writerow([escape.csv_cell(HOSTILE), "=1+1", 1])
    assert out.getvalue().count("\n") == 1
    [[first, *_]] = list(csv.reader(io.StringIO(out.getvalue())))
    assert first == escape.printable(HOSTILE)
    assert [escape.csv_cell(v) for v in ("=1+1", "+x", "-y", "@z", "ok")] == \
        ["'=1+1", "'+x", "'-y", "'@z", "ok"]


def test_dot_ids_stay_quoted():
    quoted = escape.dot('a"b\\N', HOSTILE)
    assert quoted.startswith('"a\\"b\\\\\\\\N\\n') and quoted.endswith('"') and "\n" not in quoted
    inner = quoted[1:-1].replace('\\\\', "").replace('\\"', "")
    assert '"' not in inner


def test_dot_ids_of_names_that_differ_differ():
    # session 13: a link named a\nb (a backslash) and one named a, line feed, b were one
    # node of the graph: two roots drawn as one chain
    names = ["a\\nb", "a\nb", "a\\x1bb", "a\x1bb", "a\\\\", "a\\", "a\\u202eb", "a\u202eb"]
    assert len({escape.dot(name) for name in names}) == len(names)
    assert len({escape.dot(*pair) for pair in [("a", "b"), ("a\\nb",), ("a\nb",)]}) == 3


def test_dot_character_entities_are_text_not_characters():
    """Graphviz reads ``&#x1b;`` and ``&#x202e;`` in a quoted string as the characters (in every
    output; in SVG a reference to ESC, which no XML reader takes): a name holding one drew, and
    wrote into the SVG, a control or a bidi override; ``a&amp;b`` and ``a&b`` were one label."""
    assert escape.dot("a&#x1b;b", "c&amp;") == '"a&amp;#x1b;b\\nc&amp;amp;"'
    assert escape.dot("a&b") != escape.dot("a&amp;b")


def test_yaml_reads_back_exactly_and_no_scalar_starts_a_line():
    data = {"joints": [{"joint": HOSTILE, "long": "w " * 200 + "::error::x"}],
            "::k\n::error::key": "é"}
    text = escape.yaml_text(data)
    assert yaml.safe_load(text) == data
    assert not any(line.lstrip().startswith("::") for line in text.split("\n"))
    assert _one_line_without_controls(text.replace("\n", ""))


def test_json_stays_exact_in_ascii():
    from urdftool.report.json_output import dumps

    text = dumps({"name": HOSTILE})
    assert text.isascii() and json.loads(text) == {"name": HOSTILE}


@pytest.mark.parametrize("writer", ["dumps", "line"])
def test_json_holds_no_unpaired_surrogate(writer):
    """A file name's undecodable byte (os.fsdecode: U+DCFF) or a YAML "\\ud800" is a surrogate
    code point: json writes it as an escape no strict reader takes (I-JSON); it is written as
    U+FFFD and the byte's two hex digits (json_output.named), the rest exact (an astral
    character stays a pair)."""
    from urdftool.report import json_output
    from tests.fuzz.forge import unpaired

    data = {"file": "dir\udcff/r.urdf", "k\ud800": ["\U0001F600", "a\\udcff", 1.5]}
    text = getattr(json_output, writer)(data)
    assert unpaired(text, writer) == [] and text.isascii()
    assert json.loads(text) == {"file": "dir\ufffdFF/r.urdf", "k\ufffdED\ufffdA0\ufffd80":
                                ["\U0001F600", "a\\udcff", 1.5]}


# ---- the scan: output written past urdftool.report.escape ------------------------------------

SINKS = {("typer", "echo"), ("click", "echo"), ("sys.stdout", "write"), ("sys.stderr", "write")}
# where a command prints: terminal.py's say, show, document and plain_echo (click's echo)
PRINTERS = {"say", "show", "document", "plain_echo"}
# escapers of other libraries: only urdftool/report/escape.py may call them
FOREIGN_ESCAPERS = {("html", "escape"), ("markup", "escape"), ("saxutils", "escape"),
                    ("yaml", "dump"), ("yaml", "safe_dump"), ("cgi", "escape")}


def _calls(tree):
    """(function it is in, dotted receiver, attribute or name, node) for every call."""
    def walk(node, function):
        for child in ast.iter_child_nodes(node):
            inner = child.name if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)) \
                else function
            if isinstance(child, ast.Call):
                func = child.func
                if isinstance(func, ast.Attribute):
                    yield function, ast.unparse(func.value), func.attr, child
                elif isinstance(func, ast.Name):
                    yield function, "", func.id, child
            yield from walk(child, inner)

    yield from walk(tree, None)


def _sources(*folders: str, files=()):
    for folder in folders:
        yield from sorted((URDFTOOL / folder).glob("*.py"))
    for name in files:
        yield URDFTOOL / name


# modules that print only urdftool's own text (with rich markup of their own)
OWN_TEXT = {"rules.py": "the rule catalogue: codes, names and docstrings are ours"}


def scan() -> list[str]:
    """Each place that writes output past the escaping functions and the guarded sinks."""
    found = []
    for path in _sources("cli", "report", files=("server.py", "pytest_plugin.py", "docs.py",
                                                  "terminal.py", "checking.py")):
        relative = path.relative_to(URDFTOOL.parent).as_posix()
        source = path.read_text()
        tree = parsed(source)
        for node in walked(source):
            if isinstance(node, ast.ImportFrom) and node.module in ("html", "rich.markup") and \
                    any(a.name == "escape" for a in node.names) and \
                    path.name not in ("escape.py", *OWN_TEXT):
                found.append(f"{relative}:{node.lineno}: imports {node.module}.escape "
                             "(use urdftool.report.escape)")
        for function, receiver, name, node in _calls(tree):
            where = f"{relative}:{node.lineno}"
            if (receiver, name) in SINKS or (receiver == "" and name == "print"):
                allowed = path.name == "terminal.py" and function in PRINTERS
                if not allowed and path.name != "docs.py":
                    found.append(f"{where}: {receiver + '.' if receiver else ''}{name}() "
                                 "prints past say/show/document")
            if (receiver.rsplit(".", 1)[-1], name) in FOREIGN_ESCAPERS and \
                    path.name != "escape.py":
                found.append(f"{where}: {receiver}.{name}() escapes for itself")
            if name == "Console" and path.name not in ("console.py", "progress.py"):
                found.append(f"{where}: a rich Console not from report/console.py's guarded "
                             "factories")
            if receiver == "json" and name in ("dumps", "dump") and path.name != "json_output.py":
                found.append(f"{where}: JSON written past report/json_output (dumps, line)")
            for keyword in node.keywords:
                if keyword.arg == "ensure_ascii" and isinstance(keyword.value, ast.Constant) \
                        and keyword.value.value is False:
                    found.append(f"{where}: JSON with raw non-ASCII (bidi, C1) characters")
    return found


def test_nothing_prints_past_the_escaping_functions():
    assert scan() == []


def test_the_scan_finds_each_bypass(tmp_path, monkeypatch):
    """The scan can fail: a module of each kind of bypass, written where it looks."""
    bypasses = {
        "cli/bad_echo.py": "import typer\ndef run(name):\n    typer.echo(name)\n",
        "cli/bad_print.py": "def run(name):\n    print(name)\n",
        "report/bad_html.py": "from html import escape\ndef svg(n):\n    return escape(n)\n",
        "report/bad_yaml.py": "import yaml\ndef out(d, s):\n    s.write(yaml.safe_dump(d))\n",
        "report/bad_console.py": "from rich.console import Console\ndef c():\n"
                                 "    return Console()\n",
        "report/bad_json.py": "import json\ndef j(d):\n    return json.dumps(d, "
                              "ensure_ascii=False)\n",
        "report/bad_stdout.py": "import sys\ndef w(t):\n    sys.stdout.write(t)\n",
        "report/bad_lines.py": "import json\ndef j(d, s):\n    s.write(json.dumps(d))\n",
    }
    fake = tmp_path / "urdftool"
    for relative, source in bypasses.items():
        (fake / relative).parent.mkdir(parents=True, exist_ok=True)
        (fake / relative).write_text(source)
    for name in ("server.py", "pytest_plugin.py", "docs.py", "terminal.py", "checking.py"):
        (fake / name).write_text("")
    monkeypatch.setattr(__import__(__name__), "URDFTOOL", fake)
    found = scan()
    assert len({line.split(":")[0] for line in found}) == len(bypasses), found
    for relative in bypasses:
        assert any(line.startswith(f"urdftool/{relative}:") for line in found), relative


@pytest.mark.parametrize("function", ["text", "markup", "workflow", "markdown", "xml", "svg",
                                      "csv_cell", "dot"])
def test_every_kind_escapes_a_lone_surrogate_from_a_file_name(function):
    value = getattr(escape, function)("a\udce9b")
    assert "\udce9" not in value and value.encode("utf-8")


@pytest.mark.parametrize("encoding", ["ascii", "latin-1", "utf-8"])
def test_xml_on_a_stream_that_cannot_hold_a_name_keeps_it_exact(encoding):
    """An ASCII or Latin-1 locale: the stream writes what it cannot encode as a backslash
    escape (terminal text), which in XML is another name (b\\u0101); XML gets character
    references, read back as the name, and the stream keeps its own handler after."""
    import io

    from lxml import etree

    from urdftool.report.escape import write_xml

    raw = io.BytesIO()
    stream = io.TextIOWrapper(raw, encoding=encoding, errors="backslashreplace")
    write_xml(stream, '<robot name="b\u0101\u00e9"><link name="\u4e2d"/></robot>')
    stream.write("\u0101\n")
    stream.flush()
    document, after = raw.getvalue().rsplit(b">", 1)
    root = etree.fromstring(document.decode(encoding) + ">")  # (read as its encoding says)
    assert root.get("name") == "b\u0101\u00e9" and root[0].get("name") == "\u4e2d"
    assert after == ("\u0101\n".encode() if encoding == "utf-8" else b"\\u0101\n")
