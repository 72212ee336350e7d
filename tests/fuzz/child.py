"""Run one urdftool command in a forked child of a pre-imported parent, and watch it.

The parent imports urdftool and its heavy libraries once (:func:`preload`); each command then
runs in ``os.fork()``: the child installs an audit hook, redirects its output to a file and calls
the click command with ``standalone_mode``; the parent waits with a time limit and reads the
child's peak memory from ``os.wait4``. What the child does wrong comes back as an
:class:`Outcome`: exit status, output, peak RSS, seconds, and every file opened outside
``Allow``, every program started and every ``PWNED`` canary touched (payloads that run code
write one).

What may be opened (:class:`Allow`): the case's repository and its temporary folder (read and
write), folders the case names explicitly (``--package``, a seed's corpus repository: read
only), the Python installation (``sys.prefix``, ``sys.base_prefix``, site-packages, the urdftool
package: read only), ``/proc/self`` (and ``/proc/<own pid>``), ``/proc/loadavg``, ``/dev/null``,
``/dev/urandom``.
Anything else, after resolving symbolic links (so a link inside the repository that leads out
counts as outside), is a violation. File descriptors passed as numbers are not checked. Writes
outside (and starting programs) are refused with PermissionError after being noted, so a payload
cannot change anything beyond the case's folder (the corpus is writable on some machines).
"""

from __future__ import annotations

import io
import os
import resource
import signal
import sys
import tempfile
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path

CANARY = "PWNED"
SECRET_NAME = "URDFFUZZ_SECRET"
SECRET_VALUE = "s3cr3t-value-not-for-output"
_WRITE_FLAGS = os.O_WRONLY | os.O_RDWR | os.O_CREAT | os.O_TRUNC | os.O_APPEND
_EXEC_EVENTS = {"os.system", "subprocess.Popen", "os.exec", "os.posix_spawn", "os.spawn",
                "os.fork", "pty.spawn"}
_WRITE_EVENTS = {"os.remove", "os.rename", "os.replace", "os.rmdir", "os.truncate",
                 "os.chmod", "os.symlink", "os.link", "os.mkdir", "shutil.rmtree",
                 "shutil.copyfile", "shutil.move"}
_LIST_EVENTS = {"os.listdir", "os.scandir", "glob.glob"}


def preload() -> None:
    """Import what the commands import, so children fork with it loaded (fast, and the audit
    hook then sees the robot's files rather than Python's)."""
    import importlib

    for name in ("urdftool.cli", "urdftool.lint.engine", "urdftool.lint.runner",
                 "urdftool.lint.pool", "urdftool.description.load",
                 "urdftool.description.meshes", "urdftool.physics.dynamics", "urdftool.physics.inertia",
                 "urdftool.collision.pairs", "urdftool.collision.srdf", "urdftool.kinematics.fk",
                 "urdftool.kinematics.dh", "urdftool.report.dot", "urdftool.report",
                 "xacro", "yaml", "numpy", "trimesh", "trimesh.exchange.load", "fcl",
                 "pinocchio", "rich.console", "rich.table", "rich.tree", "json", "csv",
                 "zipfile", "xml.etree.ElementTree"):
        try:
            importlib.import_module(name)
        except Exception:  # an optional library missing: its command reports that itself
            pass
    try:  # trimesh registers its loaders lazily on first use
        import trimesh

        trimesh.available_formats()
    except Exception:
        pass
    import gc

    gc.collect()
    gc.freeze()  # children then leave the parent's objects alone: fewer copied pages


@dataclass
class Allow:
    """Folders a child may read (``read``) and write (``write``), as resolved absolute paths."""

    read: list[str] = field(default_factory=list)
    write: list[str] = field(default_factory=list)
    listable: set[str] = field(default_factory=set)  # sys.path folders (the import system lists)
    programs: set[str] = field(default_factory=set)  # what may be started (``git`` for diff --rev)

    @classmethod
    def for_case(cls, repo: Path, scratch: Path, extra_read=(), programs=()) -> "Allow":
        python = {sys.prefix, sys.base_prefix, sys.exec_prefix, sys.base_exec_prefix}
        python |= {p for p in sys.path if "-packages" in p}
        import urdftool

        python.add(os.path.dirname(urdftool.__file__))
        python.add(os.path.dirname(__file__))  # this harness: a traceback's source lines
        read = [_real(p) for p in (*python, *extra_read) if p]
        write = [_real(repo), _real(scratch)]
        listable = {_real(p or ".") for p in sys.path}
        return cls(read=sorted(set(read + write)), write=write, listable=listable,
                   programs=set(programs))

    def reads(self, path: str) -> bool:
        return _under(path, self.read)

    def writes(self, path: str) -> bool:
        return _under(path, self.write)


