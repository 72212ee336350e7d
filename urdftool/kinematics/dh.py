"""Denavit-Hartenberg tables: the matrices, extraction from a URDF chain, FK from a table.

Standard convention: A_i = Rot_z(theta_i) Trans_z(d_i) Trans_x(a_i) Rot_x(alpha_i), frame i-1 on
the axis of joint i. Modified (Craig): A_i = Rot_x(alpha_{i-1}) Trans_x(a_{i-1}) Rot_z(theta_i)
Trans_z(d_i), frame i on the axis of joint i; row i of the table holds a_{i-1} and alpha_{i-1}.
For a revolute joint ``theta`` is the offset added to the joint angle, for a prismatic joint ``d``
is the offset added to its travel. ``base * A_1 ... A_n * tool`` is the URDF chain exactly.

Choices where D-H leaves freedom (documented so tables are reproducible):
- frame 0 lies on the first joint axis at the foot of the base link's origin, its x along the base
  link's x made perpendicular to the axis (y when x is along the axis);
- parallel axes: the common normal through the previous origin (so that d = 0);
- the sign of each x axis keeps the theta offset within (-90, 90] degrees, so a and alpha take the
  sign that follows (manufacturers' tables such as UR's and Franka's do the same);
- the last frame lies on the last axis at the foot of the tip link's origin, x from the tip's x.

``textbook=True`` chooses the sign of each x axis the other way textbooks do: every link
length ``a >= 0``, the sign moved into ``alpha`` and ``theta``. Turning frame i about its z by pi
negates a_i and alpha_i and adds pi to theta_i (standard; modified: negates a_{i} and alpha_{i}
of the row that follows frame i and takes pi from its theta), and the next row's theta (or the
tool, the base) takes the turn back: the chain is unchanged, which the table is checked for.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from urdftool.numbers import number
from urdftool.errors import DHError, UnknownLink, available
from urdftool.description.urdf import MOVING
from urdftool.kinematics import transforms

CONVENTIONS = ("standard", "modified")
_EPS = 1e-9


@dataclass
class DHJoint:
    """One joint's Denavit-Hartenberg parameters."""

    joint: str
    type: str  # revolute | prismatic
    theta: float
    d: float
    a: float
    alpha: float


@dataclass
class DHTable:
    """A chain's Denavit-Hartenberg table, with its base and tool transforms."""

    convention: str
    base: np.ndarray
    tool: np.ndarray
    joints: list[DHJoint]
    base_link: str | None = None
    tip_link: str | None = None
    residual: float = field(default=0.0, compare=False)

    def as_dict(self) -> dict:
        data = {"convention": self.convention, "base": self.base.tolist(),
                "tool": self.tool.tolist(),
                "joints": [{"joint": j.joint, "type": j.type, "theta": j.theta, "d": j.d,
                            "a": j.a, "alpha": j.alpha} for j in self.joints]}
        if self.base_link is not None:
            data["base_link"], data["tip_link"] = self.base_link, self.tip_link
        return data


# -- the matrices ------------------------------------------------------------------------------

def dh_matrices(theta, d, a, alpha, convention: str = "standard") -> np.ndarray:
    """D-H link transforms ``[..., 4, 4]`` for broadcastable parameter arrays."""
    theta, d, a, alpha = np.broadcast_arrays(*(np.asarray(x, dtype=float)
                                               for x in (theta, d, a, alpha)))
    ct, st, ca, sa = np.cos(theta), np.sin(theta), np.cos(alpha), np.sin(alpha)
    out = np.zeros(theta.shape + (4, 4))
    out[..., 3, 3] = 1.0
    if convention == "standard":
        rows = [[ct, -st * ca, st * sa, a * ct],
                [st, ct * ca, -ct * sa, a * st],
                [0 * ct, sa, ca, d]]
    else:
        rows = [[ct, -st, 0 * ct, a],
                [st * ca, ct * ca, -sa, -d * sa],
                [st * sa, ct * sa, ca, d * ca]]
    for i, row in enumerate(rows):
        for j, value in enumerate(row):
            out[..., i, j] = value
    return out


