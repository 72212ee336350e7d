"""The real-repository sweep (issue 30): over a hundred public repositories with robot
descriptions (arms, hands, grippers, mobile bases, legged robots, humanoids, sensors, drones;
ROS 1 and ROS 2; with their launch files, controller YAML, ros2_control and MoveIt
configurations), listed in real_sweep/MANIFEST.tsv and restored outside the project by
``make real-sweep-setup`` (scripts/restore_real_sweep.py) into ``../sweep-repos``, or
``URDFTOOL_REAL_SWEEP``.

Each repository is checked as a user would check it, with the urdftool command:
- the folder walk: ``urdftool check . --format json --no-cache`` in the repository's root;
- the pre-commit hook's way: every ``.urdf``/``.xacro``/``.yaml``/``.yml``/``.srdf`` file of
  the repository named on one command line, with the hook's ``--no-env``
  (``pre-commit run --all-files``).

Every error and warning either way must match a row of real_sweep/JUDGED.tsv (repository,
path, lines, code, verdict, reason): TRUE (the defect is named), DEBATABLE (why), ARTEFACT (the
snapshot lacks the file: real_sweep/ABSENT.tsv), or FALSE-OPEN (a false finding owned by
another part of the work: real_sweep/OPEN.md; each is an expected failure named by its row,
strict, so that it fails again once fixed and the row must go). A row judged FALSE fails. An
unjudged finding fails, and so does a judged one no longer found (a lost true finding, or a
fixed false one whose row should go).

Slow (minutes on 2 cores); skipped when the sweep is absent.
``python tests/integration/test_real_sweep.py draft [REPO...]`` runs the sweep and prints the
unjudged findings, grouped, for judging.
"""

from __future__ import annotations

import csv
import importlib.util
import json
import os
import re
import subprocess
import sys
import time
from collections import defaultdict
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DATA = Path(__file__).resolve().parent / "real_sweep"
SWEEP = Path(os.environ.get("URDFTOOL_REAL_SWEEP", ROOT.parent / "sweep-repos"))
URDFTOOL = Path(sys.executable).with_name("urdftool")
HOOK_FILES = re.compile(r"(?i)\.(urdf|xacro|ya?ml|srdf)$")  # .pre-commit-hooks.yaml's `files`
VERDICTS = ("TRUE", "DEBATABLE", "ARTEFACT", "FALSE-OPEN", "FALSE")
pytestmark = pytest.mark.slow


