"""The self-collision matrix, classified the way MoveIt's Setup Assistant does, with convergence.

Every pair of links with collision geometry gets one class, checked in this order:

- ``Adjacent``: joined by a joint, or by a chain of joints through links without geometry;
- ``Default``: colliding in the default configuration (0, or mid-range where 0 is outside);
- ``Always``: colliding in at least ``min_fraction`` of the sampled configurations;
- ``Never``: never seen colliding, and never closer than ``margin`` (MoveIt has no margin: it
  disables pairs that came within a hair of touching);
- ``""`` (enabled): everything else; the planner must check it.

Adjacent and Default pairs are not sampled (MoveIt does not sample them either). Sampling runs in
fixed blocks, each with its own random stream derived from the seed, so the result depends only
on the seed and the sample count, not on the number of worker processes.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from functools import cached_property
from typing import Callable

import numpy as np

from urdftool.collision import geometry as geometry_module
from urdftool.collision.pairs import PairChecker, Tally
from urdftool.description.urdf import MOVING
from urdftool.kinematics.tree import adjacent_pairs, pair_key

CLASSES = ("Adjacent", "Default", "Always", "Never", "")
BLOCK = 250
# Link pairs a scene is built for: 708 links with collision geometry. Every check of a scene
# costs in proportion to its pairs (memory and time): the limit is checked before anything is
# built. At 244,650 pairs `collisions --matrix` peaks at 0.34 GB; 1,500 links (1.1 million
# pairs) peaked at 0.85 to 1.56 GB.
MAX_PAIRS = 250_000


@dataclass(slots=True)
class PairResult:
    """One pair of links: class, how often it collided and how close it came.

    min_distance: smallest distance seen in [m]; exact whenever it is below the margin, and an
        upper bound of the true minimum otherwise (FCL is only asked about near pairs)
    """

    link1: str
    link2: str
    reason: str
    collisions: int = 0
    samples: int = 0
    min_distance: float | None = None

    @property
    def fraction(self) -> float:
        return self.collisions / self.samples if self.samples else 0.0

    @property
    def disabled(self) -> bool:
        return self.reason != ""


@dataclass
class Matrix:
    """The classified pairs, sorted as MoveIt writes them, and how settled the result is."""

    pairs: list[PairResult]
    links: list[str]
    samples: int
    seed: int
    margin: float
    min_fraction: float
    unsettled: list[tuple[str, str, str, str]] = field(default_factory=list)
    rounds: list[tuple[int, int]] = field(default_factory=list)
    visual_only: list[str] = field(default_factory=list)
    problems: list = field(default_factory=list)
    assumed: list[str] = field(default_factory=list)  # Geometry.assumed: meshes read assuming

    @property
    def converged(self) -> bool:
        return not self.unsettled

    def pair(self, one: str, two: str) -> PairResult | None:
        key = tuple(sorted((one, two)))
        return next((p for p in self.pairs if (p.link1, p.link2) == key), None)


class Scene:
    """Everything the checks need, built once per robot: geometry, kinematics, link pairs.

    Configurations are rows of values of ``variables`` (urdftool.kinematics.configuration).
    Floating and planar joints are held at their origin: a self-collision matrix does not
    depend on where the base is.
    """

    def __init__(self, robot, margin: float, max_pairs: int | None = MAX_PAIRS):
        """OverLimit, before anything is built, when the links holding ``<collision>`` make
        more than ``max_pairs`` pairs (None: no limit)."""
        from urdftool.kinematics.fk import KinematicModel

        check_pairs(robot, max_pairs)
        self.robot = robot
        self.geometry = geometry_module.build(robot)
        self.kinematics = KinematicModel(robot)
        self.variables = self.kinematics.variables
        self.margin = margin
        links = [name for name in self.kinematics.links if name in self.geometry.parts]
        self.links = links
        self._link_indices = [self.kinematics.links.index(name) for name in links]
        self._held = {v.name for v in self.variables if v.kind not in MOVING}
        self.pairs = [pair_key(a, b) for i, a in enumerate(links) for b in links[i + 1:]]
        self.pairs.sort(key=lambda pair: (pair[0].encode(), pair[1].encode()))
        self.adjacent = adjacent_pairs(robot, set(links))

    @cached_property
    def checker(self) -> PairChecker:
        """FCL objects for every pair of :attr:`pairs`, made when first asked: the matrix and
        ``diff`` each make their own for the pairs they ask about."""
        return PairChecker(self.geometry, self.links, self.pairs, self.margin)

    def default(self) -> np.ndarray:
        """MoveIt's default state: 0 where the limits allow it, else the middle of the range."""
        from urdftool.kinematics import configuration

        return configuration.defaults(self.variables)

    def sample(self, seed, count: int) -> np.ndarray:
        """``count`` configurations drawn within the limits from the stream of ``seed``."""
        from urdftool.kinematics import configuration

        return configuration.random(self.variables, count, seed, hold=self._held).values

    def poses(self, q: np.ndarray) -> np.ndarray:
        """Poses ``[rows, links, 4, 4]`` of ``self.links`` for configurations ``q``."""
        return self.kinematics.link_poses(q, self._link_indices)

    def at(self, q: np.ndarray) -> np.ndarray:
        return self.poses(q[None])[0]


