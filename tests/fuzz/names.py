"""Fuzz mode ``--names``: hostile names through every command and format.

Each case composes the names of tests/fuzz/forge.py's repository from drawn pieces: the fixed
payloads (workflow commands, Markdown, HTML, rich markup, bidi, C1, ...) and runs of characters
of the dangerous classes (line breaks, separators, format characters, Markdown and table
syntax, blanks GitHub strips before ``::``), builds the repository, and runs a drawn sample of
:func:`forge.invocations` (every command, format and output option). :func:`forge.judge` and
:func:`forge.file_written` say what is forged; a failing case is kept in tests/fuzz/regressions
as ``names-<hash>.json`` (its pieces and the invocations that failed), replayed by
tests/integration/test_fuzz_output.py.
"""

from __future__ import annotations

import hashlib
import json
import resource
import shutil
import tempfile
from pathlib import Path

from hypothesis import strategies as st

from . import forge
from .harness import REGRESSIONS

# Characters a name can hold in XML 1.0 that act on a terminal, a CI runner, Markdown, HTML, a
# table or a spreadsheet (no '$': xacro would read an expression; no '/': a file name).
DANGEROUS = ("\n\r\t\x85\x9b\x90\x9d\x9c\u2028\u2029\u202a\u202b\u202c\u202d\u202e\u2066\u2067"
             "\u2068\u2069\u200b\u200e\u200f\ufeff\u00a0\u3000\u2003 :#|`<>[]()!*_@=%,&\"'\\~-")
PIECES = st.one_of(st.sampled_from(sorted({*forge.NAME_PAYLOADS.values(), "::"})),
                   st.text(alphabet=DANGEROUS, min_size=1, max_size=8))


@st.composite
def cases(draw, count: int):
    """(payloads for forge.names, indexes of the invocations to run)."""
    pieces = draw(st.lists(PIECES, min_size=1, max_size=6))
    payloads = {f"p{i}": piece for i, piece in enumerate(pieces)}
    chosen = draw(st.lists(st.integers(0, count - 1), min_size=1, max_size=4, unique=True))
    return payloads, sorted(chosen)


def run_case(payloads: dict, chosen=None, argv_kept=None) -> tuple[list[str], list]:
    """Run the invocations ``chosen`` (indexes) or ``argv_kept`` (argv with ``<root>`` for the
    repository) on a repository named with ``payloads``; (problems, argv of each failing run
    with ``<root>``)."""
    root = Path(tempfile.mkdtemp(prefix="urdffuzz-names-"))
    try:
        repo = forge.repository(root, payloads)
        runs = forge.invocations(repo)
        if argv_kept is not None:
            wanted = [[word.replace("<root>", str(root)) for word in argv] for argv in argv_kept]
            runs = [run for run in runs if run.argv in wanted]
        else:
            runs = [runs[i] for i in chosen]
        problems, failed = [], []
        for run in runs:
            for path in run.writes:
                path.unlink(missing_ok=True)
            code, stdout, stderr = forge.run_in_process(run.argv, root)
            where = "urdftool " + " ".join(word[:12] for word in run.argv[:3])
            found = forge.judge(run.kind, stdout, stderr, where)
            if code not in (0, 1, 2) or "Traceback (most recent call last)" in stderr:
                found.append(f"{where}: exit {code}: {stderr[-300:]}")
            for path in [*run.writes, *run.checks]:
                found += [f"{where}: {p}" for p in forge.file_written(path, code)]
            for path in run.checks:
                found += [f"{where}: {p}" for p in forge.names_kept(path, repo.names)]
            if found:
                problems += found
                failed.append([word.replace(str(root), "<root>") for word in run.argv])
        return problems, failed
    finally:
        shutil.rmtree(root, ignore_errors=True)


def save(payloads: dict, failed: list, problems: list[str]) -> Path:
    data = {"mode": "names", "payloads": payloads, "argv": failed, "found": problems[:20]}
    digest = hashlib.sha256(json.dumps([payloads, failed], sort_keys=True).encode()).hexdigest()
    REGRESSIONS.mkdir(exist_ok=True)
    path = REGRESSIONS / f"names-{digest[:12]}.json"
    path.write_text(json.dumps(data, indent=1, ensure_ascii=True) + "\n")
    return path


def replay(path: Path) -> list[str]:
    data = json.loads(path.read_text())
    return run_case(data["payloads"], argv_kept=data["argv"])[0]


def run(count: int, seed: int = 0, keep: bool = True) -> dict:
    """``count`` cases; figures: cases, invocations run, failures, forged outputs, peak memory
    [MiB] of this process and its children, seconds."""
    from .run import drive

    with tempfile.TemporaryDirectory() as probe:
        total = len(forge.invocations(forge.repository(Path(probe))))

    def attempt(drawn, stats):
        payloads, chosen = drawn
        stats["invocations"] += len(chosen)
        problems, failed = run_case(payloads, chosen)
        stats["forged"] += len(problems)
        return problems, lambda: save(payloads, failed, problems)

    stats = drive(cases(total), attempt, count, seed, keep, invocations=0, forged=0)
    stats["peak_mib"] = max(resource.getrusage(who).ru_maxrss for who in
                            (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN)) // 1024
    return stats
