"""The posed scene: yourdfpy's scene graph, meshes only through urdftool's resolver."""

from __future__ import annotations

import re

import numpy as np
import pytest

from conftest import ROBOTS, load_text
from urdftool.description.load import load
from urdftool.errors import SceneError
from urdftool.kinematics.scene import posed, scene_model

ARM = """<robot name="arm">
  <material name="red"><color rgba="1 0 0 1"/></material>
  <link name="base"><visual><geometry><box size="0.2 0.2 0.1"/></geometry>
    <material name="red"/></visual></link>
  <link name="upper"><visual><origin xyz="0 0 0.25"/><geometry>
    <cylinder radius="0.05" length="0.5"/></geometry>
    <material name="blue"><color rgba="0 0 1 1"/></material></visual></link>
  <link name="finger"><visual><geometry><sphere radius="0.03"/></geometry></visual></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.05"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="wrist" type="revolute"><parent link="upper"/><child link="finger"/>
    <origin xyz="0 0 0.5"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/>
    <mimic joint="shoulder" multiplier="2"/></joint>
</robot>"""


def test_yourdfpy_poses_match_urdftool_fk():
    from urdftool.kinematics import configuration as config
    from urdftool.kinematics.fk import KinematicModel, forward_kinematics

    robot = load(ROBOTS / "humanoid" / "humanoid.urdf.xacro")
    model = KinematicModel(robot)
    chosen = config.random(model.variables, 1, seed=3)
    q = {v.name: float(x) for v, x in zip(model.variables, chosen.values[0])}
    scene = scene_model(robot).pose(q)
    fk = forward_kinematics(model, chosen)
    for link, pose in zip(fk.frames, fk.matrices[0]):
        np.testing.assert_allclose(scene.frames[link], pose, atol=1e-9)


def test_a_mimic_of_a_mimic_is_posed_as_urdftool_fk_poses_it(tmp_path):
    """yourdfpy follows one step of a mimic chain: a joint mimicking a mimic joint stayed at its
    offset (qb SoftHand's virtual joints in the sweep), in render, collisions --render and diff
    --render."""
    from urdftool.kinematics import configuration as config
    from urdftool.kinematics.fk import KinematicModel, forward_kinematics

    path = tmp_path / "chain.urdf"
    path.write_text(ARM.replace("</robot>", """  <link name="tip"><visual><geometry>
    <sphere radius="0.01"/></geometry></visual></link>
  <joint name="nail" type="revolute"><parent link="finger"/><child link="tip"/>
    <origin xyz="0 0 0.1"/><axis xyz="1 0 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/>
    <mimic joint="wrist" multiplier="-0.5" offset="0.1"/></joint>
</robot>"""))
    robot = load(path)
    model = KinematicModel(robot)
    chosen = config.from_words(model.variables, {"shoulder": "0.7"})
    fk = forward_kinematics(model, chosen)
    scene = scene_model(robot).pose({"shoulder": 0.7})
    for link, pose in zip(fk.frames, fk.matrices[0]):
        np.testing.assert_allclose(scene.frames[link], pose, atol=1e-9)


# a tilted planar base carrying an arm that carries an object on a floating joint
MULTIPLE = """<robot name="p">
  <link name="world"/>
  <link name="base"><visual><geometry><box size="0.2 0.1 0.1"/></geometry></visual></link>
  <link name="arm"><visual><geometry><box size="0.05 0.4 0.05"/></geometry></visual></link>
  <link name="obj"><visual><geometry><sphere radius="0.05"/></geometry></visual></link>
  <joint name="slide" type="planar"><parent link="world"/><child link="base"/>
    <origin xyz="0 0 0.1" rpy="0.3 0 0"/><axis xyz="0 0 1"/></joint>
  <joint name="elbow" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0.2 0 0"/><axis xyz="1 0 0"/>
    <limit lower="-2" upper="2" effort="10" velocity="1"/></joint>
  <joint name="free" type="floating"><parent link="arm"/><child link="obj"/>
    <origin xyz="0 0.4 0"/></joint>
</robot>"""


