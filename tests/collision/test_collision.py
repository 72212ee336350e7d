"""urdftool.collision and ``urdftool collisions``: pose checks, the matrix, SRDF handling."""

from __future__ import annotations

import io
import json

import numpy as np
import pytest

from conftest import ROBOTS, corpus_or_skip
from urdftool.collision import matrix, pose, srdf
from urdftool.description.load import load

HUMANOID = ROBOTS / "humanoid" / "humanoid.urdf.xacro"


def _box_link(name: str, size: float = 0.1, xyz: str = "0 0 0") -> str:
    return (f'<link name="{name}"><visual><geometry><box size="{size} {size} {size}"/></geometry>'
            f'</visual><collision><origin xyz="{xyz}"/><geometry><box size="{size} {size} '
            f'{size}"/></geometry></collision></link>')


def two_boxes(lower: float, upper: float, extra: str = "") -> str:
    """base (far away box) with two children: a fixed box at 0 and a box on a slider along x."""
    return f"""<robot name="boxes">
  {_box_link("base", xyz="0 0 -5")}
  {_box_link("fixed_box")}
  {_box_link("sliding_box")}
  <joint name="fix" type="fixed"><parent link="base"/><child link="fixed_box"/></joint>
  <joint name="slider" type="prismatic"><parent link="base"/><child link="sliding_box"/>
    <axis xyz="1 0 0"/><limit lower="{lower}" upper="{upper}" effort="1" velocity="1"/></joint>
  {extra}
</robot>
"""


def write(tmp_path, text: str, name: str = "robot.urdf"):
    path = tmp_path / name
    path.write_text(text)
    return path


def robot_of(tmp_path, text: str):
    return load(str(write(tmp_path, text)))


def pose_report(robot, **q):
    scene = matrix.Scene(robot, 0.0)
    values = pose.configuration(scene, {k: str(v) for k, v in q.items()}).values[0]
    return pose.check(scene, values, {})


def test_two_boxes_collide_with_depth(tmp_path):
    report = pose_report(robot_of(tmp_path, two_boxes(0, 1)), slider=0.06)
    [contact] = [c for c in report.colliding if c.link2 == "sliding_box"]
    assert (contact.link1, contact.allowed) == ("fixed_box", "")
    assert contact.depth == pytest.approx(0.04, abs=1e-6)
    assert report.forbidden == [contact]


@pytest.mark.parametrize("slider, touching", [(0.1, True), (0.0995, True), (0.098, False)])
def test_boxes_that_touch_do_not_collide(run_cli, tmp_path, slider, touching):
    """Two boxes sharing a face are an FCL contact of depth 0: they touch (exit 0), as up to
    pairs.TOUCHING (1 mm) deep; deeper is a collision. They were COLLIDING, exit 1."""
    from urdftool.collision.pairs import TOUCHING

    report = pose_report(robot_of(tmp_path, two_boxes(0, 1)), slider=slider)
    [contact] = [c for c in report.colliding if c.link2 == "sliding_box"]
    assert contact.touching is touching and TOUCHING == 0.001
    assert report.forbidden == ([] if touching else [contact])
    result = run_cli("collisions", tmp_path / "robot.urdf", "--q", f"slider={slider}")
    assert result.exit_code == (0 if touching else 1), result.output
    assert ("no self-collision (1 pair(s) touching)" in result.stdout) is touching
    assert ("touching: in contact at most 1 mm deep" in result.stdout) is touching
    data = json.loads(run_cli("collisions", tmp_path / "robot.urdf", "--q", f"slider={slider}",
                              "-f", "json").stdout)
    assert data["touching_depth"] == TOUCHING
    assert [c["touching"] for c in data["colliding"]] == [touching]


def _mesh_boxes(tmp_path, mesh) -> str:
    """two_boxes with every box's collision the mesh ``mesh`` (a trimesh) instead; the slider
    from 0.02 (its default pose mid-range, apart)."""
    mesh.export(tmp_path / "part.stl")
    return two_boxes(0.02, 1).replace('<box size="0.1 0.1 0.1"/></geometry></collision>',
                                   '<mesh filename="part.stl"/></geometry></collision>')


def _dumbbell():
    """Two 10 cm cubes 10 cm apart in one mesh: closed, not convex (its hull is 30 cm long)."""
    import trimesh

    cube = trimesh.creation.box((0.1, 0.1, 0.1))
    return trimesh.util.concatenate([cube, cube.copy().apply_translation((0.2, 0, 0))])


@pytest.mark.parametrize("slider, depth, touching", [(0.05, 0.05, False), (0.0995, 0.0005, True)])
def test_a_convex_mesh_contact_has_its_depth(run_cli, tmp_path, slider, depth, touching):
    """Box meshes (convex) take their depth from their convex hulls, as boxes from FCL: FCL's
    contacts between triangles carry one triangle's depth through the other's plane (0.098 m
    for these cubes at any overlap), so half a millimetre of overlap was '? (mesh)' and a
    collision (exit 1), and the SRDF overlaps said 98 mm."""
    import trimesh
    from lxml import etree

    text = _mesh_boxes(tmp_path, trimesh.creation.box((0.1, 0.1, 0.1)))
    robot = robot_of(tmp_path, text)
    report = pose_report(robot, slider=slider)
    [contact] = [c for c in report.colliding if c.link2 == "sliding_box"]
    assert contact.depth == pytest.approx(depth, abs=1e-6) == contact.depth_at_most
    assert contact.touching is touching and report.forbidden == ([] if touching else [contact])
    result = run_cli("collisions", tmp_path / "robot.urdf", "--q", f"slider={slider}")
    assert result.exit_code == (0 if touching else 1), result.output
    assert "(hulls)" not in result.stdout and "?" not in result.stdout
    state = ('<group name="g"><joint name="slider"/></group><group_state name="s" group="g">'
             f'<joint name="slider" value="{slider}"/></group_state>')
    found = srdf.overlaps(robot, etree.fromstring(f'<robot name="boxes">{state}</robot>'))
    assert [(pair, o.depth) for pair, o in found.items()] == \
        ([] if touching else [(("fixed_box", "sliding_box"), pytest.approx(depth, abs=1e-6))])


