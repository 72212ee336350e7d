"""Fuzz mode ``--server``: language-server sessions (floods, huge and slow documents).

Each case is a drawn session against a real ``urdftool server --timeout BUDGET`` over stdio: a
few documents opened, changed (floods within and past the debounce), saved and closed, each
text drawn from fast robots (with findings), hostile names, malformed XML, a huge buffer, a
document that takes hours to expand. Invariants:

- the server never dies, never writes a traceback, answers a hover promptly at the end, and
  goes on past messages framed right that pygls cannot read (GARBAGE: not JSON, the wrong
  shape, a hostile method name, nesting past the recursion limit);
- input that breaks the framing (BREAKS: a 100 GB length, a length that is not a number, none,
  an endless header line) ends it with status 1 and one line saying so;
- it never runs more checks at once than its pool allows (JOBS: its worker processes sampled
  throughout), so no flood queues unbounded work;
- every document still open ends with the diagnostics of its last version (the log says which
  version each published check read; no older one is published after a newer one), a slow one
  with U015 within its budget;
- its peak memory stays under MEMORY_LIMIT_MIB, and it ends within seconds of ``exit``.

A failing session is kept as ``server-<hash>.json`` in tests/fuzz/regressions and replayed by
tests/integration/test_fuzz_output.py.
"""

from __future__ import annotations

import hashlib
import json
import os
import queue
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

from hypothesis import strategies as st

from tests.slow_robots import slow_xacro

from . import forge
from .harness import REGRESSIONS

BUDGET = 3  # [s] the server's --timeout
JOBS = 4  # the most checks a server runs at once (urdftool.server: at most 4)
MEMORY_LIMIT_MIB = 1024  # peak RSS of the server process
SETTLE = BUDGET * 4 + 20  # [s] for the last versions to be published
ROBOT = """<?xml version="1.0"?>
<robot name="r{n}">
  <link name="a"/><link name="b{n}"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b{n}"/>
    <limit lower="1" upper="-1" effort="1" velocity="1"/></joint>
</robot>
"""


def text_of(kind: str, n: int) -> str:
    if kind == "fast":
        return ROBOT.format(n=n)
    if kind == "slow":
        return slow_xacro(link=f"base{n}")
    if kind == "hostile":
        return forge.robot_urdf(forge.names()) + f"<!-- {n} -->"
    if kind == "malformed":
        return ROBOT.format(n=n)[:-20]
    if kind == "huge":  # 20 MB: over the 16 MiB a check reads
        return ROBOT.format(n=n).replace("</robot>", "<!--" + "x" * (20 << 20) + "--></robot>")
    if kind == "many":  # 3 MB of links: a long check, within the size limit
        links = "".join(f'<link name="l{i}"/>' for i in range(120_000))
        return ROBOT.format(n=n).replace("</robot>", links + "</robot>")
    return ""


KINDS = ["fast", "fast", "slow", "hostile", "malformed", "huge", "many", "empty"]
DOCUMENTS = ["a.urdf", "b.urdf.xacro", "c.urdf"]


def _framed(body: bytes) -> bytes:
    return b"Content-Length: %d\r\n\r\n" % len(body) + body


# Messages framed right that pygls cannot read or run: the server answers or logs one line
# each and goes on.
GARBAGE = {
    "not-json": _framed(b"{xx}}"),
    "wrong-shape": _framed(b'{"jsonrpc": "2.0", "method": "textDocument/didOpen", '
                           b'"params": {"textDocument": 5}}'),
    "hostile-method": _framed(b'{"jsonrpc": "2.0", "id": 777, "method": '
                              b'"\\u001b[2J\\n::error::x\\u202e", "params": null}'),
    "deep": _framed(b"[" * 200_000),
    "bad-version": _framed(b'{"jsonrpc": "1.0", "method": "x"}'),
}
# Input that breaks the framing: the server stops with status 1 and one line saying why.
BREAKS = {
    "100GB": b"Content-Length: 100000000000\r\n\r\n{}",
    "not-a-number": b"Content-Length: abc\r\n\r\n{}",
    "no-length": b"Content-Type: x\r\n\r\n{}",
    "endless-line": b"X" * 5_000_000,
    "bare-newline": b"\n",
}


