"""How far a link's geometry reaches (physics/support.py), against independent derivations:
dense samples of each shape's surface, closed forms, and the distance to a box computed by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest

from conftest import load_text
from urdftool.kinematics.transforms import rotation_from_rpy
from urdftool.physics.frames import joint_frames, link_frames
from urdftool.physics.support import DIRECTIONS, link_reach

SHAPES = {
    "box": '<box size="0.3 0.1 0.05"/>',
    "cylinder": '<cylinder radius="0.07" length="0.2"/>',
    "sphere": '<sphere radius="0.04"/>',
}
RPY = (0.3, -0.7, 1.1)
XYZ = (0.05, -0.02, 0.1)


def _robot(tmp_path, shape: str, extra: str = ""):
    return load_text(tmp_path, f"""<robot name="r"><link name="a">
      <collision><origin xyz="{' '.join(map(str, XYZ))}" rpy="{' '.join(map(str, RPY))}"/>
      <geometry>{shape}</geometry></collision>{extra}</link></robot>""")


def _surface(kind: str, n: int = 400) -> np.ndarray:
    """Dense points on a shape's surface in its own frame (its support is their maximum, up to
    the sampling)."""
    rng = np.random.default_rng(0)
    if kind == "box":
        half = np.array([0.15, 0.05, 0.025])
        grid = np.array(np.meshgrid(*[np.linspace(-1, 1, 21)] * 3)).reshape(3, -1).T
        return grid * half
    if kind == "cylinder":
        angles = np.linspace(0, 2 * np.pi, n, endpoint=False)
        rim = np.stack([0.07 * np.cos(angles), 0.07 * np.sin(angles)], -1)
        return np.vstack([np.column_stack([rim, np.full(n, z)]) for z in (-0.1, 0.1)])
    points = rng.normal(size=(20000, 3))
    return 0.04 * points / np.linalg.norm(points, axis=1, keepdims=True)


@pytest.mark.parametrize("kind", SHAPES)
def test_support_is_the_largest_projection(tmp_path, kind):
    robot = _robot(tmp_path, SHAPES[kind])
    reach = link_reach(robot, robot.links["a"], ("collision",))
    placed = _surface(kind) @ rotation_from_rpy(np.array(RPY)).T + np.array(XYZ)
    for d in DIRECTIONS[::7]:
        sampled = float((placed @ np.array(d)).max())
        assert reach.support(d) >= sampled - 1e-12
        assert reach.support(d) <= sampled + (2e-3 if kind == "sphere" else 1e-4)
    p = (0.3, 0.2, -0.1)
    distances = np.linalg.norm(placed - np.array(p), axis=1)
    assert reach.farthest(p) >= distances.max() - 1e-12
    assert reach.farthest(p) <= distances.max() + 1e-3


def test_lowest_point_of_a_tilted_cylinder_is_the_closed_form(tmp_path):
    # a cylinder's lowest point: centre - h |u_z| - r sqrt(1 - u_z^2), u its axis
    robot = _robot(tmp_path, SHAPES["cylinder"])
    u = rotation_from_rpy(np.array(RPY))[:, 2]
    expected = XYZ[2] - 0.1 * abs(u[2]) - 0.07 * math.sqrt(1 - u[2] ** 2)
    reach = link_reach(robot, robot.links["a"], ("collision",))
    assert math.isclose(reach.lowest(), expected, rel_tol=0, abs_tol=1e-15)


def test_distance_outside_a_box_is_a_lower_bound_and_close(tmp_path):
    robot = load_text(tmp_path, """<robot name="r"><link name="a"><collision>
      <geometry><box size="0.2 0.2 0.2"/></geometry></collision></link></robot>""")
    reach = link_reach(robot, robot.links["a"], ("collision",))
    for p in [(0.3, 0.0, 0.0), (0.3, 0.3, 0.0), (0.25, 0.4, -0.3), (0.0, 0.0, 0.05)]:
        outside = np.maximum(np.abs(p) - 0.1, 0.0)
        exact = float(np.linalg.norm(outside))  # the distance to the box, by hand
        found = reach.outside(p)
        assert found <= exact + 1e-12
        assert found >= 0.97 * exact  # 134 directions and the one towards the point


def test_a_mesh_reaches_as_far_as_its_vertices_open_or_not(tmp_path):
    (tmp_path / "lid.obj").write_text("v 0 0 0\nv 0.2 0 0\nv 0 0.1 0\nv 0 0 0.3\nf 1 2 3\nf 1 2 4\n")
    robot = load_text(tmp_path, """<robot name="r"><link name="a"><visual>
      <origin xyz="0 0 1"/><geometry><mesh filename="lid.obj"/></geometry></visual></link>
      </robot>""")
    reach = link_reach(robot, robot.links["a"])
    assert reach.complete
    assert math.isclose(reach.support((0, 0, 1)), 1.3)
    assert math.isclose(reach.lowest(), 1.0)
    assert math.isclose(reach.farthest((0, 0, 1)), 0.3)


def test_missing_geometry_leaves_the_reach_incomplete(tmp_path):
    robot = load_text(tmp_path, """<robot name="r"><link name="a">
      <visual><geometry><mesh filename="missing.stl"/></geometry></visual>
      <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
      <collision><geometry><cone radius="1"/></geometry></collision></link></robot>""")
    reach = link_reach(robot, robot.links["a"])
    assert not reach.complete
    assert len(reach.missing) == 2 and len(reach.pieces) == 1


def test_rigid_reach_and_zero_pose_frames(tmp_path):
    robot = load_text(tmp_path, """<robot name="r">
      <link name="a"/><link name="b"><collision><geometry><sphere radius="0.1"/></geometry>
      </collision></link><link name="c"/>
      <joint name="ab" type="fixed"><parent link="a"/><child link="b"/>
        <origin xyz="0 0 0.5" rpy="0 0 1.5707963267948966"/></joint>
      <joint name="bc" type="revolute"><parent link="b"/><child link="c"/>
        <origin xyz="1 0 0"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1"
        velocity="1"/></joint></robot>""")
    reach = link_reach(robot, robot.links["a"], rigid=True)
    assert reach.links == ["a", "b"]
    assert math.isclose(reach.support((0, 0, 1)), 0.6)
    frames = link_frames(robot)
    np.testing.assert_allclose(frames["c"][0], (0, 1, 0.5), atol=1e-12)  # b is turned 90 deg
    assert joint_frames(robot)["bc"] == frames["c"]


def test_a_mesh_piece_keeps_only_its_hull_vertices_and_answers_the_same():
    """Support and farthest point are reached at a vertex of the convex hull: a mesh piece
    keeps only those (U312 asks 134 directions per link of every reach holding the mesh)."""
    import numpy as np

    from urdftool.description.mesh_arrays import extreme_points as _extreme_points
    from urdftool.physics.support import Piece

    rng = np.random.default_rng(3)
    cloud = rng.normal(size=(5000, 3))
    kept = _extreme_points(cloud)
    assert len(kept) < len(cloud) / 10
    whole = Piece("mesh", (0.0, 0.0, 0.0), ((1, 0, 0), (0, 1, 0), (0, 0, 1)), vertices=cloud)
    hull = Piece("mesh", (0.0, 0.0, 0.0), ((1, 0, 0), (0, 1, 0), (0, 0, 1)), vertices=kept)
    for d in rng.normal(size=(50, 3)):
        assert hull.support(tuple(d)) == whole.support(tuple(d))
    for p in rng.normal(size=(20, 3)) * 3:
        assert hull.farthest(tuple(p)) == whole.farthest(tuple(p))
    flat = np.c_[rng.normal(size=(200, 2)), np.zeros(200)]  # qhull refuses: all kept
    assert len(_extreme_points(flat)) == 200


def _pieces(tmp_path, mesh: bool):
    """A link's reach of a turned box, cylinder and sphere (and an open mesh)."""
    from benchmarks.generate import _sphere_stl

    (tmp_path / "open.stl").write_bytes(_sphere_stl(0.05, 16, 24, open_top=True))
    extra = ('<visual><origin xyz="0.1 0.2 -0.1" rpy="1 0.5 0.2"/><geometry><mesh '
             'filename="open.stl" scale="1 2 0.5"/></geometry></visual>') if mesh else ""
    parts = "".join(f'<collision><origin xyz="{0.1 * i} {-0.05 * i} {0.02 * i}" '
                    f'rpy="{0.3 * i} {-0.7 + i} {1.1 * i}"/><geometry>{shape}</geometry>'
                    '</collision>' for i, shape in enumerate(SHAPES.values()))
    robot = load_text(tmp_path, f'<robot name="r"><link name="a">{parts}{extra}</link></robot>')
    return link_reach(robot, robot.links["a"])


