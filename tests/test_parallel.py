"""Worker processes: a time budget per file, stable order, crashes become findings."""

from __future__ import annotations

import pytest

from urdftool.engine import CheckOptions
from urdftool.parallel import check_files

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

    from urdftool import parallel

    real = parallel.check_file

    def die_on_second(path, options):
        if path == robots[1]:
            os._exit(3)
        return real(path, options)

    monkeypatch.setattr(parallel, "check_file", die_on_second)
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
