"""``pytest --urdftool`` collects robots as items and fails them with located findings; the
``urdftool_check`` fixture does the same for a team's own tests."""

from __future__ import annotations

import shutil

import pytest

from conftest import ROBOTS

pytest_plugins = ["pytester"]

BROKEN = """<robot name="broken"><link name="a"/><link name="b"/>
<joint name="elbow" type="revolute"><parent link="a"/><child link="b"/>
<limit lower="1" upper="-1" effort="1" velocity="1"/></joint></robot>
"""


@pytest.fixture
def project(pytester):
    shutil.copytree(ROBOTS / "humanoid", pytester.path / "robots" / "humanoid")
    (pytester.path / "robots" / "broken.urdf").write_text(BROKEN)
    return pytester


def test_robots_become_items_and_a_broken_one_fails_with_its_findings(project):
    result = project.runpytest_inprocess("--urdftool", "robots", "-p", "no:cacheprovider",
                                         "-p", "no:xdist")
    result.assert_outcomes(passed=1, failed=1)  # humanoid.urdf.xacro and broken.urdf only
    text = result.stdout.str()
    assert "robots/broken.urdf:3: error U204" in text
    result.stdout.fnmatch_lines(["FAILED robots/broken.urdf::urdftool - robots/broken.urdf:3: "
                                 "error U204*"])


def test_robot_files_that_are_no_regular_file_fail_as_check_reports_them(project):
    """A named pipe, a link loop and links to devices named as robots: ``urdftool check``
    reports each (U001, U017, exit 1), pytest's walk never handed them to the plugin, and
    ``pytest --urdftool`` passed (or collected nothing)."""
    import os

    robots = project.path / "robots"
    os.mkfifo(robots / "pipe.urdf")
    (robots / "loop.urdf").symlink_to("loop.urdf")
    (robots / "zero.urdf").symlink_to("/dev/zero")
    (robots / "humanoid" / "null.urdf").symlink_to("/dev/null")
    result = project.runpytest_inprocess("--urdftool", "robots", "-p", "no:cacheprovider",
                                         "-p", "no:xdist")
    result.assert_outcomes(passed=1, failed=5)
    result.stdout.fnmatch_lines_random([
        "FAILED robots/pipe.urdf::urdftool - robots/pipe.urdf: error U001*",
        "FAILED robots/loop.urdf::urdftool - robots/loop.urdf: error*",
        "FAILED robots/zero.urdf::urdftool - robots/zero.urdf: error*",
        "FAILED robots/humanoid/null.urdf::urdftool - robots/humanoid/null.urdf: error*"])
    assert "robots/zero.urdf: error U017 is a symbolic link leading outside" in \
        result.stdout.str()
    alone = project.runpytest_inprocess("robots", "-p", "no:cacheprovider", "-p", "no:xdist")
    alone.assert_outcomes()  # without --urdftool: nothing of ours


def test_the_session_s_robots_are_checked_in_one_run(project, monkeypatch):
    """As ``urdftool check FILE...``: one check of every robot item (a check per item asked
    the repository, packages and launch files again each time: 20 -> 7 s CPU for the 10
    robots of universal_robot's ur_description); each item still fails with its own file's
    findings, and a deselected robot is not checked."""
    import importlib

    # the module the plugin's import finds (sys.modules), not the package's attribute: a test
    # run before this one in the process may have imported the module anew
    runner = importlib.import_module("urdftool.lint.runner")
    calls = []
    real = runner.check_paths

    def counted(paths, *args, **options):
        calls.append(sorted(str(path).rsplit("/", 1)[-1] for path in paths))
        return real(paths, *args, **options)

    monkeypatch.setattr(runner, "check_paths", counted)
    (project.path / "robots" / "fine.urdf").write_text(BROKEN.replace('lower="1" upper="-1"',
                                                                      'lower="-1" upper="1"'))
    result = project.runpytest_inprocess("--urdftool", "robots", "-p", "no:cacheprovider",
                                         "-p", "no:xdist")
    result.assert_outcomes(passed=2, failed=1)
    assert calls == [["broken.urdf", "fine.urdf", "humanoid.urdf.xacro"]]
    result.stdout.fnmatch_lines(["FAILED robots/broken.urdf::urdftool - robots/broken.urdf:3: "
                                 "error U204*"])
    calls.clear()
    result = project.runpytest_inprocess("--urdftool", "robots", "-k", "fine", "-p",
                                         "no:cacheprovider", "-p", "no:xdist")
    result.assert_outcomes(passed=1)
    assert calls == [["fine.urdf"]]


def test_macro_libraries_are_not_items(project):
    result = project.runpytest_inprocess("--urdftool", "robots", "--collect-only", "-q",
                                         "-p", "no:cacheprovider", "-p", "no:xdist")
    collected = [line for line in result.stdout.lines if "::urdftool" in line]
    assert sorted(collected) == ["robots/broken.urdf::urdftool",
                                 "robots/humanoid/humanoid.urdf.xacro::urdftool"]


