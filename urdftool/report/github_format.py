"""``--format github``: GitHub Actions workflow commands, shown as annotations on the diff."""

from __future__ import annotations

from urdftool.report.summary import Summary, all_findings, counted, printable, via_text

_LEVELS = {"error": "error", "warning": "warning", "info": "notice"}


def _escape_data(text: str) -> str:
    """Workflow-command data: a line break is %0A (the message goes on in the annotation, it
    cannot start a command), every other control character is written as an escape."""
    return printable(text, keep="\r\n").replace("%", "%25").replace("\r", "%0D") \
        .replace("\n", "%0A")


def _escape_property(text: str) -> str:
    return _escape_data(text).replace(":", "%3A").replace(",", "%2C")


def render(results, stream) -> None:
    for finding in all_findings(results):
        properties = [f"file={_escape_property(finding.file)}"]
        if finding.line is not None:
            properties.append(f"line={finding.line}")
            if finding.column is not None:
                properties.append(f"col={finding.column}")
        title = f"{finding.code} {finding.name}" + (f" ({finding.target})" if finding.target
                                                    else "")
        properties.append(f"title={_escape_property(title)}")
        message = "\n".join([finding.message, *via_text(finding.location)])
        stream.write(f"::{_LEVELS[finding.severity.value]} {','.join(properties)}::"
                     f"{_escape_data(message)}\n")
    summary = Summary.of(results)
    stream.write(f"urdftool: {counted(summary.files, 'file')}, {counted(summary.errors, 'error')}, "
                 f"{counted(summary.warnings, 'warning')}, {counted(summary.infos, 'note')}\n")