def _real(path) -> str:
    return os.path.realpath(os.fspath(path))


def _under(path: str, folders: list[str]) -> bool:
    return any(path == f or path.startswith(f + os.sep) for f in folders)


def _own_special(raw: str) -> bool:
    # /proc/loadavg: the machine's load, which the default --jobs reads (budget.busy_cores)
    if raw in ("/dev/null", "/dev/urandom", "/dev/random", "/proc/loadavg"):
        return True
    for prefix in ("/proc/self/", "/proc/thread-self/", f"/proc/{os.getpid()}/"):
        if raw.startswith(prefix):
            return True
    return False


@dataclass
class Outcome:
    argv: list[str]
    status: int | None  # exit code; negative: killed by that signal; None: over the time limit
    output: str
    peak_kib: int
    seconds: float
    events: list[str]  # outside opens, programs started, canaries

    @property
    def hung(self) -> bool:
        return self.status is None


def run(argv: list[str], **options) -> Outcome:
    """Run ``urdftool ARGV`` in a forked child and wait for it; see :func:`start`."""
    return start(argv, **options).finish()


def run_all(commands: list[list[str]], parallel: int = 1, **options) -> list[Outcome | None]:
    """Run several commands, at most ``parallel`` at a time; outcomes in the given order.

    After a command hangs the rest are not started (their outcome is None): what makes one
    command hang mostly makes them all hang, and each would cost the whole time limit."""
    pending = list(enumerate(commands))
    running: list[tuple[int, Running]] = []
    outcomes: list[Outcome | None] = [None] * len(commands)
    while pending or running:
        while pending and len(running) < max(1, parallel):
            index, argv = pending.pop(0)
            running.append((index, start(argv, **options)))
        for index, child in list(running):
            if child.poll():
                outcomes[index] = child.finish()
                running.remove((index, child))
                if outcomes[index].hung:
                    pending.clear()
        time.sleep(0.005)
    return outcomes


def start(argv: list[str], *, cwd: Path, allow: Allow, scratch: Path, stdin: bytes | None = None,
          time_limit: float = 30.0, memory_limit: int | None = None,
          env: dict[str, str] | None = None) -> "Running":
    """Start ``urdftool ARGV`` in a forked child; see the module docstring.

    time_limit: [s] before the child and its process group are killed (the outcome then has
    status None); memory_limit: address-space limit for the child [bytes] (a safety net for the
    machine; the verdict on memory uses the measured peak RSS).
    """
    out = tempfile.NamedTemporaryFile(dir=scratch, prefix="out-", delete=False)
    log = tempfile.NamedTemporaryFile(dir=scratch, prefix="audit-", delete=False)
    stdin_path = None
    if stdin is not None:
        handle, name = tempfile.mkstemp(dir=scratch, prefix="stdin-")
        with os.fdopen(handle, "wb") as file:
            file.write(stdin)
        stdin_path = Path(name)
    for stream in (sys.stdout, sys.stderr):
        stream.flush()
    pid = os.fork()
    if pid == 0:  # the child: never returns
        _child(argv, cwd, allow, scratch, out.fileno(), log.fileno(), stdin_path,
               memory_limit, env or {})
    out.close()
    log.close()
    return Running(argv, pid, Path(out.name), Path(log.name), time_limit)