@pytest.mark.parametrize("slider, touching", [(0.05, False), (0.0995, True)])
def test_a_non_convex_mesh_contact_has_its_hulls_depth_as_a_bound(run_cli, tmp_path, slider,
                                                                  touching):
    """Dumbbells whose cubes meet: the depth is not known (None, JSON null), at most the hulls'
    (the same here, as the cubes that meet are the hulls' ends); hulls that only touch make
    the meshes touch."""
    report = pose_report(robot_of(tmp_path, _mesh_boxes(tmp_path, _dumbbell())),
                         slider=0.2 + slider)
    [contact] = [c for c in report.colliding if c.link2 == "sliding_box"]
    assert contact.depth is None and contact.depth_at_most == pytest.approx(
        0.1 - slider, abs=1e-6)
    assert contact.touching is touching and report.forbidden == ([] if touching else [contact])
    result = run_cli("collisions", tmp_path / "robot.urdf", "--q", f"slider={0.2 + slider}")
    assert result.exit_code == (0 if touching else 1), result.output
    assert f"<= {1000 * (0.1 - slider):.2f} (hulls)" in result.stdout
    assert "(flat mesh)" not in result.stdout
    data = json.loads(run_cli("collisions", tmp_path / "robot.urdf", "--q",
                              f"slider={0.2 + slider}", "-f", "json").stdout)
    assert [(c["depth"], c["touching"]) for c in data["colliding"]] == [(None, touching)]


@pytest.mark.parametrize("shape, depth", [
    ('<cylinder radius="0.025" length="0.09"/>', 0.037),  # EPA: 62 mm
    ('<box size="0.1 0.1 0.1"/>', 0.1)])  # FCL's box-box: right; the mesh cubes' EPA: 141 mm
def test_parts_centred_on_each_other_have_their_depth(tmp_path, shape, depth):
    """Parts placed at one origin, as CAD exports place them: libccd's EPA overshoots there
    (crossing cylinders 37 mm into each other were 62 mm; coincident cube meshes 141 mm), so
    the depth is bounded by the least overlap along the parts' axes."""
    import trimesh

    first = shape if "cylinder" in shape else '<mesh filename="part.stl"/>'
    second = '<cylinder radius="0.012" length="0.26"/>' if "cylinder" in shape else first
    trimesh.creation.box((0.1, 0.1, 0.1)).export(tmp_path / "part.stl")
    text = two_boxes(-1, 1).replace(
        '<collision><origin xyz="0 0 0"/><geometry><box size="0.1 0.1 0.1"/></geometry>',
        f'<collision><origin rpy="0 1.5707963 0"/><geometry>{first}</geometry>', 1).replace(
        '<collision><origin xyz="0 0 0"/><geometry><box size="0.1 0.1 0.1"/></geometry>',
        f'<collision><origin rpy="1.5707963 0 0"/><geometry>{second}</geometry>', 1)
    report = pose_report(robot_of(tmp_path, text), slider=0.0)
    [contact] = [c for c in report.colliding if c.link2 == "sliding_box"]
    assert contact.depth == pytest.approx(depth, abs=1e-6)


def test_parts_welded_by_fixed_joints_are_allowed_at_a_pose(run_cli, tmp_path):
    """Two links fixed to one body overlap in every configuration (Upkie's femur inside its
    hip horn, both fixed to the motor's rotor): 'Welded', not a collision that exits 1."""
    text = two_boxes(0, 1).replace('<joint name="slider" type="prismatic">',
                                   '<joint name="slider" type="fixed">').replace(
        '<axis xyz="1 0 0"/><limit lower="0" upper="1" effort="1" velocity="1"/>',
        '<origin xyz="0.05 0 0"/>')
    robot = robot_of(tmp_path, text)
    report = pose.check(matrix.Scene(robot, 0.0), np.zeros(0), {})
    [contact] = [c for c in report.colliding if c.link2 == "sliding_box"]
    assert contact.allowed == "Welded" and not report.forbidden
    result = run_cli("collisions", tmp_path / "robot.urdf")
    assert result.exit_code == 0 and "allowed (Welded)" in result.stdout, result.output