@st.composite
def sessions(draw):
    """A list of events: (action, document index, text kind, pause [s] after it)."""
    events = []
    for _ in range(draw(st.integers(1, 6))):
        action = draw(st.sampled_from(["open", "change", "change", "flood", "save", "close",
                                       "garbage"]))
        kind = draw(st.sampled_from(sorted(GARBAGE) if action == "garbage" else KINDS))
        events.append([action, draw(st.integers(0, len(DOCUMENTS) - 1)), kind,
                       draw(st.sampled_from([0.0, 0.01, 0.2, 0.5, 1.0]))])
    if draw(st.booleans()):  # the session ends with its input broken, not with exit
        events.append(["break", 0, draw(st.sampled_from(sorted(BREAKS))), 0.0])
    return events


def children(pid: int) -> int:
    """How many processes ``pid`` started that have not ended (a server's check workers)."""
    count = 0
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        count += fields[1] == str(pid) and fields[0] != "Z"
    return count


class Session:
    """A server process, what it sent, and a JSON-RPC writer."""

    def __init__(self, folder: Path):
        self.process = subprocess.Popen(
            [sys.executable, "-m", "urdftool", "server", "--timeout", str(BUDGET)],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, cwd=folder)
        self.messages: queue.Queue = queue.Queue()
        self.seen: list[dict] = []
        self.stderr = b""
        threading.Thread(target=self._read, daemon=True).start()
        threading.Thread(target=self._read_errors, daemon=True).start()
        self.ids = iter(range(1, 1 << 30))

    def _read(self) -> None:
        stream = self.process.stdout
        while True:
            header = b""
            while not header.endswith(b"\r\n\r\n"):
                byte = stream.read(1)
                if not byte:
                    return
                header += byte
            length = int(header.split(b"Content-Length:")[1].split(b"\r\n")[0])
            self.messages.put(json.loads(stream.read(length)))

    def _read_errors(self) -> None:
        self.stderr = self.process.stderr.read()

    def send(self, method: str, params: dict, request: bool = False) -> int | None:
        message = {"jsonrpc": "2.0", "method": method, "params": params}
        number = next(self.ids) if request else None
        if request:
            message["id"] = number
        body = json.dumps(message).encode()
        self.process.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        self.process.stdin.flush()
        return number

    def send_raw(self, data: bytes) -> None:
        try:
            self.process.stdin.write(data)
            self.process.stdin.flush()
        except BrokenPipeError:  # the server stopped reading (a broken input ends it): what
            pass  # follows says whether it should have

    def drain(self) -> None:
        while True:
            try:
                self.seen.append(self.messages.get_nowait())
            except queue.Empty:
                return

    def answer(self, number: int, seconds: float) -> dict | None:
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            self.drain()
            for message in self.seen:
                if message.get("id") == number and "method" not in message:
                    return message
            time.sleep(0.02)
        return None

    def workers(self) -> int:
        return children(self.process.pid)

    def peak_mib(self) -> int:
        try:
            for line in Path(f"/proc/{self.process.pid}/status").read_text().splitlines():
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) // 1024
        except OSError:
            pass
        return 0

    def checked(self) -> list[str]:
        return [m["params"]["message"] for m in self.seen if m.get("method") ==
                "window/logMessage" and m["params"]["message"].startswith("checked ")]


