"""Run fuzz cases and list what went wrong.

:func:`problems` checks a mutated robot with the check engine in-process. Invariants: no
traceback escapes, no U900 (a crash inside urdftool), no hang, every file that fails to load has
at least one error with a line, and nothing from /etc/passwd reaches output.

:func:`case_report` runs a whole hostile repository (cases.py) through every command, each in a
forked child (child.py), and adds: exit status 0, 1 or 2, a time limit per command, peak memory,
no file opened outside the repository, no code run, no write through a planted link.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import os
import re
import signal
from dataclasses import dataclass, field
from pathlib import Path

from urdftool.lint.engine import CheckOptions, load_and_check

from .cases import SECRET_LINK, Case, cleanup, commands, git_environment, materialize
from .child import CANARY, SECRET_VALUE, Allow, run_all
from .mutate import CORPUS, ROOT, Seed

REGRESSIONS = Path(os.environ.get("URDFFUZZ_REGRESSIONS",
                                  Path(__file__).resolve().parent / "regressions"))
HANG_SECONDS = 60
_UNLOCATED_OK = {"U008"}  # file-too-large is about the whole file


class _Hang(Exception):
    pass


def _alarm(signum, frame):
    raise _Hang()


def problems(seed: Seed, data: bytes) -> list[str]:
    """What this case violates (empty when it behaves)."""
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(HANG_SECONDS)
    try:
        result = load_and_check(str(seed.path), CheckOptions(xacro_args=dict(seed.args),
                                                         allow_env=False), data=data)
    except _Hang:
        return [f"hang: over {HANG_SECONDS} s"]
    except BaseException as error:  # the point of the harness
        return [f"traceback: {type(error).__name__}: {error}"]
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)
    found = []
    for finding in result.findings:
        if finding.code == "U900":
            found.append(f"U900 at {finding.location}: {finding.message}")
        if "root:x:0:0" in finding.message:
            found.append(f"/etc/passwd leaked into {finding.code}")
    if result.robot is None:
        located = [f for f in result.findings if f.severity.value == "error"
                   and (f.line is not None or f.code in _UNLOCATED_OK)]
        if not located:
            found.append("load failed without a located error: "
                         + "; ".join(f"{f.code} {f.location}" for f in result.findings))
    elif "root:x:0:0" in result.robot.urdf:
        found.append("/etc/passwd leaked into the expanded URDF")
    return found


def save_regression(seed: Seed, data: bytes, why: list[str], name: str | None = None) -> Path:
    """Keep a failing input as tests/fuzz/regressions/<hash>.bin plus a .json describing it."""
    REGRESSIONS.mkdir(exist_ok=True)
    digest = name or hashlib.sha256(data).hexdigest()[:12]
    path = REGRESSIONS / f"{digest}.bin"
    path.write_bytes(data)
    meta = {"seed": _portable(seed.path), "args": {k: _portable_text(v) for k, v in seed.args.items()},
            "found": why}
    path.with_suffix(".json").write_text(json.dumps(meta, indent=1) + "\n")
    return path


def load_regression(path: Path) -> tuple[Seed, bytes]:
    meta = json.loads(path.with_suffix(".json").read_text())
    seed_path = Path(meta["seed"].replace("<corpus>", str(CORPUS)).replace("<root>", str(ROOT)))
    args = {k: v.replace("<corpus>", str(CORPUS)) for k, v in meta["args"].items()}
    return Seed(seed_path, args), path.read_bytes()


def _portable(path: Path) -> str:
    return _portable_text(str(path))


def _portable_text(text: str) -> str:
    return text.replace(str(CORPUS), "<corpus>").replace(str(ROOT), "<root>")


# ------------------------------------------------------------ every command, in forked children

MEMORY_LIMIT_KIB = int(2.5 * 1024 * 1024)  # peak RSS a case may reach in one command [KiB]
NO_ENV_COMMANDS = {"check", "check-text", "check-walk", "xacro"}
_NO_ENV_OUTPUTS = {"report.json", "robot.urdf"}  # what check and xacro write (with --no-env)
_LEAKS = {"root:x:0:0": "/etc/passwd", SECRET_LINK: "a file outside the repository"}


@dataclass
class CaseReport:
    """What one case did: failures, and figures for the run's summary."""

    failures: list[str] = field(default_factory=list)
    failed_commands: list[str] = field(default_factory=list)
    peak_kib: int = 0
    outside: int = 0  # files opened outside the allowed folders
    seconds: float = 0.0