def test_planar_and_floating_joints_are_posed_as_urdftool_fk_poses_them(tmp_path):
    """yourdfpy counts a planar joint as 2 values and a floating one as 3: render drew both at
    their origin whatever --q said (``render --q slide.x=1``: the base at 0, exit 0). Posed
    by urdftool now, as fk poses them (fk: Pinocchio's, tests/kinematics/test_fk.py)."""
    from urdftool.kinematics import configuration as config
    from urdftool.kinematics.fk import KinematicModel, forward_kinematics

    path = tmp_path / "multiple.urdf"
    path.write_text(MULTIPLE)
    robot = load(path)
    model = KinematicModel(robot)
    chosen = config.random(model.variables, 1, seed=5)
    q = {v.name: float(x) for v, x in zip(model.variables, chosen.values[0])}
    assert abs(q["slide.x"]) > 0.01 and abs(q["free.roll"]) > 0.01
    scene = scene_model(robot).pose(q)
    fk = forward_kinematics(model, chosen)
    for link, pose in zip(fk.frames, fk.matrices[0]):
        np.testing.assert_allclose(scene.frames[link], pose, atol=1e-9)
    assert scene_model(robot).pose({}).frames["obj"][:3, 3] == pytest.approx(
        forward_kinematics(model, config.from_words(model.variables, {})).matrices[0, -1][:3, 3])


@pytest.mark.parametrize("written, unit", [("1e308 1e308 1e308", "1 1 1"), ("1e-320 0 0", "1 0 0"),
                                           ("0 0 1e-200", "0 0 1"), ("0 3 0", "0 1 0")])
def test_an_axis_is_posed_and_drawn_as_urdftool_fk_reads_it(tmp_path, written, unit):
    """yourdfpy rotated about the axis as written: a child on ``1e-320 0 0`` was posed at NaN
    (drawn nowhere; numpy's "invalid value" warnings from the picture), on ``1e308 1e308 1e308``
    it overflowed. Every axis is read by ``fk.unit_axis``: posed as its unit vector is."""
    import warnings

    def scene_of(axis: str):
        text = ARM.replace('<axis xyz="0 1 0"/>', f'<axis xyz="{axis}"/>', 1)
        return scene_model(load_text(tmp_path, text)).pose({"shoulder": 0.7})

    expected = scene_of(unit)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = scene_of(written)
    np.testing.assert_allclose(got.triangles, expected.triangles, atol=1e-12)
    [(_, _, direction), _] = got.axes
    norm = np.sqrt(sum(float(u) ** 2 for u in unit.split()))
    np.testing.assert_allclose(direction, [float(u) / norm for u in unit.split()], atol=1e-12)


def test_an_axis_with_no_direction_is_a_scene_error_at_its_joint(tmp_path):
    robot = load_text(tmp_path, ARM.replace('<axis xyz="0 1 0"/>', '<axis xyz="0 0 0"/>', 1))
    with pytest.raises(SceneError,
                       match="'shoulder': <axis xyz> '0 0 0' has no direction") as error:
        posed(robot)
    assert error.value.element is robot.joints["shoulder"]


@pytest.mark.parametrize("mimics, message, at", [
    (("jb", "ja"), "joint 'ja' has no value (a mimic cycle?)", "joint"),
    (("jaa", None), "joint 'ja' mimics unknown joint 'jaa'", "mimic"),  # (where fk says it)
])
def test_a_moving_joint_without_a_value_is_a_scene_error_at_the_joint(tmp_path, mimics,
                                                                      message, at):
    """A mimic cycle, or a mimic of a joint that does not exist, leaves a moving joint without
    a value: fk refuses it at the joint; the scene was drawn with yourdfpy's 0 (render exit 0)."""
    joints = "".join(
        f'<joint name="{name}" type="revolute"><parent link="base"/><child link="{child}"/>'
        f'<limit lower="-1" upper="1" effort="1" velocity="1"/>'
        + (f'<mimic joint="{leader}"/>' if leader else "") + "</joint>"
        for name, child, leader in (("ja", "a", mimics[0]), ("jb", "b", mimics[1])))
    box = '<visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>'
    robot = load_text(tmp_path, f'<robot name="r"><link name="base"/><link name="a">{box}'
                                f'</link><link name="b">{box}</link>{joints}</robot>')
    with pytest.raises(SceneError, match=re.escape(message)) as error:
        scene_model(robot)
    joint = robot.joints["ja"]
    assert error.value.element is (joint if at == "joint" else joint.find("mimic"))