def run_session(events: list) -> tuple[list[str], int]:
    """Play ``events``; (what broke an invariant, peak memory of the server [MiB])."""
    folder = Path(tempfile.mkdtemp(prefix="urdffuzz-lsp-"))
    (folder / ".git").mkdir()
    session = Session(folder)
    found: list[str] = []
    peak = 0
    try:
        session.send("initialize", {"processId": None, "rootUri": folder.as_uri(),
                                    "capabilities": {}}, request=True)
        session.send("initialized", {})
        open_docs: dict[int, tuple[int, str]] = {}  # index -> (version, kind)
        versions = dict.fromkeys(range(len(DOCUMENTS)), 0)  # never back: reopened goes on
        most = 0
        broken = events[-1][2] if events and events[-1][0] == "break" else None
        for action, index, kind, pause in events:
            uri = (folder / DOCUMENTS[index]).as_uri()
            if action == "break":
                continue  # at the end, once the documents are published
            if action == "garbage":
                session.send_raw(GARBAGE[kind])
            elif action == "open" or index not in open_docs and action != "close":
                versions[index] += 1
                (folder / DOCUMENTS[index]).write_text(text_of(kind, 0))
                session.send("textDocument/didOpen", {"textDocument": {
                    "uri": uri, "languageId": "xml", "version": versions[index],
                    "text": text_of(kind, 0)}})
                open_docs[index] = (versions[index], kind)
            elif action in ("change", "flood"):
                for _ in range(60 if action == "flood" else 1):
                    versions[index] += 1
                    version = versions[index]
                    session.send("textDocument/didChange", {
                        "textDocument": {"uri": uri, "version": version},
                        "contentChanges": [{"text": text_of(kind, version)}]})
                    open_docs[index] = (version, kind)
                    most = max(most, session.workers())
            elif action == "save" and index in open_docs:
                session.send("textDocument/didSave", {"textDocument": {"uri": uri}})
            elif action == "close" and index in open_docs:
                session.send("textDocument/didClose", {"textDocument": {"uri": uri}})
                del open_docs[index]
            end = time.monotonic() + pause
            while True:
                most = max(most, session.workers())
                if time.monotonic() >= end:
                    break
                time.sleep(0.05)
        if most > JOBS:
            found.append(f"{most} checks ran at once (the pool has at most {JOBS})")
        deadline = time.monotonic() + SETTLE
        while time.monotonic() < deadline:
            session.drain()
            last = {index: f"{DOCUMENTS[index]} (version {version})"
                    for index, (version, kind) in open_docs.items()}
            if all(any(text in m for m in session.checked()) for text in last.values()):
                break
            time.sleep(0.1)
            if session.process.poll() is not None:
                break
        else:
            waiting = [text for text in last.values()
                       if not any(text in m for m in session.checked())]
            errors = [m["params"]["message"][:300] for m in session.seen
                      if m.get("method") == "window/logMessage" and m["params"]["type"] == 1]
            found.append(f"not published within {SETTLE} s: {waiting}; checked: "
                         f"{session.checked()[-6:]}; errors: {errors[-3:]}")
        found += _order(session.checked())
        number = session.send("textDocument/hover", {
            "textDocument": {"uri": (folder / DOCUMENTS[0]).as_uri()},
            "position": {"line": 0, "character": 0}}, request=True)
        if session.answer(number, 5.0) is None:
            found.append("no answer to a hover within 5 s")
        peak = session.peak_mib()
        if peak > MEMORY_LIMIT_MIB:
            found.append(f"the server peaked at {peak} MiB")
        if session.process.poll() is not None:
            found.append(f"the server died (exit {session.process.returncode})")
        elif broken:
            session.send_raw(BREAKS[broken])
            try:
                status = session.process.wait(SETTLE)
            except subprocess.TimeoutExpired:
                status = None
            time.sleep(0.2)  # its standard error read to the end
            if status != 1 or b"the client's input" not in session.stderr:
                found.append(f"input broken ({broken}): exit {status}, standard error "
                             f"{session.stderr[-300:]!r}")
        else:
            number = session.send("shutdown", {}, request=True)
            session.answer(number, 10.0)
            session.send("exit", {})
            try:
                session.process.wait(10)
            except subprocess.TimeoutExpired:
                found.append("the server did not end within 10 s of exit")
    finally:
        if session.process.poll() is None:
            session.process.kill()
            session.process.wait()
        time.sleep(0.1)
        if b"Traceback" in session.stderr:
            found.append("traceback: " + session.stderr.decode("utf-8", "replace")[-3000:])
        import shutil

        shutil.rmtree(folder, ignore_errors=True)
    return found, peak


def _order(checked: list[str]) -> list[str]:
    """A published check of an older version after a newer one of the same document."""
    import re

    last: dict[str, int] = {}
    found = []
    for message in checked:
        match = re.match(r"checked (.*) \(version (\d+)\)", message)
        if match:
            name, version = match.group(1), int(match.group(2))
            if version < last.get(name, 0):
                found.append(f"version {version} of {name} published after {last[name]}")
            last[name] = max(version, last.get(name, 0))
    return found


def save(events: list, found: list[str]) -> Path:
    digest = hashlib.sha256(json.dumps(events).encode()).hexdigest()
    REGRESSIONS.mkdir(exist_ok=True)
    path = REGRESSIONS / f"server-{digest[:12]}.json"
    path.write_text(json.dumps({"mode": "server", "events": events, "found": found},
                               indent=1) + "\n")
    return path


def replay(path: Path) -> list[str]:
    return run_session(json.loads(path.read_text())["events"])[0]


def run(count: int, seed: int = 0, keep: bool = True) -> dict:
    """``count`` sessions; figures: cases, failures, peak memory of a server [MiB], seconds."""
    from .run import drive

    def attempt(events, stats):
        found, peak = run_session(events)
        stats["peak_mib"] = max(stats["peak_mib"], peak)
        return found, lambda: save(events, found)

    return drive(sessions(), attempt, count, seed, keep, every=10, peak_mib=0)


if __name__ == "__main__":  # one session of the draws, for a look: python -m ...server_session
    print(run(int(os.environ.get("COUNT", "1")), keep=False))
