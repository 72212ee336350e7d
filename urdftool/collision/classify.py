"""The collision matrix of a robot, checked against an SRDF: what ``urdftool collisions
--matrix`` computes (writing files is the caller's business)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from urdftool.collision.matrix import MAX_PAIRS, Matrix, compute
from urdftool.collision.srdf import Stale, read, stale


@dataclass(frozen=True)
class MatrixOptions:
    """How to sample (see urdftool.collision.matrix.compute) and which SRDF to audit.

    check_srdf: an SRDF whose disable_collisions the matrix is compared with; None: none
    """

    samples: int = 10000
    seed: int = 0
    min_fraction: float = 0.95
    margin: float = 0.005
    until_converged: bool = False
    max_samples: int = 160000
    workers: int | None = None
    check_srdf: Path | None = None
    max_pairs: int | None = MAX_PAIRS


@dataclass
class MatrixOutcome:
    """The classified pairs and the SRDF entries they show to be stale."""

    matrix: Matrix
    stale: list[Stale] = field(default_factory=list)


def classify(robot, options: MatrixOptions = MatrixOptions(),
             on_progress: Callable[[int, int], None] | None = None) -> MatrixOutcome:
    """Classify every pair of ``robot``'s links with geometry, then audit ``check_srdf``.

    on_progress: called with (samples done, samples planned) as sampling advances
    Raises SrdfError when ``check_srdf`` cannot be read.
    """
    result = compute(robot, options.samples, options.seed, options.min_fraction, options.margin,
                     options.until_converged, options.max_samples, options.workers, on_progress,
                     max_pairs=options.max_pairs)
    found = []
    if options.check_srdf:
        entries, root = read(options.check_srdf)
        found = stale(result, entries, robot.links, root)
    return MatrixOutcome(result, found)
