"""``urdftool server`` driven by a real LSP client over stdio (pytest-lsp): diagnostics on open,
on change (debounced) and on save, on the macro file and the companion a finding is in; hover;
the suppression quick fix; a check that raises does not stop the server."""

from __future__ import annotations

import asyncio
import re
import shutil
import sys
import textwrap
from pathlib import Path

import pytest

pytest_lsp = pytest.importorskip("pytest_lsp")
from lsprotocol import types  # noqa: E402
from pytest_lsp import ClientServerConfig, LanguageClient, client_capabilities  # noqa: E402

from conftest import CASES  # noqa: E402
from rule_links import assert_rule_page  # noqa: E402
from slow_robots import slow_xacro  # noqa: E402

MACRO = """\
<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="arm" params="prefix lower upper">
    <link name="${prefix}_link"/>
    <joint name="${prefix}_joint" type="revolute">
      <parent link="base_link"/><child link="${prefix}_link"/>
      <axis xyz="0 0 1"/>
      <limit lower="${lower}" upper="${upper}" effort="5" velocity="1"/>
    </joint>
  </xacro:macro>
</robot>
"""
ROBOT = """\
<?xml version="1.0"?>
<robot name="bot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="arm.xacro"/>
  <link name="base_link"/>
  <xacro:arm prefix="left" lower="{lower}" upper="{upper}"/>
</robot>
"""
BROKEN, FIXED = ROBOT.format(lower=1, upper=-1), ROBOT.format(lower=-1, upper=1)
LIMIT_LINE, CALL_LINE = 7, 4  # 0-based: the <limit> in arm.xacro, the macro call in the robot


@pytest_lsp.fixture(scope="module", config=ClientServerConfig(
    server_command=[sys.executable, "-m", "urdftool", "server"]))
async def editor(lsp_client: LanguageClient):
    """One server for the editor tests of a test process (its start: 0.5 s of CPU, importing
    lsprotocol). Each test works in its own folder, which no other test's documents concern,
    and reads only what concerns its own files (see ``client``)."""
    lsp_client.registrations = []

    @lsp_client.feature(types.CLIENT_REGISTER_CAPABILITY)
    def register(params: types.RegistrationParams):  # as an editor does: it watches the files
        lsp_client.registrations.extend(params.registrations)

    await lsp_client.initialize_session(types.InitializeParams(
        capabilities=client_capabilities("visual-studio-code")))
    yield
    await lsp_client.shutdown_session()


@pytest.fixture
def client(editor: LanguageClient) -> LanguageClient:
    """The shared server, its messages and logs from earlier tests forgotten (diagnostics are
    kept by URI, and each test's URIs are its own; ``checked`` matches the whole path)."""
    editor.messages.clear()
    editor.log_messages.clear()
    return editor


SHARED = pytest.mark.asyncio(loop_scope="module")  # the tests of the shared server (its loop)


async def wait_until(condition, seconds: float = 60.0):
    """Poll ``condition()`` until it is true (a check takes about a second the first time)."""
    for _ in range(int(seconds / 0.05)):
        if condition():
            return
        await asyncio.sleep(0.05)
    raise AssertionError("timed out waiting for the server")


def open_document(client: LanguageClient, path: Path, text: str | None = None,
                  language: str = "xml") -> str:
    uri = path.as_uri()
    client.text_document_did_open(types.DidOpenTextDocumentParams(
        text_document=types.TextDocumentItem(uri=uri, language_id=language, version=1,
                                             text=path.read_text() if text is None else text)))
    return uri


def change_document(client: LanguageClient, uri: str, version: int, text: str) -> None:
    client.text_document_did_change(types.DidChangeTextDocumentParams(
        text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=version),
        content_changes=[types.TextDocumentContentChangeWholeDocument(text=text)]))


def codes(client: LanguageClient, uri: str) -> list[tuple[int, str]]:
    return [(d.range.start.line, d.code) for d in client.diagnostics.get(uri, [])]


def checked(client: LanguageClient, robot: Path | str) -> list[str]:
    """The server's log lines of the checks of ``robot``: its whole path (a server checks the
    robots of other tests too), or a word in it for a server of the test's own."""
    return [m.message for m in client.log_messages if m.message.startswith("checked ")
            and (m.message.startswith((f"checked {robot} (", f"checked {robot}:"))
                 if isinstance(robot, Path) else robot in m.message)]


def write_robot(folder: Path, robot: str = BROKEN) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "arm.xacro").write_text(MACRO)
    path = folder / "robot.urdf.xacro"
    path.write_text(robot)
    return path


@SHARED
async def test_a_finding_in_an_included_macro_is_published_there_and_cleared_when_fixed(
        client: LanguageClient, tmp_path):
    robot = write_robot(tmp_path / "bot")
    macro_uri = (tmp_path / "bot" / "arm.xacro").as_uri()
    uri = open_document(client, robot)
    await wait_until(lambda: macro_uri in client.diagnostics and uri in client.diagnostics)

    [on_macro] = client.diagnostics[macro_uri]
    assert (on_macro.range.start.line, on_macro.code, on_macro.source) == \
        (LIMIT_LINE, "U204", "urdftool")
    assert on_macro.severity == types.DiagnosticSeverity.Error
    assert "lower limit 1 is above upper limit -1" in on_macro.message
    assert_rule_page(on_macro.code_description.href, "U204")
    assert [(r.location.uri, r.location.range.start.line) for r in on_macro.related_information] \
        == [(uri, CALL_LINE)]
    [at_call] = client.diagnostics[uri]
    assert (at_call.range.start.line, at_call.code) == (CALL_LINE, "U204")
    assert at_call.range.start.character == 2  # the element, not its indentation
    assert [(r.location.uri, r.location.range.start.line) for r in at_call.related_information] \
        == [(macro_uri, LIMIT_LINE)]

    change_document(client, uri, 2, FIXED)  # fixed in the buffer, not on disk
    await wait_until(lambda: codes(client, uri) == [] and codes(client, macro_uri) == [])
    assert robot.read_text() == BROKEN


@SHARED
async def test_an_unsaved_edit_in_an_included_macro_file_rechecks_its_robot_until_closed(
        client: LanguageClient, tmp_path):
    robot = write_robot(tmp_path / "bot", FIXED)
    macro = tmp_path / "bot" / "arm.xacro"
    uri = open_document(client, robot)
    await wait_until(lambda: checked(client, robot))
    macro_uri = open_document(client, macro)  # checks its robot again
    await wait_until(lambda: len(checked(client, robot)) == 2)
    assert codes(client, uri) == [] and codes(client, macro_uri) == []

    edited = MACRO.replace("  <xacro:macro", "  <!-- two lines\n  more -->\n  <xacro:macro") \
        .replace('lower="${lower}"', 'lower="2"')  # the limit, two lines down, inverted
    change_document(client, macro_uri, 2, edited)  # in the buffer, not saved
    await wait_until(lambda: codes(client, macro_uri) == [(LIMIT_LINE + 2, "U204")]
                     and codes(client, uri) == [(CALL_LINE, "U204")])
    assert "lower limit 2 is above upper limit 1" in client.diagnostics[macro_uri][0].message
    assert macro.read_text() == MACRO

    client.text_document_did_close(types.DidCloseTextDocumentParams(
        text_document=types.TextDocumentIdentifier(uri=macro_uri)))  # unsaved: the disk's
    await wait_until(lambda: codes(client, macro_uri) == [] and codes(client, uri) == [])


