"""Every robot of the public corpus is checked: no crash, the real defects found, and whatever
urdftool passes must load in Pinocchio and yourdfpy (otherwise urdftool missed something).
The findings come from the shared ``corpus_run`` (tests/conftest.py)."""

from __future__ import annotations

import io

import pytest

from conftest import corpus_entry_points, entry_id

ENTRIES = corpus_entry_points()
pytestmark = pytest.mark.skipif(not ENTRIES, reason="corpus not available")

# Real defects in the public files, by the foundation's rule families (U0 loading, U1 tree,
# U2 joints). Everything not listed must have no finding from these families.
KNOWN = {
    # committed generated URDF that still holds <xacro:grey/> elements
    "robotis_op_description/robots/robotis_op.urdf": {"U007"},
    # a .urdf that is really xacro (${...} values)
    "sam_bot_description/src/description/sam_bot_description.urdf": {"U007"},
    # pre-2019 un-prefixed macros: current xacro stops with "unknown macro name"
    "robotis_op_description/robots/robotis_op.urdf.xacro": {"U005"},
    # includes through package:// and a wrong folder
    "example-robot-data/robots/hector_description/robots/quadrotor_base.xacro": {"U005"},
    # revolute joints whose <limit> has no lower/upper: frozen at 0
    "example-robot-data/robots/quadruped_description/urdf/quadruped.urdf": {"U215"},
    # joint1 declared revolute with effort=0 velocity=0 and no range
    "example-robot-data/robots/double_pendulum_description/urdf/double_pendulum.urdf":
        {"U212", "U215"},
    "example-robot-data/robots/double_pendulum_description/urdf/double_pendulum_simple.urdf":
        {"U212", "U215"},
    "example-robot-data/robots/double_pendulum_description/urdf/double_pendulum_continuous.urdf":
        {"U212"},
    # rotor joints with effort=0 velocity=0
    "example-robot-data/robots/iris_description/robots/iris.urdf": {"U212"},
    # the gripper joints carry a second <limit> that is silently ignored
    "urdf_sim_tutorial/urdf/12-gripper.urdf.xacro": {"U214"},
    "urdf_sim_tutorial/urdf/13-diffdrive.urdf.xacro": {"U214"},
    "ros2/urdf_sim_tutorial/urdf/12-gripper.urdf.xacro": {"U214"},
    "ros2/urdf_sim_tutorial/urdf/12a-mimic-gripper.urdf.xacro": {"U214"},
    "ros2/urdf_sim_tutorial/urdf/13-diffdrive.urdf.xacro": {"U214"},
}
FOUNDATION = ("U0", "U1", "U2", "U9")


@pytest.mark.parametrize("entry", ENTRIES, ids=entry_id)
def test_corpus_robot_findings(entry, corpus_run):
    _, result = corpus_run[entry_id(entry)]
    assert not [f for f in result.findings if f.code == "U900"], result.findings
    codes = {f.code for f in result.findings if f.code.startswith(FOUNDATION)
             and not f.code.startswith("U02")}  # the vocabulary: test_corpus_vocabulary.py
    path, args = entry
    expected = KNOWN.get(path, set())
    if path.endswith("/ur.xacro") and not args:
        expected = {"U005"}  # robot_model and the *_params args are required
    assert codes == expected, [f"{f.location} {f.code} {f.message}" for f in result.findings]


@pytest.mark.parametrize("entry", ENTRIES, ids=entry_id)
def test_what_passes_loads_in_pinocchio_and_yourdfpy(entry, corpus_run):
    pinocchio = pytest.importorskip("pinocchio")
    yourdfpy = pytest.importorskip("yourdfpy")
    _, result = corpus_run[entry_id(entry)]
    if result.robot is None or any(f.severity.value == "error" for f in result.findings):
        pytest.skip("urdftool reports errors")
    model = pinocchio.buildModelFromXML(result.robot.urdf)
    assert model.njoints >= 1
    parsed = yourdfpy.URDF.load(io.StringIO(result.robot.urdf), load_meshes=False,
                                build_collision_scene_graph=False)
    assert set(parsed.link_map) == set(result.robot.links)
