"""``urdftool diff`` as text, JSON, or Markdown (a pull-request comment or a GitHub job summary)."""

from __future__ import annotations

import math
import sys

from urdftool.compare.structure import percent_change
from urdftool.numbers import number, numbers
from urdftool.report.escape import lines as _lines, markdown as _code, text as _text

FRAMES_SHOWN = 15  # rows of the moved-frames table in text and Markdown
JOINTS_SHOWN = 8  # joint values shown for "where" (JSON gives all)


def _value(value, quote) -> str:
    """A field's value; ``quote`` marks text (a name, a file name: the robot's words)."""
    if value is None:
        return "(none)"
    if isinstance(value, float):
        return number(value, 6)
    if isinstance(value, tuple):
        if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
            return "(" + numbers(value, 6, ", ") + ")"
        return "(" + ", ".join(number(v, 6) if isinstance(v, float) else _value(v, quote)
                               for v in value) + ")"
    return str(value) if isinstance(value, int) else quote(str(value))  # (and a bool: its
    # name; anything else holds the file's words: a YAML date, set or pair as its text)


def _amount(change) -> str:
    """How much, in the unit people read: mm for lengths, degrees for angles, % for masses."""
    parts = []
    if change.delta is not None:
        vector = isinstance(change.old, tuple)
        if change.unit == "m":
            parts.append(f"moved {number(change.delta * 1000)} mm" if vector else
                         f"{number(change.delta * 1000, plus=True)} mm")
        elif change.unit == "rad":
            parts.append(f"turned {number(math.degrees(change.delta))} deg" if vector else
                         f"{number(math.degrees(change.delta), plus=True)} deg")
        elif not vector:
            parts.append(f"{number(change.delta, plus=True)}"
                         f"{' ' + change.unit if change.unit else ''}")
    if change.percent is not None:
        parts.append(f"{number(change.percent, 3, plus=True)} %")
    return ", ".join(parts)


def _quoted(name) -> str:
    return f"'{_text(name)}'"


def change_line(change, quote=_quoted, field=_text) -> str:
    """One change as a sentence; ``quote`` marks names and the other text of the robot's
    (quotes around terminal text in text, a code span in Markdown), ``field`` writes what
    changed (a controller file's key is the file's words: terminal text, a code span)."""
    if change.kind == "renamed":
        return f"renamed {change.element} {quote(change.old_name)} -> {quote(change.name)}"
    if change.kind in ("added", "removed"):
        return f"{change.kind} {change.element} {quote(change.name)}"
    line = (f"{change.element} {quote(change.name)}: {field(change.field)} "
            f"{_value(change.old, quote)} -> {_value(change.new, quote)}"
            + (f" {change.unit}" if change.unit and change.delta is not None
               and change.field != "axis" else ""))  # (an axis: a direction, turned by delta)
    amount = _amount(change)
    return line + (f" ({amount})" if amount else "")


def not_compared_line(item, quote=_quoted, why=_text) -> str:
    """A companion file not compared, with why for each side that could not read it;
    ``quote`` marks its name, ``why`` the reasons (they quote the file's characters)."""
    sides = "; ".join(f"{side}: {why(reason)}" for side, reason in (("old", item.old),
                                                                    ("new", item.new)) if reason)
    return f"not compared: {item.element} {quote(item.name)} ({sides})"


def _where(at: dict, joints: list[str], limit: int = JOINTS_SHOWN, quote=_text) -> str:
    """The values in ``at`` of ``joints``, the joints that move what changed (the other
    joints' values change nothing there), named even at zero (names marked by ``quote``); with
    none, the change is the same in every configuration."""
    if not joints:
        return "every configuration alike"
    shown = ", ".join(f"{quote(name)}={number(at.get(name, 0.0), 3)}" for name in joints[:limit])
    return shown + (f", ... ({len(joints)} joints)" if len(joints) > limit else "")


def _frame_cells(frame, quote=_text) -> tuple[str, str, str, str, str]:
    """A moved frame's numbers as people read them: at zero (mm, deg), at most (mm, deg),
    and where it moved most (the joints that move it, names marked by ``quote``)."""
    return (number(frame.zero_position * 1000, 3), number(math.degrees(frame.zero_rotation), 3),
            number(frame.max_position * 1000, 3), number(math.degrees(frame.max_rotation), 3),
            _where(frame.at, frame.joints, quote=quote))