def check_pairs(robot, max_pairs: int | None = MAX_PAIRS) -> None:
    """OverLimit when the links of ``robot`` holding a ``<collision>`` (an upper bound of those
    with collision geometry) make more than ``max_pairs`` pairs; None: no limit."""
    from urdftool.errors import OverLimit

    links = sum(1 for link in robot.links.values() if link.find("collision") is not None)
    pairs = links * (links - 1) // 2
    if max_pairs is not None and pairs > max_pairs:
        raise OverLimit(f"{links} links with collision geometry",
                        pairs, max_pairs, "pairs")


def default_collisions(scene: Scene, q: np.ndarray) -> set[tuple[str, str]]:
    poses = scene.at(q)
    tally = scene.checker.tally(poses[None], distances=False)
    return {pair for pair, hits in zip(scene.pairs, tally.collisions) if hits}


# Worker state: set in the parent before the pool forks, so children inherit the FCL objects.
_WORK: dict = {}


def _run_block(block: int) -> Tally:
    scene = _WORK["scene"]
    q = scene.sample([_WORK["seed"], block], BLOCK)
    return _WORK["checker"].tally(scene.poses(q), block * BLOCK)


def _sample_blocks(pool, blocks: range, pairs: int, progress) -> Tally:
    """Tally over ``blocks`` (in a worker pool when there is one), merged in block order."""
    total = Tally.empty(pairs)
    for tally in (pool.imap(_run_block, blocks) if pool else map(_run_block, blocks)):
        total = total.merge(tally)
        progress(tally.samples)
    return total


def _pool(workers: int):
    """A pool of forked workers that inherit ``_WORK``, or None to work in this process."""
    import contextlib
    import multiprocessing

    if workers < 2 or "fork" not in multiprocessing.get_all_start_methods():
        return contextlib.nullcontext(None)
    return multiprocessing.get_context("fork").Pool(workers)


