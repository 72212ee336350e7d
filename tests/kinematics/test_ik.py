"""Inverse kinematics: every solution re-checked by the vectorised FK (urdftool.kinematics.fk,
numpy Rodrigues, not the Pinocchio path the solver uses), closed forms against the numeric
solver, mimic and continuous joints, limits, unreachable targets, target files and the CLI."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from conftest import ROBOTS, corpus_or_skip
from urdftool.description.load import load
from urdftool.errors import ConfigError, IKError
from urdftool.kinematics import configuration as config
from urdftool.kinematics import ik
from urdftool.kinematics.chain import build_chain
from urdftool.kinematics.fk import forward_kinematics

HUMANOID = ROBOTS / "humanoid" / "humanoid.urdf.xacro"

# a planar arm in the x-z plane (axes +y, -y, +y), a hand offset, and a sensor mimicking the
# elbow off the chain; "spin" is a continuous wrist about the hand's x
PLANAR = b"""<robot name="planar">
  <link name="base"/><link name="upper"/><link name="fore"/><link name="hand"/>
  <link name="tool"/><link name="sensor"/><link name="tcp"/>
  <joint name="tcp_joint" type="fixed"><parent link="hand"/><child link="tcp"/>
    <origin xyz="0.08 0 0.02"/></joint>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.5"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/>
    <origin xyz="0.3 0.05 0.1"/><axis xyz="0 -1 0"/>
    <limit lower="-2.5" upper="2.5" effort="1" velocity="1"/></joint>
  <joint name="wrist" type="revolute"><parent link="fore"/><child link="hand"/>
    <origin xyz="0.25 0 0" rpy="0 0.3 0"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="spin" type="continuous"><parent link="hand"/><child link="tool"/>
    <origin xyz="0.1 0 0"/><axis xyz="1 0 0"/></joint>
  <joint name="sensor_joint" type="revolute"><parent link="fore"/><child link="sensor"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
    <mimic joint="elbow" multiplier="0.5"/></joint>
</robot>"""

# a mimic joint inside the chain: "b" turns with twice "a" plus 0.1
MIMIC = b"""<robot name="mimic">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/><link name="tip"/>
  <joint name="a" type="revolute"><parent link="base"/><child link="l1"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="b" type="revolute"><parent link="l1"/><child link="l2"/>
    <origin xyz="0.2 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
    <mimic joint="a" multiplier="2" offset="0.1"/></joint>
  <joint name="c" type="continuous"><parent link="l2"/><child link="l3"/>
    <origin xyz="0.2 0 0"/><axis xyz="1 0 0"/></joint>
  <joint name="d" type="prismatic"><parent link="l3"/><child link="tip"/>
    <origin xyz="0 0.1 0"/><axis xyz="0 0 1"/>
    <limit lower="0" upper="0.2" effort="1" velocity="1"/></joint>
</robot>"""


def _robot(tmp_path, text, name="robot.urdf"):
    path = tmp_path / name
    path.write_bytes(text)
    return load(path)


@pytest.fixture(scope="module")
def humanoid():
    return load(HUMANOID)


def _fk_pose(chain, row):
    """base^-1 tip by urdftool's vectorised FK, independent of the solver's Pinocchio calls."""
    configurations = config.Configurations(chain.kinematics.variables, row[None, :], [])
    return forward_kinematics(chain.kinematics, configurations, [chain.tip],
                              chain.base).matrices[0, 0]


def _reachable(chain, count, seed):
    """Targets made by FK of random in-limit configurations: (x, Target) pairs."""
    values = config.random(chain.variables, count, seed).values
    pairs = []
    for x in values:
        pose = _fk_pose(chain, chain.row_of(x))
        pairs.append((x, ik.Target(pose[:3, 3], pose[:3, :3])))
    return pairs


def _check(chain, solution, target, tolerance=1e-6):
    """The solution's row, through FK, puts the tip on the target; limits hold."""
    assert solution.solved, solution.reason
    pose = _fk_pose(chain, solution.row)
    assert np.linalg.norm(pose[:3, 3] - target.position) <= tolerance
    if target.rotation is not None:
        chord = np.linalg.norm(pose[:3, :3] - target.rotation) / math.sqrt(8)
        assert 2 * math.asin(min(1.0, chord)) <= 2 * tolerance
    assert np.all(solution.x >= chain.lower - 1e-12) and np.all(solution.x <= chain.upper + 1e-12)


@pytest.mark.parametrize("base,tip", [("body_link", "l_foot_link"),
                                      ("body_link", "r_foot_link"),
                                      ("body_link", "l_forearm_link"),
                                      ("r_foot_link", "l_forearm_link")])