def _worst_line(effects, quote=_text) -> str:
    """The configuration where the frames moved most (``diff --render`` draws it): the joints
    that move the changed frames, with their values."""
    return (f"largest change at {_where(effects.worst, effects.moving, quote=quote)} (the joints "
            "that move the changed frames; --render draws this configuration)")


def _effect_lines(effects, quote=_text) -> list[str]:
    """The effects as lines of text; ``quote`` marks names (as :func:`change_line`)."""
    lines = [f"Effect over {effects.samples + 1} configurations (zero + {effects.samples} "
             "within the limits both allow):"]
    if effects.frames:
        lines.append(f"  {len(effects.frames)} frame(s) moved; most:")
        for frame in effects.frames[:FRAMES_SHOWN]:
            zero_mm, zero_deg, max_mm, max_deg, where = _frame_cells(frame)
            lines.append(f"    {quote(frame.link)}: at zero {zero_mm} mm {zero_deg} deg; at most "
                         f"{max_mm} mm {max_deg} deg (at {where})")
        if len(effects.frames) > FRAMES_SHOWN:
            lines.append(f"    ... {len(effects.frames) - FRAMES_SHOWN} more (--format json)")
        lines.append(f"  {_worst_line(effects)}")
    else:
        lines.append("  no frame moved")
    lines.append("  " + _mass_line(effects))
    for chain in effects.chains:
        lines.append(f"  reach {quote(chain.base)} -> {quote(chain.tip)}: "
                     f"{number(chain.old_reach * 1000)} -> {number(chain.new_reach * 1000)} mm "
                     f"({number((chain.new_reach - chain.old_reach) * 1000, 3, plus=True)} mm; "
                     f"at zero {number((chain.new_zero - chain.old_zero) * 1000, 3, plus=True)}"
                     " mm)")
    for collision in effects.collisions:
        verb = "newly collides" if collision.new_count else "no longer collides"
        lines.append(f"  {quote(collision.link1)} / {quote(collision.link2)} {verb}: in "
                     f"{collision.old_count} -> {collision.new_count} of "
                     f"{effects.samples + 1} configurations")
    return lines


def _mass_line(effects, name=_text) -> str:
    """The mass and centre of mass effect; ``name``: how the text of a file is escaped (text,
    or Markdown's code span)."""
    if effects.mass_unknown:
        return (f"total mass and centre of mass not compared: {name(effects.mass_unknown)} "
                "('urdftool check' says why)")
    com = math.dist(effects.old_com, effects.new_com) * 1000  # [mm]; below 1 nm: round-off
    moved = f"centre of mass at zero moved {number(com, 3)} mm" if com >= 1e-6 else \
        "centre of mass unchanged"
    if effects.old_mass == effects.new_mass:
        return f"total mass {number(effects.new_mass, 6)} kg unchanged; {moved}"
    change = effects.new_mass - effects.old_mass
    ratio = percent_change(effects.old_mass, effects.new_mass) if effects.old_mass else None
    percent = f", {number(ratio, 3, plus=True)} %" if ratio is not None else ""
    return (f"total mass {number(effects.old_mass, 6)} -> {number(effects.new_mass, 6)} kg "
            f"({number(change, plus=True)} kg{percent}); {moved}")


def text(result) -> str:
    changes = result.changes + result.companions
    old, new = _text(result.old), _text(result.new)
    if result.equivalent:
        return f"{old} and {new}: equivalent (no change)\n"
    lines = [f"{old} -> {new}: {len(changes)} change(s)" if changes else
             f"{old} and {new}: no change in what was compared"]
    lines += ["  " + change_line(change) for change in changes]
    lines += ["  " + not_compared_line(item) for item in result.not_compared]
    if result.effects is not None:
        lines += _effect_lines(result.effects)  # its warnings: on stderr, as every command's
    return "\n".join(lines) + "\n"


