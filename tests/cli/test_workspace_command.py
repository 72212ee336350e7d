"""``urdftool workspace`` (urdftool.cli.workspace): what it says besides the envelope."""

from __future__ import annotations

ROBOT = ('<robot name="r"><link name="base"/><link name="a"/><link name="b"/>'
         '<joint name="ja" type="revolute"><parent link="base"/><child link="a"/>'
         '<axis xyz="0 0 1"/><limit lower="{lower}" upper="1" effort="1" velocity="1"/></joint>'
         '<joint name="jb" type="revolute"><parent link="a"/><child link="b"/>'
         '<origin xyz="0.3 0 0"/><axis xyz="0 0 1"/>'
         '<limit lower="0.5" upper="0.5" effort="1" velocity="1"/></joint></robot>')


def test_joints_of_no_range_are_said(tmp_path, run_cli):
    path = tmp_path / "r.urdf"
    path.write_text(ROBOT.format(lower=-1))
    result = run_cli("workspace", str(path), "--tip", "b", "--samples", "20")
    assert result.exit_code == 0, result.output
    assert "warning: 'jb' has no range (lower = upper): held there in every sample" \
        in result.stderr
    assert "(2 joints: ja, jb)" in result.stdout
    path.write_text(ROBOT.format(lower=1))
    result = run_cli("workspace", str(path), "--tip", "b", "--samples", "20")
    assert "warning: 'ja', 'jb' have no range (lower = upper): the limb cannot move: its " \
        "workspace is one point" in result.stderr
    result = run_cli("workspace", str(path), "--tip", "a", "--samples", "20")
    assert "(1 joint: ja)" in result.stdout, result.output