TWO_URIS = ('<robot name="r"><link name="a"/><link name="b"/>\n<joint name="j" type="revolute">'
            '<parent link="a"/><child link="b"/><axis xyz="0 0 1"/>\n'
            '<limit lower="{}" upper="{}" effort="1" velocity="1"/></joint></robot>\n')


@SHARED
async def test_one_file_open_by_two_uris_is_one_document_to_every_check(client, tmp_path):
    """Session 20 left it: two URIs of one path (``…/r.urdf`` and ``…/sub/../r.urdf``) were
    one entry of the open documents, the URI opened last: an edit in the other was checked
    in that one's buffer (the fix never seen) and published to it only (the other kept its
    diagnostics), and once that one was closed the file was no longer open, its edits
    ignored. Now each URI of the path is published to, the buffer edited last is the one a
    check reads, and closing one leaves the file open by the other."""
    folder = tmp_path / "two-uris"
    folder.mkdir()
    robot = folder / "r.urdf"
    robot.write_text(TWO_URIS.format(1, -1))
    first = open_document(client, robot)
    second = folder.as_uri() + "/sub/../r.urdf"
    client.text_document_did_open(types.DidOpenTextDocumentParams(
        text_document=types.TextDocumentItem(uri=second, language_id="xml", version=1,
                                             text=robot.read_text())))

    def has(uri) -> bool:
        return any(code == "U204" for _, code in codes(client, uri))

    await wait_until(lambda: has(first) and has(second))
    change_document(client, first, 2, TWO_URIS.format(-1, 1))
    await wait_until(lambda: not has(first) and not has(second))
    client.text_document_did_close(types.DidCloseTextDocumentParams(
        text_document=types.TextDocumentIdentifier(uri=second)))
    change_document(client, first, 3, TWO_URIS.format(2, -2))
    await wait_until(lambda: has(first))
    client.text_document_did_close(types.DidCloseTextDocumentParams(
        text_document=types.TextDocumentIdentifier(uri=first)))


@SHARED
async def test_quick_changes_are_checked_once_at_their_last_version(client: LanguageClient,
                                                                     tmp_path):
    robot = write_robot(tmp_path / "bot", FIXED)
    uri = open_document(client, robot)
    await wait_until(lambda: checked(client, robot))
    assert codes(client, uri) == []

    for version in range(2, 7):  # well within the debounce time; only the last one is broken
        change_document(client, uri, version, BROKEN if version == 6 else FIXED + " " * version)
    await wait_until(lambda: len(checked(client, robot)) > 1)
    await asyncio.sleep(1.0)  # a check of an older version would have been logged by now

    assert len(checked(client, robot)) == 2
    assert "(version 6)" in checked(client, robot)[-1]
    assert codes(client, uri) == [(CALL_LINE, "U204")]


@SHARED
async def test_hover_on_a_rule_code_shows_its_documentation(client: LanguageClient, tmp_path):
    from urdftool.lint.rules import CATALOGUE

    text = FIXED.replace("  <link name=\"base_link\"/>",
                         "  <!-- urdftool: ignore U204, unused-suppression -->\n"
                         "  <link name=\"base_link\"/>")
    uri = open_document(client, write_robot(tmp_path / "bot", text))
    line = text.splitlines().index("  <!-- urdftool: ignore U204, unused-suppression -->")

    hover = await client.text_document_hover_async(types.HoverParams(
        text_document=types.TextDocumentIdentifier(uri=uri),
        position=types.Position(line, text.splitlines()[line].index("U204") + 2)))
    assert "**U204 inverted-limits**" in hover.contents.value
    assert CATALOGUE.get("U204").summary in hover.contents.value
    by_name = await client.text_document_hover_async(types.HoverParams(
        text_document=types.TextDocumentIdentifier(uri=uri),
        position=types.Position(line, text.splitlines()[line].index("unused-suppression") + 3)))
    assert "**U901 unused-suppression**" in by_name.contents.value
    nothing = await client.text_document_hover_async(types.HoverParams(
        text_document=types.TextDocumentIdentifier(uri=uri), position=types.Position(0, 3)))
    assert nothing is None


def apply(text: str, edits: list[types.TextEdit]) -> str:
    lines = text.splitlines(keepends=True)
    for edit in sorted(edits, key=lambda e: (e.range.start.line, e.range.start.character),
                       reverse=True):
        start = sum(map(len, lines[:edit.range.start.line])) + edit.range.start.character
        end = sum(map(len, lines[:edit.range.end.line])) + edit.range.end.character
        text = text[:start] + edit.new_text + text[end:]
        lines = text.splitlines(keepends=True)
    return text


@SHARED
async def test_the_quick_fix_inserts_a_suppression_that_silences_the_finding(
        client: LanguageClient, tmp_path):
    path = tmp_path / "robot.urdf"
    text = (CASES / "U204_inverted_limits.urdf").read_text()
    path.write_text(text)
    uri = open_document(client, path)
    await wait_until(lambda: client.diagnostics.get(uri))
    [diagnostic] = client.diagnostics[uri]

    actions = await client.text_document_code_action_async(types.CodeActionParams(
        text_document=types.TextDocumentIdentifier(uri=uri), range=diagnostic.range,
        context=types.CodeActionContext(diagnostics=[diagnostic])))
    titles = [action.title for action in actions]
    assert titles == ["Ignore U204 (inverted-limits) here",
                      "Ignore U204 (inverted-limits) in this file"]
    [preferred] = [action for action in actions if action.is_preferred]
    fixed = apply(text, preferred.edit.changes[uri])
    limit = diagnostic.range.start.line
    assert fixed.splitlines()[limit] == "    <!-- urdftool: ignore U204 -->"
    assert fixed.splitlines()[limit + 1] == text.splitlines()[limit]

    change_document(client, uri, 2, fixed)
    await wait_until(lambda: len(checked(client, path)) == 2)
    assert codes(client, uri) == []  # silenced, and the suppression is used (no U901)


@SHARED
async def test_a_companion_file_gets_its_findings_and_a_macro_library_its_robots(
        client: LanguageClient, tmp_path):
    folder = tmp_path / "ctl"
    shutil.copytree(CASES / "U602_controller_unknown_joint", folder)
    controllers = folder / "config" / "controllers.yaml"
    uri = open_document(client, controllers, language="yaml")
    await wait_until(lambda: uri in client.diagnostics)
    line = controllers.read_text().splitlines().index("      - head_jnt  # expect: U602")
    assert (line, "U602") in codes(client, uri)

    fixed = controllers.read_text().replace("      - head_jnt  # expect: U602\n", "")
    change_document(client, uri, 2, fixed)  # as an editor saves: the buffer, then the file
    controllers.write_text(fixed)
    client.text_document_did_save(types.DidSaveTextDocumentParams(
        text_document=types.TextDocumentIdentifier(uri=uri)))
    await wait_until(lambda: (line, "U602") not in codes(client, uri))

    write_robot(tmp_path / "bot")
    macro_uri = open_document(client, tmp_path / "bot" / "arm.xacro")  # a library: its robot
    await wait_until(lambda: macro_uri in client.diagnostics)
    assert codes(client, macro_uri) == [(LIMIT_LINE, "U204")]


