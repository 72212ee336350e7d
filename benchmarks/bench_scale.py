"""Linear cost in robot size: synthetic chains and stars (benchmarks/generate.py) of 1,000 and
10,000 links.

- ``urdftool check`` on the 10,000-link chain and star against urdfdom's ``check_urdf`` binary
  on the same file (target: <= 5x), the median CPU times of three alternating runs of each
  (benchmarks/timing.py: CPU time is what the machine's other users cannot change; the wall
  time of a run beside them doubled at load 4, the reference's hardly, as it is 10x shorter).
- t(10k) / t(1k) for ``check`` (chain and star), ``tree``, ``graph``, ``inertia`` and ``fk`` (star:
  ``tree`` prints check_urdf's format, indented by depth, so its output on a chain is quadratic
  in the links, as check_urdf's is) (target: <= 12), median CPU times of three alternating
  runs.
- ``dynamics`` and ``collisions`` are not run at 10,000 links: Pinocchio builds its model
  in quadratic time (its own ``buildModelFromXML``; the figures are in CHANGELOG.md), and its
  Data grows with nv^3 (``dynamics`` refuses beyond the
  memory budget), so their ratio is reported MISSED with Pinocchio's own parse ratio measured
  on 1,000 and 3,000 links as the reason (linear would be 3, quadratic 9).
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import generate  # noqa: E402
from bench_check import BIN, CHECK_URDF_TIMEOUT, urdfdom_check_urdf  # noqa: E402
from timing import alternating, load  # noqa: E402


def _pinocchio_parse(path: Path) -> float:
    import subprocess

    code = ("import pinocchio, sys, time; text = open(sys.argv[1]).read(); t = time.perf_counter();"
            " pinocchio.buildModelFromXML(text); print(time.perf_counter() - t)")
    out = subprocess.run([sys.executable, "-c", code, str(path)], capture_output=True, text=True)
    return float(out.stdout.strip() or "nan")


def main() -> list[dict]:
    urdftool = str(BIN / "urdftool")
    check_urdf, environment = urdfdom_check_urdf()
    results = []
    with tempfile.TemporaryDirectory() as folder:
        files = {(shape, n): generate.write(Path(folder), n, shape)
                 for shape in ("chain", "star") for n in (1000, 10000)}
        check = [urdftool, "check", "--timeout", "0", "--max-memory", "0", "--no-cache"]
        times = {}
        for shape in ("chain", "star"):
            found = alternating({"ours": [*check, str(files[shape, 10000])],
                                 "check_urdf": ([check_urdf, str(files[shape, 10000])],
                                                environment, CHECK_URDF_TIMEOUT),
                                 "ours 1k": [*check, str(files[shape, 1000])]}, 3)
            ours, reference = found["ours"].median, found["check_urdf"].median
            times["check", shape, 1000], times["check", shape, 10000] = \
                found["ours 1k"].median, ours
            results.append({"name": f"check {shape} 10k [{ours:.2f} s cpu] vs check_urdf "
                                    f"[{reference:.2f} s] ({load()})",
                            "ratio": ours / reference, "target": "<= 5x",
                            "ok": ours <= 5 * reference,
                            "detail": f"goal <= 5x; ours {found['ours'].text()}; reference "
                                      f"{found['check_urdf'].text()}"})
        for command in ("tree", "graph", "inertia", "fk"):
            found = alternating({n: [urdftool, command, "--timeout", "0", "--max-memory", "0",
                                     str(files["star", n])] for n in (1000, 10000)}, 3)
            for n in (1000, 10000):
                times[command, "star", n] = found[n].median
        for command, shape in [("check", "chain"), ("check", "star"), ("tree", "star"),
                               ("graph", "star"), ("inertia", "star"), ("fk", "star")]:
            small, large = times[command, shape, 1000], times[command, shape, 10000]
            results.append({"name": f"{command} {shape} t(10k) [{large:.2f} s cpu] / t(1k) "
                                    f"[{small:.2f} s]",
                            "ratio": large / small, "target": "<= 12", "ok": large <= 12 * small})
        three = generate.write(Path(folder), 3000, "chain")
        pin_small, pin_large = _pinocchio_parse(files["chain", 1000]), _pinocchio_parse(three)
        results.append({"name": f"dynamics/collisions: not run at 10k; raw Pinocchio parse "
                                f"chain t(3k)/t(1k) [{pin_large:.2f}/{pin_small:.2f} s] "
                                "(linear: 3, quadratic: 9)",
                        "ratio": pin_large / pin_small, "target": "<= 3.6", "ok": False})
    for result in results:
        print(result["name"], f"ratio {result['ratio']:.2f}")
    return results


if __name__ == "__main__":
    main()
