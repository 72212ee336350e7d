"""How urdftool writes and ends when its output fails (:mod:`urdftool.streams`): every command,
every output format, Typer's help, version and usage errors, against a reader that left
(EPIPE), a full device (ENOSPC), a closed standard output (EBADF) and a failing standard error.

The commands and their formats are read from the Typer app (each command's ``--format``
choices, its module's FORMATS): a new command, or a new format, is walked without editing this
file; a new command that cannot run on ``WORDS``' default (the robot alone) fails here until
its words are given. The walk runs in this process, the streams made of real file
descriptors (a pipe whose reader is closed, /dev/full, the null device opened read-only); what
only the operating system's state shows (a descriptor closed at start, Python's own flush at
exit) is run as the program, a few times.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import ROOT

ROBOT = """<robot name="r">
  <link name="a"><inertial><mass value="1"/>
    <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual></link>
  <link name="b"><inertial><mass value="1"/>
    <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <origin xyz="0 0 {z}"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""
# the words of a command beyond the robot, when it needs more ({robot}, {other}, {out}: files)
WORDS = {
    "crosscheck": ["{robot}", "--loader", "pinocchio"],
    "dh": ["{robot}", "--base", "a", "--tip", "b"],
    "diff": ["{robot}", "{other}"],
    "ik": ["{robot}", "--tip", "b", "--xyz", "0", "0", "0.6"],
    "render": ["{robot}", "--output", "{out}/r.svg"],  # writes a file: its stdout is empty
    "rules": [],
    "server": [],  # standard input: the LSP messages of SERVER_INPUT
    "workspace": ["{robot}", "--tip", "b", "--samples", "50"],
}
NO_OUTPUT = {"render"}  # commands that write nothing on standard output


def _lsp(*messages: dict) -> bytes:
    bodies = [json.dumps(message).encode() for message in messages]
    return b"".join(b"Content-Length: %d\r\n\r\n%s" % (len(body), body) for body in bodies)


SERVER_INPUT = _lsp({"jsonrpc": "2.0", "id": 1, "method": "initialize",
                     "params": {"capabilities": {}}},
                    {"jsonrpc": "2.0", "id": 2, "method": "shutdown"},
                    {"jsonrpc": "2.0", "method": "exit"})


def _commands() -> dict[str, list[str]]:
    """Each command of the Typer app with its ``--format`` values ([None]: it has none); the
    commands with a budget (``--timeout``) in :data:`UNBUDGETED`."""
    from urdftool.cli import COMMANDS, LazyGroup, app, command
    import typer

    group = typer.main.get_command(app)
    assert isinstance(group, LazyGroup)
    formats = {}
    for name in group.list_commands(None):
        assert name in COMMANDS
        built = command(name)
        choices = [None]
        for param in built.params:
            if "--timeout" in getattr(param, "opts", ()):
                UNBUDGETED.add(name)
            if "--format" in getattr(param, "opts", ()):
                module = sys.modules[f"urdftool.cli.{name}"]
                choices = list(module.FORMATS)  # the values it takes (the command says so)
        formats[name] = choices
    return formats


# run in this process (``--timeout 0 --max-memory 0``): a budgeted command's worker would
# import its libraries again on each run (a budgeted worker: test_a_budgeted_worker_...)
UNBUDGETED: set[str] = set()
COMMAND_FORMATS = _commands()
# outputs chosen by other options than --format
OTHER_OUTPUTS = {"check": [["--statistics"], ["--diff", "--unsafe-fixes"]], "rules": [["U204"]],
                 "collisions": [["--matrix"]], "fk": [["--matrix"]]}
CASES = [pytest.param(name, ["--format", fmt] if fmt else [], id=f"{name}-{fmt or 'plain'}")
         for name, choices in COMMAND_FORMATS.items() for fmt in choices]
CASES += [pytest.param(name, words, id=f"{name}{''.join(words)}")
          for name, more in OTHER_OUTPUTS.items() for words in more]
# the paths Typer and the door answer before any command runs
FRONT = [pytest.param(words, columns, id=f"{' '.join(words) or 'none'}-{columns}")
         for columns in ("100", "40")  # the door's kept help; Typer's (narrow terminal)
         for words in ([], ["--help"], ["-V"], ["chek"], ["check", "--no-such-option"],
                       *([name, "--help"] for name in COMMAND_FORMATS))]

STATES = {
    "pipe": "the reader left",
    "full": "a full device",
    "closed": "a closed standard output",
    "stderr": "a failing standard error",
}


