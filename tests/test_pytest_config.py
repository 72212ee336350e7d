"""``make test`` (pytest with the project's settings) says which tests it skipped and why."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def test_the_summary_lists_skipped_tests_with_their_reasons(tmp_path):
    (tmp_path / "test_skips.py").write_text(
        "import pytest\n\n"
        "def test_runs():\n    pass\n\n"
        "def test_needs_a_tool():\n    pytest.skip('Graphviz dot is not installed')\n")
    done = subprocess.run(
        [sys.executable, "-m", "pytest", "-c", str(ROOT / "pyproject.toml"), "--rootdir",
         str(tmp_path), "-p", "no:cacheprovider", "-p", "no:xdist", "-p", "no:urdftool",
         str(tmp_path / "test_skips.py")],
        capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "SKIPPED [1] test_skips.py:7: Graphviz dot is not installed" in done.stdout, \
        done.stdout


def test_the_tests_of_one_case_file_are_scheduled_together():
    """``make test``'s scheduler gives every test of one case file (tests/lint/test_cases.py's
    and tests/integration/test_parity.py's) to one worker, which checks the case once; other
    tests keep their own scope, the corpus's its group."""
    from conftest import CASE_PATHS, case_group, in_corpus_group

    case = CASE_PATHS[0].name
    assert case_group(f"tests/lint/test_cases.py::test_case_findings_match_marks[{case}]") \
        == case_group(f"tests/integration/test_parity.py::test_parity_on_case_files[{case}]") \
        == f"case:{case}"
    assert case_group(f"tests/lint/test_cases.py::test_case_findings_match_marks[{case}x]") is None
    assert case_group("tests/lint/test_cases.py::test_every_rule_has_a_case") is None
    assert in_corpus_group("tests/integration/test_corpus_xacro.py::test_x[a]")