@pytest.mark.parametrize("mesh", [False, True])
def test_the_table_answers_as_the_pieces_do(tmp_path, mesh):
    """_Table (every piece as arrays, every direction at once) against each Piece's own
    closed form: support, farthest point, holds, and outside (by the pieces, direction by
    direction, as Reach.outside asked before)."""
    from urdftool.physics.support import _Table

    reach = _pieces(tmp_path, mesh)
    table = _Table(reach.pieces)
    rng = np.random.default_rng(5)
    directions = rng.normal(size=(3, 40))
    np.testing.assert_allclose(table.support(directions),
                               [reach.support(tuple(d)) for d in directions.T], atol=1e-12)
    for p in rng.normal(size=(60, 3)) * 0.2:
        p = tuple(p)
        assert table.farthest(p) == pytest.approx(reach.farthest(p), abs=1e-12)
        assert table.holds(np.asarray(p)) == any(piece.holds(p) for piece in reach.pieces)
        if any(piece.holds(p) for piece in reach.pieces):
            expected = 0.0
        else:
            centre = [(reach.support(a) - reach.support(tuple(-v for v in a))) / 2
                      for a in np.eye(3)]
            towards = np.asarray(p) - centre
            extra = (tuple(towards / np.linalg.norm(towards)),)
            expected = max(float(np.dot(d, p)) - reach.support(d) for d in DIRECTIONS + extra)
        found = expected
        if table.within(np.asarray(p)):  # found inside the hull from a few points: 0
            assert expected <= 0
            found = 0.0
        assert table.outside(p) == pytest.approx(found, abs=1e-12)
        # the reach asks the table only with a mesh among its pieces
        assert reach.outside(p) == pytest.approx(found if mesh else expected, abs=1e-12)