def test_a_flat_mesh_contact_has_no_depth_and_is_a_collision(run_cli, tmp_path):
    """A mesh without volume (a square; the fixed one stood on its edge, crossed by the
    sliding one) has no hull: its contact is a collision of unknown depth, never only
    touching."""
    import trimesh

    square = trimesh.Trimesh([[-0.05, -0.05, 0], [0.05, -0.05, 0], [0.05, 0.05, 0],
                              [-0.05, 0.05, 0]], [[0, 1, 2], [0, 2, 3]])
    text = _mesh_boxes(tmp_path, square).replace('<origin xyz="0 0 0"/><geometry><mesh',
                                                  '<origin rpy="0 1.5708 0"/><geometry><mesh', 1)
    report = pose_report(robot_of(tmp_path, text), slider=0.03)
    contact = next(c for c in report.colliding if c.link2 == "sliding_box")
    assert (contact.depth, contact.depth_at_most, contact.touching) == (None, None, False)
    result = run_cli("collisions", tmp_path / "robot.urdf", "--q", "slider=0.03")
    assert result.exit_code == 1 and "? (flat mesh)" in result.stdout, result.output
    assert "<= (hulls)" not in result.stdout


def test_a_comment_before_the_shape_is_not_the_geometry(tmp_path):
    """youBot's base: <geometry><!--<box .../>--><mesh .../></geometry>. The comment was taken
    for the shape: "<collision> has no geometry; ignored", so every pose with the base was
    "not established" (exit 1)."""
    text = two_boxes(0, 1).replace('<geometry><box size="0.1 0.1 0.1"/></geometry></collision>',
                                   '<geometry><!-- <sphere radius="1"/> --><box size="0.1 0.1 '
                                   '0.1"/></geometry></collision>')
    report = pose_report(robot_of(tmp_path, text), slider=0.06)
    assert not report.problems
    [contact] = [c for c in report.colliding if c.link2 == "sliding_box"]
    assert contact.depth == pytest.approx(0.04, abs=1e-6)


def test_a_pose_check_places_the_parts_once_for_all_pairs(tmp_path, monkeypatch):
    scene = matrix.Scene(robot_of(tmp_path, two_boxes(0, 1)), 0.0)
    placed = []
    part_poses = scene.checker.part_poses
    monkeypatch.setattr(scene.checker, "part_poses", lambda p: placed.append(1) or part_poses(p))
    report = pose.check(scene, pose.configuration(scene, {"slider": "0.06"}).values[0], {})
    assert len(scene.pairs) == 3 and len(placed) == 1  # was once per pair
    assert [(c.link1, c.link2) for c in report.colliding] == [("fixed_box", "sliding_box")]


def test_two_boxes_apart_with_distance(tmp_path):
    report = pose_report(robot_of(tmp_path, two_boxes(0, 1)), slider=0.5)
    assert not report.colliding
    nearest = report.closest[0]
    assert (nearest.link1, nearest.link2) == ("fixed_box", "sliding_box")
    assert nearest.distance == pytest.approx(0.4, abs=1e-6)


def test_unknown_joint_in_q_names_the_joints_but_no_option(tmp_path):
    from urdftool.kinematics.configuration import ConfigError

    with pytest.raises(ConfigError, match="^unknown joint 'slidr'; did you mean 'slider'"):
        pose.check_pose(robot_of(tmp_path, two_boxes(0, 1)), {"slidr": "1"})


def test_check_pose_reads_the_srdf_given_and_warns_outside_limits(tmp_path):
    robot = robot_of(tmp_path, two_boxes(0, 1))
    allowed = write(tmp_path, '<robot name="boxes"><disable_collisions link1="sliding_box" '
                    'link2="fixed_box" reason="User"/></robot>', "allow.srdf")
    report = pose.check_pose(robot, {"slider": "0.05"}, srdf=allowed)
    assert [c.allowed for c in report.colliding] == ["User"] and not report.forbidden
    assert report.srdf.endswith("allow.srdf") and report.warnings == []
    beyond = pose.check_pose(robot, {"slider": "2"})
    assert beyond.warnings == ["joint 'slider' = 2 is outside its limits [0, 1]; computed anyway"]


def test_check_pose_refuses_a_broken_srdf(tmp_path):
    broken = write(tmp_path, "<robot>", "broken.srdf")
    with pytest.raises(srdf.SrdfError, match="broken.srdf:1"):
        pose.check_pose(robot_of(tmp_path, two_boxes(0, 1)), {}, srdf=broken)


def test_collisions_finds_the_srdf_in_config_as_check_does(run_cli, tmp_path, monkeypatch):
    """One SRDF finder: config/<robot>.srdf is the robot's SRDF for collisions as for check
    (collisions used to look only beside the file and printed 'SRDF: none')."""
    path = write(tmp_path, two_boxes(0, 1))
    (tmp_path / "config").mkdir()
    write(tmp_path / "config", '<robot name="boxes"><disable_collisions link1="fixed_box" '
          'link2="sliding_box" reason="User"/></robot>', "boxes.srdf")
    monkeypatch.chdir(tmp_path)
    result = run_cli("collisions", "robot.urdf", "--q", "slider=0.05")
    assert result.exit_code == 0, result.output
    assert "SRDF: config/boxes.srdf" in result.output and "allowed (User)" in result.output
    assert pose.check_pose(load(str(path)), {}).srdf == "config/boxes.srdf"


def test_adjacency_looks_through_links_without_geometry(tmp_path):
    text = f"""<robot name="chain">
  {_box_link("a")}<link name="m1"/><link name="m2"/>{_box_link("b")}{_box_link("c")}
  <joint name="j1" type="fixed"><parent link="a"/><child link="m1"/></joint>
  <joint name="j2" type="fixed"><parent link="m1"/><child link="m2"/></joint>
  <joint name="j3" type="fixed"><parent link="m2"/><child link="b"/></joint>
  <joint name="j4" type="fixed"><parent link="b"/><child link="c"/>
    <origin xyz="1 0 0"/></joint>
</robot>"""
    scene = matrix.Scene(robot_of(tmp_path, text), 0.005)
    assert scene.adjacent == {("a", "b"), ("b", "c")}