@SHARED
async def test_a_check_that_raises_is_reported_and_the_server_goes_on(client: LanguageClient,
                                                                      tmp_path):
    bad = write_robot(tmp_path / "bad")
    (tmp_path / "bad" / "urdftool.toml").write_text('select = ["U999"]\n')
    open_document(client, bad)
    await wait_until(lambda: client.messages)
    [message] = client.messages
    assert message.type == types.MessageType.Error
    assert "no rule 'U999'" in message.message

    uri = open_document(client, write_robot(tmp_path / "good"))
    await wait_until(lambda: uri in client.diagnostics)
    assert codes(client, uri) == [(CALL_LINE, "U204")]
    assert bad.as_uri() not in client.diagnostics  # nothing published for it


@SHARED
async def test_saving_a_settings_file_rechecks_the_robots_under_it(client: LanguageClient,
                                                                   tmp_path):
    uri = open_document(client, write_robot(tmp_path / "bot"))
    await wait_until(lambda: codes(client, uri))
    settings = tmp_path / "bot" / "urdftool.toml"
    settings.write_text('ignore = ["inverted-limits"]\n')
    client.text_document_did_save(types.DidSaveTextDocumentParams(
        text_document=types.TextDocumentIdentifier(uri=settings.as_uri())))
    await wait_until(lambda: codes(client, uri) == [])
    assert codes(client, (tmp_path / "bot" / "arm.xacro").as_uri()) == []


def test_a_crash_in_the_check_becomes_an_error_not_an_exception(monkeypatch, tmp_path):
    from urdftool import server
    from urdftool.lint import runner

    def crash(path, data=None):
        raise RuntimeError("boom")

    monkeypatch.setattr(runner, "check_file", crash)
    outcome = server.check_robot(str(write_robot(tmp_path)), {}, None)
    assert outcome.by_path == {} and not outcome.user_error
    assert "RuntimeError: boom" in outcome.error


def test_a_file_named_with_bytes_that_are_not_utf8_has_one_uri_read_back_exactly(monkeypatch,
                                                                                  tmp_path):
    # session 13: pygls's from_fs_path raised UnicodeEncodeError on such a name, so a robot
    # whose controllers YAML or launch file was so named lost its whole check to U900; its
    # to_fs_path read each such byte as U+FFFD, a file that is not there
    import os

    from pygls.workspace.position_codec import PositionCodec

    from urdftool import server
    from urdftool.diagnostics import Finding, Location, Severity
    from urdftool.lint import runner

    name = os.fsdecode(os.fsencode(str(tmp_path)) + b"/c\n\xff\xfe\x1b%.yaml")
    for path in (name, str(tmp_path / "a b#é%.yaml")):
        uri = server.uri_of_path(path)
        assert uri.isascii() and server.path_of_uri(uri) == path
    robot = str(write_robot(tmp_path))
    finding = Finding("U602", "controller-unknown-joint", Severity.WARNING, "m",
                      Location(name, 1))
    monkeypatch.setattr(runner, "check_file",
                        lambda path, data=None: runner.FileResult(path, [finding]))
    outcome = server.check_robot(robot, {}, PositionCodec())
    assert outcome.error is None and [f.code for _, f in outcome.by_path[name]] == ["U602"]


def test_a_check_out_of_memory_is_the_budgets_finding_not_an_internal_error(monkeypatch,
                                                                            tmp_path):
    """A MemoryError in a check (a flood of many-link documents under the memory budget: the
    kept fuzz sessions server-134d20129a69 and server-875c27987241, replayed by ``make fuzz``)
    is the budget's: the pool makes it U018 on the robot, not an internal error with a
    traceback in the editor's log. The check runs in a forked worker, as the server runs it."""
    import threading

    from pygls.workspace.position_codec import PositionCodec

    from urdftool import server
    from urdftool.lint import runner

    def exhausted(path, data=None):
        raise MemoryError

    monkeypatch.setattr(runner, "check_file", exhausted)
    robot = str(write_robot(tmp_path))
    outcome = server.checked(robot, {}, PositionCodec(), server.Limits(timeout=60),
                             threading.Event())
    assert outcome.error is None
    assert [finding.code for _, finding in outcome.by_path[robot]] == ["U018"]


def test_without_pygls_the_command_says_which_extra_to_install():
    import subprocess

    hide = ("import sys; sys.modules.update(pygls=None, lsprotocol=None); "
            "sys.argv = ['urdftool', 'server']; from urdftool.cli import main; main()")
    result = subprocess.run([sys.executable, "-c", hide], capture_output=True, text=True,
                            timeout=120)
    assert result.returncode == 2
    from urdftool.origin import install_command

    assert install_command("lsp") in result.stderr and "Traceback" not in result.stderr


def test_ranges_count_in_the_clients_units():
    from pygls.workspace.position_codec import PositionCodec

    from urdftool.diagnostics import Location
    from urdftool.server import _range

    text = textwrap.dedent("""\
        <robot name="é">
          <!-- 𝜃 --><joint name="j"/>
        </robot>
        """)
    utf16 = _range(Location("r.urdf", 2, column=13), text, PositionCodec())
    assert (utf16.start.line, utf16.start.character, utf16.end.character) == (1, 13, 30)
    utf32 = _range(Location("r.urdf", 2, column=13),
                   text, PositionCodec(types.PositionEncodingKind.Utf32))
    assert (utf32.start.character, utf32.end.character) == (12, 29)
    unknown = _range(Location("r.urdf", 2), text, PositionCodec())
    assert unknown.start.character == 2


def test_the_ranges_of_a_files_findings_split_and_measure_it_once(monkeypatch):
    """Each finding's range split its whole file again and counted its line twice with pygls's
    counters (character by character, in Python): a one-line robot of 1,000 findings took
    8.5 s to publish after a 0.5 s check. The file is split once, each line measured once, by
    its encoding; every range is still what pygls counts, in each of its encodings."""
    import random

    from pygls.workspace.position_codec import PositionCodec

    import urdftool.server as server
    from urdftool.diagnostics import Finding, Location, Severity

    rng = random.Random(17)
    alphabet = ["a", " ", "\t", "\xe9", "\u20ac", "\U0001d703", "\udcff", "\n", "\r\n", "\r"]
    for _ in range(200):
        text = "".join(rng.choice(alphabet) for _ in range(rng.randrange(0, 40)))
        place = Location("r.urdf", rng.randrange(1, 6),
                         column=rng.choice([None, *range(1, 12)]))
        for encoding in (types.PositionEncodingKind.Utf8, types.PositionEncodingKind.Utf16,
                         types.PositionEncodingKind.Utf32, "latin-1"):
            codec = PositionCodec(encoding)
            lines = server.lines_of(text) or [""]
            number = min(max(place.line - 1, 0), len(lines) - 1)
            line = lines[number]
            start = min(place.column - 1, len(line)) if place.column is not None else \
                len(line) - len(line.lstrip())
            end, start = codec.client_num_units(line), codec.client_num_units(line[:start])
            span = server._range(place, text, codec)
            assert (span.start.line, span.start.character, span.end.character) == \
                (number, start if start < end else 0, end), (text, place, encoding)
    text = "<robot>" + "<link/>" * 1000 + "</robot>"
    findings = [Finding("U206", "axis-not-unit", Severity.WARNING, "m",
                        Location("/w/r.urdf", 1, column=8 + 7 * i))
                for i in range(1000)]
    splits = []
    monkeypatch.setattr(server, "lines_of", lambda *a, **k: splits.append(1) or [text])
    codec = PositionCodec()
    monkeypatch.setattr(codec, "client_num_units", None)  # (pygls's counter: never asked)
    shown = server.diagnostics_by_path(findings, lambda path: text, codec)
    assert len(splits) == 1 and len(shown["/w/r.urdf"]) == 1000
    assert shown["/w/r.urdf"][-1][0].range.start.character == 8 + 7 * 999 - 1


