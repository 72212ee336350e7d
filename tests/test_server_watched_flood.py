"""Files changed under the language server in bulk (docs/attacks.md, session 8): a checkout
or a build changes 300,000 files of the workspace, and the editor reports each
(``workspace/didChangeWatchedFiles``). Each changed path that concerned a robot scheduled a
job of its own (keyed by the path), each checking the same robots again: 30,000 events
queued 30,000 checks and the server answered no hover for minutes; ``Record.concerns`` also
scanned every path it knew for each question. Now ``watched`` schedules one job per robot
concerned (keyed by the robot), and a record answers "a folder above a path it knows" from an
index."""

from __future__ import annotations

import sys

import pytest

from test_server import _package, offline_server  # noqa: F401  (the fixture)
from urdftool.description import files
from urdftool.description.record import Record, recording


def test_a_flood_of_changed_files_schedules_one_job_per_robot_concerned(offline_server,  # noqa: F811
                                                                        tmp_path, monkeypatch):
    from urdftool.server import check_robot

    server, _ = offline_server
    robot = str(_package(tmp_path))
    server._publish(check_robot(robot, {}, server.workspace.position_codec), ticket=1)
    scheduled = []
    monkeypatch.setattr(server, "schedule", lambda path, *a, **k: scheduled.append(path))
    config = tmp_path / "pkg" / "config"
    server.watched([(config / f"c{i}.yaml").as_uri() for i in range(5000)])
    server.watched([(config / "c1.yaml").as_uri()] * 100)
    assert scheduled == [robot, robot], scheduled[:5]


def _traced_steps(call) -> int:
    """How many Python calls, lines and loop turns ``call()`` runs (sys.settrace's events: a
    loop or comprehension over the paths is one event per turn at least)."""
    steps = 0

    def tracer(frame, event, arg):
        nonlocal steps
        steps += 1
        return tracer

    sys.settrace(tracer)
    try:
        call()
    finally:
        sys.settrace(None)
    return steps


def test_a_record_answers_what_it_concerns_without_scanning_every_path(tmp_path):
    """A question costs the same whatever the record holds (a scan of every path it knows, per
    question, made 30,000 questions to a record of 3,000 paths take 20 s): counted in the
    Python steps of 300 questions to a record of 300 paths and to one of 3,000."""
    steps = []
    for size in (300, 3000):
        record = Record()
        with recording(record):
            for i in range(size):
                files.kind_of(tmp_path / "deep" / f"f{i}" / "x.yaml", follow=False)
        assert record.concerns(tmp_path / "deep") and record.concerns(tmp_path)
        assert not record.concerns(tmp_path / "elsewhere" / "y.txt", file=True)
        steps.append(_traced_steps(lambda: [record.concerns(tmp_path / "other" / f"g{i}.txt",
                                                            file=True) for i in range(300)]))
    small, large = steps
    assert large < 1.5 * small, steps  # a scan per question: about 10 times as many


def test_saves_of_files_never_opened_queue_nothing_of_their_own(offline_server,  # noqa: F811
                                                                tmp_path, monkeypatch):
    """``textDocument/didSave`` of 300 robot files not open scheduled 300 checks; the robot
    open waited 54 s behind them. A save of a file not open is a file changed: the robots it
    concerns, one job each."""
    from urdftool.server import check_robot

    server, _ = offline_server
    robot = str(_package(tmp_path))
    server._publish(check_robot(robot, {}, server.workspace.position_codec), ticket=1)
    scheduled = []
    monkeypatch.setattr(server, "schedule", lambda path, *a, **k: scheduled.append(path))
    others = tmp_path / "others"
    others.mkdir()
    for i in range(300):
        (others / f"r{i}.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
        server.saved((others / f"r{i}.urdf").as_uri())
    assert set(scheduled) <= {robot}  # (a new file at the top concerns it: one job, replaced)
    scheduled.clear()
    server.saved((tmp_path / "pkg" / "urdftool.toml").as_uri())  # settings: its robot
    assert scheduled == [robot]


def test_a_flood_parses_each_folders_uri_once_and_stops_when_every_robot_is_concerned(
        offline_server, tmp_path, monkeypatch):  # noqa: F811
    """session 9: 300,000 files changed cost the server's loop 5 s, each URI parsed by pygls
    and each path walked to the root; each folder's URI is now parsed once, a folder's walk
    answered once, and the flood stops looking once every robot checked is concerned."""
    from urdftool import server as module
    from urdftool.server import check_robot

    server, _ = offline_server
    robot = str(_package(tmp_path))
    server._publish(check_robot(robot, {}, server.workspace.position_codec), ticket=1)
    scheduled = []
    monkeypatch.setattr(server, "schedule", lambda path, *a, **k: scheduled.append(path))
    parsed = []
    monkeypatch.setattr(module, "to_fs_path",
                        lambda uri, real=module.to_fs_path: parsed.append(uri) or real(uri))
    asked = []
    record = server.records[robot]
    monkeypatch.setattr(record, "concerns", lambda *a, real=record.concerns: asked.append(a)
                        or real(*a))
    server.watched([(tmp_path / "pkg" / "config" / f"c{i}.yaml").as_uri() for i in range(3000)])
    assert scheduled == [robot] and len(asked) == 1 and len(parsed) == 1
    del scheduled[:], asked[:], parsed[:]
    server.watched([(tmp_path.parent / f"{tmp_path.name}-elsewhere" / f"d{i % 7}" / f"c{i}.yaml").as_uri()
                    for i in range(3000)])
    assert scheduled == [] and len(asked) == 3000 and len(parsed) == 7


@pytest.mark.parametrize("uri", [
    "file:///a/b/c.yaml", "file:///a/b/..", "file:///a/b/.", "file:///a/b%20c/d.yaml",
    "file:///a/b/d%2e%2e", "file:///a/../b/c", "file:///a?x/c.yaml", "file:///a#x/c.yaml",
    "file:///a;p/c.yaml", "file:///C:/x/y.yaml", "file://host/share/x.yaml", "file:///",
    "file:///a/\tb/c.yaml", "file:///a/b\n/c.yaml", " file:///a/c.yaml", "http://x/a/b.yaml",
    "untitled:/a/b.yaml", "file:", "file:///a/b/", "file:///%00/x.yaml", "file:///a/é/x.yaml",
    "file:///a/b/c.yaml\x00", "file:////a//b/c.yaml", "file://", "file:///x/-"])
def test_paths_of_a_flood_are_the_paths_of_each_uri(offline_server, uri):  # noqa: F811
    server, _ = offline_server
    assert list(server.paths_of([uri])) == [server.path_of(uri)]
