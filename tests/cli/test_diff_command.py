"""``urdftool diff`` on the command line: exit codes, formats, --rev, --render."""

from __future__ import annotations

import json
import shutil
import subprocess

import pytest

from compare.test_diff import ARM  # tests/ is on the path: one robot for both files


@pytest.fixture
def pair(tmp_path):
    (tmp_path / ".git").mkdir()
    old, new = tmp_path / "old.urdf", tmp_path / "new.urdf"
    old.write_text(ARM)
    new.write_text(ARM.replace('<origin xyz="0 0 0.4"/>', '<origin xyz="0 0 0.403"/>')
                   .replace('<mass value="1.0"/>', '<mass value="1.1"/>'))
    return old, new


def test_equivalent_files_exit_0(run_cli, pair, tmp_path):
    old, _ = pair
    same = tmp_path / "same.urdf"
    same.write_text(ARM.replace("<!-- a three-link arm -->", ""))
    result = run_cli("diff", old, same)
    assert result.exit_code == 0, result.output
    assert "equivalent" in result.output


def test_different_files_exit_1_with_changes_and_effects(run_cli, pair):
    result = run_cli("diff", *pair, "--chain", "base:hand")
    assert result.exit_code == 1, result.output
    assert "joint 'elbow': origin.xyz (0, 0, 0.4) -> (0, 0, 0.403) m (moved 3 mm)" in result.output
    assert "link 'upper': inertial.mass 1 -> 1.1 kg (+0.1 kg, +10 %)" in result.output
    assert "hand: at zero 3 mm 0 deg" in result.output
    assert "total mass 3.5 -> 3.6 kg" in result.output
    assert "reach base -> hand:" in result.output


def test_json_and_markdown(run_cli, pair, tmp_path):
    result = run_cli("diff", *pair, "--format", "json")
    data = json.loads(result.output)
    assert data["equivalent"] is False
    assert {c["field"] for c in data["changes"]} == {"origin.xyz", "inertial.mass"}
    frames = {f["link"]: f for f in data["effects"]["frames"]}
    assert frames["hand"]["max_position_m"] == pytest.approx(0.003)
    summary = tmp_path / "summary.md"
    assert run_cli("diff", *pair, "--format", "markdown", "-o", summary).exit_code == 1
    text = summary.read_text()
    assert text.startswith("### Robot description:")
    assert "- joint `elbow`: `origin.xyz`" in text and "| `hand` | 3 | 0 | 3 | 0 | `shoulder`=0, `elbow`=0 |" in text  # names as code spans


def test_render_overlays_old_and_new(run_cli, pair, tmp_path):
    import numpy as np
    from PIL import Image

    picture = tmp_path / "diff.png"
    assert run_cli("diff", *pair, "--render", picture).exit_code == 1
    pixels = np.asarray(Image.open(picture).convert("RGB"), dtype=float)
    blue = (pixels[..., 2] > pixels[..., 0] + 80).sum()
    orange = (pixels[..., 0] > pixels[..., 2] + 80).sum()
    grey = (np.ptp(pixels, axis=-1) < 4) & (pixels[..., 0] < 240)
    assert blue > 5 and orange > 5 and grey.sum() > 1000


@pytest.mark.parametrize("renamed", ["elbow2", "arm.elbow"])  # (a '.' as a coordinate's has)
def test_render_poses_the_old_side_under_its_old_joint_names(run_cli, pair, tmp_path,
                                                             monkeypatch, renamed):
    """The old robot is drawn at the configuration where they differ most, its renamed joint
    under its old name: 'arm.elbow' was taken as coordinate 'elbow' of a joint 'arm', so the
    old arm was drawn with its elbow at 0 while the new one was bent."""
    from urdftool.kinematics.scene import SceneModel

    old, _ = pair
    new = tmp_path / "renamed.urdf"
    bent = '<axis xyz="0 1 0"/>\n    <limit lower="-2.0"'  # the elbow's axis, turned
    new.write_text(old.read_text().replace('"elbow"', f'"{renamed}"')
                   .replace(bent, bent.replace("0 1 0", "1 0 0")))
    poses, pose = [], SceneModel.pose
    monkeypatch.setattr(SceneModel, "pose", lambda self, q=None, *rest: poses.append(dict(q))
                        or pose(self, q, *rest))
    result = run_cli("diff", old, new, "--render", tmp_path / "diff.png", "--no-collisions",
                     "--samples", "20")
    assert result.exit_code == 1, result.output
    drawn_old, drawn_new = poses
    assert drawn_new[renamed] != 0 and drawn_old == {"shoulder": drawn_new["shoulder"],
                                                     "elbow": drawn_new[renamed]}