def test_a_large_rigid_body_seen_from_a_member_reaches_as_its_own_walk(tmp_path, monkeypatch):
    """The reach of a member of a body of more than GROUP_DIRECT links (placed once in the
    root's frame, questions turned into it) against the member's own walk of the body."""
    from benchmarks.generate import _sphere_stl
    from conftest import rigid_body_robot
    from urdftool.physics import solids

    (tmp_path / "open.stl").write_bytes(_sphere_stl(0.05, 8, 12, open_top=True))
    text = rigid_body_robot(30, mesh='<mesh filename="open.stl" scale="1 0.5 2"/>')
    robot = load_text(tmp_path, text)
    monkeypatch.setattr(solids, "GROUP_DIRECT", 10 ** 6)
    (tmp_path / "w").mkdir()
    (tmp_path / "w" / "open.stl").write_bytes((tmp_path / "open.stl").read_bytes())
    walked = load_text(tmp_path / "w", text)
    expected = {name: link_reach(walked, walked.links[name], rigid=True)
                for name in ("l0", "l7", "l29")}
    monkeypatch.undo()
    rng = np.random.default_rng(2)
    for name, theirs in expected.items():
        mine = link_reach(robot, robot.links[name], rigid=True)
        assert type(mine).__name__ == "_Body" and mine.links == theirs.links
        assert mine.complete and theirs.complete
        for d in rng.normal(size=(20, 3)):
            assert mine.support(tuple(d)) == pytest.approx(theirs.support(tuple(d)), abs=1e-9)
        for p in rng.normal(size=(20, 3)) * 3:
            p = tuple(p)
            assert mine.farthest(p) == pytest.approx(theirs.farthest(p), abs=1e-9)
            assert mine.outside(p) == pytest.approx(theirs.outside(p), abs=1e-9)
        assert mine.lowest() == pytest.approx(theirs.lowest(), abs=1e-9)