def _restore_module():
    spec = importlib.util.spec_from_file_location("restore_real_sweep",
                                                  ROOT / "scripts" / "restore_real_sweep.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


RESTORE = _restore_module()
MANIFEST = RESTORE.read_manifest()


def _table(name: str) -> list[dict[str, str]]:
    with (DATA / name).open(newline="", encoding="utf-8") as handle:
        lines = [line for line in handle if line.strip() and not line.startswith("#")]
    return list(csv.DictReader(lines, delimiter="\t"))


@dataclass(frozen=True)
class Judgement:
    repository: str
    path: str
    lines: tuple[int, ...]
    code: str
    verdict: str
    reason: str

    @property
    def keys(self):
        return [(self.repository, self.path, line, self.code) for line in self.lines]

    def __str__(self):
        return (f"{self.repository} {self.path}:{','.join(map(str, self.lines))} {self.code} "
                f"{self.verdict}: {self.reason}")


def judgements() -> list[Judgement]:
    return [Judgement(row["repository"], row["path"],
                      tuple(int(n) for n in row["lines"].split(",")), row["code"],
                      row["verdict"], row["reason"]) for row in _table("JUDGED.tsv")]


def hook_files(folder: Path) -> list[str]:
    """What ``pre-commit run --all-files`` passes to the hook: the repository's files matching
    the hook's pattern (every restored file is tracked), relative to its root."""
    found = []
    for dirpath, dirnames, filenames in os.walk(folder):
        dirnames[:] = sorted(d for d in dirnames if not (dirpath == str(folder) and d == ".git"))
        found += [os.path.relpath(os.path.join(dirpath, name), folder)
                  for name in sorted(filenames) if HOOK_FILES.search(name)]
    return found


def run_urdftool(folder: Path, words: list[str]) -> list[dict]:
    """``urdftool check WORDS --format json --no-cache`` in ``folder``: its diagnostics."""
    env = {key: value for key, value in os.environ.items()
           if not key.startswith(("ROS_", "AMENT_", "COLCON_", "URDFTOOL_", "CI", "GITHUB_"))}
    out = subprocess.run([str(URDFTOOL), "check", *words, "--format", "json", "--no-cache"],
                         cwd=folder, env=env, capture_output=True, text=True, timeout=1800)
    if out.returncode == 2 and out.stderr.startswith(("urdftool: error: nothing checked: ",
                                                      "urdftool: error: no .urdf or .xacro")):
        # macro libraries only (a sensor's), or no robot file at all (a MoveIt configuration
        # whose robot is another repository's): a usage error, no finding
        return []
    unexpanded = out.returncode == 2 and "not checked: a package" \
        in out.stderr  # robots needing another repository's package: U006 in the report
    assert out.returncode in (0, 1) or unexpanded, (folder.name, words[:3], out.returncode,
                                                    out.stderr[-2000:])
    return json.loads(out.stdout)["diagnostics"]


def sweep_one(repository: str) -> dict[tuple[str, str, int, str], dict]:
    """Every error and warning of ``repository``, both ways: (repo, path, line, code) ->
    {"modes": {...}, "messages": {...}, "severity": ...}."""
    folder = SWEEP / RESTORE.folder_name(repository)
    found: dict[tuple[str, str, int, str], dict] = {}
    runs = [("walk", ["."])]
    named = hook_files(folder)
    if named:
        runs.append(("named", ["--no-env", *named]))
    for mode, words in runs:
        for diagnostic in run_urdftool(folder, words):
            if diagnostic["severity"] not in ("error", "warning"):
                continue
            path = os.path.relpath(os.path.join(folder, diagnostic["file"]), folder)
            key = (repository, path, diagnostic["line"] or 0, diagnostic["code"])
            entry = found.setdefault(key, {"modes": set(), "messages": set(),
                                           "severity": diagnostic["severity"]})
            entry["modes"].add(mode)
            entry["messages"].add(diagnostic["message"])
    return found


def sweep(repositories: list[str]) -> tuple[dict, dict[str, float]]:
    found, seconds = {}, {}
    for repository in repositories:
        start = time.monotonic()
        found.update(sweep_one(repository))
        seconds[repository] = time.monotonic() - start
    return found, seconds


def restored() -> list[str]:
    return [row["repository"] for row in MANIFEST
            if RESTORE.is_current(SWEEP / RESTORE.folder_name(row["repository"]), row["commit"])]


@pytest.fixture(scope="module")
def sweep_run():
    if not SWEEP.is_dir() or not restored():
        pytest.skip(f"the real sweep is not restored at {SWEEP} (make real-sweep-setup)")
    start = time.monotonic()
    found, seconds = sweep(restored())
    print(f"\nreal sweep: {len(seconds)} repositories, {len(found)} findings (by line), "
          f"{time.monotonic() - start:.0f} s", file=sys.stderr)
    return found


def test_every_manifest_repository_is_restored():
    if not SWEEP.is_dir():
        pytest.skip(f"the real sweep is not restored at {SWEEP} (make real-sweep-setup)")
    missing = sorted({row["repository"] for row in MANIFEST} - set(restored()))
    assert not missing, f"not restored at their commits (make real-sweep-setup): {missing}"


def test_the_manifest_says_what_each_repository_holds():
    wrong = {}
    for repository in restored():
        row = next(r for r in MANIFEST if r["repository"] == repository)
        surveyed = RESTORE.survey(SWEEP / RESTORE.folder_name(repository))
        recorded = {key: row[key] for key in surveyed}
        if surveyed != recorded:
            wrong[repository] = (recorded, surveyed)
    assert not wrong


def test_the_sweep_is_a_hundred_repositories_of_every_kind():
    assert len({row["repository"] for row in MANIFEST}) == len(MANIFEST) >= 100
    kinds = {row["kind"] for row in MANIFEST}
    assert {"arm", "hand", "gripper", "mobile", "legged", "humanoid", "sensor", "drone"} <= kinds
    assert {"1", "2"} <= {row["ros"] for row in MANIFEST}
    for column in ("commit", "licence", "kind", "has"):
        assert all(row[column].strip() for row in MANIFEST), column


def test_the_judged_table_is_well_formed():
    for row in _table("JUDGED.tsv"):  # six fields: a seventh is two rows joined on one line
        assert None not in row and all(value is not None for value in row.values()), row
    rows = judgements()
    keys = [key for row in rows for key in row.keys]
    assert len(keys) == len(set(keys)), "a finding judged twice"
    repositories = {row["repository"] for row in MANIFEST}
    absent = {(row["repository"], row["path"]) for row in _table("ABSENT.tsv")}
    for row in rows:
        assert row.repository in repositories, row
        assert row.verdict in VERDICTS and row.reason.strip(), row
        if row.verdict == "ARTEFACT":  # names a file that the snapshot lacks
            assert any(repo == row.repository and Path(path).name in row.reason
                       for repo, path in absent), row
    open_text = (DATA / "OPEN.md").read_text()
    for row in rows:
        if row.verdict == "FALSE-OPEN":
            assert f"{row.path}:{row.lines[0]} {row.code}" in open_text, row


def test_every_error_and_warning_on_the_real_sweep_is_judged(sweep_run):
    judged = {key: row for row in judgements() for key in row.keys}
    unjudged = sorted(f"{r} {p}:{line} {code} [{'+'.join(sorted(e['modes']))}] "
                      f"{sorted(e['messages'])[0]}"
                      for (r, p, line, code), e in sweep_run.items()
                      if (r, p, line, code) not in judged)
    false = sorted({str(row) for key, row in judged.items()
                    if key in sweep_run and row.verdict == "FALSE"})
    swept = set(restored())
    lost = sorted({str(row) for key, row in judged.items() if key not in sweep_run
                   and row.repository in swept and row.verdict != "FALSE-OPEN"})
    assert not unjudged and not false and not lost, (len(unjudged), unjudged[:60], false, lost)


def _open_rows() -> list[Judgement]:
    return [row for row in judgements() if row.verdict == "FALSE-OPEN"]


@pytest.mark.parametrize("row", _open_rows(), ids=lambda row: f"{row.path}:{row.lines[0]}"
                                                            f"-{row.code}")
def test_open_false_finding(sweep_run, row):
    """Each false finding still open (real_sweep/OPEN.md) is an expected failure while it is
    found; fixed, it passes, and the strict xfail fails so that its row is removed."""
    if row.repository not in restored():
        pytest.skip(f"{row.repository} not restored")
    if any(key in sweep_run for key in row.keys):
        pytest.xfail(f"open false finding: {row}")
    pytest.fail(f"no longer found (fixed?): remove its row from JUDGED.tsv and OPEN.md: {row}")


def draft(repositories: list[str]) -> None:
    """Print the unjudged findings of ``repositories`` grouped by file and code: lines,
    modes and messages, to judge by reading the files."""
    judged = {key for row in judgements() for key in row.keys}
    found, seconds = sweep(repositories or restored())
    if os.environ.get("REAL_SWEEP_DUMP"):  # every finding, judged or not, for tools
        Path(os.environ["REAL_SWEEP_DUMP"]).write_text(json.dumps(
            [[*key, sorted(entry["modes"]), sorted(entry["messages"])]
             for key, entry in sorted(found.items())]))
    groups = defaultdict(list)
    for (repository, path, line, code), entry in sorted(found.items()):
        if (repository, path, line, code) not in judged:
            groups[(repository, path, code)].append((line, entry))
    for (repository, path, code), items in groups.items():
        modes = "+".join(sorted(set().union(*(e["modes"] for _, e in items))))
        messages = sorted(set().union(*(e["messages"] for _, e in items)))
        print("\t".join([repository, path, ",".join(str(line) for line, _ in items), code,
                         modes, " || ".join(messages)[:600]]))
    print(f"# {len(seconds)} repositories in {sum(seconds.values()):.0f} s", file=sys.stderr)


if __name__ == "__main__":
    if sys.argv[1:2] == ["draft"]:
        draft(sys.argv[2:])