def test_humanoid_limbs_reach_fk_targets(humanoid, base, tip):
    chain = build_chain(humanoid, base, tip)
    starts = ik.seeds(chain, 8, 1)
    for _, target in _reachable(chain, 15, 7):
        _check(chain, ik.solve(chain, target, starts, method="numeric"), target)


def test_position_only_ignores_the_orientation(humanoid):
    chain = build_chain(humanoid, "body_link", "l_foot_link")
    (_, target), = _reachable(chain, 1, 3)
    position_only = ik.Target(target.position)
    solution = ik.solve(chain, position_only, ik.seeds(chain, 4, 0))
    _check(chain, solution, position_only)
    assert solution.rotation_error == 0.0


def test_joints_off_the_limb_stay_where_they_were_given(humanoid):
    kinematics = build_chain(humanoid, "body_link", "l_foot_link").kinematics
    row = config.from_words(kinematics.variables, {"r_knee": "1.2", "head_pan": "0.3"}).values[0]
    chain = build_chain(humanoid, "body_link", "l_foot_link", row, kinematics)
    (_, target), = _reachable(chain, 1, 4)
    solution = ik.solve(chain, target, ik.seeds(chain, 4, 0))
    _check(chain, solution, target)
    names = [v.name for v in kinematics.variables]
    assert solution.row[names.index("r_knee")] == 1.2
    assert solution.row[names.index("head_pan")] == 0.3


def test_planar_closed_form_agrees_with_numeric(tmp_path):
    robot = _robot(tmp_path, PLANAR)
    chain = build_chain(robot, "base", "hand")
    assert ik.planar(chain) is not None
    for x, target in _reachable(chain, 40, 2):
        closed = ik.closed_form(chain, target, x)
        numeric = ik.solve(chain, target, ik.seeds(chain, 8, 0, first=x + 0.05),
                           method="numeric")
        _check(chain, closed, target, 1e-9)
        _check(chain, numeric, target)
        assert closed.method == "closed form" and closed.iterations == 0
        assert numeric.method == "numeric" and numeric.iterations > 0
        # seeded at x, the closed form picks x's elbow branch; the numeric one lands on one of
        # the two branches
        assert np.allclose(closed.x, x, atol=1e-9)
        other = ik.closed_form(chain, target, 2 * closed.x - x + np.array([0, 1, 0]))
        assert min(np.abs(numeric.x - closed.x).max(),
                   np.abs(numeric.x - other.x).max()) < 1e-5


def test_two_joint_closed_form_both_elbow_branches(tmp_path):
    robot = _robot(tmp_path, PLANAR)
    chain = build_chain(robot, "upper", "tcp")  # elbow and wrist (tcp is fixed): position only
    assert [v.name for v in chain.variables] == ["elbow", "wrist"]
    x = np.array([0.4, 0.9])
    pose = _fk_pose(chain, chain.row_of(x))
    target = ik.Target(pose[:3, 3])
    near = ik.closed_form(chain, target, x)
    _check(chain, near, target, 1e-9)
    assert np.allclose(near.x, x)
    other = ik.closed_form(chain, target, np.array([x[0], -x[1]]))
    _check(chain, other, target, 1e-9)
    assert other.x[1] < -0.5  # the mirrored elbow: bent the other way


def test_closed_form_declines_what_it_cannot_do(tmp_path, humanoid):
    robot = _robot(tmp_path, PLANAR)
    three = build_chain(robot, "base", "hand")
    assert ik.closed_form(three, ik.Target(np.array([0.3, 0.05, 0.7])), np.zeros(3)) is None
    assert ik.planar(build_chain(robot, "base", "tool")) is None  # 4 joints
    assert ik.planar(build_chain(humanoid, "body_link", "l_forearm_link")) is None  # x and y axes


def test_mimic_joint_in_the_chain_follows_its_variable(tmp_path):
    robot = _robot(tmp_path, MIMIC)
    chain = build_chain(robot, "base", "tip")
    assert [v.name for v in chain.variables] == ["a", "c", "d"]
    for x, target in _reachable(chain, 10, 5):
        solution = ik.solve(chain, target, ik.seeds(chain, 8, 0))
        _check(chain, solution, target)
        assert -math.pi < solution.x[1] <= math.pi  # the continuous joint is wrapped
        b = chain.kinematics.joint_values(solution.row[None, :], "b")[0]
        assert b == pytest.approx(2 * solution.x[0] + 0.1)