def test_a_link_nothing_is_fixed_to_has_one_reach_for_its_body_and_itself(tmp_path):
    """Its rigid body is itself: the reach (and its table of every direction) is built once,
    not once per question."""
    _pieces(tmp_path, mesh=True)  # writes robot.urdf: link 'a', alone
    robot = load_text(tmp_path, (tmp_path / "robot.urdf").read_text())
    link = robot.links["a"]
    assert link_reach(robot, link, rigid=True) is link_reach(robot, link)
    assert link_reach(robot, link).links == ["a"]


def test_a_point_found_inside_from_a_few_points_is_inside_the_hull(tmp_path):
    """_Inside (no mesh vertex placed, no qhull): every point it finds inside a reach's pieces
    is inside the hull of the pieces (below their support in each of 4,000 directions: the
    pieces' closed forms and every mesh vertex), and most points well inside are found so."""
    from urdftool.physics.support import _Table

    reach = _pieces(tmp_path, mesh=True)
    table = _Table(reach.pieces)
    rng = np.random.default_rng(8)
    directions = rng.normal(size=(3, 4000))
    directions /= np.linalg.norm(directions, axis=0)
    heights = table.support(directions)
    samples = rng.normal(size=(2000, 3)) * 0.15 + table.points.mean(axis=0)
    found = np.array([table.within(p) for p in samples])
    margins = samples @ directions - heights  # > 0: beyond the geometry in that direction
    assert (margins[found] <= 1e-12).all()
    assert not found[(margins > 1e-9).any(axis=1)].any()
    deep = (margins < -0.02).all(axis=1)
    assert deep.sum() > 50 and found[deep].mean() > 0.8


def test_a_mesh_piece_places_its_vertices_only_when_asked_exactly(tmp_path):
    """A centre of mass found inside the hull from the mesh's few inner points: no vertex is
    placed (and no hull built); the support then places them all, and answers as qhull's
    hull vertices do."""
    scipy_spatial = pytest.importorskip("scipy.spatial")
    reach = _pieces(tmp_path, mesh=True)
    mesh = next(piece for piece in reach.pieces if piece.kind == "mesh")
    assert mesh.vertices is None and mesh.mesh is not None and mesh.inner is None
    assert len(mesh.inner_placed()) <= 26  # its few inner points, placed when asked
    centre = tuple(mesh.inner.mean(axis=0))
    assert reach.outside(centre) == 0.0 and mesh.vertices is None
    height = mesh.support((0.3, -0.2, 0.9))
    placed = mesh.vertices
    kept = placed[scipy_spatial.ConvexHull(placed).vertices]
    assert height == float((kept @ (0.3, -0.2, 0.9)).max())


def test_a_point_inside_one_mesh_far_from_the_reachs_middle_is_found_inside(tmp_path):
    """A small mesh two metres from a large one: points inside the small one, which the
    reach's own star (about a middle near the large one) leaves to every vertex, are found
    inside by the mesh's star (in its frame, made once per run); none found inside is beyond
    the geometry."""
    from benchmarks.generate import _sphere_stl
    from urdftool.physics.support import _Table

    (tmp_path / "ball.stl").write_bytes(_sphere_stl(0.05, 12, 16, open_top=False))
    parts = "".join(f'<visual><origin xyz="{x} 0 0" rpy="0.3 0.2 {x}"/><geometry><mesh '
                    f'filename="ball.stl" scale="{k} {k} {k}"/></geometry></visual>'
                    for x, k in ((0, 1), (2, 10)))
    robot = load_text(tmp_path, f'<robot name="r"><link name="a">{parts}</link></robot>')
    table = _Table(link_reach(robot, robot.links["a"]).pieces)
    rng = np.random.default_rng(4)
    small = table.points[:len(table._pieces[0].placed())]  # the first mesh's vertices
    samples = rng.normal(size=(400, 3)) * 0.03 + small.mean(axis=0)
    directions = rng.normal(size=(3, 2000))
    directions /= np.linalg.norm(directions, axis=0)
    margins = samples @ directions - table.support(directions)
    found = np.array([table.within(p) for p in samples])
    by_reach = np.array([table._inside.star.holds(p) for p in samples])
    assert (margins[found] <= 1e-12).all()
    assert (found & ~by_reach).sum() > 20  # the mesh's own star finds what the reach's misses


