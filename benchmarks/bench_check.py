"""`check` speed on the corpus, against references timed in the same run (start-up:
bench_startup.py).

- `check` over every corpus URDF in one process against a shell loop of urdfdom's `check_urdf`
  over the same files (target: within 5x of its CPU time, runs alternating), first without the
  result cache (the CI path), then again with it
  on an unchanged corpus (target: within 1x; the run's findings served from the cache's one
  entry for the whole run and rendered; other spellings of the same options are shown too). The reference is the ELF binary shipped in the pin
  wheel (``cmeel.prefix/bin/check_urdf`` with its ``lib/``), not ``.venv/bin/check_urdf``: that
  one is a Python wrapper that starts an interpreter per file, a flattering reference.
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import sysconfig
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BIN = Path(sys.executable).parent
CORPUS = Path(os.environ.get("URDFTOOL_CORPUS", ROOT.parent / "shared" / "corpus"))
# [s] for any one run of urdfdom's check_urdf in a benchmark (one file, or the shell loop over
# the corpus): the slowest healthy run, the 10,000-link chain (its listing is quadratic), takes
# 4 s, the corpus loop 0.3 s; on a kinematic cycle below the root check_urdf never returns, and
# a benchmark waiting on it would wait for ever (timing.Hung says which command instead).
CHECK_URDF_TIMEOUT = 120.0


def timed(command: list[str], repeat: int = 7, timeout: float | None = None, **kwargs) -> float:
    """Median wall time of a command in [s]; ``timeout`` as :func:`timing.run_once`'s."""
    from benchmarks.timing import run_once

    return statistics.median(run_once(command, timeout, **kwargs)[1] for _ in range(repeat))


def paired(ours: list[str], reference: list[str], repeat: int = 3,
           reference_env: dict | None = None,
           reference_timeout: float | None = None) -> tuple[float, float, str]:
    """Median wall times [s] of ``ours`` and ``reference``, timed alternately ``repeat`` times
    each, and the samples as text for the report. On a shared virtual machine the speed drifts
    by a third within minutes, so a sample of each taken a minute apart compares two hosts
    (CHANGELOG.md, issue 20 round 5, has what that read). Both sides get the same statistic."""
    mine, theirs = [], []
    for _ in range(repeat):
        mine.append(timed(ours, repeat=1))
        theirs.append(timed(reference, repeat=1, timeout=reference_timeout, env=reference_env))
    samples = (f"ours {'/'.join(f'{t:.2f}' for t in mine)}, "
               f"reference {'/'.join(f'{t:.2f}' for t in theirs)}")
    return statistics.median(mine), statistics.median(theirs), samples


def corpus_urdfs() -> list[Path]:
    if not CORPUS.is_dir():
        return []
    rows = (CORPUS / "MANIFEST.tsv").read_text().splitlines()[1:]
    return [CORPUS / r.split("\t")[0] for r in rows if r.split("\t")[4] == "urdf"]


def urdfdom_check_urdf() -> tuple[str, dict]:
    """urdfdom's check_urdf binary from the pin wheel and the environment it runs in (its
    ``lib/`` on LD_LIBRARY_PATH): the real thing at its fastest."""
    prefix = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix"
    binary = prefix / "bin" / "check_urdf"
    if not binary.is_file():
        raise SystemExit(f"no urdfdom check_urdf binary at {binary}: is pin installed?")
    library = os.pathsep.join(filter(None, [str(prefix / "lib"),
                                            os.environ.get("LD_LIBRARY_PATH")]))
    return str(binary), {**os.environ, "LD_LIBRARY_PATH": library}