class Running:
    """A started child; ``poll()`` says when it is done (or over time), ``finish()`` reaps it."""

    def __init__(self, argv, pid, out: Path, log: Path, time_limit: float):
        self.argv, self.pid, self.out, self.log = argv, pid, out, log
        self.started = time.perf_counter()
        self.time_limit = time_limit
        self.deadline = time.monotonic() + time_limit
        self.status: int | None = None
        self.usage = None
        self.done = False

    def poll(self) -> bool:
        if not self.done:
            pid, status, usage = os.wait4(self.pid, os.WNOHANG)
            if pid:
                self.status, self.usage, self.done = os.waitstatus_to_exitcode(status), usage, True
                self.seconds = time.perf_counter() - self.started
            elif time.monotonic() > self.deadline and self._over_time():
                _kill_group(self.pid)
                _, _, self.usage = os.wait4(self.pid, 0)
                self.status, self.done = None, True
                self.seconds = time.perf_counter() - self.started
            if self.done:
                _kill_group(self.pid)  # workers the command left behind
        return self.done

    def _over_time(self) -> bool:
        """Whether the child, past its wall deadline, counts as hung: it and its descendants
        have spent ``time_limit`` seconds of CPU (a busy hang, whatever the machine's load), or
        ``WALL_FACTOR`` times that in wall time (a hang that sleeps). On a loaded machine a
        command that ends within its limit of CPU is late, not hung; it is waited for."""
        over_wall = time.monotonic() > self.deadline + (WALL_FACTOR - 1) * self.time_limit
        return over_wall or tree_cpu_seconds(self.pid) >= self.time_limit

    def finish(self) -> Outcome:
        delay = 0.002
        while not self.poll():
            time.sleep(delay)
            delay = min(delay * 2, 0.05)
        output = self.out.read_bytes().decode("utf-8", "replace")
        events = self.log.read_bytes().decode("utf-8", "replace").splitlines()
        self.out.unlink()
        self.log.unlink()
        return Outcome(self.argv, self.status, output, self.usage.ru_maxrss if self.usage else 0,
                       self.seconds, list(dict.fromkeys(events)))


WALL_FACTOR = 6  # a child under its CPU limit is hung only past this many limits of wall time
_TICKS = os.sysconf("SC_CLK_TCK")


def tree_cpu_seconds(root: int) -> float:
    """CPU seconds [s] spent by process ``root`` and its live descendants, whatever group or
    session they moved to (the pool's workers have their own), with the children each reaped
    (``/proc/PID/stat``: ppid, utime, stime, cutime, cstime)."""
    parents, spent = {}, {}
    for entry in os.scandir("/proc"):
        if not entry.name.isdigit():
            continue
        try:
            with open(f"/proc/{entry.name}/stat", "rb") as file:
                fields = file.read().rsplit(b")", 1)[1].split()
        except OSError:  # gone meanwhile
            continue
        pid = int(entry.name)
        parents[pid] = int(fields[1])  # fields after the name: state, ppid, pgrp, ...
        spent[pid] = sum(int(value) for value in fields[11:15])
    total, tree = 0, {root}
    while True:
        grown = {pid for pid, parent in parents.items() if parent in tree} - tree
        if not grown:
            break
        tree |= grown
    for pid in tree:
        total += spent.get(pid, 0)
    return total / _TICKS