def _balls(tmp_path, count: int):
    """A link of ``count`` closed ball meshes 0.5 m apart along x, each turned its own way
    (each standing on its origin: its centre 5 cm up its own z axis)."""
    from benchmarks.generate import _sphere_stl

    (tmp_path / "ball.stl").write_bytes(_sphere_stl(0.05, 12, 16, open_top=False))
    parts = "".join(f'<visual><origin xyz="{0.5 * i} 0 0" rpy="0.3 {0.2 * i} 0.1"/><geometry>'
                    '<mesh filename="ball.stl"/></geometry></visual>' for i in range(count))
    robot = load_text(tmp_path, f'<robot name="r"><link name="a">{parts}</link></robot>')
    return link_reach(robot, robot.links["a"])


def _centre(piece, off=(0.0, 0.0, 0.0)):
    """The centre of a ball of :func:`_balls` in the reach's frame (moved by ``off`` in the
    ball's frame)."""
    return np.asarray(piece.centre) + np.asarray(piece.rotation) @ np.add((0.0, 0.0, 0.05), off)


def test_a_point_inside_its_own_mesh_makes_no_star_of_the_reach(tmp_path):
    """A centre of mass inside one of a reach's first meshes is found inside by that mesh's
    star (made once per run), and the reach makes no star of its own points for it."""
    from urdftool.physics.support import _Table

    table = _Table(_balls(tmp_path, 2).pieces)
    assert table.within(_centre(table._pieces[1], (0.01, 0.02, -0.015)))  # in the 2nd ball
    assert table._inside._star is None


def test_a_body_of_many_meshes_asks_at_most_a_few_own_stars_before_its_own(tmp_path,
                                                                          monkeypatch):
    """Between the balls (inside the reach's hull, in no ball): the first OWN_STARS_FIRST
    meshes' stars are asked, then the reach's star finds it; the other meshes' are not."""
    from urdftool.physics import support

    table = support._Table(_balls(tmp_path, 8).pieces)
    asked = []
    real = support._mesh_star
    monkeypatch.setattr(support, "_mesh_star", lambda mesh: asked.append(mesh) or real(mesh))
    assert table.within((_centre(table._pieces[2]) + _centre(table._pieces[3])) / 2)
    assert len(asked) == support.OWN_STARS_FIRST and table._inside._star is not None


def _margin(extent: float) -> float:
    return max(0.2 * extent, 0.01)


def test_a_point_near_the_hull_is_judged_by_its_few_points_without_placing_a_vertex(tmp_path):
    """Just outside a ball (outside its star, so not found inside), within the margin the
    caller names for geometry that large: 0 from the star's points alone, no vertex placed
    and the mesh not merged; beyond it, the exact distance from every vertex."""
    reach = _balls(tmp_path, 1)
    piece = reach.pieces[0]
    near = _centre(piece, (0.053, 0.0, 0.0))  # 3 mm outside the ball
    assert reach.outside(near, beyond=_margin) == 0.0
    assert piece.vertices is None and piece.mesh._merge is not None
    far = _centre(piece, (0.09, 0.0, 0.0))  # 4 cm out: beyond a fifth of its 10 cm
    assert reach.outside(far, beyond=_margin) == pytest.approx(0.04, abs=2e-3)
    assert piece.vertices is not None


