"""``make fuzz``: mutate real robots and check them, N cases (default 10,000).

Usage: python -m tests.fuzz.run [N] [--seed S] [--max-seed-bytes B]
Every failing input is kept in tests/fuzz/regressions/ and the run goes on; exit 1 if any failed.
"""

from __future__ import annotations

import argparse
import sys
import time

from hypothesis import HealthCheck, given, settings
from hypothesis import seed as hypothesis_seed

from .harness import problems, save_regression
from .mutate import mutant, seeds


def run(count: int, seed: int = 0, max_seed_bytes: int | None = None) -> dict:
    seed_list = seeds(max_seed_bytes)
    stats = {"cases": 0, "failures": 0, "seeds": len(seed_list)}
    start = time.perf_counter()

    @hypothesis_seed(seed)
    @settings(max_examples=count, deadline=None, database=None, derandomize=False,
              suppress_health_check=list(HealthCheck), phases=["generate"])
    @given(mutant(seed_list))
    def case(pair):
        seed_file, data = pair
        stats["cases"] += 1
        found = problems(seed_file, data)
        if found:
            stats["failures"] += 1
            path = save_regression(seed_file, data, found)
            print(f"FAIL {path.name} (seed {seed_file.path.name}): {found[0][:200]}", flush=True)
        if stats["cases"] % 500 == 0:
            print(f"{stats['cases']} cases, {stats['failures']} failures, "
                  f"{time.perf_counter() - start:.0f} s", flush=True)

    case()
    stats["seconds"] = round(time.perf_counter() - start, 1)
    return stats


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("count", type=int, nargs="?", default=10_000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--max-seed-bytes", type=int, default=None)
    options = parser.parse_args(argv)
    stats = run(options.count, options.seed, options.max_seed_bytes)
    print(f"fuzz: {stats['cases']} cases from {stats['seeds']} seed robots, "
          f"{stats['failures']} failures, {stats['seconds']} s")
    return 1 if stats["failures"] else 0


if __name__ == "__main__":
    sys.exit(main())