def test_default_pose_collision_is_default_class(tmp_path):
    result = matrix.compute(robot_of(tmp_path, two_boxes(0, 1)), samples=500, workers=1)
    assert result.pair("fixed_box", "sliding_box").reason == "Default"


def test_always_never_and_the_margin(tmp_path):
    # 0 is outside [0.2, 0.5]: the default is mid-range and the boxes stay >= 0.1 m apart.
    robot = robot_of(tmp_path, two_boxes(0.2, 0.5))
    assert matrix.compute(robot, samples=500, workers=1).pair(
        "fixed_box", "sliding_box").reason == "Never"
    wide = matrix.compute(robot, samples=500, workers=1, margin=0.2).pair("fixed_box",
                                                                          "sliding_box")
    assert wide.reason == "" and wide.collisions == 0
    assert wide.min_distance == pytest.approx(0.1, abs=0.01)


def test_matrix_is_deterministic_for_a_seed_and_any_worker_count(tmp_path):
    robot = load(str(HUMANOID))
    runs = [matrix.compute(robot, samples=1000, seed=7, workers=w) for w in (1, 2, 2)]
    rows = [[(p.link1, p.link2, p.reason, p.collisions, p.min_distance) for p in run.pairs]
            for run in runs]
    assert rows[0] == rows[1] == rows[2]
    other = matrix.compute(robot, samples=1000, seed=8, workers=1)
    assert [p.collisions for p in other.pairs] != [p.collisions for p in runs[0].pairs]



@pytest.mark.parametrize("samples, until, most", [(1000, False, 4), (1000, True, 640)])
def test_the_matrix_starts_no_more_workers_than_blocks(tmp_path, monkeypatch, samples, until, most):
    """collisions --matrix --workers 10**18 asked the pool for that many processes, which
    forked until the budget stopped them, for 4 blocks of samples."""
    import contextlib

    asked = []
    monkeypatch.setattr(matrix, "_pool", lambda workers: asked.append(workers) or
                        contextlib.nullcontext(None))
    robot = robot_of(tmp_path, two_boxes(0.2, 0.5))
    matrix.compute(robot, samples=samples, workers=10 ** 18, until_converged=until)
    assert asked == [most]


def test_progress_reports_every_block_up_to_the_planned_total(tmp_path):
    robot = robot_of(tmp_path, two_boxes(0.2, 0.5))
    calls = []
    result = matrix.compute(robot, samples=1000, workers=2,
                            progress=lambda done, planned: calls.append((done, planned)))
    assert [done for done, _ in calls] == sorted(done for done, _ in calls)
    assert calls[-1] == (result.samples, result.samples) and len(calls) == result.samples // 250

@pytest.fixture(scope="module")
def humanoid_matrix():
    robot = load(str(HUMANOID))
    return robot, matrix.compute(robot, samples=2000, seed=0)


def test_humanoid_adjacent_pairs_match_its_srdf(humanoid_matrix):
    _, result = humanoid_matrix
    entries, _ = srdf.read(ROBOTS / "humanoid" / "humanoid.srdf")
    expected = {matrix.pair_key(e.link1, e.link2) for e in entries if e.reason == "Adjacent"}
    assert {(p.link1, p.link2) for p in result.pairs if p.reason == "Adjacent"} == expected


def test_srdf_round_trip_and_merge_keeps_other_content(humanoid_matrix, tmp_path):
    robot, result = humanoid_matrix
    fresh = tmp_path / "new.srdf"
    fresh.write_text(srdf.render(result, robot.name))
    entries, _ = srdf.read(fresh)
    assert [(e.link1, e.link2, e.reason) for e in entries] == srdf.entries_of(result)
    assert [(e.link1, e.link2) for e in entries] == sorted(
        [(e.link1, e.link2) for e in entries], key=lambda p: (p[0].encode(), p[1].encode()))
    existing = tmp_path / "old.srdf"
    existing.write_text('<?xml version="1.0"?>\n<!-- head -->\n<robot name="humanoid_robot">\n'
                        '  <!-- keep me -->\n  <group name="g"><link name="body_link"/></group>\n'
                        '  <disable_collisions link1="gone" link2="body_link" reason="Never"/>\n'
                        '  <disable_collisions link1="body_link" link2="l_foot_link" '
                        'reason="User"/>\n</robot>\n')
    merged = srdf.render(result, robot.name, existing)
    assert merged.startswith('<?xml version="1.0"?>\n<!-- head -->\n<robot name=')
    assert "<!-- keep me -->" in merged and '<group name="g">' in merged
    assert 'link1="gone"' not in merged and 'reason="User"' in merged
    existing.write_text(merged)
    again, _ = srdf.read(existing)
    assert len(again) == len(entries) + 1


@pytest.mark.parametrize("document, tag", [
    ('<robot name="r">\n  <link name="a"/>\n</robot>\n', "<link>"),
    ('<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n  <xacro:macro name="m"/>\n'
     '</robot>\n', "<xacro:macro>")])