@pytest.mark.parametrize("shape, xyz", [('<box size="1e300 1 1"/>', "0 0 0"),
                                       ('<sphere radius="1e200"/>', "0 0 0"),
                                       ('<cylinder radius="1" length="1e300"/>', "0 0 0"),
                                       ('<mesh filename="t.stl" scale="1e30 1 1"/>', "0 0 0"),
                                       ('<sphere radius="0.03"/>', "1e300 0 0")])
@pytest.mark.parametrize("collision", [False, True])
def test_a_part_past_the_farthest_coordinate_is_not_drawn_and_said(tmp_path, shape, xyz,
                                                                   collision):
    """trimesh's primitive of a box 1e300 long overflowed, a sphere of radius 1e200 had NaN
    corners (numpy's warnings, the picture's casts of NaN): a part reaching past
    MAX_COORDINATE is left out with a note (transforms.too_far, collisions' bound too)."""
    import warnings

    (tmp_path / "t.stl").write_text(
        "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
        "endloop\nendfacet\nendsolid t\n")
    far = f'<origin xyz="{xyz}"/><geometry>{shape}</geometry>'
    text = ARM.replace('<link name="finger"><visual><geometry><sphere radius="0.03"/></geometry>'
                       '</visual></link>', f'<link name="finger"><visual>{far}</visual>'
                       f'<collision>{far}</collision></link>')
    assert text != ARM
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        scene, _ = posed(load_text(tmp_path, text), collision=collision)
    [note] = [p for p in scene.problems if "finger" in p]
    assert "past the 4.612e+10 m" in note and note.endswith("not drawn")
    assert "finger" not in scene.links and np.isfinite(scene.triangles).all()


def test_triangles_are_posed_coloured_and_owned(tmp_path):
    robot = load_text(tmp_path, ARM)
    scene, warnings = posed(robot, {"shoulder": "90"}, degrees=True)
    assert warnings == [] and scene.problems == []
    assert scene.links == ["base", "upper", "finger"]
    upper = scene.triangles[scene.owners == 1].reshape(-1, 3)
    # the cylinder turned about y by 90 degrees lies along +x, from 0 to 0.5 m
    assert upper[:, 0].max() == pytest.approx(0.5) and upper[:, 2].max() == pytest.approx(0.1)
    np.testing.assert_allclose(scene.colours[scene.owners == 0][0], (1, 0, 0))  # named
    np.testing.assert_allclose(scene.colours[scene.owners == 1][0], (0, 0, 1))  # inline
    # the finger at the cylinder's tip, turned 90 + 2 * 90 degrees about y (the mimic wrist)
    assert scene.frames["finger"][:3, 3] == pytest.approx([0.5, 0, 0.05])
    np.testing.assert_allclose(scene.frames["finger"][:3, :3],
                               [[0, 0, -1], [0, 1, 0], [1, 0, 0]], atol=1e-9)
    assert [name for name, _, _ in scene.axes] == ["shoulder", "wrist"]


MESH = """<robot name="m"><link name="a"><visual><geometry>
  <mesh filename="{uri}" scale="2 2 2"/></geometry></visual></link></robot>"""


def _stl(path):
    import trimesh

    trimesh.creation.box(extents=(0.1, 0.1, 0.1)).export(path)


def test_meshes_load_through_urdftools_resolver(tmp_path):
    _stl(tmp_path / "box.stl")
    scene, _ = posed(load_text(tmp_path, MESH.format(uri="box.stl")))
    assert len(scene.triangles) == 12
    assert scene.triangles.reshape(-1, 3).max() == pytest.approx(0.1)  # scaled 2x


def test_a_mesh_outside_the_repository_is_not_opened(tmp_path):
    outside = tmp_path / "outside.stl"
    _stl(outside)
    inner = tmp_path / "repo"
    inner.mkdir()
    robot = load_text(inner, MESH.format(uri=f"file://{outside}"))
    scene, _ = posed(robot)
    assert len(scene.triangles) == 0
    assert "outside" in scene.problems[0] and "not drawn" in scene.problems[0]
    # yourdfpy's own filename handler is urdftool's resolver: nothing outside resolves
    assert scene_model(robot).urdf._filename_handler(f"file://{outside}") == ""