def _descriptor(kind: str, path: Path) -> int:
    """A file descriptor to write on: a file (``path``), a pipe whose reader left, /dev/full,
    or the null device opened read-only (every write fails with EBADF, as a closed one)."""
    if kind == "file":
        return os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC)
    if kind == "pipe":
        read, write = os.pipe()
        os.close(read)
        return write
    if kind == "full":
        return os.open("/dev/full", os.O_WRONLY)
    return os.open(os.devnull, os.O_RDONLY)


@pytest.fixture
def program(monkeypatch, tmp_path):
    """``program(words, stdout=KIND, stderr=KIND)``: ``urdftool WORDS`` run as the ``urdftool``
    script runs it (``urdftool.__main__.main``), in this process, on standard streams of those
    kinds (:func:`_descriptor`); (exit status, its stdout, its stderr) as text, a stream that
    failed read as empty."""
    import logging

    import urdftool.__main__ as door

    # the door's start-up tricks that change this process's collector and compilers: not
    # about the streams
    monkeypatch.setattr(door, "kept_code", lambda path=None: None)
    monkeypatch.setattr(door, "_collect_less", lambda: None)
    if hasattr(door, "_end"):  # the door's check ends the process (os._exit): as the program
        # only (test_the_program_ends_as_its_output_allows[door])

        def end(code, exit_functions=True):
            raise SystemExit(code)

        monkeypatch.setattr(door, "_end", end)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    monkeypatch.delenv("GITHUB_ACTIONS", raising=False)
    (tmp_path / "r.urdf").write_text(ROBOT.format(z=0.5))
    (tmp_path / "r2.urdf").write_text(ROBOT.format(z=0.6))
    (tmp_path / "stdin").write_bytes(SERVER_INPUT)
    handlers = list(logging.getLogger().handlers)
    runs = iter(range(10**6))

    def run(words, stdout="file", stderr="file", columns="100"):
        monkeypatch.setenv("COLUMNS", columns)
        streams = sys.modules.get("urdftool.streams")
        if streams is not None:  # a fresh start: guard() again
            monkeypatch.setattr(streams, "_WATCHED", [])
            monkeypatch.setattr(streams, "_ERR", [])
        number = next(runs)
        out_path, err_path = tmp_path / f"out{number}", tmp_path / f"err{number}"
        out, err = _descriptor(stdout, out_path), _descriptor(stderr, err_path)
        saved = sys.stdin, sys.stdout, sys.stderr, sys.argv
        sys.stdin = open(tmp_path / "stdin", encoding="utf-8")
        sys.stdout = open(out, "w", encoding="utf-8", closefd=False)
        sys.stderr = open(err, "w", buffering=1, encoding="utf-8", errors="backslashreplace",
                          closefd=False)
        sys.argv = ["urdftool", *(word.format(robot=tmp_path / "r.urdf",
                                              other=tmp_path / "r2.urdf", out=tmp_path)
                                  for word in words)]
        try:
            door.main()
            code = 0
        except SystemExit as ended:
            code = ended.code
        finally:
            for stream in (sys.stdout, sys.stderr):
                try:
                    stream.flush()
                except (OSError, ValueError):
                    pass
            sys.stdin.close()
            sys.stdin, sys.stdout, sys.stderr, sys.argv = saved
            os.close(out)
            os.close(err)
            for handler in logging.getLogger().handlers:
                if handler not in handlers:
                    logging.getLogger().removeHandler(handler)
        read = [path.read_text(errors="replace") if path.exists() else ""
                for path in (out_path, err_path)]
        return code, *read

    return run


def _walk(program, words, columns="100"):
    """``urdftool WORDS`` with healthy streams, then in each state of STATES; assert each ends
    as urdftool.streams says, with no traceback."""
    code, stdout, stderr = program(words, columns=columns)
    assert "Traceback" not in stderr, stderr
    wrote = bool(stdout)
    for state in STATES:
        if state == "stderr":
            failing = program(words, stderr="closed", columns=columns)
            assert failing[:2] == (code, stdout), (state, failing)
            continue
        got, _, said = program(words, stdout=state, columns=columns)
        assert "Traceback" not in said and "Exception ignored" not in said, (state, said)
        lines = [line for line in said.splitlines() if "cannot write standard output" in line]
        if not wrote:
            assert (got, lines) == (code, []), (state, said)
        elif state == "pipe":  # quietly, as click ends
            assert (got, lines) == (1, []), (state, got, said)
        else:
            assert got == 2 and len(lines) == 1, (state, got, said)
            assert lines[0].startswith("urdftool: error: cannot write standard output: ")
    return code, stdout