@pytest.mark.parametrize("args, message", [
    (["{old}"], "diff takes OLD NEW, or --rev REV FILE"),
    (["{old}", "{new}", "--format", "html"], "--format must be one of"),
    (["{old}", "{new}", "--chain", "base"], "--chain must be BASE:TIP"),
    (["{old}", "{new}", "--chain", "base:hnd"], "did you mean 'hand'?"),
    (["{old}", "{old}", "--chain", "base:hnd"], "did you mean 'hand'?"),  # no effect computed
    (["{old}", "{old}", "--chain", "nope:hand", "-f", "json"], "link 'nope' does not exist"),
    (["{old}", "{new}", "--render", "{old}.jpg"], "must end in .png or .svg"),
])
def test_usage_errors_exit_2(run_cli, pair, args, message):
    old, new = pair
    result = run_cli("diff", *(a.format(old=old, new=new) for a in args))
    assert result.exit_code == 2, result.output
    assert message in result.output


def test_chain_splits_at_the_colon_between_two_links(run_cli, pair, tmp_path):
    # link names with ':' (a namespace written into them): 'arm:base:arm:hand' is the chain
    # arm:base -> arm:hand, the only ':' with a link on each side
    old, new = (tmp_path / "ns_old.urdf", tmp_path / "ns_new.urdf")
    for named, path in zip(pair, (old, new)):
        path.write_text(named.read_text().replace('"base"', '"arm:base"')
                        .replace('"hand"', '"arm:hand"'))
    result = run_cli("diff", old, new, "--chain", "arm:base:arm:hand")
    assert result.exit_code == 1, result.output
    assert "reach arm:base -> arm:hand:" in result.output
    result = run_cli("diff", old, new, "--chain", "arm:base:arm:hnd")
    assert result.exit_code == 2 and "link 'arm:hnd' does not exist" in result.output
    assert "did you mean 'arm:hand'?" in result.output


@pytest.mark.parametrize("output_format", ("text", "json", "markdown"))
def test_a_companion_a_side_cannot_read_is_said_not_compared_and_exits_2(run_cli, pair, tmp_path,
                                                                         output_format):
    # diff's exit statuses are diff(1)'s: 0 the same, 1 different, 2 trouble; a controller
    # YAML beside the new side that is a folder was "removed" (exit 1), one of invalid UTF-8
    # on both sides "equivalent" (exit 0)
    old, new = (tmp_path / side / "arm.urdf" for side in ("old", "new"))
    for robot, changed in ((old, pair[0]), (new, pair[0])):
        (robot.parent / "config").mkdir(parents=True)
        robot.write_text(changed.read_text())
    (old.parent / "config" / "controllers.yaml").write_bytes(b"arm:\n  type: a/B\n")
    (new.parent / "config" / "controllers.yaml").mkdir()
    (old.parent / "config" / "ros_controllers.yaml").write_bytes(b"arm: \xff\n")
    (new.parent / "config" / "ros_controllers.yaml").write_bytes(b"arm: \xfe\n")
    result = run_cli("diff", old, new, "-f", output_format)
    assert result.exit_code == 2, result.output
    if output_format == "json":
        data = json.loads(result.output)
        assert data["equivalent"] is False and data["changes"] == []
        assert [(i["name"], bool(i["old"]), bool(i["new"])) for i in data["not_compared"]] == [
            ("config/controllers.yaml", False, True), ("config/ros_controllers.yaml", True, True)]
    else:
        assert "equivalent" not in result.output and "removed" not in result.output
        quote = "`" if output_format == "markdown" else "'"
        for place in ("config/controllers.yaml", "config/ros_controllers.yaml"):
            assert f"not compared: controllers {quote}{place}{quote}" in result.output


