"""``--format github``: GitHub Actions workflow commands, shown as annotations on the diff."""

from __future__ import annotations

from urdftool.report.escape import printable, workflow
from urdftool.report.summary import Summary, all_findings, counted, via_text

_LEVELS = {"error": "error", "warning": "warning", "info": "notice"}


def render(results, stream) -> None:
    for finding in all_findings(results):
        properties = [f"file={workflow(finding.file, property=True)}"]
        if finding.line is not None:
            properties.append(f"line={finding.line}")
            if finding.column is not None:
                properties.append(f"col={finding.column}")
        title = f"{finding.code} {finding.name}" + (f" ({finding.target})" if finding.target
                                                    else "")
        properties.append(f"title={workflow(title, property=True)}")
        # the message's own line breaks escaped; %0A only between the message and its call sites
        message = "\n".join(map(printable, [finding.message, *via_text(finding.location)]))
        stream.write(f"::{_LEVELS[finding.severity.value]} {','.join(properties)}::"
                     f"{workflow(message)}\n")
    summary = Summary.of(results)
    stream.write(f"urdftool: {', '.join([counted(summary.files, 'file'), *summary.counts()])}\n")
