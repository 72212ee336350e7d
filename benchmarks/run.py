"""`make bench`: run every benchmarks/bench_*.py and compare each against its reference.

Each module has ``main() -> list[dict]`` (or a dict); a result has ``name``, ``value``,
``reference`` (what it is measured against, in the same run), ``ratio``, ``target`` and ``ok``.
Exit code 1 when a target is missed.
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent


def main() -> int:
    results = []
    for path in sorted(HERE.glob("bench_*.py")):
        spec = importlib.util.spec_from_file_location(path.stem, path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        outcome = module.main()
        results.extend(outcome if isinstance(outcome, list) else [outcome])
    print()
    print(f"{'benchmark':58} {'ratio':>8} {'target':>10}  verdict")
    for result in results:
        verdict = "ok" if result.get("ok", True) else "MISSED"
        print(f"{result['name']:58} {result.get('ratio', float('nan')):8.2f} "
              f"{str(result.get('target', '')):>10}  {verdict}")
    return 0 if all(r.get("ok", True) for r in results) else 1


if __name__ == "__main__":
    sys.path.insert(0, str(HERE.parent))
    sys.exit(main())