def test_an_srdf_is_never_merged_into_a_robot_description(humanoid_matrix, tmp_path,
                                                          document, tag):
    # session 13: collisions --write-srdf naming a URDF or a macro file merged the entries into
    # it, its tags rewritten by lxml (attributes written across lines joined)
    robot, result = humanoid_matrix
    existing = tmp_path / "arm.xacro"
    existing.write_text(document)
    with pytest.raises(srdf.SrdfError, match=f"arm.xacro:2: {tag} is not an SRDF element"):
        srdf.render(result, robot.name, existing)
    assert existing.read_text() == document


@pytest.mark.parametrize("prolog, body", [
    ("<!-- ------ -->\n", '<group name="g"/>'),
    ('<!DOCTYPE robot [<!ENTITY g "arm">]>\n', '<group name="&g;"/>')])
def test_an_srdf_srdfdom_reads_otherwise_than_xml_is_never_merged_into(humanoid_matrix, tmp_path,
                                                                       prolog, body):
    # session 20: an SRDF with '--' in a comment before its root (khi_duaro's, victor's are
    # read with a warning) ended `collisions --matrix --write-srdf` in expat's traceback after
    # the matrix; merged, its comments' hyphens and its entities would be written as srdfdom
    # reads them (blanks, "&amp;g;")
    robot, result = humanoid_matrix
    existing = tmp_path / "r.srdf"
    document = f'<?xml version="1.0"?>\n{prolog}<robot name="r">\n  {body}\n</robot>\n'
    existing.write_text(document)
    with pytest.raises(srdf.SrdfError, match=r"r.srdf:[24]: not updated: .*srdfdom"):
        srdf.check_update(existing)
    with pytest.raises(srdf.SrdfError, match=r"r.srdf:[24]: not updated"):
        srdf.render(result, robot.name, existing)
    assert existing.read_text() == document


def test_check_srdf_locates_stale_entries_at_the_start_tag(humanoid_matrix, tmp_path):
    robot, result = humanoid_matrix
    never = next(p for p in result.pairs if p.reason == "" and p.collisions)
    path = tmp_path / "stale.srdf"
    path.write_text('<robot name="humanoid_robot">\n'
                    '  <disable_collisions link1="nope_link"\n      link2="body_link" '
                    'reason="Never"/>\n'
                    f'  <disable_collisions\n    link1="{never.link1}" link2="{never.link2}"\n'
                    '    reason="Never"/>\n</robot>\n')
    entries, root = srdf.read(path)
    found = {(s.location.line, s.message.split(";")[0]) for s in
             srdf.stale(result, entries, robot.links, root)}
    assert (2, "disable_collisions names link 'nope_link', which does not exist") in found
    assert any(line == 4 and "disabled as Never but collided" in m for line, m in found)
    assert sum(line == 1 and "are adjacent but are not disabled" in m for line, m in found) == 20


def test_plot_svg_has_a_cell_per_pair(humanoid_matrix, tmp_path):
    from urdftool.report import plot

    _, result = humanoid_matrix
    out = tmp_path / "m.svg"
    plot.write(result, out, "humanoid")
    text = out.read_text()
    assert text.startswith("<svg") and text.count("<title>") == 2 * len(result.pairs)



def test_plot_column_labels_stay_below_the_title_and_legend_matches_cells(humanoid_matrix):
    import re

    from urdftool.report import plot

    _, result = humanoid_matrix
    text = plot.svg(result, "humanoid")
    longest = max(len(name) for name in result.links)
    tops = [float(y) for y in re.findall(r'translate\([\d.]+,([\d.]+)\) rotate', text)]
    assert tops and min(tops) - 7 * longest >= 16 + 4  # title baseline + descent
    never = plot._shade(next(p for p in result.pairs if p.reason == "Never"))
    assert f'fill="{plot.COLOURS["Never"]}" fill-opacity="{never:.2f}"></rect>' in text


def test_plot_png_draws_the_same_cells(humanoid_matrix, tmp_path):
    image_module = pytest.importorskip("PIL.Image")
    from urdftool.report import plot

    _, result = humanoid_matrix
    plot.write(result, tmp_path / "m.png", "humanoid")
    width, height, items = plot._layout(result, "humanoid")
    image = image_module.open(tmp_path / "m.png").convert("RGB")
    assert image.size == (2 * width, 2 * height)
    for item in [i for i in items if i[0] == "rect" and i[5] == "#000000"][:3]:
        assert image.getpixel((2 * item[1] + 4, 2 * item[2] + 4)) == (0, 0, 0)
    adjacent = next(i for i in items if i[0] == "rect" and i[5] == plot.COLOURS["Adjacent"])
    assert image.getpixel((2 * adjacent[1] + 4, 2 * adjacent[2] + 4)) == (127, 127, 127)

def test_missing_mesh_and_visual_only_links_are_reported(tmp_path):
    text = two_boxes(0, 1, extra="""
  <link name="camera"><visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual></link>
  <joint name="cam" type="fixed"><parent link="base"/><child link="camera"/></joint>
  <link name="meshy"><collision><geometry><mesh filename="missing.stl"/></geometry></collision>
  </link>
  <joint name="m" type="fixed"><parent link="base"/><child link="meshy"/></joint>""")
    scene = matrix.Scene(robot_of(tmp_path, text), 0.0)
    assert scene.geometry.visual_only == ["camera"]
    [problem] = scene.geometry.problems
    assert "missing.stl" in problem.message and problem.location.line == 11


