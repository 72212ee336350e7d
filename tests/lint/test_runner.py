"""The linter's entry points: files checked in worker processes within budgets, in stable order,
crashes and budgets become findings; check_paths and Run."""

from __future__ import annotations

import pytest

from urdftool.lint.engine import CheckOptions
from urdftool.lint.runner import check_files

pytestmark = pytest.mark.worker  # budgets and deaths: run_cli's commands in the forked worker

GOOD = '<robot name="r"><link name="a"/></robot>\n'
BAD = '<robot name="r"><link name="a"></robot>\n'
# Slow but legal arithmetic: the sandbox lets it through, only the budget stops it.
SLOW = ('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        + '<link name="${python.len(python.sorted(python.map(str, python.range(10**6))))}"/>' * 40
        + '</robot>\n')


@pytest.fixture
def robots(tmp_path):
    files = []
    for index, text in enumerate([GOOD, BAD, GOOD, BAD, GOOD]):
        path = tmp_path / f"r{index}.urdf"
        path.write_text(text)
        files.append(str(path))
    return files


def _codes(results):
    return [sorted({f.code for f in r.findings}) for r in results]


def test_results_come_back_in_the_order_given(robots):
    results = check_files(robots, lambda p: CheckOptions(), jobs=3, timeout=30)
    assert [r.path for r in results] == robots
    assert _codes(results) == [[], ["U001"], [], ["U001"], []]


def test_same_findings_in_process_and_in_workers(robots):
    in_process = check_files(robots, lambda p: CheckOptions(), jobs=1, timeout=None)
    workers = check_files(robots, lambda p: CheckOptions(), jobs=2, timeout=30)
    assert [r.findings for r in in_process] == [r.findings for r in workers]


def test_a_file_over_the_budget_gets_a_finding_and_the_run_goes_on(tmp_path, robots):
    slow = tmp_path / "slow.urdf.xacro"
    slow.write_text(SLOW)
    files = [robots[0], str(slow), robots[1]]
    results = check_files(files, lambda p: CheckOptions(), jobs=1, timeout=0.5)
    assert _codes(results) == [[], ["U015"], ["U001"]]
    assert results[1].findings[0].file.endswith("slow.urdf.xacro")


def test_a_dying_worker_becomes_an_internal_error(robots, monkeypatch):
    import os

    from urdftool.lint import engine

    real = engine.load_and_check

    def die_on_second(path, options, data=None):
        if path == robots[1]:
            os._exit(3)
        return real(path, options, data)

    monkeypatch.setattr(engine, "load_and_check", die_on_second)
    results = check_files(robots, lambda p: CheckOptions(), jobs=2, timeout=30)
    assert _codes(results) == [[], ["U900"], [], ["U001"], []]
    assert "exit code 3" in results[1].findings[0].message


def test_cli_timeout_and_jobs(run_cli, tmp_path, robots):
    slow = tmp_path / "slow.urdf.xacro"
    slow.write_text(SLOW)
    result = run_cli("check", "--timeout", "0.5", "--jobs", "2", robots[0], slow)
    assert result.exit_code == 1
    assert "U015" in result.output and "slow.urdf.xacro" in result.output


def test_negative_jobs_is_a_usage_error(run_cli, robots):
    assert run_cli("check", "--jobs", "-1", robots[0]).exit_code == 2


def test_a_memory_error_in_a_worker_is_located_where_the_work_was(monkeypatch, tmp_path):
    from urdftool import budget
    from urdftool.lint import engine
    from urdftool.diagnostics import Location

    files = []
    for name in ("a.urdf", "b.urdf", "c.urdf"):
        (tmp_path / name).write_text(GOOD)
        files.append(str(tmp_path / name))
    real = engine.load_and_check

    def hungry_b(path, options, data=None):
        if path.endswith("b.urdf"):
            budget.working_at(Location("b.urdf", 7, (Location("top.xacro", 2),)))
            raise MemoryError
        return real(path, options, data)

    monkeypatch.setattr(engine, "load_and_check", hungry_b)
    for jobs, timeout, memory in ((1, 30, 2 * 1024 ** 3), (1, None, None)):  # worker, here
        results = check_files(files, lambda p: CheckOptions(), jobs=jobs, timeout=timeout,
                              memory=memory)
        assert [[f.code for f in r.findings] for r in results] == [[], ["U018"], []]
        finding = results[1].findings[0]
        assert (finding.file, finding.line, finding.location.via) == (
            "b.urdf", 7, (Location("top.xacro", 2),))