def test_continuous_joint_wraps_a_far_seed(tmp_path):
    robot = _robot(tmp_path, MIMIC)
    chain = build_chain(robot, "base", "tip")
    x = np.array([0.2, 3.0, 0.1])
    pose = _fk_pose(chain, chain.row_of(x))
    target = ik.Target(pose[:3, 3], pose[:3, :3])
    solution = ik.solve(chain, target, np.array([[0.2, 3.0 + 4 * math.pi, 0.1]]))
    _check(chain, solution, target)
    assert solution.x[1] == pytest.approx(3.0)


def test_unreachable_target_says_why(humanoid):
    chain = build_chain(humanoid, "body_link", "l_forearm_link")
    far = ik.solve(chain, ik.Target(np.array([0.5, 0.5, 0.5])), ik.seeds(chain, 3, 0))
    assert not far.solved and far.reason.startswith("out of reach")
    assert far.position_error > 0.3
    _, radius = ik.reach(chain)
    assert radius == pytest.approx(0.0888, abs=1e-3)  # shoulder offsets + upper arm


def test_target_behind_a_limit_names_the_joint(tmp_path):
    chain = build_chain(_robot(tmp_path, PLANAR), "upper", "tcp")
    # 0.18 m from the elbow, within reach, but the wrist would have to fold past its 2 rad
    folded = ik.Target(np.array([0.3 + 0.18, 0.05, 0.1]))
    for method in ("auto", "numeric"):
        solution = ik.solve(chain, folded, ik.seeds(chain, 4, 0), method=method)
        assert not solution.solved
        assert solution.reason == "held back by the limits of wrist (upper)"
        assert solution.x[1] == 2.0


def test_a_joint_of_no_range_is_never_at_a_limit(tmp_path):
    """HSR's wrist_ft_sensor_frame_joint has limits 0 and 0: every solution said it was at
    its lower and its upper limit."""
    robot = _robot(tmp_path, PLANAR.replace(b'<limit lower="-2" upper="2" effort="1" '
                                            b'velocity="1"/></joint>\n  <joint name="spin"',
                                            b'<limit lower="0" upper="0" effort="1" '
                                            b'velocity="1"/></joint>\n  <joint name="spin"'))
    chain = build_chain(robot, "upper", "hand")
    target = ik.Target(np.array([0.3 + 0.25 * np.cos(0.4), 0.05, 0.1 + 0.25 * np.sin(0.4)]))
    solution = ik.solve(chain, target, ik.seeds(chain, 4, 0), method="numeric")
    assert [v.name for v in chain.variables][-1] == "wrist"
    assert solution.solved and not solution.at_limits


def test_orientation_a_short_limb_cannot_take(humanoid):
    chain = build_chain(humanoid, "body_link", "l_forearm_link")
    x = np.array([0.3, 0.4, -0.5])
    pose = _fk_pose(chain, chain.row_of(x))
    twisted = ik.Target(pose[:3, 3], pose[:3, :3] @ np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1]]))
    solution = ik.solve(chain, twisted, ik.seeds(chain, 2, 0))
    assert not solution.solved
    assert "cannot take every orientation" in solution.reason


def test_limbs_ik_cannot_work_on(tmp_path):
    from test_fk import TINY

    robot = _robot(tmp_path, TINY)
    with pytest.raises(IKError, match="joint 'free' between 'world' and 'd' is floating"):
        build_chain(robot, "world", "d")
    with pytest.raises(IKError, match="no joint moves 'a' relative to 'a'"):
        build_chain(robot, "a", "a")
    # below the floating joint: a continuous joint, a mimic of it and a prismatic one
    chain = build_chain(robot, "a", "d")
    assert [v.name for v in chain.variables] == ["spin", "slide"]
    for x, target in _reachable(chain, 5, 1):
        _check(chain, ik.solve(chain, target, ik.seeds(chain, 8, 0)), target)


def test_unknown_link_lists_the_links(humanoid):
    from urdftool.errors import UnknownLink

    with pytest.raises(UnknownLink, match="did you mean 'l_foot_link'"):
        build_chain(humanoid, "body_link", "l_fot_link")


@pytest.mark.parametrize("command", [["ik", "--xyz", "0", "0", "0"], ["workspace"]])
def test_an_unknown_tip_or_base_is_a_usage_error(run_cli, command):
    """A link named on the command line that the robot does not have is a usage error (exit 2)
    in every command, as fk, dh and inertia say it; ik and workspace said it at the robot's
    file with exit 1."""
    for option in ("--tip", "--base"):
        words = ["--tip", "l_foot_link", "--base", "body_link"]
        words[words.index(option) + 1] = "l_fot_link"
        result = run_cli(command[0], HUMANOID, *words, *command[1:])
        assert result.exit_code == 2, result.output
        assert "link 'l_fot_link' does not exist; did you mean 'l_foot_link'" in result.output


