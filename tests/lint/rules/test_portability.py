"""Each portability rule against its real loader: the robot of the rule's case file
(tests/cases/U9xx_*) is loaded by the loader the rule speaks of (through crosscheck: a worker
process of its own), and the loader must refuse it (an error rule), or load it and show the
change the rule announces (a warning or a note). A loader that changes its behaviour turns its
rule's test red. A loader that is not installed skips, saying which and how to install it.

Gazebo Classic (sdformat 9) and Isaac Sim do not run here: their rules are checked against the
sources they were read in (the Isaac name rule against usd-core's TfMakeValidIdentifier when
usd-core is installed).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import CASES, case_robot, expected_marks

from urdftool.crosscheck import crosscheck
from urdftool.crosscheck.loaders import LOADERS, available
from urdftool.lint.catalogue import TARGET_DECADES
from urdftool.simulators import SIMULATORS

FILE_INERTIA = 0.001667  # the cases' links: 1 kg boxes of 0.1 m


def _refused(*words):
    def check(result):
        assert not result.loaded, f"{result.name} loaded it: the rule says it refuses the file"
        text = f"{result.error}\n{result.output}"
        assert any(word in text for word in words), text[-800:]
    return check


def _loads(check):
    def run(result):
        assert result.loaded, f"{result.name} refused it: {result.error}"
        check(result)
    return run


def _unlimited(joint):
    def check(result):
        assert result.details["joints"][joint] is None, result.details["joints"]
    return check


# code -> what its loader does with the case's robot
EXPECTED = {
    "U920": _refused("Error opening file 'package:/u920_robot"),
    "U921": _refused("no decoder found for mesh file"),
    "U922": _refused("Error opening file"),
    "U923": _loads(lambda r: r.details["geoms"] == 2),  # base's and arm's boxes: no visual
    "U924": _refused("inertia must satisfy A + B >= C"),
    "U925": _refused("mass and inertia of moving bodies must be larger than mjMINVAL"),
    "U926": _loads(_unlimited("shoulder")),
    "U927": _loads(lambda r: "tool0" not in r.links and "tool0" in r.dropped_links),
    "U928": _loads(lambda r: not r.floating_base and "base" not in r.links),
    "U930": _refused("invalid mesh filename extension"),
    "U931": _refused("cannot find 'meshes/cover.stl'"),
    "U932": _refused("cannot find 'u932_meshes/meshes/box.stl'"),
    "U933": _refused("Cannot load URDF file"),
    "U934": _loads(lambda r: r.inertia["tool0"]["mass"] == 1.0),
    "U935": _loads(lambda r: abs(r.inertia["arm"]["inertia"][0] - FILE_INERTIA) > 1e-5),
    "U936": _loads(lambda r: r.details["joints"]["shoulder"] == [1.0, -1.0]),
    "U937": _loads(lambda r: r.details["constraints"] == 0 and r.dof == 2),
    "U940": _refused("MakeConvexHull only applies to .obj, .vtk, and .gltf"),
    "U941": _refused("textures/wood.png", "which does not exist"),
    "U942": _refused("pos_lower_limits.array() <= pos_upper_limits.array()"),
    "U943": _refused("which has 0 DOF cannot mimic"),
    "U944": _loads(lambda r: r.floating_base and r.dof == 7),
    "U950": _loads(lambda r: {"arm", "hand"} <= set(r.dropped_links)),
    "U951": _refused("A model must have at least one link"),
    "U952": _refused("Pose values must be finite"),
    "U953": _refused("has invalid inertia"),
    "U954": _loads(lambda r: "imu_link" in r.dropped_links),
    "U955": _loads(lambda r: r.details["joints"]["shoulder"] == [-1.0, 1.0]),
    "U980": _loads(lambda r: r.dof == 2),
}
# rules whose loader does not run here: where their facts come from
NOT_RUN = {"gazebo": "Gazebo Classic's sdformat 9 is not packaged here: U96x follow its "
                     "parser_urdf.cc, the same code paths as sdformat 12's (U95x, tested)",
           "isaac": "Isaac Sim does not run here: U970 follows its importer's source "
                    "(test_isaac_names_are_usd_identifiers)"}
_VERSIONED = {"U950": "gz@12.3"}  # facts that changed: the version the installed loader is


def _cases():
    for case in sorted(CASES.iterdir()):
        target = TARGET_DECADES.get(case.name[:3])
        if target is not None:
            yield pytest.param(case, id=case.name)


@pytest.mark.integration
@pytest.mark.parametrize("case", list(_cases()))
def test_rule_against_its_loader(case):
    code = case.name[:4]
    target = TARGET_DECADES[code[:3]]
    if target in NOT_RUN:
        pytest.skip(NOT_RUN[target])
    loader = SIMULATORS[target].loader
    if not available(loader):
        pytest.skip(f"{LOADERS[loader].title} is not installed: {LOADERS[loader].install}")
    assert code in EXPECTED, f"{code} has no loader expectation in this test"
    [result] = crosscheck(str(case_robot(case)), [loader]).loaders
    EXPECTED[code](result)
    if not result.loaded and result.location is not None:
        _same_place(case, code, result.location)


def _same_place(case, code, location):
    """The loader's error points where the rule's finding does: at the marked element, at the
    link holding it (a link's name is all MuJoCo and sdformat give), or at a link the finding
    names (sdformat names the link a NaN ends in, the rule the massless inertial causing it)."""
    from conftest import case_targets
    from urdftool.lint.engine import CheckOptions, load_and_check
    from urdftool.lint.options import Selection

    marks = {(file, line) for file, line, mark in expected_marks(case) if mark == code}
    assert Path(location.file).name in {file for file, _ in marks}
    if location.line <= max(line for _, line in marks):
        return
    checked = load_and_check(str(case_robot(case)), CheckOptions(
        selection=Selection(select=(code,), targets=case_targets(case))))
    text = Path(case_robot(case)).read_text().splitlines()[location.line - 1]
    assert any(f"'{name}'" in finding.message for finding in checked.findings
               for name in _names_on(text)), (location, text)


def _names_on(line: str) -> list[str]:
    import re

    return re.findall(r'name="([^"]+)"', line)


def test_every_target_rule_is_tested_or_says_why_not():
    from urdftool.lint.rules import CATALOGUE

    for rule in CATALOGUE:
        if rule.target is not None and rule.target not in NOT_RUN:
            assert rule.code in EXPECTED, f"{rule.code} has no loader test"


def test_isaac_names_are_usd_identifiers():
    """U970's renaming is the importer's makeValidUSDIdentifier: TfMakeValidIdentifier, then "a"
    before a leading "_"."""
    from urdftool.lint.rules.portability import _usd_identifier

    tf = pytest.importorskip("pxr.Tf", reason="usd-core is not installed: pip install usd-core")
    for name in ("arm-joint.1", "2nd_link", "_base", "base_link", "tool 0", "a.b"):
        made = tf.MakeValidIdentifier(name)
        assert _usd_identifier(name) == ("a" + made if made.startswith("_") else made)
