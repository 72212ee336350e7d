"""Benchmark: ``urdftool ik``'s solver against a plain Pinocchio CLIK loop, in the same run.

Targets are the full poses (position and orientation) of random in-limit configurations, so
every one is reachable. The reference is the CLIK loop of Pinocchio's documentation
(examples/inverse-kinematics.py: log6 error, frame Jacobian through Jlog6, damped least squares
``J^T (J J^T + 1e-12 I)^-1 e``, ``integrate``) with a full step (its DT of 0.1 takes ten times the
iterations) on the same reduced limb model, from the same first seed, without joint limits and
without restarts; a solve counts as a success when it ends within the tolerance. urdftool's side is
``ik.solve`` as the command runs it (16 seeds, the first the same, limits respected), and each of
its solutions is re-checked by the vectorised FK. Limbs: the bundled humanoid's arms and legs and
the corpus UR5 (skipped without the corpus).
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

TARGETS = 200
TOLERANCE = 1e-6
TIME_TARGET = 1.5  # urdftool's time per solve / the reference's
SUCCESS_TARGET = 0.99
CORPUS = Path(os.environ.get("URDFTOOL_CORPUS", ROOT.parent / "shared" / "corpus"))


def _reference(chain, goal, start, iterations=1000):
    """Pinocchio's documented CLIK loop on the frame: (converged, iterations, q)."""
    import numpy as np
    import pinocchio as pin

    model, data, frame = chain.model, chain.data, chain.tip_frame
    q = chain.q(start)
    pin.framesForwardKinematics(model, data, q)
    goal = data.oMf[chain.base_frame] * goal  # the base is fixed: the target in the world
    eye = np.eye(6)
    for iteration in range(iterations):
        pin.framesForwardKinematics(model, data, q)
        difference = data.oMf[frame].actInv(goal)
        error = pin.log6(difference).vector
        if error @ error < TOLERANCE * TOLERANCE:
            return True, iteration, q
        jacobian = pin.computeFrameJacobian(model, data, q, frame, pin.LOCAL)
        jacobian = -pin.Jlog6(difference.inverse()) @ jacobian
        velocity = -jacobian.T @ np.linalg.solve(jacobian @ jacobian.T + 1e-12 * eye, error)
        q = pin.integrate(model, q, velocity)
    return False, iterations, q


def _limbs():
    from urdftool.description.load import load

    humanoid = load(ROOT / "robots" / "humanoid" / "humanoid.urdf.xacro")
    limbs = [(f"humanoid {tip}", humanoid, "body_link", tip)
             for tip in ("l_forearm_link", "r_forearm_link", "l_foot_link", "r_foot_link")]
    ur5 = CORPUS / "ur_description" / "urdf" / "ur5.xacro"
    if ur5.is_file():
        limbs.append(("ur5 tool0", load(str(ur5)), "base_link", "tool0"))
    else:
        print(f"corpus not found at {CORPUS}: UR5 skipped")
    return limbs


def _measure(name, robot, base, tip) -> dict:
    import numpy as np

    from urdftool.kinematics import configuration as config
    from urdftool.kinematics import ik
    from urdftool.kinematics.chain import build_chain
    from urdftool.kinematics.fk import forward_kinematics

    chain = build_chain(robot, base, tip)
    if chain.base_moves:
        raise SystemExit(f"{name}: the reference loop needs a fixed base")
    values = config.random(chain.variables, TARGETS, seed=42).values
    rows = np.array([chain.row_of(x) for x in values])
    poses = forward_kinematics(chain.kinematics, config.Configurations(
        chain.kinematics.variables, rows, []), [tip], base).matrices[:, 0]
    targets = [ik.Target(pose[:3, 3], pose[:3, :3]) for pose in poses]
    goals = [target.se3() for target in targets]
    starts = ik.seeds(chain, ik.SEEDS, 0)

    # interleaved, target by target, so that the load of a shared machine falls on both
    solutions, reference, ours, theirs = [], [], 0.0, 0.0
    for target, goal in zip(targets, goals):
        start = time.perf_counter()
        solutions.append(ik.solve(chain, target, starts, TOLERANCE, method="numeric"))
        middle = time.perf_counter()
        reference.append(_reference(chain, goal, starts[0]))
        ours, theirs = ours + middle - start, theirs + time.perf_counter() - middle
    ours, theirs = ours / TARGETS, theirs / TARGETS

    rows = np.array([s.row for s in solutions])
    reached = forward_kinematics(chain.kinematics, config.Configurations(
        chain.kinematics.variables, rows, []), [tip], base).matrices[:, 0]
    rechecked = [s.solved and np.linalg.norm(p[:3, 3] - t.position) <= TOLERANCE
                 for s, p, t in zip(solutions, reached, targets)]
    success = sum(rechecked) / TARGETS
    reference_success = sum(done for done, _, _ in reference) / TARGETS
    # the reference knows no limits: how many of its answers a robot could take (q is x here)
    within = sum(done and bool(np.all(q >= chain.lower - 1e-9) & np.all(q <= chain.upper + 1e-9))
                 for done, _, q in reference) / TARGETS
    ratio = ours / theirs
    iterations = np.mean([s.iterations for s in solutions])
    reference_iterations = np.mean([count for _, count, _ in reference])
    print(f"ik {name} ({len(chain.variables)} joints, {TARGETS} reachable 6-D targets): "
          f"urdftool {ours * 1e3:.2f} ms/solve, {success:.1%} solved (FK re-checked), "
          f"{iterations:.1f} iterations; Pinocchio CLIK {theirs * 1e3:.2f} ms/solve, "
          f"{reference_success:.1%} converged ({within:.1%} within the limits), "
          f"{reference_iterations:.1f} iterations; "
          f"ratio {ratio:.2f} (target <= {TIME_TARGET})")
    return {"name": f"ik_{name.replace(' ', '_')}", "ratio": ratio, "target": TIME_TARGET,
            "ok": ratio <= TIME_TARGET and success >= SUCCESS_TARGET, "success": success,
            "reference_success": reference_success, "reference_within_limits": within, "urdftool_s": ours, "pinocchio_s": theirs,
            "iterations": float(iterations), "reference_iterations": float(reference_iterations)}


def main() -> list[dict]:
    return [_measure(*limb) for limb in _limbs()]


if __name__ == "__main__":
    main()