def test_ur5_from_the_corpus():
    robot = load(str(corpus_or_skip() / "ur_description" / "urdf" / "ur5.xacro"))
    chain = build_chain(robot, "base_link", "tool0")
    assert len(chain.variables) == 6
    starts = ik.seeds(chain, 8, 0)
    for _, target in _reachable(chain, 10, 11):
        _check(chain, ik.solve(chain, target, starts), target)


def test_target_files(tmp_path):
    csv_path = tmp_path / "t.csv"
    csv_path.write_text("x,y,z,roll,pitch,yaw\n0.1,0.2,0.3,0,0,90\n0,0,0,0,0,0\n")
    first, second = ik.read_targets(str(csv_path), degrees=True)
    assert first.name == "target 1" and np.allclose(first.position, [0.1, 0.2, 0.3])
    assert np.allclose(first.rotation, [[0, -1, 0], [1, 0, 0], [0, 0, 1]], atol=1e-12)
    json_path = tmp_path / "t.json"
    json_path.write_text(json.dumps({"x": 1, "y": 2, "z": 3}))
    plain, = ik.read_targets(str(json_path))
    assert plain.rotation is None and np.allclose(plain.position, [1, 2, 3])
    json_path.write_text(json.dumps([{"x": 0, "y": 0, "z": 1, "qx": 0, "qy": 0, "qz": 1,
                                      "qw": 1}]))
    quarter, = ik.read_targets(str(json_path))
    assert np.allclose(quarter.rotation, first.rotation, atol=1e-12)
    for text, message in (("x,y,z,roll\n1,2,3,0\n", "roll, pitch, yaw or none"),
                          ("x,y,w\n1,2,3\n", "unknown column 'w'"),
                          ("x,y,z\n1,2,a\n", r"t2.csv: row 1: value 'a' for column 'z'"),
                          ("x,y,z,qx,qy,qz,qw\n1,2,3,0,0,0,0\n", "row 1: a quaternion of length 0")):
        bad = tmp_path / "t2.csv"
        bad.write_text(text)
        with pytest.raises(ConfigError, match=message):
            ik.read_targets(str(bad))



def test_the_targets_of_a_file_are_made_as_they_are_reached(tmp_path, monkeypatch):
    """A Target (a position, a 3x3 rotation) was made for every row before the first was
    solved: 150,000 targets of a 13.7 MB file were 97 MB and 5 s. A row target() refuses is
    refused all the same when the file is read, before any is used: a coordinate past what
    the solver squares, a quaternion of length 0, or one whose squares underflow."""
    made = []
    real = ik.target
    monkeypatch.setattr(ik, "target", lambda *a, **k: made.append(a) or real(*a, **k))
    path = tmp_path / "t.csv"
    path.write_text("x,y,z,qx,qy,qz,qw\n" + "0.1,0,0.3,0,0,1,1\n" * 40)
    targets = ik.read_targets(str(path))
    assert len(targets) == 40 and made == []
    first = next(iter(targets))
    assert len(made) == 1 and first.name == "target 1"
    assert [t.name for t in targets][-1] == "target 40"
    for row, message in (("1e300,0,0,0,0,1,1", r"row 7: target position x 1e\+300 m is past"),
                         ("0,0,0,0,0,0,0", "row 7: a quaternion of length 0"),
                         ("0,0,0,1e-200,1e-200,0,0", "row 7: a quaternion of length 0")):
        path.write_text("x,y,z,qx,qy,qz,qw\n" + "0.1,0,0.3,0,0,1,1\n" * 6 + row + "\n"
                        + "0,0,0,0,0,0,0\n")
        with pytest.raises(ConfigError, match=message):
            ik.read_targets(str(path))
    path.write_text("x,y,z,qx,qy,qz,qw\n0,0,0,0,0,0,1e-11\n")  # (near the shortest: asked)
    assert next(iter(ik.read_targets(str(path)))).rotation is not None

# -- the command ----------------------------------------------------------------------------


