"""A link's geometry as solids and boxes (physics/solids.py)."""

from __future__ import annotations

import pytest

from conftest import rigid_body_robot
from urdftool.description.load import load
from urdftool.physics.solids import rigid_bounds

# base (1 cm cube) -fixed, 1 m along x and turned 90 deg about z- sensor (a 10 x 20 x 30 cm
# box 0.1 m along the sensor's own x) -fixed- tip; arm moves (not part of base's body).
RIGID = """<robot name="r">
  <link name="base"><collision><geometry><box size="0.01 0.01 0.01"/></geometry></collision></link>
  <link name="sensor"><visual><origin xyz="0.1 0 0"/><geometry><box size="0.1 0.2 0.3"/></geometry></visual></link>
  <link name="tip"/>
  <link name="arm"><visual><geometry><sphere radius="5"/></geometry></visual></link>
  <joint name="f" type="fixed"><parent link="base"/><child link="sensor"/>
    <origin xyz="1 0 0" rpy="0 0 1.5707963267948966"/></joint>
  <joint name="g" type="fixed"><parent link="sensor"/><child link="tip"/></joint>
  <joint name="m" type="revolute"><parent link="base"/><child link="arm"/>
    <limit lower="0" upper="1" effort="1" velocity="1"/></joint>
</robot>"""


def _robot(tmp_path, text=RIGID):
    (tmp_path / "r.urdf").write_text(text)
    return load(tmp_path / "r.urdf")


def test_rigid_bounds_join_links_fixed_either_way_in_the_link_frame(tmp_path):
    robot = _robot(tmp_path)
    base = rigid_bounds(robot, robot.links["base"])
    assert base.links == ["base", "sensor", "tip"] and base.complete
    # the sensor box, turned 90 deg: x in [0.9, 1.1] (its y), y in [0.05, 0.15] (its x)
    assert base.bounds[0] == pytest.approx((-0.005, -0.005, -0.15))
    assert base.bounds[1] == pytest.approx((1.1, 0.15, 0.15))
    tip = rigid_bounds(robot, robot.links["tip"])  # reached through its parent, backwards
    assert tip.links == ["tip", "sensor", "base"]
    assert tip.bounds[0] == pytest.approx((-0.005, -0.1, -0.15))
    assert tip.bounds[1] == pytest.approx((0.15, 1.005, 0.15))


def test_rigid_bounds_of_a_link_without_a_name_are_its_own_box(tmp_path):
    # no joint can name it, so nothing is fixed to it: its own geometry (U307 crashed on it)
    robot = _robot(tmp_path, RIGID.replace('<link name="arm">', '<link>'))
    nameless = next(link for link in robot.children("link") if link.get("name") is None)
    bounds = rigid_bounds(robot, nameless)
    assert bounds.links == [None] and bounds.complete
    assert bounds.bounds == ((-5.0, -5.0, -5.0), (5.0, 5.0, 5.0))


def test_rigid_bounds_of_a_link_alone_are_what_its_frames_give(tmp_path):
    # the shortcut for a link nothing is fixed to gives what walking its one frame gives
    from urdftool.physics import solids

    robot = _robot(tmp_path)
    arm = robot.links["arm"]
    frames = solids._rigid_frames(robot, "arm")
    members, box, complete = solids._placed_corners(robot, arm)
    assert list(frames) == ["arm"]
    assert rigid_bounds(robot, arm) == solids.RigidBounds(["arm"], complete, box)


def test_rigid_bounds_say_when_a_mesh_could_not_be_measured(tmp_path):
    robot = _robot(tmp_path, RIGID.replace('<box size="0.1 0.2 0.3"/>',
                                           '<mesh filename="missing.stl"/>'))
    base = rigid_bounds(robot, robot.links["base"])
    assert not base.complete and base.bounds[1] == pytest.approx((0.005,) * 3)