def table_fk(table: DHTable, values: np.ndarray) -> np.ndarray:
    """Tip poses ``[rows, 4, 4]`` relative to the base link for joint values ``[rows, n]``."""
    values = np.atleast_2d(np.asarray(values, dtype=float))
    result = np.broadcast_to(table.base, (len(values), 4, 4))
    for column, joint in enumerate(table.joints):
        q = values[:, column]
        theta = joint.theta + q if joint.type == "revolute" else np.full_like(q, joint.theta)
        d = joint.d + q if joint.type == "prismatic" else np.full_like(q, joint.d)
        result = np.matmul(result, dh_matrices(theta, d, joint.a, joint.alpha, table.convention))
    return np.matmul(result, table.tool)


# -- extraction -------------------------------------------------------------------------------

def chain(robot, base: str, tip: str) -> list:
    """The joint elements from ``base`` down to ``tip``; DHError when tip is not below base."""
    from urdftool.kinematics.tree import beside_the_tree, posed_links

    UnknownLink.unless_among((base, tip), posed_links(robot), beside_the_tree(robot))
    parent_joint = {}
    for joint in robot.children("joint"):
        child = joint.find("child")
        if child is not None:
            parent_joint.setdefault(child.get("link"), joint)
    joints, link = [], tip
    while link != base:
        joint = parent_joint.get(link)
        if joint is None or joint in joints:
            hint = ""
            if base != tip and _is_below(parent_joint, base, tip):
                hint = f"; '{base}' is below '{tip}': swap --base and --tip"
            raise DHError(f"link '{tip}' is not below link '{base}': a D-H chain runs from a "
                          f"link down to one of its descendants{hint}", asked=True)
        joints.append(joint)
        link = joint.find("parent").get("link")
    return joints[::-1]


def _is_below(parent_joint: dict, link: str, ancestor: str) -> bool:
    seen = set()
    while link != ancestor and link in parent_joint and link not in seen:
        seen.add(link)
        link = parent_joint[link].find("parent").get("link")
    return link == ancestor


def _refuse_joints_without_form(joints) -> None:
    """DHError at the chain's first joint that has no D-H form (a mimic joint: not an
    independent variable; planar, floating: not one axis), naming every other one as well, so
    that one run says which joints a --base and --tip must leave out."""
    without = []
    for joint in joints:
        mimic = joint.find("mimic")
        if mimic is not None:
            without.append((joint, f"mimics '{mimic.get('joint')}'", "a mimic",
                            "a D-H table has one independent variable per joint"))
        elif joint.get("type") not in MOVING + ("fixed",):
            without.append((joint, f"is {joint.get('type')}", joint.get("type"),
                            "only revolute, continuous and prismatic joints have a D-H form "
                            "(one axis, one variable)"))
    if not without:
        return
    (first, what, _, why), *others = without
    more = "" if not others else (
        f"; {len(others)} more joint(s) of the chain have none: "
        + ", ".join(f"'{joint.get('name')}' ({kind})" for joint, _, kind, _ in others))
    raise DHError(f"joint '{first.get('name')}' {what}: {why}{more}", first, asked=True)


