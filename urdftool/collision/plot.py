"""The collision matrix as a picture: links on both axes, each cell coloured by class and shaded
by how often the pair collided.

SVG is written directly (no plotting dependency: a matrix of coloured squares needs none). PNG
goes through matplotlib when it is installed, which urdftool does not require.
"""

from __future__ import annotations

from html import escape
from pathlib import Path

from ..errors import UsageError

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


def svg(matrix, title: str) -> str:
    links = matrix.links
    index = {name: i for i, name in enumerate(links)}
    label = max((len(name) for name in links), default=4) * 7 + 10
    size = len(links) * CELL
    width, height = label + size + 190, label + size + 40
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'font-family="sans-serif" font-size="11">',
           f'<rect width="{width}" height="{height}" fill="white"/>',
           f'<text x="4" y="14" font-size="13">{escape(title)}</text>']
    for name, i in index.items():
        y = label + i * CELL + CELL * 0.75
        out.append(f'<text x="{label - 4}" y="{y:.1f}" text-anchor="end">{escape(name)}</text>')
        x = label + i * CELL + CELL * 0.75
        out.append(f'<text transform="translate({x:.1f},{label - 4}) rotate(-90)">'
                   f'{escape(name)}</text>')
    for pair in matrix.pairs:
        i, j = index[pair.link1], index[pair.link2]
        tip = (f"{pair.link1} / {pair.link2}: {pair.reason or 'enabled'}, "
               f"{pair.collisions}/{pair.samples} collisions")
        if pair.min_distance is not None:
            tip += f", min distance {pair.min_distance * 1000:.1f} mm"
        for row, column in ((i, j), (j, i)):
            out.append(f'<rect x="{label + column * CELL}" y="{label + row * CELL}" '
                       f'width="{CELL - 1}" height="{CELL - 1}" fill="{COLOURS[pair.reason]}" '
                       f'fill-opacity="{_shade(pair):.2f}"><title>{escape(tip)}</title></rect>')
    for i in range(len(links)):
        out.append(f'<rect x="{label + i * CELL}" y="{label + i * CELL}" width="{CELL - 1}" '
                   f'height="{CELL - 1}" fill="black"/>')
    for k, (reason, colour) in enumerate(COLOURS.items()):
        y = label + k * 20
        out.append(f'<rect x="{label + size + 20}" y="{y}" width="14" height="14" '
                   f'fill="{colour}"/>')
        out.append(f'<text x="{label + size + 40}" y="{y + 11}">{LABELS[reason]}</text>')
    out.append(f'<text x="{label + size + 20}" y="{label + 5 * 20 + 11}">shade: collision '
               'fraction</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def write(matrix, path: Path, title: str) -> None:
    """Write ``path`` as SVG or PNG (PNG needs matplotlib); UsageError otherwise."""
    suffix = path.suffix.lower()
    if suffix == ".svg":
        path.write_text(svg(matrix, title), encoding="utf-8")
    elif suffix == ".png":
        _png(matrix, path, title)
    else:
        raise UsageError(f"--plot: '{path.name}' must end in .svg or .png")


def _png(matrix, path: Path, title: str) -> None:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.colors import to_rgba
    except ImportError:
        raise UsageError("--plot: PNG output needs matplotlib (pip install matplotlib); "
                         "an .svg needs nothing") from None
    import numpy as np

    links = matrix.links
    index = {name: i for i, name in enumerate(links)}
    image = np.ones((len(links), len(links), 4))
    image[np.arange(len(links)), np.arange(len(links))] = (0, 0, 0, 1)
    for pair in matrix.pairs:
        colour = to_rgba(COLOURS[pair.reason], _shade(pair))
        i, j = index[pair.link1], index[pair.link2]
        image[i, j] = image[j, i] = colour
    figure, axes = plt.subplots(figsize=(2 + len(links) * 0.3, 2 + len(links) * 0.3))
    axes.imshow(image, interpolation="nearest")
    axes.set_xticks(range(len(links)), links, rotation=90, fontsize=7)
    axes.set_yticks(range(len(links)), links, fontsize=7)
    axes.set_title(title, fontsize=9)
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)
