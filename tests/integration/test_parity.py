"""Parity with urdfdom's check_urdf (shipped in the pin wheel): every file it rejects, urdftool
rejects too, with at least one located error; `urdftool tree` prints what check_urdf prints."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import CASES, CORPUS, corpus_entry_points
from conftest import CASE_PATHS, case_robot
from urdftool.lint.engine import CheckOptions, check_file

CHECK_URDF = shutil.which("check_urdf", path=str(Path(sys.executable).parent)) or \
    shutil.which("check_urdf")
pytestmark = pytest.mark.skipif(CHECK_URDF is None, reason="check_urdf not installed")


def check_urdf(path: Path) -> subprocess.CompletedProcess:
    return subprocess.run([CHECK_URDF, str(path)], capture_output=True, text=True, timeout=60)


def urdf_for(robot_file: Path, tmp_path: Path) -> Path:
    """The file check_urdf should read: the file itself, or urdftool's expansion of a xacro."""
    if not robot_file.name.endswith(".xacro"):
        return robot_file
    result = check_file(str(robot_file), CheckOptions())
    if result.robot is None:
        pytest.skip("xacro does not expand; urdftool reports that itself")
    expanded = tmp_path / "expanded.urdf"
    expanded.write_text(result.robot.urdf)
    return expanded


def assert_parity(robot_file: Path, urdf: Path, **options):
    reference = check_urdf(urdf)
    result = check_file(str(robot_file), CheckOptions(**options))
    errors = [f for f in result.findings if f.severity.value == "error"]
    if reference.returncode != 0:
        assert errors, f"check_urdf rejects {robot_file.name} but urdftool does not:\n" + \
            reference.stdout + reference.stderr
        assert any(f.line is not None for f in errors), "urdftool's errors are not located"


@pytest.mark.parametrize("case", CASE_PATHS, ids=[p.name for p in CASE_PATHS])
def test_parity_on_case_files(case, tmp_path):
    robot_file = case_robot(case)
    assert_parity(robot_file, urdf_for(robot_file, tmp_path))


CORPUS_URDFS = [path for path, args in corpus_entry_points()
                if not path.endswith(".xacro") and not args]


@pytest.mark.parametrize("relative", CORPUS_URDFS)
def test_parity_on_corpus_urdfs(relative):
    assert_parity(CORPUS / relative, CORPUS / relative)


def _tree_cases():
    plain = [CORPUS / p for p in CORPUS_URDFS]
    return [p for p in plain if p.exists()] + sorted(CASES.glob("U*.urdf"))


@pytest.mark.parametrize("path", _tree_cases(), ids=lambda p: p.name)
def test_tree_matches_check_urdf(path, run_cli):
    reference = check_urdf(path)
    if reference.returncode != 0:
        pytest.skip("check_urdf rejects the file")
    if check_file(str(path), CheckOptions()).robot is None:
        pytest.skip("urdftool refuses to load it (e.g. entity declarations, U009)")
    result = run_cli("tree", path)
    assert result.exit_code == 0, result.output
    assert result.stdout == reference.stdout