def extract(robot, base: str, tip: str, convention: str = "standard",
            textbook: bool = False) -> DHTable:
    """The D-H table of the chain ``base`` -> ``tip`` with its base and tool transforms;
    ``textbook``: every link length ``a >= 0`` (:func:`textbook_form`)."""
    if convention not in CONVENTIONS:
        raise DHError(f"unknown convention '{convention}'; use one of {', '.join(CONVENTIONS)}",
                      asked=True)
    joints = chain(robot, base, tip)
    moving = []  # (element, type, point, direction) in base-link coordinates at zero
    pose = np.eye(4)
    _refuse_joints_without_form(joints)
    for joint in joints:
        kind = joint.get("type")
        pose = pose @ _origin(joint)
        if kind != "fixed":
            axis = pose[:3, :3] @ _unit_axis(joint)
            moving.append((joint, "prismatic" if kind == "prismatic" else "revolute",
                           pose[:3, 3].copy(), axis))
    if not moving:
        raise DHError(f"no revolute or prismatic joint between '{base}' and '{tip}'", asked=True)
    frames = (_standard_frames if convention == "standard" else _modified_frames)(moving, pose)
    rows, residual, tolerance = [], 0.0, _tolerance(*frames, pose)
    for i, (joint, kind, _, _) in enumerate(moving):
        link = transforms.invert(frames[i]) @ frames[i + 1]
        theta, d, a, alpha = (_standard_parameters if convention == "standard"
                              else _modified_parameters)(link)
        error = np.abs(dh_matrices(theta, d, a, alpha, convention) - link).max()
        if not error <= tolerance:  # NaN included
            raise DHError(f"joint '{joint.get('name')}': its axis cannot be placed in D-H form "
                          f"(residual {number(error, 2)}; axes nearly parallel?); choose a --base "
                          "or --tip that leaves it out", joint, asked=True)  # (a chain dh does
            # not take, as a joint with no D-H form: another --base or --tip answers it)
        residual = max(residual, error)
        rows.append(DHJoint(joint.get("name"), kind, _clean(theta), _clean(d), _clean(a),
                            _clean(alpha)))
    tool = transforms.invert(frames[-1]) @ pose
    table = DHTable(convention, _clean_matrix(frames[0]), _clean_matrix(tool), rows, base, tip,
                    residual)
    return textbook_form(table) if textbook else table


def _tolerance(*poses: np.ndarray) -> float:
    """The residual [m, or of a rotation's entries] a D-H table is held to: 1e-9, or what a
    float resolves at the farthest of ``poses``' translations when that is coarser (16
    ulps' worth at 1e8 m is 3e-8): a chain placed 1e8 m from its base link (within
    ``numbers.MAX_COORDINATE``) was refused as "axes nearly parallel?", its residual the
    rounding of its place."""
    far = max((float(np.abs(pose[:3, 3]).max()) for pose in poses), default=0.0)
    return max(1e-9, 16 * np.spacing(far)) if math.isfinite(far) else 1e-9


def _reach_tolerance(table: DHTable) -> float:
    """:func:`_tolerance` at the farthest any frame of ``table`` may be from its base link
    (base, every link length and offset, a prismatic joint's probe of up to pi [m], tool): the
    textbook form's check held the table to the rounding at its base and tool only, and
    refused a chain reaching 2e7 m out and back (3.7e-9 m apart, the rounding there)."""
    far = float(np.abs(table.base[:3, 3]).sum() + np.abs(table.tool[:3, 3]).sum()) + sum(
        abs(j.a) + abs(j.d) + math.pi * (j.type == "prismatic") for j in table.joints)
    reach = np.eye(4)
    reach[0, 3] = far
    return _tolerance(reach)


_TURN = np.diag([-1.0, -1.0, 1.0, 1.0])  # Rot_z(pi)


def _wrapped(angle: float) -> float:
    """An angle in (-pi, pi]."""
    wrapped = math.remainder(angle, 2 * math.pi)
    return math.pi if wrapped == -math.pi else wrapped