def test_cli_solves_and_its_words_reproduce_the_pose_in_fk(run_cli):
    result = run_cli("ik", HUMANOID, "--base", "body_link", "--tip", "l_foot_link",
                     "--target-frame", "l_foot_link", "--target-q", "l_knee=1",
                     "--target-q", "l_hip_pitch=-0.5", "--target-q", "l_ank_pitch=-0.5",
                     "--q", "r_knee=0.5", "-f", "json")
    assert result.exit_code == 0, result.output
    document = json.loads(result.output)
    assert document["solved"] and document["position_error"] <= 1e-6
    assert "--q r_knee=0.5" in document["q_words"]
    fk = run_cli("fk", HUMANOID, "--base", "body_link", "--frame", "l_foot_link", "-f", "json",
                 *document["q_words"].split())
    assert fk.exit_code == 0, fk.output
    position = json.loads(fk.output)["frames"][0]["position"]
    assert np.allclose(position, document["position"], atol=1e-6)


def test_cli_text_unreachable_exits_1_with_the_closest_pose(run_cli):
    result = run_cli("ik", HUMANOID, "--tip", "l_forearm_link", "--xyz", "0.5", "0.5", "0.5",
                     "--seeds", "2")
    assert result.exit_code == 1
    assert "UNREACHABLE" in result.output and "closest pose reached: xyz" in result.output
    assert "out of reach" in result.output


def test_a_target_past_what_the_solver_squares_is_refused_where_it_was_given(run_cli, tmp_path):
    """A target at 1e308 was "UNREACHABLE ... the target is inf m from the limb's first joint"
    after numpy's overflow warnings: the solver squares distances. Every target is made by
    ``Target``, which refuses it, said at the option or row that gave it."""
    table = tmp_path / "far.csv"
    table.write_text("x,y,z\n0.1,0,0\n0,-1e200,0\n")
    said = {}
    for name, words in (("--xyz", ["--xyz", "1e308", "0", "0"]),
                        ("--check-reach", ["--check-reach", str(table)])):
        result = run_cli("ik", HUMANOID, "--tip", "l_forearm_link", "--seeds", "2", *words)
        assert result.exit_code == 2, result.output
        said[name] = result.output
    assert "--xyz: target position x 1e+308 m is past what the solver computes with" \
        in said["--xyz"]
    assert "far.csv: row 2: target position y -1e+200 m" in said["--check-reach"]
    assert "inf" not in "".join(said.values()) and "Warning" not in "".join(said.values())
    with pytest.raises(ConfigError):
        ik.Target(np.array([0.0, 0.0, math.inf]))
    assert ik.Target(np.array([0.0, 0.0, ik.MAX_TARGET])).position[2] == 1e150


@pytest.mark.parametrize("command", ["ik", "workspace"])
def test_a_point_the_kinematics_cannot_square_is_refused_at_its_option(run_cli, command):
    """One step from the targets: ``--point 1e308 0 0`` (the point on --tip placed) gave
    numpy's overflow warnings and "max reach inf m", "manipulability: min inf" in workspace;
    build_chain, where every point enters, refuses it past numbers.SQUARABLE."""
    words = ["--xyz", "0.1", "0", "0", "--seeds", "2"] if command == "ik" else ["--samples", "5"]
    result = run_cli(command, HUMANOID, "--tip", "l_forearm_link", "--point", "1e308", "0", "0",
                     *words)
    assert result.exit_code == 2, result.output
    assert "--point: point x 1e+308 m is past what the kinematics computes with" in \
        result.output
    assert "inf" not in result.output and "Warning" not in result.output


def test_cli_check_reach(run_cli, humanoid, tmp_path):
    chain = build_chain(humanoid, "body_link", "l_forearm_link")
    pose = _fk_pose(chain, chain.row_of(np.array([0.2, 0.3, -0.4])))
    path = tmp_path / "cell.csv"
    path.write_text("x,y,z\n" + ",".join(repr(float(v)) for v in pose[:3, 3]) + "\n1,1,1\n")
    result = run_cli("ik", HUMANOID, "--base", "body_link", "--tip", "l_forearm_link",
                     "--check-reach", path)
    assert result.exit_code == 1, result.output
    lines = result.output.splitlines()
    assert "target 1" in lines[1] and "reachable" in lines[1] and "UNREACHABLE" not in lines[1]
    assert "UNREACHABLE" in lines[2]
    assert lines[-1] == "1 of 2 targets reachable"
    path.write_text("x,y,z\n" + ",".join(repr(float(v)) for v in pose[:3, 3]) + "\n")
    assert run_cli("ik", HUMANOID, "--base", "body_link", "--tip", "l_forearm_link",
                   "--check-reach", path).exit_code == 0


