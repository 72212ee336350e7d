"""Fuzzing: every kept crashing input stays fixed, and a short seeded slice of new cases runs.

``make fuzz`` runs 10,000 cases (tests/fuzz/run.py); this runs a few hundred from small seeds.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import corpus_or_skip
from tests.fuzz.harness import REGRESSIONS, load_regression, problems

REGRESSION_FILES = sorted(REGRESSIONS.glob("*.bin"))
CI_CASES = 300


@pytest.mark.parametrize("path", REGRESSION_FILES, ids=[p.stem for p in REGRESSION_FILES])
def test_regression_input_behaves(path: Path):
    seed, data = load_regression(path)
    if not seed.path.exists():
        corpus_or_skip()
        pytest.skip(f"seed {seed.path} is missing")
    assert problems(seed, data) == []


def test_seeded_fuzz_slice():
    corpus_or_skip()
    from tests.fuzz.run import run

    stats = run(CI_CASES, seed=20240601, max_seed_bytes=50_000)
    assert stats["cases"] == CI_CASES
    assert stats["failures"] == 0, "see the FAIL lines above; inputs kept in tests/fuzz/regressions"