def test_what_yourdfpy_cannot_read_is_a_scene_error(tmp_path):
    robot = load_text(tmp_path, '<robot name="r"><link name="a"><visual><geometry/>'
                                 '</visual></link></robot>')
    with pytest.raises(SceneError, match="yourdfpy cannot build the scene"):
        posed(robot)


@pytest.mark.parametrize("scale", ["1 1 1", "-1 1 1"])
def test_closed_surfaces_know_which_way_they_face(tmp_path, scale):
    _stl(tmp_path / "box.stl")
    text = MESH.format(uri="box.stl").replace('scale="2 2 2"', f'scale="{scale}"')
    scene, _ = posed(load_text(tmp_path, text))
    assert set(scene.facing.tolist()) <= {-1, 1} and len(set(scene.facing.tolist())) == 1
    normals = np.cross(scene.triangles[:, 1] - scene.triangles[:, 0],
                       scene.triangles[:, 2] - scene.triangles[:, 0])
    outward = scene.triangles.mean(axis=1) - scene.triangles.reshape(-1, 3).mean(axis=0)
    assert np.all(np.einsum("ij,ij->i", normals * scene.facing[:, None], outward) > 0)


def test_an_open_surface_faces_nowhere(tmp_path):
    import trimesh

    trimesh.Trimesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]]).export(tmp_path / "tri.stl")
    scene, _ = posed(load_text(tmp_path, MESH.format(uri="tri.stl")))
    assert scene.facing.tolist() == [0]


def test_a_missing_attribute_yourdfpy_needs_is_named(tmp_path):
    robot = load_text(tmp_path, '<robot name="r"><link name="a"/><link name="b"/><joint '
                      'type="fixed"><parent link="a"/><child link="b"/></joint></robot>')
    with pytest.raises(SceneError, match="an element lacks its 'name' attribute"):
        posed(robot)


def test_a_link_without_a_name_is_urdfdoms_empty_link_and_the_loop_beside_the_tree_left_out(
        tmp_path):
    """An only ``<link>`` without a name is urdfdom's link '' with nothing in it (yourdfpy
    refused it: "an element lacks its 'name' attribute"); a loop beside the tree is dropped
    as urdfdom drops it (trimesh's scene graph went round it: "Iteration limit exceeded!")."""
    box = '<visual><geometry><box size="1 1 1"/></geometry></visual>'
    scene, _ = posed(load_text(tmp_path, f'<robot name="r"><link>{box}</link></robot>'))
    assert len(scene.triangles) == 0
    scene, _ = posed(load_text(tmp_path, (
        f'<robot name="r"><link name="r">{box}</link><link name="a">{box}</link><link '
        f'name="b">{box}</link><joint name="j1" type="fixed"><parent link="a"/><child '
        'link="b"/></joint><joint name="j2" type="fixed"><parent link="b"/><child link="a"/>'
        '</joint></robot>')))
    assert scene.links == ["r"]


def test_a_long_chain_is_posed_without_walking_each_links_path_from_the_base(tmp_path,
                                                                             monkeypatch):
    """trimesh's graph.get walks the path from the base for each node: a 3,000-link chain
    took minutes to render (quadratic; U015 at the budget). Each frame is composed once from
    its parent's, and equals what the walk gives."""
    from trimesh.scene.transforms import EnforcedForest

    links = "".join(f'<link name="l{i}"><visual><origin xyz="0 0 0.05"/><geometry>'
                    f'<box size="0.1 0.1 0.1"/></geometry></visual></link>' for i in range(60))
    joints = "".join(f'<joint name="j{i}" type="revolute"><parent link="l{i}"/>'
                     f'<child link="l{i + 1}"/><origin xyz="0 0.1 0.1" rpy="0.1 0.2 0.3"/>'
                     f'<axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/>'
                     f'</joint>' for i in range(59))
    model = scene_model(load_text(tmp_path, f'<robot name="chain">{links}{joints}</robot>'))
    q = {f"j{i}": 0.01 * i for i in range(59)}
    walked = model.pose(q)  # the reference: every frame through trimesh's own walk
    expected = {name: model.scene.graph.get(name)[0] for name in walked.frames}

    def no_walk(*args, **kwargs):
        raise AssertionError("a path walked from the base")

    monkeypatch.setattr(EnforcedForest, "shortest_path", no_walk)
    model.scene.graph._cache.clear()
    again = model.pose(q)
    for name, pose in again.frames.items():
        np.testing.assert_allclose(pose, expected[name], atol=1e-12)
    np.testing.assert_allclose(again.triangles, walked.triangles, atol=1e-12)


