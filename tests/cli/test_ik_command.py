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


def test_the_targets_of_a_file_are_written_as_they_are_solved(tmp_path, run_cli, monkeypatch):
    """Each target's output is written before the next is solved (text, --check-reach, CSV
    and a JSON list): every solution and the whole text were held until the last target."""
    from urdftool.cli import ik as command
    from urdftool.kinematics import ik
    from urdftool.report import json_output

    path, targets = tmp_path / "r.urdf", tmp_path / "targets.csv"
    path.write_text(ROBOT)
    targets.write_text("x,y,z\n" + "".join(f"0.{4 + k % 3},0.0{k},0\n" for k in range(6)))
    events: list[str] = []
    solve, show, dumps = ik.solve, command.show, json_output.dumps
    monkeypatch.setattr(ik, "solve", lambda *a, **k: events.append("solve") or solve(*a, **k))
    monkeypatch.setattr(command, "show", lambda *a, **k: events.append("write") or show(*a, **k))
    monkeypatch.setattr(json_output, "dumps",
                        lambda *a, **k: events.append("write") or dumps(*a, **k))
    for words in (("--targets", targets), ("--check-reach", targets),
                  ("--targets", targets, "-f", "csv"), ("--targets", targets, "-f", "json")):
        events.clear()
        result = run_cli("ik", path, "--tip", "b", "--seeds", "2", *words)
        assert events.count("solve") == 6, (words, result.output)
        last_solve = len(events) - 1 - events[::-1].index("solve")
        assert "write" in events[:last_solve], (words, events)
        assert result.stdout.count("0.0") >= 6
