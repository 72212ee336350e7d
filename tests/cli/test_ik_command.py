"""``urdftool ik`` (urdftool.cli.ik): an option asked for and not honoured is said."""

from __future__ import annotations

# a prismatic joint then a revolute one: no closed form applies
ROBOT = ('<robot name="r"><link name="base"/><link name="a"/><link name="b"/>'
         '<joint name="ja" type="prismatic"><parent link="base"/><child link="a"/>'
         '<axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
         '<joint name="jb" type="revolute"><parent link="a"/><child link="b"/>'
         '<origin xyz="0.3 0 0"/><axis xyz="0 0 1"/>'
         '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>')


def test_closed_form_asked_for_a_limb_it_does_not_take_says_it_solved_numerically(tmp_path,
                                                                                   run_cli):
    path = tmp_path / "r.urdf"
    path.write_text(ROBOT)
    words = ("ik", str(path), "--tip", "b", "--xyz", "0.5", "0", "0")
    result = run_cli(*words, "--method", "closed-form")
    assert result.exit_code == 0, result.output
    assert "(position only, numeric): solved" in result.stdout
    assert "warning: --method closed-form: the target was solved numerically: the closed " \
        "form takes a planar limb" in result.stderr
    result = run_cli(*words)
    assert result.exit_code == 0 and "warning" not in result.stderr, result.output
