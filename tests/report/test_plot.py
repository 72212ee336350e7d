"""urdftool.report.plot: the collision matrix's picture (the humanoid's cells and PNG are tested
with the matrix, tests/collision/test_collision.py); here what its size follows."""

from __future__ import annotations

import resource

import pytest

from urdftool.collision.matrix import Matrix, PairResult
from urdftool.errors import UsageError
from urdftool.report import plot


def _matrix(links: list[str]) -> Matrix:
    return Matrix(pairs=[PairResult(links[0], links[1], "Adjacent", 0, 10, 0.0)], links=links,
                  samples=10, seed=0, margin=0.0, min_fraction=0.0)


def test_a_long_link_name_is_cut_in_the_labels_and_kept_whole_in_the_tooltips():
    """A link named with 100,000 characters made the margins 700,000 pixels: a PNG of 1.4
    million pixels a side, out of memory (U018) after the matrix's work."""
    name = "L" * 100_000
    width, height, items = plot._layout(_matrix(["base", name]), "r")
    assert width < 2000 and height < 2000
    labels = [item[3] for item in items if item[0] == "text"]
    assert "L" * (plot.LABEL - 1) + "\u2026" in labels and name not in labels
    assert any(item[0] == "rect" and item[7] and name in item[7] for item in items)
    assert "base" in labels  # a short name as it is


def test_a_png_larger_than_the_memory_budget_leaves_is_refused_before_it_is_drawn():
    pytest.importorskip("PIL")
    from urdftool.budget import address_space

    used = address_space()
    if used is None:
        pytest.skip("no address space to read on this system")
    limit = resource.getrlimit(resource.RLIMIT_AS)
    resource.setrlimit(resource.RLIMIT_AS, (used + (512 << 20), limit[1]))
    try:
        with pytest.raises(UsageError, match=r"an \.svg \(drawn by the viewer\)"):
            plot.png_of(40_000, 40_000, [])
    finally:
        resource.setrlimit(resource.RLIMIT_AS, limit)