def test_lines_are_the_protocols_a_line_separator_or_nel_ends_none():
    """pygls and ``_range`` split with str.splitlines, which also ends a line at U+2028, NEL
    and FF (XML holds them raw in a comment): an editor's incremental change after one went
    into another line, and a diagnostic's range was measured on another line's text."""
    from pygls.workspace.position_codec import PositionCodec

    from urdftool.diagnostics import Location
    from urdftool.server import Document, _range

    text = '<robot name="r"> <!-- a\u2028b\x85c\x0cd -->\n  <link name="base"/>\n</robot>\n'
    document = Document("file:///r.urdf", text,
                        sync_kind=types.TextDocumentSyncKind.Incremental)
    assert len(document.lines) == 3
    document.apply_change(types.TextDocumentContentChangePartial(
        range=types.Range(start=types.Position(1, 14), end=types.Position(1, 18)),
        text="arm"))
    assert document.source == text.replace('"base"', '"arm"')
    span = _range(Location("r.urdf", 2, column=3), text, PositionCodec())
    assert (span.start.line, span.start.character, span.end.character) == (1, 2, 21)
    lines = Document("file:///r.urdf", "a\rb\r\nc\nd").lines
    assert lines == ("a\r", "b\r\n", "c\n", "d")


def _applied(text: str, span: types.Range, new: str) -> str:
    """The protocol's meaning of an incremental change, on the whole text: a line is ended by
    CR LF, LF or CR, a character past a line's end is its end, a line past the last the end."""
    from urdftool.diagnostics import lines_of

    lines = lines_of(text, keepends=True)

    def offset(position):
        if position.line >= len(lines):
            return len(text)
        line = lines[position.line]
        body = line[:-2] if line.endswith("\r\n") else \
            line[:-1] if line.endswith(("\r", "\n")) else line
        units = count = 0
        for character in body:
            if units >= position.character:
                break
            units, count = units + (2 if ord(character) > 0xFFFF else 1), count + 1
        return sum(map(len, lines[:position.line])) + count

    start, end = sorted((offset(span.start), offset(span.end)))
    return text[:start] + new + text[end:]


def test_incremental_changes_mean_what_the_protocol_says_and_cost_what_they_span(monkeypatch):
    """Drawn documents of CR, LF, CR LF, U+2028, NEL and characters outside the BMP, drawn
    changes (past a line's end, past the last line, joining a CR and a LF): the document is the
    text the protocol means. And a replace-all of 2,000 edits in a 20,000-line robot splits
    what the edits span, not the document 2,000 times (pygls: 5 s of the server's loop)."""
    import random

    import urdftool.server as server
    from urdftool.diagnostics import lines_of

    draw = random.Random(15)
    pieces = ["a", "b", "\n", "\r", "\r\n", "\u2028", "\x85", "é", "\U0001f60b"]
    for _ in range(400):
        text = "".join(draw.choice(pieces) for _ in range(draw.randint(0, 12)))
        document = server.Document("file:///r.urdf", text,
                                   sync_kind=types.TextDocumentSyncKind.Incremental)
        for _ in range(draw.randint(1, 5)):
            most = len(lines_of(text, keepends=True)) + 1
            span = types.Range(start=types.Position(draw.randint(0, most), draw.randint(0, 4)),
                               end=types.Position(draw.randint(0, most), draw.randint(0, 4)))
            new = "".join(draw.choice(pieces) for _ in range(draw.randint(0, 4)))
            text = _applied(text, span, new)
            document.apply_change(types.TextDocumentContentChangePartial(range=span, text=new))
            assert (document.source, list(document.lines)) == \
                (text, lines_of(text, keepends=True))
    robot = "<robot>\n" + "".join(f'  <link name="link_{i}"/>\n' for i in range(20_000))
    document = server.Document("file:///r.urdf", robot + "</robot>\n",
                               sync_kind=types.TextDocumentSyncKind.Incremental)
    document.lines  # noqa: B018  (split once, as the first change does)
    split = []
    monkeypatch.setattr(server, "lines_of", lambda text, keepends=False: split.append(
        len(text)) or lines_of(text, keepends))
    for line in range(1, 2_001):
        document.apply_change(types.TextDocumentContentChangePartial(
            range=types.Range(start=types.Position(line, 14), end=types.Position(line, 18)),
            text="LINK"))
    assert document.source.count("LINK") == 2_000 and sum(split) < 100_000


@SHARED
async def test_an_incremental_change_after_a_line_separator_is_the_editors(
        client: LanguageClient, tmp_path):
    """The served document is the editor's: the robot's limits mended by an incremental change
    below a comment holding U+2028 clear its finding (pygls changed another line: U001)."""
    text = BROKEN.replace('<link name="base_link"/>', '<link name="base_link"/> <!-- \u2028 -->')
    robot = write_robot(tmp_path / "bot", text)
    uri = open_document(client, robot, text)
    await wait_until(lambda: codes(client, uri) == [(CALL_LINE, "U204")])
    line = text.split("\n")[CALL_LINE]
    start = line.index('lower="1" upper="-1"')
    client.text_document_did_change(types.DidChangeTextDocumentParams(
        text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=2),
        content_changes=[types.TextDocumentContentChangePartial(
            range=types.Range(start=types.Position(CALL_LINE, start),
                              end=types.Position(CALL_LINE, start + 20)),
            text='lower="-1" upper="1"')]))
    await wait_until(lambda: len(checked(client, robot)) == 2)
    assert codes(client, uri) == []


def test_the_vscode_extension_starts_the_server_for_the_files_it_checks():
    import re

    from conftest import ROOT
    from urdftool.server import COMPANION_SUFFIXES, ROBOT_SUFFIXES

    source = (ROOT / "editors" / "vscode" / "extension.js").read_text()
    assert '{ command: "urdftool", args: ["server"] }' in source
    patterns = re.findall(r'pattern: "\*\*/\*\.\{([^}]*)\}"', source)
    suffixes = {suffix for pattern in patterns for suffix in pattern.split(",")}
    robot = {s.lstrip(".") for s in ROBOT_SUFFIXES}
    # robot files in capitals too (SolidWorks' NAME.URDF), as the server takes them
    assert suffixes == robot | {s.upper() for s in robot} | {
        s.lstrip(".") for s in COMPANION_SUFFIXES}


@pytest.fixture
def offline_server(monkeypatch, tmp_path):
    """A server with a workspace and no client: what it would publish is recorded."""
    from pygls.workspace import Workspace

    from urdftool.server import UrdftoolServer

    server = UrdftoolServer()
    server.protocol._workspace = Workspace(tmp_path.as_uri())
    sent = []
    monkeypatch.setattr(server, "text_document_publish_diagnostics",
                        lambda params: sent.append((params.uri, len(params.diagnostics))))
    monkeypatch.setattr(server, "window_log_message", lambda params: None)
    return server, sent


