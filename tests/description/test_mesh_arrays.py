"""Meshes read and measured without trimesh: the arrays and numbers trimesh gives, corners merged
by position (the whole public corpus is compared in tests/integration/test_corpus_meshes.py)."""

from __future__ import annotations

import numpy as np
import pytest

from conftest import without_heavy_imports
from urdftool.description import mesh_arrays


def _trimesh_of(path):
    import trimesh

    return trimesh.load(str(path), force="mesh", process=True)


def _trimesh_by_position(path):
    """trimesh's mesh with its corners merged by position alone (normals and texture
    coordinates ignored): what the arrays of a COLLADA or OBJ file are."""
    mesh = _trimesh_of(path)
    mesh.merge_vertices(merge_tex=True, merge_norm=True)
    return mesh


def _box(tmp_path, name="box.stl", ascii=False, open_=False):
    import trimesh

    mesh = trimesh.creation.box((0.1, 0.2, 0.3))
    mesh.apply_translation((0.5, -1.0, 0.25))
    if open_:
        mesh.update_faces(np.arange(len(mesh.faces)) != 0)
    path = tmp_path / name
    data = trimesh.exchange.stl.export_stl_ascii(mesh).encode() if ascii else \
        trimesh.exchange.stl.export_stl(mesh)
    path.write_bytes(data)
    return path


@pytest.mark.parametrize("ascii", [False, True])
@pytest.mark.parametrize("open_", [False, True])
def test_stl_arrays_and_measures_are_trimeshs(tmp_path, ascii, open_):
    path = _box(tmp_path, ascii=ascii, open_=open_)
    vertices, faces = mesh_arrays.read(path, path.read_bytes())
    mesh = _trimesh_of(path)
    assert np.array_equal(vertices, mesh.vertices) and np.array_equal(faces, mesh.faces)
    assert np.array_equal(np.array(mesh_arrays.bounds(vertices, faces)), mesh.bounds)
    assert mesh_arrays.is_watertight(faces) == mesh.is_watertight == (not open_)
    ours, theirs = mesh_arrays.mass_properties(vertices, faces), mesh.mass_properties
    assert ours["volume"] == pytest.approx(theirs["volume"], rel=1e-12)
    if not open_:
        assert ours["volume"] == pytest.approx(0.006)
        assert np.allclose(ours["center_mass"], (0.5, -1.0, 0.25))
        assert np.allclose(ours["inertia"], theirs["inertia"], rtol=1e-12, atol=0)


def test_a_mirroring_scale_turns_the_faces_over_as_trimesh_does(tmp_path):
    path = _box(tmp_path)
    vertices, faces = mesh_arrays.read(path, path.read_bytes())
    mesh = _trimesh_of(path)
    mesh.apply_scale((0.001, -0.001, 0.001))
    moved, turned = mesh_arrays.scaled(vertices, faces, (0.001, -0.001, 0.001))
    assert np.array_equal(moved, mesh.vertices) and np.array_equal(turned, mesh.faces)
    assert mesh_arrays.mass_properties(moved, turned)["volume"] == pytest.approx(6e-12)


def test_scale_within_1e_8_of_one_changes_nothing_as_in_trimesh(tmp_path):
    path = _box(tmp_path)
    vertices, faces = mesh_arrays.read(path, path.read_bytes())
    moved, _ = mesh_arrays.scaled(vertices, faces, (1 + 1e-9, 1, 1))
    assert moved is vertices


def test_corners_that_differ_by_sign_are_not_merged():
    """Rows (a, b, c) and (a, -b, -c) once hashed alike with a weaker hash: the grouping is
    checked against the rows, and the hash keeps them apart."""
    corners = np.array([[-0.000525, 0.0122, 0.013], [-0.000525, -0.0122, -0.013],
                        [0.1, 0.0, 0.0]] * 2)
    vertices, faces = mesh_arrays.merged(corners, np.arange(6).reshape(2, 3))
    assert len(vertices) == 3 and faces.tolist() == [[0, 1, 2], [0, 1, 2]]


def test_rows_sharing_a_hash_are_still_told_apart(monkeypatch):
    keys = np.array([[1, 2, 3], [4, 5, 6], [1, 2, 3], [4, 5, 6]], dtype=np.int64)
    # every row hashes alike: only the check against the rows can tell them apart
    monkeypatch.setattr(mesh_arrays, "_row_hash",
                        lambda columns: np.zeros(columns.shape[1], np.uint64))
    first, inverse = mesh_arrays._unique_rows(np.ascontiguousarray(keys.T))
    assert first.tolist() == [0, 1] and inverse.tolist() == [0, 1, 0, 1]


def test_merged_keeps_the_first_of_equal_vertices_in_order_of_first_use():
    corners = np.array([[0.5, 0, 0], [0, 0, 0], [0.5 + 1e-10, 0, 0], [1, 1, 1], [0, 0, 0],
                        [1, 1, 1]])
    vertices, faces = mesh_arrays.merged(corners, np.arange(6).reshape(2, 3))
    assert vertices.tolist() == [[0.5, 0, 0], [0, 0, 0], [1, 1, 1]]
    assert faces.tolist() == [[0, 1, 0], [2, 1, 2]]


