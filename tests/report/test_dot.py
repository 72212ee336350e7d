"""``urdftool graph``: DOT of the kinematic tree, coloured by findings; rendering with dot."""

from __future__ import annotations

import shutil

import pytest

from conftest import ROBOTS

BAD = """<robot name="bad">
  <link name="base_link"/>
  <link name="arm"/>
  <link name="hand"/>
  <joint name="elbow" type="revolute">
    <parent link="base_link"/><child link="arm"/>
    <limit lower="1" upper="-1" effort="1" velocity="1"/>
  </joint>
  <joint name="wrist" type="continuous">
    <parent link="arm"/><child link="hand"/><axis xyz="0 0 2"/>
  </joint>
</robot>
"""


@pytest.fixture
def bad(tmp_path):
    path = tmp_path / "bad.urdf"
    path.write_text(BAD)
    return path


def _line(dot: str, start: str) -> str:
    return next(line.strip() for line in dot.splitlines() if line.strip().startswith(start))


def test_dot_colours_links_and_joints_by_worst_finding(run_cli, bad):
    result = run_cli("graph", bad)
    assert result.exit_code == 0, result.output
    dot = result.stdout
    assert dot.startswith('digraph "bad" {')
    assert _line(dot, '"base_link"') == '"base_link";'
    assert 'fillcolor="#ffcdd2"' in _line(dot, '"arm" [')        # error: red
    assert 'fillcolor="#ffe0b2"' in _line(dot, '"hand" [')       # warning: orange
    elbow = _line(dot, '"base_link" -> "arm"')
    assert 'label="elbow\\nrevolute [1, -1] rad"' in elbow and "U204" in elbow
    assert 'label="wrist\\ncontinuous"' in _line(dot, '"arm" -> "hand"')


def test_humanoid_graph_has_every_link_and_joint(run_cli):
    result = run_cli("graph", ROBOTS / "humanoid" / "humanoid.urdf.xacro")
    assert result.exit_code == 0
    assert result.stdout.count(" -> ") == 21 and "#ffcdd2" not in result.stdout
    assert 'label="l_knee\\nrevolute [0, 2.269] rad"' in result.stdout


def test_dot_output_file(run_cli, bad, tmp_path):
    result = run_cli("graph", bad, "-o", tmp_path / "tree.dot")
    assert result.exit_code == 0
    assert (tmp_path / "tree.dot").read_text().startswith('digraph "bad"')


def test_without_dot_the_dot_source_is_written_and_explained(run_cli, bad, tmp_path,
                                                              monkeypatch):
    monkeypatch.setenv("PATH", str(tmp_path / "empty"))
    result = run_cli("graph", bad, "-o", tmp_path / "tree.svg")
    assert result.exit_code == 2
    assert "'dot' program is not installed" in result.stderr
    assert f"wrote the DOT source to {tmp_path / 'tree.dot'}" in result.stderr
    assert not (tmp_path / "tree.svg").exists()
    assert (tmp_path / "tree.dot").read_text().startswith('digraph "bad"')


def test_the_command_suggested_without_dot_is_one_shell_word_a_path(run_cli, bad, tmp_path,
                                                                    monkeypatch):
    # session 13: a path with a blank or a ';' was pasted into the suggested command as is
    import shlex

    monkeypatch.setenv("PATH", str(tmp_path / "empty"))
    result = run_cli("graph", bad, "-o", tmp_path / "a b;touch x.svg")
    command = result.stderr.split("render it with `", 1)[1].split("`", 1)[0]
    assert shlex.split(command) == ["dot", "-Tsvg", str(tmp_path / "a b;touch x.dot"), "-o",
                                    str(tmp_path / "a b;touch x.svg")]


@pytest.mark.skipif(shutil.which("dot") is None, reason="Graphviz's dot is not installed (apt-get install graphviz)")
@pytest.mark.parametrize("suffix, magic", [(".svg", b"<?xml"), (".png", b"\x89PNG")])
def test_rendered_with_dot(run_cli, bad, tmp_path, suffix, magic):
    out = tmp_path / f"tree{suffix}"
    result = run_cli("graph", bad, "-o", out)
    assert result.exit_code == 0, result.output
    assert out.read_bytes().startswith(magic)


