"""The fuzz modes of issue 29's classes 6 and 7: every kept failing input stays fixed.

``make fuzz`` runs ``--names`` (hostile names through every command and format, tests/fuzz/
names.py), ``--server`` (language-server sessions: floods, huge and slow documents,
tests/fuzz/server_session.py) and ``--environments`` (odd environments, streams, memory
budgets and output targets, tests/fuzz/environments.py) at length, and the tests marked
``slow`` here: the kept server sessions (a flood of 20 MB documents each, 10-20 s; what they
caught is proven in tests/test_server.py, the check out of memory) and seeded slices of each
mode. ``make test`` replays the kept names and environments and tests the loop the modes share.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.fuzz import environments, names, server_session
from tests.fuzz.harness import REGRESSIONS

NAMES = sorted(REGRESSIONS.glob("names-*.json"))
SESSIONS = sorted(REGRESSIONS.glob("server-*.json"))
ENVIRONMENTS = sorted(REGRESSIONS.glob("env-*.json"))


@pytest.mark.parametrize("path", NAMES, ids=[p.stem for p in NAMES])
def test_kept_hostile_names_forge_nothing(path: Path):
    assert names.replay(path) == []


@pytest.mark.slow
@pytest.mark.parametrize("path", SESSIONS, ids=[p.stem for p in SESSIONS])
def test_kept_server_sessions_behave(path: Path):
    assert server_session.replay(path) == []


@pytest.mark.slow
def test_seeded_names_slice():
    stats = names.run(5, seed=29, keep=False)
    assert stats["cases"] == 5 and stats["failures"] == 0, "see the FAIL lines above"


@pytest.mark.slow
def test_seeded_server_slice():
    stats = server_session.run(2, seed=29, keep=False)
    assert stats["cases"] == 2 and stats["failures"] == 0, "see the FAIL lines above"


@pytest.mark.parametrize("path", ENVIRONMENTS, ids=[p.stem for p in ENVIRONMENTS])
def test_kept_environments_behave(path: Path):
    assert environments.replay(path) == []


@pytest.mark.slow
def test_seeded_environments_slice():
    stats = environments.run(5, seed=29, keep=False)
    assert stats["cases"] == 5 and stats["failures"] == 0, "see the FAIL lines above"


def test_the_fuzz_loop_counts_keeps_and_goes_on(capsys):
    """tests/fuzz/run.drive, the loop of the names, server and environments modes: every case
    drawn is attempted, a failing one is counted, kept (only when asked) and named, and the
    run goes on past it."""
    from hypothesis import strategies as st

    from tests.fuzz.run import drive

    kept = []

    def attempt(drawn, stats):
        stats["seen"] += 1
        return (["odd"] if drawn % 2 else []), lambda: kept.append(drawn) or Path(f"k-{drawn}")

    stats = drive(st.integers(0, 1 << 20), attempt, 20, seed=3, keep=True, every=10, seen=0)
    assert stats["cases"] == stats["seen"] == 20 and stats["failures"] == len(kept) > 0
    assert all(n % 2 for n in kept)
    assert capsys.readouterr().out.count("FAIL k-") == len(kept)
    quiet = drive(st.integers(0, 1 << 20), attempt, 20, seed=3, keep=False, seen=0)
    assert quiet["failures"] == stats["failures"] and len(kept) == stats["failures"]