def compute(robot, samples: int = 10000, seed: int = 0, min_fraction: float = 0.95,
            margin: float = 0.005, until_converged: bool = False, max_samples: int = 160000,
            workers: int | None = None, progress: Callable[[int, int], None] | None = None,
            scene: Scene | None = None, max_pairs: int | None = MAX_PAIRS) -> Matrix:
    """Classify every pair of links with geometry; see the module docstring.

    samples: configurations to sample (rounded up to whole blocks of 250)
    margin: a pair that came closer than this in [m] is never marked Never
    until_converged: double the samples until no pair changed class in the second half
    progress: called with (samples done, samples planned) as blocks finish
    max_pairs: OverLimit, before any work, for more link pairs (None: no limit)
    """
    scene = scene or Scene(robot, margin, max_pairs)
    workers = workers or min(2, os.cpu_count() or 1)
    classes = {pair: "" for pair in scene.pairs}
    for pair in scene.adjacent:
        classes[pair] = "Adjacent"
    for pair in default_collisions(scene, scene.default()):
        if not classes[pair]:
            classes[pair] = "Default"
    sampled = [pair for pair in scene.pairs if not classes[pair]]
    checker = PairChecker(scene.geometry, scene.links, sampled, margin)
    blocks = max(2, -(-samples // BLOCK))
    blocks += blocks % 2
    done = 0
    planned = blocks * BLOCK
    # no more worker processes than blocks to draw, ever (--workers 10**18 forked until the
    # budget stopped it, for 40 blocks)
    workers = min(workers, max(blocks, -(-max_samples // BLOCK) if until_converged else 0))

    def advance(count: int) -> None:
        nonlocal done
        done += count
        if progress:
            progress(done, planned)

    _WORK.update(scene=scene, seed=seed, checker=checker)
    with _pool(workers) as pool:
        half = _sample_blocks(pool, range(blocks // 2), len(sampled), advance)
        full = half.merge(_sample_blocks(pool, range(blocks // 2, blocks), len(sampled), advance))
        rounds = []
        while True:
            before = _classify(half, min_fraction, margin)
            after = _classify(full, min_fraction, margin)
            unsettled = [(*sampled[i], before[i], after[i]) for i in range(len(sampled))
                         if before[i] != after[i]]
            rounds.append((full.samples, len(unsettled)))
            if not until_converged or not unsettled or blocks * 2 * BLOCK > max_samples:
                break
            planned = blocks * 2 * BLOCK
            half = full
            full = half.merge(_sample_blocks(pool, range(blocks, blocks * 2), len(sampled),
                                             advance))
            blocks *= 2
    distances = _distances(scene, checker, full, seed)
    sampled_index = {pair: i for i, pair in enumerate(sampled)}
    results = []
    for pair in scene.pairs:
        result = PairResult(*pair, classes[pair])
        i = sampled_index.get(pair)
        if i is not None:
            result.reason = after[i]
            result.collisions, result.samples = int(full.collisions[i]), full.samples
            result.min_distance = distances[i]
        results.append(result)
    return Matrix(results, scene.links, full.samples, seed, margin, min_fraction, unsettled,
                  rounds, scene.geometry.visual_only, scene.geometry.problems,
                  scene.geometry.assumed)


def _classify(tally: Tally, min_fraction: float, margin: float) -> list[str]:
    fraction = tally.collisions / max(tally.samples, 1)
    return ["Always" if f >= min_fraction else
            ("Never" if c == 0 and d >= margin else "")
            for f, c, d in zip(fraction, tally.collisions, tally.min_distance)]


def _distances(scene: Scene, checker: PairChecker, tally: Tally, seed) -> list[float]:
    """Exact distances where known; for pairs FCL never saw, the distance at the sample where
    the bounding spheres came closest (an upper bound of the smallest distance). Each block of
    samples is drawn and posed once, not once per pair (a large robot has a million such
    pairs)."""
    result = [float(distance) for distance in tally.min_distance]
    # (a pair no sample bounded, its sample -1, keeps its distance unknown: block -1 was drawn
    # as the seed [seed, -1], which numpy refused: "--seed must be an integer ... not 0")
    unseen = np.nonzero(~np.isfinite(tally.min_distance) & (tally.bound_sample >= 0))[0]
    order = unseen[np.argsort(tally.bound_sample[unseen], kind="stable")]
    block_poses = (None, None)
    for i in order:
        block, offset = divmod(int(tally.bound_sample[i]), BLOCK)
        if block_poses[0] != block:
            block_poses = (block, checker.part_poses(scene.poses(scene.sample([seed, block],
                                                                              BLOCK))))
        result[i] = float(checker.exact(None, int(i), part_poses=block_poses[1][offset])[1])
    return result
