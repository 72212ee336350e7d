"""COLLADA meshes read by urdftool's own reader against trimesh, in fresh processes.

Each side is a ``python -c`` run that imports its reader and reads every corpus ``.dae`` (then
only the first one: what a robot with one COLLADA mesh pays): ``read_collada`` (lxml and numpy)
against ``trimesh.load(path, force="mesh", process=True)`` as ``meshes.reading._read_mesh`` calls it,
imports included. The ratio is of the CPU time of the two child processes (2 cores shared by
several agents make wall time noisy); the medians of a few runs, wall times shown too.
Target: the reader in at most half trimesh's time over the corpus.
"""

from __future__ import annotations

import os
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CORPUS = Path(os.environ.get("URDFTOOL_CORPUS", ROOT.parent / "shared" / "corpus"))

OURS = ("import sys\nfrom urdftool.description.collada import read_collada\n"
        "for path in sys.argv[1:]:\n"
        "    with open(path, 'rb') as handle:\n"
        "        read_collada(handle.read(), max_triangles=2_000_000)\n")
TRIMESH = ("import logging, sys, trimesh\nlogging.getLogger('trimesh').setLevel(50)\n"
           "for path in sys.argv[1:]:\n"
           "    trimesh.load(path, force='mesh', process=True)\n")


def _run(code: str, files: list[str]) -> tuple[float, float]:
    """(CPU time, wall time) in [s] of one fresh interpreter running ``code`` on ``files``."""
    environment = {**os.environ, "PYTHONPATH": str(ROOT)}
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-c", code, *files], env=environment,
                          stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode:
        raise SystemExit(f"benchmark child failed: {done.stderr.strip()[-500:]}")
    return (after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime), wall


def _compare(name: str, files: list[str], target: float, repeat: int = 5) -> dict:
    samples = {"ours": [], "trimesh": []}
    for _ in range(repeat):  # interleaved, so that both meet the same load on the machine
        samples["ours"].append(_run(OURS, files))
        samples["trimesh"].append(_run(TRIMESH, files))
    cpu = {side: statistics.median(s[0] for s in runs) for side, runs in samples.items()}
    wall = {side: statistics.median(s[1] for s in runs) for side, runs in samples.items()}
    return {"name": f"{name} [{cpu['ours']:.2f} s cpu, {wall['ours']:.2f} s wall] vs trimesh "
                    f"[{cpu['trimesh']:.2f} s cpu, {wall['trimesh']:.2f} s wall]",
            "value": cpu["ours"], "reference": cpu["trimesh"],
            "ratio": cpu["ours"] / cpu["trimesh"], "target": target}


def main() -> list[dict]:
    files = sorted(str(path) for path in CORPUS.rglob("*.dae")) if CORPUS.is_dir() else []
    if not files:
        return [{"name": f"collada: no corpus at {CORPUS}", "ok": True}]
    return [_compare(f"read_collada, {len(files)} corpus DAEs", files, 0.5),
            _compare("read_collada, one corpus DAE", files[:1], 0.5)]


if __name__ == "__main__":
    for result in main():
        print(result)
