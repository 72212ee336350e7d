"""Forward kinematics: the vectorised FK against Pinocchio, configurations, and the CLI."""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest

from conftest import ROBOTS, corpus_or_skip, walked
from urdftool.kinematics import configuration as config
from urdftool.physics import mat3
from urdftool.kinematics import transforms
from urdftool.kinematics.fk import FKError, KinematicModel, forward_kinematics, pose_components
from urdftool.description.load import load
from urdftool.description.urdf import JOINT_TYPES, MOVING

HUMANOID = ROBOTS / "humanoid" / "humanoid.urdf.xacro"

# world root + floating joint, continuous joint on a negative axis, mimic joint, prismatic joint
TINY = b"""<robot name="tiny">
  <link name="world"/><link name="a"/><link name="b"/><link name="c"/><link name="d"/>
  <joint name="free" type="floating"><parent link="world"/><child link="a"/>
    <origin xyz="0 0 1"/></joint>
  <joint name="spin" type="continuous"><parent link="a"/><child link="b"/>
    <origin xyz="0.1 0.2 0.3" rpy="0.1 0.2 0.3"/><axis xyz="0 0 -1"/></joint>
  <joint name="follow" type="revolute"><parent link="b"/><child link="c"/>
    <origin xyz="0.5 0 0"/><axis xyz="0 0.6 0.8"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
    <mimic joint="spin" multiplier="2" offset="0.1"/></joint>
  <joint name="slide" type="prismatic"><parent link="c"/><child link="d"/>
    <axis xyz="1 0 0"/><limit lower="0.1" upper="0.5" effort="1" velocity="1"/></joint>
</robot>"""


@pytest.fixture(scope="module")
def humanoid():
    return KinematicModel(load(HUMANOID))


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    path = tmp_path_factory.mktemp("fk") / "tiny.urdf"
    path.write_bytes(TINY)
    return KinematicModel(load(path))


def _pinocchio_poses(model, values):
    import pinocchio

    data = model.model.createData()
    q = model.pinocchio_q(values)
    out = np.empty((len(values), len(model.links), 4, 4))
    for row in range(len(values)):
        pinocchio.forwardKinematics(model.model, data, q[row])
        pinocchio.updateFramePlacements(model.model, data)
        for k, name in enumerate(model.links):
            frame = model.model.getFrameId(name, pinocchio.FrameType.BODY)
            out[row, k] = data.oMf[frame].homogeneous
    return out


@pytest.mark.parametrize("floating", [False, True])
def test_vectorised_fk_matches_pinocchio_on_humanoid(floating):
    model = KinematicModel(load(HUMANOID), floating=floating)
    values = config.random(model.variables, 30, seed=4).values
    np.testing.assert_allclose(model.link_poses(values), _pinocchio_poses(model, values),
                               atol=1e-12)


def test_tiny_model_with_floating_continuous_mimic_prismatic_matches_pinocchio(tiny):
    names = [v.name for v in tiny.variables]
    assert names == ["free.x", "free.y", "free.z", "free.roll", "free.pitch", "free.yaw",
                     "spin", "slide"]  # the mimic joint is not a variable
    values = config.random(tiny.variables, 20, seed=1).values
    np.testing.assert_allclose(tiny.link_poses(values), _pinocchio_poses(tiny, values),
                               atol=1e-12)
    assert tiny.model.nq == 7 + 2 + 1 + 1  # free-flyer quaternion, continuous cos/sin


def test_a_planar_joint_matches_pinocchio(tmp_path):
    """A planar joint (x, y in its frame's plane, yaw about its z; Pinocchio's q x, y, cos,
    sin) in a tilted frame, below it an arm: fk's poses are Pinocchio's."""
    path = tmp_path / "planar.urdf"
    path.write_text('<robot name="p"><link name="w"/><link name="b"/><link name="a"/>'
                    '<joint name="slide" type="planar"><parent link="w"/><child link="b"/>'
                    '<origin xyz="0.1 0 0.2" rpy="0.3 -0.4 0.2"/><axis xyz="0 0 1"/></joint>'
                    '<joint name="elbow" type="revolute"><parent link="b"/><child link="a"/>'
                    '<origin xyz="0.2 0 0"/><axis xyz="1 0 0"/>'
                    '<limit lower="-2" upper="2" effort="1" velocity="1"/></joint></robot>')
    model = KinematicModel(load(path))
    assert [v.name for v in model.variables] == ["slide.x", "slide.y", "slide.yaw", "elbow"]
    values = config.random(model.variables, 20, seed=2).values
    np.testing.assert_allclose(model.link_poses(values), _pinocchio_poses(model, values),
                               atol=1e-12)


def test_mimic_joint_follows_with_multiplier_and_offset(tiny):
    spin = tiny.variables[[v.name for v in tiny.variables].index("spin")]
    assert spin.kind == "continuous"
    values = config.defaults(tiny.variables)[None]
    values[0, 6] = 0.3
    assert tiny.joint_values(values, "follow")[0] == pytest.approx(2 * 0.3 + 0.1)
    poses = tiny.link_poses(values)[0]
    b, c = tiny.links.index("b"), tiny.links.index("c")
    relative = transforms.invert(poses[b]) @ poses[c]
    expected = np.eye(4)
    expected[:3, :3] = transforms.rotations_about((0, 0.6, 0.8), np.array(0.7))
    expected[:3, 3] = (0.5, 0, 0)
    np.testing.assert_allclose(relative, expected, atol=1e-12)


