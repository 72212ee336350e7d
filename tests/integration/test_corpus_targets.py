"""The proof of issue 33 on six robots nobody here wrote (ANYmal C, TALOS, iCub, PR2, Solo12,
UR5e from ../shared/corpus): each is loaded with every real loader installed (crosscheck, one
worker process each), and every load that fails must be predicted by ``check --target`` for that
loader, with an error at the line the loader points at (or, when the loader names no place, an
error somewhere in the robot). The table printed with ``-s`` is the one in docs/targets.md.

The loaders are also run by hand (a plain ``python -c`` per loader, as a user would) and must
give crosscheck's verdict.
"""

from __future__ import annotations

import functools
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import CORPUS

from urdftool.crosscheck import crosscheck
from urdftool.crosscheck.loaders import LOADERS, available

ROBOTS = {
    "ANYmal C": "example-robot-data/robots/anymal_c_simple_description/urdf/anymal.urdf",
    "TALOS": "example-robot-data/robots/talos_data/robots/talos_full_v2.urdf",
    "iCub": "example-robot-data/robots/icub_description/robots/icub.urdf",
    "PR2": "example-robot-data/robots/pr2_description/urdf/pr2.urdf",
    "Solo12": "example-robot-data/robots/solo_description/robots/solo12.urdf",
    "UR5e": "ur_description/urdf/ur5e.xacro",
}
# the version of each installed loader's facts (sdformat 12's differ from the newest)
TARGET_OF = {"mujoco": "mujoco", "pybullet": "pybullet", "drake": "drake",
             "sdformat": "gz@12.3", "pinocchio": "pinocchio"}

pytestmark = pytest.mark.skipif(CORPUS is None or not (CORPUS / ROBOTS["PR2"]).is_file(),
                                reason="the corpus (../shared/corpus) is not here")


@functools.cache
def _crosscheck(robot: str):
    """crosscheck's report on ``robot`` with every loader installed, made once per test process:
    both tests below read it (each loader's verdict is its own worker's)."""
    return crosscheck(str(CORPUS / ROBOTS[robot]), [name for name in LOADERS if available(name)])


def _check(path: Path, target: str):
    from urdftool.lint.runner import check_paths

    run = check_paths([str(path)], targets=(target,), timeout=0, jobs=1, use_settings=False)
    [result] = run.results
    return [f for f in result.findings if f.target is not None and f.severity.value == "error"]


@pytest.mark.parametrize("robot", list(ROBOTS))
def test_every_load_failure_is_predicted_at_its_line(robot, capsys):
    path = CORPUS / ROBOTS[robot]
    report = _crosscheck(robot)
    rows = []
    for result in report.loaders:
        if result.loaded:
            rows.append(f"{robot} | {result.name} | loads |")
            continue
        errors = _check(path, TARGET_OF[result.name])
        assert errors, f"{result.name} fails on {robot} ({result.error}) and check --target " \
                       f"{TARGET_OF[result.name]} predicts nothing"
        where = result.location
        if where is not None:
            # at that line, or about the link the loader names there (MuJoCo and sdformat name
            # a link: the rule points into it, at the <inertia> or <inertial> at fault)
            named = _link_on(where)
            at = [f for f in errors if Path(f.file).resolve() == Path(where.file).resolve()
                  and (f.line == where.line or (named and f"'{named}'" in f.message))]
            assert at, (f"{result.name} fails on {robot} at {where}, where check --target "
                        f"{TARGET_OF[result.name]} has no error: "
                        f"{sorted({(f.file, f.line, f.code) for f in errors})[:8]}")
            rows.append(f"{robot} | {result.name} | fails at {where} | {at[0].code}")
        else:
            rows.append(f"{robot} | {result.name} | fails ({result.error[:60]}) | "
                        f"{errors[0].code} at {errors[0].location}")
    with capsys.disabled():
        print("\n" + "\n".join(rows))


def _link_on(where) -> str | None:
    import re

    line = Path(where.file).read_text(errors="replace").splitlines()[where.line - 1]
    found = re.search(r'<link\s+name="([^"]+)"', line)
    return found.group(1) if found else None


BY_HAND = {
    "mujoco": "import mujoco, sys; m = mujoco.MjModel.from_xml_path(sys.argv[1]); "
              "print(round(float(sum(m.body_mass)), 6))",
    "pinocchio": "import pinocchio, sys; m = pinocchio.buildModelFromUrdf(sys.argv[1]); "
                 "print(round(float(sum(i.mass for i in m.inertias)), 6))",
    "pybullet": "import pybullet as p, sys; p.connect(p.DIRECT); b = p.loadURDF(sys.argv[1]); "
                "print(round(sum(p.getDynamicsInfo(b, i)[0] for i in range(-1, "
                "p.getNumJoints(b))), 6))",
}


@pytest.mark.parametrize("robot", [r for r in ROBOTS if not ROBOTS[r].endswith(".xacro")])
@pytest.mark.parametrize("loader", list(BY_HAND))
def test_crosscheck_agrees_with_the_loader_run_by_hand(robot, loader):
    if not available(loader):
        pytest.skip(f"{loader} is not installed: {LOADERS[loader].install}")
    path = str(CORPUS / ROBOTS[robot])
    done = subprocess.run([sys.executable, "-c", BY_HAND[loader], path], capture_output=True,
                          text=True, timeout=300)
    [result] = [result for result in _crosscheck(robot).loaders if result.name == loader]
    assert result.loaded == (done.returncode == 0), (done.stderr[-400:], result.error)
    if result.loaded:
        import re

        by_hand = float(re.findall(r"-?\d+\.?\d*(?:e-?\d+)?$", done.stdout.strip())[-1])
        assert abs(by_hand - result.mass) < 1e-6