def test_a_side_that_does_not_load_exits_1_located(run_cli, pair, tmp_path):
    broken = tmp_path / "broken.urdf"
    broken.write_text("<robot name='x'><link name='a'>\n")
    result = run_cli("diff", pair[0], broken)
    assert result.exit_code == 1 and "broken.urdf:" in result.output


def test_rev_compares_with_the_committed_file(run_cli, tmp_path):
    if shutil.which("git") is None:
        pytest.skip("git is not installed")
    robot = tmp_path / "arm.urdf"
    robot.write_text(ARM)
    for args in (["init", "-q"], ["add", "."], ["commit", "-qm", "one"]):
        subprocess.run(["git", "-C", str(tmp_path), "-c", "user.email=t@t", "-c",
                        "user.name=t", *args], check=True, capture_output=True)
    assert run_cli("diff", "--rev", "HEAD", robot).exit_code == 0
    robot.write_text(ARM.replace('"fore"', '"forearm"'))
    result = run_cli("diff", "--rev", "HEAD", robot)
    assert result.exit_code == 1
    assert "HEAD:arm.urdf ->" in result.output
    assert "renamed link 'fore' -> 'forearm'" in result.output
    assert run_cli("diff", "--rev", "nope", robot).exit_code == 2


def test_a_side_yourdfpy_cannot_draw_is_located_in_its_own_file(run_cli, pair, tmp_path):
    nameless = tmp_path / "nameless.urdf"
    nameless.write_text(ARM.replace('<visual><geometry><box size="0.2 0.2 0.1"/>',
                                    '<visual><geometry><box/>'))
    result = run_cli("diff", nameless, pair[1], "--render", tmp_path / "d.png")
    assert result.exit_code == 1
    assert "nameless.urdf: error: yourdfpy cannot build the scene" in result.output
    assert "change(s)" in result.output  # the report came first


# two arms on one base: a change in the left one moves only the left one's frames
TWO_ARMS = """<robot name="two">
  <link name="base"><visual><geometry><box size="0.4 0.1 0.1"/></geometry></visual></link>
  <link name="left_upper"><visual><origin xyz="0 0 0.15"/><geometry>
    <box size="0.04 0.04 0.3"/></geometry></visual></link>
  <link name="left_fore"><visual><origin xyz="0 0 0.12"/><geometry>
    <box size="0.03 0.03 0.24"/></geometry></visual></link>
  <link name="right_upper"><visual><origin xyz="0 0 0.15"/><geometry>
    <box size="0.04 0.04 0.3"/></geometry></visual></link>
  <joint name="left_shoulder" type="revolute"><parent link="base"/><child link="left_upper"/>
    <origin xyz="-0.15 0 0.05"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="left_elbow" type="revolute"><parent link="left_upper"/><child link="left_fore"/>
    <origin xyz="0 0 0.3"/><axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="right_shoulder" type="revolute"><parent link="base"/><child link="right_upper"/>
    <origin xyz="0.15 0 0.05"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"""


@pytest.fixture
def arms(tmp_path):
    (tmp_path / ".git").mkdir()
    old, new = tmp_path / "old.urdf", tmp_path / "new.urdf"
    old.write_text(TWO_ARMS)
    # the left elbow turned a little: the left forearm's frame turns, more with the shoulder
    new.write_text(TWO_ARMS.replace('<origin xyz="0 0 0.3"/><axis xyz="1 0 0"/>',
                                    '<origin xyz="0 0 0.3" rpy="0.01 0 0"/><axis xyz="1 0 0"/>'))
    return old, new


def test_the_worst_pose_names_the_joints_that_move_the_changed_frames(run_cli, arms):
    result = run_cli("diff", *arms, "--no-collisions")
    assert result.exit_code == 1, result.output
    [line] = [line for line in result.output.splitlines() if "left_fore:" in line]
    assert "(at left_shoulder=" in line and ", left_elbow=" in line
    assert "right_shoulder" not in line  # its value changes nothing for the left forearm
    [worst] = [line for line in result.output.splitlines() if "largest change at" in line]
    assert "left_shoulder=" in worst and "right_shoulder" not in worst
    data = json.loads(run_cli("diff", *arms, "--no-collisions", "-f", "json").output)
    [frame] = [f for f in data["effects"]["frames"] if f["link"] == "left_fore"]
    assert frame["joints"] == ["left_shoulder", "left_elbow"]
    assert data["effects"]["worst_joints"] == ["left_shoulder", "left_elbow"]


