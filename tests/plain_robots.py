"""Random robots of plain links (boxes, cylinders and spheres only) with awkward numbers, for the
tests that compare what is measured of all links at once (physics/solids.plain_links) with
the per-link path: zeros of either sign, subnormal, huge and non-finite origins, sizes and
centres of mass, turned and unturned shapes, and links that are not plain (fixed together,
with a shape that cannot be measured, without geometry, a name used twice)."""

from __future__ import annotations

import random

NUMBERS = ["0", "-0.0", "5e-324", "1e-320", "0.25", "-0.3", "1.5", "-2", "0.05", "-0.05",
           "1e150", "-1e150", "1e300", "-1e300", "1.7e308", "-1.7e308", "inf", "-inf", "nan"]
SIZES = ["5e-324", "1e-320", "1e-200", "0.01", "0.02", "0.1", "0.3", "2", "1e150", "1e300",
         "1.7e308"]
ANGLES = ["0", "-0.0", "0.5", "1.5707963267948966", "3.141592653589793", "-2", "1e10", "inf",
          "nan"]


def _pick(rng: random.Random, awkward: list[str], spread: float = 1.0) -> str:
    """An awkward number one time in three, else a plain one."""
    return rng.choice(awkward) if rng.random() < 0.35 else repr(rng.uniform(-spread, spread))


def _shape(rng: random.Random, tag: str) -> tuple[str, list[float], list[float]]:
    """A <visual>/<collision> of a random primitive, coordinates near its surface, and its
    centre."""
    xyz = " ".join(_pick(rng, NUMBERS) for _ in range(3))
    rpy = " ".join(rng.choice(ANGLES) if rng.random() < 0.5 else "0" for _ in range(3))
    kind = rng.choice(["box", "cylinder", "sphere"])
    size = [rng.choice(SIZES) if rng.random() < 0.3 else repr(rng.uniform(0.001, 1.0))
            for _ in range(3)]
    geometry = {"box": f'<box size="{" ".join(size)}"/>',
                "cylinder": f'<cylinder radius="{size[0]}" length="{size[1]}"/>',
                "sphere": f'<sphere radius="{size[0]}"/>'}[kind]
    origin = f'<origin xyz="{xyz}" rpy="{rpy}"/>' if rng.random() < 0.8 else ""
    # centres of mass on and near the shape's faces: where the two paths would part
    near = []
    for axis in range(3):
        centre, half = float(xyz.split()[axis]), float(size[axis]) / 2
        near.append(rng.choice([centre, centre + half, centre - half, centre + 1.01 * half,
                                centre + 0.99 * half, centre + 20 * half]))
    centre = [float(v) for v in xyz.split()] if origin else [0.0, 0.0, 0.0]
    return f"<{tag}>{origin}<geometry>{geometry}</geometry></{tag}>", near, centre


def plain_robot(seed: int, links: int = 120) -> str:
    """The URDF text of a random robot; most of its links are plain."""
    rng = random.Random(seed)
    # a box whose sizes halve to zero, at -0.0: its least corner is -0.0 until made +0
    parts = [f'<robot name="plain{seed}"><link name="zero"><visual><origin xyz="-0.0 -0.0 -0.0"/>'
             '<geometry><box size="5e-324 5e-324 5e-324"/></geometry></visual></link>']
    # centres of mass on the bounds, in numbers exact in binary: as far outside the box as
    # it is large (U307 does not count it far), a trace on U316's bound, on a box's face
    for name, com in (("edge", "0.75 0 0"), ("face", "0.25 0 0")):
        parts.append(f'<link name="{name}"><inertial><origin xyz="{com}"/><mass value="1"/>'
                     '<inertia ixx="0.125" ixy="0" ixz="0" iyy="0.0625" iyz="0" izz="0.0625"/>'
                     '</inertial><visual><geometry><box size="0.5 0.5 0.5"/></geometry>'
                     '</visual></link>')
    for i in range(links):
        name = f"l{i}" if rng.random() > 0.02 else "l0"  # a name used twice, now and then
        shapes, nears, centres = [], [], []
        for _ in range(rng.choice([0, 1, 1, 2, 2, 3])):
            text, near, centre = _shape(rng, rng.choice(["visual", "collision"]))
            shapes.append(text)
            nears.append(near)
            centres.append(centre)
        if rng.random() < 0.03:
            shapes.append('<collision><geometry><box size="0 1 1"/></geometry></collision>')
        if nears and rng.random() < 0.3:  # a shape's centre: inside it
            com = " ".join(repr(v) for v in rng.choice(centres))
        elif nears and rng.random() < 0.7:
            com = " ".join(repr(v) for v in rng.choice(nears))
        else:
            com = " ".join(_pick(rng, NUMBERS, 3.0) for _ in range(3))
        moment = rng.choice(["1e-6", "0.01", "10", "1e6"])
        inertial = (f'<inertial><origin xyz="{com}"/><mass value="{rng.uniform(0.01, 5):.3f}"/>'
                    f'<inertia ixx="{moment}" ixy="0" ixz="0" iyy="{moment}" iyz="0" '
                    f'izz="{moment}"/></inertial>') if rng.random() < 0.9 else ""
        parts.append(f'<link name="{name}">{inertial}{"".join(shapes)}</link>')
        if i:
            kind = "fixed" if rng.random() < 0.1 else "revolute"
            parts.append(f'<joint name="j{i}" type="{kind}"><parent link="l{rng.randrange(i)}"/>'
                         f'<child link="l{i}"/><axis xyz="0 0 1"/>'
                         '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>')
    parts.append("</robot>")
    return "".join(parts)