def textbook_form(table: DHTable) -> DHTable:
    """The same chain with every ``a >= 0``: each frame whose link length is negative is
    turned by pi about its z axis (a and alpha change sign, theta takes the turn, the next row's
    theta or the tool/base takes it back). DHError if the result does not reproduce the table
    (it always should: the products are the same)."""
    rows = [DHJoint(j.joint, j.type, j.theta, j.d, j.a, j.alpha) for j in table.joints]
    base, tool = table.base.copy(), table.tool.copy()
    for i, row in enumerate(rows):
        if row.a >= 0:
            continue
        row.a, row.alpha = -row.a, _wrapped(-row.alpha)
        if table.convention == "standard":  # frame i: A_i Rz(pi), then Rz(-pi) A_{i+1}
            row.theta = _wrapped(row.theta + math.pi)
            if i + 1 < len(rows):
                rows[i + 1].theta = _wrapped(rows[i + 1].theta - math.pi)
            else:
                tool = _TURN @ tool
        else:  # frame i-1: Rz(-pi) A_i, then A_{i-1} Rz(pi) (or the base)
            row.theta = _wrapped(row.theta - math.pi)
            if i > 0:
                rows[i - 1].theta = _wrapped(rows[i - 1].theta + math.pi)
            else:
                base = base @ _TURN
    rows = [DHJoint(j.joint, j.type, _clean(j.theta), j.d, _clean(j.a), _clean(j.alpha))
            for j in rows]
    result = DHTable(table.convention, _clean_matrix(base), _clean_matrix(tool), rows,
                     table.base_link, table.tip_link, table.residual)
    from urdftool.kinematics.configuration import random_stream, within

    probe = within(random_stream(0), -math.pi, math.pi, (16, len(rows)))
    error = float(np.abs(table_fk(result, probe) - table_fk(table, probe)).max())
    if not error <= _reach_tolerance(table):  # (a form dh cannot vouch for: the question's, as
        # an axis with no D-H form; the table without --textbook answers it)
        raise DHError(f"the textbook form of the table does not reproduce it ({number(error, 2)}); "
                      "the table without --textbook does", asked=True)
    result.residual = max(table.residual, error)
    return result


def _standard_frames(moving, tip_pose) -> list[np.ndarray]:
    """Frames 0..n: frame i-1 has z along joint i's axis, x along the common normal."""
    point, z = moving[0][2], moving[0][3]
    frames = [_frame(_foot(np.zeros(3), point, z), _perpendicular(np.eye(3), z), z)]
    for _, _, next_point, next_z in moving[1:]:
        frames.append(_next_frame(frames[-1], next_point, next_z))
    return frames + [_tip_frame(frames[-1], tip_pose)]


def _modified_frames(moving, tip_pose) -> list[np.ndarray]:
    """Frames 0..n: frame i on joint i's axis, x along the normal to joint i+1's axis."""
    point, z = moving[0][2], moving[0][3]
    frame = _frame(_foot(np.zeros(3), point, z), _perpendicular(np.eye(3), z), z)
    frames = [frame]
    for i, (_, _, point, z) in enumerate(moving[:-1]):
        # frame i's origin on axis i: the foot of the previous x line (parallel case) or the
        # closest point to axis i+1
        on_axis = _frame(_foot(frames[-1][:3, 3], point, z), frames[-1][:3, 0], z)
        nxt_point, nxt_z = moving[i + 1][2], moving[i + 1][3]
        step = _next_frame(on_axis, nxt_point, nxt_z)  # a standard step from axis i to i+1
        origin, x = _common_normal_start(on_axis, step)
        frames.append(_frame(origin, x, z))
    last_point, last_z = moving[-1][2], moving[-1][3]
    last = _frame(_foot(frames[-1][:3, 3], last_point, last_z), frames[-1][:3, 0], last_z)
    return frames + [_tip_frame(last, tip_pose)]


def _common_normal_start(on_axis: np.ndarray, step: np.ndarray):
    """Where the common normal leaves axis i (the foot of ``step``'s x line) and its direction."""
    z, origin, x = on_axis[:3, 2], on_axis[:3, 3], step[:3, 0]
    along = float(np.dot(step[:3, 3] - origin, z))
    return origin + along * z, x


