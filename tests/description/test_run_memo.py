"""One view of the file system per run (urdftool/description/run_memo.py)."""

from __future__ import annotations

from urdftool.description.packages import repository_root
from urdftool.description.run_memo import one_run, per_run


def test_answers_are_remembered_only_inside_a_run():
    calls = []

    @per_run
    def answer(x):
        calls.append(x)
        return x * 2

    assert answer(2) == answer(2) == 4 and calls == [2, 2]  # outside: asked every time
    with one_run():
        assert answer(2) == answer(2) == 4
        with one_run():  # nested: the outer run's memory
            assert answer(2) == 4
        assert answer(3) == 6
    assert calls == [2, 2, 2, 3]
    answer(2)
    assert calls == [2, 2, 2, 3, 2]  # the run ended: forgotten


def test_a_repository_made_between_runs_is_seen(tmp_path):
    folder = tmp_path / "robot"
    folder.mkdir()
    with one_run():
        before = repository_root(folder)
        (tmp_path / ".git").mkdir()
        assert repository_root(folder) == before  # one view per run
    assert repository_root(folder) == tmp_path


def test_settings_changed_between_two_checks_apply_to_the_second(tmp_path, monkeypatch):
    from urdftool.lint.runner import check_paths

    robot = tmp_path / "bot.urdf"
    robot.write_text('<robot name="b"><link name="a"/><link name="b"/><joint name="j" '
                     'type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>'
                     '<limit lower="1" upper="-1" effort="1" velocity="1"/></joint></robot>')
    (tmp_path / ".git").mkdir()
    first = check_paths([str(robot)])
    assert "U204" in {f.code for f in first.results[0].findings}
    (tmp_path / "urdftool.toml").write_text('ignore = ["U204"]\n')
    second = check_paths([str(robot)])
    assert "U204" not in {f.code for f in second.results[0].findings}


def test_companion_folders_are_listed_once_per_run(tmp_path, monkeypatch):
    from urdftool.description import companions

    for name in ("a", "b"):
        (tmp_path / f"{name}.urdf").write_text("<robot name='x'/>")
    listed = []
    original = companions._robot_files.__wrapped__

    def counting(folder):
        listed.append(folder)
        return original(folder)

    monkeypatch.setattr(companions, "_robot_files", companions.per_run(counting))
    with one_run():
        assert companions._robots_beside(tmp_path / "a.urdf") == [tmp_path / "b.urdf"]
        assert companions._robots_beside(tmp_path / "b.urdf") == [tmp_path / "a.urdf"]
    assert listed == [tmp_path]
