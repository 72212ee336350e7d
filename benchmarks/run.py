"""`make bench`: run every benchmarks/bench_*.py and compare each against its reference.

Each module has ``main() -> list[dict]`` (or a dict); a result has ``name``, ``value``,
``reference`` (what it is measured against, in the same run), ``ratio``, ``target`` and ``ok``,
and ``detail``: the goal, and the median and spread of each side (printed under its row).
Each module runs in a process of its own: what one leaves in memory (the render bench's meshes,
some 100,000 objects) would slow the next one's in-process timings, for the reference and the
code alike. Exit code 1 when a target is missed.
"""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent


def run_one(path: Path) -> list[dict]:
    """The results of one module's ``main()``, in this process."""
    sys.path.insert(0, str(HERE.parent))
    spec = importlib.util.spec_from_file_location(path.stem, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    outcome = module.main()
    return outcome if isinstance(outcome, list) else [outcome]


def main() -> int:
    results = []
    for path in sorted(HERE.glob("bench_*.py")):
        with tempfile.NamedTemporaryFile("r", suffix=".json") as out:
            done = subprocess.run([sys.executable, __file__, "--one", str(path), out.name])
            found = json.loads(out.read() or "null")
        if done.returncode != 0 or found is None:
            found = [{"name": f"{path.stem}: failed (exit code {done.returncode})", "ok": False}]
        for result in found:
            if "ok" not in result and isinstance(result.get("target"), (int, float)):
                result["ok"] = result["ratio"] <= result["target"]
            results.append(result)
    print()
    print(f"{'benchmark':58} {'ratio':>8} {'target':>10}  verdict")
    for result in results:
        verdict = "ok" if result.get("ok", True) else "MISSED"
        print(f"{result['name']:58} {result.get('ratio', float('nan')):8.2f} "
              f"{str(result.get('target', '')):>10}  {verdict}")
        if result.get("detail"):  # goal, reference, median and spread [min-max] of each side
            print(f"    {result['detail']}")
    return 0 if all(r.get("ok", True) for r in results) else 1


if __name__ == "__main__":
    if sys.argv[1:2] == ["--one"]:
        found = run_one(Path(sys.argv[2]))
        # numpy's numbers and booleans as Python's (a numpy False written as text would be true)
        Path(sys.argv[3]).write_text(json.dumps(
            found, default=lambda value: value.item() if hasattr(value, "item") else str(value)))
        sys.exit(0)
    sys.exit(main())