def test_default_is_mid_range_when_zero_is_outside_limits(tiny):
    slide = tiny.variables[-1]
    assert (slide.lower, slide.upper, slide.default) == (0.1, 0.5, pytest.approx(0.3))
    assert tiny.variables[0].default == 0.0


def test_floating_root_pose_and_base_option(tiny):
    words = {"free.x": "1", "free.yaw": "90", "spin": "0"}
    configurations = config.from_words(tiny.variables, words, degrees=True)
    assert configurations.values[0, 0] == 1.0  # metres are not scaled by --deg
    result = forward_kinematics(tiny, configurations, ["a"], None)
    position, rpy, quaternion = pose_components(result.matrices[0, 0])
    np.testing.assert_allclose(position, [1, 0, 1], atol=1e-12)
    np.testing.assert_allclose(rpy, [0, 0, math.pi / 2], atol=1e-12)
    np.testing.assert_allclose(quaternion, [0, 0, math.sqrt(0.5), math.sqrt(0.5)], atol=1e-12)
    relative = forward_kinematics(tiny, configurations, ["a"], "a")
    np.testing.assert_allclose(relative.matrices[0, 0], np.eye(4), atol=1e-12)
    assert relative.base == "a" and result.base == "world"


def test_floating_keeps_a_robots_own_free_base(tiny, run_cli, tmp_path):
    """TINY hangs from a massless 'world' by its own floating joint 'free': --floating adds no
    second free base above it (it added 'root_joint', which moved 'world' too)."""
    free = KinematicModel(tiny.robot, floating=True)
    assert [v.name for v in free.variables] == [v.name for v in tiny.variables]
    assert not free.floating and free.root_frame == "world"
    path = tmp_path / "tiny.urdf"
    path.write_bytes(TINY)
    result = run_cli("fk", path, "--floating", "--q", "free.z=2", "--frame", "world",
                     "--frame", "a", "-f", "json")
    assert result.exit_code == 0, result.output
    frames = {f["frame"]: f["position"] for f in json.loads(result.stdout)["frames"]}
    assert frames == {"world": [0.0, 0.0, 0.0], "a": [0.0, 0.0, 3.0]}
    refused = run_cli("fk", path, "--floating", "--q", "root_joint.z=2")
    assert refused.exit_code == 2 and "unknown joint 'root_joint.z'" in refused.output


def test_humanoid_leg_pose_by_hand(humanoid):
    configurations = config.from_words(humanoid.variables, {"l_knee": "90"}, degrees=True)
    pose = forward_kinematics(humanoid, configurations, ["l_foot_link"], "body_link").matrices[0, 0]
    # hip 0.122 below the body, thigh 0.093 down, then the shin points 0.093 backwards (-x)
    np.testing.assert_allclose(pose[:3, 3], [-0.093, 0.037, -0.122 - 0.093], atol=1e-12)


def test_unknown_joint_lists_valid_names(humanoid):
    with pytest.raises(config.ConfigError, match="^unknown joint 'l_kne'; did you mean 'l_knee'"
                                                 ".*available joints"):  # no option named
        config.from_words(humanoid.variables, {"l_kne": "1"})


def test_setting_a_mimic_joint_names_its_master(tiny):
    with pytest.raises(config.ConfigError, match="'follow' mimics 'spin'"):
        config.from_words(tiny.variables, {"follow": "1"}, mimics=tiny.mimics)


def test_non_numeric_value(humanoid):
    with pytest.raises(config.ConfigError, match="^value 'abc' for joint 'l_knee' is not a "
                                                 "number"):
        config.from_words(humanoid.variables, {"l_knee": "abc"})


def test_out_of_limits_warns_and_computes(humanoid):
    configurations = config.from_words(humanoid.variables, {"l_knee": "-1"})
    assert configurations.warnings == [
        "joint 'l_knee' = -1 is outside its limits [0, 2.26893]; computed anyway"]
    assert configurations.values[0, [v.name for v in humanoid.variables].index("l_knee")] == -1


def test_q_file_csv_wrong_column_count_is_located_by_row(humanoid, tmp_path):
    path = tmp_path / "q.csv"
    path.write_text("l_knee,l_hip_pitch\n0.1,0.2\n\n0.3\n")
    with pytest.raises(config.ConfigError, match=r"q\.csv:4: row has 1 values but the header "
                                                 "names 2 joints"):
        config.from_file(humanoid.variables, str(path))


@pytest.mark.parametrize("reader, text, name", [
    ("q", "l_knee,l_knee\n0.1,0.5\n", "l_knee"),  # (this one was refused; the rest were not)
    ("q", '[{"l_knee": 0.1, "l_knee": 0.5}]', "l_knee"),
    ("targets", "x,y,z,x\n0.1,0,0,5\n", "x"),
    ("targets", '[{"x": 0.1, "y": 0, "z": 0, "x": 5}]', "x"),
])
def test_a_file_of_numbers_naming_a_column_twice_is_refused(humanoid, tmp_path, reader, text, name):
    """Which of two values for one joint or coordinate is meant is a guess: ``json`` and
    ``csv.DictReader`` took the last (``ik --targets`` solved for x = 5). ``read_table``,
    the one reader of files of numbers, refuses it for every command."""
    from urdftool.kinematics import ik

    path = tmp_path / ("t.json" if text.startswith("[") else "t.csv")
    path.write_text(text)
    with pytest.raises(config.ConfigError, match=f"'{name}' is (named|given) twice"):
        if reader == "q":
            config.from_file(humanoid.variables, str(path))
        else:
            ik.read_targets(str(path))


