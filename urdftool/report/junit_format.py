"""``--format junit``: one test suite per file, one test case per finding.

Valid against the Jenkins xunit plugin's ``junit-10.xsd``, the strictest of the JUnit dialects
CI services read: a ``<testcase>`` carries only a name and a class name (the file and line are
in the failure's message), and the file goes on its ``<testsuite>``. A finding fails its test
case only when it fails the check (an error, or a warning under ``strict``), so a run that exits
0 reports no failure; the other findings pass, their text in ``<system-out>``.
"""

from __future__ import annotations

from lxml import etree

from urdftool.diagnostics import display_path
from urdftool.report.escape import write_xml, xml
from urdftool.report.summary import via_text


def render(results, stream) -> None:
    """Every text is passed through :func:`~urdftool.report.escape.xml`: XML 1.0 cannot hold
    most control characters (lxml refuses them), CI pages show the message attribute as a line
    and the failure's text line by line (each line of ours stays one line)."""
    suites = etree.Element("testsuites", name="urdftool", tests=str(_tests(results)),
                           failures=str(sum(len(r.failures) for r in results)), errors="0")
    for result in results:
        shown = xml(display_path(result.path))
        failing = {id(finding) for finding in result.failures}
        suite = etree.SubElement(suites, "testsuite", name=shown,
                                 tests=str(max(1, len(result.findings))),
                                 failures=str(len(failing)), errors="0", skipped="0", file=shown)
        if not result.findings:
            etree.SubElement(suite, "testcase", name="urdftool check", classname=shown)
        for finding in result.findings:
            # junit-10.xsd gives a test case no properties: the target is in its name
            target = f" ({finding.target})" if finding.target is not None else ""
            case = etree.SubElement(suite, "testcase",
                                    name=xml(f"{finding.code} {finding.name}{target}"),
                                    classname=shown)
            text = "\n".join(map(xml, [f"{finding.location}: {finding.severity.value} "
                                       f"{finding.code} {finding.message}",
                                       *via_text(finding.location)]))
            if id(finding) in failing:
                failure = etree.SubElement(case, "failure", type=finding.severity.value,
                                           message=xml(f"{finding.location}: {finding.message}"))
                failure.text = text
            else:
                etree.SubElement(case, "system-out").text = text
    write_xml(stream, etree.tostring(suites, pretty_print=True, xml_declaration=True,
                                     encoding="UTF-8").decode())


def _tests(results) -> int:
    return sum(max(1, len(r.findings)) for r in results)