def test_robot_files_of_which_none_is_a_robot_are_no_pass(project):
    # session 20: a robot whose root link was deleted (a part nobody includes) passed `pytest
    # --urdftool` with the other tests, never collected, where `urdftool check` says "nothing
    # checked" (exit 2, session 7's class); and macro libraries alone the same
    (project.path / "robots" / "broken.urdf").write_text(BROKEN.replace('<link name="a"/>', ""))
    shutil.rmtree(project.path / "robots" / "humanoid")
    project.makepyfile(test_other="def test_other():\n    pass\n")
    for args in (("robots", "test_other.py"), ("robots", "-k", "other")):
        result = project.runpytest_inprocess("--urdftool", *args, "-p", "no:cacheprovider",
                                             "-p", "no:xdist")
        assert result.ret == pytest.ExitCode.USAGE_ERROR
        assert "urdftool: nothing checked: " in result.stderr.str()
        assert "broken.urdf: a part of a robot defined elsewhere" in result.stderr.str()
    # a robot beside them is checked; they are left out, as check leaves them
    shutil.copytree(ROBOTS / "humanoid", project.path / "robots" / "humanoid")
    result = project.runpytest_inprocess("--urdftool", "robots", "-k", "other", "-p",
                                         "no:cacheprovider", "-p", "no:xdist")
    assert result.ret == pytest.ExitCode.NO_TESTS_COLLECTED  # (humanoid's item deselected)


def test_settings_apply_to_items(project):
    (project.path / "urdftool.toml").write_text('ignore = ["U204"]\n')
    result = project.runpytest_inprocess("--urdftool", "robots", "-p", "no:cacheprovider",
                                         "-p", "no:xdist")
    result.assert_outcomes(passed=2)


def test_a_settings_file_another_user_owns_is_said_by_the_items_and_the_fixture(project, monkeypatch):
    """The check says it did not read another user's settings file outside a repository
    (lint.settings.foreign); the plugin, which runs the same check, said nothing: a warning of
    the test that ran the check, in pytest's summary."""
    from conftest import another_users

    (project.path / "urdftool.toml").write_text('ignore = ["U204"]\n')
    another_users(project.path / "urdftool.toml", monkeypatch)
    project.makepyfile(test_own="def test_own(urdftool_check):\n"
                                "    urdftool_check('robots/humanoid')\n")
    result = project.runpytest_inprocess("--urdftool", "robots", "test_own.py", "-p",
                                         "no:cacheprovider", "-p", "no:xdist")
    result.assert_outcomes(passed=2, failed=1)  # U204 of broken.urdf not ignored
    result.stdout.fnmatch_lines(["*UrdftoolWarning: urdftool: settings file '*urdftool.toml' "
                                 "not read: it belongs to another user*"])
    assert result.stdout.str().count("UrdftoolWarning: urdftool: settings file") == 2  # (the
    # items' check and the fixture's)


def test_a_settings_file_that_stops_every_item_fails_each_in_one_line(project):
    """Broken settings above every robot: ``check`` refuses the run (exit 2, one line); each
    item failed with a traceback of urdftool's runner ending in the SettingsError."""
    (project.path / "urdftool.toml").write_text("strict = 1979-05-27\n")
    result = project.runpytest_inprocess("--urdftool", "robots", "-p", "no:cacheprovider",
                                         "-p", "no:xdist")
    result.assert_outcomes(failed=2)
    text = result.stdout.str()
    assert "Traceback" not in text and "runner.py" not in text and "raise SettingsError" not in text
    result.stdout.fnmatch_lines(["urdftool: error: *urdftool.toml: 'strict' must be true or false*",
                                 "FAILED robots/broken.urdf::urdftool - urdftool: error: *"])


def test_the_fixture_fails_a_refused_check_in_one_line_and_no_path_is_no_pass(project):
    """``urdftool_check(*glob("urdf/*.urdf"))`` of a glob that matched nothing passed (an empty
    run, exit 0); a path that does not exist failed with a traceback of urdftool's runner
    ending in TargetError, where an item says the command line's one line."""
    project.makepyfile(test_robots="""
        def test_none(urdftool_check):
            urdftool_check()

        def test_missing(urdftool_check):
            urdftool_check("robots/nope.urdf")
        """)
    outcome = project.runpytest_inprocess("test_robots.py", "-p", "no:cacheprovider",
                                          "-p", "no:xdist")
    said = [line for line in outcome.stdout.lines if line.startswith("urdftool: error: ")]
    assert said == ["urdftool: error: nothing checked: no path given",
                    "urdftool: error: path 'robots/nope.urdf' does not exist"]
    assert outcome.ret == pytest.ExitCode.TESTS_FAILED and not any(
        word in outcome.stdout.str() for word in ("Traceback", "targets.py", "another exception"))


