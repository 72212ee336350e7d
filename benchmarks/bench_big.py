"""Big generated robots: ``urdftool fk`` of a chain, text output to a pipe, against Pinocchio's
own ``buildModelFromXML`` of the same file (target: 1.5x at 2,000 links), and how ``fk`` grows
(target: t(8,000 links) / t(1,000 links) at most 12, i.e. no worse than n log n by much); the
same growth for the other long tables on the chain: ``dh`` from its first link to its last and
``inertia`` (issue 34: "fk, dh, inertia and other tables"). ``dynamics`` has no line: Pinocchio's
Data holds nv^3 tensors, so it refuses a 2,000-joint chain before any work (its memory check),
and ``M(q)`` is nv^2 numbers to print anyway (``--max-matrix-rows``).
Median CPU times of the child processes, runs alternating (benchmarks/timing.py).
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
    results = []
    with tempfile.TemporaryDirectory() as folder:
        chain = {n: str(generate.write(Path(folder), n, "chain")) for n in (1000, 2000, 8000)}
        build = ("import pinocchio, sys; "
                 "pinocchio.buildModelFromXML(open(sys.argv[1]).read())")
        found = alternating({"fk": [URDFTOOL, "fk", chain[2000]],
                             "pinocchio": [sys.executable, "-c", build, chain[2000]]}, 3)
        ratio = found["fk"].median / found["pinocchio"].median
        print(f"fk 2000-link chain: {found['fk'].text()}; buildModelFromXML "
              f"{found['pinocchio'].text()}; {ratio:.2f}x; {load()}")
        results.append({"name": f"fk 2000-link chain, text [{found['fk'].median:.2f} s cpu] vs "
                                f"buildModelFromXML [{found['pinocchio'].median:.2f} s] "
                                f"({load()})",
                        "ratio": ratio, "target": 1.5, "ok": ratio <= 1.5,
                        "detail": f"goal <= 1.5x; ours {found['fk'].text()}; reference "
                                  f"{found['pinocchio'].text()}"})
        budget = ["--timeout", "0", "--max-memory", "0"]
        growing = {"fk": lambda n: ["fk", chain[n]],
                   "dh": lambda n: ["dh", "--base", "l0", "--tip", f"l{n - 1}", *budget, chain[n]],
                   "inertia": lambda n: ["inertia", *budget, chain[n]]}
        for name, words in growing.items():
            grown = alternating({n: [URDFTOOL, *words(n)] for n in (1000, 8000)}, 2)
            growth = grown[8000].median / grown[1000].median
            print(f"{name} 8000 vs 1000 links: {grown[8000].text()} / {grown[1000].text()} = "
                  f"{growth:.1f}; {load()}")
            results.append({"name": f"{name} t(8000 links)/t(1000 links) [{grown[8000].median:.2f}"
                                    f" / {grown[1000].median:.2f} s cpu] ({load()})",
                            "ratio": growth, "target": 12.0, "ok": growth <= 12,
                            "detail": f"goal <= 12; 8k {grown[8000].text()}; 1k (reference) "
                                      f"{grown[1000].text()}"})
    return results


if __name__ == "__main__":
    main()