FAR_PARTS = {"box": '<box size="1e300 1 1"/>', "sphere": '<sphere radius="1e200"/>',
             "cylinder": '<cylinder radius="1" length="1e300"/>',
             "mesh": '<mesh filename="t.stl" scale="1e30 1e30 1e30"/>',
             "origin": '<box size="1 1 1"/>'}


def far_robot(tmp_path, part: str) -> str:
    """base and a far part on a slider (its geometry in ``FAR_PARTS``), and a box beyond."""
    (tmp_path / "t.stl").write_text("solid t\n" + "".join(
        f"facet normal 0 0 0\nouter loop\nvertex {a}\nvertex {b}\nvertex {c}\nendloop\n"
        "endfacet\n" for a, b, c in (("0 0 0", "1 0 0", "0 1 0"), ("0 0 0", "0 1 0", "0 0 1"),
                                     ("0 0 0", "0 0 1", "1 0 0"), ("1 0 0", "0 1 0", "0 0 1")))
        + "endsolid t\n")
    xyz = "1e300 0 0" if part == "origin" else "0 0 0"
    far = (f'<origin xyz="{xyz}"/><geometry>{FAR_PARTS[part]}</geometry>')
    return two_boxes(0, 1, extra=f"""
  <link name="far"><visual>{far}</visual><collision>{far}</collision></link>
  <joint name="f" type="fixed"><parent link="sliding_box"/><child link="far"/></joint>""")


@pytest.mark.parametrize("part", FAR_PARTS)
def test_a_part_past_the_farthest_coordinate_is_left_out_with_a_note(tmp_path, part):
    """A box 1e300 long, a sphere of radius 1e200, a mesh scaled by 1e30, a part at 1e300: FCL
    measured "inf" distances and numpy warned of overflows. Each is left out of every check
    (transforms.too_far, the bound render's parts share), the rest checked."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        scene = matrix.Scene(robot_of(tmp_path, far_robot(tmp_path, part)), 0.0)
        [problem] = scene.geometry.problems
        assert "link 'far'" in problem.message and "past the 4.612e+10 m" in problem.message
        assert "far" not in scene.geometry.parts
        report = pose.check_pose(robot_of(tmp_path, far_robot(tmp_path, part)), {})
        assert all(np.isfinite(c.distance) for c in report.closest), report.closest


def test_a_pair_no_sample_bounded_keeps_its_distance_unknown():
    """A tally whose pair has no bounding sample (index -1: its spheres' gaps were never
    finite, as with a part at 1e200 before the bound) drew block -1 as the seed [0, -1]:
    numpy refused it and the matrix said "--seed must be an integer, 0 or more, not 0". No
    sample, nothing drawn or posed: the distance stays unknown."""
    from urdftool.collision.pairs import Tally

    assert matrix._distances(None, None, Tally.empty(2), 0) == [np.inf, np.inf]


def test_cli_pose_exit_codes_and_json(run_cli, tmp_path):
    path = write(tmp_path, two_boxes(0, 1))
    colliding = run_cli("collisions", path, "--q", "slider=0.05")
    assert colliding.exit_code == 1 and "COLLIDING" in colliding.output
    apart = run_cli("collisions", path, "--q", "slider=0.5", "--format", "json")
    assert apart.exit_code == 0
    assert json.loads(apart.output)["closest"][0]["distance"] == pytest.approx(0.4)
    allowed = write(tmp_path, '<robot name="boxes"><disable_collisions link1="sliding_box" '
                    'link2="fixed_box" reason="User"/></robot>', "allow.srdf")
    result = run_cli("collisions", path, "--q", "slider=0.05", "--srdf", allowed)
    assert result.exit_code == 0 and "allowed (User)" in result.output
    unknown = run_cli("collisions", path, "--q", "slidr=1")
    assert unknown.exit_code == 2
    assert unknown.stderr.startswith("urdftool: error: --q: unknown joint 'slidr'")
    broken = write(tmp_path, "<robot>", "broken.srdf")
    refused = run_cli("collisions", path, "--srdf", broken)
    assert refused.exit_code == 2 and "broken.srdf:1" in refused.stderr


def test_cli_matrix_json_and_write_srdf(run_cli, tmp_path):
    path = write(tmp_path, two_boxes(0.2, 0.5))
    out = tmp_path / "out.srdf"
    result = run_cli("collisions", path, "--matrix", "--samples", "500", "--format", "json",
                     "--write-srdf", out)
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert data["converged"] and data["samples"] == 500
    assert {(p["link1"], p["link2"], p["class"]) for p in data["pairs"]} >= {
        ("fixed_box", "sliding_box", "Never")}
    assert 'reason="Never"' in out.read_text()


@pytest.mark.parametrize("target", ["include", "description"])
def test_an_srdf_update_it_would_refuse_is_refused_before_the_matrix(run_cli, tmp_path,
                                                                     monkeypatch, target):
    # session 13: the refusals of --write-srdf (an include read, a robot description) came
    # after the matrix, minutes of work on a big robot
    path = write(tmp_path, two_boxes(0.2, 0.5).replace(
        '<robot name="boxes">', '<robot name="boxes" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="colours.xacro"/>'), "robot.urdf.xacro")
    write(tmp_path, '<robot>\n  <material name="m"/>\n</robot>\n', "colours.xacro")
    other = write(tmp_path, two_boxes(0.2, 0.5), "other.urdf")

    def classify(*_):
        raise AssertionError("the matrix was computed")

    monkeypatch.setattr("urdftool.collision.classify.classify", classify)
    result = run_cli("collisions", path, "--matrix", "--write-srdf",
                     tmp_path / "colours.xacro" if target == "include" else other,
                     "--timeout", "0", "--max-memory", "0")
    assert result.exit_code == 2, result.output
    assert ("it is a file the command read (as companion SRDF, include)" if target == "include"
            else "not an SRDF element") in result.output


def test_ur5_matches_moveit_adjacency_and_never():
    corpus = corpus_or_skip()
    robot = load(str(corpus / "ur_description" / "urdf" / "ur5.xacro"))
    result = matrix.compute(robot, samples=500, seed=0)
    entries, _ = srdf.read(corpus / "ur5_moveit_config" / "config" / "ur5.srdf")
    moveit = {matrix.pair_key(e.link1, e.link2): e.reason for e in entries}
    ours = {(p.link1, p.link2): p.reason for p in result.pairs if p.disabled}
    assert {k for k, v in moveit.items() if v == "Adjacent"} == \
        {k for k, v in ours.items() if v == "Adjacent"}
    assert ours[("wrist_1_link", "wrist_3_link")] == "Never"
    # MoveIt's SRDF disables these as Never; they collide in a few percent of samples (checked
    # independently with yourdfpy + trimesh; see the merge report).
    for pair in [("base_link_inertia", "upper_arm_link"), ("shoulder_link", "wrist_1_link")]:
        assert moveit[pair] == "Never" and result.pair(*pair).collisions > 0


def test_always_colliding_pair(tmp_path):
    # A bar swinging about y next to a long fixed bar: apart at 0 (the default), crossing it
    # whenever |angle| > 0.1 rad, so in about 93% of the range [-1.5, 1.5].
    text = f"""<robot name="swing">
  {_box_link("base", xyz="0 0 -50")}
  <link name="post"><collision><geometry><box size="0.02 0.02 6"/></geometry></collision></link>
  <link name="bar"><collision><geometry><box size="0.02 0.02 6"/></geometry></collision></link>
  <joint name="fix" type="fixed"><parent link="base"/><child link="post"/></joint>
  <joint name="swing" type="revolute"><parent link="base"/><child link="bar"/>
    <origin xyz="0.3 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-1.5" upper="1.5" effort="1" velocity="1"/></joint>
