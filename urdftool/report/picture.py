"""Pictures of posed robots: PNG with numpy and Pillow, SVG written directly. Headless: no GPU,
no display, no OpenGL.

An orthographic camera looks along one of :data:`VIEWS`. Each triangle is shaded flat (Lambert,
a fixed light over the viewer's shoulder, lit on both sides so that meshes wound either way
look the same); faces of closed surfaces turned away from the viewer are left out (hidden
anyway). Triangles are drawn far to near by their mean depth (the painter's
algorithm), with Pillow's C polygon filler for PNG (~300,000 triangles a second on one
core) and as polygons for SVG.

A picture is made of layers (:class:`Layer`): one scene in its own colours, a scene with some
links painted (colliding pairs), or, for a comparison, two scenes tinted in two colours, grey
where both cover the same pixels, so that what moved shows in one colour alone.
"""

from __future__ import annotations

import io
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
MAX_EDGE = 40.0  # [px] longer triangle sides are split for the painter's order
_ROUNDS = 5  # splits at most: a side of the whole picture becomes 1/32 of it
SVG_MIN_AREA = 0.05  # [px^2] triangles smaller than this are left out of an SVG


@dataclass(frozen=True)
class PictureOptions:
    """How to draw: ``view`` one of VIEWS, ``size`` (width, height) in pixels, link frames
    (x red, y green, z blue) and joint axes (magenta) drawn over the geometry or not."""

    view: str = "iso"
    size: tuple[int, int] = (600, 600)
    frames: bool = False
    axes: bool = False


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


def _camera(layers: list[Layer], view: str, width: int, height: int) -> _Camera:
    import numpy as np

    points = [layer.scene.triangles.reshape(-1, 3) for layer in layers]
    points += [np.array([pose[:3, 3] for pose in layer.scene.frames.values()]).reshape(-1, 3)
               for layer in layers]
    return _Camera(view, np.concatenate(points), width, height)


def _project(layer: Layer, camera: _Camera, ordered: bool = False) -> _Drawn:
    """The layer's triangles shaded; with ``ordered`` sorted far to near (the painter's
    order, for SVG)."""
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
    screen, colours, owners = _subdivided(camera.screen(triangles), colours, owners)
    if ordered:
        order = np.argsort(screen[:, :, 2].sum(axis=1), kind="stable")
        screen, colours, owners = screen[order], colours[order], owners[order]
    return _Drawn(screen[..., :2], screen[..., 2], colours, owners, scene.links)


def _subdivided(screen, colours, owners):
    """Triangles (in screen coordinates) with a side longer than ``MAX_EDGE`` pixels split in
    four at their midpoints (a few rounds): the painter's order by mean depth is then right
    where a long triangle (a cylinder's side) meets another shape."""
    import numpy as np

    done = [(screen, colours, owners)]
    for _ in range(_ROUNDS):
        screen, colours, owners = done.pop()
        flat = screen[..., :2]
        edges = np.abs(flat - flat[:, [1, 2, 0]]).max(axis=(1, 2))  # the longest side's x or y
        large = edges > MAX_EDGE
        if not large.any():
            done.append((screen, colours, owners))
            break
        done.append((screen[~large], colours[~large], owners[~large]))
        a, b, c = (screen[large][:, i] for i in range(3))
        ab, bc, ca = (a + b) / 2, (b + c) / 2, (c + a) / 2
        split = np.concatenate([np.stack(corners, axis=1) for corners in
                                ((a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca))])
        done.append((split, np.tile(colours[large], (4, 1)), np.tile(owners[large], 4)))
    return tuple(np.concatenate(parts) for parts in zip(*done))


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


def _painted(drawn: _Drawn, width: int, height: int):
    """The triangles filled far to near with Pillow, as an RGB image."""
    import numpy as np
    from PIL import Image, ImageDraw

    image = Image.new("RGB", (width, height), BACKGROUND)
    # Pillow's C drawing call, without ImageDraw.polygon's per-call colour parsing (2/3 of the
    # time): an RGB ink is the packed integer r + g << 8 + b << 16
    polygon = ImageDraw.Draw(image).draw.draw_polygon
    inks = drawn.colours.astype(np.int64) @ np.array([1, 1 << 8, 1 << 16])
    for corners, ink in zip(drawn.corners.reshape(-1, 6).tolist(), inks.tolist()):
        polygon(corners, ink, 1)
    return image