def default_jobs_against_one(urdftool: str, files: list[Path]) -> list[dict]:
    """The default ``--jobs`` against ``--jobs 1`` on the corpus (``--no-cache``, the CI path),
    in wall time (what a user waits for; the pool always costs more CPU), runs alternating: as
    the machine is, then with one more core kept busy (``python -c "while 1: pass"``), the case
    where a second worker finds no idle core. Target: the default never slower (issue 34)."""
    from benchmarks.timing import alternating, load

    words = ["check", "--no-cache", "--format", "json", *map(str, files)]
    results = []
    for label in ("as the machine is", "one more core busy"):
        busy = subprocess.Popen([sys.executable, "-c", "while 1: pass"]) \
            if label == "one more core busy" else None
        try:
            found = alternating({"default": [urdftool, *words],
                                 "one": [urdftool, *words, "--jobs", "1"]}, repeat=3)
        finally:
            if busy is not None:
                busy.kill()
                busy.wait()
        ours, one = found["default"], found["one"]
        ratio = statistics.median(ours.wall) / statistics.median(one.wall)
        print(f"check corpus, default --jobs vs --jobs 1, {label}: {ratio:.2f}x wall; default "
              f"{ours.text()}; --jobs 1 {one.text()}; {load()}")
        results.append({"name": f"default --jobs vs --jobs 1, corpus, {label} ({load()})",
                        "ratio": ratio, "target": 1.0, "ok": ratio <= 1.0,
                        "detail": f"goal <= 1.0x wall; default {ours.text()}; --jobs 1 "
                                  f"(reference) {one.text()}"})
    return results


def main() -> list[dict]:
    urdftool = str(BIN / "urdftool")
    results = []  # --help and check r2d2 against their references: bench_startup.py
    files = corpus_urdfs()
    if files:
        check_urdf, environment = urdfdom_check_urdf()
        loop = "for f in \"$@\"; do \"$0\" \"$f\" >/dev/null 2>&1; done"
        reference_loop = ["bash", "-c", loop, check_urdf, *map(str, files)]
        # one process, as the target says: no worker processes, no per-file time budget
        command = [urdftool, "check", "--jobs", "1", "--timeout", "0", "--max-memory", "0",
                   "--format", "json"]
        from benchmarks.timing import alternating, load

        found = alternating({"ours": [*command, "--no-cache", *map(str, files)],
                             "reference": (reference_loop, environment,
                                           CHECK_URDF_TIMEOUT)}, repeat=5)
        ours, reference = found["ours"], found["reference"]
        print(f"check {len(files)} corpus URDFs, --no-cache: {ours.text()}; check_urdf loop "
              f"{reference.text()}; {load()}")
        results.append({
            "name": f"check {len(files)} corpus URDFs --no-cache [{ours.median:.2f} s cpu] vs "
                    f"urdfdom check_urdf loop [{reference.median:.2f} s cpu] ({load()})",
            "ratio": ours.median / reference.median, "target": 5.0,
            "ok": ours.median <= 5 * reference.median,
            "detail": f"goal <= 5x; ours {ours.text()}; reference {reference.text()}"})
        results += default_jobs_against_one(urdftool, files)
        with tempfile.TemporaryDirectory() as folder:
            cached = [*command, "--cache-dir", folder, *map(str, files)]
            timed(cached, repeat=1)  # fills the cache
            again, reference, _ = paired(cached, reference_loop, repeat=5,
                                         reference_env=environment,
                                         reference_timeout=CHECK_URDF_TIMEOUT)
            # other words: the findings come from the cache, the command runs and renders them
            # (no target; what a changed command line costs), each spelling of the format
            # option once.
            other = [[*command[:-2], *spelling, "--cache-dir", folder, *map(str, files)]
                     for spelling in (["-f", "text"], ["--format", "text"], ["--format=text"])]
            rendered = statistics.median(timed(words, repeat=1) for words in other)
        results.append({
            "name": f"re-check {len(files)} unchanged corpus URDFs, cached [{again:.2f} s] vs "
                    f"urdfdom check_urdf loop [{reference:.2f} s]",
            "ratio": again / reference, "target": "<= 1x", "ok": again <= reference})
        results.append({
            "name": f"  the same with other words: findings cached, output rendered "
                    f"[{rendered:.2f} s]",
            "ratio": rendered / reference, "target": "(none)"})
    for result in results:
        print(result["name"], f"ratio {result['ratio']:.2f}")
    return results


if __name__ == "__main__":
    main()