@pytest.mark.integration
@pytest.mark.parametrize("name, chosen", CASES)
def test_every_command_and_format_ends_as_its_output_allows(program, name, chosen):
    words = list(WORDS.get(name, ["{robot}"])) + chosen
    if name in UNBUDGETED:
        words += ["--timeout", "0", "--max-memory", "0"]
    code, stdout = _walk(program, [name, *words])
    assert code in (0, 1), f"urdftool {name} did not run on {words}: give its words in WORDS"
    assert bool(stdout) is (name not in NO_OUTPUT), (name, stdout)


@pytest.mark.parametrize("words, columns", FRONT)
def test_help_version_and_usage_errors_end_as_their_output_allows(program, words, columns):
    code, stdout = _walk(program, words, columns)
    assert code in (0, 2)


@pytest.mark.parametrize("words", [
    ["check", "{robot}", "--timeout", "5"],  # the door's plain check (no Typer), its worker
    ["check", "{robot}", "--timeout", "5", "-ftext"],  # Typer's check (-ftext: not plain)
    ["fk", "{robot}", "--timeout", "5"],  # a budgeted command's worker
], ids=["door", "typer", "budgeted"])
def test_a_command_in_a_budgeted_worker_ends_as_its_output_allows(program, words):
    """The command runs in a forked worker, which writes the output and ends (its status and
    its one line, said there, pass through the parent)."""
    assert _walk(program, words)[0] in (0, 1)


# ---- as the program: what only the operating system's state shows --------------------------

def _shell(command: str, cwd: Path) -> subprocess.CompletedProcess:
    """``command`` run by sh (``urdftool``: this Python's ``-m urdftool``), ``set -o pipefail``
    where the shell has it; stderr captured unless the command redirects it."""
    urdftool = f"{sys.executable} -m urdftool"
    return subprocess.run(["bash", "-c", "set -o pipefail; " + command.replace("urdftool",
                                                                                urdftool)],
                          capture_output=True, text=True, cwd=cwd, timeout=120,
                          env={**os.environ, "PYTHONPATH": str(ROOT),
                               "XDG_CACHE_HOME": str(cwd / "cache")})


@pytest.mark.parametrize("words", [["check", "r.urdf"], ["fk", "r.urdf", "--format", "csv"]],
                         ids=["door", "typer"])
def test_the_program_ends_as_its_output_allows(tmp_path, words):
    """Standard output closed at start (``>&-``), a full device, a reader that left before
    reading (a pipe, closed), standard error closed: no traceback, nothing said by Python's
    flush at exit ("Exception ignored"), the exit status of each."""
    (tmp_path / "r.urdf").write_text(ROBOT.format(z=0.5))
    command = " ".join(words)
    healthy = _shell(f"urdftool {command}", tmp_path)
    assert healthy.returncode == 0 and healthy.stdout, healthy.stderr
    for redirect, status in ((">&-", 2), (">/dev/full", 2)):
        ended = _shell(f"urdftool {command} {redirect}", tmp_path)
        assert ended.returncode == status, (redirect, ended.stderr)
        assert ended.stderr.startswith("urdftool: error: cannot write standard output: ")
        assert ended.stderr.count("\n") == 1, (redirect, ended.stderr)
    read, write = os.pipe()
    os.close(read)  # the reader left before anything was written
    left = subprocess.run([sys.executable, "-m", "urdftool", *words], stdout=write,
                          stderr=subprocess.PIPE, text=True, cwd=tmp_path, timeout=120,
                          env={**os.environ, "PYTHONPATH": str(ROOT)})
    os.close(write)
    assert (left.returncode, left.stderr) == (1, ""), left.stderr
    quiet = _shell(f"urdftool {command} 2>&-", tmp_path)
    assert (quiet.returncode, quiet.stdout) == (0, healthy.stdout)


# ---- output files ------------------------------------------------------------------------------

# the words an output option needs beside it
OUTPUT_WORDS = {"--plot": {"collisions": ["--matrix"], "dynamics": ["--support", "a"]},
                "--write-srdf": {"collisions": ["--matrix"]}}