def markdown(result) -> str:
    """For a pull-request comment or ``$GITHUB_STEP_SUMMARY``: a heading, the changes as a
    list, the effects as tables."""
    changes = result.changes + result.companions
    title = f"### Robot description: {_code(result.old)} → {_code(result.new)}"
    if result.equivalent:
        return f"{title}\n\nNo change: the two describe the same robot.\n"
    out = [title, "", f"**{len(changes)} change(s)**" if changes else
           "**No change in what was compared**", ""]
    out += [f"- {change_line(change, _code, _code)}" for change in changes]
    out += [f"- {not_compared_line(item, _code, _code)}" for item in result.not_compared]
    effects = result.effects
    if effects is not None:
        out += ["", f"**Effect** over {effects.samples + 1} configurations (zero + "
                    f"{effects.samples} within the limits both allow)", ""]
        if effects.frames:
            out += ["| link | at zero (mm) | at zero (deg) | at most (mm) | at most (deg) | "
                    "where |", "|---|---:|---:|---:|---:|---|"]
            for frame in effects.frames[:FRAMES_SHOWN]:
                out.append(f"| {_code(frame.link)} | " + " | ".join(_frame_cells(frame, _code))
                           + " |")
            if len(effects.frames) > FRAMES_SHOWN:
                out.append(f"\n… and {len(effects.frames) - FRAMES_SHOWN} more frame(s)")
            out += ["", f"{_worst_line(effects, _code)}."]
        else:
            out.append("No frame moved.")
        out += ["", f"- {_mass_line(effects, _code)}"]
        out += [f"- {line.strip()}" for line in _effect_lines(effects, _code)
                if line.startswith("  reach") or "collides" in line]
    return "\n".join(out) + "\n"


def change_detail(result):
    """What ``diff --render`` magnifies: the frame that moved most, how far at the drawn
    configuration's scale, as a :class:`~urdftool.report.picture.Detail`; None when no frame
    moved."""
    from urdftool.report.picture import Detail

    effects = result.effects
    if effects is None or not effects.frames:
        return None
    frame = effects.frames[0]
    moved = (f"{frame.link} moved {number(frame.max_position * 1000, 3)} mm"
             if frame.max_position else
             f"{frame.link} turned {number(math.degrees(frame.max_rotation), 3)} deg")
    return Detail(frame.max_position, moved)


def as_json(result) -> dict:
    def change(c) -> dict:
        data = {"kind": c.kind, "element": c.element, "name": c.name}
        if c.old_name:
            data["old_name"] = c.old_name
        if c.kind == "changed":
            data.update({"field": c.field, "old": c.old, "new": c.new})
            for key in ("delta", "percent"):
                if getattr(c, key) is not None:
                    data[key] = getattr(c, key)
            if c.unit:
                data["unit"] = c.unit
        return data

    data = {"version": 1, "old": result.old, "new": result.new,
            "equivalent": result.equivalent,
            "changes": [change(c) for c in result.changes + result.companions],
            "not_compared": [{"element": item.element, "name": item.name, "old": item.old,
                              "new": item.new} for item in result.not_compared]}
    effects = result.effects
    if effects is not None:
        data["effects"] = {
            "configurations": effects.samples + 1,
            "frames": [{"link": f.link, "zero_position_m": f.zero_position,
                        "zero_rotation_rad": f.zero_rotation, "max_position_m": f.max_position,
                        "max_rotation_rad": f.max_rotation, "at": f.at, "joints": f.joints}
                       for f in effects.frames],
            "mass_kg": {"old": effects.old_mass, "new": effects.new_mass}
            if not effects.mass_unknown else None,
            "com_m": {"old": list(effects.old_com), "new": list(effects.new_com)}
            if not effects.mass_unknown else None,
            "mass_not_compared": effects.mass_unknown,
            "chains": [{"base": c.base, "tip": c.tip, "old_reach_m": c.old_reach,
                        "new_reach_m": c.new_reach, "old_zero_m": c.old_zero,
                        "new_zero_m": c.new_zero} for c in effects.chains],
            "collisions": [{"link1": c.link1, "link2": c.link2, "old_count": c.old_count,
                            "new_count": c.new_count} for c in effects.collisions],
            "worst_configuration": effects.worst,
            "worst_joints": effects.moving,
            "warnings": effects.warnings}
    return data


def write(result, output_format: str, stream=None) -> None:
    """``result`` (urdftool.compare.diff.Diff) as text, json or markdown on ``stream``; a number
    JSON cannot hold (YAML's ``.inf``) as the text and Markdown write it: ``"inf"``,
    ``"-inf"``, ``"nan"``."""
    stream = stream or sys.stdout
    if output_format == "json":
        from urdftool.report.json_output import write_json

        write_json(as_json(result), stream, spelt=True)  # (null: a value that is none)
    elif output_format == "markdown":
        stream.write(_lines(markdown(result)))
    else:
        stream.write(_lines(text(result)))