def test_render_magnifies_a_small_change_in_an_inset(run_cli, tmp_path):
    """A 3 mm change is a line of a pixel or two on the picture: an inset magnifies where it
    is, and says what moved; the SVG says it in text."""
    import numpy as np
    from PIL import Image

    from urdftool.description.load import load
    from urdftool.kinematics.scene import scene_model
    from urdftool.report import picture

    (tmp_path / ".git").mkdir()
    old, new = tmp_path / "old.urdf", tmp_path / "new.urdf"
    old.write_text(TWO_ARMS)
    new.write_text(TWO_ARMS.replace('<origin xyz="0 0 0.3"/><axis xyz="1 0 0"/>',
                                    '<origin xyz="0 0 0.303"/><axis xyz="1 0 0"/>'))

    def moved_pixels(path):  # below the legend: the pixels of one side only
        pixels = np.asarray(Image.open(path).convert("RGB"), dtype=float)[40:]
        blue = (pixels[..., 2] > pixels[..., 0] + 80).sum()
        orange = (pixels[..., 0] > pixels[..., 2] + 80).sum()
        return blue + orange

    shown = tmp_path / "diff.png"
    assert run_cli("diff", old, new, "--no-collisions", "--render", shown).exit_code == 1
    plain = tmp_path / "plain.png"
    layers = [picture.Layer(scene_model(load(path)).pose({}), tint=tint, label=label)
              for path, tint, label in ((old, picture.OLD, "old"), (new, picture.NEW, "new"))]
    picture.write(plain, layers)  # no detail: the change at the picture's scale
    assert 0 < 5 * moved_pixels(plain) < moved_pixels(shown)
    vector = tmp_path / "diff.svg"
    assert run_cli("diff", old, new, "--no-collisions", "--render", vector).exit_code == 1
    text = vector.read_text()
    assert "magnified" in text and "left_fore moved 3 mm" in text


def test_no_inset_for_a_change_large_enough_to_see(tmp_path):
    from urdftool.description.load import load
    from urdftool.kinematics.scene import scene_model
    from urdftool.report import picture

    (tmp_path / ".git").mkdir()
    robot = tmp_path / "arm.urdf"
    robot.write_text(ARM)
    scene = scene_model(load(robot))
    layers = [picture.Layer(scene.pose({}), tint=picture.OLD, label="old"),
              picture.Layer(scene.pose({"shoulder": 0.8}), tint=picture.NEW, label="new")]
    text = picture.svg(layers, picture.PictureOptions(detail=picture.Detail(0.3, "big")))
    assert "magnified" not in text


def test_a_warning_is_said_once_on_stderr_not_in_the_report(run_cli, pair):
    old, new = pair
    hand = ('<link name="hand"><collision><geometry><mesh filename="gone.stl"/></geometry>'
            '</collision></link>')
    for path in pair:
        path.write_text(path.read_text().replace('<link name="hand"/>', hand))
    result = run_cli("diff", old, new)
    assert result.exit_code == 1, result.output
    assert "gone.stl" not in result.stdout
    # (the same on both sides: said once, where the new file has it)
    assert [line.split(": ")[2:4] for line in result.stderr.splitlines()
            if "gone.stl" in line] == [["old and new", f"{new}:25"]]


def test_a_side_with_a_joint_without_a_name_is_compared_without_its_effects(run_cli, tmp_path):
    """A joint without a name (urdfdom refuses it: U103): diff died sorting the joints by name
    ('NoneType' object has no attribute 'encode'); the structure is compared and the effects
    are said not computed, as for a robot of two roots."""
    robot = ('<robot name="r"><link name="a"/><link name="b"/><joint {name}type="fixed">'
             '<parent link="a"/><child link="b"/></joint></robot>')
    old, new = tmp_path / "old.urdf", tmp_path / "new.urdf"
    old.write_text(robot.format(name=""))
    new.write_text(robot.format(name='name="j" '))
    result = run_cli("diff", old, new)
    assert result.exit_code == 1, result.output
    assert "effects not computed: a <joint> has no name attribute" in result.stderr
    assert "added joint 'j'" in result.stdout