@pytest.mark.parametrize("text", ["l_knee,l_hip_pitch\r\n0.1,0.2\r\n", '[{"l_knee": 0.1, "l_hip_pitch": 0.2}]'])
def test_a_file_of_numbers_with_a_byte_order_mark_is_read(humanoid, tmp_path, text):
    """Excel's "CSV UTF-8" starts with a byte-order mark: it was read as part of the first
    name ("unknown joint '\\ufeffl_knee'"), and JSON refused it."""
    from urdftool.kinematics import ik

    path = tmp_path / ("q.json" if text.startswith("[") else "q.csv")
    path.write_bytes(b"\xef\xbb\xbf" + text.encode())
    values = config.from_file(humanoid.variables, str(path)).values[0]
    names = [v.name for v in humanoid.variables]
    assert (values[names.index("l_knee")], values[names.index("l_hip_pitch")]) == (0.1, 0.2)
    (tmp_path / "t.csv").write_bytes(b"\xef\xbb\xbfx,y,z\n0.1,0,0.2\n")
    assert len(ik.read_targets(str(tmp_path / "t.csv"))) == 1


def test_q_file_non_numeric_cell_is_located_by_row(humanoid, tmp_path):
    path = tmp_path / "q.csv"
    path.write_text("l_knee\n0.1\nnope\n")
    with pytest.raises(config.ConfigError, match="row 2: value 'nope'"):
        config.from_file(humanoid.variables, str(path))


def test_q_file_json_and_csv_agree(humanoid, tmp_path):
    (tmp_path / "q.csv").write_text("l_knee,l_hip_pitch\n10,20\n30,40\n")
    (tmp_path / "q.json").write_text(json.dumps([{"l_knee": 10, "l_hip_pitch": 20},
                                                 {"l_knee": 30, "l_hip_pitch": 40}]))
    from_csv = config.from_file(humanoid.variables, str(tmp_path / "q.csv"), degrees=True)
    from_json = config.from_file(humanoid.variables, str(tmp_path / "q.json"), degrees=True)
    np.testing.assert_array_equal(from_csv.values, from_json.values)
    assert from_csv.values.shape == (2, 20)
    # l_hip_pitch's limits are [-100, 30] deg: 40 deg in row 2 is outside
    assert from_csv.warnings == ["joint 'l_hip_pitch' = 0.698132 is outside its limits "
                                 "[-1.74533, 0.523599] in 1 row(s), first row 2; computed anyway"]


def test_random_configurations_stay_within_limits(humanoid):
    values = config.random(humanoid.variables, 500, seed=3).values
    lower = np.array([v.lower for v in humanoid.variables])
    upper = np.array([v.upper for v in humanoid.variables])
    assert np.all(values >= lower) and np.all(values <= upper)
    np.testing.assert_array_equal(values, config.random(humanoid.variables, 500, seed=3).values)


def test_unknown_frame_lists_links(humanoid):
    from urdftool.errors import UnknownLink

    with pytest.raises(UnknownLink, match="did you mean 'l_foot_link'"):
        forward_kinematics(humanoid, config.random(humanoid.variables, 1, 0), ["l_foot"])


def test_quaternion_and_rpy_round_trip():
    rpy = np.random.default_rng(0).uniform(-3, 3, size=(200, 3))
    rpy[:, 1] /= 2.5  # keep pitch within (-pi/2, pi/2) where rpy is unique
    rotations = transforms.rotation_from_rpy(rpy)
    # a round trip alone passes for any convention: pin it to mat3's Rz(y) Ry(p) Rx(r)
    np.testing.assert_allclose(rotations, [mat3.rpy_matrix(row) for row in rpy], atol=1e-15)
    np.testing.assert_allclose(transforms.rpy_from_rotation(rotations), rpy, atol=1e-12)
    x, y, z, w = np.moveaxis(transforms.quaternion_from_rotation(rotations), -1, 0)
    rebuilt = np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1)], -2)
    np.testing.assert_allclose(rebuilt, rotations, atol=1e-12)
    assert np.all(w >= 0)


def test_panda_fk_matches_pinocchio():
    path = corpus_or_skip() / "franka_description/robots/panda/panda.urdf.xacro"
    model = KinematicModel(load(path))
    values = config.random(model.variables, 10, seed=2).values
    np.testing.assert_allclose(model.link_poses(values), _pinocchio_poses(model, values),
                               atol=1e-12)


# -- CLI -----------------------------------------------------------------------------------------