def _opened(server, path: Path, version: int, text: str) -> tuple[str, str]:
    """(path, URI) of ``text`` opened in the offline server at ``version``."""
    uri = path.as_uri()
    server.protocol.workspace.put_text_document(types.TextDocumentItem(
        uri=uri, language_id="xml", version=version, text=text))
    server.open[str(path)] = uri
    server.aliases.setdefault(str(path), {})[uri] = None
    return str(path), uri


def test_a_result_for_an_older_version_or_an_older_check_is_never_published(offline_server,
                                                                            tmp_path):
    from urdftool.server import Outcome

    server, sent = offline_server
    robot, uri = _opened(server, tmp_path / "robot.urdf", 3, "<robot/>")
    diagnostic = types.Diagnostic(range=types.Range(start=types.Position(0, 0),
                                                    end=types.Position(0, 8)), message="m")

    server._publish(Outcome(robot, 2, {robot: [(diagnostic, None)]}), ticket=5)
    assert sent == []  # checked version 2, the editor has version 3
    server._publish(Outcome(robot, 3, {robot: []}), ticket=7)
    server._publish(Outcome(robot, 3, {robot: [(diagnostic, None)]}), ticket=6)
    assert sent == [(uri, 0)]  # the check that started later wins


def test_code_actions_are_offered_only_for_findings_this_server_published(offline_server,
                                                                          tmp_path):
    """A diagnostic in a codeAction request is the client's: one named "urdftool" that this
    server never published (another extension's, or forged) had its code written into the
    robot by the quick fix: ``<!-- urdftool: ignore U204 --><script/><!-- -->``."""
    from urdftool.diagnostics import Finding, Location, Severity
    from urdftool.server import Outcome

    server, _ = offline_server
    robot, uri = _opened(server, tmp_path / "robot.urdf", 1, "<robot>\n  <joint/>\n</robot>\n")
    span = types.Range(start=types.Position(1, 2), end=types.Position(1, 10))
    ours = types.Diagnostic(range=span, message="m", code="U204", source="urdftool")
    finding = Finding("U204", "inverted-limits", Severity.ERROR, "m", Location(robot, 2))
    server._publish(Outcome(robot, 1, {robot: [(ours, finding)]}), ticket=1)
    forged = types.Diagnostic(range=span, message="m", code="U204 --><script/><!--",
                              source="urdftool")

    def actions(diagnostic):
        return server.code_actions(types.CodeActionParams(
            text_document=types.TextDocumentIdentifier(uri=uri), range=span,
            context=types.CodeActionContext(diagnostics=[diagnostic]))) or []

    assert actions(forged) == []
    assert [edit.new_text.strip() for action in actions(ours)
            for edit in action.edit.changes[uri]][0] == "<!-- urdftool: ignore U204 -->"


@pytest.mark.parametrize("before", [
    '  <origin xyz="0 0\n 0"/>',  # the line starts inside an attribute value
    '  <origin xyz="0 0 0"\n  rpy="0 0 0"/>',  # between a tag's attributes
    '  <!-- a comment\n  ending here -->',  # inside a comment
])
def test_a_suppression_is_never_offered_where_a_comment_breaks_the_document(offline_server,
                                                                            tmp_path, before):
    """"Ignore here" writes a comment at the start of the finding's line: where that line
    starts inside the tag before it (written across lines, or with a line break in a value) or
    inside a comment, the comment made the robot not well-formed (a raw tab or line break in
    an origin, U023's finding on the next element of the line)."""
    from xml.parsers import expat

    from urdftool.diagnostics import Finding, Location, Severity
    from urdftool.server import Outcome

    server, _ = offline_server
    text = f"<robot>\n{before}<mass value='1 '/>\n  <joint/>\n</robot>\n"
    robot, uri = _opened(server, tmp_path / "robot.urdf", 1, text)
    line = text.count("\n", 0, text.index("<mass"))
    published = []
    for number, code in [(line, "U023"), (line + 1, "U204")]:
        span = types.Range(start=types.Position(number, 0), end=types.Position(number, 5))
        published.append((types.Diagnostic(range=span, message="m", code=code,
                                           source="urdftool"),
                          Finding(code, "x", Severity.ERROR, "m", Location(robot, number + 1))))
    server._publish(Outcome(robot, 1, {robot: published}), ticket=1)

    def edited(diagnostic) -> list[str]:
        actions = server.code_actions(types.CodeActionParams(
            text_document=types.TextDocumentIdentifier(uri=uri), range=diagnostic.range,
            context=types.CodeActionContext(diagnostics=[diagnostic]))) or []
        texts = []
        for action in actions:
            [edit] = action.edit.changes[uri]
            lines = text.splitlines(keepends=True)
            at = sum(map(len, lines[:edit.range.start.line]))
            texts.append(text[:at] + edit.new_text + text[at:])
        return texts

    inside, outside = edited(published[0][0]), edited(published[1][0])
    assert len(inside) == 1 and "ignore-file" in inside[0]  # "here" cannot be written
    assert len(outside) == 2  # the element's line starts outside every tag: both offered
    for document in inside + outside:
        expat.ParserCreate().Parse(document, True)  # every edit offered keeps it well-formed


def test_a_result_that_read_an_older_buffer_of_an_included_file_is_never_published(
        offline_server, monkeypatch, tmp_path):
    from urdftool.server import Outcome, check_robot

    server, _ = offline_server
    sent = []
    monkeypatch.setattr(server, "text_document_publish_diagnostics", sent.append)
    robot = write_robot(tmp_path / "bot", FIXED)
    macro = str(tmp_path / "bot" / "arm.xacro")
    uri = Path(macro).as_uri()
    edited = MACRO.replace('lower="${lower}"', 'lower="2"')
    for version, text in [(1, MACRO), (2, edited)]:
        server.protocol.workspace.put_text_document(types.TextDocumentItem(
            uri=uri, language_id="xml", version=version, text=text))
    server.open[macro] = uri

    outcome = check_robot(str(robot), server._buffers(), server.workspace.position_codec)
    assert outcome.versions == {macro: 2}  # the buffer, not the disk
    assert [d.range.start.line for d, _ in outcome.by_path[macro]] == [LIMIT_LINE]
    server._publish(Outcome(str(robot), None, {macro: outcome.by_path[macro]},
                            versions={macro: 1}), ticket=1)
    assert sent == []  # it read version 1; the editor has version 2
    server._publish(outcome, ticket=2)
    [on_macro] = [params for params in sent if params.uri == uri]
    assert (on_macro.version, len(on_macro.diagnostics)) == (2, 1)


PACKAGE_ROBOT = """\
<?xml version="1.0"?>
<robot name="bot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="arm.xacro"/>
  <link name="base_link"><visual><geometry><mesh filename="package://pkg/meshes/base.stl"/>
  </geometry></visual></link>
  <xacro:arm prefix="left" lower="-1" upper="1"/>
</robot>
"""
CONTROLLERS = """\
arm_controller:
  type: position_controllers/JointGroupPositionController
  joints: [elbow]
"""


def _package(root: Path) -> Path:
    """A repository holding package pkg: the robot in urdf/ including a macro file, a mesh in
    meshes/, no config/ yet. Returns the robot file."""
    (root / ".git").mkdir()
    package = root / "pkg"
    (package / "package.xml").parent.mkdir()
    (package / "package.xml").write_text("<package><name>pkg</name></package>\n")
    write_robot(package / "urdf", PACKAGE_ROBOT)
    (package / "meshes").mkdir()
    import trimesh

    trimesh.creation.box((0.1, 0.1, 0.1)).export(package / "meshes" / "base.stl")
    return package / "urdf" / "robot.urdf.xacro"