def test_what_is_found_near_from_a_few_points_is_within_the_margin_of_every_vertex(tmp_path):
    """Points all round a reach of meshes and primitives: every one judged near (0) has an
    exact distance (every vertex and closed form, as before) within the margin of the
    reach's largest extent; most points near the hull but outside its stars are judged so."""
    from urdftool.physics.support import _Table

    reach = _pieces(tmp_path, mesh=True)
    rng = np.random.default_rng(11)
    extent = max(reach.support(a) + reach.support(tuple(-v for v in a)) for a in np.eye(3))
    samples = rng.normal(size=(600, 3)) * 0.25
    judged = 0
    for p in samples:
        fast = _Table(reach.pieces).outside(p, beyond=_margin)
        exact = _Table(reach.pieces).outside(p)
        if fast == 0.0 and exact > 0.0:
            judged += 1
            assert exact <= _margin(extent)
        elif exact > 0.0:
            assert fast == exact
    assert judged > 50, judged


def test_the_highest_products_asked_by_blocks_are_the_whole_products():
    """support.highest asks a mesh's vertices a block of rows at a time: the same numbers as
    the whole product's largest (NaN carried, zeros' signs too), on counts around the block
    size and awkward coordinates."""
    from urdftool.physics.support import HIGHEST_ROWS, _columns, highest

    rng = np.random.default_rng(34)
    directions = np.hstack([_columns()[0], rng.normal(size=(3, 1))])
    for trial in range(60):
        n = int(rng.choice([1, HIGHEST_ROWS - 1, HIGHEST_ROWS, HIGHEST_ROWS + 1,
                            3 * HIGHEST_ROWS + 17, int(rng.integers(2, 5000))]))
        points = rng.normal(size=(n, 3)) * 10.0 ** rng.integers(-8, 8, size=(n, 3))
        if trial % 4 == 1:
            points[rng.integers(0, n, size=3)] = rng.choice([0.0, -0.0, 1e308, -1e308], size=3)
        if trial % 4 == 2:
            points[rng.integers(0, n)] = [np.nan, np.inf, -np.inf][trial % 3]
        if trial % 4 == 3:  # the largest in a late block only
            points[-1] = 1e6
        with np.errstate(all="ignore"):
            whole = (points @ directions).max(axis=0)
            found = highest(points, directions)
        assert np.array_equal(found, whole, equal_nan=True), trial
        assert np.array_equal(np.signbit(found), np.signbit(whole)), trial


def test_outside_asks_every_point_in_a_few_directions_and_finds_the_same_number(
        tmp_path, monkeypatch):
    """Beyond its stars, a point's distance from a reach with meshes is the largest d . p -
    h(d) over every direction (every vertex asked in all 136, as before): the same number to
    the bit when the vertices are asked only in the directions whose bound from the stars'
    points can still be the largest, and most points ask far fewer than all."""
    from urdftool.physics import support

    asked = []
    pruned = support._Table._lifted_less
    monkeypatch.setattr(support._Table, "_lifted_less", staticmethod(
        lambda lifted, rounded, directions, chosen, points:
        asked.append(len(chosen)) or pruned(lifted, rounded, directions, chosen, points)))
    rng = np.random.default_rng(21)
    for reach in (_pieces(tmp_path, mesh=True), _balls(tmp_path, 3)):
        table = support._Table(reach.pieces)
        assert len(table.points) > support._PRUNED_BELOW
        middle = table.points.mean(axis=0)
        for p in middle + rng.normal(size=(150, 3)) * rng.choice([0.05, 0.2, 1.0, 30.0], (150, 1)):
            every, six, _ = support._columns()
            heights = table.support(six)
            towards = p - (heights[:3] - heights[3:]) / 2
            directions = np.hstack([every, (towards / np.linalg.norm(towards)).reshape(3, 1)])
            expected = float((p @ directions - table.support(directions)).max())
            found = table.outside(p)
            assert found == expected or (found == 0.0 and table.within(p))
    assert len(asked) > 200 and np.mean(asked) < 20


