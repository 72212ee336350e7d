"""Findings before and after a speed change, byte for byte.

    python benchmarks/same_findings.py record FOLDER   # before the change
    python benchmarks/same_findings.py compare FOLDER  # after it: exit 1 on any difference
    python benchmarks/same_findings.py record FOLDER meshes300  # those cases only

Each case is ``urdftool check --format json --no-cache --jobs 1 --timeout 0`` (every rule on,
no time budget: slow code before a change must finish too) over: the
corpus URDFs (../shared/corpus or URDFTOOL_CORPUS), robots/, and synthetic robots of
benchmarks/generate.py (a 1,000-link chain and star, a 10,000-link star, the robot of
meshes of 300 links, 150 of them one rigid body: before the bodies were measured once, more
links took minutes and gigabytes). Speed work must not
change one byte of what a check finds.
"""

from __future__ import annotations

import difflib
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benchmarks"))
CORPUS = Path(os.environ.get("URDFTOOL_CORPUS", ROOT.parent / "shared" / "corpus"))
SYNTHETIC = [(1000, "chain"), (1000, "star"), (10000, "star"), (10000, "chain"), (300, "meshes")]


def cases(folder: Path) -> dict[str, list[str]]:
    """name -> the paths one check command is given."""
    import generate

    found = {"robots": [str(ROOT / "robots")]}
    if CORPUS.is_dir():
        rows = (CORPUS / "MANIFEST.tsv").read_text().splitlines()[1:]
        found["corpus"] = [str(CORPUS / r.split("\t")[0]) for r in rows
                           if r.split("\t")[4] == "urdf"]
    for links, shape in SYNTHETIC:
        found[f"{shape}{links}"] = [str(generate.write(folder, links, shape))]
    return found


def run(paths: list[str]) -> bytes:
    command = [str(Path(sys.executable).parent / "urdftool"), "check", "--format", "json",
               "--no-cache", "--jobs", "1", "--timeout", "0", *paths]
    done = subprocess.run(command, capture_output=True, cwd=ROOT)
    return done.stdout + b"\n--- stderr ---\n" + done.stderr + \
        f"\n--- exit {done.returncode} ---\n".encode()


def main() -> int:
    verb, folder = sys.argv[1], Path(sys.argv[2])
    folder.mkdir(parents=True, exist_ok=True)
    differ = 0
    robots = folder / "robots"  # the same paths in both runs' findings
    robots.mkdir(exist_ok=True)
    chosen = sys.argv[3:]
    for name, paths in cases(robots).items():
        if chosen and name not in chosen:
            continue
        out = run(paths)
        kept = folder / f"{name}.out"
        if verb == "record":
            kept.write_bytes(out)
            print(f"{name}: recorded {len(out)} bytes")
        elif kept.read_bytes() == out:
            print(f"{name}: same ({len(out)} bytes)")
        else:
            differ += 1
            print(f"{name}: DIFFERENT")
            sys.stdout.writelines(list(difflib.unified_diff(
                kept.read_text(errors="replace").splitlines(True),
                out.decode(errors="replace").splitlines(True), "before", "after"))[:60])
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