def case_report(case: Case, *, time_limit: float = 30.0, parallel: int = 2) -> CaseReport:
    """Run ``case`` through its commands (each in a forked child, see child.py) and judge them.

    A command fails on: exit status other than 0, 1, 2 (or a signal), a hang over
    ``time_limit``, a Python traceback or U900 in its output, /etc/passwd or a file from outside
    in its output or written files, the secret environment variable in the output of a command
    run with ``--no-env``, peak RSS over MEMORY_LIMIT_KIB, a file opened outside the repository,
    a program started, a ``PWNED`` canary touched, a write through a symbolic link planted at an
    output path, or a text report saying "no problems found" while exiting 1.
    """
    layout = materialize(case)
    report = CaseReport()
    try:
        allow = Allow.for_case(layout.repo, layout.scratch,
                               extra_read=[str(p) for p in layout.reads],
                               programs=("git",) if case.git else ())
        table = commands(case, layout)
        outcomes = run_all(list(table.values()), parallel=parallel, cwd=layout.cwd, allow=allow,
                           scratch=layout.scratch, stdin=layout.stdin, time_limit=time_limit,
                           memory_limit=_address_space_limit(),
                           env=git_environment(case, layout))
        for name, outcome in zip(table, outcomes):
            if outcome is None:  # not started after another command hung
                continue
            found = _judge(name, outcome, time_limit) + _expected(case, name, outcome)
            report.peak_kib = max(report.peak_kib, outcome.peak_kib)
            report.outside += sum(e.startswith("outside:") for e in outcome.events)
            report.seconds += outcome.seconds
            if found:
                report.failures.extend(found)
                report.failed_commands.append(name)
        report.failures.extend(_after(layout))
        traced = _git_traced(layout)
        report.outside += sum(found.startswith("outside") for found in traced)
        report.failures.extend(traced)
    finally:
        cleanup(layout)
    return report


_CHECKS = {"check", "check-text", "check-walk"}


def _expected(case: Case, name: str, outcome) -> list[str]:
    """What the case itself asks: names found outside never printed (include patterns), a
    hostile settings file refused by every check (exit 2, said why)."""
    found = [f"leak: {name} printed '{text}', a name from outside the repository"
             for text in case.forbidden if text in outcome.output]
    if case.expect and name in _CHECKS and (outcome.status != 2
                                            or case.expect not in outcome.output):
        found.append(f"settings: {name} did not refuse the settings (exit {outcome.status})")
    return found


# what git may open: the repository (its .git), the scratch folder, its own installation
_GIT_READS = ("/etc/ld.so.cache", "/lib/", "/lib64/", "/usr/lib/", "/usr/lib64/",
              "/usr/share/locale/", "/usr/share/git-core/", "/dev/null", "/proc/self/",
              "/etc/localtime")
_TRACED = re.compile(r'^\d+\s+(openat|open|creat|execve|rename|unlink|mkdir)\((?:AT_FDCWD, )?'
                     r'"([^"]*)"(.*)= (-?\d+)')


def _git_traced(layout) -> list[str]:
    """Every file git opened outside the repository, its scratch folder and its own
    installation, every program it started but itself, and every marker a planted git
    configuration wrote (scratch/markers): strace's logs of scratch/bin/git."""
    found = []
    markers = layout.scratch / "markers"
    if markers.is_dir():
        found += [f"code ran: git ran what a planted config names ({path.name})"
                  for path in sorted(markers.iterdir())]
    allowed = (os.path.realpath(layout.repo), os.path.realpath(layout.scratch))
    for log in sorted(layout.scratch.glob("strace.*")):
        for line in log.read_text(errors="replace").splitlines():
            match = _TRACED.match(line)
            if not match or int(match.group(4)) < 0:
                continue
            call, path = match.group(1), match.group(2)
            if call == "execve":
                if not os.path.basename(path).startswith("git"):
                    found.append(f"code ran: git started {path}")
                continue
            absolute = path if path.startswith("/") else None
            if absolute is None or any((os.path.realpath(absolute) + "/").startswith(a + "/")
                                       for a in allowed) or absolute.startswith(_GIT_READS):
                continue
            found.append(f"outside: git {call} {absolute}")
    return found