@pytest.mark.parametrize("args,message", [
    (["--tip", "l_foot_link"], "give one target"),
    (["--tip", "l_foot_link", "--xyz", "0", "0", "0", "--rpy", "0", "0", "0", "--quat", "0",
      "0", "0", "1"], "--rpy or --quat, not both"),
    (["--tip", "l_foot_link", "--xyz", "0", "0", "0", "--seeds", "0"], "--seeds must be"),
    (["--tip", "l_foot_link", "--xyz", "0", "0", "0", "--q", "l_kne=1"],
     "--q: unknown joint 'l_kne'; did you mean 'l_knee'"),
    (["--tip", "l_foot_link", "--target-frame", "l_fot_link"],  # a traceback before
     "link 'l_fot_link' does not exist; did you mean 'l_foot_link'"),
    (["--tip", "l_foot_link", "--target-frame", "l_foot_link", "--target-q", "l_kne=1"],
     "--target-q: unknown joint 'l_kne'"),
    (["--tip", "l_foot_link", "--xyz", "0", "0", "0", "--quat", "0", "0", "0", "0"],
     "--quat: a quaternion of length 0 is no rotation"),
])
def test_cli_usage_errors(run_cli, args, message):
    result = run_cli("ik", HUMANOID, *args)
    assert result.exit_code == 2
    assert message in result.output


def test_solve_limb_says_which_input_a_configuration_error_is_about(humanoid):
    """The core names its parameters, never an option: the command maps them to its flags."""
    for inputs, argument in (({"q": {"l_kne": "1"}, "xyz": (0, 0, 0)}, "q"),
                             ({"xyz": (0, 0, 0), "quaternion": (0, 0, 0, 0)}, "orientation"),
                             ({"frame": "l_foot_link", "frame_q": {"l_kne": "1"}}, "frame_q")):
        with pytest.raises(ConfigError) as raised:
            ik.solve_limb(humanoid, "l_foot_link", "body_link", **inputs)
        assert raised.value.argument == argument and "--" not in str(raised.value)
    found = ik.solve_limb(humanoid, "l_foot_link", "body_link", q={"l_knee": "9"},
                          frame="l_foot_link", frame_q={"l_knee": "1"}, name="there")
    [solution] = found.solutions
    assert solution.solved and solution.target.name == "there"
    assert found.chain.tip == "l_foot_link" and "outside its limits" in found.warnings[0]


def test_cli_csv(run_cli):
    result = run_cli("ik", HUMANOID, "--base", "l_hip_link", "--tip", "l_ankle_link",
                     "--target-frame", "l_ankle_link", "--target-q", "l_knee=1", "-f", "csv")
    assert result.exit_code == 0, result.output
    header, row = result.output.splitlines()
    assert header.endswith("l_hip_pitch,l_knee,l_ank_pitch")
    assert float(row.split(",")[-2]) == pytest.approx(1.0)


def test_a_point_on_the_tip_is_placed(humanoid):
    point = np.array([0.0, 0.0, -0.07])
    chain = build_chain(humanoid, "body_link", "l_forearm_link", point=point)
    x = np.array([0.3, 0.4, -0.9])
    pose = _fk_pose(chain, chain.row_of(x))
    hand = pose[:3, 3] + pose[:3, :3] @ point
    solution = ik.solve(chain, ik.Target(hand), ik.seeds(chain, 8, 0))
    assert solution.solved
    reached = _fk_pose(chain, solution.row)
    assert np.linalg.norm(reached[:3, 3] + reached[:3, :3] @ point - hand) <= 1e-6


def _revolute(name, parent, child, xyz, axis, limit=3.0):
    return (f'<joint name="{name}" type="revolute"><parent link="{parent}"/>'
            f'<child link="{child}"/><origin xyz="{xyz}"/><axis xyz="{axis}"/>'
            f'<limit lower="{-limit}" upper="{limit}" effort="1" velocity="1"/></joint>')


# a PUMA-like arm: a vertical waist, shoulder and elbow about y (the shoulder axis offset along
# itself, still meeting the waist's), a wrist of three axes meeting in one point, a tool offset
PUMA = ("<robot name='puma'>" + "".join(f'<link name="{n}"/>' for n in (
    "base", "waist", "upper", "fore", "wrist1", "wrist2", "flange", "tool")) + "".join((
        _revolute("j1", "base", "waist", "0 0 0.3", "0 0 1"),
        _revolute("j2", "waist", "upper", "0 0.1 0", "0 1 0"),
        _revolute("j3", "upper", "fore", "0.4 0 0", "0 1 0"),
        _revolute("j4", "fore", "wrist1", "0.1 0 0.05", "1 0 0"),
        _revolute("j5", "wrist1", "wrist2", "0.3 0 0", "0 1 0"),
        _revolute("j6", "wrist2", "flange", "0 0 0", "1 0 0"),
        '<joint name="t" type="fixed"><parent link="flange"/><child link="tool"/>'
        '<origin xyz="0.08 0 0.01"/></joint>')) + "</robot>").encode()