@pytest.mark.parametrize("data", [
    b"\0" * 80 + (3).to_bytes(4, "little") + b"\0" * 70,  # truncated binary
    b"\0" * 80 + (0).to_bytes(4, "little"),  # no triangles
    b"solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
    b"endloop\nendfacet\nendsolid a\nsolid b\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
    b"vertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid b\n",  # two solids: a scene
    b"solid a\nvertex 0 0 0\nvertex 1 0\nendsolid a\n",  # not whole triangles
    b"solid \xff\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendsolid\n",  # not UTF-8
    b"solid a\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 nan 0\nendsolid a\n",  # not finite
    b"solid a\nvertex 0 0 0\nvertex 1 0 x\nvertex 0 1 0\nendsolid a\n",  # a word no number
])
def test_what_trimesh_should_judge_is_not_read_light(tmp_path, data):
    path = tmp_path / "m.stl"
    path.write_bytes(data)
    assert mesh_arrays.read(path, data) is None


def test_other_formats_are_left_to_trimesh(tmp_path):
    path = tmp_path / "m.ply"
    path.write_text("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                    "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    assert mesh_arrays.read(path, path.read_bytes()) is None


@pytest.mark.parametrize("name, open_", [("part.stl", False), ("part.stl", True),
                                         ("part.dae", False)])
def test_checking_a_robot_of_stl_or_collada_meshes_does_not_import_trimesh(tmp_path, name,
                                                                          open_):
    """A size, a box, a count, a volume, an open mesh's hull: all measured without loading
    trimesh (its import alone costs more than checking a small robot)."""
    import trimesh

    if name.endswith(".dae"):
        box = trimesh.creation.box((0.1, 0.2, 0.3))
        box.apply_translation((0.5, -1.0, 0.25))
        box.export(tmp_path / name)
    else:
        _box(tmp_path, name, open_=open_)
    (tmp_path / ".git").mkdir()
    robot = tmp_path / "r.urdf"
    robot.write_text(
        '<robot name="r"><link name="a"><inertial><mass value="2000"/><inertia ixx="1e-5" ixy="0" '
        'ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/></inertial><visual><geometry><mesh '
        f'filename="{name}"/></geometry></visual><collision><geometry><mesh '
        f'filename="{name}" scale="2 2 2"/></geometry></collision></link></robot>')
    output = without_heavy_imports(
        "from urdftool.lint.engine import CheckOptions, load_and_check\n"
        f"print(sorted(f.code for f in load_and_check({str(robot)!r}, CheckOptions()).findings))")
    # 2000 kg in 0.048 m^3 (the hull's volume, for the open box) is denser than osmium
    assert "U311" in output
    assert ("U414" if open_ else "U310") in output  # U310: compared with the box's inertia


@pytest.mark.parametrize("open_", [False, True])
def test_checking_a_plausible_robot_of_meshes_does_not_import_scipy(tmp_path, open_):
    """Nothing is to be reported of a light link of an open or closed mesh, its centre of mass
    inside: U311's volume and U312's hull are decided from a few of the mesh's vertices, and
    neither qhull nor scipy (0.2 s to import) is asked."""
    from benchmarks.generate import _sphere_stl

    (tmp_path / "part.stl").write_bytes(_sphere_stl(0.05, 16, 24, open_top=open_))  # 370 vertices
    (tmp_path / ".git").mkdir()
    robot = tmp_path / "r.urdf"
    robot.write_text(
        '<robot name="r"><link name="a"><inertial><origin xyz="0.005 -0.005 0.06"/><mass '
        'value="2"/><inertia ixx="2e-3" ixy="0" ixz="0" iyy="2e-3" iyz="0" izz="2e-3"/>'
        '</inertial><visual><geometry><mesh filename="part.stl"/></geometry></visual>'
        '<collision><geometry><mesh filename="part.stl" scale="2 2 2"/></geometry></collision>'
        '</link></robot>')
    output = without_heavy_imports(
        "from urdftool.lint.engine import CheckOptions, load_and_check\n"
        f"print(sorted(f.code for f in load_and_check({str(robot)!r}, CheckOptions()).findings))\n"
        "assert 'scipy' not in sys.modules, 'scipy imported'")
    assert not {"U307", "U311", "U312", "U313", "U316"} & set(eval(output))


_COLLADA = """<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="1"/><up_axis>Z_UP</up_axis></asset>
  <library_materials><material id="m" name="m"><instance_effect url="#e"/></material>
  </library_materials>
  <library_effects><effect id="e"><profile_COMMON><technique sid="t"><phong><diffuse>
    <color>0.5 0.5 0.5 1</color></diffuse></phong></technique></profile_COMMON></effect>
  </library_effects>
  <library_geometries><geometry id="g"><mesh>
    <source id="p"><float_array id="pa" count="24">0 0 0 1 0 0 1 1 0 0 1 0 0 0 1 1 0 1 1 1 1 0 1 1
      </float_array><technique_common><accessor source="#pa" count="8" stride="3">
      <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <source id="n"><float_array id="na" count="6">0 0 1 0 0 -1</float_array><technique_common>
      <accessor source="#na" count="2" stride="3"><param name="X" type="float"/>
      <param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common>
    </source>
    <source id="u"><float_array id="ua" count="4">0 0 1 1</float_array><technique_common>
      <accessor source="#ua" count="2" stride="2"><param name="S" type="float"/>
      <param name="T" type="float"/></accessor></technique_common></source>
    <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
    <polylist material="s" count="6">
      <input semantic="VERTEX" source="#v" offset="0"/>
      <input semantic="NORMAL" source="#n" offset="1"/>
      <input semantic="TEXCOORD" source="#u" offset="2" set="0"/>
      <vcount>4 4 4 4 4 4</vcount>
      <p>0 1 0 3 1 0 2 1 1 1 1 1  4 0 0 5 0 1 6 0 0 7 0 1  0 1 0 1 1 1 5 1 0 4 1 1
         1 1 0 2 1 1 6 1 0 5 1 1  2 1 0 3 1 1 7 1 0 6 1 1  3 1 0 0 1 1 4 1 0 7 1 1</p>
    </polylist></mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s">
    <node id="a"><translate>0.5 0 0</translate><rotate>0 0 1 30</rotate>
      <instance_geometry url="#g"><bind_material><technique_common>
        <instance_material symbol="s" target="#m"/></technique_common></bind_material>
      </instance_geometry></node>
    <node id="b"><scale>1 -2 1</scale><node id="c"><matrix>1 0 0 0 0 1 0 3 0 0 1 0 0 0 0 1
      </matrix><instance_geometry url="#g"/></node></node>
  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
"""


def test_collada_arrays_are_trimeshs_through_nodes_mirrors_and_seams(tmp_path):
    """A cube as quads with normals and texture coordinates, instanced twice: rotated and
    moved, and mirrored inside a nested node. trimesh splits corners where the normal or (with
    a bound material) the texture coordinate differs, and so calls the cubes open; merged by
    position they are trimesh's triangles, closed, of trimesh's volume."""
    path = tmp_path / "m.dae"
    path.write_text(_COLLADA)
    vertices, faces = mesh_arrays.read(path, path.read_bytes())
    assert not _trimesh_of(path).is_watertight  # the seams
    mesh = _trimesh_by_position(path)
    assert len(vertices) == len(mesh.vertices) == 16
    assert np.array_equal(np.sort(vertices[faces].reshape(-1, 9), axis=0),
                          np.sort(mesh.vertices[mesh.faces].reshape(-1, 9), axis=0))
    assert mesh_arrays.is_watertight(faces) and mesh.is_watertight
    ours, theirs = mesh_arrays.mass_properties(vertices, faces), mesh.mass_properties
    assert ours["volume"] == pytest.approx(theirs["volume"], rel=1e-12)
    assert ours["volume"] == pytest.approx(3.0, rel=1e-6)  # 1 + 2: the second is scaled by 2


def _cube_with_split_normals() -> str:
    """A unit cube as 12 triangles with one normal per face: 24 corners at 8 positions."""
    corners = [(0, 2, 6, 4), (1, 5, 7, 3), (0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6)]
    positions = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    normals = [(-1, 0, 0), (1, 0, 0), (0, -1, 0), (0, 1, 0), (0, 0, -1), (0, 0, 1)]
    points, indices = [], []
    for face, quad in enumerate(corners):  # every face its own four corners
        points += [positions[k] for k in quad]
        for a, b, c in ((0, 1, 2), (0, 2, 3)):
            indices += [f"{4 * face + a} {face}", f"{4 * face + b} {face}",
                        f"{4 * face + c} {face}"]
    floats = " ".join(f"{v}" for point in points for v in point)
    normal_floats = " ".join(f"{v}" for normal in normals for v in normal)
    xyz = '<param name="X" type="float"/><param name="Y" type="float"/>' \
          '<param name="Z" type="float"/>'
    return f"""<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <library_geometries><geometry id="g"><mesh>
    <source id="p"><float_array id="pa" count="72">{floats}</float_array><technique_common>
      <accessor source="#pa" count="24" stride="3">{xyz}</accessor></technique_common></source>
    <source id="n"><float_array id="na" count="18">{normal_floats}</float_array>
      <technique_common><accessor source="#na" count="6" stride="3">{xyz}</accessor>
      </technique_common></source>
    <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
    <triangles count="12"><input semantic="VERTEX" source="#v" offset="0"/>
      <input semantic="NORMAL" source="#n" offset="1"/><p>{" ".join(indices)}</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s"><node id="a"><instance_geometry url="#g"/>
  </node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
"""


def test_a_collada_cube_with_split_normals_is_watertight_with_the_cubes_volume(tmp_path):
    """24 corners (one normal per face) at 8 positions: trimesh keeps the faces apart and calls
    the cube open; by position it is closed, its volume and inertia the cube's."""
    path = tmp_path / "cube.dae"
    path.write_text(_cube_with_split_normals())
    vertices, faces = mesh_arrays.read(path, path.read_bytes())
    assert len(_trimesh_of(path).vertices) == 24 and not _trimesh_of(path).is_watertight
    assert len(vertices) == 8 and len(faces) == 12
    assert mesh_arrays.is_watertight(faces)
    properties = mesh_arrays.mass_properties(vertices, faces)
    assert properties["volume"] == pytest.approx(1.0, rel=1e-12)
    assert np.allclose(properties["center_mass"], 0.5)
    assert np.allclose(properties["inertia"], np.eye(3) / 6.0)  # m (a^2 + a^2) / 12, m = 1


def test_collada_that_is_not_well_formed_raises_for_its_recovery(tmp_path):
    """The caller (meshes) reads what libxml2's recover mode makes of it (U416)."""
    from urdftool.description.collada import ColladaProblem

    path = tmp_path / "m.dae"
    path.write_text(_COLLADA.replace('<node id="a">', '<node id="<a>">'))
    with pytest.raises(ColladaProblem) as raised:
        mesh_arrays.read(path, path.read_bytes())
    assert raised.value.not_well_formed


_OBJ_CUBE_V = "".join(f"v {x} {y} {z}\n" for x in (0, 1) for y in (0, 2) for z in (0, 3))
_OBJ_CUBE_F = [(1, 3, 2), (2, 3, 4), (5, 6, 7), (6, 8, 7), (1, 2, 5), (2, 6, 5),
               (3, 7, 4), (4, 7, 8), (1, 5, 3), (3, 5, 7), (2, 4, 6), (4, 8, 6)]


def _obj_text(form: str) -> str:
    """The cube in one corner form; texture coordinates and normals split it along seams."""
    text = "# a cube\no Cube\n" + _OBJ_CUBE_V
    text += "vt 0 0\nvt 1 0\nvt 0 1\n" + "vn 0 0 1\nvn 0 1 0\nvn 1 0 0\n"
    lines = []
    for number, face in enumerate(_OBJ_CUBE_F):
        corners = []
        for k, v in enumerate(face):
            t, n = (number + k) % 3 + 1, number // 4 + 1
            corners.append(form.format(v=v, t=t, n=n))
        lines.append("f " + " ".join(corners))
    return text + "s off\n" + "\n".join(lines) + "\n"


@pytest.mark.parametrize("form", ["{v}", "{v}/{t}", "{v}//{n}", "{v}/{t}/{n}"])
def test_obj_triangles_are_trimeshs(tmp_path, form):
    """Every corner form: the same triangles (coordinates), count and volume as trimesh
    loads; trimesh cuts the cube open along its seams where texture coordinates or normals
    differ, and merged by position it is closed (watertight), as trimesh says once merged."""
    path = tmp_path / "m.obj"
    path.write_text(_obj_text(form))
    vertices, faces = mesh_arrays.read(path, path.read_bytes())
    if form == "{v}/{t}/{n}":
        assert not _trimesh_of(path).is_watertight  # the seams
    mesh = _trimesh_by_position(path)
    assert len(vertices) == len(mesh.vertices) == 8
    assert np.array_equal(vertices[faces], mesh.vertices[mesh.faces])
    assert mesh_arrays.is_watertight(faces) and mesh.is_watertight
    ours, theirs = mesh_arrays.mass_properties(vertices, faces), mesh.mass_properties
    assert ours["volume"] == theirs["volume"] and abs(ours["volume"]) == pytest.approx(6.0)


@pytest.mark.parametrize("change", [
    lambda t: "mtllib m.mtl\n" + t,  # materials
    lambda t: t.replace("o Cube", "g part"),  # groups
    lambda t: t.replace("f 1 3 2", "f 1 3 2 4"),  # a polygon
    lambda t: t.replace("f 1 3 2", "f -8 -6 -7"),  # relative indices
    lambda t: t.replace("v 0 0 0", "v 0 0 0 1 0 0"),  # a colour
    lambda t: t.replace("f 1 3 2", "  f 1 3 2"),  # indented
    lambda t: t.replace("f 1 3 2", "f 1 3 99"),  # no such vertex
    lambda t: t.replace("f 1 3 2", "f 1//1 3 2"),  # mixed corner forms
    lambda t: t.replace("v 0 0 0", "v 0 0"),  # too few coordinates
    lambda t: t.replace("s off", "v zero 0 0\ns off"),  # a word that is no number
    lambda t: t.replace("f 1 3 2", "f 1 3 2\u00a0"),  # other white space than ASCII's
    lambda t: t.replace("v 0 0 0", "v 0 0 0+e0"),  # trimesh rewrites "+e" and "-e" first
    lambda t: t.replace("v 0 0 0", "v 0 0 0\nv 0 0 1-e0"),
])
def test_obj_that_is_not_plain_is_left_to_trimesh(tmp_path, change):
    path = tmp_path / "m.obj"
    path.write_text(change(_obj_text("{v}")))
    assert mesh_arrays.read(path, path.read_bytes()) is None


def test_obj_white_space_within_a_line_is_white_space(tmp_path):
    plain = tmp_path / "plain.obj"
    plain.write_text(_obj_text("{v}"))
    spaced = tmp_path / "spaced.obj"
    spaced.write_text(_obj_text("{v}").replace("f 1 3 2", "f \t1\t3  2 \t").replace(
        "v 0 0 0", "v  0\t0 0 "))
    ours, expected = (mesh_arrays.read(p, p.read_bytes()) for p in (spaced, plain))
    assert all(np.array_equal(a, b) for a, b in zip(ours, expected))


def _obj_layouts():
    """The cube of ``_obj_text("{v}/{t}/{n}")`` with its rows in other orders: each kind's
    rows in one run elsewhere in the file, or in several runs (objects, comments between)."""
    lines = _obj_text("{v}/{t}/{n}").splitlines(keepends=True)
    kind = {head: [line for line in lines if line.startswith(head)]
            for head in ("v ", "vt ", "vn ", "f ")}
    return {
        "kinds reordered": "".join(kind["f "] + kind["vn "] + kind["v "] + kind["vt "]),
        "two objects": "".join(["o A\n"] + kind["v "][:4] + kind["vt "] + kind["f "][:6] +
                               ["o B\n"] + kind["v "][4:] + kind["vn "] + kind["f "][6:]),
        "comments between": "".join(sum(([f"# row {n}\n", line] for n, line in
                                         enumerate(lines)), [])),
        "rows interleaved": "".join(line for pair in zip(kind["v "], kind["f "])
                                    for line in pair) + "".join(
            kind["v "][8:] + kind["f "][8:] + kind["vt "] + kind["vn "]),
    }


@pytest.mark.parametrize("layout", list(_obj_layouts()))
def test_obj_rows_are_read_wherever_each_kind_is(tmp_path, layout):
    """A kind's rows read as one slice of the text (one run of lines) or gathered (several
    runs) give the same triangles, as trimesh reads them wherever they are."""
    plain = tmp_path / "plain.obj"
    plain.write_text(_obj_text("{v}/{t}/{n}"))
    moved = tmp_path / "moved.obj"
    moved.write_text(_obj_layouts()[layout])
    ours, expected = (mesh_arrays.read(p, p.read_bytes()) for p in (moved, plain))
    assert all(np.array_equal(a, b) for a, b in zip(ours, expected))
    assert np.array_equal(ours[0][ours[1]], _trimesh_by_position(moved).triangles)


def _merged_then_bounds(vertices, scale=None):
    merged_vertices, faces = mesh_arrays.merged(vertices, np.arange(len(vertices)).reshape(-1, 3))
    if scale is not None:
        merged_vertices, faces = mesh_arrays.scaled(merged_vertices, faces, scale)
    return mesh_arrays.bounds(merged_vertices, faces)


def test_merged_bounds_are_those_of_the_merged_vertices_or_none():
    rng = np.random.default_rng(5)
    decided = 0
    for _ in range(200):
        grid = rng.integers(-3, 4, size=(30, 3)) * 0.25  # many equal, some equal to 1e-8
        jitter = rng.choice([0.0, 0.0, 3e-9, -3e-9, 0.25], size=(30, 3))
        corners = np.vstack([grid, grid[rng.permutation(30)] + jitter])
        scale = tuple(rng.choice([1.0, 0.001, -2.0], size=3))
        moved, _ = mesh_arrays.scaled(corners, np.arange(60).reshape(-1, 3), scale)
        found = mesh_arrays.merged_bounds(moved, corners)
        decided += found is not None
        if found is not None:
            expected = _merged_then_bounds(corners, scale)
            assert all(np.array_equal(a, b) and (np.signbit(a) == np.signbit(b)).all()
                       for a, b in zip(found, expected))
    assert 10 < decided < 200  # both outcomes are exercised


def test_merged_bounds_leave_to_merging_what_they_cannot_tell():
    # the greatest x (row 2) merges into row 0, which merging keeps
    merges_into_an_earlier = np.array([[0.5, 0, 0], [0, 0, 1], [0.5 + 4e-9, 0, 0]])
    assert mesh_arrays.merged_bounds(merges_into_an_earlier, merges_into_an_earlier) is None
    assert _merged_then_bounds(merges_into_an_earlier)[1][0] == 0.5
    signed_zeros = np.array([[0.0, 1, 1], [-0.0, 2, 2], [1, 0, 1]])
    assert mesh_arrays.merged_bounds(signed_zeros, signed_zeros) is None
    huge = np.array([[1e11, 0, 0], [0, 1, 0], [0, 0, 1]])
    assert mesh_arrays.merged_bounds(huge, huge) is None  # merge keys overflow there


def test_obj_comments_and_names_may_hold_any_text(tmp_path):
    plain = tmp_path / "plain.obj"
    plain.write_text(_obj_text("{v}"))
    named = tmp_path / "named.obj"
    named.write_text("# caf\u00e9\n" + _obj_text("{v}").replace("o Cube", "o W\u00fcrfel"),
                     encoding="utf-8")
    ours, expected = (mesh_arrays.read(p, p.read_bytes()) for p in (named, plain))
    assert all(np.array_equal(a, b) for a, b in zip(ours, expected))


def test_obj_lines_joined_by_a_backslash_and_crlf_are_read_as_trimesh_joins_them(tmp_path):
    plain = tmp_path / "plain.obj"
    plain.write_text(_obj_text("{v}/{t}"))
    joined = tmp_path / "joined.obj"
    joined.write_bytes(_obj_text("{v}/{t}").replace("f 1/1 3/2", "f 1/1 \\\n3/2").replace(
        "\n", "\r\n").encode() + b"\\")
    ours, expected = (mesh_arrays.read(p, p.read_bytes()) for p in (joined, plain))
    assert all(np.array_equal(a, b) for a, b in zip(ours, expected))


@pytest.mark.parametrize("scale", [(0.001, 0.001, 0.001), (-1.0, 1.0, 1.0), (2.0, 2.0, -3.0),
                                   (1e300, 1e-300, 2.0), (1e-320, 1.0, 1.0)])
def test_a_scale_is_the_transforms_product_to_the_bit_without_blas(scale, monkeypatch):
    """Each coordinate times its factor, a zero of either sign +0.0 and an overflow inf, as
    np.dot of the 4 x 4 transform makes them; no BLAS call (whose threads spin on after it)."""
    rng = np.random.default_rng(7)
    vertices = rng.normal(size=(40000, 3)) * 10.0 ** rng.uniform(-300, 300, size=(40000, 3))
    vertices[::7], vertices[::11, 1] = 0.0, -0.0
    faces = np.arange(len(vertices) - 1).reshape(-1, 3)
    matrix = np.eye(4)
    matrix[:3, :3] *= np.asarray(scale)
    with np.errstate(all="ignore"):
        expected = np.dot(matrix, np.column_stack((vertices, np.ones(len(vertices)))).T).T[:, :3]
        monkeypatch.setattr(np, "dot", None)
        moved, turned = mesh_arrays.scaled(vertices, faces, scale)
    assert np.ascontiguousarray(moved).tobytes() == np.ascontiguousarray(expected).tobytes()
    assert np.array_equal(turned, faces[:, ::-1] if np.prod(np.sign(scale)) < 0 else faces)


def _clouds():
    """Point clouds of many shapes (scipy's qhull is the oracle of their hulls): round, long,
    thin, a box's surface with points on its faces, a far-off small one, few points."""
    rng = np.random.default_rng(11)
    box = rng.uniform(-1, 1, size=(400, 3))
    box[np.arange(400), rng.integers(0, 3, 400)] = rng.choice([-1.0, 1.0], 400)
    grid = np.array([(x, y, z) for x in (0, .5, 1) for y in (0, .5, 1) for z in (0, .5, 1)])
    return [rng.normal(size=(3000, 3)), rng.normal(size=(500, 3)) * [2.0, 0.5, 0.01],
            box * [0.1, 0.2, 0.3], rng.normal(size=(200, 3)) * 1e-3 + [50.0, -20.0, 3.0],
            rng.normal(size=(6, 3)), grid, np.c_[rng.normal(size=(100, 2)), np.zeros(100)]]


def _against_qhull(bound_of):
    """(cloud, its bound, the volume of qhull's hull of it) of each of :func:`_clouds` that is
    not flat; of a flat one the bound must be 0."""
    scipy_spatial = pytest.importorskip("scipy.spatial")
    found = []
    for cloud in _clouds():
        bound = bound_of(cloud)
        try:
            found.append((cloud, bound, scipy_spatial.ConvexHull(cloud).volume))
        except scipy_spatial.QhullError:  # flat: no volume
            assert bound == 0.0
    return found


def test_inner_volume_is_below_qhulls_hull_volume_and_near_it():
    """The bound U311 asks before building a hull (no qhull, no scipy): never above the
    volume of the hull qhull builds, and not far below it on solid shapes."""
    scipy_spatial = pytest.importorskip("scipy.spatial")
    for cloud, bound, volume in _against_qhull(mesh_arrays.inner_volume):
        assert 0.0 <= bound <= volume
        assert bound >= 0.3 * volume or len(cloud) < 10
    rng = np.random.default_rng(2)
    for _ in range(20):  # few points: the small hull itself is qhull's, less its margin
        points = rng.normal(size=(rng.integers(4, 27), 3))
        found = mesh_arrays._small_hull_volume([tuple(p) for p in points.tolist()])
        assert found == pytest.approx(scipy_spatial.ConvexHull(points).volume, rel=1e-5)
        assert found <= scipy_spatial.ConvexHull(points).volume


def test_inner_tetrahedron_volume_is_below_qhulls_hull_volume():
    """The first bound U311 asks (one tetrahedron of the hull's points): never above the
    hull's volume, the tetrahedron's own for four points, 0 for flat points."""
    scipy_spatial = pytest.importorskip("scipy.spatial")
    for _, bound, volume in _against_qhull(mesh_arrays.inner_tetrahedron_volume):
        assert 0.0 < bound <= volume
    rng = np.random.default_rng(3)
    for _ in range(20):  # (of four points the cube's directions may miss one: then 0)
        corners = rng.normal(size=(4, 3)) * rng.uniform(1e-3, 1e3)
        volume = scipy_spatial.ConvexHull(corners).volume
        found = mesh_arrays._first_tetrahedron_volume([tuple(p) for p in corners.tolist()])
        assert found == pytest.approx(volume, rel=1e-12)
        assert 0.0 <= mesh_arrays.inner_tetrahedron_volume(corners) <= volume


def test_cube_extremes_are_hull_vertices_largest_along_the_cubes_directions():
    scipy_spatial = pytest.importorskip("scipy.spatial")
    cloud = _clouds()[0]
    found = mesh_arrays.cube_extremes(cloud)
    assert len(found) == 26 and set(found) <= set(scipy_spatial.ConvexHull(cloud).vertices)
    directions = np.array(mesh_arrays._CUBE, dtype=float)
    np.testing.assert_array_equal((cloud[found[:13]] * directions).sum(axis=1),
                                  (cloud @ directions.T).max(axis=0))


def test_cube_heights_are_the_matrix_products_to_the_bit():
    """The sums and differences stand for the product: every entry the same number (the
    same bits but a zero's sign), so the same extremes, the first of equals, at any
    magnitude and rounding on every sum; coordinates where a sum could overflow, and
    non-finite ones, are taken by the product itself."""
    rng = np.random.default_rng(11)
    product = mesh_arrays._cube_columns().T
    clouds = [rng.normal(size=(500, 3)),
              rng.normal(size=(500, 3)) * 10.0 ** rng.integers(-30, 30, size=(500, 3)),
              np.round(rng.normal(size=(500, 3)) * 1000) / 997 +
              rng.choice([0.0, 1e16, -1e16, 5e-324], size=(500, 3)),
              rng.uniform(-1, 1, size=(500, 3)) * 1e307, rng.normal(size=(1, 3)),
              np.array([[1e308, 1e308, 0.0], [0.0, 1.0, 2.0]]),
              np.array([[np.inf, 0.0, 1.0], [np.nan, 1.0, 1.0], [-0.0, 0.0, -0.0]])]
    for cloud in clouds:
        with np.errstate(all="ignore"):
            expected = product @ cloud.T
            found = mesh_arrays._cube_heights(cloud)
        assert found.shape == expected.shape
        assert np.array_equal(found, expected, equal_nan=True)
        nonzero = expected != 0
        assert np.array_equal(found[nonzero].view(np.int64), expected[nonzero].view(np.int64))
        if np.isfinite(expected).all():
            assert np.array_equal(mesh_arrays.cube_extremes(cloud), np.concatenate(
                [expected.argmax(axis=1), expected.argmin(axis=1)]))


def test_binary_stl_corners_ignore_the_normal_and_attribute_bytes():
    """A record's normal and attribute are skipped, whatever they hold (NaN, garbage): the
    corners alone are read, in float64, three a record."""
    rng = np.random.default_rng(3)
    corners = rng.normal(size=(5, 3, 3)).astype("<f4")
    records = np.zeros(5, dtype=[("normal", "<f4", 3), ("vertices", "<f4", (3, 3)),
                                 ("attribute", "<u2")])
    records["vertices"] = corners
    plain = b"\0" * 80 + (5).to_bytes(4, "little") + records.tobytes()
    records["normal"], records["attribute"] = np.nan, 0xFFFF
    noisy = b"\0" * 80 + (5).to_bytes(4, "little") + records.tobytes()
    for data in (plain, noisy):
        vertices, faces = mesh_arrays.read_unmerged(_path("m.stl"), data)
        assert vertices.dtype == np.float64 and vertices.flags.c_contiguous
        assert np.array_equal(vertices, corners.reshape(-1, 3).astype(np.float64))
        assert faces is None  # each three corners in order a triangle
    # a count that lies (one record more or fewer than the bytes hold) is not binary
    for count in (4, 6):
        lying = plain[:80] + count.to_bytes(4, "little") + plain[84:]
        assert mesh_arrays.read_unmerged(_path("m.stl"), lying) is None


def _path(name):
    from pathlib import Path

    return Path(name)


def test_unique_rows_are_the_first_of_each_distinct_row_in_order_of_first_use(monkeypatch):
    rng = np.random.default_rng(11)
    for size in (1, 2, 7, 300, 5000):
        keys = rng.integers(-3, 3, size=(size, 3)).astype(np.int64)
        seen, expected_first = {}, []
        for at, row in enumerate(map(tuple, keys.tolist())):
            if row not in seen:
                seen[row] = len(seen)
                expected_first.append(at)
        expected_inverse = [seen[row] for row in map(tuple, keys.tolist())]
        for weak in (False, True):  # every row hashing alike: told apart by the rows
            if weak:
                monkeypatch.setattr(mesh_arrays, "_row_hash",
                                    lambda columns: np.zeros(columns.shape[1], np.uint64))
            first, inverse = mesh_arrays._unique_rows(np.ascontiguousarray(keys.T))
            assert first.tolist() == expected_first and inverse.tolist() == expected_inverse
            monkeypatch.undo()


def _trimeshs_mass_properties(triangles) -> dict:
    """trimesh.triangles.mass_properties (trimesh 4), its expressions as it writes them (density
    1, with the inertia): importing trimesh costs a second."""
    vectors = triangles[:, 1:, :] - triangles[:, :2, :]
    crosses = np.cross(vectors[:, 0], vectors[:, 1])
    t0, t1, t2 = triangles[:, 0, :], triangles[:, 1, :], triangles[:, 2, :]
    f1 = t0 + t1 + t2
    f2 = t0 ** 2 + t1 ** 2 + t0 * t1 + t2 * f1
    f3 = (t0 ** 3) + (t0 ** 2) * (t1) + (t0) * (t1 ** 2) + (t1 ** 3) + (t2 * f2)
    g0, g1, g2 = (f2 + (t + f1) * t for t in (t0, t1, t2))
    integral = np.zeros((10, len(f1)))
    integral[0] = crosses[:, 0] * f1[:, 0]
    integral[1:4] = (crosses * f2).T
    integral[4:7] = (crosses * f3).T
    for i in range(3):
        j = np.mod(i + 1, 3)
        integral[i + 7] = crosses[:, i] * ((t0[:, j] * g0[:, i]) + (t1[:, j] * g1[:, i]) +
                                           (t2[:, j] * g2[:, i]))
    integrated = integral.sum(axis=1) / np.array([6, 24, 24, 24, 60, 60, 60, 120, 120, 120],
                                                 dtype=np.float64)
    volume = integrated[0]
    center = integrated[1:4] / volume
    inertia = np.zeros((3, 3))
    inertia[0, 0] = integrated[5] + integrated[6] - (volume * (center[[1, 2]] ** 2).sum())
    inertia[1, 1] = integrated[4] + integrated[6] - (volume * (center[[0, 2]] ** 2).sum())
    inertia[2, 2] = integrated[4] + integrated[5] - (volume * (center[[0, 1]] ** 2).sum())
    inertia[0, 1] = -(integrated[7] - (volume * np.prod(center[[0, 1]])))
    inertia[1, 2] = -(integrated[8] - (volume * np.prod(center[[1, 2]])))
    inertia[0, 2] = -(integrated[9] - (volume * np.prod(center[[0, 2]])))
    inertia[2, 0], inertia[2, 1], inertia[1, 0] = inertia[0, 2], inertia[1, 2], inertia[0, 1]
    return {"volume": volume, "center_mass": center, "inertia": inertia}


def test_mass_properties_are_trimeshs_to_the_bit():
    """Every sum and product is trimesh's, in its order: the same bits, not only close."""
    rng = np.random.default_rng(2)
    for size in (1, 5, 200, 3000):
        vertices = rng.normal(size=(size + 2, 3)) * rng.choice([1e-3, 1.0, 1e3])
        faces = rng.integers(0, size + 2, size=(size, 3))
        with np.errstate(divide="ignore", invalid="ignore"):  # a flat soup: no centre
            ours, theirs = mesh_arrays.mass_properties(vertices, faces), \
                _trimeshs_mass_properties(vertices[faces])
        for key in ("volume", "center_mass", "inertia"):
            assert np.asarray(ours[key]).tobytes() == np.asarray(theirs[key]).tobytes()


@pytest.mark.parametrize("subdivisions", [2, 7])  # 162 vertices; 163,842: int64 edge keys
def test_watertightness_is_trimeshs_for_either_width_of_edge_keys(subdivisions):
    import trimesh

    sphere = trimesh.creation.icosphere(subdivisions=subdivisions)
    faces = np.asarray(sphere.faces, dtype=np.int64)
    assert (len(sphere.vertices) > 65536) == (subdivisions == 7)
    opened = trimesh.Trimesh(sphere.vertices, faces[1:], process=False)
    doubled = np.vstack([faces, faces[:1]])  # an edge shared by three faces
    assert mesh_arrays.is_watertight(faces) and sphere.is_watertight
    assert not mesh_arrays.is_watertight(faces[1:]) and not opened.is_watertight
    assert not mesh_arrays.is_watertight(doubled)
    assert not trimesh.Trimesh(sphere.vertices, doubled, process=False).is_watertight
