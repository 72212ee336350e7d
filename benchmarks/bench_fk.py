"""Benchmark: ``urdftool fk --q-file`` with 10,000 rows on the humanoid against raw Pinocchio.

The reference is Pinocchio's own forwardKinematics + updateFramePlacements over the same
configurations (already converted to Pinocchio vectors), in a Python loop; urdftool's side reads
the CSV file and parses it (timed apart: Python float parsing of 200,000 cells is a cost Pinocchio's
side does not pay) and computes every link pose. CPU time of this process (one BLAS thread, as the
command runs), the two sides alternating, medians of :data:`REPEATS` (on a shared machine the
speed drifts within seconds: a best-of-3 of each side taken apart read 1.4x and 2.6x for the same
code).
"""

from __future__ import annotations

import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

ROWS = 10_000
TARGET = 2.0
REPEATS = 7


def _alternating(functions: dict, repeats: int = REPEATS) -> dict:
    """name -> the CPU times [s] of each of ``functions`` (name -> function), called in turn
    ``repeats`` times."""
    found = {name: [] for name in functions}
    for _ in range(repeats):
        for name, function in functions.items():
            start = time.process_time()
            function()
            found[name].append(time.process_time() - start)
    return found


def _text(samples: list[float]) -> str:
    return (f"{statistics.median(samples) * 1e3:.1f} ms cpu "
            f"[{min(samples) * 1e3:.1f}-{max(samples) * 1e3:.1f}]")


# The command's reference: the plainest script printing the same poses with Pinocchio (its
# model from the URDF, forwardKinematics and updateFramePlacements per row, every body frame's
# position, roll-pitch-yaw and quaternion, numpy's text writer at six decimals)
PLAIN_SCRIPT = """
import sys, numpy as np, pinocchio
model = pinocchio.buildModelFromXML(open(sys.argv[1]).read())
data, q = model.createData(), np.load(sys.argv[2])
frames = [i for i, f in enumerate(model.frames) if f.type == pinocchio.FrameType.BODY]
rows = []
for row in q:
    pinocchio.forwardKinematics(model, data, row)
    pinocchio.updateFramePlacements(model, data)
    for i in frames:
        pose = data.oMf[i]
        rows.append([*pose.translation, *pinocchio.rpy.matrixToRpy(pose.rotation),
                     *pinocchio.Quaternion(pose.rotation).coeffs()])
np.savetxt(sys.stdout, np.array(rows), fmt="%.6f")
"""


def _command(model, path: Path, q, folder: str) -> dict:
    """``urdftool fk --q-file`` to a pipe (text tables) against :data:`PLAIN_SCRIPT`: median
    CPU times of the child processes, alternating (benchmarks/timing.py)."""
    import numpy as np

    from benchmarks.timing import alternating, load

    urdf, saved = Path(folder) / "humanoid.urdf", Path(folder) / "q.npy"
    urdf.write_text(model.robot.urdf)
    np.save(saved, q)
    urdftool = str(Path(sys.executable).parent / "urdftool")
    found = alternating({"fk": [urdftool, "fk", str(ROOT / "robots" / "humanoid" /
                                                    "humanoid.urdf.xacro"), "--q-file", str(path)],
                         "plain": [sys.executable, "-c", PLAIN_SCRIPT, str(urdf), str(saved)]}, 3)
    ratio = found["fk"].median / found["plain"].median
    print(f"fk --q-file {ROWS} rows, text: {found['fk'].text()}; plain Pinocchio script "
          f"{found['plain'].text()}; {ratio:.2f}x; {load()}")
    return {"name": f"fk --q-file {ROWS} rows, text [{found['fk'].median:.2f} s cpu] vs a plain "
                    f"Pinocchio script [{found['plain'].median:.2f} s] ({load()})",
            "ratio": ratio, "target": TARGET, "ok": ratio <= TARGET,
            "detail": f"goal <= {TARGET}x; ours {found['fk'].text()}; reference "
                      f"{found['plain'].text()}"}


def main() -> list[dict]:
    from urdftool.budget import one_blas_thread

    one_blas_thread()  # before numpy's import, as the command does
    import numpy as np
    import pinocchio

    from urdftool.kinematics import configuration as config
    from urdftool.kinematics.fk import KinematicModel, forward_kinematics
    from urdftool.description.load import load

    model = KinematicModel(load(ROOT / "robots" / "humanoid" / "humanoid.urdf.xacro"))
    values = config.random(model.variables, ROWS, seed=0).values
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "q.csv"
        lines = [",".join(v.name for v in model.variables)]
        lines += [",".join(repr(float(x)) for x in row) for row in values]
        path.write_text("\n".join(lines) + "\n")

        configurations = config.from_file(model.variables, str(path))

        def parse():
            return config.from_file(model.variables, str(path))

        def ours():
            return forward_kinematics(model, configurations)

        q = model.pinocchio_q(values)
        data = model.model.createData()

        def raw():
            for row in q:
                pinocchio.forwardKinematics(model.model, data, row)
                pinocchio.updateFramePlacements(model.model, data)

        result = ours()
        assert result.matrices.shape == (ROWS, len(model.links), 4, 4)
        raw()
        check = data.oMf[model.model.getFrameId(model.links[-1])].homogeneous
        assert np.allclose(result.matrices[-1, -1], check, atol=1e-12)
        found = _alternating({"ours": ours, "raw": raw, "parse": parse})
        command = _command(model, path, q, folder)
    ours_time, raw_time, parse_time = (statistics.median(found[name])
                                       for name in ("ours", "raw", "parse"))
    ratio = ours_time / raw_time
    with_parsing = (ours_time + parse_time) / raw_time
    print(f"fk --q-file {ROWS} rows on the humanoid: urdftool FK {ours_time * 1e3:.1f} ms "
          f"(+ {parse_time * 1e3:.1f} ms reading the CSV), raw Pinocchio {raw_time * 1e3:.1f} ms,"
          f" ratio {ratio:.2f} (target <= {TARGET}); with reading {with_parsing:.2f}")
    return [{"name": "fk_q_file_10000_rows", "ratio": ratio, "target": TARGET,
             "detail": f"goal <= {TARGET}x; ours {_text(found['ours'])}; reference "
                       f"{_text(found['raw'])}; reading the CSV {_text(found['parse'])}",
             "ratio_with_reading": with_parsing, "urdftool_s": ours_time,
             "reading_s": parse_time, "pinocchio_s": raw_time, "rows": ROWS}, command]


if __name__ == "__main__":
    main()