def _below_foreign_settings(offline_server, folder: Path, monkeypatch) -> tuple:
    """(server, the pop-ups it shows, a robot) for a robot in ``folder`` below a settings file
    another user owns (lint.settings.foreign: not read)."""
    from conftest import another_users

    server, _ = offline_server
    shown = []
    monkeypatch.setattr(server, "window_show_message", lambda params: shown.append(params.message))
    (folder / "urdftool.toml").write_text('ignore = ["U204"]\n')
    another_users(folder / "urdftool.toml", monkeypatch)
    return server, shown, str(write_robot(folder))


def test_a_settings_file_another_user_owns_is_shown_once_as_the_check_says_it(offline_server,
                                                                              tmp_path, monkeypatch):
    """urdftool check says it did not read another user's settings file outside a repository
    (lint.settings.foreign); the server, checking with the same core, said nothing."""
    from urdftool.server import check_robot

    server, shown, robot = _below_foreign_settings(offline_server, tmp_path, monkeypatch)
    for ticket in (1, 2):
        server._publish(check_robot(robot, {}, server.workspace.position_codec), ticket=ticket)
    assert len(shown) == 1 and shown[0].startswith(
        f"urdftool: settings file '{tmp_path / 'urdftool.toml'}' not read: it belongs to another user")


def test_the_pop_up_of_a_settings_file_not_read_is_the_checks_own_note(offline_server, tmp_path,
                                                                     monkeypatch):
    """Whether a settings file was not read is decided once, by the check
    (:attr:`FileResult.notes`, as ``urdftool check`` and the pytest plugin say it): the server
    looked the settings up again after the check (``settings_for`` a second time) to learn it,
    a second owner of the fact and the work done twice. Its pop-up shows the check's notes,
    and only those."""
    from urdftool.lint import runner, settings
    from urdftool.records import replace
    from urdftool.server import check_robot

    server, shown, robot = _below_foreign_settings(offline_server, tmp_path, monkeypatch)
    calls = []
    looked_up = settings.settings_for
    monkeypatch.setattr(settings, "settings_for", lambda path: calls.append(path) or
                        looked_up(path))
    outcome = check_robot(robot, {}, server.workspace.position_codec)
    assert len(calls) == 1  # the check's own look-up, none after it
    assert outcome.notes and outcome.notes == tuple(runner.check_file(robot).notes)
    checked = runner.check_file
    for notes in ((), ("a note of the check",)):  # the foreign file is still there: the
        shown.clear()  # pop-up follows the check's notes, never a look of its own
        monkeypatch.setattr(runner, "check_file", lambda path, **options: replace(
            checked(path, **options), notes=notes))
        server.notes_shown.clear()
        server._publish(check_robot(robot, {}, server.workspace.position_codec), ticket=1)
        assert shown == [f"urdftool: {note}" for note in notes]


def test_the_settings_file_not_read_is_shown_with_no_live_link(offline_server, tmp_path,
                                                               monkeypatch):
    """The path of the settings file not read is the repository's own text: its pop-up is
    escaped as every pop-up is (escape.notification), a folder named '[x](command:...)' no
    link VS Code would run."""
    from urdftool.server import check_robot

    folder = tmp_path / "[x](command:workbench.action.terminal.new)"
    folder.mkdir()
    server, shown, robot = _below_foreign_settings(offline_server, folder, monkeypatch)
    server._publish(check_robot(robot, {}, server.workspace.position_codec), ticket=1)
    assert len(shown) == 1 and "](command:" not in shown[0] and "] (command:" in shown[0]


def test_the_record_of_a_check_says_which_changes_concern_a_robot(offline_server, tmp_path):
    from urdftool.server import check_robot

    server, _ = offline_server
    robot = str(_package(tmp_path))
    server._publish(check_robot(robot, {}, server.workspace.position_codec), ticket=1)
    package = tmp_path / "pkg"
    for concerned in ["urdf/arm.xacro", "urdf/robot.urdf.xacro", "meshes/base.stl",
                      "package.xml", "config/controllers.yaml", "urdf/controllers.yaml",
                      "urdf/config/robot.srdf", "urdf/urdftool.toml", "pyproject.toml"]:
        assert server.concerned(str(package / concerned)) == [robot], concerned
    # (a file in config/, which is not there yet, concerns it: config/ would be searched)
    # a file written there (the launch files' walk lists folders, so a path not there yet may
    # become a folder holding launch files: it concerns the robot until it is a file)
    for unconcerned in ["README.md", "urdf/notes.txt", "meshes/other.stl"]:
        (package / unconcerned).write_text("x")
        assert server.concerned(str(package / unconcerned)) == [], unconcerned
    # a launch file may start the robot's controllers or build it: it concerns it
    (package / "launch").mkdir()
    (package / "launch" / "x.launch.py").write_text("")
    assert server.concerned(str(package / "launch" / "x.launch.py")) == [robot]


@SHARED
async def test_a_file_created_outside_the_editor_rechecks_the_robots_that_searched_for_it(
        client: LanguageClient, tmp_path):
    robot = _package(tmp_path)
    uri = open_document(client, robot)
    await wait_until(lambda: checked(client, robot))
    assert codes(client, uri) == []
    assert [r.method for r in client.registrations] == ["workspace/didChangeWatchedFiles"]

    controllers = tmp_path / "pkg" / "config" / "controllers.yaml"  # config/ made too
    controllers.parent.mkdir()
    controllers.write_text(CONTROLLERS)
    client.workspace_did_change_watched_files(types.DidChangeWatchedFilesParams(changes=[
        types.FileEvent(uri=controllers.as_uri(), type=types.FileChangeType.Created)]))
    await wait_until(lambda: ("U602" in [code for _, code in codes(client, controllers.as_uri())]))

    controllers.write_text(CONTROLLERS.replace("elbow", "left_joint"))  # changed, then fixed
    client.workspace_did_change_watched_files(types.DidChangeWatchedFilesParams(changes=[
        types.FileEvent(uri=controllers.as_uri(), type=types.FileChangeType.Changed)]))
    await wait_until(lambda: "U602" not in [c for _, c in codes(client, controllers.as_uri())])

    macro = robot.parent / "arm.xacro"  # an included file changed (a checkout, another editor)
    macro.write_text(MACRO.replace("lower=\"${lower}\"", "lower=\"2\""))
    client.workspace_did_change_watched_files(types.DidChangeWatchedFilesParams(changes=[
        types.FileEvent(uri=macro.as_uri(), type=types.FileChangeType.Changed)]))
    await wait_until(lambda: codes(client, macro.as_uri()) == [(LIMIT_LINE, "U204")])
# ---- the budget: a slow document holds no other, a flood of changes queues nothing -------------

SLOW = slow_xacro()  # hours to expand under every cap of the sandbox (tests/slow_robots.py)
BUDGET = 5  # [s] the server's --timeout in these tests (the slow document spins it out)


@pytest_lsp.fixture(config=ClientServerConfig(
    server_command=[sys.executable, "-m", "urdftool", "server", "--timeout", str(BUDGET)]))
async def budgeted(lsp_client: LanguageClient):
    @lsp_client.feature(types.CLIENT_REGISTER_CAPABILITY)
    def register(params: types.RegistrationParams):  # as an editor does
        pass

    await lsp_client.initialize_session(types.InitializeParams(
        capabilities=client_capabilities("visual-studio-code")))
    yield
    await lsp_client.shutdown_session()


