"""Pictures: projection, flat shading, depth order, SVG titles, overlays, a golden image."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import pytest

from conftest import load_text
from urdftool.kinematics.scene import posed
from urdftool.report import picture
from urdftool.report.picture import Layer, PictureOptions

GOLDEN = Path(__file__).parent / "golden" / "render_iso.png"
SMALL = PictureOptions("iso", (96, 96))

ROBOT = """<robot name="toy">
  <link name="base"><visual><geometry><box size="0.4 0.3 0.1"/></geometry>
    <material name="red"><color rgba="0.9 0.1 0.1 1"/></material></visual></link>
  <link name="arm"><visual><origin xyz="0 0 0.2"/><geometry>
    <cylinder radius="0.05" length="0.4"/></geometry>
    <material name="blue"><color rgba="0.1 0.2 0.9 1"/></material></visual></link>
  <link name="head"><visual><geometry><sphere radius="0.08"/></geometry></visual></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.05"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="j2" type="fixed"><parent link="arm"/><child link="head"/>
    <origin xyz="0 0 0.45"/></joint>
</robot>"""

def scene_of(tmp_path, text: str, q=None):
    return posed(load_text(tmp_path, text), q or {})[0]


def pixels(data: bytes) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(data)).convert("RGB"), dtype=float)


def test_golden_image(tmp_path):
    """The toy robot at 96x96, iso: within a small mean difference of the stored picture
    (compared 4x downsampled, so that a pixel's worth of rasterisation does not count)."""
    from PIL import Image

    drawn = pixels(picture.png([Layer(scene_of(tmp_path, ROBOT, {"j1": "0.6"}))], SMALL))
    golden = np.asarray(Image.open(GOLDEN).convert("RGB"), dtype=float)
    assert drawn.shape == golden.shape

    def down(image):
        return image.reshape(24, 4, 24, 4, 3).mean(axis=(1, 3))

    assert np.abs(down(drawn) - down(golden)).mean() < 2.0


def test_the_golden_comparison_can_fail(tmp_path):
    from PIL import Image

    other = pixels(picture.png([Layer(scene_of(tmp_path, ROBOT, {"j1": "-0.6"}))], SMALL))
    golden = np.asarray(Image.open(GOLDEN).convert("RGB"), dtype=float)
    assert np.abs(other - golden).reshape(24, 4, 24, 4, 3).mean(axis=(1, 3)).mean() > 2.0


def _boxes(first_colour, second_colour):
    return f"""<robot name="two">
  <link name="back"><visual><geometry><box size="0.2 0.2 0.2"/></geometry>
    <material name="b"><color rgba="{second_colour} 1"/></material></visual></link>
  <link name="front"><visual><geometry><box size="0.2 0.2 0.2"/></geometry>
    <material name="f"><color rgba="{first_colour} 1"/></material></visual></link>
  <joint name="j" type="fixed"><parent link="back"/><child link="front"/>
    <origin xyz="0.5 0 0"/></joint></robot>"""


@pytest.mark.parametrize("view, expected", [("front", "front"), ("side", "both")])
def test_the_nearer_shape_hides_the_farther(tmp_path, view, expected):
    scene = scene_of(tmp_path, _boxes("0 1 0", "1 0 1"))  # front green, back magenta
    image = pixels(picture.png([Layer(scene)], PictureOptions(view, (64, 64))))
    green = (image[..., 1] > 100) & (image[..., 0] < 60)
    magenta = (image[..., 0] > 100) & (image[..., 1] < 60)
    if expected == "front":  # looking along -x: the front box covers the back one
        assert green.sum() > 500 and magenta.sum() == 0
    else:  # from the side both show, apart
        assert green.sum() > 100 and magenta.sum() > 100


def test_flat_shading_lights_faces_differently(tmp_path):
    scene = scene_of(tmp_path, _boxes("0.8 0.8 0.8", "0.8 0.8 0.8"))
    image = pixels(picture.png([Layer(scene)], PictureOptions("iso", (64, 64))))
    shades = {tuple(p) for p in image.reshape(-1, 3) if tuple(p) != (255, 255, 255)}
    assert len(shades) >= 3  # three visible faces, three intensities, all grey
    assert all(r == g == b for r, g, b in shades)


def test_views_project_along_their_axes(tmp_path):
    scene = scene_of(tmp_path, ROBOT)  # taller (z) than deep (x) or wide (y)

    def extent(view):
        image = pixels(picture.png([Layer(scene)], PictureOptions(view, (100, 100))))
        rows, columns = np.nonzero((image != 255).any(axis=-1))
        return np.ptp(columns) + 1, np.ptp(rows) + 1

    width, height = extent("front")
    assert height > width  # upright
    width, height = extent("top")  # x up the screen, y across: 0.4 m by 0.3 m
    assert height > width


def test_highlighted_links_are_red(tmp_path):
    scene = scene_of(tmp_path, ROBOT)
    plain = pixels(picture.png([Layer(scene)], SMALL))
    painted = pixels(picture.png([Layer(scene, highlight={"arm"})], SMALL))
    def red(image):
        return ((image[..., 0] > 120) & (image[..., 1] < 60) & (image[..., 2] < 60)).sum()
    blue_before = ((plain[..., 2] > 120) & (plain[..., 0] < 60)).sum()
    assert blue_before > 50 and red(painted) > red(plain) + 50


def test_two_layers_blend_where_they_overlap(tmp_path):
    old = scene_of(tmp_path, ROBOT)
    new = scene_of(tmp_path, ROBOT, {"j1": "1.2"})
    image = pixels(picture.png([Layer(old, tint=picture.OLD, label="old"),
                                Layer(new, tint=picture.NEW, label="new")],
                               PictureOptions("front", (120, 120))))
    blue = (image[..., 2] > image[..., 0] + 60)  # the old arm alone
    orange = (image[..., 0] > image[..., 2] + 60) & (image[..., 1] < 160)  # the new arm alone
    assert blue.sum() > 30 and orange.sum() > 30


def test_svg_names_links_on_hover_and_draws_frames(tmp_path):
    text = picture.svg([Layer(scene_of(tmp_path, ROBOT), label="toy")],
                       PictureOptions("iso", (200, 200), frames=True, axes=True))
    assert text.startswith("<svg") and text.rstrip().endswith("</svg>")
    for link in ("base", "arm", "head"):
        assert f"<g><title>{link}</title>" in text
    assert text.count("<polygon") > 50
    # three lines per link frame, one per moving joint axis
    assert text.count("<line") == 3 * 3 + 1


def test_write_refuses_other_suffixes(tmp_path):
    with pytest.raises(picture.PlotError, match=r"\.png or \.svg"):
        picture.write(tmp_path / "x.jpg", [Layer(scene_of(tmp_path, ROBOT))])


def test_faces_turned_away_are_left_out_without_changing_the_picture(tmp_path):
    import dataclasses

    scene = scene_of(tmp_path, ROBOT, {"j1": "0.6"})
    unknown = dataclasses.replace(scene, facing=None)
    camera = picture._camera([Layer(scene)], "iso", 96, 96)
    assert len(picture._project(Layer(scene), camera).colours) < \
        0.7 * len(picture._project(Layer(unknown), camera).colours)
    # the same but along edges, where a hidden face's border pixels showed through
    difference = np.abs(pixels(picture.png([Layer(scene)], SMALL))
                        - pixels(picture.png([Layer(unknown)], SMALL)))
    assert difference.mean() < 1.0 and (difference.max(axis=-1) > 0).mean() < 0.02


def _flat_scene(triangles, colours, links=("a", "b")):
    """A scene of bare triangles (world corners [n, 3, 3], rgb [n, 3] in [0, 1]), one link
    each, open surfaces (no face left out)."""
    from urdftool.kinematics.scene import PosedScene

    triangles = np.asarray(triangles, dtype=float)
    return PosedScene(list(links), triangles, np.arange(len(triangles)),
                      np.asarray(colours, dtype=float), {}, [], facing=None)


RED, GREEN = (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)
# Seen from the front (looking along -x: screen x is y, up is z, nearer is larger x): two
# triangles with the same outline that cut through each other along y = 0. The red one leans
# (x = y), the green one stands at x = 0: left of the cut green is nearer, right of it red.
# Their mean depths are equal, so the painter's order puts one over the other everywhere.
CROSSING = [[(-1, -1, -1), (1, 1, -1), (0, 0, 1)],
            [(0, -1, -1), (0, 1, -1), (0, 0, 1)]]


def _reddish(pixel) -> bool:
    return pixel[0] > 2 * pixel[1] + 20


def _greenish(pixel) -> bool:
    return pixel[1] > 2 * pixel[0] + 20


def test_a_depth_buffer_shows_each_part_where_it_is_nearer():
    """Two triangles that cut into each other: each shows on its own side of the cut (the
    painter's order showed one of them whole; the old renderer never split these: each side
    is under 40 px)."""
    scene = _flat_scene(CROSSING, [RED, GREEN])
    image = pixels(picture.png([Layer(scene)], PictureOptions("front", (32, 32))))
    row = image[20]
    reds = [x for x in range(32) if _reddish(row[x])]
    greens = [x for x in range(32) if _greenish(row[x])]
    assert reds and greens, row
    assert max(greens) < min(reds)  # green on the left of the cut, red on the right


def test_zbuffer_resolves_depth_per_pixel_and_keys_give_the_drawing_order():
    corners = np.array([[(0, 0), (8, 0), (0, 8)], [(0, 0), (8, 0), (0, 8)]], dtype=float)
    depths = np.array([[0, 0, 0], [1, 1, 1]], dtype=float)  # the second is nearer
    shown = picture.zbuffer(corners, depths, 8, 8)
    assert shown[1, 1] == 1 and shown[7, 7] == -1  # outside both: background
    drawn_last = picture.zbuffer(corners, depths, 8, 8, keys=np.array([1.0, 0.0]))
    assert drawn_last[1, 1] == 0  # as painted, first key largest: the first triangle


def _every_pixel(corners, depths, size: int) -> np.ndarray:
    """The depth buffer the plain way: every triangle tested at every pixel centre, the
    nearest kept, the first listed of those as near (the rasteriser's inside test)."""
    shown = np.full((size, size), -1)
    best = np.full((size, size), -np.inf)
    cy, cx = np.mgrid[0:size, 0:size] + 0.5
    for i, ((a, b, c), d) in enumerate(zip(corners, depths)):
        area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        if not abs(area) > 1e-12:
            continue
        wa = ((c[0] - b[0]) * (cy - b[1]) - (c[1] - b[1]) * (cx - b[0])) * (1.0 / area)
        wb = ((a[0] - c[0]) * (cy - c[1]) - (a[1] - c[1]) * (cx - c[0])) * (1.0 / area)
        wc = 1.0 - wa - wb
        depth = wa * d[0] + wb * d[1] + wc * d[2]
        inside = (wa >= -1e-9) & (wb >= -1e-9) & (wc >= -1e-9) & (depth > best)
        best[inside], shown[inside] = depth[inside], i
    return shown


@pytest.mark.parametrize("seed", range(4))
def test_the_rasteriser_tests_each_triangles_own_pixels_and_finds_what_every_pixel_shows(seed):
    """attack27's 2,000 overlapping triangles across a 600 x 600 picture: each triangle tested
    every pixel of its box rounded up to powers of two (7 times the pixels the triangles
    cover), then the samples were sorted by pixel and depth (three quarters of what was
    left): 15.7 s for a PNG. Each triangle's own pixels are tested, row by row, and each
    pixel keeps its nearest without a sort: what every pixel shows is as before (against
    every triangle tested at every pixel; edges through pixel centres, thin and tiny
    triangles among them), and the tests are the pixels covered, a row's two ends more."""
    draw = np.random.default_rng(seed)
    size = 40
    corners = draw.uniform(-10, size + 10, (60, 3, 2))
    corners[:10] = np.round(corners[:10])  # (corners on pixel edges: centres on some sides)
    corners[10:20, 1] = corners[10:20, 0] + draw.uniform(-0.3, 0.3, (10, 2))  # thin ones
    corners[20:25] = corners[20:25, :1] + draw.uniform(0, 0.8, (5, 3, 2))  # under a pixel
    depths = draw.uniform(0, 1, (60, 3))
    depths[30:40] = depths[20:30]  # (ties: the first listed wins)
    corners[30:40] = corners[20:30]
    assert (picture.zbuffer(corners, depths, size, size) ==
            _every_pixel(corners, depths, size)).all()
    big = np.array([[(0.2, 0.2), (600, 0.2), (0.2, 600)]])  # half of a 600 x 600 picture
    assert picture.raster_tests(big, 600, 600) <= 600 * 601 / 2 + 2 * 600


def _svg_pixels(text: str, size: int) -> np.ndarray:
    """What a renderer shows at each pixel centre for the polygons and rectangles of an SVG
    picture, in the order written (later over earlier): enough to check what it draws."""
    import re

    shapes = re.findall(r'<(polygon) points="([^"]+)" fill="#([0-9a-f]{6})"'
                        r'|<(rect) x="(\d+)" y="(\d+)" width="(\d+)" height="(\d+)" '
                        r'fill="#([0-9a-f]{6})"', text)
    image = np.full((size, size, 3), 255.0)
    for shape in shapes:
        if shape[0] == "polygon":
            corners = np.array([[float(v) for v in point.split(",")]
                                for point in shape[1].split()])[None]
            shown = picture.zbuffer(corners, np.zeros((1, 3)), size, size) >= 0
            colour = shape[2]
        else:
            x, y, w, h = (int(v) for v in shape[4:8])
            shown = np.zeros((size, size), dtype=bool)
            shown[y:y + h, x:x + w] = True
            colour = shape[8]
        image[shown] = [int(colour[i:i + 2], 16) for i in (0, 2, 4)]
    return image


def test_svg_draws_crossing_parts_as_the_depth_buffer_does():
    """Where no drawing order is right (parts that cut into each other), the SVG shows what the
    depth buffer shows: green left of the cut, red right of it (it drew green over red)."""
    scene = _flat_scene(CROSSING, [RED, GREEN])
    options = PictureOptions("front", (32, 32))
    drawn = _svg_pixels(picture.svg([Layer(scene)], options), 32)
    row = drawn[20]
    reds = [x for x in range(32) if _reddish(row[x])]
    greens = [x for x in range(32) if _greenish(row[x])]
    assert reds and greens and max(greens) < min(reds), row
    assert (drawn == pixels(picture.png([Layer(scene)], options))).all(axis=-1).mean() > 0.97


def test_svg_triangles_are_outlined_in_their_colour_so_no_seam_shows(tmp_path):
    """Anti-aliasing leaves the background showing along every edge two triangles share
    unless each triangle's outline covers it: a stroke of the fill's colour, at least a pixel
    wide (half on each side of the edge); 0.3 px left visible seams."""
    import re

    text = picture.svg([Layer(scene_of(tmp_path, ROBOT))], PictureOptions("iso", (200, 200)))
    polygons = re.findall(r"<polygon [^>]*/>", text)
    assert len(polygons) > 50
    for polygon in polygons:
        fill = re.search(r'fill="([^"]+)"', polygon).group(1)
        assert f'stroke="{fill}"' in polygon
        assert float(re.search(r'stroke-width="([^"]+)"', polygon).group(1)) >= 1.0


def test_svg_leaves_out_what_is_hidden(tmp_path):
    """From the front the near box hides the far one: the SVG has none of the far box's
    triangles (they were drawn and painted over)."""
    scene = scene_of(tmp_path, _boxes("0 1 0", "1 0 1"))
    text = picture.svg([Layer(scene)], PictureOptions("front", (64, 64)))
    assert "<title>back</title>" not in text and "<title>front</title>" in text


def test_svg_of_many_overlapping_triangles_holds_no_list_of_every_pixel_each_covers():
    """attack26: the SVG's drawing order held every (pixel, triangle) each triangle covers at
    once: 2,500 overlapping triangles of an OBJ (100 KB) in a 600 x 600 picture, about 10^8
    pairs, ran out of the 2 GiB budget (U018). The pairs of a triangle hidden by another are
    gathered chunk by chunk and kept unique: here 300 triangles at 200 x 200, each covering
    a third of the picture, peaked at 220 MB; now at the rasteriser's own chunk (~50 MB),
    however many triangles overlap."""
    import tracemalloc

    count = 300
    shift = np.linspace(0, 0.2, count)[:, None, None] * np.array([1.0, 1.0, 0.0])
    triangles = np.array([[(0, -1, -1), (0, 1, -1), (0, 0, 1)]]) + shift  # nearer each time
    scene = _flat_scene(triangles, [RED] * count, links=[f"l{i}" for i in range(count)])
    tracemalloc.start()
    try:
        text = picture.svg([Layer(scene)], PictureOptions("front", (200, 200)))
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert text.count("<polygon") >= 1
    assert peak < 96 * 2 ** 20, peak


def _soup(count: int, seed: int = 5):
    """``count`` large triangles of random corners in a unit cube, overlapping each other
    across the picture, a link each (a mesh of many overlapping triangles)."""
    draw = np.random.default_rng(seed)
    triangles = draw.uniform(-0.5, 0.5, (count, 3, 3))
    colours = draw.uniform(0.2, 1.0, (count, 3))
    return _flat_scene(triangles, colours, links=[f"l{i}" for i in range(count)])


def _counting_tests(monkeypatch) -> list[int]:
    """The pixel tests of every rasteriser chunk, appended as :func:`picture._cover` runs."""
    tested = []
    cover = picture._cover

    def counted(spans, first, last, *rest):
        tested.append(int(spans.counts[first:last].sum()))
        return cover(spans, first, last, *rest)

    monkeypatch.setattr(picture, "_cover", counted)
    return tested


def test_svg_orders_and_paints_only_the_triangles_that_show(monkeypatch):
    """Triangles the depth buffer shows nowhere cannot change a pixel: they went through the
    rasteriser's three more passes (the drawing order, the painted picture twice) with the
    others. Behind a wall, 150 triangles are tested once; the picture is unchanged."""
    wall = [[(1, -2, -2), (1, 2, -2), (1, 0, 2)]]  # nearer (larger x) than the whole soup
    soup = _soup(150)
    scene = _flat_scene(np.concatenate([wall, soup.triangles]),
                        np.concatenate([[RED], soup.colours]),
                        links=["wall", *soup.links])
    options = PictureOptions("front", (64, 64))
    tested = _counting_tests(monkeypatch)
    text = picture.svg([Layer(scene)], options)
    camera = picture._camera([Layer(scene)], "front", 64, 64)
    drawn = picture._project(Layer(scene), camera)
    once = picture.raster_tests(drawn.corners, 64, 64)
    wall_tests = picture.raster_tests(drawn.corners[:1], 64, 64)
    assert sum(tested) <= once + 3 * wall_tests, (sum(tested), once, wall_tests)
    assert text.count("<polygon") == 1 and "<title>wall</title>" in text
    assert (_svg_pixels(text, 64) == pixels(picture.png([Layer(scene)], options))).all(
        axis=-1).mean() > 0.97


def test_svg_of_triangles_too_many_to_order_is_the_depth_buffers_pixels(monkeypatch, tmp_path,
                                                                        run_cli):
    """attack27: 2,000 triangles of a mesh overlapping across a 600 x 600 picture took 58 s
    (four passes of the rasteriser over some 10^8 pixel tests each, and their order), past the
    60 s budget, where the PNG took 17 s. Past SVG_ORDER_TESTS the layer is the depth buffer's
    pixels, as the PNG's, in one pass, and the picture and the command say so; under it, the
    polygons as before."""
    scene = _soup(40)
    options = PictureOptions("front", (48, 48))
    ordered = picture.svg([Layer(scene)], options)
    assert "<polygon" in ordered and "<desc>" not in ordered
    monkeypatch.setattr(picture, "SVG_ORDER_TESTS", 1000)
    tested = _counting_tests(monkeypatch)
    text, notes = picture.svg_noted([Layer(scene)], options)
    drawn = picture._project(Layer(scene), picture._camera([Layer(scene)], "front", 48, 48))
    assert sum(tested) == picture.raster_tests(drawn.corners, 48, 48)  # one pass
    assert "<polygon" not in text and (_svg_pixels(text, 48) == pixels(
        picture.png([Layer(scene)], options))).all()
    [note] = notes
    assert "drawn as the pixels of the depth buffer" in note and f"<desc>{note}</desc>" in text
    # said by the command
    import struct

    stl = tmp_path / "soup.stl"  # (a binary STL of the same triangles)

    stl.write_bytes(b"\0" * 80 + struct.pack("<I", len(scene.triangles)) + b"".join(
        struct.pack("<12fH", 0, 0, 0, *triangle.ravel(), 0) for triangle in scene.triangles))
    robot = tmp_path / "soup.urdf"
    robot.write_text('<robot name="soup"><link name="base"><visual><geometry><mesh '
                     'filename="soup.stl"/></geometry></visual></link></robot>')
    result = run_cli("render", robot, "-o", tmp_path / "soup.svg", "--size", "48x48")
    assert result.exit_code == 0, result.output
    assert "warning: " in result.stderr and "drawn as the pixels of the depth buffer" in \
        result.stderr, result.stderr