def test_check_paths_keeps_the_order_across_memory_budgets(tmp_path):
    """Files whose settings give different max-memory go to different pools; the results still
    come in the order of the targets."""
    from urdftool.lint.runner import check_paths

    for name, memory in (("a", '"1G"'), ("b", None), ("c", '"1500M"')):
        (tmp_path / name).mkdir()
        (tmp_path / name / "r.urdf").write_text(BAD if name == "b" else GOOD)
        if memory:
            (tmp_path / name / "urdftool.toml").write_text(f"max-memory = {memory}\n")
    run = check_paths([tmp_path / "a", tmp_path / "b", tmp_path / "c"], jobs=2)
    assert [r.path.split("/")[-2] for r in run.results] == ["a", "b", "c"]
    assert _codes(run.results) == [[], ["U001"], []] and run.exit_code == 1


def test_run_exit_code_is_strict_per_file():
    from urdftool.diagnostics import Finding, Location, Severity
    from urdftool.lint.engine import FileResult
    from urdftool.lint.runner import Run

    warning = FileResult("w.urdf", [Finding("U206", "n", Severity.WARNING, "m", Location("w"))])
    error = FileResult("e.urdf", [Finding("U204", "n", Severity.ERROR, "m", Location("e"))])
    clean = FileResult("c.urdf", [])
    assert Run([warning, clean], strict=[False, True]).exit_code == 0
    assert Run([warning, clean], strict=[True, False]).exit_code == 1
    assert Run([clean, error], strict=[False, False]).exit_code == 1
    assert Run([]).exit_code == 0


@pytest.mark.parametrize("declared", [True, False])
def test_a_robot_not_expanded_for_a_package_not_installed_is_no_pass_nor_error(
        run_cli, tmp_path, declared):
    """A package this machine lacks (a MoveIt configuration whose robot is another
    repository's): U006 is the environment's, a note when the package.xml declares it (install
    the dependencies: the workspace's question; it was a warning) and a warning when not
    (declare it, fresh12b's ergoCub); the robot's defects are not known, and the run that could
    not check it exits 2 either way, saying so, in every format, --exit-zero too."""
    (tmp_path / ".git").mkdir()
    depend = "<exec_depend>mount_description</exec_depend>" if declared else ""
    (tmp_path / "package.xml").write_text(
        f'<package format="2"><name>bot_description</name>{depend}</package>')
    robot = tmp_path / "bot.urdf.xacro"
    robot.write_text(
        '<robot name="b" xmlns:xacro="http://www.ros.org/wiki/xacro">\n<link name="a"/>\n'
        '  <xacro:include filename="$(find mount_description)/urdf/mount.xacro"/>\n</robot>\n')
    for extra in ([], ["-f", "json"], ["-f", "sarif"], ["--exit-zero"]):
        result = run_cli("check", "--no-cache", str(robot), *extra)
        said = ("1 file not checked: a package it needs is not installed here, so its robot "
                "was not expanded")
        assert result.exit_code == 2 and said in result.output, result.output
        # about the robot and this machine, not urdftool's own failure
        assert "urdftool: error" not in result.output, result.output
        # an undeclared package is none rosdep installs (doosan-robot2's misspelt name)
        assert ("rosdep installs only what a package.xml declares" in result.output) is \
            (not declared), result.output
        if not extra:  # the summary line does not call it checked
            assert "0 files checked, 1 not (a package it needs is not installed)" \
                in result.stdout, result.stdout
    from urdftool.lint.runner import check_paths

    run = check_paths(robot)
    [finding] = run.results[0].findings
    assert (finding.code, finding.severity.value) == (
        "U006", "info" if declared else "warning")
    assert ("declares it as a dependency" in finding.message) is declared
    assert ("does not declare it, so rosdep would not install it" in finding.message) \
        is not declared
    assert run.unexpanded == [str(robot)]
