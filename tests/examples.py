"""The examples of command output in README.md and docs/**/*.md, run and compared with what they
print (tests/test_examples.py), and rewritten when the output changed on purpose.

An example is a ```console block: lines starting with ``$ `` are commands (a line ending with
``\\`` continues on the next), the lines after each are what it prints, standard output and
standard error as a terminal shows them. Two marks leave out what is not worth showing or varies
between machines (rounding noise, library versions):

- a line ``...`` alone stands for any number of lines, none included;
- ``…`` inside a line stands for any text within that line.

Commands run in a scratch copy of the checkout's ``robots/`` and ``tests/cases/``, a git
repository whose branch ``main`` holds them as committed, so ``urdftool diff --rev main`` works.
A command is ``urdftool ...`` (run in-process as the installed command would), optionally
followed by ``| head -N`` or ``> FILE``. An HTML comment ``<!-- example: NAME -->`` just before
the block runs the named change first (``CHANGES`` below: an edit the example shows the effect
of).

``python tests/examples.py`` (``make examples``) rewrites the expected output of every example
that no longer matches, keeping the marks wherever they still match; ``make test`` only compares.
"""

from __future__ import annotations

import difflib
import os
import re
import shlex
import shutil
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SOURCES = ("README.md", "docs")
COPIED = ("robots", "tests/cases")
ANY_LINES = "..."
ANY_TEXT = "…"
COMMAND = "make examples"  # or python tests/examples.py
_BLOCK = re.compile(r"(?:<!-- example: (?P<change>[\w-]+) -->\n)?```console\n(?P<body>.*?)^```$",
                    re.S | re.M)
ENV = {"COLUMNS": "200", "NO_COLOR": "1", "TERM": "dumb", "GITHUB_ACTIONS": "", "CI": "",
       "URDFTOOL_NO_CACHE": "1"}


@dataclass
class Run:
    """One ``$`` command of an example and the lines it is expected to print."""

    command: str
    expected: list[str] = field(default_factory=list)


@dataclass
class Example:
    file: str  # relative to ROOT
    line: int  # of the opening fence
    start: int  # offsets of the block's body in the file
    end: int
    change: str | None
    runs: list[Run]

    @property
    def name(self) -> str:
        return f"{self.file}:{self.line}"


def sources(root: Path = ROOT) -> list[Path]:
    files = [root / "README.md"]
    files += sorted(p for p in (root / "docs").rglob("*.md") if "rules" not in p.parts)
    return files


def examples(root: Path = ROOT) -> list[Example]:
    found = []
    for path in sources(root):
        text = path.read_text(encoding="utf-8")
        for match in _BLOCK.finditer(text):
            line = text.count("\n", 0, match.start("body"))
            found.append(Example(path.relative_to(root).as_posix(), line, match.start("body"),
                                 match.end("body"), match.group("change"),
                                 _runs(match.group("body"))))
    return found


def _runs(body: str) -> list[Run]:
    runs: list[Run] = []
    pending = None
    for line in body.splitlines():
        if pending is not None:
            pending += " " + line.strip().removesuffix("\\").strip()
            if not line.rstrip().endswith("\\"):
                runs.append(Run(pending))
                pending = None
        elif line.startswith("$ "):
            command = line[2:].rstrip()
            if command.endswith("\\"):
                pending = command.removesuffix("\\").strip()
            else:
                runs.append(Run(command))
        elif runs:
            runs[-1].expected.append(line.rstrip())
        elif line.strip():
            raise ValueError(f"output before any command: {line!r}")
    return runs


# ---- matching ----------------------------------------------------------------------------------

def _line_matches(pattern: str, line: str) -> bool:
    if ANY_TEXT not in pattern:
        return pattern == line
    regex = ".*?".join(re.escape(part) for part in pattern.split(ANY_TEXT))
    return re.fullmatch(regex, line, re.S) is not None