_CLEAN_SUMMARY = re.compile(r"\d+ files? checked: no problems found")


def _judge(name: str, outcome, time_limit: float) -> list[str]:
    found = []
    text = outcome.output
    if outcome.hung:
        found.append(f"hang: {name} over {time_limit:.0f} s")
    elif outcome.status not in (0, 1, 2):
        found.append(f"exit status {outcome.status}: {name}")
    if "Traceback (most recent call last)" in text:
        last = [line for line in text.splitlines() if line and not line.startswith(" ")][-1:]
        kind = "memory" if "MemoryError" in text else "traceback"
        found.append(f"{kind}: {name}: {' '.join(last)[:200]}")
    if "U900" in text:
        found.append(f"U900: {name}: " + next(line for line in text.splitlines()
                                              if "U900" in line)[:200])
    for marker, what in _LEAKS.items():
        if marker in text:
            found.append(f"leak: {what} reached the output of {name}")
    if name in NO_ENV_COMMANDS and SECRET_VALUE in text:
        found.append(f"env: {name} --no-env printed an environment variable")
    lines = text.splitlines()
    if name == "check-text" and (any(line.startswith("::") for line in lines) or outcome.status == 1
                                 and any(_CLEAN_SUMMARY.match(line) for line in lines)):
        found.append(f"forged report: {name} printed a line its text format never writes")
    if outcome.peak_kib > MEMORY_LIMIT_KIB:
        found.append(f"memory: {name} peaked at {outcome.peak_kib // 1024} MiB")
    for event in outcome.events:
        kind = event.split(":", 1)[0]
        label = {"outside": "outside", "exec": "code ran", "canary": "code ran"}.get(kind, kind)
        found.append(f"{label}: {name}: {event[:240]}")
    return found


def _after(layout) -> list[str]:
    found = []
    if (layout.outside / "victim.txt").read_text() != "VICTIM\n" or \
            (layout.outside / "nowhere").exists():
        found.append("write through a symbolic link at an output path")
    linked = layout.outside / "outdir"
    if linked.is_dir() and sorted(p.name for p in linked.rglob("*")) != ["sub"]:
        found.append("write through a folder linked outside: "
                     + ", ".join(sorted(p.name for p in linked.rglob("*"))))
    for path in layout.repo.rglob(f"{CANARY}*"):
        found.append(f"code ran: {path.name} was created")
    for path in (layout.repo / "out").iterdir():
        if path.is_file() and not path.is_symlink() and path.stat().st_size < 50 << 20:
            data = path.read_bytes()
            if b"root:x:0:0" in data:
                found.append(f"leak: {path.name} holds /etc/passwd")
            if SECRET_VALUE.encode() in data and path.name in _NO_ENV_OUTPUTS:
                found.append(f"env: {path.name}, written with --no-env, holds an environment "
                             "variable")
    return found


def _address_space_limit() -> int:
    """The parent's virtual size plus 3 GiB: children inherit the parent's mappings, and a
    runaway allocation must stop before the machine's memory does."""
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmSize:"):
                return int(line.split()[1]) * 1024 + (3 << 30)
    return 8 << 30


def save_case_regression(case: Case, report: CaseReport) -> Path:
    """Keep a failing case like save_regression does, with its repository and the commands that
    failed (the replay runs only those)."""
    kept = dataclasses.replace(case, commands=tuple(report.failed_commands) or case.commands)
    meta = kept.to_json()
    digest = hashlib.sha256(case.data + json.dumps(meta, sort_keys=True).encode()).hexdigest()
    path = save_regression(case.seed, case.data, report.failures, name=digest[:12])
    stored = json.loads(path.with_suffix(".json").read_text())
    stored["case"] = meta
    path.with_suffix(".json").write_text(json.dumps(stored, indent=1) + "\n")
    return path


def replay(path: Path, time_limit: float = 30.0) -> list[str]:
    """What a kept regression input violates today (empty when it behaves)."""
    seed, data = load_regression(path)
    meta = json.loads(path.with_suffix(".json").read_text())
    if "case" not in meta:
        return problems(seed, data)
    return case_report(Case.from_json(seed, data, meta["case"]), time_limit=time_limit).failures