def test_cli_json_single_configuration(run_cli):
    result = run_cli("fk", HUMANOID, "--base", "body_link", "--frame", "l_foot_link",
                     "--q", "l_knee=90", "--deg", "-f", "json")
    assert result.exit_code == 0, result.output
    document = json.loads(result.stdout)
    assert set(document) == {"base", "frames"} and document["base"] == "body_link"
    (frame,) = document["frames"]
    assert set(frame) == {"frame", "position", "rpy", "quaternion"}
    np.testing.assert_allclose(frame["position"], [-0.093, 0.037, -0.215], atol=1e-12)


def test_cli_q_file_gives_one_document_per_row_and_csv(run_cli, tmp_path):
    path = tmp_path / "q.csv"
    path.write_text("l_knee\n0.5\n1.0\n1.5\n")
    result = run_cli("fk", HUMANOID, "--q-file", path, "--frame", "l_shin_link", "-f", "json")
    assert result.exit_code == 0, result.output
    documents = json.loads(result.stdout)
    assert isinstance(documents, list) and len(documents) == 3
    assert all(set(d) == {"base", "frames"} and [f["frame"] for f in d["frames"]] ==
               ["l_shin_link"] for d in documents)
    result = run_cli("fk", HUMANOID, "--q-file", path, "--frame", "l_shin_link", "-f", "csv",
                     "--matrix")
    lines = result.stdout.splitlines()
    assert lines[0].startswith("row,base,frame,x,y,z,roll,pitch,yaw,qx,qy,qz,qw,m00")
    assert len(lines) == 4


def test_cli_bad_inputs(run_cli, tmp_path):
    result = run_cli("fk", HUMANOID, "--q", "l_kne=1")
    assert result.exit_code == 2 and "did you mean 'l_knee'" in result.stderr
    assert result.stderr.startswith("urdftool: error: --q: unknown joint 'l_kne'")
    result = run_cli("fk", HUMANOID, "--q", "l_knee=one")
    assert result.stderr == ("urdftool: error: --q: value 'one' for joint 'l_knee' is not a "
                             "number\n") and result.exit_code == 2
    result = run_cli("fk", HUMANOID, "--q", "l_knee")
    assert result.stderr == "urdftool: error: --q must be NAME=VALUE, got 'l_knee'\n"
    # --q goes through the one NAME=VALUE parser (cli._common.pairs); blanks around names are
    # dropped, as before
    for word in ("l_knee", "=1", " =1"):
        result = run_cli("fk", HUMANOID, "--q", word)
        assert (result.exit_code, result.stderr) == (
            2, f"urdftool: error: --q must be NAME=VALUE, got '{word}'\n")
    assert run_cli("fk", HUMANOID, "--q", " l_knee =0.5", "--frame", "l_foot_link").exit_code == 0
    result = run_cli("fk", HUMANOID, "--q", "l_knee=-0.5", "--frame", "l_foot_link")
    assert result.exit_code == 0
    assert "warning: joint 'l_knee' = -0.5 is outside its limits" in result.stderr
    path = tmp_path / "q.csv"
    path.write_text("l_knee,l_el\n1,2,3\n")
    result = run_cli("fk", HUMANOID, "--q-file", path)
    assert result.exit_code == 2 and "q.csv:2: row has 3 values" in result.stderr
    assert "--q" not in result.stderr  # a file's error names the file, not an option
    assert "Traceback" not in result.output


def test_cli_text_table(run_cli):
    result = run_cli("fk", HUMANOID, "--frame", "head_link", "--matrix")
    assert result.exit_code == 0, result.output
    assert "head_link" in result.stdout and "x [m]" in result.stdout


def test_text_shows_no_negative_zero(run_cli):
    # the crouched leg's foot is back under the hip up to round-off (x = -3e-17)
    result = run_cli("fk", HUMANOID, "--base", "body_link", "--frame", "l_foot_link",
                     "--q", "l_hip_pitch=-30", "--q", "l_knee=60", "--q", "l_ank_pitch=-30", "--deg")
    assert result.exit_code == 0, result.output
    assert "-0.000000" not in result.output and "0.037000" in result.output


def test_floating_poses_are_relative_to_the_world_not_the_moving_root(run_cli):
    result = run_cli("fk", HUMANOID, "--floating", "--q", "root_joint.z=1", "--frame",
                     "body_link", "-f", "json")
    assert result.exit_code == 0, result.output
    document = json.loads(result.stdout)
    assert document["base"] == "world"
    np.testing.assert_allclose(document["frames"][0]["position"][2], 1.0 + _body_height(),
                               atol=1e-12)


def _body_height() -> float:
    model = KinematicModel(load(HUMANOID))
    result = forward_kinematics(model, config.from_words(model.variables, {}), ["body_link"])
    return float(result.matrices[0, 0, 2, 3])


def test_a_long_fk_table_is_plain_text(tmp_path, run_cli):
    from conftest import synthetic_robot

    robot = synthetic_robot(tmp_path, 120)
    result = run_cli("fk", robot, "--timeout", "0")
    assert result.exit_code == 0, result.output
    lines = result.stdout.splitlines()
    assert lines[0] == "poses relative to l0" and len(lines) == 2 + 120
    assert lines[-1].split()[0] == "l119" and not any(c in result.stdout for c in "┃│━─")
# -- fk --random: the joint values drawn, so that each pose can be computed again --------------