def align(patterns: list[str], lines: list[str]) -> tuple[int, list[str]]:
    """The fewest lines that differ between the expected ``patterns`` and the printed ``lines``
    (0: they match), and the expected text rewritten to match ``lines``: every pattern line that
    still matches kept as written, marks included; the rest the printed lines."""
    n, m = len(patterns), len(lines)
    cost = [[0] * (m + 1) for _ in range(n + 1)]
    for j in range(1, m + 1):
        cost[0][j] = j
    for i in range(1, n + 1):
        wild = patterns[i - 1] == ANY_LINES
        cost[i][0] = cost[i - 1][0] + (0 if wild else 1)
        for j in range(1, m + 1):
            if wild:
                cost[i][j] = min(cost[i - 1][j], cost[i][j - 1])
            else:
                same = 0 if _line_matches(patterns[i - 1], lines[j - 1]) else 1
                cost[i][j] = min(cost[i - 1][j - 1] + same, cost[i - 1][j] + 1,
                                 cost[i][j - 1] + 1)
    rewritten: list[str] = []
    i, j = n, m
    while i or j:
        wild = i and patterns[i - 1] == ANY_LINES
        if wild and j and cost[i][j] == cost[i][j - 1]:
            j -= 1  # the wildcard absorbs this line
            if not rewritten or rewritten[-1] != ANY_LINES:
                rewritten.append(ANY_LINES)
        elif wild and cost[i][j] == cost[i - 1][j]:
            if not rewritten or rewritten[-1] != ANY_LINES:
                rewritten.append(ANY_LINES)
            i -= 1
        elif i and j and cost[i][j] == cost[i - 1][j - 1] + (
                0 if _line_matches(patterns[i - 1], lines[j - 1]) else 1):
            same = _line_matches(patterns[i - 1], lines[j - 1])
            rewritten.append(patterns[i - 1] if same else lines[j - 1])
            i, j = i - 1, j - 1
        elif j and cost[i][j] == cost[i][j - 1] + 1:
            rewritten.append(lines[j - 1])
            j -= 1
        else:
            i -= 1  # an expected line no longer printed
    return cost[n][m], rewritten[::-1]


# ---- running -----------------------------------------------------------------------------------

def workspace(folder: Path, root: Path = ROOT) -> Path:
    """The scratch copy the examples run in (a git repository, branch main committed)."""
    for name in COPIED:
        shutil.copytree(root / name, folder / name, symlinks=True)
    git = ["git", "-c", "user.name=examples", "-c", "user.email=examples@localhost",
           "-c", "commit.gpgsign=false", "-c", "init.defaultBranch=main"]
    subprocess.run([*git, "init", "-q"], cwd=folder, check=True)
    subprocess.run([*git, "add", "-A"], cwd=folder, check=True)
    subprocess.run([*git, "commit", "-q", "--allow-empty", "-m", "examples"], cwd=folder, check=True)
    return folder


def _edit(path: Path, *replacements: tuple[str, str]) -> None:
    text = path.read_text(encoding="utf-8")
    for old, new in replacements:
        assert old in text, f"{path}: {old!r} is gone: the example's change needs updating"
        text = text.replace(old, new)
    path.write_text(text, encoding="utf-8")


def _lower_legs(folder: Path) -> None:
    """The humanoid's shins renamed lower legs (in its SRDF too), its knees 3 mm lower and
    bending to 140 degrees."""
    humanoid = folder / "robots" / "humanoid"
    _edit(humanoid / "leg.xacro", ("${prefix}_shin_link", "${prefix}_lower_leg_link"),
          ('xyz="0 0 ${-thigh_length}" axis="0 1 0"\n                       lower="0" upper="130"',
           'xyz="0 0 ${-thigh_length - 0.003}" axis="0 1 0"\n                       lower="0" upper="140"'))
    _edit(humanoid / "humanoid.srdf", ("_shin_link", "_lower_leg_link"))


