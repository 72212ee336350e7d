"""``make fuzz``: hostile repositories through every command, N cases (default 10,000).

Usage: python -m tests.fuzz.run [N] [--seed S] [--max-seed-bytes B] [--kinds K,K]
                                [--time-limit SECONDS] [--parallel P] [--in-process]
                                [--names] [--server] [--environments]

Each case (tests/fuzz/cases.py) is a mutated robot in a throw-away repository with hostile
additions, run through check (in worker mode and as a folder walk), xacro, tree, graph, fk, dh,
inertia, dynamics and collisions, each in a forked child with a time limit, its peak memory
measured and every file it opens audited (harness.case_report). ``--in-process`` runs the older,
faster mode instead: the check engine on mutated robots in this process (harness.problems).
``--names`` runs hostile names through every command and format (names.py: forged output),
``--server`` language-server sessions (server_session.py: floods, huge and slow documents),
``--environments`` the process's environment, streams, memory budget and output target
(environments.py).
Every failing input is kept in tests/fuzz/regressions/ and the run goes on; exit 1 if any failed.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections import Counter

from hypothesis import HealthCheck, given, settings
from hypothesis import seed as hypothesis_seed

from .harness import case_report, problems, save_case_regression, save_regression
from .mutate import mutant, seeds


def run(count: int, seed: int = 0, max_seed_bytes: int | None = None) -> dict:
    """The in-process mode: check_file on mutated robots."""
    seed_list = seeds(max_seed_bytes)
    stats = {"cases": 0, "failures": 0, "seeds": len(seed_list)}
    start = time.perf_counter()

    @_generate(seed, count)
    @given(mutant(seed_list))
    def case(pair):
        seed_file, data = pair
        stats["cases"] += 1
        found = problems(seed_file, data)
        if found:
            stats["failures"] += 1
            path = save_regression(seed_file, data, found)
            print(f"FAIL {path.name} (seed {seed_file.path.name}): {found[0][:200]}", flush=True)
        _progress(stats, start)

    case()
    stats["seconds"] = round(time.perf_counter() - start, 1)
    return stats


def run_commands(count: int, seed: int = 0, max_seed_bytes: int | None = None,
                 kinds: list[str] | None = None, time_limit: float = 30.0, parallel: int = 2,
                 keep: bool = True) -> dict:
    """Whole cases through every command (see the module docstring).

    Returns figures: cases, failures, failure classes (the word before the first colon of
    each failure), peak RSS over all commands [MiB], files opened outside, seconds.
    keep: save failing cases to tests/fuzz/regressions.
    """
    from .cases import case_strategy
    from .child import preload

    preload()
    seed_list = seeds(max_seed_bytes)
    stats = {"cases": 0, "failures": 0, "seeds": len(seed_list), "peak_mib": 0, "outside": 0,
             "classes": Counter(), "commands_seconds": 0.0, "failed": []}
    start = time.perf_counter()

    @_generate(seed, count)
    @given(case_strategy(seed_list, kinds))
    def case(one):
        stats["cases"] += 1
        report = case_report(one, time_limit=time_limit, parallel=parallel)
        stats["peak_mib"] = max(stats["peak_mib"], report.peak_kib // 1024)
        stats["outside"] += report.outside
        stats["commands_seconds"] += report.seconds
        if report.failures:
            stats["failures"] += 1
            classes = sorted({f.split(":", 1)[0] for f in report.failures})
            stats["classes"].update(classes)
            name = save_case_regression(one, report).name if keep else "-"
            stats["failed"].append((name, one.kind, classes))
            print(f"FAIL {name} ({one.kind}, seed {one.seed.path.name}, output {one.output}): "
                  f"{', '.join(classes)}: {report.failures[0][:200]}", flush=True)
        _progress(stats, start, every=50)

    case()
    stats["seconds"] = round(time.perf_counter() - start, 1)
    return stats


def drive(strategy, attempt, count: int, seed: int = 0, keep: bool = True, every: int = 25,
          **figures) -> dict:
    """The loop of the fuzz modes that draw whole cases (names.py, server_session.py,
    environments.py): ``count`` cases drawn from ``strategy`` (seeded), each given to
    ``attempt(drawn, stats)``, which may add to the mode's ``figures`` in ``stats`` and returns
    (problems, a function keeping the case in tests/fuzz/regressions). A failing case is kept
    (when ``keep``) and named on a FAIL line; the run goes on. Figures: cases, failures, the
    mode's, seconds."""
    stats = {"cases": 0, "failures": 0, **figures}
    start = time.perf_counter()

    @_generate(seed, count)
    @given(strategy)
    def case(drawn):
        stats["cases"] += 1
        problems, kept = attempt(drawn, stats)
        if problems:
            stats["failures"] += 1
            print(f"FAIL {kept().name if keep else '-'}: {problems[0][:200]}", flush=True)
        _progress(stats, start, every)

    case()
    stats["seconds"] = round(time.perf_counter() - start, 1)
    return stats


def _generate(seed: int, count: int):
    def wrap(test):
        return hypothesis_seed(seed)(settings(
            max_examples=count, deadline=None, database=None, derandomize=False,
            suppress_health_check=list(HealthCheck), phases=["generate"])(test))

    return wrap


def _progress(stats: dict, start: float, every: int = 500) -> None:
    if stats["cases"] % every == 0:
        print(f"{stats['cases']} cases, {stats['failures']} failures, "
              f"{time.perf_counter() - start:.0f} s", flush=True)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("count", type=int, nargs="?", default=10_000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--max-seed-bytes", type=int, default=None)
    parser.add_argument("--kinds", default=None, help="comma-separated case kinds (cases.py)")
    parser.add_argument("--time-limit", type=float, default=30.0, help="per command [s]")
    parser.add_argument("--parallel", type=int, default=2, help="commands at a time")
    parser.add_argument("--in-process", action="store_true", help="check_file only, in-process")
    parser.add_argument("--names", action="store_true",
                        help="hostile names through every command and format (names.py)")
    parser.add_argument("--server", action="store_true",
                        help="language-server sessions: floods, huge and slow documents "
                             "(server_session.py)")
    parser.add_argument("--environments", action="store_true",
                        help="odd environments, streams, memory budgets and output targets "
                             "(environments.py)")
    options = parser.parse_args(argv)
    if options.names or options.server or options.environments:
        from . import environments, names, server_session

        mode, module = (("--names", names) if options.names else ("--server", server_session)
                        if options.server else ("--environments", environments))
        stats = module.run(options.count, options.seed)
        print(f"fuzz {mode}: " + ", ".join(f"{key} {value}" for key, value in stats.items()))
        return 1 if stats["failures"] else 0
    if options.in_process:
        stats = run(options.count, options.seed, options.max_seed_bytes)
        print(f"fuzz: {stats['cases']} cases from {stats['seeds']} seed robots, "
              f"{stats['failures']} failures, {stats['seconds']} s")
        return 1 if stats["failures"] else 0
    stats = run_commands(options.count, options.seed, options.max_seed_bytes,
                         options.kinds.split(",") if options.kinds else None,
                         options.time_limit, options.parallel)
    classes = ", ".join(f"{name} {n}" for name, n in stats["classes"].most_common()) or "none"
    print(f"fuzz: {stats['cases']} cases from {stats['seeds']} seed robots, "
          f"{stats['failures']} failing ({classes}); peak memory {stats['peak_mib']} MiB; "
          f"files opened outside: {stats['outside']}; {stats['seconds']} s")
    return 1 if stats["failures"] else 0


if __name__ == "__main__":
    sys.exit(main())
