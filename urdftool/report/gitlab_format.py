"""``--format gitlab``: GitLab Code Quality, a JSON array of issues shown in merge requests.

Each issue's ``fingerprint`` identifies it across pipelines, so GitLab can tell new findings
from fixed ones: it hashes the file, the code, the message and the finding's rank among the
identical ones in that file, never the line (an unrelated edit above it would turn every
finding below into a new one).
"""

from __future__ import annotations

import hashlib

from urdftool.report.json_output import line, write_json
from urdftool.report.summary import all_findings

# https://docs.gitlab.com/ci/testing/code_quality/#code-quality-report-format
_SEVERITIES = {"error": "major", "warning": "minor", "info": "info"}


def as_list(results) -> list[dict]:
    issues, seen = [], {}
    for finding in all_findings(results):
        identity = (finding.file, finding.code, finding.message)
        seen[identity] = seen.get(identity, -1) + 1
        fingerprint = hashlib.sha256(
            line([*identity, seen[identity]]).encode()).hexdigest()
        issues.append({
            "description": f"{finding.code} {finding.message}",
            "check_name": _check_name(finding),
            "fingerprint": fingerprint,
            "severity": _SEVERITIES[finding.severity.value],
            "location": {"path": finding.file, "lines": {"begin": finding.line or 1}},
            **({"target": finding.target} if finding.target is not None else {}),
        })
    return issues


def _check_name(finding) -> str:
    """The rule, and for a portability finding its target: ``U921 mujoco-mesh-format
    (mujoco)``."""
    name = f"{finding.code} {finding.name}"
    return name if finding.target is None else f"{name} ({finding.target})"


def render(results, stream) -> None:
    write_json(as_list(results), stream)