CHANGES = {"humanoid-lower-legs": _lower_legs}


def run(command: str, folder: Path) -> list[str]:
    """What ``command`` prints, run in ``folder``, as lines."""
    from typer.testing import CliRunner

    from urdftool.cli import app

    words = shlex.split(command, comments=True)
    head = None
    output_file = None
    if "|" in words:
        at = words.index("|")
        tail, words = words[at + 1:], words[:at]
        if tail[:1] != ["head"] or len(tail) != 2 or not tail[1].startswith("-"):
            raise ValueError(f"only `| head -N` may follow a command: {command}")
        head = int(tail[1][1:])
    if ">" in words:
        at = words.index(">")
        output_file, words = words[at + 1], words[:at]
    if words[:1] != ["urdftool"]:
        raise ValueError(f"an example runs urdftool, not {words[:1]}: {command}")
    here = os.getcwd()
    os.chdir(folder)
    try:
        result = CliRunner().invoke(app, words[1:], env=ENV)
    finally:
        os.chdir(here)
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        raise result.exception
    if output_file is not None:
        (folder / output_file).write_text(result.stdout)
        lines = result.stderr.splitlines()
    else:
        lines = result.output.splitlines()
    lines = [line.rstrip() for line in lines]
    while lines and not lines[-1]:
        lines.pop()
    return lines[:head] if head is not None else lines


def outputs(example: Example, folder: Path) -> list[list[str]]:
    """What each command of ``example`` prints, run in order in ``folder``."""
    if example.change is not None:
        CHANGES[example.change](folder)
    return [run(step.command, folder) for step in example.runs]


def report(example: Example, printed: list[list[str]]) -> str | None:
    """None when ``example`` matches what it printed, else a diff for people."""
    problems = []
    for step, lines in zip(example.runs, printed):
        cost, _ = align(step.expected, lines)
        if cost:
            diff = difflib.unified_diff(step.expected, lines, "documented", "printed", lineterm="")
            problems.append(f"$ {step.command}\n" + "\n".join(diff))
    if not problems:
        return None
    return (f"{example.name}: the example no longer matches what urdftool prints (if the change "
            f"is intended, `{COMMAND}` rewrites it):\n" + "\n\n".join(problems))


def rewritten_body(example: Example, printed: list[list[str]], original: str) -> str:
    """The block's body with each command's expected output replaced as :func:`align` says."""
    body_lines = original.splitlines()
    out = []
    steps = iter(zip(example.runs, printed))
    step = None
    index = 0
    while index < len(body_lines):
        line = body_lines[index]
        if line.startswith("$ "):
            out.append(line)
            while line.rstrip().endswith("\\"):
                index += 1
                line = body_lines[index]
                out.append(line)
            step, lines = next(steps)
            out.extend(align(step.expected, lines)[1])
        index += 1
    return "\n".join(out) + "\n"


def update(root: Path = ROOT) -> list[str]:
    """Rewrite every example that no longer matches; the names of those rewritten."""
    import tempfile

    changed = []
    by_file: dict[str, list[tuple[Example, list[list[str]]]]] = {}
    for example in examples(root):
        with tempfile.TemporaryDirectory() as scratch:
            printed = outputs(example, workspace(Path(scratch), root))
        if report(example, printed) is not None:
            by_file.setdefault(example.file, []).append((example, printed))
            changed.append(example.name)
    for name, found in by_file.items():
        path = root / name
        text = path.read_text(encoding="utf-8")
        for example, printed in sorted(found, key=lambda pair: -pair[0].start):
            body = rewritten_body(example, printed, text[example.start:example.end])
            text = text[:example.start] + body + text[example.end:]
        path.write_text(text, encoding="utf-8")
    return changed


if __name__ == "__main__":
    os.environ.update(ENV)
    sys.path[:0] = [str(ROOT)]
    for name in update():
        print(f"rewrote {name}")