def workers(client: LanguageClient) -> int:
    """How many processes the server has started and not ended (its check workers)."""
    from tests.fuzz.server_session import children

    return children(client._server.pid)


def open_slow(client: LanguageClient, folder: Path) -> str:
    """The slow robot written in ``folder`` (made a repository) and opened; its URI."""
    (folder / ".git").mkdir()
    path = folder / "slow.urdf.xacro"
    path.write_text(SLOW)
    return open_document(client, path)


@pytest.mark.integration
@pytest.mark.asyncio
async def test_a_slow_document_holds_no_other_and_ends_with_the_timeout_finding(
        budgeted, tmp_path):
    client = budgeted
    slow_uri = open_slow(client, tmp_path)
    await asyncio.sleep(1.0)  # its check is under way
    fast = tmp_path / "fast.urdf"
    fast.write_text((CASES / "U204_inverted_limits.urdf").read_text())
    fast_uri = open_document(client, fast)

    await wait_until(lambda: fast_uri in client.diagnostics, seconds=BUDGET - 1)
    assert [code for _, code in codes(client, fast_uri)] == ["U204"]
    assert slow_uri not in client.diagnostics  # still being checked, within its budget

    await wait_until(lambda: slow_uri in client.diagnostics, seconds=6 * BUDGET)
    found = client.diagnostics[slow_uri]  # where the expansion was, and each macro call
    assert {d.code for d in found} == {"U015"}
    assert all(f"longer than {BUDGET} s" in d.message for d in found)
    assert {d.range.start.line for d in found} <= set(range(2, 10))
    await asyncio.sleep(0.5)
    assert workers(client) == 0  # its worker was killed


@pytest.mark.integration
@pytest.mark.asyncio
async def test_a_flood_of_changes_keeps_one_check_per_document_and_publishes_the_last(
        budgeted, tmp_path):
    client = budgeted
    uri = open_slow(client, tmp_path)
    most = 0
    version = 1
    for pause in [0.01] * 200 + [0.6] * 8:  # within the debounce, then each check started
        version += 1
        change_document(client, uri, version, SLOW + " " * version)
        await asyncio.sleep(pause)
        most = max(most, workers(client))
    assert most <= 1  # one document: one check at a time, each older one stopped
    version += 1
    change_document(client, uri, version, f'<robot name="quick"><link name="a"/></robot>\n'
                                          f"<!-- version {version} -->\n")
    await wait_until(lambda: any(f"(version {version})" in m for m in checked(client, "slow")),
                     seconds=BUDGET - 1)  # not behind any of the slow versions
    assert checked(client, "slow") == [m for m in checked(client, "slow")
                                       if f"(version {version})" in m]
    await wait_until(lambda: uri in client.diagnostics)  # published just after the log
    assert codes(client, uri) == []


# -- the transport: what the client writes is framed before pygls reads it


def _frame(message: dict) -> bytes:
    import json

    body = json.dumps(message).encode()
    return b"Content-Length: %d\r\n\r\n" % len(body) + body


_INITIALIZE = _frame({"jsonrpc": "2.0", "id": 1, "method": "initialize",
                      "params": {"capabilities": {}}})
_SHUTDOWN = _frame({"jsonrpc": "2.0", "id": 2, "method": "shutdown"})


def _serve_raw(data: bytes, tmp_path) -> tuple[int, bytes, str]:
    import subprocess

    result = subprocess.run([sys.executable, "-m", "urdftool", "server"], input=data,
                            capture_output=True, timeout=60, cwd=tmp_path)
    return result.returncode, result.stdout, result.stderr.decode(errors="replace")


@pytest.mark.parametrize("framing", [
    b"Content-Length: 100000000000\r\n\r\n{}",  # 100 GB: pygls allocated it (MemoryError)
    b"Content-Length: abc\r\n\r\n{}" + _SHUTDOWN,  # pygls skipped it, took the body for headers
    b"Content-Length: 0\r\n\r\n" + _SHUTDOWN,
    b"Content-Type: x\r\n\r\n{}" + _SHUTDOWN,  # no length
    b"Content-Length: 2\r\nContent-Length: 3\r\n\r\n{}" + _SHUTDOWN,
    b"X" * 20_000_000,  # a header line read whole, however long
    b"\n" + _SHUTDOWN,
    b"Content-Length: 50\r\n\r\n",  # a header, then the end of the input: no body
    _SHUTDOWN[:-3],  # a body cut short by the end of the input (pygls parsed the part)
], ids=["100GB", "not-a-number", "zero", "no-length", "twice", "endless-line", "bare-newline",
        "no-body", "cut-body"])
def test_input_that_breaks_the_framing_ends_the_server_with_one_line(framing, tmp_path):
    status, out, err = _serve_raw(_INITIALIZE + framing, tmp_path)
    assert b'"id": 1' in out and b'"id": 2' not in out  # nothing after the broken frame is read
    assert status == 1 and "Traceback" not in err and "MemoryError" not in err
    assert err.count("\n") == 1 and "the client's input: " in err, err


def test_a_session_that_ends_without_shutdown_ends_with_status_1(tmp_path):
    """LSP: "exit" without "shutdown" before it is status 1 (pygls's was lost: 0), and so is
    an input that ends without one; with it, 0."""
    exit_ = _frame({"jsonrpc": "2.0", "method": "exit"})
    assert _serve_raw(_INITIALIZE + exit_, tmp_path)[0] == 1
    status, _, err = _serve_raw(_INITIALIZE, tmp_path)
    assert status == 1 and err.count("\n") == 1 and "without a shutdown request" in err, err
    assert _serve_raw(_INITIALIZE + _SHUTDOWN + exit_, tmp_path)[0] == 0


def test_the_servers_messages_hold_no_lone_surrogate(tmp_path):
    # session 13 (left since session 6): pygls writes its messages with json.dumps, where a
    # name holding a byte that is not UTF-8 (U620 quoting a launch file's) was an unpaired
    # \udcff no strict reader takes; a pair (a character past U+FFFF) is kept
    import json

    ask = _frame({"jsonrpc": "2.0", "id": 3, "method": "x\udcff\U0001F600", "params": {}})
    status, out, _ = _serve_raw(_INITIALIZE + ask + _SHUTDOWN, tmp_path)
    [answer] = [part for part in out.split(b"Content-Length: ") if b'"id": 3' in part]
    length, body = answer.split(b"\r\n\r\n", 1)
    assert int(length.split(b"\r\n")[0]) == len(body)
    assert json.loads(body)["error"]["message"].endswith("x\ufffdFF\U0001F600")


def test_messages_pygls_cannot_read_are_logged_one_line_each_and_the_server_goes_on(tmp_path):
    garbage = [b"Content-Length: 5\r\n\r\n{xx}}",  # not JSON
               _frame({"jsonrpc": "2.0", "method": "textDocument/didOpen",
                       "params": {"textDocument": 5}}),  # cattrs' exception group
               _frame({"jsonrpc": "2.0", "id": 9, "method": "\x1b[2J\n::error::x",
                       "params": None}),
               b"Content-Length: 400000\r\n\r\n" + b"[" * 400_000]  # RecursionError
    status, out, err = _serve_raw(_INITIALIZE + b"".join(garbage) + _SHUTDOWN, tmp_path)
    assert b'"id": 2' in out  # answered after all of it
    assert status == 0 and "Traceback" not in err and "\x1b" not in err, err
    assert all(line.startswith("urdftool server: ") for line in err.splitlines()), err


