"""Pictures: the collision matrix (links on both axes, each cell coloured by class and shaded
by how often the pair collided), and the drawing of any picture laid out as primitives
(rectangles, polygons, circles, lines, text) as SVG or PNG.

SVG is written directly (no plotting dependency: coloured shapes need none). PNG draws the same
layout with Pillow.
"""

from __future__ import annotations

import io
from pathlib import Path

from urdftool.errors import PlotError
from urdftool.numbers import number
from urdftool.report.escape import svg as escape


COLOURS = {"Adjacent": "#7f7f7f", "Default": "#ff7f0e", "Always": "#d62728",
           "Never": "#2ca02c", "": "#1f77b4"}
LABELS = {"Adjacent": "Adjacent", "Default": "Default", "Always": "Always", "Never": "Never",
          "": "enabled (checked)"}
CELL = 16


def _shade(pair) -> float:
    """Opacity: solid for the disabled classes, by collision fraction for enabled pairs."""
    if pair.reason in ("Adjacent", "Default", "Always"):
        return 1.0
    if pair.reason == "Never":
        return 0.35
    return 0.25 + 0.75 * min(1.0, pair.fraction * 10)


TITLE = 24  # [px] the title's row, above the column labels


def _layout(matrix, title: str):
    """The picture as primitives: (width, height, items); an item is ``("rect", x, y, w, h,
    colour, opacity, tooltip)`` or ``("text", x, y, text, size, anchor, vertical)``."""
    links = matrix.links
    index = {name: i for i, name in enumerate(links)}
    shown = {name: _label(name) for name in links}  # (the whole names in the cells' tooltips)
    label = max((len(name) for name in shown.values()), default=4) * 7 + 10
    top = TITLE + label
    size = len(links) * CELL
    items = [("text", 4, 16, title, 13, "start", False)]
    for name, i in index.items():
        middle = i * CELL + CELL * 0.75
        items.append(("text", label - 4, top + middle, shown[name], 11, "end", False))
        items.append(("text", label + middle, top - 4, shown[name], 11, "start", True))
    for pair in matrix.pairs:
        i, j = index[pair.link1], index[pair.link2]
        tip = (f"{pair.link1} / {pair.link2}: {pair.reason or 'enabled'}, "
               f"{pair.collisions}/{pair.samples} collisions")
        if pair.min_distance is not None:
            tip += f", min distance {number(pair.min_distance * 1000, places=1)} mm"
        for row, column in ((i, j), (j, i)):
            items.append(("rect", label + column * CELL, top + row * CELL, CELL - 1, CELL - 1,
                          COLOURS[pair.reason], _shade(pair), tip))
    for i in range(len(links)):
        items.append(("rect", label + i * CELL, top + i * CELL, CELL - 1, CELL - 1, "#000000",
                      1.0, None))
    legend = label + size + 20
    for k, (reason, colour) in enumerate(COLOURS.items()):
        y = top + k * 20
        shade = {"Never": 0.35, "": 1.0}.get(reason, 1.0)  # as the cells show it
        items.append(("rect", legend, y, 14, 14, colour, shade, None))
        items.append(("text", legend + 20, y + 11, LABELS[reason], 11, "start", False))
    items.append(("text", legend, top + 5 * 20 + 11, "enabled: darker = collides more often",
                  11, "start", False))
    return legend + 230, top + size + 20, items


LABEL = 64  # [characters] of a link's name written beside a row or above a column


def _label(name: str) -> str:
    """A link's name as a row's or column's label: cut at :data:`LABEL` characters. The
    margins grow with the longest label: a name of 100,000 characters made the matrix's
    picture 1.4 million pixels a side (out of memory, U018, for a PNG)."""
    return name if len(name) <= LABEL else name[:LABEL - 1] + "\u2026"


def svg(matrix, title: str) -> str:
    return svg_of(*_layout(matrix, title))