def test_random_configurations_are_given_with_their_values(run_cli):
    import shlex

    robot = ROBOTS / "humanoid" / "humanoid.urdf.xacro"
    result = run_cli("fk", robot, "--random", "3", "--seed", "11", "--frame", "l_foot_link",
                     "-f", "json")
    assert result.exit_code == 0, result.output
    documents = json.loads(result.output)
    assert [d["seed"] for d in documents] == [11, 11, 11]
    for document in documents:
        words = [f"{name}={value!r}" for name, value in document["q"].items()]
        again = run_cli("fk", robot, *[w for word in words for w in ("--q", word)],
                        "--frame", "l_foot_link", "-f", "json")
        assert json.loads(again.output)["frames"] == document["frames"]
    text = run_cli("fk", robot, "--random", "2", "--seed", "11", "--frame", "l_foot_link")
    lines = [line for line in text.output.splitlines() if line.startswith("configuration ")]
    assert len(lines) == 2 and "--seed 11" in lines[0]
    words = shlex.split(lines[1].split(": ", 1)[1])
    again = run_cli("fk", robot, *words, "--frame", "l_foot_link", "-f", "json")
    assert json.loads(again.output)["frames"] == documents[1]["frames"]
    table = run_cli("fk", robot, "--random", "2", "--seed", "11", "--frame", "l_foot_link",
                    "-f", "csv").output.splitlines()
    assert table[0].split(",")[13:] == list(documents[0]["q"])
    assert [float(v) for v in table[2].split(",")[13:]] == list(documents[1]["q"].values())


# -- the model read down the parsed tree, against Pinocchio's -------------------------------------



def _random_tree(seed: int, links: int = 14) -> bytes:
    """A random tree: every joint kind, mimic joints (of mimic joints too), unaligned and
    negative axes, turned origins, joint names whose byte order is not the document order."""
    rng = np.random.default_rng(seed)
    parts, kinds = [f'<robot name="r{seed}">', '<link name="l0"/>'], {}
    for i in range(1, links):
        kind = JOINT_TYPES[rng.integers(len(JOINT_TYPES))] if i > 1 else "revolute"
        parent = int(rng.integers(i))
        name = f"{'zyxw'[rng.integers(4)]}{rng.integers(100)}_{i}"
        xyz = " ".join(f"{v:.3f}" for v in rng.uniform(-1, 1, 3))
        rpy = " ".join(f"{v:.3f}" for v in rng.uniform(-3, 3, 3)) if rng.random() < 0.7 else "0 0 0"
        axis = ["1 0 0", "0 0 -1", "0 1 0", "0 0.6 0.8", "1 1 1", "-1 0 6.12323e-17",
                "0 1 6.12323e-17"][rng.integers(7)]
        extra = f'<axis xyz="{axis}"/>'
        if kind in ("revolute", "prismatic"):
            extra += '<limit lower="-1.5" upper="1.5" effort="1" velocity="1"/>'
        movers = [n for n, k in kinds.items() if k in MOVING]
        if kind in ("revolute", "prismatic") and movers and rng.random() < 0.4:
            extra += (f'<mimic joint="{movers[rng.integers(len(movers))]}" '
                      f'multiplier="{rng.uniform(-2, 2):.3f}" offset="{rng.uniform(-1, 1):.3f}"/>')
        kinds[name] = kind
        parts.append(f'<link name="l{i}"/>')
        parts.append(f'<joint name="{name}" type="{kind}"><parent link="l{parent}"/>'
                     f'<child link="l{i}"/><origin xyz="{xyz}" rpy="{rpy}"/>{extra}</joint>')
    return "\n".join(parts + ["</robot>"]).encode()


@pytest.mark.parametrize("seed", range(12))
def test_model_read_down_the_tree_is_pinocchios(tmp_path, seed):
    """The joints, link frames, their order and Pinocchio's coordinates, and every pose, as
    Pinocchio's model has them, on random trees with every joint kind and mimic joints."""
    import pinocchio

    path = tmp_path / "random.urdf"
    path.write_bytes(_random_tree(seed))
    for floating in (False, True):
        model = KinematicModel(load(path), floating=floating)
        native = model.model
        body = [f for f in native.frames if f.type == pinocchio.FrameType.BODY]
        assert model.links == [f.name for f in body]
        assert [j.name for j in model._joints] == list(native.names)
        assert [j.parent for j in model._joints[1:]] == list(native.parents)[1:]
        assert [j.idx_q for j in model._joints[1:]] == [j.idx_q for j in native.joints][1:]
        assert model.pinocchio_q(np.zeros((1, len(model.variables)))).shape == (1, native.nq)
        values = config.random(model.variables, 8, seed=seed).values
        np.testing.assert_allclose(model.link_poses(values), _pinocchio_poses(model, values),
                                   atol=1e-12)