def _output_options():
    """(command, option) for every option of the Typer app that names a file it writes:
    ``--output``, ``--plot``, ``--log-file``, ``--write-*``."""
    from urdftool.cli import command

    for name in COMMAND_FORMATS:
        for param in command(name).params:
            for option in getattr(param, "opts", ()):
                if option in ("--output", "--plot", "--log-file") or \
                        option.startswith("--write-"):
                    yield pytest.param(name, option, id=f"{name}{option}")


@pytest.mark.parametrize("name, option", list(_output_options()))
def test_an_output_file_the_system_refuses_ends_in_one_line(program, name, option):
    """A path whose folder exists but where nothing can be written (/proc/self): exit 2, one
    line. (Not /dev/full: the writer of old replaced the device itself when run as root.)"""
    words = [word for word in WORDS.get(name, ["{robot}"]) if not word.startswith("{out}")]
    if "--output" in words:
        words.remove("--output")
    words += OUTPUT_WORDS.get(option, {}).get(name, [])
    code, _, said = program([name, *words, option, "/proc/self/out.svg"])
    assert "Traceback" not in said, said
    assert code == 2 and said.count("\n") == 1 and "cannot write" in said, said


def test_a_named_pipe_given_as_the_output_is_written_not_replaced(tmp_path):
    """``-o`` naming a named pipe (or a character device: /dev/null, /dev/full) is written in
    place; a temporary file renamed over it would replace it."""
    import stat
    import threading

    from urdftool.description.files import write_file

    fifo = tmp_path / "out.fifo"
    os.mkfifo(fifo)
    read = []
    reader = threading.Thread(target=lambda: read.append(fifo.read_bytes()))
    reader.start()
    write_file(fifo, "report\n")
    reader.join(10)
    assert read == [b"report\n"] and stat.S_ISFIFO(os.lstat(fifo).st_mode)


def test_an_output_link_to_a_standard_stream_is_written_to_it_not_replaced(tmp_path):
    """``-o /dev/stdout`` (a link to /proc/self/fd/1) writes on standard output; replacing
    the link with a file, as the writer did, broke the machine's /dev/stdout when run as root.
    Tested on a link of the test's own, never on /dev/stdout. Any other link is still
    replaced, its target untouched."""
    import subprocess
    import sys

    out = tmp_path / "stdout"
    out.symlink_to("/proc/self/fd/1")
    script = ("import sys; from urdftool.description.files import write_file; "
              "print('before', flush=True); write_file(sys.argv[1], 'report\\n')")
    done = subprocess.run([sys.executable, "-c", script, str(out)], capture_output=True)
    assert done.stdout == b"before\nreport\n", done
    assert out.is_symlink() and os.readlink(out) == "/proc/self/fd/1"
    elsewhere, link = tmp_path / "elsewhere", tmp_path / "link.txt"
    elsewhere.write_text("kept")
    link.symlink_to(elsewhere)
    subprocess.run([sys.executable, "-c", script, str(link)], capture_output=True, check=True)
    assert elsewhere.read_text() == "kept" and not link.is_symlink() and \
        link.read_text() == "report\n"


@pytest.mark.parametrize("environment", [{"PYTHONIOENCODING": "cp1252"},
                                         {"LC_ALL": "C", "PYTHONCOERCECLOCALE": "0",
                                          "PYTHONUTF8": "0"}])
def test_a_name_the_output_encoding_cannot_hold_is_escaped_not_a_traceback(tmp_path,
                                                                           environment):
    """session 9: with standard output in ASCII (a C locale) or cp1252, a robot whose link is
    named with a character outside it ended in a UnicodeEncodeError traceback in place of the
    report; streams write it as a backslash escape, as the terminal-text escaper does."""
    import os

    robot = tmp_path / "robot.urdf"
    robot.write_text('<robot name="r"><link name="a"/><link name="b"/><joint name="\u0101\ue000" '
                     'type="revolute"><parent link="a"/><child link="b"/><limit lower="1" '
                     'upper="-1" effort="1" velocity="1"/></joint></robot>\n', encoding="utf-8")
    done = subprocess.run([sys.executable, "-m", "urdftool", "check", "--no-cache", "-f",
                           "concise", str(robot)],
                          capture_output=True, timeout=120,
                          env={**{k: v for k, v in os.environ.items() if not k.startswith(
                              ("PYTHONIOENCODING", "LC_", "LANG"))}, **environment})
    assert b"Traceback" not in done.stderr, done.stderr[-300:]
    assert done.returncode == 1 and b"\\u0101\\ue000" in done.stdout, done.stdout
