"""D-H tables: the matrices, extraction against published tables, FK from tables, the CLI."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import yaml

from conftest import ROBOTS, corpus_or_skip
from urdftool.kinematics import configuration as config
from urdftool.kinematics import dh
from urdftool.kinematics.fk import KinematicModel
from urdftool.description.load import load

HUMANOID = ROBOTS / "humanoid" / "humanoid.urdf.xacro"
PI_2 = math.pi / 2

# Published tables. UR5 (Universal Robots, standard D-H): the signs of a and alpha are UR's.
UR5 = {"d": [0.089159, 0, 0, 0.10915, 0.09465, 0.0823], "a": [0, -0.425, -0.39225, 0, 0, 0],
       "alpha": [PI_2, 0, 0, PI_2, -PI_2, 0]}
# Franka Panda (Franka's documentation, Craig's modified D-H), joints 1-7 without the flange.
PANDA = {"a": [0, 0, 0, 0.0825, -0.0825, 0, 0.088], "d": [0.333, 0, 0.316, 0, 0.384, 0, 0],
         "alpha": [0, -PI_2, PI_2, PI_2, -PI_2, PI_2, PI_2]}

LIMBS = [("body_link", "l_foot_link"), ("body_link", "r_foot_link"),
         ("body_link", "l_forearm_link"), ("body_link", "r_forearm_link"),
         ("body_link", "head_link"), ("base_link", "l_foot_link")]


@pytest.fixture(scope="module")
def humanoid():
    return load(HUMANOID)


@pytest.fixture(scope="module")
def humanoid_model(humanoid):
    return KinematicModel(humanoid)


def _worst_errors(robot, model, table, count=200, seed=7):
    return dh.verify(table, model, config.random(model.variables, count, seed))


def _rot_z(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def _rot_x(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def _trans(x, y, z):
    m = np.eye(4)
    m[:3, 3] = x, y, z
    return m


# -- the matrices --------------------------------------------------------------------------------

def test_standard_matrix_by_hand():
    # theta 90 deg, d 0.2, a 0.3, alpha 90 deg: the x axis turns to y, the origin goes to
    # (0, 0.3, 0.2), and z (rotated about the new x = old y) becomes -old x.
    matrix = dh.dh_matrices(PI_2, 0.2, 0.3, PI_2)
    expected = np.array([[0, 0, 1, 0], [1, 0, 0, 0.3], [0, 1, 0, 0.2], [0, 0, 0, 1.0]])
    np.testing.assert_allclose(matrix, expected, atol=1e-15)


def test_modified_matrix_by_hand():
    # alpha 90 deg about x first, then a 0.3 along x, then theta 90 about the new z (old -y),
    # then d 0.2 along the new z: origin (0.3, -0.2, 0).
    matrix = dh.dh_matrices(PI_2, 0.2, 0.3, PI_2, "modified")
    expected = np.array([[0, -1, 0, 0.3], [0, 0, -1, -0.2], [1, 0, 0, 0], [0, 0, 0, 1.0]])
    np.testing.assert_allclose(matrix, expected, atol=1e-15)


@pytest.mark.parametrize("theta,d,a,alpha", [(0.3, -0.1, 0.7, -1.2), (-2.0, 0.5, -0.2, 2.9)])
def test_matrices_are_the_products_they_name(theta, d, a, alpha):
    standard = _rot_z(theta) @ _trans(0, 0, d) @ _trans(a, 0, 0) @ _rot_x(alpha)
    modified = _rot_x(alpha) @ _trans(a, 0, 0) @ _rot_z(theta) @ _trans(0, 0, d)
    np.testing.assert_allclose(dh.dh_matrices(theta, d, a, alpha), standard, atol=1e-15)
    np.testing.assert_allclose(dh.dh_matrices(theta, d, a, alpha, "modified"), modified,
                               atol=1e-15)


def test_planar_two_link_pose_by_hand():
    table = dh.DHTable("standard", np.eye(4), np.eye(4),
                       [dh.DHJoint("j1", "revolute", 0, 0, 1.0, 0),
                        dh.DHJoint("j2", "revolute", 0, 0, 0.5, 0)])
    pose = dh.table_fk(table, [[PI_2, -PI_2]])[0]
    np.testing.assert_allclose(pose[:3, 3], [0.5, 1.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(pose[:3, :3], np.eye(3), atol=1e-15)


# -- extraction on real robots --------------------------------------------------------------------

def test_ur5_matches_the_published_table():
    robot = load(corpus_or_skip() / "ur_description/urdf/ur5.xacro")
    # base_link_inertia is UR's D-H base frame (base_link turned 180 deg about z)
    table = dh.extract(robot, "base_link_inertia", "wrist_3_link")
    np.testing.assert_allclose([j.d for j in table.joints], UR5["d"], atol=1e-9)
    np.testing.assert_allclose([j.a for j in table.joints], UR5["a"], atol=1e-9)
    np.testing.assert_allclose([j.alpha for j in table.joints], UR5["alpha"], atol=1e-9)
    np.testing.assert_allclose([j.theta for j in table.joints], 0, atol=1e-9)
    np.testing.assert_allclose(table.base, np.eye(4), atol=1e-9)
    np.testing.assert_allclose(table.tool, np.eye(4), atol=1e-9)
    assert max(_worst_errors(robot, KinematicModel(robot), table)) < 1e-12


def test_ur5_from_base_link_differs_only_in_signs():
    """From base_link (x turned 180 deg) the table is the same up to the sign choices."""
    robot = load(corpus_or_skip() / "ur_description/urdf/ur5.xacro")
    table = dh.extract(robot, "base_link", "tool0")
    np.testing.assert_allclose([abs(j.d) for j in table.joints], UR5["d"], atol=1e-9)
    np.testing.assert_allclose([abs(j.a) for j in table.joints], np.abs(UR5["a"]), atol=1e-9)
    np.testing.assert_allclose([abs(j.alpha) for j in table.joints], np.abs(UR5["alpha"]),
                               atol=1e-9)
    assert max(_worst_errors(robot, KinematicModel(robot), table)) < 1e-12


def test_panda_matches_the_published_craig_table():
    robot = load(corpus_or_skip() / "franka_description/robots/panda/panda.urdf.xacro")
    table = dh.extract(robot, "panda_link0", "panda_link7", "modified")
    assert [j.joint for j in table.joints] == [f"panda_joint{i}" for i in range(1, 8)]
    for key in ("a", "d", "alpha"):
        np.testing.assert_allclose([getattr(j, key) for j in table.joints], PANDA[key],
                                   atol=1e-9, err_msg=key)
    np.testing.assert_allclose(table.tool, np.eye(4), atol=1e-9)
    model = KinematicModel(robot)
    assert max(_worst_errors(robot, model, table)) < 1e-12
    standard = dh.extract(robot, "panda_link0", "panda_link8")
    assert max(_worst_errors(robot, model, standard)) < 1e-12


@pytest.mark.parametrize("convention", dh.CONVENTIONS)
@pytest.mark.parametrize("base,tip", LIMBS)
def test_humanoid_limbs_agree_with_pinocchio(humanoid, humanoid_model, base, tip, convention):
    table = dh.extract(humanoid, base, tip, convention)
    position, rotation = _worst_errors(humanoid, humanoid_model, table)
    assert position < 1e-12 and rotation < 1e-12


def test_humanoid_left_leg_parameters(humanoid):
    """Hip yaw/roll intersect (a = d = 0); hip pitch, knee, ankle pitch are parallel (a = thigh)."""
    table = dh.extract(humanoid, "body_link", "l_foot_link")
    assert [j.joint for j in table.joints] == ["l_hip_yaw", "l_hip_roll", "l_hip_pitch",
                                               "l_knee", "l_ank_pitch", "l_ank_roll"]
    np.testing.assert_allclose([abs(j.a) for j in table.joints], [0, 0, 0.093, 0.093, 0, 0],
                               atol=1e-12)
    np.testing.assert_allclose([abs(j.d) for j in table.joints], [0.122, 0, 0, 0, 0, 0],
                               atol=1e-12)
    np.testing.assert_allclose(table.base[:3, 3], [0, 0.037, 0], atol=1e-12)


def test_prismatic_joint_and_fixed_joints_are_folded(tmp_path):
    path = tmp_path / "p.urdf"
    path.write_text("""<robot name="p"><link name="b"/><link name="m"/><link name="c"/>
      <link name="e"/><link name="t"/>
      <joint name="lift" type="prismatic"><parent link="b"/><child link="m"/>
        <origin xyz="0.2 0.1 0.3" rpy="0 0.4 0"/><axis xyz="0 0 1"/>
        <limit lower="0" upper="1" effort="1" velocity="1"/></joint>
      <joint name="mount" type="fixed"><parent link="m"/><child link="c"/>
        <origin xyz="0.05 0 0.1" rpy="0.3 0 0"/></joint>
      <joint name="turn" type="continuous"><parent link="c"/><child link="e"/>
        <origin xyz="0.3 0 0" rpy="0 0.2 0.5"/><axis xyz="0 1 0"/></joint>
      <joint name="tool" type="fixed"><parent link="e"/><child link="t"/>
        <origin xyz="0.1 0.2 0.3" rpy="0.1 0.2 0.3"/></joint></robot>""")
    robot = load(path)
    for convention in dh.CONVENTIONS:
        table = dh.extract(robot, "b", "t", convention)
        assert [(j.joint, j.type) for j in table.joints] == [("lift", "prismatic"),
                                                              ("turn", "revolute")]
        assert max(_worst_errors(robot, KinematicModel(robot), table)) < 1e-12


def test_chain_that_cannot_be_written_in_dh_is_located(tmp_path):
    path = tmp_path / "f.urdf"
    path.write_text("""<robot name="f"><link name="b"/><link name="m"/><link name="t"/>
      <joint name="slide2d" type="planar"><parent link="b"/><child link="m"/>
        <axis xyz="0 0 1"/></joint>
      <joint name="j" type="revolute"><parent link="m"/><child link="t"/>
        <limit lower="0" upper="1" effort="1" velocity="1"/></joint></robot>""")
    robot = load(path)
    with pytest.raises(dh.DHError, match="'slide2d' is planar") as caught:
        dh.extract(robot, "b", "t")
    assert robot.locate(caught.value.element).line == 2


def test_mimic_joint_in_chain_is_refused(tmp_path):
    path = tmp_path / "m.urdf"
    path.write_text("""<robot name="m"><link name="b"/><link name="m"/><link name="t"/>
      <joint name="j1" type="revolute"><parent link="b"/><child link="m"/>
        <limit lower="0" upper="1" effort="1" velocity="1"/></joint>
      <joint name="j2" type="revolute"><parent link="m"/><child link="t"/>
        <limit lower="0" upper="1" effort="1" velocity="1"/><mimic joint="j1"/></joint></robot>""")
    with pytest.raises(dh.DHError, match="'j2' mimics 'j1'"):
        dh.extract(load(path), "b", "t")


def test_every_joint_of_the_chain_without_a_dh_form_is_named(tmp_path):
    """One run names them all (the first at its line): a user choosing --base and --tip around
    them learnt one per run before."""
    path = tmp_path / "g.urdf"
    path.write_text("""<robot name="g"><link name="b"/><link name="m"/><link name="n"/><link name="t"/>
      <joint name="j1" type="revolute"><parent link="b"/><child link="m"/>
        <limit lower="0" upper="1" effort="1" velocity="1"/></joint>
      <joint name="j2" type="revolute"><parent link="m"/><child link="n"/>
        <limit lower="0" upper="1" effort="1" velocity="1"/><mimic joint="j1"/></joint>
      <joint name="p" type="planar"><parent link="n"/><child link="t"/>
        <axis xyz="0 0 1"/></joint></robot>""")
    robot = load(path)
    with pytest.raises(dh.DHError) as caught:
        dh.extract(robot, "b", "t")
    assert str(caught.value) == ("joint 'j2' mimics 'j1': a D-H table has one independent variable "
                                 "per joint; 1 more joint(s) of the chain have none: 'p' (planar)")
    assert robot.locate(caught.value.element).line == 4


def test_tip_not_below_base(humanoid):
    with pytest.raises(dh.DHError, match="not below link 'l_foot_link'.*swap --base and --tip"):
        dh.extract(humanoid, "l_foot_link", "body_link")
    with pytest.raises(dh.DHError, match="descendants$"):  # other branches: no swap to offer
        dh.extract(humanoid, "l_foot_link", "r_foot_link")
    from urdftool.errors import UnknownLink

    with pytest.raises(UnknownLink, match="did you mean 'l_foot_link'"):
        dh.extract(humanoid, "body_link", "l_foot")


# -- table files and the CLI ----------------------------------------------------------------------

def test_table_round_trips_through_json_and_yaml(humanoid, tmp_path):
    table = dh.extract(humanoid, "body_link", "r_foot_link", "modified")
    (tmp_path / "t.json").write_text(json.dumps(table.as_dict()))
    (tmp_path / "t.yaml").write_text(yaml.safe_dump(table.as_dict()))
    for name in ("t.json", "t.yaml"):
        loaded = dh.load_table(str(tmp_path / name))
        assert loaded.as_dict() == table.as_dict()


def test_bad_table_is_located(tmp_path):
    path = tmp_path / "t.json"
    path.write_text(json.dumps({"convention": "standard", "base": np.eye(4).tolist(),
                                "tool": np.eye(4).tolist(),
                                "joints": [{"joint": "a", "type": "revolute", "theta": 0,
                                            "d": "x", "a": 0, "alpha": 0}]}))
    with pytest.raises(dh.DHError, match="must all be finite numbers") as caught:
        dh.load_table(str(path))
    assert caught.value.where.endswith("t.json: joints[0]")


@pytest.mark.parametrize("old, new, line", [
    ("  d: 0.0\n", "  d: 0.0\n  d: 5.0\n", None),  # a row's d twice: PyYAML kept 5.0
    ("convention: ", "convention: modified\nconvention: ", 2),
    ('"d": 0.0', '"d": 0.0, "d": 5.0', 1),  # JSON is read as YAML
])
def test_a_table_writing_a_key_twice_is_a_located_error(humanoid, tmp_path, old, new, line):
    table = dh.extract(humanoid, "body_link", "r_foot_link").as_dict()
    text = json.dumps(table) if old.startswith('"') else yaml.safe_dump(table, sort_keys=False)
    path = tmp_path / "t.yaml"
    path.write_text(text.replace(old, new, 1))
    with pytest.raises(dh.DHError, match="is written twice") as caught:
        dh.load_table(str(path))
    if line is not None:
        assert caught.value.where == f"{path}:{line}"


@pytest.mark.parametrize("old, new", [
    ("  d: 0.0\n", "  d: " + "1" * 400 + "\n"),  # float() of it: OverflowError
    ("  d: 0.0\n", "  d: 2001-02-30\n"),  # a date to YAML 1.1, and none: ValueError
    ("  d: 0.0\n", "  d: !!bool x\n"),  # KeyError
    ("  - 0.0\n", "  - " + "1" * 400 + "\n"),  # numpy's OverflowError in a matrix
])
def test_a_table_value_pyyaml_cannot_construct_is_a_located_error(humanoid, tmp_path, old, new):
    table = dh.extract(humanoid, "body_link", "r_foot_link").as_dict()
    text = yaml.safe_dump(table, sort_keys=False).replace(old, new, 1)
    path = tmp_path / "t.yaml"
    path.write_text(text)
    with pytest.raises(dh.DHError, match="invalid JSON/YAML: ") as caught:
        dh.load_table(str(path))
    assert caught.value.where == f"{path}:{text[:text.index(new)].count(chr(10)) + 1}"


@pytest.mark.parametrize("value, said", [
    ("{a: 1}", "a mapping"), ("[l_hip_link]", "a list"), ("5", "the number 5"),
    ("true", "a boolean"), ("2001-01-01", "a value of type date")])
def test_a_table_naming_its_base_or_tip_with_no_text_is_a_located_error(run_cli, tmp_path,
                                                                        value, said):
    """attack30: ``tip_link: [1]`` was looked up among the robot's links by ``fk --dh
    --verify``: a TypeError traceback (the name's close matches searched in a list)."""
    table = dh.extract(load(HUMANOID), "body_link", "l_foot_link").as_dict()
    for key in ("base_link", "tip_link"):
        path = tmp_path / f"{key}.yaml"
        path.write_text(yaml.safe_dump(table, sort_keys=False)
                        .replace(f"{key}: {table[key]}", f"{key}: {value}"))
        with pytest.raises(dh.DHError, match=f"'{key}' must be a link's name, not {said}$"):
            dh.load_table(str(path))
        result = run_cli("fk", HUMANOID, "--dh", path, "--verify")
        assert result.exit_code == 2 and "Traceback" not in result.stderr, result.stderr
        assert f"{key}' must be a link's name" in result.stderr


def test_cli_dh_json_then_fk_verify(run_cli, tmp_path):
    result = run_cli("dh", HUMANOID, "--base", "body_link", "--tip", "l_foot_link", "-f", "json")
    assert result.exit_code == 0, result.output
    document = json.loads(result.stdout)
    assert {"convention", "base", "tool", "joints"} <= set(document)
    assert set(document["joints"][0]) == {"joint", "type", "theta", "d", "a", "alpha"}
    path = tmp_path / "leg.json"
    path.write_text(result.stdout)
    result = run_cli("fk", HUMANOID, "--dh", path, "--verify", "--random", "50")
    assert result.exit_code == 0, result.output
    assert "agree" in result.stdout
    result = run_cli("fk", HUMANOID, "--dh", path, "--q", "l_knee=1", "-f", "json")
    assert json.loads(result.stdout)["frames"][0]["frame"] == "l_foot_link"


def test_cli_verify_fails_on_a_wrong_table(run_cli, tmp_path):
    document = dh.extract(load(HUMANOID), "body_link", "l_foot_link").as_dict()
    document["joints"][3]["a"] += 1e-6
    path = tmp_path / "wrong.yaml"
    path.write_text(yaml.safe_dump(document))
    result = run_cli("fk", HUMANOID, "--dh", path, "--verify")
    assert result.exit_code == 1
    assert "DISAGREE" in result.stdout


def test_cli_dh_text_and_located_error(run_cli, tmp_path):
    result = run_cli("dh", HUMANOID, "--base", "body_link", "--tip", "l_forearm_link",
                     "--convention", "modified")
    assert result.exit_code == 0, result.output
    assert "l_sho_pitch" in result.stdout and "a(i-1) [m]" in result.stdout
    path = tmp_path / "f.urdf"
    path.write_text('<robot name="f"><link name="b"/><link name="t"/>\n'
                    '<joint name="fly" type="floating"><parent link="b"/><child link="t"/></joint>'
                    "</robot>")
    result = run_cli("dh", path, "--base", "b", "--tip", "t")
    # a chain the user chose that has no D-H form: a usage error, at the joint (it was exit 1)
    assert result.exit_code == 2
    assert result.stderr.startswith(f"urdftool: error: {path}:2: joint 'fly' is floating")


# two joints whose axes are antiparallel to 1e-9 rad, a joint's offset 0.49 m: the common
# normal of axes that are neither parallel to _EPS nor apart enough to place (found by fuzzing)
NEARLY_PARALLEL = (
    '<robot name="r"><link name="l0"/><link name="l1"/>'
    '<joint name="j0" type="revolute"><parent link="l0"/><child link="l1"/>'
    '<origin xyz="3.7226086368378395e-07 2.442014750133396e-09 -1.1780589691969552"'
    ' rpy="7.471601859788264e-10 3.1415926546649646 0"/>'
    '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
    '<link name="l2"/><joint name="j1" type="prismatic"><parent link="l1"/>'
    '<child link="l2"/>'
    '<origin xyz="0.49395781119002047 2.592438446614699e-07 0"'
    ' rpy="-3.0788012408650447e-09 -1.546258446280463e-10 3.1415926587183836"/>'
    '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
    '</robot>')


@pytest.mark.parametrize("convention", ["standard", "modified"])
def test_cli_dh_an_axis_it_cannot_place_is_the_chains_not_the_robots(run_cli, tmp_path,
                                                                   convention):
    """The chain the user chose goes through a joint the construction cannot place: a usage
    error (exit 2, at the joint), as a joint without a D-H form; it exited 1 as if the robot
    were at fault, where another --base or --tip answers it."""
    path = tmp_path / "p.urdf"
    path.write_text(NEARLY_PARALLEL)
    result = run_cli("dh", path, "--base", "l0", "--tip", "l2", "--convention", convention)
    assert result.exit_code == 2, result.output
    assert "its axis cannot be placed in D-H form" in result.stderr
    assert "choose a --base or --tip that leaves it out" in result.stderr


def test_cli_dh_base_defaults_to_the_root_and_needs_one(run_cli, tmp_path):
    """Like ik, fk and workspace, --base defaults to the root link; without a single root the
    table has no start, said at the robot (exit 1), not as a traceback."""
    given = run_cli("dh", HUMANOID, "--base", "base_link", "--tip", "l_foot_link", "-f", "json")
    default = run_cli("dh", HUMANOID, "--tip", "l_foot_link", "-f", "json")
    assert given.exit_code == default.exit_code == 0, default.output
    assert default.stdout == given.stdout
    path = tmp_path / "two.urdf"
    path.write_text('<robot name="two"><link name="a"/><link name="b"/><link name="t"/>\n'
                    '<joint name="j" type="revolute"><parent link="a"/><child link="t"/>'
                    '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>')
    result = run_cli("dh", path, "--tip", "t")
    assert result.exit_code == 1, result.output
    # urdfdom refuses it: the linter's U108 at its line, as every command that poses a robot
    assert "two.urdf:1: error U108 link 'b' has no parent joint: the robot has 2 roots ('a', " \
           "'b')" in result.stderr, result.stderr


@pytest.mark.parametrize("tilt", [1e-8, 1e-5, 1e-3])
def test_nearly_parallel_axes_give_a_finite_exact_table(tmp_path, tilt):
    # 1 - cos^2 of a 1e-8 rad tilt rounds to 0: the common normal must not divide by it
    path = tmp_path / "np.urdf"
    path.write_text(f"""<robot name="np"><link name="b"/><link name="m"/><link name="t"/>
      <joint name="j1" type="revolute"><parent link="b"/><child link="m"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
      <joint name="j2" type="revolute"><parent link="m"/><child link="t"/>
        <origin xyz="0.3 0 0" rpy="{tilt} 0 0"/><axis xyz="0 0 1"/>
        <limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>""")
    robot = load(path)
    for convention in dh.CONVENTIONS:
        table = dh.extract(robot, "b", "t", convention)
        assert all(np.isfinite([j.theta, j.d, j.a, j.alpha]).all() for j in table.joints)
        assert np.isfinite(table.tool).all()
        assert max(_worst_errors(robot, KinematicModel(robot), table)) < 1e-12


def test_cli_table_with_only_the_specified_keys(run_cli, tmp_path):
    """base_link/tip_link are an extension: a table with just convention, base, tool, joints
    works when --base and --frame name the chain, and otherwise says so at the table."""
    document = dh.extract(load(HUMANOID), "body_link", "l_foot_link").as_dict()
    assert set(document) == {"convention", "base", "tool", "joints", "base_link", "tip_link"}
    del document["base_link"], document["tip_link"]
    path = tmp_path / "spec.json"
    path.write_text(json.dumps(document))
    result = run_cli("fk", HUMANOID, "--dh", path, "--verify", "--random", "20",
                     "--base", "body_link", "--frame", "l_foot_link")
    assert result.exit_code == 0 and "agree" in result.stdout, result.output
    result = run_cli("fk", HUMANOID, "--dh", path, "--verify")
    # the table the user gave does not fit: a usage error, as a --q-file's (it was exit 1)
    assert result.exit_code == 2
    assert f"urdftool: error: {path}: the D-H table does not name its base_link" in \
        result.stderr


def test_cli_dh_options_that_contradict_the_table(run_cli, tmp_path):
    path = tmp_path / "leg.yaml"
    path.write_text(yaml.safe_dump(dh.extract(load(HUMANOID), "body_link", "l_foot_link")
                                   .as_dict()))
    result = run_cli("fk", HUMANOID, "--dh", path, "--verify", "--frame", "l_hip_link")
    assert result.exit_code == 2
    assert "chain is body_link -> l_foot_link; --frame l_hip_link names another" in result.stderr
    result = run_cli("fk", HUMANOID, "--dh", path, "--frame", "l_foot_link", "--frame", "x")
    assert result.exit_code == 2 and "at most one --frame" in result.output


# -- the textbook form: a >= 0, the sign in alpha and theta ----------------------------------

@pytest.mark.parametrize("convention", dh.CONVENTIONS)
@pytest.mark.parametrize("base,tip", LIMBS)
def test_textbook_form_keeps_link_lengths_positive_and_the_chain(humanoid, humanoid_model, base,
                                                                 tip, convention):
    table = dh.extract(humanoid, base, tip, convention, textbook=True)
    assert all(j.a >= 0 for j in table.joints)
    assert all(-math.pi < j.theta <= math.pi and -math.pi < j.alpha <= math.pi
               for j in table.joints)
    position, rotation = _worst_errors(humanoid, humanoid_model, table)
    assert position < 1e-12 and rotation < 1e-12


def test_textbook_form_of_the_leg_moves_the_sign_into_theta(humanoid):
    default = dh.extract(humanoid, "body_link", "l_foot_link")
    assert [j.a for j in default.joints][2:4] == [-0.093, -0.093]  # what dh writes by default
    table = dh.extract(humanoid, "body_link", "l_foot_link", textbook=True)
    np.testing.assert_allclose([j.a for j in table.joints], [0, 0, 0.093, 0.093, 0, 0],
                               atol=1e-12)
    np.testing.assert_allclose([j.theta for j in table.joints],
                               [math.pi / 2, math.pi / 2, math.pi, 0, math.pi, -math.pi / 2],
                               atol=1e-12)
    np.testing.assert_allclose([j.alpha for j in table.joints],
                               [j.alpha for j in default.joints], atol=1e-12)


def test_ur5_textbook_form_matches_the_published_magnitudes():
    robot = load(corpus_or_skip() / "ur_description/urdf/ur5.xacro")
    table = dh.extract(robot, "base_link", "tool0", textbook=True)
    assert all(j.a >= 0 for j in table.joints)
    np.testing.assert_allclose([j.a for j in table.joints], np.abs(UR5["a"]), atol=1e-9)
    assert max(_worst_errors(robot, KinematicModel(robot), table)) < 1e-12


def test_cli_dh_textbook(run_cli, tmp_path):
    out = tmp_path / "leg.json"
    result = run_cli("dh", HUMANOID, "--base", "body_link", "--tip", "l_foot_link",
                     "--textbook", "-f", "json")
    assert result.exit_code == 0, result.output
    out.write_text(result.output)
    assert all(j["a"] >= 0 for j in json.loads(result.output)["joints"])
    verified = run_cli("fk", HUMANOID, "--dh", out, "--verify", "--random", "50")
    assert verified.exit_code == 0, verified.output


@pytest.mark.parametrize("change, message", [
    (lambda t: t["joints"][0].update(d=True), "must all be finite numbers"),  # was 1 m
    (lambda t: t["joints"][0].update(a=float("nan")), "must all be finite numbers"),  # nan poses
    (lambda t: t["joints"][0].update(alpha=float("inf")), "must all be finite numbers"),
    (lambda t: t["base"][0].__setitem__(0, 5.0), "'base' must be a rigid transform"),  # a scale
    (lambda t: t["tool"][0].__setitem__(1, 3.0), "'tool' must be a rigid transform"),  # a shear
    (lambda t: t["tool"][3].__setitem__(3, 2.0), "'tool' must be a rigid transform"),
])
def test_a_table_of_values_no_chain_holds_is_a_located_error(humanoid, tmp_path, change,
                                                             message):
    """What fk --dh computed with: YAML's ``true`` as 1 m, ``.nan`` as nan poses (exit 0),
    a base scaled or sheared as poses whose rotations are no rotations."""
    table = dh.extract(humanoid, "body_link", "r_foot_link").as_dict()
    change(table)
    path = tmp_path / "t.yaml"
    path.write_text(yaml.safe_dump(table, sort_keys=False))
    with pytest.raises(dh.DHError, match=message) as caught:
        dh.load_table(str(path))
    assert caught.value.where.startswith(str(path))


FAR_CHAIN = """<robot name="c"><link name="w"/>
 <joint name="f" type="fixed"><parent link="w"/><child link="a"/>
  <origin xyz="{x} 0 0" rpy="0.3 0.2 0.1"/></joint><link name="a"/>
 <joint name="j1" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0.1 0 0.2"/>
  <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint><link name="b"/>
 <joint name="j2" type="revolute"><parent link="b"/><child link="c"/>
  <origin xyz="0.3 0.01 0" rpy="1.5707963 0 0"/><axis xyz="0 0 1"/>
  <limit lower="-1" upper="1" effort="1" velocity="1"/></joint><link name="c"/>
</robot>"""


def test_a_base_past_the_farthest_coordinate_is_refused_as_fk_refuses_it(tmp_path):
    """attack25: dh read joint origins by itself and printed a base at 1e200 as given, with
    "reproduces the URDF chain to 0"; it reads them as fk does (fk.joint_placement)."""
    from conftest import load_text

    with pytest.raises(dh.DHError, match=r"joint 'f': <origin> xyz '1e\+200 0 0' is past the "
                                         r"4\.612e\+10 m urdftool places a link within"):
        dh.extract(load_text(tmp_path, FAR_CHAIN.format(x="1e200")), "w", "c")
    with pytest.raises(dh.DHError, match="not finite"):
        dh.extract(load_text(tmp_path, FAR_CHAIN.format(x="inf")), "w", "c")


@pytest.mark.parametrize("x", ["0", "1e8", "4e10"])
def test_a_chain_far_from_its_base_link_is_held_to_what_a_float_resolves_there(tmp_path, x):
    """attack25: a chain 1e8 m from its base link (within numbers.MAX_COORDINATE) was refused
    as "axes nearly parallel?", its residual (1.3e-9) the rounding of its place; the residual
    is held to 1e-9 or 16 ulps of the farthest translation, and the table still reproduces the
    chain there."""
    from conftest import load_text

    table = dh.extract(load_text(tmp_path, FAR_CHAIN.format(x=x)), "w", "c")
    assert [round(row.a, 4) for row in table.joints] == [0.3, 0.0]
    assert table.residual <= max(1e-9, 16 * np.spacing(4e10 if x == "4e10" else float(x)))


@pytest.mark.parametrize("edit, where, said", [
    (lambda t: t["joints"][0].__setitem__("d", 1e300), "joints[0]", r"d: 1e\+300 is past"),
    (lambda t: t["joints"][1].__setitem__("theta", -1e200), "joints[1]", r"theta: 1e\+200 is"),
    (lambda t: t["base"][0].__setitem__(3, 1e308), "t.yaml", r"'base' translation: 1e\+308 is"),
])
def test_a_table_length_past_the_farthest_coordinate_is_refused(tmp_path, humanoid, edit, where,
                                                                said):
    """attack25: a D-H table file's d of 1e300 (or a base at 1e308) was read as given: fk
    printed a pose at 1e+300 and --verify "worst position error inf m" with numpy's overflow
    warning. A table's lengths and angles are bounded as joint origins and values are."""
    table = dh.extract(humanoid, "body_link", "l_foot_link").as_dict()
    edit(table)
    path = tmp_path / "t.yaml"
    path.write_text(yaml.safe_dump(table))
    with pytest.raises(dh.DHError, match=said + r".* the 4\.612e\+10 (m|rad) urdftool places") \
            as refused:
        dh.load_table(str(path))
    assert refused.value.where.endswith(where)


@pytest.mark.parametrize("x", ["0", "1e8", "4e10"])
def test_the_text_table_read_back_reproduces_the_chain_to_its_decimals(tmp_path, run_cli, x):
    """The text table printed 6 decimals of every number: 1e8 m from its base link, a theta
    off by 5e-7 rad moved the tip by metres. Its numbers read back (theta, d, a, alpha, the
    base's and tool's xyz and rpy) reproduce the extracted table to 1e-6 m and rad wherever
    the chain is (or what a float resolves there, past 1e9 m): angles get a decimal more for each power of ten the chain reaches, lengths
    keep 6, never past the 17 digits a float holds."""
    from urdftool.kinematics.transforms import from_xyz_rpy

    path = tmp_path / "far.urdf"
    path.write_text(FAR_CHAIN.format(x=x))
    result = run_cli("dh", path, "--base", "w", "--tip", "c")
    assert result.exit_code == 0, result.output
    exact = dh.extract(load(str(path)), "w", "c")
    rows, frames = [], {}
    for line in result.stdout.splitlines():
        words = line.split()
        if words and words[0] in {row.joint for row in exact.joints}:
            rows.append(dh.DHJoint(words[0], words[1], *map(float, words[2:6])))
        elif words and words[0] in ("base:", "tool:"):
            frames[words[0]] = from_xyz_rpy([float(w) for w in words[2:5]],
                                            [float(w) for w in words[6:9]])
        assert all(len(word.replace("-", "").replace(".", "")) <= 17 for word in words
                   if word.lstrip("-")[:1].isdigit()), line
    printed = dh.DHTable(exact.convention, frames["base:"], frames["tool:"], rows, "w", "c", 0.0)
    q = np.random.default_rng(0).uniform(-1, 1, (64, len(rows)))
    ours, theirs = dh.table_fk(printed, q), dh.table_fk(exact, q)
    # (4e10 m out a float resolves 7.6e-6 m: there the table is held to what dh holds it to)
    tolerance = max(1e-6, dh._tolerance(exact.base))
    assert np.abs(ours[:, :3, 3] - theirs[:, :3, 3]).max() <= tolerance
    assert np.abs(ours[:, :3, :3] - theirs[:, :3, :3]).max() <= 1e-6
