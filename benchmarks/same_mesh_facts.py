"""Every mesh fact before and after a change to mesh reading, to the bit.

    python benchmarks/same_mesh_facts.py record FILE    # before the change
    python benchmarks/same_mesh_facts.py compare FILE   # after it: exit 1 on any difference
    python benchmarks/same_mesh_facts.py record FILE --sweep 4  # and every 4th sweep mesh

Each STL, COLLADA and OBJ file of the corpus (../shared/corpus or URDFTOOL_CORPUS), and with
``--sweep N`` every Nth of /work/sweep-repos (or URDFTOOL_SWEEP), is measured as a check
measures it (:func:`urdftool.description.meshes.measures._facts_outcome`, the run cache
cleared each time) at four scales and orders of asking: the triangle count, bounds, extents,
vertices, faces, watertightness, mass properties, inner points (before and after merging),
inner volume, the problem raised, and the arrays read (:func:`.mesh_arrays.read_unmerged`).
Each fact is hashed to the bit (dtype, shape, bytes); FILE keeps the hashes. Findings are
compared by same_findings.py; this compares what they are made of, mesh by mesh.
"""

from __future__ import annotations

import hashlib
import json
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
CORPUS = Path(os.environ.get("URDFTOOL_CORPUS", ROOT.parent / "shared" / "corpus"))
SWEEP = Path(os.environ.get("URDFTOOL_SWEEP", "/work/sweep-repos"))
SUFFIXES = (".stl", ".dae", ".obj")
# (scale, inner points asked before merging)
ASKED = [((1.0, 1.0, 1.0), True), ((1.0, 1.0, 1.0), False), ((0.001, 0.001, 0.001), True),
         ((-1.0, 1.0, 2.0), True)]


def meshes(sweep_every: int) -> list[Path]:
    found = sorted(p for p in CORPUS.rglob("*") if p.suffix.lower() in SUFFIXES and p.is_file())
    if sweep_every and SWEEP.is_dir():
        swept = sorted(p for p in SWEEP.rglob("*") if p.suffix.lower() in SUFFIXES and
                       p.is_file() and not p.is_symlink())
        found += swept[::sweep_every]
    return found


def _hashed(value):
    import numpy as np

    if isinstance(value, dict):
        return {key: _hashed(item) for key, item in sorted(value.items())}
    if isinstance(value, (list, tuple)):
        return [_hashed(item) for item in value]
    if isinstance(value, np.ndarray):
        array = np.ascontiguousarray(value)
        return hashlib.sha256(repr((array.dtype.str, array.shape)).encode() +
                              array.tobytes()).hexdigest()[:20]
    if isinstance(value, (float, np.floating)):
        return np.float64(value).tobytes().hex()
    return repr(value)


def facts_of(path: Path) -> list:
    """The hashed facts of one mesh file at each of :data:`ASKED`."""
    import numpy as np

    from urdftool.description import mesh_arrays
    from urdftool.description.inputs import MeshLimits
    from urdftool.description.meshes import measures, run_cache
    from urdftool.errors import MeshProblem

    found = []
    for scale, inner_first in ASKED:
        run_cache.clear()
        try:
            facts = measures._facts_outcome(None, str(path), scale, MeshLimits())
            if isinstance(facts, MeshProblem):
                found.append(["problem", facts.kind, str(facts)])
                continue
            got = [facts.faces, facts.bounds, facts.extents, facts.moderate,
                   sorted(facts.metadata.items()), facts.nbytes]
            asks = ["vertices", "inner_points"]
            asks = (asks[::-1] if inner_first else asks) + \
                ["is_watertight", "mass_properties", "inner_volume"]
            for name in asks:
                try:
                    with np.errstate(all="ignore"):
                        got.append((name, getattr(facts, name)))
                except Exception as error:  # what a fact raises is a fact too
                    got.append((name, "raises", type(error).__name__, str(error)))
            got.append(("faces", facts._faces))
            found.append(_hashed(got))
        except Exception as error:
            found.append(["raises", type(error).__name__, str(error)[:300]])
    try:
        read = mesh_arrays.read_unmerged(path, path.read_bytes())
        if read is not None and read[1] is None:  # each three corners a triangle: as an array
            import numpy as np

            read = (read[0], np.arange(len(read[0])).reshape(-1, 3))
        found.append(_hashed(list(read) if read is not None else None))
    except Exception as error:
        found.append(["read raises", type(error).__name__, str(error)[:300]])
    return found


def main() -> int:
    verb, kept = sys.argv[1], Path(sys.argv[2])
    every = int(sys.argv[sys.argv.index("--sweep") + 1]) if "--sweep" in sys.argv else 0
    from urdftool.description.meshes import measures

    measures.resolve = lambda robot, uri: Path(uri)  # each path is the mesh itself
    start = time.process_time()
    found = {str(path): facts_of(path) for path in meshes(every)}
    seconds = time.process_time() - start
    if verb == "record":
        kept.write_text(json.dumps(found, indent=0))
        print(f"{len(found)} meshes recorded ({seconds:.1f} s cpu)")
        return 0
    before = json.loads(kept.read_text())
    differ = [path for path in before if found.get(path) != before[path]]
    missing = sorted(set(before) ^ set(found))
    for path in differ[:20]:
        print(f"DIFFERENT {path}\n  before {before[path]}\n  after  {found.get(path)}")
    print(f"{len(found)} meshes: {len(differ)} differ, {len(missing)} in one run only "
          f"({seconds:.1f} s cpu)")
    return 1 if differ or missing else 0


if __name__ == "__main__":
    sys.exit(main())
