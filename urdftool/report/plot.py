"""The collision matrix as a picture: links on both axes, each cell coloured by class and shaded
by how often the pair collided.

SVG is written directly (no plotting dependency: a matrix of coloured squares needs none). PNG
draws the same layout with Pillow when it is installed, which urdftool does not require.
"""

from __future__ import annotations

import io
from html import escape
from pathlib import Path

from urdftool.errors import PlotError


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
    label = max((len(name) for name in links), default=4) * 7 + 10
    top = TITLE + label
    size = len(links) * CELL
    items = [("text", 4, 16, title, 13, "start", False)]
    for name, i in index.items():
        middle = i * CELL + CELL * 0.75
        items.append(("text", label - 4, top + middle, name, 11, "end", False))
        items.append(("text", label + middle, top - 4, name, 11, "start", True))
    for pair in matrix.pairs:
        i, j = index[pair.link1], index[pair.link2]
        tip = (f"{pair.link1} / {pair.link2}: {pair.reason or 'enabled'}, "
               f"{pair.collisions}/{pair.samples} collisions")
        if pair.min_distance is not None:
            tip += f", min distance {pair.min_distance * 1000:.1f} mm"
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


def svg(matrix, title: str) -> str:
    width, height, items = _layout(matrix, title)
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
    """Write ``path`` as SVG or PNG (PNG needs Pillow), a link planted at ``path`` replaced,
    never followed; PlotError for another suffix."""
    from urdftool.report.picture import write_by_suffix

    write_by_suffix(path, {".svg": lambda: svg(matrix, title), ".png": lambda: _png(matrix, title)})


def _png(matrix, title: str, scale: int = 2) -> bytes:
    """The same picture as :func:`svg`, drawn with Pillow at ``scale`` times the size."""
    try:
        from PIL import Image, ImageColor, ImageDraw, ImageFont
    except ImportError:
        raise PlotError("PNG output needs Pillow (pip install pillow); an .svg needs "
                         "nothing") from None
    width, height, items = _layout(matrix, title)
    image = Image.new("RGB", (width * scale, height * scale), "white")
    draw = ImageDraw.Draw(image)
    fonts = {}
    for item in items:
        if item[0] == "rect":
            _, x, y, w, h, colour, opacity, _tip = item
            rgb = tuple(round(255 * (1 - opacity) + c * opacity)
                        for c in ImageColor.getrgb(colour))
            draw.rectangle([x * scale, y * scale, (x + w) * scale - 1, (y + h) * scale - 1],
                           fill=rgb)
            continue
        _, x, y, text, size, anchor, vertical = item
        if size not in fonts:
            fonts[size] = ImageFont.load_default(size=size * scale)
        font = fonts[size]
        if not vertical:
            draw.text((x * scale, y * scale), text, font=font, fill="black",
                      anchor="rs" if anchor == "end" else "ls")
            continue
        length = int(draw.textlength(text, font=font)) + 2
        strip = Image.new("L", (length, 16 * scale), 0)
        ImageDraw.Draw(strip).text((0, 12 * scale), text, font=font, fill=255, anchor="ls")
        strip = strip.rotate(90, expand=True)
        image.paste((0, 0, 0), (int(x * scale - 12 * scale), int(y * scale - length)), strip)
    buffer = io.BytesIO()
    image.save(buffer, format="PNG")
    return buffer.getvalue()
