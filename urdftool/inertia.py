"""Rigid-body mass properties: URDF inertials, solids from geometry, and their combination.

Conventions: every tensor is about the body's centre of mass, in [kg m^2]; ``com`` is in [m] and,
unless said otherwise, expressed in the link frame with axes parallel to the link frame. A URDF
``<inertial>`` gives its tensor in the frame of its ``<origin>`` (rotated by ``rpy``), so
:func:`declared` rotates it into the link axes: ``I_link = R I R^T``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .rules._values import parse_numbers

INERTIA_ATTRIBUTES = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


@dataclass
class MassProperties:
    """mass [kg], com [m] (3,), inertia [kg m^2] (3, 3) about the com, link axes."""

    mass: float
    com: np.ndarray
    inertia: np.ndarray

    def principal_moments(self) -> np.ndarray:
        return np.linalg.eigvalsh(_symmetric(self.inertia))

    def scaled_to(self, mass: float) -> "MassProperties":
        """The same shape with another mass: inertia scales linearly with mass."""
        factor = mass / self.mass if self.mass else 0.0
        return MassProperties(mass, self.com.copy(), self.inertia * factor)

    def as_dict(self) -> dict:
        i = self.inertia
        return {"mass": float(self.mass), "com": [float(v) for v in self.com],
                "inertia": {"ixx": float(i[0, 0]), "ixy": float(i[0, 1]),
                            "ixz": float(i[0, 2]), "iyy": float(i[1, 1]),
                            "iyz": float(i[1, 2]), "izz": float(i[2, 2])}}


def _symmetric(matrix: np.ndarray) -> np.ndarray:
    return (matrix + matrix.T) / 2


def rpy_matrix(rpy) -> np.ndarray:
    """Rotation matrix of URDF roll-pitch-yaw (fixed axes x, y, z): Rz(y) Ry(p) Rx(r)."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), \
        math.cos(y), math.sin(y)
    return np.array([
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ])


def origin_of(element) -> tuple[np.ndarray, np.ndarray]:
    """(xyz, R) of an element's ``<origin>``; identity when absent. Malformed parts count as 0."""
    origin = element.find("origin") if element is not None else None
    xyz, rpy = [0.0] * 3, [0.0] * 3
    if origin is not None:
        xyz = parse_numbers(origin.get("xyz", "0 0 0"), 3)[0] or xyz
        rpy = parse_numbers(origin.get("rpy", "0 0 0"), 3)[0] or rpy
    return np.array(xyz, dtype=float), rpy_matrix(rpy)


def tensor(values: dict[str, float]) -> np.ndarray:
    return np.array([[values["ixx"], values["ixy"], values["ixz"]],
                     [values["ixy"], values["iyy"], values["iyz"]],
                     [values["ixz"], values["iyz"], values["izz"]]], dtype=float)


def declared(link) -> MassProperties | None:
    """A link's ``<inertial>`` in link axes, or None when absent or not fully numeric."""
    inertial = link.find("inertial")
    if inertial is None:
        return None
    mass_el, inertia_el = inertial.find("mass"), inertial.find("inertia")
    if mass_el is None or inertia_el is None:
        return None
    mass = parse_numbers(mass_el.get("value"), 1)[0]
    values = {}
    for name in INERTIA_ATTRIBUTES:
        number = parse_numbers(inertia_el.get(name), 1)[0]
        if number is None:
            return None
        values[name] = number[0]
    if mass is None:
        return None
    xyz, rotation = origin_of(inertial)
    return MassProperties(mass[0], xyz, rotation @ tensor(values) @ rotation.T)


# Solids: mass properties per unit density, about their own centre, in their own frame.

def box(size) -> MassProperties:
    """Solid box of edges ``size`` [m], unit density."""
    a, b, c = size
    m = a * b * c
    return MassProperties(m, np.zeros(3), np.diag([m * (b * b + c * c) / 12,
                                                   m * (a * a + c * c) / 12,
                                                   m * (a * a + b * b) / 12]))


def cylinder(radius: float, length: float) -> MassProperties:
    """Solid cylinder along z, unit density."""
    m = math.pi * radius * radius * length
    side = m * (3 * radius * radius + length * length) / 12
    return MassProperties(m, np.zeros(3), np.diag([side, side, m * radius * radius / 2]))


def sphere(radius: float) -> MassProperties:
    """Solid sphere, unit density."""
    m = 4 / 3 * math.pi * radius ** 3
    moment = 2 / 5 * m * radius * radius
    return MassProperties(m, np.zeros(3), np.diag([moment] * 3))


def mesh_solid(mesh) -> MassProperties:
    """A closed trimesh as a unit-density solid (trimesh: volume, center_mass, moment_inertia).

    ``moment_inertia`` is about ``center_mass`` with axes of the mesh frame, for density 1.
    An inside-out mesh has negative volume; it is flipped.
    """
    properties = mesh.mass_properties  # density 1: mass == volume
    mass = float(properties["mass"])
    inertia = np.asarray(properties["inertia"], dtype=float)
    if mass < 0:
        mass, inertia = -mass, -inertia
    return MassProperties(mass, np.asarray(properties["center_mass"], dtype=float), inertia)


def transformed(solid: MassProperties, xyz: np.ndarray, rotation: np.ndarray) -> MassProperties:
    """A solid placed by ``<origin>``: its com moved into the link frame, tensor rotated."""
    return MassProperties(solid.mass, xyz + rotation @ solid.com,
                          rotation @ solid.inertia @ rotation.T)


def combine(parts: list[MassProperties]) -> MassProperties:
    """Several bodies as one, by the parallel-axis theorem about the common centre of mass."""
    mass = sum(p.mass for p in parts)
    if mass <= 0:
        raise ValueError("bodies without mass cannot be combined")
    com = sum(p.mass * p.com for p in parts) / mass
    inertia = np.zeros((3, 3))
    for part in parts:
        d = part.com - com
        inertia += part.inertia + part.mass * (d @ d * np.eye(3) - np.outer(d, d))
    return MassProperties(mass, com, inertia)


def triangle_violation(moments, tolerance: float = 0.0) -> str | None:
    """Which triangle inequality principal moments break (a + b >= c), or None."""
    a, b, c = sorted(float(m) for m in moments)
    if a + b < c * (1 - tolerance):
        return f"{a:.4g} + {b:.4g} < {c:.4g}"
    return None


def relative_difference(declared_value, computed_value) -> float:
    """|declared - computed| / |computed| for scalars or arrays (Frobenius norm)."""
    d = np.asarray(declared_value, dtype=float)
    c = np.asarray(computed_value, dtype=float)
    scale = np.linalg.norm(c)
    if scale == 0:
        return 0.0 if np.linalg.norm(d) == 0 else math.inf
    return float(np.linalg.norm(d - c) / scale)
