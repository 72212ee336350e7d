"""The fuzz modes of issue 29's classes 6 and 7: every kept failing input stays fixed, and short
seeded slices of new cases run.

``make fuzz`` runs ``--names`` (hostile names through every command and format, tests/fuzz/
names.py), ``--server`` (language-server sessions: floods, huge and slow documents,
tests/fuzz/server_session.py) and ``--environments`` (odd environments, streams, memory
budgets and output targets, tests/fuzz/environments.py) at length; here each kept input is replayed and a few cases of
each run.
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


@pytest.mark.parametrize("path", SESSIONS, ids=[p.stem for p in SESSIONS])
def test_kept_server_sessions_behave(path: Path):
    assert server_session.replay(path) == []


def test_seeded_names_slice():
    stats = names.run(5, seed=29, keep=False)
    assert stats["cases"] == 5 and stats["failures"] == 0, "see the FAIL lines above"


def test_seeded_server_slice():
    stats = server_session.run(2, seed=29, keep=False)
    assert stats["cases"] == 2 and stats["failures"] == 0, "see the FAIL lines above"


@pytest.mark.parametrize("path", ENVIRONMENTS, ids=[p.stem for p in ENVIRONMENTS])
def test_kept_environments_behave(path: Path):
    assert environments.replay(path) == []


def test_seeded_environments_slice():
    stats = environments.run(5, seed=29, keep=False)
    assert stats["cases"] == 5 and stats["failures"] == 0, "see the FAIL lines above"