def _next_frame(previous: np.ndarray, point, z) -> np.ndarray:
    """Frame with z along the line (point, z), x along the common normal from previous z."""
    z_prev, o_prev, x_prev = previous[:3, 2], previous[:3, 3], previous[:3, 0]
    cross = np.cross(z_prev, z)
    if np.linalg.norm(cross) < _EPS:  # parallel: the normal through the previous origin
        origin = _foot(o_prev, point, z)
        offset = origin - o_prev
        x = offset / np.linalg.norm(offset) if np.linalg.norm(offset) > _EPS else x_prev
    else:
        w0 = o_prev - point
        b, d1, e = np.dot(z_prev, z), np.dot(z_prev, w0), np.dot(z, w0)
        t = (e - b * d1) / np.dot(cross, cross)  # 1 - b^2, without cancellation near 1
        origin = point + t * z
        x = cross / np.linalg.norm(cross)
    x = x - np.dot(x, z) * z
    x /= np.linalg.norm(x)
    # the sign of x keeps the theta offset within (-90, 90] degrees
    cosine, sine = np.dot(x, x_prev), np.dot(x, np.cross(z_prev, x_prev))
    if cosine < -_EPS or (abs(cosine) <= _EPS and sine < 0):
        x = -x
    return _frame(origin, x, z)


def _tip_frame(previous: np.ndarray, tip_pose: np.ndarray) -> np.ndarray:
    z = previous[:3, 2]
    return _frame(_foot(tip_pose[:3, 3], previous[:3, 3], z), _perpendicular(tip_pose[:3, :3], z),
                  z)


def _standard_parameters(link: np.ndarray):
    r, p = link[:3, :3], link[:3, 3]
    theta = math.atan2(r[1, 0], r[0, 0])
    alpha = math.atan2(r[2, 1], r[2, 2])
    return theta, p[2], p[0] * math.cos(theta) + p[1] * math.sin(theta), alpha


def _modified_parameters(link: np.ndarray):
    r, p = link[:3, :3], link[:3, 3]
    theta = math.atan2(-r[0, 1], r[0, 0])
    alpha = math.atan2(-r[1, 2], r[2, 2])
    return theta, -p[1] * math.sin(alpha) + p[2] * math.cos(alpha), p[0], alpha


def _foot(target, point, direction) -> np.ndarray:
    """The point of the line (point, direction) nearest ``target``."""
    return point + np.dot(target - point, direction) * direction


def _perpendicular(rotation: np.ndarray, z) -> np.ndarray:
    """The rotation's x axis made perpendicular to z (its y when x is along z)."""
    for column in (0, 1):
        v = rotation[:3, column] - np.dot(rotation[:3, column], z) * z
        if np.linalg.norm(v) > 1e-6:
            return v / np.linalg.norm(v)
    raise AssertionError("unreachable: x and y cannot both be along z")


def _frame(origin, x, z) -> np.ndarray:
    x = x - np.dot(x, z) * z
    x = x / np.linalg.norm(x)
    frame = np.eye(4)
    frame[:3, 0], frame[:3, 1], frame[:3, 2], frame[:3, 3] = x, np.cross(z, x), z, origin
    return frame


def _origin(joint) -> np.ndarray:
    """:func:`urdftool.kinematics.fk.joint_placement` (the one reading of a joint's ``<origin>``
    as a pose: malformed, not finite, or past ``numbers.MAX_COORDINATE`` refused), its refusal a
    DHError: dh read the origin by itself, and printed a base at 1e200 as given, with "base *
    D-H chain * tool reproduces the URDF chain to 0" (every offset below it rounded away)."""
    from urdftool.errors import FKError
    from urdftool.kinematics.fk import joint_placement

    try:
        return joint_placement(joint)
    except FKError as error:
        raise DHError(str(error), error.element) from None


def _unit_axis(joint) -> np.ndarray:
    """:func:`urdftool.kinematics.fk.unit_axis` (the one reading of an axis), its refusal a
    DHError."""
    from urdftool.errors import FKError
    from urdftool.kinematics.fk import unit_axis

    try:
        return unit_axis(joint)
    except FKError as error:
        raise DHError(str(error), error.element) from None