def test_the_fixture_fails_an_option_it_does_not_take_in_one_line(project):
    """``urdftool_check("robots", strictt=True)`` or ``strict="yes"``: a traceback of
    CheckRequest's "unexpected keyword argument", or strict; now the one guard's one line."""
    project.makepyfile(test_robots="""
        def test_misspelt(urdftool_check):
            urdftool_check("robots", strictt=True)

        def test_not_a_flag(urdftool_check):
            urdftool_check("robots", strict="yes")
        """)
    outcome = project.runpytest_inprocess("test_robots.py", "-p", "no:cacheprovider",
                                          "-p", "no:xdist")
    said = [line for line in outcome.stdout.lines if line.startswith("urdftool: error: ")]
    assert [line.split(";")[0] for line in said] == [
        "urdftool: error: no option 'strictt'", 'urdftool: error: strict must be True or False, '
        'not "yes"']
    assert outcome.ret == pytest.ExitCode.TESTS_FAILED and "Traceback" not in outcome.stdout.str()


def test_without_the_option_nothing_is_collected(project):
    result = project.runpytest_inprocess("robots", "-p", "no:cacheprovider", "-p", "no:xdist")
    assert result.ret == pytest.ExitCode.NO_TESTS_COLLECTED


def test_the_fixture_fails_a_test_with_the_findings(project):
    project.makepyfile(test_robots="""
        def test_clean(urdftool_check):
            run = urdftool_check("robots/humanoid")
            assert run.exit_code == 0

        def test_broken(urdftool_check):
            urdftool_check("robots/broken.urdf")
        """)
    result = project.runpytest_inprocess("test_robots.py", "-p", "no:cacheprovider",
                                         "-p", "no:xdist")
    result.assert_outcomes(passed=1, failed=1)
    result.stdout.fnmatch_lines(["*robots/broken.urdf:3: error U204*"])


def test_the_plugin_is_registered_for_pytest():
    from importlib.metadata import entry_points

    assert {e.value for e in entry_points(group="pytest11") if e.name == "urdftool"} == \
        {"urdftool.pytest_plugin"}


def test_the_fixture_fails_with_broken_settings_that_stop_some_files(tmp_path):
    """A settings file that is broken stops only the files it applies to (issue 29, class 2):
    the run checks the others and the fixture fails, saying why."""
    import pytest as _pytest

    from urdftool.pytest_plugin import _check, _text

    for folder in ("a", "b"):
        (tmp_path / folder).mkdir()
        (tmp_path / folder / "r.urdf").write_text('<robot name="r"><link name="x"/></robot>')
    (tmp_path / "b" / "urdftool.toml").write_text("bogus = 1\n")
    run = _check([str(tmp_path / "a"), str(tmp_path / "b")])
    assert run.exit_code == 2 and len(run.results) == 1
    assert "unknown urdftool setting(s) bogus" in _text(run)
    from urdftool.errors import SettingsError

    with _pytest.raises(SettingsError):  # nothing could be checked
        _check([str(tmp_path / "b")])


def test_a_crash_while_collecting_is_an_item_of_its_own_at_the_file_read(project, monkeypatch):
    """A reader's crash while the plugin finds the robots (U900, urdftool's internal error)
    was kept until a robot item's check said it: no item said it (the session's check had no
    item for the file read), or the first robot failed with another file's crash. It is an
    item of its own at the file being read, failing with the U900 as ``urdftool check`` says
    it; the robots pass or fail on their own findings."""
    import importlib

    targets = importlib.import_module("urdftool.lint.targets")
    answer = targets._top_level_answer

    def crashing(data):
        if b"crash" in data:
            raise RuntimeError("boom")
        return answer(data)

    (project.path / ".git").mkdir()
    (project.path / "other").mkdir()
    (project.path / "other" / "crash.urdf").write_text(BROKEN.replace("broken", "crash"))
    monkeypatch.setattr(targets, "_top_level_answer", crashing)
    result = project.runpytest_inprocess("--urdftool", "robots", "other", "-p",
                                         "no:cacheprovider", "-p", "no:xdist")
    result.assert_outcomes(passed=1, failed=2)  # humanoid; broken.urdf, the crash once
    result.stdout.fnmatch_lines_random([
        "FAILED robots/broken.urdf::urdftool - robots/broken.urdf:3: error U204*",
        "FAILED other/crash.urdf::urdftool - other/crash.urdf: error U900*"])
    text = result.stdout.str()
    assert "other/crash.urdf: error U900 finding the robots to check crashed: RuntimeError: " \
        "boom" in text
    broken = text.split("urdftool check broken.urdf")[1].split("\n_")[0]
    assert "U900" not in broken, text  # (its own findings only)
    assert "robots/humanoid/humanoid.urdf.xacro ." in text