def test_the_highest_products_of_some_directions_are_the_same_as_of_all():
    """The heights a pruned question asks (a few columns of the directions, two or more)
    are the same numbers as those columns of the product of every direction."""
    from urdftool.physics.support import _columns, highest

    rng = np.random.default_rng(35)
    directions = np.hstack([_columns()[0], rng.normal(size=(3, 1))])
    for trial in range(60):
        n = int(rng.integers(2, 5000))
        points = rng.normal(size=(n, 3)) * 10.0 ** rng.integers(-8, 8, size=(n, 3))
        chosen = rng.choice(directions.shape[1], size=int(rng.integers(2, 20)), replace=False)
        whole = highest(points, directions)
        found = highest(points, np.ascontiguousarray(directions[:, chosen]))
        assert np.array_equal(found.view(np.int64), whole[chosen].view(np.int64)), trial


def test_a_question_of_the_same_shapes_is_answered_once_per_run(tmp_path):
    """Two robots of the same shapes (one robot described twice): the second's question is
    answered from the first's (no table of its pieces made), the same number; another point,
    or shapes placed elsewhere, are asked again."""
    from benchmarks.generate import _sphere_stl

    (tmp_path / "ball.stl").write_bytes(_sphere_stl(0.05, 12, 16, open_top=False))

    def reach(x: float):
        robot = load_text(tmp_path, f'<robot name="r"><link name="a"><visual><origin xyz="{x} 0 '
                          '0"/><geometry><mesh filename="ball.stl"/></geometry></visual>'
                          '<collision><geometry><box size="0.1 0.1 0.1"/></geometry>'
                          '</collision></link></robot>')
        return link_reach(robot, robot.links["a"])

    far = (0.0, 0.0, 0.4)
    first, second, moved = reach(0.2), reach(0.2), reach(0.25)
    assert first.pieces[0].mesh is second.pieces[0].mesh  # (measured once per run)
    expected = first.outside(far, beyond=_margin)
    assert expected > 0.2 and first._table is not None
    assert second.outside(far, beyond=_margin) == expected and second._table is None
    assert second.outside((0.0, 0.0, 0.5), beyond=_margin) > expected
    assert moved.outside(far, beyond=_margin) != expected and moved._table is not None


def test_a_point_inside_a_links_own_geometry_is_inside_its_bodys_hull(tmp_path):
    """inside_own says a point is inside only where the hull of the link's rigid body (its
    own pieces and those fixed to it) holds it: outside 0 for a reach of primitives, to
    rounding with meshes; points outside the link's own geometry, beyond 1e6 m or not a
    number are not claimed."""
    from benchmarks.generate import _sphere_stl
    from urdftool.physics.support import inside_own

    (tmp_path / "ball.stl").write_bytes(_sphere_stl(0.05, 12, 16, open_top=False))
    for own in (SHAPES["box"], SHAPES["cylinder"], '<mesh filename="ball.stl"/>'):
        robot = load_text(tmp_path, f"""<robot name="r">
          <link name="a"><collision><origin xyz="{' '.join(map(str, XYZ))}"
            rpy="{' '.join(map(str, RPY))}"/><geometry>{own}</geometry></collision></link>
          <link name="b"><visual><geometry>{SHAPES["sphere"]}</geometry></visual></link>
          <joint name="ab" type="fixed"><parent link="a"/><child link="b"/>
            <origin xyz="0.4 0.1 0"/></joint></robot>""")
        link = robot.links["a"]
        body = link_reach(robot, link, rigid=True)
        assert body.links == ["a", "b"]
        rng = np.random.default_rng(1)
        points = np.asarray(XYZ) + rng.uniform(-0.08, 0.08, size=(300, 3))
        inside = [bool(inside_own(robot, link, tuple(p))) for p in points.tolist()]
        assert 20 < sum(inside) < 280, own
        for p, held in zip(points.tolist(), inside):
            if held:
                assert body.outside(tuple(p)) <= (0.0 if "mesh" not in own else 1e-12)
        near_b = (0.4, 0.1, 0.0)  # inside b's sphere, outside a's own geometry
        assert not inside_own(robot, link, near_b) and body.outside(near_b) == 0.0
        assert not inside_own(robot, link, (1e6, 0.0, 0.0))
        assert not inside_own(robot, link, (math.nan, 0.0, 0.0))
