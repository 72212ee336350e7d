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
    assert "- joint `elbow`: origin.xyz" in text and "| `hand` | 3 | 0 | 3 | 0 | zero |" in text


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


@pytest.mark.parametrize("args, message", [
    (["{old}"], "diff takes OLD NEW, or --rev REV FILE"),
    (["{old}", "{new}", "--format", "html"], "--format must be one of"),
    (["{old}", "{new}", "--chain", "base"], "--chain must be BASE:TIP"),
    (["{old}", "{new}", "--chain", "base:hnd"], "did you mean 'hand'?"),
    (["{old}", "{new}", "--render", "{old}.jpg"], "must end in .png or .svg"),
])
def test_usage_errors_exit_2(run_cli, pair, args, message):
    old, new = pair
    result = run_cli("diff", *(a.format(old=old, new=new) for a in args))
    assert result.exit_code == 2, result.output
    assert message in result.output


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
    nameless.write_text(ARM.replace('<link name="hand"/>', '<link name="hand"/><link/>'))
    result = run_cli("diff", nameless, pair[1], "--render", tmp_path / "d.png")
    assert result.exit_code == 1
    assert "nameless.urdf: error: yourdfpy cannot build the scene" in result.output
    assert "change(s)" in result.output  # the report came first