@pytest.mark.parametrize("seed", range(4))
def test_poses_of_some_links_are_those_of_all(tmp_path, seed):
    """Poses asked for some links (in any order, one twice, a link at its joint left out while
    one below it is asked) are, to the bit, those of the same links among all: a moving
    joint's pose is written into its link's block only when that link is asked for."""
    path = tmp_path / "random.urdf"
    path.write_bytes(_random_tree(seed))
    for floating in (False, True):
        model = KinematicModel(load(path), floating=floating)
        values = config.random(model.variables, 5, seed=seed).values
        every = model.link_poses(values)
        rng = np.random.default_rng(seed)
        chosen = [int(i) for i in rng.permutation(len(model.links))[: len(model.links) // 2]]
        chosen += chosen[:1]
        assert np.array_equal(model.link_poses(values, chosen), every[:, chosen])

def test_fk_builds_no_pinocchio_model(tiny, monkeypatch):
    """Poses come from the tree read once, not from Pinocchio's model (quadratic in links),
    past the size where urdfdom's verdict is asked of it."""
    from urdftool.kinematics import fk, native

    def refused(*args):
        raise AssertionError("Pinocchio's model was built")

    monkeypatch.setattr(native, "build_model", refused)
    monkeypatch.setattr(fk, "URDFDOM_VERDICT_UP_TO", len(tiny.links) - 1)
    model = KinematicModel(tiny.robot)
    values = config.random(model.variables, 3, seed=0).values
    result = forward_kinematics(model, config.Configurations(model.variables, values, []))
    np.testing.assert_allclose(result.matrices, tiny.link_poses(values), atol=1e-12)


def test_every_random_stream_comes_from_one_maker_that_refuses_a_negative_seed():
    """``--seed -1`` (fk, ik, dynamics, workspace, collisions, diff) ended in numpy's
    traceback ("expected non-negative integer"): every stream is made by
    configuration.random_stream, whose refusal is a usage error."""
    import ast
    from pathlib import Path

    import urdftool
    from urdftool.errors import UsageError
    from urdftool.kinematics.configuration import random_stream

    for seed in (-1, [-1, 0]):
        with pytest.raises(UsageError, match="--seed must be an integer, 0 or more, not -1"):
            random_stream(seed)
    assert random_stream(2 ** 70).integers(10) == random_stream(2 ** 70).integers(10)
    makers = []
    for path in Path(urdftool.__file__).parent.rglob("*.py"):
        for node in walked(path.read_text()):
            if isinstance(node, ast.Attribute) and node.attr in ("default_rng", "RandomState",
                                                                 "SeedSequence"):
                makers.append(f"{path.name}:{node.lineno}")
    assert [m for m in makers if not m.startswith("configuration.py:")] == [] and makers


def test_a_draw_past_what_numpy_allocates_is_out_of_memory_not_its_traceback():
    """fk --random, workspace/dynamics --samples, ik --seeds of 10^18 (an int64): numpy's
    uniform raised ValueError "array is too big", a traceback, where 10^10 ran out of the
    memory budget (U018). The one draw between limits says MemoryError for both."""
    with pytest.raises(MemoryError):
        config.within(config.random_stream(0), [-1.0, -1.0], [1.0, 1.0], (10 ** 18, 2))
    assert config.within(config.random_stream(0), [-1.0], [1.0], (3, 1)).shape == (3, 1)


def test_a_negative_seed_is_a_usage_error(run_cli, tmp_path):
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/><link name="b"/><joint name="j" '
                     'type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>'
                     '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>')
    result = run_cli("fk", robot, "--random", "2", "--seed", "-1")
    assert result.exit_code == 2 and "--seed must be an integer, 0 or more" in result.output


@pytest.mark.parametrize("text, said", [
    ('[{"j1": 0, "j2": 1}, {"j1": ' + "9" * 5000 + ', "j2": 1}]', "q.json: row 2: value '9999"),
    ('[{"j1": 0, "j2": 1}, {"j1": 1, "j2": -' + "9" * 400 + "}]", "q.json: row 2: value '-999"),
    ('[{"j1": 1e400, "j2": 1}]', "q.json: row 1: value '1e400' for joint 'j1' is not finite"),
    ('[{"j1": [1, 2.50], "j2": 1}]', "q.json: row 1: value '[1, 2.50]' for joint 'j1' is not a number"),
    ("[" * 100_000, "invalid JSON"),
])
def test_a_json_table_too_long_or_deep_for_python_is_a_config_error(tmp_path, text, said):
    """json.loads raises ValueError past int()'s 4,300 digits and RecursionError past its
    nesting, neither a JSONDecodeError (fk --q-file, ik --targets/--check-reach: tracebacks);
    an integer past a double was float()'s OverflowError (a traceback). A number is kept as
    written and is not finite at its row, as the same number in a CSV file."""
    from urdftool.errors import ConfigError

    path = tmp_path / "q.json"
    path.write_text(text)
    with pytest.raises(ConfigError) as raised:
        config.read_table(str(path), "configurations", "joint")
    assert said in f"{raised.value.where}: {raised.value}"
    assert "not finite" in str(raised.value) or said == "invalid JSON" or "[1, 2.50]" in said


@pytest.mark.parametrize("origin", ['xyz="0 0 0" rpy="inf 0 0"', 'xyz="nan 0 0"',
                                    'xyz="0 1e999 0"', 'rpy="0 -inf nan"'])
def test_an_origin_that_is_not_finite_is_a_located_error(tmp_path, origin):
    """rpy="inf": math.sin raised ValueError, a traceback from fk, ik and every command
    that poses the robot; "nan": every pose below it nan, exit 0 (attacks.md, session 7)."""
    from conftest import load_text

    robot = load_text(tmp_path, f"""<robot name="r"><link name="a"/><link name="b"/>
      <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
      <origin {origin}/><axis xyz="0 0 1"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>""")
    with pytest.raises(FKError, match="not finite"):
        KinematicModel(robot)


def test_an_axis_without_xyz_is_urdfdoms_zero_axis(tmp_path):
    """``<axis/>`` is urdfdom's 0 0 0 (parseJoint reads xyz only when written, after clearing
    the axis): Pinocchio's joint turns about nothing, and physics.frames read no direction;
    fk turned it about x (description.values.axis_xyz, the one reading now)."""
    from conftest import load_text

    robot = load_text(tmp_path, """<robot name="r"><link name="a"/><link name="b"/>
      <joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>""")
    with pytest.raises(FKError, match=r"<axis> without xyz \(urdfdom's 0 0 0\) has no direction"):
        KinematicModel(robot)


def test_a_chain_of_3000_mimic_joints_has_its_values(tmp_path):
    """Each joint mimicking the one before, twice its value plus 0.001: mimic_source recursed
    once per joint (RecursionError from fk, ik, dynamics, collisions, workspace) and walked
    the chain again for each (attacks.md, session 7)."""
    from conftest import load_text

    links = "".join(f'<link name="l{i}"/>' for i in range(3001))
    joints = "".join(
        f'<joint name="j{i}" type="revolute"><parent link="l0"/><child link="l{i + 1}"/>'
        f'<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
        + (f'<mimic joint="j{i - 1}" multiplier="{2 if i < 3 else 1}" offset="0.001"/>'
           if i else "") + "</joint>" for i in range(3000))
    model = KinematicModel(load_text(tmp_path, f'<robot name="r">{links}{joints}</robot>'))
    assert [v.name for v in model.variables] == ["j0"]
    from urdftool.kinematics.configuration import mimic_source

    assert mimic_source(model.robot, "j2", {"j0"}) == ("j0", 4.0, 2 * 0.001 + 0.001)
    assert mimic_source(model.robot, "j2999", {"j0"})[1] == 4.0


@pytest.mark.parametrize("text", [
    "l_knee,l_hip_pitch\n0.1\n0.1,0.2,0.3\n",  # rows of 1 and 3 values: 4, as 2 rows of 2 hold
    "l_knee,l_hip_pitch\n0.1,0.2,0.3\n",
    '[{"l_knee": true}]', '[{"l_knee": false, "l_hip_pitch": 0.1}]',
])
def test_the_fast_readers_refuse_what_the_row_by_row_reader_refuses(humanoid, tmp_path,
                                                                      monkeypatch, text):
    """The vectorised readers of a file of numbers give the row-by-row reader's answer: a CSV
    row of another width than its header was read across rows (0.1 and 0.1, 0.2 and 0.3);
    a JSON ``true`` was 1 rad."""
    path = tmp_path / ("q.json" if text.startswith("[") else "q.csv")
    path.write_text(text)
    with pytest.raises(config.ConfigError) as fast:
        config.from_file(humanoid.variables, str(path))
    monkeypatch.setattr(config, "_vectorised", lambda rows, width, any_json: None)
    with pytest.raises(config.ConfigError) as careful:
        config.from_file(humanoid.variables, str(path))
    assert str(fast.value) == str(careful.value)
    assert "true" in str(fast.value) or "false" in str(fast.value) or "row has" in str(fast.value)


def test_a_value_or_name_of_a_file_of_numbers_is_quoted_cut(humanoid, tmp_path):
    """A 10 MB cell (or header name) was repeated whole in the one-line error."""
    path = tmp_path / "q.csv"
    path.write_text("l_knee\n" + "1" * 1_000_000 + "\n")
    with pytest.raises(config.ConfigError) as error:
        config.from_file(humanoid.variables, str(path))
    assert len(str(error.value)) < 300 and "(1000000 characters)" in str(error.value)
    path.write_text("j" * 1_000_000 + "\n0\n")
    with pytest.raises(config.ConfigError) as error:
        config.from_file(humanoid.variables, str(path))
    assert len(str(error.value)) < 600 and "(1000000 characters)" in str(error.value)


def test_a_name_given_twice_is_found_in_one_pass():
    """A header of 100,000 columns took fk's 60 s budget: each name searched among those
    before it."""
    from conftest import counting_str

    compared = []
    Name = counting_str(compared)

    names = [Name(f"x{i}") for i in range(2000)] + [Name("x7")]
    assert config.named_twice(names) == "x7" and len(compared) < 100
    assert config.named_twice(["a", "b"]) is None


@pytest.mark.parametrize("text, line", [
    ('j1\n"0.2\n"\n0.1,0.2\n', 4),           # a quoted cell across two lines: the row's own line
    ("j1\r0.1\r\r0.1,0.2\r", 4),             # lines ended by CR alone, a blank line kept
    ("j1\n0.1\u2028\n0.1,0.2\n", 3),         # a LINE SEPARATOR ends no line of the file
])
def test_a_row_of_a_file_of_numbers_is_said_at_its_line_of_the_file(tmp_path, text, line):
    """A row's error names the line it starts on, as every Location numbers lines: the quoted
    reader numbered records (a cell holding a line break put every later row a line up)."""
    from urdftool.errors import ConfigError
    from urdftool.kinematics.configuration import read_table

    path = tmp_path / "q.csv"
    path.write_bytes(text.encode())
    with pytest.raises(ConfigError) as caught:
        read_table(str(path), "q-file", "joint")
    assert str(caught.value).split(": ")[0].endswith(f"q.csv:{line}"), str(caught.value)


@pytest.mark.parametrize("output_format", ["json", "csv"])
def test_cli_machine_formats_write_no_signed_zero(run_cli, output_format):
    """A level frame's pitch is atan2's -0.0; the humanoid's JSON and CSV wrote it 22 times."""
    result = run_cli("fk", HUMANOID, "-f", output_format, "--matrix")
    assert result.exit_code == 0, result.output
    assert not re.search(r"(?<![\w.])-0\.0(?![\w.])", result.stdout)


FAR_JOINT = """<robot name="r">
  <link name="a"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0"
    iyz="0"/></inertial><visual><geometry><box size="1 1 1"/></geometry></visual></link>
  <link name="b"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0"
    iyz="0"/></inertial><visual><geometry><box size="1 1 1"/></geometry></visual></link>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    <origin xyz="{x} 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"""


def _model_builder(build: str):
    """(the builder of ``build``'s model, the error it refuses a robot with): urdftool's own
    (fk, ik, workspace, collisions, diff), Pinocchio's of dynamics, yourdfpy's of render."""
    from urdftool.errors import DynamicsError, FKError, SceneError
    from urdftool.kinematics.fk import KinematicModel
    from urdftool.kinematics.scene import posed
    from urdftool.physics import dynamics

    return {"fk": (KinematicModel, FKError), "dynamics": (dynamics.build, DynamicsError),
            "render": (posed, SceneError)}[build]


@pytest.mark.parametrize("build", ["fk", "dynamics", "render"])
def test_a_joint_placed_past_the_farthest_coordinate_is_refused_by_every_model(tmp_path, build):
    """A joint at 1e200: workspace said "max reach 0 m", ik "inf m", dynamics torques of NaN,
    collisions distances of inf (its matrix "--seed must be an integer"), render numpy's
    warnings. One check of joint origins (fk.placed_within, at numbers.MAX_COORDINATE) for
    every model: urdftool's own (fk, ik, workspace, collisions, diff), Pinocchio's of dynamics,
    yourdfpy's of render; just within, each builds."""
    from conftest import load_text

    make, error = _model_builder(build)
    far = load_text(tmp_path, FAR_JOINT.format(x="1e200"))
    with pytest.raises(error, match=r"joint 'j': <origin> xyz '1e\+200 0 0' is past the "
                                    r"4\.612e\+10 m urdftool places a link within") as refused:
        make(far)
    assert refused.value.element is far.joints["j"].find("origin")
    make(load_text(tmp_path, FAR_JOINT.format(x="4e10")))


@pytest.mark.parametrize("attribute", ["multiplier", "offset"])
@pytest.mark.parametrize("build", ["fk", "dynamics", "render"])
def test_a_mimic_moving_its_link_past_the_farthest_coordinate_is_refused_by_every_model(
        tmp_path, build, attribute):
    """A prismatic mimic of multiplier (or offset) 1e200 placed its link at 5e199 for any value
    of the joint it follows: workspace "max reach inf m", dynamics "total tau nan", collisions'
    distances of inf. The one check of joint placements refuses it at its <mimic>."""
    from conftest import load_text

    make, error = _model_builder(build)
    text = FAR_JOINT.format(x="1").replace("</robot>", f"""
  <link name="c"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0"
    iyz="0"/></inertial></link>
  <joint name="m" type="prismatic"><parent link="a"/><child link="c"/><axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
    <mimic joint="j" {attribute}="{{value}}"/></joint>
</robot>""")
    far = load_text(tmp_path, text.format(value="1e200"))
    with pytest.raises(error, match=rf"joint 'm': <mimic {attribute}> 1e\+200 is past the "
                                    r"4\.612e\+10 urdftool places a link") as refused:
        make(far)
    assert refused.value.element is far.joints["m"].find("mimic")
    make(load_text(tmp_path, text.format(value="4e10")))


def test_a_centre_of_mass_past_the_farthest_coordinate_is_refused_by_the_dynamics(tmp_path):
    """An ``<inertial><origin xyz="1e200 0 0">``: dynamics said "M(q) is singular" and torques
    of NaN. The one check of placements, asked for masses by the dynamics, refuses it at the
    origin; kinematics (which has no masses) and just within the bound build."""
    from conftest import load_text
    from urdftool.errors import DynamicsError
    from urdftool.kinematics.fk import KinematicModel
    from urdftool.physics import dynamics

    text = FAR_JOINT.format(x="1").replace('<link name="b"><inertial>',
                                           '<link name="b"><inertial><origin xyz="{com}"/>')
    far = load_text(tmp_path, text.replace("{com}", "1e200 0 0"))
    with pytest.raises(DynamicsError, match=r"link 'b': <inertial><origin> xyz '1e\+200 0 0' is "
                                            r"past the 4\.612e\+10 m urdftool places a centre"):
        dynamics.build(far)
    KinematicModel(far)
    dynamics.build(load_text(tmp_path, text.replace("{com}", "4e10 0 0")))
