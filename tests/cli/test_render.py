"""``urdftool render`` and ``collisions --render``: pictures from the command line."""

from __future__ import annotations

import numpy as np
import pytest

from conftest import ROBOTS

HUMANOID = ROBOTS / "humanoid" / "humanoid.urdf.xacro"


def _image(path):
    from PIL import Image

    return np.asarray(Image.open(path).convert("RGB"), dtype=float)


def test_render_writes_a_png_of_the_posed_robot(tmp_path, run_cli):
    straight, bent = tmp_path / "straight.png", tmp_path / "bent.png"
    result = run_cli("render", HUMANOID, "-o", straight, "--size", "200x160", "--view", "side")
    assert result.exit_code == 0, result.output
    assert "wrote" in result.output
    result = run_cli("render", HUMANOID, "-o", bent, "--size", "200x160", "--view", "side",
                     "--q", "l_hip_pitch=-60", "--q", "r_hip_pitch=-60", "--deg", "--frames")
    assert result.exit_code == 0, result.output
    one, two = _image(straight), _image(bent)
    assert one.shape == (160, 200, 3)
    assert np.abs(one - two).mean() > 1.0


def test_render_svg_names_each_link(tmp_path, run_cli):
    out = tmp_path / "robot.svg"
    assert run_cli("render", HUMANOID, "-o", out, "--collision").exit_code == 0
    text = out.read_text()
    assert "<title>l_thigh_link</title>" in text and "<title>head_link</title>" in text


@pytest.mark.parametrize("args, message", [
    (["-o", "{tmp}/x.jpg"], "must end in .png or .svg"),
    (["-o", "{tmp}/x.png", "--view", "back"], "--view must be one of"),
    (["-o", "{tmp}/x.png", "--size", "600"], "--size must be WIDTHxHEIGHT"),
    (["-o", "{tmp}/x.png", "--size", "1\u00b2x100"], "--size must be WIDTHxHEIGHT"),  # int():
    (["-o", "{tmp}/x.png", "--size", "100x" + "9" * 5000], "(5004 characters)"),  # ValueError
    (["-o", "{tmp}/x.png", "--q", "elbw=1"], "--q: unknown joint 'elbw'"),
    (["-o", "{tmp}/missing/x.png"], "does not exist"),
])
def test_render_usage_errors_exit_2(tmp_path, run_cli, args, message):
    result = run_cli("render", HUMANOID, *(a.format(tmp=tmp_path) for a in args))
    assert result.exit_code == 2 and message in result.output


@pytest.mark.worker  # the memory budget applies in the forked worker
def test_a_size_past_what_the_memory_budget_leaves_is_refused_before_drawing(tmp_path,
                                                                             run_cli):
    """``--size`` follows the budget: 8192x8192 (in the option's range) under 1 GiB was a
    drawing out of memory (U018, exit 1); it is a usage error saying the largest that fits."""
    result = run_cli("render", HUMANOID, "-o", tmp_path / "x.png", "--size", "8192x8192",
                     "--max-memory", "1G")
    assert result.exit_code == 2, result.output
    assert "needs about 2.75 GiB" in result.output and "at most" in result.output
    assert "U018" not in result.output and not (tmp_path / "x.png").exists()


def test_render_a_robot_yourdfpy_cannot_read_exits_1_located(tmp_path, run_cli):
    path = tmp_path / "bad.urdf"
    path.write_text('<robot name="r"><link name="a"><visual><geometry/></visual></link></robot>')
    result = run_cli("render", path, "-o", tmp_path / "x.png")
    assert result.exit_code == 1 and "bad.urdf" in result.output and "yourdfpy" in result.output


def test_render_refuses_a_mimic_cycle_at_its_joint(tmp_path, run_cli):
    """As fk does (it drew the cycle at 0, exit 0)."""
    box = '<visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>'
    path = tmp_path / "cycle.urdf"
    path.write_text(
        f'<robot name="r"><link name="base"/><link name="a">{box}</link>\n'
        f'<joint name="ja" type="continuous"><parent link="base"/><child link="a"/>'
        f'<mimic joint="jb"/></joint>\n<link name="b">{box}</link>\n'
        f'<joint name="jb" type="continuous"><parent link="base"/><child link="b"/>'
        f'<mimic joint="ja"/></joint></robot>')
    result = run_cli("render", path, "-o", tmp_path / "x.png")
    assert result.exit_code == 1, result.output
    assert f"{path}:2: error: joint 'ja' has no value (a mimic cycle?)" in result.output
    assert not (tmp_path / "x.png").exists()


def test_collisions_render_paints_colliding_links_red(tmp_path, run_cli):
    crossed, apart = tmp_path / "crossed.png", tmp_path / "apart.png"
    result = run_cli("collisions", HUMANOID, "--q", "l_hip_roll=-0.5", "--q", "r_hip_roll=0.5",
                     "--render", crossed)
    assert result.exit_code == 1, result.output  # the thighs collide
    assert run_cli("collisions", HUMANOID, "--render", apart).exit_code == 0

    def red(path):
        image = _image(path)
        return ((image[..., 0] > 150) & (image[..., 1] < 80) & (image[..., 2] < 80)).sum()

    assert red(crossed) > 200 and red(apart) == 0
    assert run_cli("collisions", HUMANOID, "--matrix", "--render", apart).exit_code == 2


def test_an_empty_picture_says_why(tmp_path, run_cli):
    """A robot of collision shapes only drew '0 triangles' and said no more (so did champ's of
    the sweep, every mesh outside its repository: the warnings said it, not the last line)."""
    path = tmp_path / "boxes.urdf"
    path.write_text('<robot name="boxes"><link name="a"><collision><geometry>'
                    '<box size="0.1 0.1 0.1"/></geometry></collision></link></robot>')
    result = run_cli("render", path, "-o", tmp_path / "x.png")
    assert result.exit_code == 0
    assert ("(0 triangles): the robot has no <visual> geometry, only <collision>; "
            "--collision draws it") in result.stderr
    drawn = run_cli("render", path, "-o", tmp_path / "x.png", "--collision")
    assert "(12 triangles)\n" in drawn.stderr


def test_a_picture_of_nothing_because_every_shape_was_left_out_exits_1(tmp_path, run_cli):
    """NAO, Pepper and iCub without their mesh packages drew 0 triangles and exited 0; a
    picture missing some shapes is still drawn, exit 0, the warnings saying which."""
    missing = '<visual><geometry><mesh filename="package://nowhere/m.stl"/></geometry></visual>'
    box = '<visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>'
    path = tmp_path / "r.urdf"
    path.write_text(f'<robot name="r"><link name="a">{missing}</link></robot>')
    result = run_cli("render", path, "-o", tmp_path / "x.png")
    assert result.exit_code == 1
    assert "(0 triangles): every <visual> shape was left out" in result.stderr
    path.write_text(f'<robot name="r"><link name="a">{missing}{box}</link></robot>')
    result = run_cli("render", path, "-o", tmp_path / "x.png")
    assert result.exit_code == 0 and "(12 triangles)" in result.stderr
