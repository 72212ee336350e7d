"""The inertia rules on big robots with meshes: ``check --select U3`` of benchmarks/generate.py's
``meshes`` robot (every other link fixed to the base: one rigid body of half the links; open
and closed STL meshes at five scales) at 1,000 and 10,000 links. Target: t(10k) / t(1k) at
most 12 (linear, with room for the load). Median CPU times of the child processes, runs
alternating (benchmarks/timing.py).

Before the rigid bodies were measured once (physics.solids._bodies), every member gathered
the whole body again: 1,000 links fixed together took 195 s, and this robot at 1,000 links
ran out of the 2 GiB budget.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from benchmarks import generate  # noqa: E402
from benchmarks.timing import alternating, load  # noqa: E402

URDFTOOL = str(Path(sys.executable).parent / "urdftool")


def main() -> list[dict]:
    with tempfile.TemporaryDirectory() as folder:
        robots = {n: str(generate.write(Path(folder), n, "meshes")) for n in (1000, 10000)}
        check = [URDFTOOL, "check", "--select", "U3", "--no-cache", "--jobs", "1",
                 "--timeout", "0", "--max-memory", "0", "--format", "json"]
        found = alternating({"1k": [*check, robots[1000]], "10k": [*check, robots[10000]]}, 3)
    growth = found["10k"].median / found["1k"].median
    print(f"check --select U3, meshes robot: 10,000 links {found['10k'].text()}; 1,000 links "
          f"{found['1k'].text()}; {growth:.1f}; {load()}")
    return [{"name": f"check U3 meshes t(10k) [{found['10k'].median:.2f}] / t(1k) "
                     f"[{found['1k'].median:.2f} s cpu] ({load()})",
             "ratio": growth, "target": 12.0, "ok": growth <= 12}]


if __name__ == "__main__":
    main()