def _kill_group(pid: int) -> None:
    try:
        os.killpg(pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass


def _child(argv, cwd, allow, scratch, out_fd, log_fd, stdin_path, memory_limit, env):
    code = 125
    try:
        os.setpgid(0, 0)
        signal.signal(signal.SIGINT, signal.SIG_DFL)
        os.chdir(cwd)
        os.dup2(out_fd, 1)
        os.dup2(out_fd, 2)
        os.dup2(os.open(stdin_path or os.devnull, os.O_RDONLY), 0)
        sys.stdin = io.TextIOWrapper(io.FileIO(0, "r", closefd=False))
        sys.stdout = io.TextIOWrapper(io.FileIO(1, "w", closefd=False), write_through=True)
        sys.stderr = io.TextIOWrapper(io.FileIO(2, "w", closefd=False), write_through=True)
        os.environ.update({"TMPDIR": str(scratch), "COLUMNS": "150", "NO_COLOR": "1",
                           "TERM": "dumb", "GITHUB_ACTIONS": "", "CI": "", SECRET_NAME:
                           SECRET_VALUE, "MPLCONFIGDIR": str(scratch),
                           # the result cache on, as users have it (the test suite turns it
                           # off for itself), its signing key ($XDG_CACHE_HOME/urdftool/key)
                           # made in the case's scratch folder, not read from the user's home
                           "URDFTOOL_NO_CACHE": "", "XDG_CACHE_HOME": str(scratch), **env})
        tempfile.tempdir = str(scratch)
        if memory_limit:
            resource.setrlimit(resource.RLIMIT_AS, (memory_limit, memory_limit))
        # Python's own bytecode cache is not the command's doing (a module imported first here
        # is compiled, and pytest's rewrite of urdftool, a plugin's package, makes its folder):
        # an installed urdftool has its bytecode, and make test lets Python write it
        sys.dont_write_bytecode = True
        sys.addaudithook(_auditor(allow, log_fd))
        from urdftool.cli import app

        try:
            app(args=list(argv), prog_name="urdftool", standalone_mode=True)
            code = 0
        except SystemExit as stop:
            code = stop.code if isinstance(stop.code, int) else (0 if stop.code is None else 1)
        except BaseException:  # what a user would see: a traceback, exit 1
            traceback.print_exc()
            code = 1
    except BaseException:
        try:
            traceback.print_exc()
        except BaseException:
            pass
    finally:
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except BaseException:
                pass
        os._exit(code)


def _program(args) -> str | None:
    """The program name a ``subprocess.Popen`` audit event starts (executable or argv[0])."""
    executable, argv = (tuple(args) + (None, None))[:2]
    first = executable or (argv[0] if isinstance(argv, (list, tuple)) and argv else argv)
    return os.path.basename(os.fsdecode(first)) if isinstance(first, (str, bytes)) else None


def _auditor(allow: Allow, log_fd: int):
    busy = [False]

    def note(text: str) -> None:
        os.write(log_fd, (text.replace("\n", "\\n") + "\n").encode("utf-8", "replace"))

    def hook(event: str, args) -> None:
        if busy[0]:
            return
        flags = None
        if event == "open":
            target, mode, flags = (tuple(args) + (None, None))[:3]
            writing = (isinstance(mode, str) and any(c in mode for c in "wax+")) or \
                      (isinstance(flags, int) and flags & _WRITE_FLAGS)
        elif event in _LIST_EVENTS:
            target, writing = args[0] if args else ".", False
        elif event in _WRITE_EVENTS:
            target, writing = args[0] if args else None, True
            if event in ("os.rename", "os.replace", "shutil.copyfile", "shutil.move"):
                target = args[1]
        elif event in _EXEC_EVENTS:
            if event == "os.fork":
                return  # check's own worker processes
            if event == "subprocess.Popen" and _program(args) in allow.programs:
                return  # git for diff --rev: what it opens and starts is traced (strace)
            note(f"exec: {event} {args!r}"[:300])
            raise PermissionError(f"fuzz harness: {event} refused")
        else:
            return
        if target is None or isinstance(target, int):
            return
        busy[0] = True
        refuse = False
        try:
            raw = os.path.abspath(os.fsdecode(target))
            if os.path.basename(raw).startswith(CANARY):
                note(f"canary: {event} {raw}")
            if _own_special(raw):
                return
            real = os.path.realpath(raw)
            if event in _WRITE_EVENTS or (event == "open" and isinstance(flags, int)
                                          and flags & os.O_NOFOLLOW):
                # these act on a final symbolic link itself, not on where it leads
                real = os.path.join(os.path.realpath(os.path.dirname(raw)),
                                    os.path.basename(raw))
            if event in _LIST_EVENTS and real in allow.listable:
                return
            if not (allow.writes(real) if writing else allow.reads(real)):
                shown = raw if real == raw else f"{raw} -> {real}"
                note(f"outside: {event} {'write' if writing else 'read'} {shown}")
                refuse = writing  # reads go on (their effects are judged); writes never land
        except Exception as error:  # the hook must never break the command
            note(f"audit hook error: {error!r}")
        finally:
            busy[0] = False
        if refuse:
            raise PermissionError(f"fuzz harness: write outside the case refused: {target!r}")

    return hook