def _clean(value: float) -> float:
    """Round off noise below 1e-15 so that tables read as written (0.0, not 3e-17)."""
    return 0.0 if abs(value) < 1e-15 else float(value)


def _clean_matrix(matrix: np.ndarray) -> np.ndarray:
    return np.where(np.abs(matrix) < 1e-15, 0.0, matrix)


# -- table files ------------------------------------------------------------------------------

def load_table(path: str) -> DHTable:
    """A table from JSON or YAML in ``dh``'s output format; DHError says where it is wrong."""
    import yaml

    from urdftool.description.files import read_regular
    from urdftool.description.packages import link_out
    from urdftool.description.yaml_limits import OnceLoader, line_of

    leads = link_out(path)
    if leads:
        raise DHError(f"cannot read D-H table: it is a symbolic link leading outside the "
                      f"repository ({leads[1]}); not followed", where=path)
    try:
        text = read_regular(path).decode("utf-8")
        data = yaml.load(text, Loader=OnceLoader)  # noqa: S506 - SafeLoader; JSON is YAML
    except (OSError, UnicodeDecodeError) as error:
        raise DHError(f"cannot read D-H table: {error}", where=path) from None
    except yaml.YAMLError as error:
        mark = getattr(error, "problem_mark", None)
        where = f"{path}:{line_of(mark, text)}" if mark is not None else path
        raise DHError(f"invalid JSON/YAML: {getattr(error, 'problem', error)}", where=where) \
            from None
    if not isinstance(data, dict):
        raise DHError("expected a mapping with convention, base, tool, joints", where=path)
    convention = data.get("convention", "standard")
    if convention not in CONVENTIONS:
        raise DHError(f"convention '{convention}' is not one of {', '.join(CONVENTIONS)}",
                      where=path)
    base, tool = (_matrix(data.get(key, np.eye(4).tolist()), key, path) for key in ("base", "tool"))
    rows = data.get("joints")
    if not isinstance(rows, list) or not rows:
        raise DHError("'joints' must be a non-empty list", where=path)
    joints = []
    for number, row in enumerate(rows, start=1):
        where = f"{path}: joints[{number - 1}]"
        if not isinstance(row, dict) or not isinstance(row.get("joint"), str):
            raise DHError("each joint needs a 'joint' name", where=where)
        kind = row.get("type", "revolute")
        if kind not in ("revolute", "prismatic"):
            raise DHError(f"type '{kind}' is not revolute or prismatic", where=where)
        try:  # (a boolean is no number: YAML's ``true`` was 1 m; nan and inf were poses)
            values = [float(row[key]) if row[key].__class__ is not bool else math.nan
                      for key in ("theta", "d", "a", "alpha")]
        except (KeyError, TypeError, ValueError):
            values = [math.nan]
        if not all(map(math.isfinite, values)):
            raise DHError("theta, d, a and alpha must all be finite numbers", where=where)
        for key, value in zip(("theta", "d", "a", "alpha"), values):
            _within([value], key, "m" if key in ("d", "a") else "rad", where)
        joints.append(DHJoint(row["joint"], kind, *values))
    for key in ("base_link", "tip_link"):  # (a list or a number was a traceback of --verify:
        if not isinstance(data.get(key), (str, type(None))):  # looked up among the links)
            raise DHError(f"'{key}' must be a link's name, not {_kind(data[key])}", where=path)
    return DHTable(convention, base, tool, joints, data.get("base_link"), data.get("tip_link"))


def _kind(value) -> str:
    """What a YAML value that is no text is, in words."""
    return ("a mapping" if isinstance(value, dict) else "a list" if isinstance(value, list)
            else "a boolean" if isinstance(value, bool) else f"the number {value}"
            if isinstance(value, (int, float)) else f"a value of type {type(value).__name__}")


