"""``--format junit``: one test suite per file, one failing test case per finding."""

from __future__ import annotations

from lxml import etree

from urdftool.diagnostics import display_path
from urdftool.report.summary import printable


def render(results, stream) -> None:
    """Every text is passed through :func:`printable`: XML 1.0 cannot hold most control
    characters (lxml refuses them), and CI pages show the message attribute as a line."""
    suites = etree.Element("testsuites", name="urdftool", tests=str(_tests(results)),
                           failures=str(sum(len(r.findings) for r in results)))
    for result in results:
        shown = printable(display_path(result.path))
        suite = etree.SubElement(suites, "testsuite", name=shown,
                                 tests=str(max(1, len(result.findings))),
                                 failures=str(len(result.findings)), errors="0", skipped="0")
        if not result.findings:
            etree.SubElement(suite, "testcase", name="urdftool check", classname=shown)
        for finding in result.findings:
            file, message = printable(finding.file), printable(finding.message)
            case = etree.SubElement(suite, "testcase", name=f"{finding.code} {finding.name}",
                                    classname=file, file=file)
            if finding.line is not None:
                case.set("line", str(finding.line))
            failure = etree.SubElement(case, "failure", message=message,
                                       type=finding.severity.value)
            failure.text = printable(f"{finding.location}: {finding.code} {finding.message}")
    stream.write(etree.tostring(suites, pretty_print=True, xml_declaration=True,
                                encoding="UTF-8").decode())


def _tests(results) -> int:
    return sum(max(1, len(r.findings)) for r in results)
