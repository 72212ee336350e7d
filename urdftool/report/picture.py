"""Pictures of posed robots: PNG with numpy and Pillow, SVG written directly. Headless: no GPU,
no display, no OpenGL.

An orthographic camera looks along one of :data:`VIEWS`. Each triangle is shaded flat (Lambert,
a fixed light over the viewer's shoulder, lit on both sides so that meshes wound either way
look the same); faces of closed surfaces turned away from the viewer are left out (hidden
anyway).

Which triangle a pixel shows is decided by a depth buffer (:func:`zbuffer`, numpy): the nearest
at the pixel's centre, so that parts which cut into each other meet along their intersection
(drawing whole triangles far to near, the painter's order, gave saw-tooth edges there); its
work is linear in the pixels the triangles cover (each triangle's own pixels, row by row, and
each pixel's nearest kept without a sort). PNG
is that buffer's colours. SVG is vector: the triangles that show anywhere, outlined in their
own colour (no seams where a renderer's anti-aliasing leaves background between them), in an
order taken from the depth buffer (a triangle after every triangle it hides), and, where no
order is right (parts that cut into each other), the pixels the depth buffer shows.

A picture is made of layers (:class:`Layer`): one scene in its own colours, a scene with some
links painted (colliding pairs), or, for a comparison, two scenes tinted in two colours, grey
where both cover the same pixels, so that what moved shows in one colour alone.
"""

from __future__ import annotations

import io
import math
from dataclasses import dataclass, field

from urdftool.errors import PlotError
from urdftool.report.escape import svg as escape