def test_spherical_wrist_closed_form_agrees_with_numeric(tmp_path):
    chain = build_chain(_robot(tmp_path, PUMA), "base", "tool")
    assert ik.spherical(chain) is not None
    starts = ik.seeds(chain, 16, 0)
    for x, target in _reachable(chain, 25, 9):
        closed = ik.closed_form(chain, target, x)
        _check(chain, closed, target, 1e-9)
        assert closed.method == "closed form"
        # the generating configuration is one of the branches: seeded there, it is found
        assert np.allclose(closed.x, x, atol=1e-7)
        numeric = ik.solve(chain, target, starts, method="numeric")
        _check(chain, numeric, target)
        assert ik.solve(chain, target, starts).method == "closed form"  # auto takes it


def test_spherical_wrist_needs_meeting_axes(tmp_path):
    offset = PUMA.replace(b'<origin xyz="0 0 0"/><axis xyz="1 0 0"/>',
                          b'<origin xyz="0 0.02 0"/><axis xyz="1 0 0"/>')
    assert offset != PUMA
    chain = build_chain(_robot(tmp_path, offset), "base", "tool")
    assert ik.spherical(chain) is None  # the sixth axis passes 2 cm beside the wrist centre
    ur5 = build_chain(load(str(corpus_or_skip() / "ur_description" / "urdf" / "ur5.xacro")),
                      "base_link", "tool0")
    assert ik.spherical(ur5) is None  # UR's wrist axes do not meet


# ---- issue 29, class 10: degenerate limbs ----------------------------------------------------

_BODY = ('<inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" '
         'iyz="0"/></inertial><collision><geometry><box size="0.05 0.05 0.05"/></geometry>'
         '</collision>')


def _limb(kinds: list[str]) -> str:
    """A robot whose limb from 'base' to the last link is the joints ``kinds``, in turn."""
    links = ["base", *(f"l{i}" for i in range(len(kinds)))]
    text = ['<robot name="limb">', *(f'<link name="{name}">{_BODY}</link>' for name in links)]
    for i, kind in enumerate(kinds):
        limit = {"revolute": '<limit lower="-1" upper="1" effort="1" velocity="1"/>',
                 "prismatic": '<limit lower="-1" upper="1" effort="1" velocity="1"/>',
                 "continuous": '<limit effort="1" velocity="1"/>'}.get(kind, "")
        text.append(f'<joint name="j{i}" type="{kind}"><parent link="{links[i]}"/>'
                    f'<child link="{links[i + 1]}"/><origin xyz="0 0 0.1"/>'
                    f'<axis xyz="0 1 0"/>{limit}</joint>')
    return "\n".join([*text, "</robot>"])


@pytest.mark.parametrize("kinds", [["revolute"], ["prismatic"], ["continuous"],
                                   ["fixed", "revolute"], ["prismatic", "prismatic"]],
                         ids=lambda kinds: "+".join(kinds))
@pytest.mark.parametrize("orientation", [(), ("--rpy", "0", "0", "0")], ids=["xyz", "pose"])
def test_a_limb_of_one_joint_is_solved(run_cli, tmp_path, kinds, orientation):
    """Pinocchio hands back the Jacobian of a one-velocity limb as a vector of 6: ik raised
    ValueError (solve1: not enough dimensions) on one revolute, prismatic or continuous joint."""
    path = tmp_path / "limb.urdf"
    path.write_text(_limb(kinds))
    tip = f"l{len(kinds) - 1}"
    result = run_cli("ik", path, "--tip", tip, "--xyz", "0", "0", 0.1 * len(kinds),
                     *orientation, "--format", "json", "--timeout", "0", "--max-memory", "0")
    assert result.exit_code == 0, result.output
    assert json.loads(result.stdout)["solved"] is True


@pytest.mark.parametrize("kinds", [[], ["fixed", "fixed"]], ids=["no joint", "fixed only"])
def test_a_limb_that_cannot_move_is_a_located_error(run_cli, tmp_path, kinds):
    path = tmp_path / "limb.urdf"
    path.write_text(_limb(kinds))
    result = run_cli("ik", path, "--tip", f"l{len(kinds) - 1}" if kinds else "base",
                     "--xyz", "0", "0", "0.1", "--timeout", "0", "--max-memory", "0")
    assert result.exit_code in (1, 2) and "Traceback" not in result.output
    assert "no joint moves" in result.output