def test_the_log_file_is_judged_as_any_output_and_a_pipe_nobody_reads_is_refused(tmp_path,
                                                                                monkeypatch):
    """The language server's ``--log-file`` was opened by logging's FileHandler, past the door:
    a named pipe nobody read hung it before its first message, ``.git/HEAD`` took its log (the
    branch gone). ``files.append_stream`` judges it as every output and waits for no reader."""
    import os
    import threading

    from urdftool.description import files
    from urdftool.server import _Log

    monkeypatch.setattr(files, "PIPE_READER_WAIT", 0.5)  # (10 s as shipped)
    (tmp_path / ".git").mkdir()
    (tmp_path / ".git" / "HEAD").write_text("ref: refs/heads/main\n")
    os.mkfifo(tmp_path / "log")
    done: list = []
    worker = threading.Thread(target=lambda: done.append(_refusal(_Log, tmp_path / "log")),
                              daemon=True)
    worker.start()
    worker.join(5)
    if worker.is_alive():  # unblock the opener so the test process can end
        with open(tmp_path / "log", "rb") as reader:
            reader.read()
        pytest.fail("the log file waited for a reader of a named pipe")
    assert "no process reads" in done[0]
    assert "version control system's own folder" in _refusal(_Log, tmp_path / ".git" / "HEAD")
    assert (tmp_path / ".git" / "HEAD").read_text() == "ref: refs/heads/main\n"
    handler = _Log(str(tmp_path / "server.log"))
    handler.stream.write("one\n")
    handler.close()
    handler = _Log(str(tmp_path / "server.log"))
    handler.stream.write("two\n")  # appended
    handler.close()
    assert (tmp_path / "server.log").read_text() == "one\ntwo\n"


def _refusal(make, path) -> str:
    from urdftool.errors import UsageError

    try:
        make(str(path))
    except UsageError as error:
        return str(error)
    return "written"


def test_the_document_uses_only_pygls_public_names(monkeypatch):
    """The document of the protocol's lines is made and changed through pygls's public names
    only: with pygls's private ones gone (a release renaming them), an opened document is
    still a Document and its changes are the protocol's (the private overrides before would
    have let pygls's own splitlines back without a word)."""
    from pygls.workspace import TextDocument, Workspace

    from urdftool.server import Document, adopt

    for name in ("_apply_incremental_change", "_apply_full_change", "_apply_none_change"):
        monkeypatch.delattr(TextDocument, name)
    workspace = Workspace(None)
    uri, text = "file:///r.urdf", '<robot name="r"> <!-- a\u2028b -->\r  <link name="base"/>\r'
    workspace.put_text_document(types.TextDocumentItem(uri=uri, language_id="xml", version=1,
                                                       text=text))
    adopt(workspace, uri)
    monkeypatch.setattr(TextDocument, "_source", property(lambda self: 1 / 0,  # (pygls's text)
                                                           lambda self, value: None),
                        raising=False)
    document = workspace.get_text_document(uri)
    assert isinstance(document, Document) and document.source == text and document.version == 1
    workspace.update_text_document(
        types.VersionedTextDocumentIdentifier(uri=uri, version=2),
        types.TextDocumentContentChangePartial(
            range=types.Range(start=types.Position(1, 14), end=types.Position(1, 18)), text="arm"))
    assert document.source == text.replace('"base"', '"arm"') and len(document.lines) == 2
    workspace.update_text_document(types.VersionedTextDocumentIdentifier(uri=uri, version=3),
                                   types.TextDocumentContentChangeWholeDocument(text="x\ry"))
    assert document.lines == ("x\r", "y") and document.version == 3


def test_a_uri_no_file_can_have_names_no_document_and_never_breaks_the_others(offline_server,
                                                                               tmp_path):
    """Session 20 (attack20b): a document opened as ``file:///…/a%00b.urdf`` was the path
    ``a\\x00b.urdf``; each later check read every open buffer, so every robot's check from then
    on ended in "internal error: ValueError: embedded null byte". A path no file can have (a
    NUL byte) is no path: the document is not the server's, as an ``http:`` one is not."""
    from urdftool import server as module

    server, _ = offline_server
    for uri in (tmp_path.as_uri() + "/a%00b.urdf", tmp_path.as_uri() + "/%00/r.urdf"):
        assert module.path_of_uri(uri) is None and list(server.paths_of([uri])) == [None]
        server.protocol.workspace.put_text_document(types.TextDocumentItem(
            uri=uri, language_id="xml", version=1, text=BROKEN))
        server.opened(uri)
    assert server.open == {}
    robot = write_robot(tmp_path)
    server.protocol.workspace.put_text_document(types.TextDocumentItem(
        uri=robot.as_uri(), language_id="xml", version=1, text=BROKEN))
    outcome = module.check_robot(str(robot), server._buffers(),
                                 server.workspace.position_codec)
    assert outcome.error is None, outcome.error


def test_hover_and_code_actions_on_a_document_never_opened_answer_nothing(offline_server,
                                                                         tmp_path):
    """Session 20 (attack20b): a code action asked for a robot file the client never opened
    was pygls's FileNotFoundError, an internal error with its traceback sent to the client
    (hover answered nothing): one guard, the document of an open URI, serves both."""
    server, _ = offline_server
    uri = (tmp_path / "gone.urdf").as_uri()
    span = types.Range(start=types.Position(500, 0), end=types.Position(501, 0))
    diagnostic = types.Diagnostic(range=span, message="m", code="U204", source="urdftool")
    assert server.code_actions(types.CodeActionParams(
        text_document=types.TextDocumentIdentifier(uri=uri), range=span,
        context=types.CodeActionContext(diagnostics=[diagnostic]))) is None
    assert server.hover(types.HoverParams(text_document=types.TextDocumentIdentifier(uri=uri),
                                          position=types.Position(0, 0))) is None


# VS Code's link in a notification (vs/base/common/linkedText.ts), opened with allowCommands
_VSCODE_LINK = re.compile(r"\[([^\]]+)\]\(((?:https?://|command:|file:)[^)\s]+)"
                          r"(?: ([\"'])(.+?)(\3))?\)", re.I)


def test_a_notification_holds_no_link_an_editor_would_run(offline_server, tmp_path,
                                                          monkeypatch):
    """A check that cannot run is a notification (``window/showMessage``) naming the robot and
    why; VS Code renders ``[label](command:ID)`` in a notification as a link that runs the
    command when clicked. A settings key of the repository (``"[Open](command:...)" = 1``)
    or a file so named put one there; a line break and ESC reached clients that print it."""
    from urdftool.server import Outcome

    server, _ = offline_server
    shown = []
    monkeypatch.setattr(server, "window_show_message", lambda params: shown.append(params))
    name = "[Run](command:workbench.action.terminal.new)\n\x1b[2J"
    robot = str(tmp_path / f"{name}.urdf")
    server._publish(Outcome(robot, None, error=f"urdftool.toml: unknown setting(s) {name}",
                            user_error=True), ticket=1)
    [params] = shown
    assert not _VSCODE_LINK.search(params.message), params.message
    assert "\n" not in params.message and "\x1b" not in params.message
    assert "[Run] (command:workbench.action.terminal.new)" in params.message