def _matrix(value, key: str, path: str) -> np.ndarray:
    try:
        matrix = np.array(value, dtype=float)
    except (TypeError, ValueError):
        matrix = None
    if matrix is None or matrix.shape != (4, 4) or not np.all(np.isfinite(matrix)):
        raise DHError(f"'{key}' must be a 4x4 matrix of numbers", where=path)
    rotation = matrix[:3, :3]  # a pose: a rotation and a translation, as every pose fk gives
    if not (np.allclose(rotation @ rotation.T, np.eye(3), atol=1e-6) and
            np.linalg.det(rotation) > 0 and np.array_equal(matrix[3], [0, 0, 0, 1])):
        raise DHError(f"'{key}' must be a rigid transform (a rotation, a translation and the "
                      "row 0 0 0 1)", where=path)
    _within(matrix[:3, 3], f"'{key}' translation", "m", path)
    return matrix


def _within(values, what: str, unit: str, where: str) -> None:
    """DHError for a table's length or angle past ``numbers.MAX_COORDINATE``, the bound of
    every joint origin and value (fk.joint_placement, configuration.placeable): a ``d`` of
    1e300 printed a pose at 1e+300 and ``--verify`` "worst position error inf m"."""
    from urdftool.numbers import MAX_COORDINATE

    far = max((abs(float(v)) for v in values), default=0.0)
    if not far < MAX_COORDINATE:
        raise DHError(f"{what}: {number(far)} is past the {number(MAX_COORDINATE)} {unit} "
                      "urdftool places a link within", where=where)


# -- FK from a table, and its check against the URDF -----------------------------------------------

def table_columns(table: DHTable, model) -> list[int]:
    """The model's variable column of each table joint; DHError for a name the robot lacks."""
    columns = {v.name: i for i, v in enumerate(model.variables)}
    result = []
    for joint in table.joints:
        if joint.joint not in columns:
            raise DHError(f"D-H table joint '{joint.joint}' is not a joint of the robot; "
                          + available("joints", joint.joint, columns), asked=True)
        result.append(columns[joint.joint])
    return result


def table_links(table: DHTable, base: str | None, tip: str | None) -> tuple[str, str]:
    """The chain's base and tip links: from the table, or from ``--base`` / ``--frame``."""
    for option, given, named in (("--base", base, table.base_link), ("--frame", tip,
                                                                      table.tip_link)):
        if given and named and given != named:
            raise DHError(f"the D-H table's chain is {table.base_link} -> {table.tip_link}; "
                          f"{option} {given} names another link (leave it out)", asked=True)
    base, tip = table.base_link or base, table.tip_link or tip
    if not base or not tip:
        raise DHError("the D-H table does not name its base_link and tip_link: pass --base LINK "
                      "and --frame LINK", asked=True)
    return base, tip


def table_forward(table: DHTable, model, configurations, base=None, tip=None):
    """An FKResult for the chain's tip computed from the table."""
    from urdftool.kinematics.fk import FKResult

    base, tip = table_links(table, base, tip)
    values = configurations.values[:, table_columns(table, model)]
    return FKResult(base, [tip], table_fk(table, values)[:, None], list(configurations.warnings))


def verify(table: DHTable, model, configurations, base=None, tip=None) -> tuple[float, float]:
    """Worst (position [m], orientation [rad]) difference between table FK and URDF FK."""
    from urdftool.kinematics.fk import forward_kinematics

    base, tip = table_links(table, base, tip)
    expected = forward_kinematics(model, configurations, [tip], base).matrices[:, 0]
    got = table_fk(table, configurations.values[:, table_columns(table, model)])
    position = np.linalg.norm(got[:, :3, 3] - expected[:, :3, 3], axis=-1).max()
    rotation = transforms.rotation_angle_between(got[:, :3, :3], expected[:, :3, :3]).max()
    return float(position), float(rotation)