@pytest.mark.parametrize("command, kinds", [
    (["workspace", "{path}", "--tip", "l0", "--samples", "10"], ["continuous"]),
    (["workspace", "{path}", "--tip", "l0", "--samples", "10"], ["revolute"]),
    (["dynamics", "{path}", "--support", "base"], ["fixed"]),
    (["dynamics", "{path}", "--support", "base"], []),
    (["dh", "{path}", "--base", "base", "--tip", "l0"], ["prismatic"]),
    (["dh", "{path}", "--base", "base", "--tip", "l0"], []),
    (["fk", "{path}"], []),
], ids=["workspace-continuous", "workspace-revolute", "dynamics-fixed", "dynamics-no-joint",
        "dh-prismatic", "dh-no-joint", "fk-no-joint"])
def test_the_other_analyses_take_degenerate_limbs(run_cli, tmp_path, command, kinds):
    """The neighbours of the ik crash: workspace on one continuous joint (the same Jacobian),
    dynamics --support of a robot with no moving joint (max() of nothing)."""
    path = tmp_path / "limb.urdf"
    path.write_text(_limb(kinds))
    words = [word.replace("{path}", str(path)) for word in command]
    if not kinds:
        words = [word if word != "l0" else "base" for word in words]
    result = run_cli(*words, "--timeout", "0", "--max-memory", "0")
    assert result.exit_code in (0, 1, 2) and result.exception is None or \
        isinstance(result.exception, SystemExit), result.output
    assert "Traceback" not in result.output


def test_pinocchio_frame_jacobians_come_from_one_function():
    """getFrameJacobian is called in kinematics/chain.py's frame_jacobian alone, which makes
    its answer [6, nv] whatever nv is."""
    from pathlib import Path

    import urdftool

    package = Path(urdftool.__file__).parent
    callers = sorted(path.relative_to(package).as_posix() for path in package.rglob("*.py")
                     if "getFrameJacobian(" in path.read_text())
    assert callers == ["kinematics/chain.py"]
    assert (package / "kinematics" / "chain.py").read_text().count("getFrameJacobian(") == 1
def test_cli_check_reach_reads_comment_lines(run_cli, humanoid, tmp_path):
    chain = build_chain(humanoid, "body_link", "l_forearm_link")
    pose = _fk_pose(chain, chain.row_of(np.array([0.2, 0.3, -0.4])))
    path = tmp_path / "cell.csv"
    path.write_text("# the work cell's targets, in body_link\nx,y,z\n"
                    "  # the first one is reached at the pose above\n"
                    + ",".join(repr(float(v)) for v in pose[:3, 3]) + "\n# far away\n1,1,1\n")
    result = run_cli("ik", HUMANOID, "--base", "body_link", "--tip", "l_forearm_link",
                     "--check-reach", path)
    assert result.exit_code == 1, result.output
    assert result.output.splitlines()[-1] == "1 of 2 targets reachable"


def test_a_wrong_row_after_comments_is_located_on_its_own_line(tmp_path):
    from urdftool.kinematics.configuration import ConfigError, read_table

    path = tmp_path / "cell.csv"
    path.write_text("# comment\nx,y,z\n# another\n1,2\n")
    with pytest.raises(ConfigError) as raised:
        read_table(str(path), "target file", "column")
    assert raised.value.where == f"{path}:4"


def test_a_point_far_off_the_tip_is_solved_not_spent_on_steps_of_nan(humanoid):
    """attack25: with ``--point 1e4 0 0`` J^T J is 1e8, the absolute damping (1e-12) vanishes
    beside it, and the leg's hessian is singular to the bit: the solve was NaN (numpy's
    "invalid value" warning, 101 of them over these targets), each seed spent on steps of NaN
    (1 of the 20 targets reached). Such a solve is damped again, relative to the hessian."""
    import warnings

    chain = build_chain(humanoid, None, "l_foot_link", point=(1e4, 0.0, 0.0))
    starts = ik.seeds(chain, 8, 1)
    reached = 0
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        for x in config.random(chain.variables, 10, 5).values:
            pose = chain.pose(x)
            for rotation in (None, np.array(pose.rotation)):
                target = ik.Target(np.array(pose.translation), rotation)
                solution = ik.solve(chain, target, starts, method="numeric")
                reached += solution.solved
                assert np.isfinite(solution.x).all()
    assert reached >= 5