def test_rigid_bounds_equal_the_placed_corners_exactly(tmp_path):
    # the link's own box is taken whole: the same numbers as moving each corner by 0 + I c
    from urdftool.physics import mat3
    from urdftool.physics.solids import _corners, _local_box, shapes

    text = RIGID.replace('<box size="0.01 0.01 0.01"/></geometry>',
                         '<box size="0.01 0.01 0.01"/></geometry></collision><collision>'
                         '<origin xyz="0.3 -0.1 0" rpy="0.1 0.2 0.3"/><geometry>'
                         '<cylinder radius="0.07" length="0.3"/></geometry>')
    robot = _robot(tmp_path, text)
    link = robot.links["base"]
    robot.links = {"base": link}  # nothing fixed to it
    corners = [mat3.add((0.0, 0.0, 0.0), mat3.apply(mat3.IDENTITY, mat3.add(
        s.xyz, mat3.apply(s.rotation, c)))) for s in shapes(robot, link, "collision")
        for c in _corners(_local_box(s))]
    expected = (tuple(min(c[i] for c in corners) for i in range(3)),
                tuple(max(c[i] for c in corners) for i in range(3)))
    assert rigid_bounds(robot, link).bounds == expected


def test_a_links_shapes_are_read_once_per_robot(tmp_path, monkeypatch):
    from urdftool.lint.engine import CheckOptions, load_and_check
    from urdftool.physics import solids

    read, shape_of = [], solids.shape_of
    monkeypatch.setattr(solids, "shape_of",
                        lambda holder, *groups: read.append(holder) or shape_of(holder, *groups))
    (tmp_path / "r.urdf").write_text(RIGID.replace(
        '<link name="tip"/>', '<link name="tip"><inertial><mass value="1"/><inertia ixx="1" '
        'ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>').replace(
        '<link name="arm">', '<link name="arm"><inertial><mass value="1"/><inertia ixx="0.1" '
        'ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>'))
    load_and_check(str(tmp_path / "r.urdf"), CheckOptions())
    assert len(read) == len(set(read)) == 3  # base's collision, sensor's and arm's visuals


def test_primitives_are_placed_only_when_the_parts_are_read(tmp_path, monkeypatch):
    from urdftool.physics import mass, solids

    placed, transformed = [], mass.transformed
    monkeypatch.setattr(mass, "transformed", lambda *a: placed.append(1) or transformed(*a))
    robot = _robot(tmp_path)
    solid = solids.link_solid(robot, robot.links["sensor"])  # a 10 x 20 x 30 cm box
    volume = solids.volume(solid)
    assert solid.counts and solid.volume_floor() == volume and not placed
    assert volume == sum(part.mass for part in solid.parts) == pytest.approx(6e-3)
    assert placed == [1] and solid.parts[0].com == pytest.approx((0.1, 0.0, 0.0))
    assert not solids.link_solid(robot, robot.links["tip"]).counts


def _open_box(tmp_path):
    """A 10 x 20 x 30 cm box without its top (its hull: the box, 6e-3 m^3), on link 'a'."""
    trimesh = pytest.importorskip("trimesh")
    box = trimesh.creation.box(extents=(0.1, 0.2, 0.3))
    box.update_faces(box.face_normals[:, 2] < 0.5)
    box.export(tmp_path / "open.stl")
    return _robot(tmp_path, '<robot name="r"><link name="a"><collision><geometry>'
                            '<mesh filename="open.stl"/></geometry></collision></link></robot>')


def test_an_open_meshs_hull_is_built_once_for_its_floor_and_its_parts(tmp_path, monkeypatch):
    from urdftool.description import mesh_arrays
    from urdftool.physics.solids import HULL_USED, link_solid, volume

    built, hull = [], mesh_arrays.convex_hull
    monkeypatch.setattr(mesh_arrays, "convex_hull", lambda v: built.append(1) or hull(v))
    robot = _open_box(tmp_path)
    solid = link_solid(robot, robot.links["a"])
    assert not solid.sound and solid.bounds is not None and not built
    floor = solid.volume_floor()
    assert built == [1] and 6e-3 * (1 - 2e-6) < floor < 6e-3
    assert HULL_USED in solid.problems[0][1] and built == [1]
    assert volume(solid) == pytest.approx(6e-3) and floor <= volume(solid)


