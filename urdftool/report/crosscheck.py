"""``urdftool crosscheck`` as text: a table of the loaders, then what failed, where the loaders
disagree, how they differ, and what is missing (with how to install it)."""

from __future__ import annotations

from urdftool.report.escape import text as _text


def _cell(value) -> str:
    if value is None:
        return "-"
    if isinstance(value, bool):
        return "floating" if value else "fixed"
    if isinstance(value, float):
        from urdftool.numbers import number

        return number(value, 6)
    return str(value)


def text(result) -> str:
    from urdftool.diagnostics import display_path

    header = ("loader", "version", "loaded", "mass [kg]", "dof", "base", "links", "dropped")
    rows = [header]
    for loader in result.loaders:
        # a loader that failed has no model: what it read before failing is no figure of one
        figures = (_cell(loader.mass), _cell(loader.dof), _cell(loader.floating_base),
                   str(len(loader.links)), str(len(loader.dropped_links))) if loader.loaded \
            else ("-",) * 5
        rows.append((loader.name, loader.version or "?", "yes" if loader.loaded else "NO",
                     *figures))
    widths = [max(len(row[i]) for row in rows) for i in range(len(header))]
    lines = [f"{display_path(result.path)}", ""]
    lines += ["  ".join(cell.ljust(width) for cell, width in zip(row, widths)).rstrip()
              for row in rows]
    failed = [loader for loader in result.loaders if not loader.loaded]
    if failed:
        lines += ["", "failed:"]
        for loader in failed:
            where = f"{loader.location}: " if loader.location is not None else ""
            error = " ".join((loader.error or "?").split())
            lines.append(f"  {loader.name}: {where}{error[:400]}")
    if result.disagreements:
        lines += ["", "disagree:"] + [f"  {line}" for line in result.disagreements]
    if result.differences:
        lines += ["", "differ (as each loader reads a URDF):"]
        lines += [f"  {line}" for line in result.differences]
    if result.missing:
        lines += ["", "not installed:"]
        lines += [f"  {name}: {how}" for name, how in result.missing.items()]
    verdict = ("the loaders agree" if not failed and not result.disagreements else
               f"{len(failed)} loader(s) failed, {len(result.disagreements)} disagreement(s)")
    lines += ["", verdict]
    return "".join(_text(line) + "\n" for line in lines)  # one line each, none a command
