"""One case per rule: each case marks the lines where a finding is expected with ``expect: CODE``
(inside an XML comment, or a YAML/TOML comment; ``expect: CODE at FILE:LINE`` where the line
itself cannot hold a comment, as inside a tag or in an empty file), and the set of (file, line, code) found must
equal the set marked.

A mark may say the severity too (``expect: U604 warning``: a finding that holds only in some
configurations is reported below its rule's severity, docs/certainty.md); then it must be so.

A case is a file ``tests/cases/<CODE>_<slug>.urdf`` (or ``.urdf.xacro``), or a folder
``tests/cases/<CODE>_<slug>/`` whose robot is the one ``.urdf``/``.urdf.xacro`` file in it and whose
other files (included xacro, controller YAML, SRDF, spec) are companions found beside it.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from conftest import CASE_PATHS, case_result, case_targets, expected_marks, expected_severities
from urdftool.lint.rules import CATALOGUE

@pytest.mark.parametrize("case", CASE_PATHS, ids=[p.name for p in CASE_PATHS])
def test_case_findings_match_marks(case):
    result = case_result(case, case_targets(case))
    found = {(Path(f.file).name, f.line, f.code) for f in result.findings}
    assert found == expected_marks(case), "\n".join(
        f"{f.location}: {f.code} {f.message}" for f in result.findings)
    severities = {(Path(f.file).name, f.line, f.code): f.severity.value for f in result.findings}
    for mark, severity in expected_severities(case).items():
        assert severities[mark] == severity, f"{mark}: {severities[mark]}, marked {severity}"
    for finding in result.findings:
        _carries_its_parts(finding)


# the words of the parts a report says once (Finding.repeated): errors.available's list, the
# "looked in" of errors.PackageNotFound
_PARTS = {"available": re.compile(r"\bavailable [a-z ]+: "), "searched": re.compile("; looked in: ")}


def _carries_its_parts(finding):
    """A finding whose message holds a part other findings repeat carries it as a field
    (``Finding.repeated``): a wrapper rebuilding a message (a condition before it, a clause
    after) with an f-string or a str method dropped it silently, and the text report wrote the
    list in full at every finding. errors.Said refuses f-strings; this finds the rest (a
    ``join``, a ``replace``, a ``%`` of a tuple)."""
    for kind, words in _PARTS.items():
        if words.search(finding.message):
            assert any(part[0] == kind and part[1] in finding.message
                       for part in finding.repeated), \
                f"{finding.location}: {finding.code} says a part of kind {kind!r} it does not " \
                f"carry (Finding.repeated: {finding.repeated}): {finding.message}"


def test_every_case_marks_its_own_code():
    for case in CASE_PATHS:
        code = case.name[:4]
        assert code in {c for _, _, c in expected_marks(case)}, f"{case.name} never marks {code}"


def test_every_rule_has_a_case():
    covered = {p.name[:4] for p in CASE_PATHS}
    missing = [r.code for r in CATALOGUE if r.code not in covered and r.code not in NO_CASE]
    assert not missing, f"rules without a case file in tests/cases: {missing}"


# Codes that cannot be provoked by a file on disk (documented why).
NO_CASE = {
    "U900",  # internal-error: needs a crashing rule; tested in test_engine.py
    "U008",  # file-too-large: would need a 16 MiB fixture; tested in test_loader.py
    "U014",  # file-outside-root-refused: needs --no-env; tested in test_xacro_sandbox.py
    "U015",  # timeout: needs a file slower than the budget; tested in tests/lint/test_runner.py
    "U018",  # out-of-memory: needs a memory budget; tested in test_budgets.py
    "U902",  # analysis-unavailable: needs a lint-only install; tested in test_engine.py
}
