"""Collision matrix speed: 10,000 samples on the humanoid against a naive python-fcl loop.

The reference checks the same link pairs (those the matrix samples: not Adjacent, not Default)
with ``fcl.collide`` one by one, after setting every link's transform, for every sample, with the
link poses handed to it for free. It runs on a tenth of the samples and is scaled up (its cost
per sample is constant). Targets: at least 3x faster, and under 1 s on 2 cores. Medians of three
rounds, each timing ours (one worker, then two) and the reference: the first round's warm-up
counts for neither side, and a drift of the host's speed for both.

Memory: the peak memory numpy allocates (tracemalloc) while one block of 16 samples is checked
on a 300-link and a 1,200-link chain (16x the pairs: 44,850 and 719,400): the pairs are checked
in slices of bounded size, so only the per-pair result grows. Target: <= 2x.
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SAMPLES = 10000
REPEATS = 3


def naive(scene, sampled, q) -> tuple[float, float]:
    """Wall and CPU seconds for the per-sample, per-pair python-fcl loop over configurations ``q``."""
    import fcl

    checker = scene.checker
    index = {pair: i for i, pair in enumerate(scene.pairs)}
    rows = [checker.pair_of.tolist().index(index[pair]) for pair in sampled]
    parts = [(checker.pa[row], checker.pb[row]) for row in rows]
    poses = scene.poses(q)
    start, cpu = time.perf_counter(), time.process_time()
    request = fcl.CollisionRequest()
    for sample in poses:
        world = sample[checker.part_link] @ checker.origins
        objects = checker.moving
        for k, pose in enumerate(world):
            objects[k].setTransform(fcl.Transform(pose[:3, :3], pose[:3, 3]))
        for a, b in parts:
            fcl.collide(objects[a], objects[b], request, fcl.CollisionResult())
    return time.perf_counter() - start, time.process_time() - cpu


def tally_memory(links: int) -> tuple[int, int]:
    """(peak bytes numpy allocated checking 16 samples, pairs) on a ``links``-link chain."""
    import tempfile
    import tracemalloc

    sys.path.insert(0, str(ROOT / "benchmarks"))
    import generate

    from urdftool.collision import matrix
    from urdftool.description.load import load

    with tempfile.TemporaryDirectory() as folder:
        # past the command's --max-pairs default (1,200 links: 719,400 pairs): a memory
        # measure, asked for explicitly, as --max-pairs 0 would
        scene = matrix.Scene(load(str(generate.write(Path(folder), links, "chain"))), 0.005,
                             max_pairs=None)
    poses = scene.poses(scene.sample(0, 16))
    checker = scene.checker  # (made when first asked, since session 15: made before, as it was)
    tracemalloc.start()
    checker.tally(poses)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak, len(scene.pairs)


def main() -> list[dict]:
    sys.path.insert(0, str(ROOT))
    import numpy as np

    from urdftool.collision import matrix
    from urdftool.description.load import load

    robot = load(str(ROOT / "robots" / "humanoid" / "humanoid.urdf.xacro"))
    scene = matrix.Scene(robot, 0.005)
    # ours and the reference alternately, medians of each: the host's speed may drift within
    # minutes, and one side timed after the other would compare two hosts
    timings, cpus, references, reference_cpus = {1: [], 2: []}, [], [], []
    q = scene.sample(0, SAMPLES // 10)
    for _ in range(REPEATS):
        for workers in (1, 2):
            start, cpu = time.perf_counter(), time.process_time()
            result = matrix.compute(robot, samples=SAMPLES, seed=0, workers=workers, scene=scene)
            timings[workers].append(time.perf_counter() - start)
            if workers == 1:  # the machine may be shared: CPU time tells both
                cpus.append(time.process_time() - cpu)
        sampled = [(p.link1, p.link2) for p in result.pairs
                   if p.reason not in ("Adjacent", "Default")]
        wall, cpu = naive(scene, sampled, q)
        references.append(10 * wall)
        reference_cpus.append(10 * cpu)
    median = statistics.median
    ours, reference, reference_cpu = median(timings[2]), median(references), median(reference_cpus)
    cpu, timings = median(cpus), {workers: median(t) for workers, t in timings.items()}
    ratio = reference / ours
    name = (f"collision matrix humanoid {SAMPLES} samples [{ours:.2f} s on 2 workers, "
            f"{timings[1]:.2f} s ({cpu:.2f} s CPU) on 1] vs naive fcl loop [{reference:.2f} s, "
            f"{reference_cpu:.2f} s CPU]")
    print(name, f"ratio {ratio:.2f} (CPU time ratio {reference_cpu / cpu:.2f})")
    (small, small_pairs), (large, large_pairs) = tally_memory(300), tally_memory(1200)
    memory = (f"collision tally memory 1,200-link chain [{large >> 20} MiB, {large_pairs} pairs] "
              f"vs 300 links [{small >> 20} MiB, {small_pairs} pairs]")
    print(memory, f"ratio {large / small:.2f}")
    return [{"name": name, "ratio": ratio, "target": ">= 3x, < 1 s",
             "ok": ratio >= 3 and ours < 1, "value": ours, "reference": reference,
             "cpu_one_worker": cpu, "cpu_ratio": reference_cpu / cpu},
            {"name": memory, "ratio": large / small, "target": "<= 2x", "ok": large <= 2 * small}]


if __name__ == "__main__":
    main()