</robot>"""
    robot = robot_of(tmp_path, text)
    loose = matrix.compute(robot, samples=1000, workers=1, min_fraction=0.9).pair("bar", "post")
    assert loose.reason == "Always" and 0.9 < loose.fraction < 0.95
    strict = matrix.compute(robot, samples=1000, workers=1).pair("bar", "post")
    assert strict.reason == "" and strict.collisions == loose.collisions


def test_batched_link_poses_match_yourdfpy():
    import io

    import yourdfpy

    robot = load(str(HUMANOID))
    scene = matrix.Scene(robot, 0.0)
    q = scene.sample(3, 4)
    poses = scene.poses(q)
    reference = yourdfpy.URDF.load(io.StringIO(robot.urdf), load_meshes=False)
    root = scene.kinematics.links[0]
    for k in range(len(q)):
        reference.update_cfg(dict(zip((v.name for v in scene.variables), q[k])))
        for i, link in enumerate(scene.links):
            assert np.allclose(reference.get_transform(link, root), poses[k, i], atol=1e-12)


def test_pose_q_in_degrees_and_out_of_limit_warning(run_cli):
    result = run_cli("collisions", HUMANOID, "--q", "l_knee=90", "--deg", "--format", "json")
    assert json.loads(result.stdout)["q"]["l_knee"] == pytest.approx(np.pi / 2)
    beyond = run_cli("collisions", HUMANOID, "--q", "l_knee=9", "--format", "json")
    assert "joint 'l_knee' = 9 is outside its limits" in beyond.stderr


def test_a_pose_with_geometry_left_out_is_not_called_free_of_collision(run_cli, tmp_path):
    """A collision mesh that does not resolve is left out: its link may collide unseen, so
    'no self-collision' is not said and the exit code is 1."""
    missing = ('<link name="arm"><collision><geometry><mesh filename="missing.stl"/></geometry>'
               '</collision></link><joint name="j" type="fixed"><parent link="base"/>'
               '<child link="arm"/></joint>')
    path = write(tmp_path, two_boxes(0, 1, missing))
    result = run_cli("collisions", path, "--q", "slider=0.5")
    assert result.exit_code == 1, result.output
    assert "no self-collision among the geometry checked" in result.stdout
    assert "1 collision element(s) were left out" in result.stdout
    assert "robot.urdf:" in result.stdout and "missing.stl" in result.stdout
    clean = run_cli("collisions", write(tmp_path, two_boxes(0, 1)), "--q", "slider=0.5")
    assert clean.exit_code == 0 and "no self-collision" in clean.stdout


def test_srdf_poses_are_the_default_and_each_group_state(tmp_path):
    from lxml import etree

    from conftest import CASES

    path = tmp_path / "r.urdf"
    path.write_text((CASES / "U810_srdf_disabled_pair_collides" / "robot.urdf").read_text())
    root = etree.fromstring(
        '<robot name="r"><group_state name="hug" group="arms"><joint name="l_sho" value="0.7"/>'
        '<joint name="r_sho" value="-0.7"/><joint name="root_joint" value="0 0 0 0 0 0 1"/></group_state>'
        '<group_state name="odd" group="arms"><joint name="nope" value="1"/></group_state></robot>')
    robot = load(str(path))
    poses = srdf.named_poses(matrix.Scene(robot, 0.0), root)
    assert [label for label, _, _ in poses] == ["the default configuration", "group state 'hug' of 'arms'"]
    found = srdf.overlaps(robot, root)
    assert list(found) == [("l_hand", "r_hand")]
    assert found[("l_hand", "r_hand")].poses[0][0] == "group state 'hug' of 'arms'"
    assert found[("l_hand", "r_hand")].depth > 0.05


def test_pair_checks_work_in_slices_of_bounded_size(monkeypatch):
    # a 1,500-link robot has 1.1 million pairs: 250 samples of all of them at once were 2 GB
    from urdftool.collision import pairs

    robot = load(str(HUMANOID))
    whole = matrix.compute(robot, samples=500, seed=3, workers=1)
    sizes = []
    real = pairs.separated
    monkeypatch.setattr(pairs, "CHUNK", 1000)
    monkeypatch.setattr(pairs, "separated", lambda a, *rest: sizes.append(a.shape[0]) or real(a, *rest))
    sliced = matrix.compute(robot, samples=500, seed=3, workers=1)
    assert [(p.reason, p.collisions, p.min_distance) for p in sliced.pairs] == \
        [(p.reason, p.collisions, p.min_distance) for p in whole.pairs]
    assert sizes and max(sizes) <= 1000


@pytest.mark.parametrize("gap, reported", [(-0.0005, False), (-0.005, True), (0.01, False)])
def test_srdf_overlaps_leave_out_surfaces_that_only_touch(tmp_path, gap, reported):
    """Two 10 cm cubes, not adjacent, 10 cm + gap apart: half a millimetre of overlap is a
    seam (a lift resting on its base), 5 mm is a collision."""
    from lxml import etree

    text = ('<robot name="r"><link name="a"><collision><geometry><box size="0.1 0.1 0.1"/>'
            '</geometry></collision></link><link name="m"><collision><origin xyz="0 1 0"/>'
            '<geometry><sphere radius="0.01"/></geometry></collision></link>'
            '<link name="b"><collision><origin '
            f'xyz="{0.1 + gap} 0 0"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
            '</link><joint name="j1" type="revolute"><parent link="a"/><child link="m"/>'
            '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
            '<joint name="j2" type="revolute"><parent link="m"/><child link="b"/>'
            '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>')
    path = tmp_path / "r.urdf"
    path.write_text(text)
    found = srdf.overlaps(load(str(path)), etree.fromstring('<robot name="r"/>'))
    assert bool(found) == reported, found


def test_a_tally_without_distances_counts_the_same_collisions():
    scene = matrix.Scene(load(HUMANOID), 0.0)
    poses = scene.poses(scene.sample(3, 40))
    full, counted = scene.checker.tally(poses), scene.checker.tally(poses, distances=False)
    assert full.collisions.sum() > 0 and np.isfinite(full.min_distance).any()
    assert np.array_equal(full.collisions, counted.collisions)
    assert np.isinf(counted.min_distance[counted.collisions == 0]).all()


def test_check_tells_touching_meshes_at_the_srdf_poses_without_building_their_hulls(
        tmp_path, monkeypatch):
    """Parts exported to share a face, in contact at an SRDF pose: their contact is told by the
    least overlap along the axes and the centres' line from the meshes' vertices (at most
    0.5 mm here: touching, not reported), without qhull and a processed trimesh of each mesh
    for its hull; a contact deeper than that still gets its hulls' depth. (scipy itself is
    imported anyway: trimesh, which reads the meshes, imports scipy.spatial.)"""
    import trimesh
    from lxml import etree

    from urdftool.collision import pairs

    robot = robot_of(tmp_path, _mesh_boxes(tmp_path, trimesh.creation.box((0.1, 0.1, 0.1))))
    built = []
    original = pairs._convex
    monkeypatch.setattr(pairs, "_convex", lambda *mesh: built.append(1) or original(*mesh))

    def overlaps(slider: str):
        state = ('<group name="g"><joint name="slider"/></group><group_state name="s" '
                 f'group="g"><joint name="slider" value="{slider}"/></group_state>')
        found = srdf.overlaps(robot, etree.fromstring(f'<robot name="boxes">{state}</robot>'))
        return [(pair, round(overlap.depth, 6)) for pair, overlap in found.items()]

    assert overlaps("0.0995") == [] and built == []
    assert overlaps("0.05") == [(("fixed_box", "sliding_box"), 0.05)] and built


def test_a_planar_joint_is_one_joint_of_the_pose_not_three(tmp_path):
    """The header counted the values set: a robot of one planar and one prismatic joint was
    'at the given configuration (4 joints)'."""
    from urdftool.report.collisions import pose_text

    planar = ('<link name="deck"/><joint name="slide" type="planar"><parent link="base"/>'
              '<child link="deck"/><axis xyz="0 0 1"/></joint>')
    report = pose.check_pose(robot_of(tmp_path, two_boxes(0, 1, planar)), {"slide.x": "0.5"})
    assert len(report.q) == 4 and report.joints == 2
    stream = io.StringIO()
    pose_text("boxes", report, custom=True, stream=stream)
    assert "at the given configuration (2 joints)" in stream.getvalue()