@pytest.mark.parametrize("collision", [False, True])
def test_a_scene_of_many_primitives_is_built_without_hashing_the_graph_per_link(
        tmp_path, monkeypatch, collision):
    """yourdfpy's scene asks trimesh's ``graph.nodes`` once per link, which trimesh computes
    again from a hash of the whole graph after each update: 4,000 links of a box and a sphere
    took 44 s where 1,000 took 2 (quadratic). The scene is built with a hash or two, is the
    one yourdfpy built (nodes, geometry per link, one concatenated per link for collision),
    and a geometry named as another, or as a link, gets a name of its own."""
    from trimesh.scene.transforms import SceneGraph

    shapes = ('<{kind} name="shape"><geometry><box size="0.01 0.02 0.03"/></geometry></{kind}>'
              '<{kind} name="l3"><origin xyz="0 0 0.1"/><geometry><sphere radius="0.01"/>'
              '</geometry></{kind}>').format(kind="collision" if collision else "visual")
    links = "".join(f'<link name="l{i}">{shapes}</link>' for i in range(200))
    joints = "".join(f'<joint name="j{i}" type="fixed"><parent link="l0"/>'
                     f'<child link="l{i}"/><origin xyz="0.01 0 0"/></joint>'
                     for i in range(1, 199))  # l199 joined to nothing: hung from the base
    hashed: dict = {}  # graph -> its hashes (each primitive comes as a scene of its own)
    original = SceneGraph.__hash__
    monkeypatch.setattr(SceneGraph, "__hash__", lambda self: hashed.update(
        {id(self): hashed.get(id(self), 0) + 1}) or original(self))
    robot = load_text(tmp_path, f'<robot name="many">{links}{joints}</robot>')
    model = scene_model(robot, collision)
    assert max(hashed.values()) < 20
    posed_scene = model.pose({}, None)
    assert len(posed_scene.triangles) == 200 * (12 + 1280)
    assert set(posed_scene.links) == {f"l{i}" for i in range(200)}
    nodes = model.scene.graph.nodes_geometry
    assert len(nodes) == (200 if collision else 400) and "l3" not in nodes
    np.testing.assert_allclose(posed_scene.frames["l5"][:3, 3], [0.01, 0, 0])
    np.testing.assert_allclose(posed_scene.frames["l199"], np.eye(4))


@pytest.mark.parametrize("collision", [False, True])
@pytest.mark.parametrize("name", ["humanoid/humanoid.urdf.xacro", "r2d2/r2d2.urdf.xacro",
                                  "diffbot/diffbot.urdf.xacro"])
def test_the_scene_graph_is_the_one_yourdfpy_builds(name, collision):
    """yourdfpy is the oracle of :func:`_scene_graph` (urdftool builds the same scene in time
    linear in the links): each geometry hangs from the same link, with the same triangles and
    the same place in the robot's frame."""
    import yourdfpy

    from urdftool.kinematics.scene import _contained, _yourdfpy

    robot = load(ROBOTS / name)
    ours = _yourdfpy(robot, collision)
    theirs = yourdfpy.URDF(ours.robot, build_scene_graph=not collision,
                           build_collision_scene_graph=collision, load_meshes=False,
                           load_collision_meshes=False,
                           filename_handler=lambda fname: _contained(robot, fname))

    def drawn(scene):
        found = []
        for node in scene.graph.nodes_geometry:
            transform, geometry = scene.graph.get(node)
            found.append((scene.graph.transforms.parents[node],
                          len(scene.geometry[geometry].faces),
                          tuple(np.round(transform, 9).ravel())))
        return sorted(found)

    scenes = (ours.collision_scene, theirs.collision_scene) if collision else \
        (ours.scene, theirs.scene)
    assert drawn(scenes[0]) == drawn(scenes[1]) != []