def rasterise(layers: list[Layer], options: PictureOptions = PictureOptions()):
    """The picture as a Pillow RGB image; where several layers overlap it is grey."""
    import numpy as np
    from PIL import Image, ImageDraw

    width, height = options.size
    camera = _camera(layers, options.view, width, height)
    images = [_painted(_project(layer, camera, ordered=True), width, height)
              for layer in layers]
    if len(images) == 1:
        image = images[0]
    else:  # what several layers cover is grey (their mean brightness): the rest stands out
        white = np.array(BACKGROUND, dtype=np.float32)
        arrays = [np.asarray(image, dtype=np.float32) for image in images]
        covered = [np.any(array != white, axis=-1) for array in arrays]
        count = np.sum(covered, axis=0)
        total = np.sum([np.where(c[..., None], a, 0) for c, a in zip(covered, arrays)], axis=0)
        pixels = np.where(count[..., None] > 0, total / np.maximum(count, 1)[..., None], white)
        # the tints are about half as bright as white: the grey is lifted back
        grey = np.repeat(np.clip(pixels.mean(axis=-1, keepdims=True) * 1.6, 0, 235), 3, axis=-1)
        pixels = np.where(count[..., None] > 1, grey, pixels)
        image = Image.fromarray(pixels.astype(np.uint8), "RGB")
    draw = ImageDraw.Draw(image)
    for start, end, colour, line_width in _overlays(layers, camera, options):
        draw.line([tuple(start), tuple(end)], fill=colour, width=line_width)
    _legend(draw, layers)
    return image


def _legend(draw, layers: list[Layer]) -> None:
    labelled = [layer for layer in layers if layer.tint is not None and layer.label]
    for row, layer in enumerate(labelled):
        colour = tuple(int(c * 255) for c in layer.tint)
        draw.rectangle([6, 6 + 16 * row, 18, 18 + 16 * row], fill=colour)
        draw.text((24, 6 + 16 * row), layer.label, fill=(0, 0, 0))


def png(layers: list[Layer], options: PictureOptions = PictureOptions()) -> bytes:
    buffer = io.BytesIO()
    rasterise(layers, options).save(buffer, format="PNG", compress_level=3)  # flat colours
    # compress about as well at level 3 as at 6, in half the time
    return buffer.getvalue()


def svg(layers: list[Layer], options: PictureOptions = PictureOptions()) -> str:
    """The picture as SVG polygons, far to near; each run of one link's triangles is a group
    whose ``<title>`` names the link (shown on hover). Triangles under 0.05 px^2 are left out."""
    import numpy as np

    width, height = options.size
    camera = _camera(layers, options.view, width, height)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="11">',
           f'<rect width="{width}" height="{height}" fill="white"/>']
    for layer in layers:
        drawn = _project(layer, camera, ordered=True)
        corners = drawn.corners
        one, two = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
        area = 0.5 * np.abs(one[:, 0] * two[:, 1] - one[:, 1] * two[:, 0])
        keep = area >= SVG_MIN_AREA
        opacity = f' opacity="{1 / len(layers):.2f}"' if len(layers) > 1 else ""
        title = f"<title>{escape(layer.label)}</title>" if layer.label else ""
        out.append(f"<g{opacity}>{title}")
        current = None
        for points, colour, owner in zip(corners[keep].round(1).reshape(-1, 6).tolist(),
                                         drawn.colours[keep].tolist(), drawn.owners[keep].tolist()):
            if owner != current:
                if current is not None:
                    out.append("</g>")
                out.append(f"<g><title>{escape(drawn.links[owner])}</title>")
                current = owner
            text = " ".join(f"{x:g},{y:g}" for x, y in zip(points[::2], points[1::2]))
            fill = "#%02x%02x%02x" % tuple(colour)
            out.append(f'<polygon points="{text}" fill="{fill}" stroke="{fill}" '
                       'stroke-width="0.3"/>')
        if current is not None:
            out.append("</g>")
        out.append("</g>")
    for start, end, colour, line_width in _overlays(layers, camera, options):
        out.append(f'<line x1="{start[0]:.1f}" y1="{start[1]:.1f}" x2="{end[0]:.1f}" '
                   f'y2="{end[1]:.1f}" stroke="#%02x%02x%02x" stroke-width="{line_width}"/>'
                   % colour)
    for row, layer in enumerate(l for l in layers if l.tint is not None and l.label):
        fill = "#%02x%02x%02x" % tuple(int(c * 255) for c in layer.tint)
        out.append(f'<rect x="6" y="{6 + 16 * row}" width="12" height="12" fill="{fill}"/>')
        out.append(f'<text x="24" y="{16 + 16 * row}">{escape(layer.label)}</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def write(path, layers: list[Layer], options: PictureOptions = PictureOptions()) -> None:
    """Write ``path`` as PNG or SVG by its suffix; PlotError for another suffix."""
    write_by_suffix(path, {".png": lambda: png(layers, options),
                           ".svg": lambda: svg(layers, options)})


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