def svg_of(width: int, height: int, items) -> str:
    """SVG of primitives: ``("rect", x, y, w, h, colour, opacity, tooltip)``, ``("text", x, y,
    text, size, anchor, vertical)``, ``("polygon", [(x, y)...], fill, opacity, stroke)``,
    ``("circle", x, y, radius, colour, opacity)`` and ``("line", x1, y1, x2, y2, colour)``."""
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'font-family="sans-serif" font-size="11">',
           f'<rect width="{width}" height="{height}" fill="white"/>']
    for item in items:
        if item[0] == "rect":
            _, x, y, w, h, colour, opacity, tip = item
            shade = f' fill-opacity="{opacity:.2f}"' if opacity < 1 else ""
            body = f"<title>{escape(tip)}</title></rect>" if tip else "</rect>"
            out.append(f'<rect x="{x}" y="{y}" width="{w}" height="{h}" fill="{colour}"'
                       f'{shade}>{body}')
        elif item[0] == "polygon":
            _, points, fill, opacity, stroke = item
            corners = " ".join(f"{x:.1f},{y:.1f}" for x, y in points)
            out.append(f'<polygon points="{corners}" fill="{fill}" fill-opacity="{opacity:.2f}" '
                       f'stroke="{stroke}"/>')
        elif item[0] == "circle":
            _, x, y, radius, colour, opacity = item
            out.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="{radius}" fill="{colour}" '
                       f'fill-opacity="{opacity:.2f}"/>')
        elif item[0] == "line":
            _, x1, y1, x2, y2, colour = item
            out.append(f'<line x1="{x1:.1f}" y1="{y1:.1f}" x2="{x2:.1f}" y2="{y2:.1f}" '
                       f'stroke="{colour}"/>')
        else:
            _, x, y, text, size, anchor, vertical = item
            style = (f' font-size="{size}"' if size != 11 else "") + \
                (f' text-anchor="{anchor}"' if anchor != "start" else "")
            where = f'transform="translate({x:.1f},{y:.1f}) rotate(-90)"' if vertical else \
                f'x="{x:.1f}" y="{y:.1f}"'
            out.append(f"<text {where}{style}>{escape(text)}</text>")
    out.append("</svg>")
    return "\n".join(out) + "\n"


def write(matrix, path: Path, title: str) -> None:
    """Write ``path`` as SVG or PNG (PNG needs Pillow) with :func:`urdftool.description.files.write_file`
    (a link planted at ``path`` is replaced, never followed); PlotError for another suffix."""
    write_items(path, *_layout(matrix, title))


def write_items(path: Path, width: int, height: int, items) -> None:
    """Write primitives (see :func:`svg_of`) to ``path``, an .svg or a .png (Pillow)."""
    from urdftool.report.picture import write_by_suffix

    write_by_suffix(path, {".svg": lambda: svg_of(width, height, items),
                           ".png": lambda: png_of(width, height, items)})


def png_of(width: int, height: int, items, scale: int = 2) -> bytes:
    """The same picture as :func:`svg_of`, drawn with Pillow at ``scale`` times the size."""
    try:
        from PIL import Image, ImageColor, ImageDraw, ImageFont
    except ImportError:
        from urdftool.origin import install_command

        raise PlotError(f"PNG output needs Pillow ({install_command('analysis')}); an .svg "
                        "needs nothing") from None
    from urdftool.report.picture import check_fits

    check_fits((width * scale, height * scale), smaller="an .svg (drawn by the viewer)")
    image = Image.new("RGB", (width * scale, height * scale), "white")
    draw = ImageDraw.Draw(image)
    fonts = {}

    def shaded(colour, opacity):
        return tuple(round(255 * (1 - opacity) + c * opacity) for c in ImageColor.getrgb(colour))

    for item in items:
        if item[0] == "rect":
            _, x, y, w, h, colour, opacity, _tip = item
            draw.rectangle([x * scale, y * scale, (x + w) * scale - 1, (y + h) * scale - 1],
                           fill=shaded(colour, opacity))
            continue
        if item[0] == "polygon":
            _, points, fill, opacity, stroke = item
            draw.polygon([(x * scale, y * scale) for x, y in points],
                         fill=shaded(fill, opacity), outline=stroke)
            continue
        if item[0] == "circle":
            _, x, y, radius, colour, opacity = item
            r = radius * scale
            draw.ellipse([x * scale - r, y * scale - r, x * scale + r, y * scale + r],
                         fill=shaded(colour, opacity))
            continue
        if item[0] == "line":
            _, x1, y1, x2, y2, colour = item
            draw.line([x1 * scale, y1 * scale, x2 * scale, y2 * scale], fill=colour)
            continue
        _, x, y, text, size, anchor, vertical = item
        if size not in fonts:
            fonts[size] = ImageFont.load_default(size=size * scale)
        font = fonts[size]
        if not vertical:
            draw.text((x * scale, y * scale), text, font=font, fill="black",
                      anchor="rs" if anchor == "end" else ("ms" if anchor == "middle" else "ls"))
            continue
        length = int(draw.textlength(text, font=font)) + 2
        strip = Image.new("L", (length, 16 * scale), 0)
        ImageDraw.Draw(strip).text((0, 12 * scale), text, font=font, fill=255, anchor="ls")
        strip = strip.rotate(90, expand=True)
        image.paste((0, 0, 0), (int(x * scale - 12 * scale), int(y * scale - length)), strip)
    buffer = io.BytesIO()
    image.save(buffer, format="PNG")
    return buffer.getvalue()