def test_unknown_suffix_is_a_usage_error(run_cli, bad, tmp_path):
    result = run_cli("graph", bad, "-o", tmp_path / "tree.jpeg")
    assert result.exit_code == 2 and "use .dot" in result.stderr


def test_one_file_only(run_cli, bad):
    assert run_cli("graph", bad, bad).exit_code == 2


def test_a_link_a_joint_names_but_nobody_defines_is_drawn_as_missing(run_cli, tmp_path):
    path = tmp_path / "r.urdf"
    path.write_text('<robot name="r"><link name="a"/><joint name="j" type="fixed">'
                    '<parent link="a"/><child link="ghost"/></joint></robot>')
    dot = run_cli("graph", path, "--timeout", "0").stdout
    [node] = [line for line in dot.splitlines() if line.strip().startswith('"ghost" [')]
    assert 'style="dashed"' in node and 'label="ghost\\n(missing)"' in node


def test_links_beside_the_tree_are_drawn_apart_as_the_warning_says(run_cli, tmp_path):
    """A loop of joints no joint from the root reaches (urdfdom drops it; every other command
    leaves it out, by kinematics.tree.beside_the_tree): graph drew its links and joints as
    links of the tree, while its warning said they were "left out". They are drawn dashed and
    grey, labelled as beside the tree, the loop's finding still coloured, and the warning says
    how they are drawn; the tree itself is drawn as before."""
    path = tmp_path / "r.urdf"
    path.write_text('<robot name="r"><link name="r"/><link name="x"/><link name="a"/>'
                    '<link name="b"/>' + "".join(
                        f'<joint name="{name}" type="fixed"><parent link="{parent}"/>'
                        f'<child link="{child}"/></joint>'
                        for name, parent, child in (("j0", "r", "x"), ("j1", "a", "b"),
                                                    ("j2", "b", "a"))) + "</robot>")
    result = run_cli("graph", "--timeout", "0", "--max-memory", "0", path)
    assert result.exit_code == 0, result.output
    dot = result.stdout
    for link in ("a", "b"):
        line = _line(dot, f'"{link}" [')
        assert 'style="rounded,dashed,filled"' in line, line
        assert f'label="{link}\\n(beside the tree)"' in line and "urdfdom" in line, line
    assert 'style="dashed"' in _line(dot, '"a" -> "b"')
    loop = _line(dot, '"b" -> "a"')
    assert 'style="dashed"' in loop and "U109" in loop and "#c62828" in loop, loop
    assert _line(dot, '"r"') == '"r";' and _line(dot, '"r" -> "x"') == \
        '"r" -> "x" [label="j0\\nfixed"];'
    assert "2 links beside the tree, which no joint from the root reaches, drawn dashed, " \
        "apart from the tree" in result.stderr and "left out" not in result.stderr


def test_each_root_of_a_robot_of_several_is_labelled_so(tmp_path):
    """elephantrobotics' ultraArm_p340_aiki.urdf: a link 'env' no joint reaches beside the arm
    from 'base' (U108, which urdfdom refuses). graph drew both parts as any links, and only the
    finding's tooltip (which a PNG has not) said that 'base' was a second root; 'env', the part
    apart, looked like a link of the robot. Each root is labelled with its place among them,
    a tooltip saying why; a robot of one root is drawn as before."""
    from urdftool.description.load import load
    from urdftool.report.dot import to_dot

    def load_text(text: str):
        (tmp_path / "r.urdf").write_text(text)
        return load(tmp_path / "r.urdf")

    robot = load_text('<robot name="r"><link name="env"/><link name="base"/><link name="a"/>'
                      '<joint name="j" type="fixed"><parent link="base"/><child link="a"/>'
                      '</joint></robot>')
    dot = to_dot(robot)
    assert 'label="env\\n(root 1 of 2)"' in _line(dot, '"env" [')
    assert 'label="base\\n(root 2 of 2)"' in _line(dot, '"base" [')
    assert "urdfdom refuses" in _line(dot, '"base" [') and _line(dot, '"a"') == '"a";'
    one = load_text('<robot name="r"><link name="base"/><link name="a"/><joint name="j" '
                    'type="fixed"><parent link="base"/><child link="a"/></joint></robot>')
    assert _line(to_dot(one), '"base"') == '"base";'
