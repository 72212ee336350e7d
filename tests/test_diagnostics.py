"""Findings and their order (urdftool/diagnostics.py)."""

from __future__ import annotations

from urdftool.diagnostics import Finding, Location, Severity


def test_findings_that_differ_only_in_their_call_site_sort_the_same_in_every_order():
    def at(site_line):
        return Finding("U022", "x", Severity.INFO, "same", Location(
            "arm.xacro", 7, (Location("robot.urdf.xacro", site_line),), column=3))

    findings = [at(9), at(4), at(12)]
    assert [f.location.via[0].line for f in sorted(findings, key=Finding.sort_key)] == [4, 9, 12]
    assert sorted(reversed(findings), key=Finding.sort_key) == \
        sorted(findings, key=Finding.sort_key)
