"""COLLADA read with lxml and numpy: hand-written documents for each feature and each way of
being malformed, and every corpus file compared with trimesh."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from conftest import CORPUS, corpus_or_skip
from urdftool.description.collada import ColladaProblem, read_collada

TRIANGLE = "0 1 2"
POSITIONS = "0 0 0  1 0 0  0 1 0"


def _source(id_: str, values: str, params: str = "XYZ") -> str:
    count = len(values.split())
    return (f'<source id="{id_}"><float_array id="{id_}-a" count="{count}">{values}'
            f'</float_array><technique_common><accessor source="#{id_}-a" '
            f'count="{count // len(params)}" stride="{len(params)}">'
            + "".join(f'<param name="{p}" type="float"/>' for p in params)
            + "</accessor></technique_common></source>")


def _geometry(id_: str = "g", positions: str = POSITIONS, primitives: str | None = None,
              extra_sources: str = "") -> str:
    if primitives is None:
        primitives = (f'<triangles count="{len(TRIANGLE.split()) // 3}"><input semantic="VERTEX" '
                      f'source="#{id_}-v" offset="0"/><p>{TRIANGLE}</p></triangles>')
    return (f'<geometry id="{id_}"><mesh>{_source(id_ + "-pos", positions)}{extra_sources}'
            f'<vertices id="{id_}-v"><input semantic="POSITION" source="#{id_}-pos"/>'
            f'</vertices>{primitives}</mesh></geometry>')


def _dae(nodes: str, geometries: str | None = None, library_nodes: str = "",
         scenes: str | None = None, scene: str = '<scene><instance_visual_scene url="#s"/>'
                                                 '</scene>') -> bytes:
    geometries = _geometry() if geometries is None else geometries
    scenes = f'<visual_scene id="s">{nodes}</visual_scene>' if scenes is None else scenes
    library = f"<library_nodes>{library_nodes}</library_nodes>" if library_nodes else ""
    return (f'<?xml version="1.0"?><COLLADA xmlns="http://www.collada.org/2005/11/'
            f'COLLADASchema" version="1.4.1"><asset><unit meter="0.001"/></asset>'
            f"<library_geometries>{geometries}</library_geometries>{library}"
            f"<library_visual_scenes>{scenes}</library_visual_scenes>{scene}"
            f"</COLLADA>").encode()


def _read(data: bytes, max_triangles: int = 1000):
    return read_collada(data, max_triangles=max_triangles)


def _soup(data: bytes, **kwargs) -> np.ndarray:
    """The corners of every triangle, in order: (m, 3, 3)."""
    vertices, faces = _read(data, **kwargs)
    return vertices[faces]


PLACED = '<instance_geometry url="#g"/>'
NODE = f'<node id="n">{PLACED}</node>'


def _placed(**geometry) -> bytes:
    """A document whose one node places geometry "g", made by ``_geometry(**geometry)``."""
    return _dae(NODE, _geometry(**geometry))


def test_one_triangle_in_the_document_unit():
    # the <unit meter="0.001"> is left to meshes.collada_unit, as trimesh leaves it
    corners = _soup(_dae(f'<node id="n">{PLACED}</node>'))
    np.testing.assert_array_equal(corners, [[[0, 0, 0], [1, 0, 0], [0, 1, 0]]])


@pytest.mark.parametrize("transform, expected", [
    ("<translate>1 2 3</translate>", [[1, 2, 3], [2, 2, 3], [1, 3, 3]]),
    ("<scale>2 3 4</scale>", [[0, 0, 0], [2, 0, 0], [0, 3, 0]]),
    ("<rotate>0 0 1 90</rotate>", [[0, 0, 0], [0, 1, 0], [-1, 0, 0]]),
    ("<matrix>1 0 0 5  0 1 0 6  0 0 1 7  0 0 0 1</matrix>", [[5, 6, 7], [6, 6, 7], [5, 7, 7]]),
    # eye at z=2 looking at the origin, y up: the node's -Z points down the world's -Z
    ("<lookat>0 0 2  0 0 0  0 1 0</lookat>", [[0, 0, 2], [1, 0, 2], [0, 1, 2]]),
    # eye on +X looking at the origin: the node's -Z is the world's -X, its X the world's -Z
    ("<lookat>3 0 0  0 0 0  0 1 0</lookat>", [[3, 0, 0], [3, 0, -1], [3, 1, 0]]),
    ("<skew>45 0 1 0 1 0 0</skew>", [[0, 0, 0], [1, 0, 0], [0, 1, 0]]),  # ignored, as assimp
])
def test_each_transform_kind(transform, expected):
    corners = _soup(_dae(f'<node id="n">{transform}{PLACED}</node>'))
    np.testing.assert_allclose(corners[0], expected, atol=1e-6)


def test_transforms_compose_in_document_order():
    translate_first = _soup(_dae(
        f'<node id="n"><translate>1 0 0</translate><rotate>0 0 1 90</rotate>{PLACED}</node>'))
    rotate_first = _soup(_dae(
        f'<node id="n"><rotate>0 0 1 90</rotate><translate>1 0 0</translate>{PLACED}</node>'))
    # T R x: the rotated triangle moved along X; R T x: the moved triangle rotated onto Y
    np.testing.assert_allclose(translate_first[0, 1], [1, 1, 0], atol=1e-6)
    np.testing.assert_allclose(rotate_first[0, 1], [0, 2, 0], atol=1e-6)


def test_nested_nodes_and_instance_node_compose_with_their_parents():
    library = f'<node id="lib"><scale>2 2 2</scale>{PLACED}</node>'
    corners = _soup(_dae(
        '<node id="a"><translate>0 0 10</translate>'
        f'<node id="b"><translate>1 0 0</translate>{PLACED}</node>'
        '<instance_node url="#lib"/></node>', library_nodes=library))
    np.testing.assert_allclose(corners, [[[1, 0, 10], [2, 0, 10], [1, 1, 10]],
                                         [[0, 0, 10], [2, 0, 10], [0, 2, 10]]], atol=1e-6)


def test_polylist_with_normals_and_texcoords_at_other_offsets():
    # one quad then one triangle; each corner is (normal, vertex, texcoord): VERTEX at offset 1
    quad = "0 1 0 0 2 1 0 3 2 0 4 3"
    triangle = "0 0 0 0 3 1 0 4 2"
    primitives = ('<polylist count="2"><input semantic="NORMAL" source="#g-n" offset="0"/>'
                  '<input semantic="VERTEX" source="#g-v" offset="1"/>'
                  '<input semantic="TEXCOORD" source="#g-t" offset="2" set="0"/>'
                  f'<vcount>4 3</vcount><p>{quad} {triangle}</p></polylist>')
    positions = "9 9 9  0 0 0  1 0 0  1 1 0  0 1 0  5 5 5"  # the last is used by no triangle
    extra = _source("g-n", "0 0 1") + _source("g-t", "0 0 1 0 1 1 0 1", "ST")
    vertices, faces = _read(_placed(positions=positions, primitives=primitives,
                                    extra_sources=extra))
    assert len(vertices) == 5  # every position a triangle uses, the unused one dropped
    np.testing.assert_array_equal(vertices[faces], [
        [[0, 0, 0], [1, 0, 0], [1, 1, 0]],  # the quad fanned from its first corner
        [[0, 0, 0], [1, 1, 0], [0, 1, 0]],
        [[9, 9, 9], [1, 1, 0], [0, 1, 0]],
    ])


def test_polygons_fan_and_several_primitives_in_one_geometry():
    positions = "0 0 0  1 0 0  2 1 0  1 2 0  0 1 0"
    primitives = ('<polygons count="1"><input semantic="VERTEX" source="#g-v" offset="0"/>'
                  '<p>0 1 2 3 4</p></polygons>'
                  '<lines count="1"><input semantic="VERTEX" source="#g-v" offset="0"/>'
                  '<p>0 1</p></lines>'  # lines make no triangles, as in trimesh
                  '<triangles count="1"><input semantic="VERTEX" source="#g-v" offset="0"/>'
                  '<p>4 3 2</p></triangles>')
    vertices, faces = _read(_placed(positions=positions, primitives=primitives))
    np.testing.assert_array_equal(vertices[faces][:, :, :2], [
        [[0, 0], [1, 0], [2, 1]], [[0, 0], [2, 1], [1, 2]], [[0, 0], [1, 2], [0, 1]],
        [[0, 1], [1, 2], [2, 1]]])


def test_triangles_of_several_p_blocks_at_an_offset_are_joined_in_order():
    # two <p> blocks of (normal, vertex) corners: the VERTEX column of both, end to end
    primitives = ('<triangles count="2"><input semantic="NORMAL" source="#g-n" offset="0"/>'
                  '<input semantic="VERTEX" source="#g-v" offset="1"/>'
                  '<p>0 0 0 1 0 2</p><p>0 2 0 1 0 3</p></triangles>')
    positions = "0 0 0  1 0 0  0 1 0  1 1 0"
    vertices, faces = _read(_placed(positions=positions, primitives=primitives,
                                    extra_sources=_source("g-n", "0 0 1")))
    np.testing.assert_array_equal(vertices[faces], [
        [[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 0], [1, 0, 0], [1, 1, 0]]])


@pytest.mark.parametrize("transform", ["", "<translate>0 0 0</translate>",
                                       "<translate>0 0 1e-9</translate>"])
def test_a_geometry_placed_where_it_is_keeps_its_numbers_and_zeros_turn_positive(transform):
    """A placement at (or within 1e-8 of) the identity gives each coordinate as the product
    with the identity gives it: itself, and +0.0 for a zero of either sign."""
    positions = "-0 0 -0.25  1e-30 -0 0  0.1 -7.5 -0"
    vertices, _ = _read(_dae(f'<node id="n">{transform}{PLACED}</node>',
                             _geometry(positions=positions)))
    expected = np.array(positions.split(), dtype=np.float32).astype(np.float64).reshape(-1, 3)
    product = np.dot(expected, np.identity(3).T) + np.zeros(3)
    assert vertices.tobytes() == product.tobytes()
    assert not np.signbit(vertices[vertices == 0]).any()


def _volume(vertices, faces) -> float:
    a, b, c = (vertices[faces[:, i]] for i in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


TETRAHEDRON = _geometry(positions="0 0 0  1 0 0  0 1 0  0 0 1", primitives=(
    '<triangles count="4"><input semantic="VERTEX" source="#g-v" offset="0"/>'
    "<p>0 2 1  0 1 3  0 3 2  1 2 3</p></triangles>"))


def test_a_mirroring_transform_keeps_the_volume_positive():
    plain = _read(_dae(NODE, TETRAHEDRON))
    mirrored = _read(_dae(f'<node id="n"><scale>-1 1 1</scale>{PLACED}</node>', TETRAHEDRON))
    assert _volume(*plain) == pytest.approx(1 / 6)
    assert _volume(*mirrored) == pytest.approx(1 / 6)
    assert mirrored[0][:, 0].min() == -1


def test_the_scene_named_by_scene_else_the_first():
    scenes = (f'<visual_scene id="first"><node id="a">{PLACED}</node></visual_scene>'
              f'<visual_scene id="second"><node id="b"><translate>5 0 0</translate>{PLACED}'
              "</node></visual_scene>")
    named = _soup(_dae("", scenes=scenes, scene='<scene><instance_visual_scene url="#second"/>'
                                                '</scene>'))
    unnamed = _soup(_dae("", scenes=scenes, scene=""))
    assert named[0, 0, 0] == 5 and unnamed[0, 0, 0] == 0


def test_a_scene_without_geometry_has_no_triangles():
    vertices, faces = _read(_dae('<node id="n"/>'))
    assert vertices.shape == (0, 3) and faces.shape == (0, 3)


def _triangles(p: str, count: int | None = 1, inputs: str = "") -> str:
    declared = "" if count is None else f' count="{count}"'
    return (f'<triangles{declared}><input semantic="VERTEX" source="#g-v" offset="0"/>{inputs}'
            f"<p>{p}</p></triangles>")


def _polylist(vcount: str | None, p: str) -> str:
    counts = "" if vcount is None else f"<vcount>{vcount}</vcount>"
    return (f'<polylist count="{len((vcount or "").split())}"><input semantic="VERTEX" '
            f'source="#g-v" offset="0"/>{counts}<p>{p}</p></polylist>')


MALFORMED = {
    "not XML": b"<COLLADA><library_geometries>",
    "not COLLADA": b"<robot name='r'/>",
    "no visual scene": _dae("", scenes="", scene=""),
    "scene names nothing": _dae(NODE, scene='<scene><instance_visual_scene url="#nothing"/>'
                                            "</scene>"),
    "geometry named nothing": _dae('<node id="n"><instance_geometry url="#missing"/></node>'),
    "instance_node named nothing": _dae('<node id="n"><instance_node url="#missing"/></node>'),
    "instance_node cycle": _dae('<node id="n"><instance_node url="#lib"/></node>',
                                library_nodes='<node id="lib"><instance_node url="#lib"/></node>'),
    "vertices named nothing": _placed(primitives=_triangles("0 1 2").replace("#g-v", "#other")),
    "no VERTEX input": _placed(primitives=_triangles("0 1 2").replace("VERTEX", "NORMAL")),
    "no POSITION input": _dae(NODE, _geometry().replace("POSITION", "NORMAL")),
    "index out of range": _placed(primitives=_triangles("0 1 3")),
    "negative index": _placed(primitives=_triangles("0 -1 2")),
    "index not a whole number": _placed(primitives=_triangles("0 1.5 2")),
    "index beyond int64": _placed(primitives=_triangles("0 1 99999999999999999999999")),
    "corners not a multiple of three": _placed(primitives=_triangles("0 1 2 0", None)),
    "indices not a multiple of the inputs": _placed(primitives=_triangles(
        "0 0 1 1 2", None, '<input semantic="NORMAL" source="#g-pos" offset="1"/>')),
    "triangle count does not match": _placed(primitives=_triangles("0 1 2", 2)),
    "vcount does not match p": _placed(primitives=_polylist("4", "0 1 2")),
    # 3 * 2**62 + (2**62 + 3) wraps around int64 to the 3 corners <p> holds
    "vcounts summing past int64": _placed(primitives=_polylist(
        f"{' '.join([str(2 ** 62)] * 3)} {2 ** 62 + 3}", "0 1 2")),
    "polylist without vcount": _placed(primitives=_polylist(None, "0 1 2")),
    "offset not a number": _dae(NODE, _geometry().replace('offset="0"', 'offset="x"')),
    "float_array count does not match": _dae(NODE, _geometry().replace('count="9"',
                                                                       'count="12"')),
    "positions not in threes": _placed(positions="0 0 0 1 0 0 0 1 0 5"),
    "a position is NaN": _placed(positions="0 0 0 1 nan 0 0 1 0"),
    "a position is infinite": _placed(positions="0 0 0 1 inf 0 0 1 0"),
    "a position beyond float32": _placed(positions="0 0 0 1 1e39 0 0 1 0"),
    "a position is text": _placed(positions="0 0 0 1 zero 0 0 1 0"),
    "a transform is NaN": _dae(f'<node id="n"><translate>0 nan 0</translate>{PLACED}</node>'),
    "a transform has too few numbers": _dae(f'<node id="n"><rotate>0 0 1</rotate>{PLACED}</node>'),
    "a transform moves beyond float range": _dae(
        f'<node id="n"><scale>3e38 1 1</scale><scale>3e38 1 1</scale>{PLACED}</node>'),
    "a degenerate lookat": _dae(f'<node id="n"><lookat>0 0 0 0 0 0 0 1 0</lookat>{PLACED}'
                                "</node>"),
    "an entity reference": (b'<?xml version="1.0"?><!DOCTYPE COLLADA [<!ENTITY e "0 1 2">]>'
                            + _placed(primitives=_triangles("&e;")).split(b"?>", 1)[1]),
}


@pytest.mark.parametrize("name", sorted(MALFORMED))
def test_malformed_documents_raise_collada_problem(name):
    with pytest.raises(ColladaProblem) as raised:
        _read(MALFORMED[name])
    assert raised.value.kind == "corrupt" and str(raised.value)
    assert raised.value.not_well_formed == (name == "not XML")


def test_the_triangle_limit_holds_per_geometry_and_per_scene():
    one_geometry = _dae(NODE, TETRAHEDRON)
    with pytest.raises(ColladaProblem) as raised:
        _read(one_geometry, max_triangles=3)
    assert raised.value.kind == "too-large"
    placed_twice = _dae(f'<node id="n">{PLACED}{PLACED}</node>', TETRAHEDRON)
    assert len(_read(placed_twice, max_triangles=8)[1]) == 8
    with pytest.raises(ColladaProblem) as raised:
        _read(placed_twice, max_triangles=7)
    assert raised.value.kind == "too-large"


def _fan_library(leaf: str) -> str:
    """Nodes l0 (holding ``leaf``) to l9, each instancing the one before ten times: l9 is
    10**9 instances of l0."""
    return f'<node id="l0">{leaf}</node>' + "".join(
        f'<node id="l{i}">' + f'<instance_node url="#l{i - 1}"/>' * 10 + "</node>"
        for i in range(1, 10))


def test_an_instancing_bomb_is_refused_before_it_is_built():
    # 10**9 triangles from a file of a few kilobytes
    library = _fan_library(PLACED)
    with pytest.raises(ColladaProblem) as raised:
        _read(_dae('<node id="n"><instance_node url="#l9"/></node>', library_nodes=library),
              max_triangles=2_000_000)
    assert raised.value.kind == "too-large"


def test_a_walk_of_empty_nodes_is_bounded():
    # no triangles at all, but 10**9 node instances to walk
    library = _fan_library("")
    with pytest.raises(ColladaProblem) as raised:
        _read(_dae('<node id="n"><instance_node url="#l9"/></node>', library_nodes=library))
    assert raised.value.kind == "too-large"


def test_instance_nodes_nested_too_deep_are_refused():
    library = f'<node id="l0">{PLACED}</node>' + "".join(
        f'<node id="l{i}"><instance_node url="#l{i - 1}"/></node>' for i in range(1, 400))
    with pytest.raises(ColladaProblem) as raised:
        _read(_dae('<node id="n"><instance_node url="#l399"/></node>', library_nodes=library))
    assert raised.value.kind == "too-large"


def _corpus_daes():
    return sorted(CORPUS.rglob("*.dae")) if CORPUS.is_dir() else []


def test_every_corpus_file_equals_trimesh():
    """Same triangle count, bounds (of trimesh's processed mesh too) within 1e-9 of the mesh
    size, same signed volume of the triangle soup within 1e-9 of the size cubed."""
    corpus_or_skip()
    trimesh = pytest.importorskip("trimesh")
    logging.getLogger("trimesh").setLevel(logging.CRITICAL)
    files = _corpus_daes()
    assert files, f"no .dae under {CORPUS}"
    differ = []
    for path in files:
        vertices, faces = read_collada(path.read_bytes(), max_triangles=2_000_000)
        raw = trimesh.load(str(path), force="mesh", process=False)
        processed = trimesh.load(str(path), force="mesh", process=True)
        size = max(float(np.ptp(raw.bounds, axis=0).max()), 1e-300)
        bounds = np.array([vertices.min(axis=0), vertices.max(axis=0)])
        worst = max(float(np.abs(bounds - raw.bounds).max()),
                    float(np.abs(bounds - processed.bounds).max())) / size
        volume = abs(_volume(vertices, faces) - _volume(raw.vertices, raw.faces)) / size ** 3
        if len(faces) != len(raw.faces) or not worst <= 1e-9 or not volume <= 1e-9:
            differ.append(f"{path}: {len(faces)} vs {len(raw.faces)} triangles, bounds off by "
                          f"{worst:.2g}, volume by {volume:.2g} of the size")
    assert not differ, "\n".join(differ)


def test_mutated_documents_give_triangles_or_collada_problem():
    """Seeded random edits of a document using every feature: each read ends in triangles or
    a ColladaProblem, never another exception."""
    import random
    import re

    library = '<node id="lib"><rotate>0 1 0 30</rotate><scale>1 2 1</scale>' + PLACED + "</node>"
    source = _dae('<node id="n"><matrix>1 0 0 1 0 1 0 0 0 0 1 0 0 0 0 1</matrix>'
                  '<lookat>3 0 0 0 0 0 0 1 0</lookat><instance_node url="#lib"/>'
                  f"{PLACED}</node>", TETRAHEDRON, library_nodes=library)
    pieces = [b"-1", b"nan", b"1e400", b"99999999999999999999", b"#", b"<p>", b"</p>", b"x",
              b" ", b"0", b"7", b'"', b'offset="3"', b"<node>", b'count="2"', b"1.5", b""]
    texts = [m.span(1) for m in re.finditer(rb">([^<]+)<", source)]  # numbers, mostly
    rng = random.Random(20)
    for _ in range(400):
        data = bytearray(source)
        for _ in range(rng.randint(1, 3)):
            start, end = rng.choice(texts) if rng.random() < 0.8 else (0, len(data))
            at = rng.randrange(start, end)
            data[at:at + rng.randint(0, 4)] = rng.choice(pieces)
        try:
            vertices, faces = _read(bytes(data))
        except ColladaProblem:
            continue
        assert np.all(np.isfinite(vertices)) and (faces.size == 0 or faces.max() < len(vertices))