VIEWS = ("front", "side", "top", "iso")
# (towards the viewer, up on the screen) in the robot's root frame: x forward, z up
_CAMERAS = {"front": ((1.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
            "side": ((0.0, -1.0, 0.0), (0.0, 0.0, 1.0)),
            "top": ((0.0, 0.0, 1.0), (1.0, 0.0, 0.0)),
            "iso": ((1.0, -0.8, 0.7), (0.0, 0.0, 1.0))}
BACKGROUND = (255, 255, 255)
HIGHLIGHT = (0.86, 0.1, 0.1)  # rgb of painted links (colliding pairs)
OLD, NEW = (0.15, 0.4, 0.85), (0.95, 0.45, 0.05)  # the two sides of a comparison
AMBIENT = 0.35
MARGIN = 0.06  # of the picture's size, around the robot
SVG_MIN_AREA = 0.05  # [px^2] triangles smaller than this are left out of an SVG
# [pixel tests] of the triangles an SVG layer draws (each tests its own pixels, row by row:
# 3 passes of the rasteriser order them), past which the layer is drawn as the depth buffer's
# pixels instead, in one pass as a PNG is (said in the picture and by the command): 2,000
# triangles of a mesh overlapping across a 600 x 600 picture took 58 s, past the 60 s budget,
# when each tested its box of powers of two; tested so, they are 1e7 tests (852 of them show)
# and ordered in about 10 s, 10,000 of them 2.8e7 in about 26 s; a robot's meshes test ~5e5
SVG_ORDER_TESTS = 2 ** 25


@dataclass(frozen=True)
class Detail:
    """For a comparison whose change is too small to see at the picture's scale: a magnified
    inset of where the layers differ most, in a corner, its place in the picture outlined.

    size: how far the change moves things in [m] (the inset magnifies it to about VISIBLE
        pixels); 0 when unknown (then measured on the picture: the width of what differs)
    label: what changed, written in the inset (``l_forearm_link moved 4 mm``)
    """

    size: float = 0.0
    label: str = ""


VISIBLE = 24.0  # [px] a change is shown at least this wide, magnified when smaller
MAX_ZOOM = 16.0
INSET = 0.42  # the inset's side, of the picture's smaller side


@dataclass(frozen=True)
class PictureOptions:
    """How to draw: ``view`` one of VIEWS, ``size`` (width, height) in pixels, link frames
    (x red, y green, z blue) and joint axes (magenta) drawn over the geometry or not, and for a
    comparison the ``detail`` (:class:`Detail`) to magnify, if any."""

    view: str = "iso"
    size: tuple[int, int] = (600, 600)
    frames: bool = False
    axes: bool = False
    detail: Detail | None = None


@dataclass
class Layer:
    """A posed scene (urdftool.kinematics.scene.PosedScene) to draw.

    tint: one rgb in [0, 1] for every triangle (a side of a comparison), else its own colours
    highlight: links painted ``HIGHLIGHT`` (e.g. colliding pairs)
    label: what the layer is, for the SVG and the legend
    """

    scene: object
    tint: tuple | None = None
    highlight: set[str] = field(default_factory=set)
    label: str = ""


@dataclass
class _Drawn:
    """A layer projected: pixel corners ``[n, 3, 2]``, their depths ``[n, 3]`` (larger is
    nearer), rgb ``[n, 3]`` 0-255, owners ``[n]`` indexing ``links``."""

    corners: object
    depths: object
    colours: object
    owners: object
    links: list[str]


class _Camera:
    def __init__(self, view: str, points, width: int, height: int):
        import numpy as np

        if view not in _CAMERAS:
            raise PlotError(f"view must be one of {', '.join(VIEWS)}, not '{view}'")
        toward, up = (np.array(v, dtype=float) for v in _CAMERAS[view])
        toward /= np.linalg.norm(toward)
        right = np.cross(up, toward)
        right /= np.linalg.norm(right)
        up = np.cross(toward, right)
        self.rotation = np.stack([right, up, toward])  # rows: screen x, screen y, depth
        self.light = 0.75 * toward + 0.55 * up - 0.35 * right
        self.light /= np.linalg.norm(self.light)
        self.width, self.height = width, height
        flat = self.rotation[:2] @ np.asarray(points, dtype=float).reshape(-1, 3).T \
            if len(points) else np.zeros((2, 1))
        low, high = flat.min(axis=1), flat.max(axis=1)
        span = np.maximum(high - low, 1e-6)
        usable = np.array([width, height]) * (1 - 2 * MARGIN)
        self.scale = float(min(usable / span))
        self.centre = (low + high) / 2

    def screen(self, points):
        """``[..., 3]``: pixel x, pixel y (down) and depth (larger is nearer) of points
        ``[..., 3]``; one affine map, so a triangle's midpoints map to its image's."""
        import numpy as np

        mapped = points @ self.rotation.T
        mapped[..., 0] = self.width / 2 + (mapped[..., 0] - self.centre[0]) * self.scale
        mapped[..., 1] = self.height / 2 - (mapped[..., 1] - self.centre[1]) * self.scale
        return np.asarray(mapped)

    def pixels(self, points):
        """Pixel coordinates ``[..., 2]`` of points ``[..., 3]`` (y down)."""
        return self.screen(points)[..., :2]

    def zoomed(self, x: float, y: float, factor: float, side: int) -> "_Camera":
        """A camera ``factor`` times closer, ``side`` pixels square, centred on this one's
        pixel (x, y)."""
        import copy

        import numpy as np

        other = copy.copy(self)
        other.centre = np.array([self.centre[0] + (x - self.width / 2) / self.scale,
                                 self.centre[1] - (y - self.height / 2) / self.scale])
        other.scale = self.scale * factor
        other.width = other.height = side
        return other


def _camera(layers: list[Layer], view: str, width: int, height: int) -> _Camera:
    import numpy as np

    points = [layer.scene.triangles.reshape(-1, 3) for layer in layers]
    points += [np.array([pose[:3, 3] for pose in layer.scene.frames.values()]).reshape(-1, 3)
               for layer in layers]
    return _Camera(view, np.concatenate(points), width, height)


def _project(layer: Layer, camera: _Camera) -> _Drawn:
    """The layer's triangles shaded and projected (closed surfaces' faces turned away left
    out), in the scene's order."""
    import numpy as np

    scene = layer.scene
    triangles = scene.triangles
    normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    lengths = np.linalg.norm(normals, axis=1)
    keep = lengths > 0
    if scene.facing is not None:  # faces of closed surfaces turned away: hidden anyway
        keep &= scene.facing * (normals @ camera.rotation[2]) >= 0
    triangles, normals, lengths = triangles[keep], normals[keep], lengths[keep]
    intensity = AMBIENT + (1 - AMBIENT) * np.abs(normals @ camera.light) / lengths
    if layer.tint is not None:
        base = np.tile(np.asarray(layer.tint, dtype=float), (len(triangles), 1))
    else:
        base = scene.colours[keep].copy()
    owners = scene.owners[keep]
    if layer.highlight:
        painted = np.isin(owners, [i for i, name in enumerate(scene.links)
                                   if name in layer.highlight])
        base[painted] = HIGHLIGHT
    colours = np.clip(base * intensity[:, None] * 255, 0, 255).astype(np.uint8)
    screen = camera.screen(triangles)
    return _Drawn(screen[..., :2], screen[..., 2], colours, owners, scene.links)


def _visibility_order(drawn: _Drawn, shown, width: int, height: int):
    """Indices of the triangles in an order to draw them far to near: a triangle comes after
    every triangle it hides at some pixel of the depth buffer (``shown``, flat), else by mean
    depth (the painter's order). Parts that cut into each other hide each other in turn; such
    a cycle is broken at its farthest triangle, and the pixels it gets wrong are drawn again
    from the depth buffer."""
    import heapq

    import numpy as np

    n = len(drawn.corners)
    mean = drawn.depths.sum(axis=1)
    hidden = _HiddenPairs(shown, n)
    zbuffer(drawn.corners, drawn.depths, width, height, covered=hidden)
    pairs = hidden.pairs()
    if not len(pairs):
        return np.argsort(mean, kind="stable")
    before, after = pairs // n, pairs % n  # before is hidden by after somewhere
    waiting = np.bincount(after, minlength=n)  # triangles to draw before each one
    following = np.split(after[np.argsort(before, kind="stable")],
                         np.cumsum(np.bincount(before, minlength=n))[:-1])
    ready = [(float(mean[i]), int(i)) for i in np.flatnonzero(waiting == 0)]
    heapq.heapify(ready)
    stuck = sorted(range(n), key=lambda i: (mean[i], i))  # for breaking cycles, farthest first
    done = np.zeros(n, dtype=bool)
    order = []
    position = 0
    while len(order) < n:
        if ready:
            _, i = heapq.heappop(ready)
            if done[i]:
                continue
        else:  # a cycle: the farthest triangle left goes first
            while done[stuck[position]]:
                position += 1
            i = stuck[position]
        done[i] = True
        order.append(i)
        for j in following[i].tolist():
            waiting[j] -= 1
            if waiting[j] == 0 and not done[j]:
                heapq.heappush(ready, (float(mean[j]), j))
    return np.array(order, dtype=np.int64)


class _HiddenPairs:
    """The pairs ``hidden * n + front`` of triangles where ``front`` shows (``shown``, the depth
    buffer, flat) at a pixel that ``hidden`` covers too, gathered chunk by chunk as
    :func:`zbuffer` covers them and kept unique as they come: the pixels every triangle covers
    are never held at once (2,500 triangles that overlap across a 600 x 600 picture cover
    about 10^8 pixels: the SVG ran out of memory)."""

    _MERGE = 1 << 22  # pairs gathered before they are made unique together

    def __init__(self, shown, n: int):
        self.shown, self.n, self.parts, self.size = shown, n, [], 0

    def __call__(self, pixel, triangles) -> None:
        import numpy as np

        front = self.shown[pixel]
        behind = (triangles != front) & (front >= 0)
        part = np.unique(triangles[behind] * self.n + front[behind])
        self.parts.append(part)
        self.size += len(part)
        if self.size > self._MERGE and len(self.parts) > 1:
            self.parts = [self.pairs()]
            self.size = len(self.parts[0])

    def pairs(self):
        import numpy as np

        return np.unique(np.concatenate(self.parts)) if self.parts else np.zeros(0, np.int64)


def zbuffer(corners, depths, width: int, height: int, keys=None, covered=None):
    """Which triangle each pixel shows: ``[height, width]`` indices into ``corners``
    (``[n, 3, 2]`` pixel positions, y down), -1 where none covers the pixel's centre.

    A pixel shows the triangle nearest at its centre (``depths [n, 3]`` at the corners,
    larger is nearer, interpolated over the triangle: exact for the orthographic camera), so
    parts that cut into each other meet along their true intersection. ``keys [n]``: one
    depth per triangle instead (a drawing order: the largest key wins, as the last painted).
    A pixel centre on an edge two triangles share is covered by both (no cracks); on a tie
    the triangle listed first wins. ``covered``: called chunk by chunk with the
    ``(pixels, triangles)`` of every pixel centre each triangle covers, hidden or not.

    The pixels tested are each triangle's own, row by row (:func:`_spans`), not its box: a
    large triangle tested every pixel of its box rounded up to powers of two, some four times
    its area (2,000 overlapping triangles of a mesh across a 600 x 600 picture: 15.7 s).
    """
    import numpy as np

    n = len(corners)
    buffer = np.full(width * height, -np.inf)
    index = np.full(width * height, -1, dtype=np.int64)
    if n == 0:
        return index.reshape(height, width)
    spans = _spans(corners, width, height)
    for first, last in _chunks(spans.counts):
        _cover(spans, first, last, corners, depths, width, keys, buffer, index, covered)
    return index.reshape(height, width)


_RASTER_CHUNK = 1 << 19  # pixel tests at a time [samples]
_EDGE = -1e-9  # a pixel centre this far outside an edge (in barycentric weight) is inside


class _Spans:
    """The pixels whose centres a rasteriser tests for triangles: for each (triangle, row)
    pair, the triangle's row ``rows`` and its first column ``starts`` and how many ``counts``
    (one more on each side than the row's crossing of the triangle, so that no centre the
    test takes is left out by the rounding of the crossing), and each triangle's signed
    doubled ``area``."""

    def __init__(self, triangles, rows, starts, counts, area):
        self.triangles, self.rows, self.starts, self.counts, self.area = \
            triangles, rows, starts, counts, area


def _spans(corners, width: int, height: int) -> _Spans:
    """Each triangle's pixels row by row: where the row of pixel centres crosses it, as the
    inside test (:func:`_cover`) decides, widened by a pixel on each side and kept within the
    triangle's box of the picture. A triangle of no area or wholly outside has none."""
    import numpy as np

    a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]
    area = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    low = np.floor(corners.min(axis=1) - 0.5) + 1  # the first pixel whose centre may be inside
    high = np.floor(corners.max(axis=1) - 0.5)
    low = np.maximum(low, 0).astype(np.int64)
    high = np.minimum(high, [width - 1, height - 1]).astype(np.int64)
    span = high - low + 1
    usable = np.flatnonzero(np.isfinite(area) & (np.abs(area) > 1e-12) & (span > 0).all(axis=1))
    heights = span[usable, 1]
    triangles = np.repeat(usable, heights)
    rows = np.repeat(low[usable, 1], heights) + _ramps(heights)
    # each weight along the row, w = slope * cx + w0 (_cover's weights at cy, as cx varies)
    cy = rows + 0.5
    inverse = 1.0 / area[triangles]
    ta, tb, tc = (corners[triangles, i] for i in range(3))
    slope_a = -(tc[:, 1] - tb[:, 1]) * inverse
    slope_b = -(ta[:, 1] - tc[:, 1]) * inverse
    w0_a = ((tc[:, 0] - tb[:, 0]) * (cy - tb[:, 1]) + (tc[:, 1] - tb[:, 1]) * tb[:, 0]) * inverse
    w0_b = ((ta[:, 0] - tc[:, 0]) * (cy - tc[:, 1]) + (ta[:, 1] - tc[:, 1]) * tc[:, 0]) * inverse
    lo = np.full(len(rows), -np.inf)
    hi = np.full(len(rows), np.inf)
    for slope, w0 in ((slope_a, w0_a), (slope_b, w0_b), (-slope_a - slope_b, 1.0 - w0_a - w0_b)):
        with np.errstate(divide="ignore", invalid="ignore"):
            bound = (_EDGE - w0) / slope
        lo = np.where(slope > 0, np.maximum(lo, bound), lo)
        hi = np.where(slope < 0, np.minimum(hi, bound), hi)
        hi = np.where((slope == 0) & (w0 < _EDGE), -np.inf, hi)  # (a row beside an edge)
    first = np.ceil(np.clip(lo, -1.0, width + 1.0) - 0.5) - 1  # (centres x + 0.5 in [lo, hi])
    last = np.floor(np.clip(hi, -2.0, width + 1.0) - 0.5) + 1
    first = np.maximum(first, low[triangles, 0]).astype(np.int64)
    last = np.minimum(last, high[triangles, 0]).astype(np.int64)
    counts = np.maximum(last - first + 1, 0)
    return _Spans(triangles, rows, first, counts, area)


def _ramps(counts):
    """0, 1, ... count - 1 for each of ``counts``, one after another."""
    import numpy as np

    return np.arange(int(counts.sum())) - np.repeat(np.cumsum(counts) - counts, counts)


def _chunks(counts) -> list[tuple[int, int]]:
    """(first, last) ranges of the pairs whose pixels (``counts`` each) are tested together:
    about :data:`_RASTER_CHUNK` at a time, a pair at least."""
    import numpy as np

    ends = np.cumsum(counts)
    chunks, first = [], 0
    while first < len(counts):
        done = ends[first - 1] if first else 0
        last = max(int(np.searchsorted(ends, done + _RASTER_CHUNK, side="right")), first + 1)
        chunks.append((first, last))
        first = last
    return chunks


def raster_tests(corners, width: int, height: int) -> int:
    """How many pixel centres :func:`zbuffer` tests for the triangles ``corners`` ``[n, 3,
    2]``: each its own pixels, row by row (:func:`_spans`)."""
    if not len(corners):
        return 0
    return int(_spans(corners, width, height).counts.sum())


def _cover(spans: _Spans, first: int, last: int, corners, depths, width: int, keys, buffer,
           index, covered) -> None:
    """Rasterise the pixels of the pairs ``first:last`` of ``spans`` into the depth ``buffer``
    and the ``index`` of the triangle each pixel shows. What holds along a row is taken once
    per pair and repeated for its pixels."""
    import numpy as np

    triangles, counts = spans.triangles[first:last], spans.counts[first:last]
    cy = spans.rows[first:last] + 0.5
    a, b, c = (corners[triangles, i] for i in range(3))
    px = np.repeat(spans.starts[first:last], counts)
    px += _ramps(counts)
    cx = px + 0.5
    inverse = np.repeat(1.0 / spans.area[triangles], counts)

    def weight(one, two):
        """((two - one) across (cy - one's y) - (two - one) down (cx - one's x)) / area, as
        the row's terms repeated for its pixels, in place (the chunk's largest arrays)."""
        term = cx - np.repeat(one[:, 0], counts)
        term *= np.repeat(two[:, 1] - one[:, 1], counts)
        weight = np.repeat((two[:, 0] - one[:, 0]) * (cy - one[:, 1]), counts)
        weight -= term
        weight *= inverse
        return weight

    # barycentric weights of the pixel centre: of a, of b, of c
    wa, wb = weight(b, c), weight(c, a)
    wc = 1.0 - wa - wb
    inside = np.flatnonzero((wa >= _EDGE) & (wb >= _EDGE) & (wc >= _EDGE))
    if not len(inside):
        return
    pair = np.repeat(np.arange(len(counts)), counts)[inside]
    triangles = triangles[pair]
    if keys is None:
        d = depths[triangles]
        depth = wa[inside] * d[:, 0] + wb[inside] * d[:, 1] + wc[inside] * d[:, 2]
    else:
        depth = keys[triangles].astype(float)
    pixel = spans.rows[first:last][pair] * width + px[inside]
    if covered is not None:
        covered(pixel, triangles)
    # the nearest sample per pixel, the first listed of those as near: the buffer takes the
    # nearest (fmax: a depth that is not a number never wins), then where it came nearer here
    # the pixel's triangle is forgotten and the least of those as near as it is kept (a sort
    # of the samples by pixel and depth was three quarters of the time)
    before = buffer[pixel]
    np.fmax.at(buffer, pixel, depth)
    now = buffer[pixel]
    nearest = depth == now
    index[pixel[nearest & (now > before)]] = len(corners)  # (more than any triangle)
    np.minimum.at(index, pixel[nearest], triangles[nearest])


def _colour_image(drawn: _Drawn, shown):
    """RGB pixels ``[height, width, 3]`` of the triangles ``shown`` (from :func:`zbuffer`)."""
    import numpy as np

    image = np.empty(shown.shape + (3,), dtype=np.uint8)
    image[...] = BACKGROUND
    covered = shown >= 0
    image[covered] = drawn.colours[shown[covered]]
    return image


def _overlays(layers: list[Layer], camera: _Camera, options: PictureOptions) -> list:
    """Lines drawn over the geometry: ``(start [2], end [2], rgb, width)`` in pixels."""
    import numpy as np

    lines = []
    extent = max(camera.width, camera.height) / camera.scale  # [m] across the picture
    for layer in layers:
        if options.frames:
            length = 0.04 * extent
            for pose in layer.scene.frames.values():
                origin = pose[:3, 3]
                for column, colour in enumerate(((220, 40, 40), (40, 170, 40), (40, 70, 220))):
                    tip = origin + length * pose[:3, column]
                    lines.append((camera.pixels(origin), camera.pixels(tip), colour, 2))
        if options.axes:
            length = 0.07 * extent
            for _, point, direction in layer.scene.axes:
                start, end = point - length / 2 * direction, point + length / 2 * direction
                lines.append((camera.pixels(start), camera.pixels(end), (200, 0, 200), 3))
    return [(np.asarray(a, dtype=float), np.asarray(b, dtype=float), c, w)
            for a, b, c, w in lines]


def _composite(layers: list[Layer], camera: _Camera):
    """The layers' pixels ``[height, width, 3]`` (uint8) seen by ``camera``, and how many
    layers cover each pixel: what several layers cover is grey (their mean brightness), so
    that what only one covers stands out in its colour."""
    import numpy as np

    width, height = camera.width, camera.height
    arrays, covered = [], []
    for layer in layers:
        drawn = _project(layer, camera)
        shown = zbuffer(drawn.corners, drawn.depths, width, height)
        arrays.append(_colour_image(drawn, shown).astype(np.float32))
        covered.append(shown >= 0)
    count = np.sum(covered, axis=0)
    if len(layers) == 1:
        return arrays[0].astype(np.uint8), count
    white = np.array(BACKGROUND, dtype=np.float32)
    total = np.sum([np.where(c[..., None], a, 0) for c, a in zip(covered, arrays)], axis=0)
    pixels = np.where(count[..., None] > 0, total / np.maximum(count, 1)[..., None], white)
    # the tints are about half as bright as white: the grey is lifted back
    grey = np.repeat(np.clip(pixels.mean(axis=-1, keepdims=True) * 1.6, 0, 235), 3, axis=-1)
    pixels = np.where(count[..., None] > 1, grey, pixels)
    return pixels.astype(np.uint8), count


@dataclass
class _Inset:
    """Where a detail is magnified: the window (x, y, side) of the picture, in pixels, shown
    ``zoom`` times larger in the square at (left, top) of ``side`` pixels."""

    x: float
    y: float
    window: float
    zoom: float
    left: int
    top: int
    side: int
    camera: _Camera
    label: str


def _inset(layers: list[Layer], camera: _Camera, count, detail: Detail | None):
    """The inset that shows a comparison's small change, or None: no detail asked for, no
    difference, or one already large enough to see."""
    import numpy as np

    if detail is None or len(layers) < 2:
        return None
    differs = count == 1  # covered by one side only: what moved
    if not differs.any():
        return None
    rows, columns = np.nonzero(differs)
    if detail.size > 0:
        band = detail.size * camera.scale  # [px]
    else:  # a band's width: its area over its length
        band = differs.sum() / max(np.ptp(rows) + 1, np.ptp(columns) + 1)
    zoom = min(MAX_ZOOM, VISIBLE / max(band, 0.25))
    if zoom < 2:
        return None
    side = int(INSET * min(camera.width, camera.height))
    window = side / zoom
    # the window that holds the most of the difference (a box sum over the picture)
    step = max(1, int(window))
    sums = np.pad(differs.astype(np.int64).cumsum(0).cumsum(1), ((1, 0), (1, 0)))
    height, width_px = differs.shape
    top = np.clip(np.arange(height) - step // 2, 0, max(0, height - step))
    left = np.clip(np.arange(width_px) - step // 2, 0, max(0, width_px - step))
    bottom, right = np.minimum(top + step, height), np.minimum(left + step, width_px)
    boxes = (sums[bottom][:, right] - sums[top][:, right] - sums[bottom][:, left]
             + sums[top][:, left])
    y, x = np.unravel_index(int(np.argmax(boxes)), boxes.shape)
    x, y = float(left[x] + step / 2), float(top[y] + step / 2)
    # the corner where the inset hides least of the robot and not the window (the legend
    # takes the top left's first rows)
    margin, legend = 6, 6 + 16 * sum(1 for layer in layers if layer.tint is not None
                                     and layer.label)
    corners = [(camera.width - side - margin, camera.height - side - margin),
               (margin, camera.height - side - margin),
               (camera.width - side - margin, margin), (margin, legend + margin)]

    def cost(corner):
        left_, top_ = (max(0, int(v)) for v in corner)
        over = (left_ < x + window / 2 and x - window / 2 < left_ + side
                and top_ < y + window / 2 and y - window / 2 < top_ + side)
        return over, int((count[top_:top_ + side, left_:left_ + side] > 0).sum())

    corner = min(corners, key=cost)
    return _Inset(x, y, window, zoom, int(corner[0]), int(corner[1]), side,
                  camera.zoomed(x, y, zoom, side), detail.label)


def _inset_words(inset: _Inset) -> list[str]:
    from urdftool.numbers import number

    return [f"magnified {number(inset.zoom, 2)}x", *([inset.label] if inset.label else [])]


def rasterise(layers: list[Layer], options: PictureOptions = PictureOptions()):
    """The picture as a Pillow RGB image; where several layers overlap it is grey; a small
    change of a comparison magnified in an inset (``options.detail``)."""
    from PIL import Image, ImageDraw

    width, height = options.size
    camera = _camera(layers, options.view, width, height)
    pixels, count = _composite(layers, camera)
    image = Image.fromarray(pixels, "RGB")
    draw = ImageDraw.Draw(image)
    for start, end, colour, line_width in _overlays(layers, camera, options):
        draw.line([tuple(start), tuple(end)], fill=colour, width=line_width)
    inset = _inset(layers, camera, count, options.detail)
    if inset is not None:
        magnified, _ = _composite(layers, inset.camera)
        image.paste(Image.fromarray(magnified, "RGB"), (inset.left, inset.top))
        half = inset.window / 2
        draw.rectangle([inset.x - half, inset.y - half, inset.x + half, inset.y + half],
                       outline=(0, 0, 0))
        draw.line([(inset.x, inset.y + half if inset.top > inset.y else inset.y - half),
                   (inset.left + inset.side / 2,
                    inset.top if inset.top > inset.y else inset.top + inset.side)],
                  fill=(0, 0, 0))
        draw.rectangle([inset.left, inset.top, inset.left + inset.side - 1,
                        inset.top + inset.side - 1], outline=(0, 0, 0))
        for row, words in enumerate(_inset_words(inset)):
            draw.text((inset.left + 4, inset.top + 3 + 12 * row), words, fill=(0, 0, 0))
    _legend(draw, layers)
    return image


def _legend(draw, layers: list[Layer]) -> None:
    labelled = [layer for layer in layers if layer.tint is not None and layer.label]
    for row, layer in enumerate(labelled):
        colour = tuple(int(c * 255) for c in layer.tint)
        draw.rectangle([6, 6 + 16 * row, 18, 18 + 16 * row], fill=colour)
        draw.text((24, 6 + 16 * row), layer.label, fill=(0, 0, 0))


# [bytes] of address space each pixel of each layer takes at the drawing's peak: the humanoid
# at 600, 3000 and 5000 pixels square peaked at 483, 752 and 1,278 MB (PNG: 34 bytes a pixel
# over the 470 MB of the process and its scene), at 600 and 3000 as SVG at 488 and 849 MB (43)
PIXEL_BYTES = 44


def check_fits(size: tuple[int, int], layers: int = 1,
               smaller: str = "a smaller --size") -> None:
    """UsageError when a picture of ``size`` (width, height) [pixels] of ``layers`` would not
    fit in what this process's memory budget (its address-space cap) leaves, said before
    anything is drawn with the largest square that fits: the range of ``--size`` follows the
    budget, as a drawing out of memory (U018) after minutes would."""
    import resource

    from urdftool.budget import address_space, format_memory
    from urdftool.errors import UsageError

    cap, _ = resource.getrlimit(resource.RLIMIT_AS)
    used = address_space()
    if cap == resource.RLIM_INFINITY or used is None:
        return
    needed, left = size[0] * size[1] * PIXEL_BYTES * layers, max(cap - used, 0)
    if needed > left:
        side = math.isqrt(left // (PIXEL_BYTES * layers))
        raise UsageError(
            f"a picture of {size[0]}x{size[1]} pixels needs about {format_memory(needed)} of "
            f"memory, more than the budget of {format_memory(cap)} leaves "
            f"({format_memory(left)}: {side}x{side} at most); {smaller}, or a larger "
            "--max-memory")


def png(layers: list[Layer], options: PictureOptions = PictureOptions()) -> bytes:
    check_fits(options.size, len(layers))
    buffer = io.BytesIO()
    rasterise(layers, options).save(buffer, format="PNG", compress_level=3)  # flat colours
    # compress about as well at level 3 as at 6, in half the time
    return buffer.getvalue()


def svg(layers: list[Layer], options: PictureOptions = PictureOptions()) -> str:
    """The picture as SVG: each layer's visible triangles as polygons far to near (each run of
    one link's triangles a group whose ``<title>`` names the link, shown on hover), then, where
    that order is wrong (parts that cut into each other), the pixels the depth buffer shows.
    Each polygon is outlined in its own colour, so that no background shows through the seams
    a renderer's anti-aliasing leaves between triangles."""
    return svg_noted(layers, options)[0]


def svg_noted(layers: list[Layer], options: PictureOptions = PictureOptions()
              ) -> tuple[str, list[str]]:
    """:func:`svg`, and the notes about how it is drawn (written in it as its ``<desc>``
    too): a layer drawn as pixels (:data:`SVG_ORDER_TESTS`)."""
    check_fits(options.size, len(layers))
    width, height = options.size
    camera = _camera(layers, options.view, width, height)
    notes: list[str] = []
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="11">',
           f'<rect width="{width}" height="{height}" fill="white"/>']
    out += _svg_layers(layers, camera, notes)
    inset = None
    if options.detail is not None and len(layers) > 1:
        inset = _inset(layers, camera, _composite(layers, camera)[1], options.detail)
    if inset is not None:
        half, side = inset.window / 2, inset.side
        out.append(f'<rect x="{inset.x - half:.1f}" y="{inset.y - half:.1f}" '
                   f'width="{2 * half:.1f}" height="{2 * half:.1f}" fill="none" '
                   'stroke="black"/>')
        below = inset.top > inset.y
        out.append(f'<line x1="{inset.x:.1f}" y1="{inset.y + (half if below else -half):.1f}" '
                   f'x2="{inset.left + side / 2:.1f}" '
                   f'y2="{inset.top if below else inset.top + side:.1f}" stroke="black"/>')
        out.append(f'<svg x="{inset.left}" y="{inset.top}" width="{side}" height="{side}" '
                   f'viewBox="0 0 {side} {side}">')
        out.append(f'<rect width="{side}" height="{side}" fill="white"/>')
        out += _svg_layers(layers, inset.camera, notes)
        out.append(f'<rect x="0.5" y="0.5" width="{side - 1}" height="{side - 1}" '
                   'fill="none" stroke="black"/>')
        out += [f'<text x="4" y="{13 + 12 * row}">{escape(words)}</text>'
                for row, words in enumerate(_inset_words(inset))]
        out.append("</svg>")
    for start, end, colour, line_width in _overlays(layers, camera, options):
        out.append(f'<line x1="{start[0]:.1f}" y1="{start[1]:.1f}" x2="{end[0]:.1f}" '
                   f'y2="{end[1]:.1f}" stroke="#%02x%02x%02x" stroke-width="{line_width}"/>'
                   % colour)
    for row, layer in enumerate(l for l in layers if l.tint is not None and l.label):
        fill = "#%02x%02x%02x" % tuple(int(c * 255) for c in layer.tint)
        out.append(f'<rect x="6" y="{6 + 16 * row}" width="12" height="12" fill="{fill}"/>')
        out.append(f'<text x="24" y="{16 + 16 * row}">{escape(layer.label)}</text>')
    out.append("</svg>")
    notes = list(dict.fromkeys(notes))
    if notes:
        out.insert(1, f"<desc>{escape(' '.join(notes))}</desc>")
    return "\n".join(out) + "\n", notes


def _svg_layers(layers: list[Layer], camera: _Camera, notes: list[str]) -> list[str]:
    """Each layer's SVG group as ``camera`` sees it (see :func:`_svg_layer`)."""
    out = []
    for layer in layers:
        opacity = f' opacity="{1 / len(layers):.2f}"' if len(layers) > 1 else ""
        title = f"<title>{escape(layer.label)}</title>" if layer.label else ""
        out.append(f"<g{opacity}>{title}")
        out += _svg_layer(_project(layer, camera), camera.width, camera.height, notes)
        out.append("</g>")
    return out


def _svg_layer(drawn: _Drawn, width: int, height: int, notes: list[str]) -> list[str]:
    """One layer's SVG elements: its triangles that show anywhere (in the depth buffer), in the
    painter's order, then the corrections: runs of pixels where the painter's order shows
    another colour than the depth buffer, as rectangles drawn without anti-aliasing. Only the
    triangles that show are ordered and painted (the others cannot change a pixel): every
    triangle went through the rasteriser's three more passes. A layer whose triangles would
    cost more than :data:`SVG_ORDER_TESTS` pixel tests to order is its depth buffer's pixels
    (as the corrections are), said in ``notes``."""
    import numpy as np

    true = zbuffer(drawn.corners, drawn.depths, width, height)
    one = drawn.corners[:, 1] - drawn.corners[:, 0]
    two = drawn.corners[:, 2] - drawn.corners[:, 0]
    area = 0.5 * np.abs(one[:, 0] * two[:, 1] - one[:, 1] * two[:, 0])
    visible = np.zeros(len(drawn.corners), dtype=bool)
    visible[true[true >= 0]] = True
    shown = np.flatnonzero(visible & (area >= SVG_MIN_AREA))
    tests = raster_tests(drawn.corners[shown], width, height)
    if tests > SVG_ORDER_TESTS:
        notes.append(f"{len(shown)} triangles that show, overlapping (the rasteriser would test "
                     f"{tests} pixels to order them, over {SVG_ORDER_TESTS}): drawn as the "
                     "pixels of the depth buffer, as a PNG is, not as polygons")
        wanted = _colour_image(drawn, true)
        return _pixel_runs(wanted, true >= 0)
    order = shown[_visibility_order(_subset(drawn, shown), _among(true.reshape(-1), shown,
                                                                 len(drawn.corners)),
                                    width, height)]
    painted = _painted(drawn, order, width, height)
    # a triangle drawn over one nearer than it (parts that cut into each other) would show
    # its anti-aliased edges there: it is drawn as the pixels where it shows instead
    wrong = np.unique(painted[(painted != true) & (painted >= 0)])
    if len(wrong):
        order = order[~np.isin(order, wrong)]
        painted = _painted(drawn, order, width, height)
    out, current = [], None
    for points, colour, owner in zip(drawn.corners[order].round(1).reshape(-1, 6).tolist(),
                                     drawn.colours[order].tolist(),
                                     drawn.owners[order].tolist()):
        if owner != current:
            if current is not None:
                out.append("</g>")
            out.append(f"<g><title>{escape(drawn.links[owner])}</title>")
            current = owner
        text = " ".join(f"{x:g},{y:g}" for x, y in zip(points[::2], points[1::2]))
        fill = "#%02x%02x%02x" % tuple(colour)
        out.append(f'<polygon points="{text}" fill="{fill}" stroke="{fill}" '
                   'stroke-width="1" stroke-linejoin="round"/>')
    if current is not None:
        out.append("</g>")
    wanted, got = _colour_image(drawn, true), _colour_image(drawn, painted)
    return out + _pixel_runs(wanted, (wanted != got).any(axis=-1))


def _pixel_runs(image, mask) -> list[str]:
    """The pixels of ``image`` where ``mask`` is set, as rectangles drawn without
    anti-aliasing (:func:`_runs`)."""
    patches = _runs(image, mask)
    if not patches:
        return []
    return ['<g shape-rendering="crispEdges">',
            *(f'<rect x="{x}" y="{y}" width="{w}" height="{h}" fill="#%02x%02x%02x"/>'
              % colour for x, y, w, h, colour in patches), "</g>"]


def _subset(drawn: _Drawn, which) -> _Drawn:
    """The triangles ``which`` of ``drawn`` (their indices, in that order)."""
    return _Drawn(drawn.corners[which], drawn.depths[which], drawn.colours[which],
                  drawn.owners[which], drawn.links)


def _among(shown, which, n: int):
    """``shown`` (indices of ``n`` triangles, -1 for none) as indices into ``which``; -1 for a
    triangle not in it."""
    import numpy as np

    position = np.full(n + 1, -1, dtype=np.int64)  # (the last: -1's)
    position[which] = np.arange(len(which))
    return position[shown]


def _painted(drawn: _Drawn, order, width: int, height: int):
    """Which triangle each pixel shows when the triangles ``order`` are drawn in that order
    (the others, never drawn, are not rasterised: they showed nowhere)."""
    import numpy as np

    painted = zbuffer(drawn.corners[order], drawn.depths[order], width, height,
                      keys=np.arange(len(order), dtype=float))
    if not len(order):  # (nothing drawn: no pixel shows a triangle, and order has none)
        return np.full_like(painted, -1)
    return np.where(painted >= 0, order[np.maximum(painted, 0)], -1)


def _runs(image, mask) -> list[tuple[int, int, int, int, tuple]]:
    """The pixels of ``mask`` as rectangles ``(x, y, width, height, rgb)`` of one colour of
    ``image``: runs along each row, joined with the same run on the rows below."""
    import numpy as np

    open_runs: dict[tuple, list] = {}  # (x, width, rgb) -> [x, y, width, height, rgb]
    done = []
    for y in range(mask.shape[0]):
        columns = np.flatnonzero(mask[y])
        row: dict[tuple, list] = {}
        if len(columns):
            colours = image[y, columns]
            breaks = np.flatnonzero((np.diff(columns) != 1)
                                    | (colours[1:] != colours[:-1]).any(axis=1)) + 1
            for piece in np.split(np.arange(len(columns)), breaks):
                x, run = int(columns[piece[0]]), len(piece)
                key = (x, run, tuple(int(v) for v in colours[piece[0]]))
                rect = open_runs.pop(key, None)
                if rect is None:
                    rect = [x, y, run, 0, key[2]]
                rect[3] += 1
                row[key] = rect
        done += open_runs.values()
        open_runs = row
    done += open_runs.values()
    return [tuple(rect) for rect in done]


def write(path, layers: list[Layer], options: PictureOptions = PictureOptions()) -> list[str]:
    """Write ``path`` as PNG or SVG by its suffix; PlotError for another suffix. Returns the
    notes on how it is drawn (:func:`svg_noted`), for the command to say."""
    notes: list[str] = []

    def noted_svg() -> str:
        text, said = svg_noted(layers, options)
        notes.extend(said)
        return text

    write_by_suffix(path, {".png": lambda: png(layers, options), ".svg": noted_svg})
    return notes


def write_by_suffix(path, drawings: dict) -> None:
    """Write ``path`` with :func:`urdftool.description.files.write_file` (a link planted at
    ``path`` is replaced, never followed) from the drawing its suffix names (``{".png": make
    bytes, ".svg": make text}``); PlotError for another suffix."""
    from pathlib import Path

    from urdftool.description.files import write_file

    suffix = Path(path).suffix.lower()
    if suffix not in drawings:
        raise PlotError(f"'{Path(path).name}' must end in {' or '.join(drawings)}")
    write_file(path, drawings[suffix]())