def test_an_open_meshs_floor_asks_one_tetrahedron_before_its_small_hull(tmp_path, monkeypatch):
    # a floor that is enough from one tetrahedron of the hull's points grows no small hull;
    # one that is not asks the small hull, then qhull's: each a lower bound of the next
    from urdftool.description import mesh_arrays
    from urdftool.physics.solids import link_solid

    grown, small = [], mesh_arrays._small_hull_volume
    monkeypatch.setattr(mesh_arrays, "_small_hull_volume", lambda p: grown.append(1) or small(p))
    robot = _open_box(tmp_path)  # its hull: 6e-3 m^3; a tetrahedron of it: 1e-3
    asked = []
    floor = link_solid(robot, robot.links["a"]).volume_floor(
        enough=lambda v: asked.append(v) or v > 1e-4)
    assert not grown and len(asked) == 1 and 1e-3 * (1 - 1e-5) < floor <= 1e-3
    asked.clear()
    floor = link_solid(robot, robot.links["a"]).volume_floor(
        enough=lambda v: asked.append(v) or v > 2e-3)
    assert grown == [1] and len(asked) == 2 and asked[0] < asked[1] <= 6e-3
    assert 6e-3 * (1 - 2e-6) < floor <= 6e-3


@pytest.mark.parametrize("shape", ["sphere", "cylinder", "normal", "uniform", "flat"])
def test_hull_floor_is_qhulls_volume_shaved_for_rounding(shape):
    np = pytest.importorskip("numpy")
    trimesh = pytest.importorskip("trimesh")
    from scipy.spatial import ConvexHull, QhullError

    from urdftool.description.meshes import MeshFacts
    from urdftool.physics.solids import _hull_floor

    rng = np.random.default_rng(7)
    points = np.asarray({
        "sphere": lambda: trimesh.creation.icosphere(3).vertices,
        "cylinder": lambda: trimesh.creation.cylinder(0.1, 1.0).vertices,
        "normal": lambda: rng.normal(size=(500, 3)) * (1.0, 0.1, 0.01),
        "uniform": lambda: rng.uniform(size=(3000, 3)),
        "flat": lambda: np.c_[rng.uniform(size=(100, 2)), np.zeros(100)]}[shape](), dtype=float)
    try:
        hull = ConvexHull(points).volume
    except QhullError:
        hull = 0.0
    floor = _hull_floor(MeshFacts(points, np.arange(len(points) // 3 * 3).reshape(-1, 3), {}))
    if shape == "flat":  # qhull fails; joggled, it encloses next to nothing
        assert hull == 0.0 and floor < 1e-9
    else:
        assert hull * (1 - 2e-6) < floor < hull


@pytest.mark.parametrize("xyz", ["0 0 0", "-0 0.3 -0", "1e308 -1e308 0.05", "inf 0 nan"])
@pytest.mark.parametrize("size", ["0.02 0.02 0.1", "5e-324 1 1", "1e308 1e308 1e308", "3 0.5 7"])
def test_unturned_shapes_are_placed_as_the_rotation_would_place_them(tmp_path, xyz, size):
    # rpy 0 0 0 moves the corners without products; the same numbers, box and finiteness
    import math

    from urdftool.physics import mat3
    from urdftool.physics.solids import _box, _corners, _local_box, _measured, _placed, \
        _shape_corners, shapes

    robot = _robot(tmp_path, f'<robot name="r"><link name="a"><visual><origin xyz="{xyz}"/>'
                             f'<geometry><box size="{size}"/></geometry></visual></link></robot>')
    [shape] = shapes(robot, robot.links["a"], "visual")
    assert shape.rotation is mat3.NO_TURN
    placed = _placed(shape.xyz, shape.rotation, _corners(_local_box(shape)))
    assert _measured(robot, shape)
    assert shape.finite == math.isfinite(sum(map(sum, placed)))
    assert [[float(v).hex() for v in c] for c in shape.box] == \
        [[float(v).hex() for v in c] for c in _box(placed)]
    assert [[float(v).hex() for v in c] for c in _shape_corners(shape)] == \
        [[float(v).hex() for v in c] for c in placed]


def test_two_boxes_join_as_min_and_max_choose_to_the_bit():
    # two boxes (a visual and a collision) are joined written out: the same numbers as the
    # builtins, which keep the first of equals (0.0 before -0.0) and a nan only when first
    import itertools
    import math

    from urdftool.physics.solids import _joined

    values = (0.0, -0.0, 1.0, -2.5, math.inf, -math.inf, math.nan)
    for a, b in itertools.product(values, repeat=2):
        first, second = ((a, b, a), (b, a, b)), ((b, a, 1.0), (a, b, -1.0))
        low, high = _joined([first, second])
        expected = (tuple(min(x, y) for x, y in zip(first[0], second[0])),
                    tuple(max(x, y) for x, y in zip(first[1], second[1])))
        assert [v.hex() for v in low + high] == [v.hex() for v in expected[0] + expected[1]]


def test_a_solid_measures_its_extent_once(tmp_path):
    from urdftool.physics.solids import link_solid

    robot = _robot(tmp_path)
    solid = link_solid(robot, robot.links["sensor"])
    (lx, ly, lz), (hx, hy, hz) = solid.bounds
    assert solid.extent == max(hx - lx, hy - ly, hz - lz) == pytest.approx(0.3)
    solid.bounds = ((0.0, 0.0, 0.0), (9.0, 9.0, 9.0))  # kept: not measured again
    assert solid.extent == pytest.approx(0.3)


def test_a_large_rigid_body_gives_each_member_the_box_its_own_walk_gives(tmp_path,
                                                                         monkeypatch):
    """A body of more than GROUP_DIRECT links is measured once in its root's frame; each
    member's box is what gathering the body from the member's own frame gives (the way every
    smaller body is measured), to rounding."""
    from urdftool.physics import solids

    text = rigid_body_robot(40)
    measured = _robot(tmp_path, text)
    assert len(solids._bodies(measured)["l5"][1]) == 40 > solids.GROUP_DIRECT
    (tmp_path / "walked").mkdir()
    walked = _robot(tmp_path / "walked", text)
    for name in [f"l{i}" for i in range(41)]:
        mine = rigid_bounds(measured, measured.links[name])
        monkeypatch.setattr(solids, "GROUP_DIRECT", 10 ** 6)
        theirs = rigid_bounds(walked, walked.links[name])  # every body walked from each member
        monkeypatch.undo()
        assert mine.links == theirs.links and mine.complete == theirs.complete
        assert mine.bounds[0] == pytest.approx(theirs.bounds[0], abs=1e-12)
        assert mine.bounds[1] == pytest.approx(theirs.bounds[1], abs=1e-12)


def test_the_members_of_a_rigid_body_cost_each_a_constant(tmp_path, monkeypatch):
    """Asking the box and the reach of every member of a body of n links composes O(n)
    frames, not n per member (a body of 10,000 fixed links took hours)."""
    from urdftool.physics import solids
    from urdftool.physics.support import link_reach

    robot = _robot(tmp_path, rigid_body_robot(300))
    calls = []
    multiply = solids.mat3.multiply
    monkeypatch.setattr(solids.mat3, "multiply", lambda *a: calls.append(1) or multiply(*a))
    for i in range(300):
        link = robot.links[f"l{i}"]
        assert rigid_bounds(robot, link).bounds is not None
        assert link_reach(robot, link, rigid=True).pieces
    assert len(calls) < 3 * 300


def _bits(box) -> tuple:
    """A box's numbers as their bytes (-0.0 and 0.0 differ, a nan equals itself)."""
    import struct

    return tuple(struct.pack("<d", v) for corner in box for v in corner)


def test_plain_links_keep_no_shapes_of_their_own(tmp_path, monkeypatch):
    """The bulk path reads each link's shapes straight into its table: no per-link Shapes
    made and kept for it (a 10,000-link robot's 20,000: a sixth of the table's time); the
    links it leaves read their own when the per-link path asks."""
    from plain_robots import plain_robot
    from urdftool.physics import solids

    monkeypatch.setattr(solids, "BULK_LINKS", 1)
    robot = _robot(tmp_path, plain_robot(0))
    assert len(solids.plain_links(robot).rows) > 20
    assert not robot.memoized(solids._link_shapes)


@pytest.mark.parametrize("seed", range(8))
def test_plain_links_measured_at_once_are_the_per_link_boxes_to_the_bit(tmp_path, monkeypatch,
                                                                        seed):
    """Every row of plain_links is rigid_bounds' box of the link, byte for byte, over random
    robots with zeros of either sign, subnormal, huge and non-finite numbers; and each plain
    link whose own box is finite has a row (the per-link path is not left doing the work)."""
    from plain_robots import plain_robot
    from urdftool.physics import solids

    monkeypatch.setattr(solids, "BULK_LINKS", 1)
    text = plain_robot(seed)
    table = solids.plain_links(_robot(tmp_path, text))
    robot = _robot(tmp_path, text)  # another load: the per-link path measures afresh
    assert len(table.rows) > 20
    for name, link in robot.links.items():
        found = solids._link_shapes(robot, link)
        plain = name not in solids._fixed_neighbours(robot) and all(
            len(found[tag][0]) == found[tag][1] for tag in ("visual", "collision")) and \
            found["visual"][0] + found["collision"][0] and \
            all(s.kind != "mesh" for s in found["visual"][0] + found["collision"][0])
        if name not in table.rows:
            assert not plain or solids._placed_corners(robot, link)[1] is None, name
            continue
        assert plain, name
        row = table.rows[name]
        rigid = rigid_bounds(robot, link)
        assert rigid.links == [name] and rigid.complete
        assert _bits((tuple(table.low[row].tolist()), tuple(table.high[row].tolist()))) == \
            _bits(rigid.bounds), name


@pytest.mark.parametrize("seed", range(8))
def test_plain_links_inside_is_what_the_pieces_hold(tmp_path, monkeypatch, seed):
    """PlainLinks.inside says a point is inside only when a piece of the link's reach holds it
    (Piece.holds, the per-link path), and for links without cylinders exactly when."""
    import random

    from plain_robots import plain_robot
    from urdftool.physics import solids
    from urdftool.physics.support import link_reach

    monkeypatch.setattr(solids, "BULK_LINKS", 1)
    robot = _robot(tmp_path, plain_robot(seed))
    table = solids.plain_links(robot)
    rng = random.Random(seed)
    names, points = [], []
    for name in table.rows:
        for piece in link_reach(robot, robot.links[name]).pieces:  # points about each piece
            for _ in range(3):
                names.append(name)
                points.append(tuple(c + rng.choice([0.0, 1.0, -1.0, 0.5]) * s * rng.random()
                                    for c, s in zip(piece.centre, piece.size * 3)))
            for axis in range(3):  # on the faces of an unturned box, to the bit
                names.append(name)
                points.append(tuple(c + (piece.size[0] if i == axis else 0.0)
                                    for i, c in enumerate(piece.centre)))
    inside = table.inside(names, points).tolist()
    decided = 0
    for name, point, found in zip(names, points, inside):
        pieces = link_reach(robot, robot.links[name]).pieces
        held = any(piece.holds(point) for piece in pieces)
        assert held or not found, (name, point)
        if all(piece.kind != "cylinder" for piece in pieces):
            assert found == held, (name, point)
        decided += found
    assert decided > 20


@pytest.mark.parametrize("seed", range(8))
def test_plain_solids_measured_at_once_are_the_per_link_solids_to_the_bit(tmp_path, monkeypatch,
                                                                          seed):
    """Every plain link's PlainSolid (its shapes' unit solids placed and combined with the
    others' at once) gives what the link's LinkSolid gives to the inertia rules, byte for
    byte: computed() at several masses (or None for both), volume(), source, extent, bounds
    (zeros as +0), over random robots with zeros of either sign, subnormal, huge and
    non-finite numbers, several shapes per link, turned and unturned."""
    import struct

    from plain_robots import plain_robot
    from urdftool.physics import solids

    def bits(values) -> bytes:
        return struct.pack(f"<{len(values)}d", *values)

    def body_bits(body):
        return None if body is None else \
            bits([body.mass, *body.com, *(v for row in body.inertia for v in row)])

    monkeypatch.setattr(solids, "BULK_LINKS", 1)
    text = plain_robot(seed)
    robot = _robot(tmp_path, text)
    alone = _robot(tmp_path, text)  # another load: the per-link path measures afresh
    table = solids.plain_links(robot)
    pairs = dict(zip(robot.children("link"), alone.children("link")))
    found = 0
    for link in robot.children("link"):
        plain = solids.plain_solid(robot, link)
        if plain is None:
            assert link.get("name") not in table.rows or robot.links[link.get("name")] is not link
            continue
        found += 1
        solid = solids.link_solid(alone, pairs[link])
        for mass in (1.0, 0.37, 1e-300, 5e-324, 1e300):
            assert body_bits(solids.computed(plain, mass=mass)) == \
                body_bits(solids.computed(solid, mass=mass)), link.get("name")
        assert body_bits(solids.computed(plain, density=7850.0)) == \
            body_bits(solids.computed(solid, density=7850.0))
        assert bits([solids.volume(plain), plain.extent]) == \
            bits([solids.volume(solid), solid.extent])
        assert (plain.source, plain.sound, plain.counts) == \
            (solid.source, solid.sound, bool(solid.counts))
        assert bits([v + 0.0 for corner in solid.bounds for v in corner]) == \
            bits([v for corner in plain.bounds for v in corner])
    assert found > 20


def test_a_shape_read_from_its_holders_grouped_children_is_the_shape_read_alone(tmp_path):
    import random

    from urdftool.description.load import load
    from urdftool.physics import solids

    rng = random.Random(34)
    shapes_ = ['<box size="1 2 3"/>', '<box size="1 2"/>', '<cylinder radius="1" length="2"/>',
               '<sphere radius="-1"/>', '<mesh filename="m.stl" scale="1 1 2"/>', "<cone/>",
               "<!-- s -->"]
    for case in range(40):
        holders = []
        for _ in range(30):
            parts = ["<geometry>" + "".join(rng.choice(shapes_) for _ in range(
                rng.randrange(0, 3))) + "</geometry>" for _ in range(rng.choice([0, 1, 1, 2]))]
            parts += [f'<origin xyz="{rng.choice(["0 0 1", "1 2", "-0 0 0"])}" rpy="0 0 1"/>'
                      for _ in range(rng.choice([0, 1, 2]))] + ["<!-- c -->", "<material/>"]
            rng.shuffle(parts)
            tag = rng.choice(["visual", "collision"])
            holders.append(f"<{tag}>{''.join(parts)}</{tag}>")
        text = '<robot name="r"><link name="a">' + "".join(holders) + "</link></robot>"
        path = tmp_path / f"r{case}.urdf"
        path.write_text(text)
        robot = load(path)
        for holder in robot.children("link")[0]:
            if isinstance(holder.tag, str):
                assert repr(solids.shape_of(holder, robot.grouped(holder))) == \
                    repr(solids.shape_of(holder)), text


@pytest.mark.parametrize("links", [2, 5, 16])
def test_held_box_is_inside_the_rigid_bounds_to_the_bit(tmp_path, links):
    """Each member's held_box (its own box) is held by rigid_bounds' box, coordinate for
    coordinate as the floats compare, for bodies walked from the member (up to GROUP_DIRECT
    links) and a link alone; a link without geometry has none."""
    from urdftool.physics import solids

    robot = _robot(tmp_path, rigid_body_robot(links))
    for name, link in robot.links.items():
        held = solids.held_box(robot, link)
        assert held == solids.link_bounds(robot, link)[0] and held is not None
        (low, high), (rigid_low, rigid_high) = held, rigid_bounds(robot, link).bounds
        assert all(r <= h for r, h in zip(rigid_low, low)), name
        assert all(r >= h for r, h in zip(rigid_high, high)), name
    assert solids.held_box(robot, _robot(tmp_path).links["tip"]) is None


def test_held_box_of_a_member_of_a_larger_body_is_none(tmp_path):
    """A body of more than GROUP_DIRECT links is measured in its root's frame and turned:
    its box need not hold the member's own to the bit, so no box is offered."""
    from urdftool.physics import solids

    robot = _robot(tmp_path, rigid_body_robot(solids.GROUP_DIRECT + 1))
    assert solids.held_box(robot, robot.links["l3"]) is None
    alone = robot.links[f"l{solids.GROUP_DIRECT + 1}"]  # on the revolute joint: its own box
    assert solids.held_box(robot, alone) == rigid_bounds(robot, alone).bounds is not None
