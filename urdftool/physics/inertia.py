"""Mass properties as numpy arrays (``urdftool inertia``), and closed meshes as solids.

The formulas live in :mod:`urdftool.physics.mass` (pure Python, used by the inertia rules);
this module gives them numpy arrays for the code that computes with numpy, and reads a
trimesh mesh's volume, centre of mass and tensor. Conventions are those of
:mod:`urdftool.physics.mass`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from urdftool.physics import mass as pure
from urdftool.physics import mat3
from urdftool.physics.mass import INERTIA_ATTRIBUTES, relative_difference, triangle_violation

__all__ = ["INERTIA_ATTRIBUTES", "MassProperties", "box", "combine", "cylinder", "declared",
           "mesh_solid", "relative_difference", "sphere", "transformed", "triangle_violation"]


@dataclass
class MassProperties:
    """mass [kg], com [m] (3,), inertia [kg m^2] (3, 3) about the com, link axes."""

    mass: float
    com: np.ndarray
    inertia: np.ndarray

    @classmethod
    def of(cls, body: pure.Body) -> "MassProperties":
        return cls(body.mass, np.array(body.com, dtype=float), np.array(body.inertia, dtype=float))

    def body(self) -> pure.Body:
        return pure.Body(float(self.mass), mat3.vector(self.com), mat3.matrix(self.inertia))

    def principal_moments(self) -> np.ndarray:
        return np.array(self.body().principal_moments())

    def scaled_to(self, mass: float) -> "MassProperties":
        """The same shape with another mass: inertia scales linearly with mass."""
        return MassProperties.of(self.body().scaled_to(mass))

    def as_dict(self) -> dict:
        i = self.inertia
        return {"mass": float(self.mass), "com": [float(v) for v in self.com],
                "inertia": {"ixx": float(i[0, 0]), "ixy": float(i[0, 1]),
                            "ixz": float(i[0, 2]), "iyy": float(i[1, 1]),
                            "iyz": float(i[1, 2]), "izz": float(i[2, 2])}}


def declared(link) -> MassProperties | None:
    """A link's ``<inertial>`` in link axes, or None when absent or not fully numeric."""
    body = pure.declared(link)
    return MassProperties.of(body) if body is not None else None


def box(size) -> MassProperties:
    """Solid box of edges ``size`` [m], unit density."""
    return MassProperties.of(pure.box(size))


def cylinder(radius: float, length: float) -> MassProperties:
    """Solid cylinder along z, unit density."""
    return MassProperties.of(pure.cylinder(radius, length))


def sphere(radius: float) -> MassProperties:
    """Solid sphere, unit density."""
    return MassProperties.of(pure.sphere(radius))


def transformed(solid: MassProperties, xyz, rotation) -> MassProperties:
    """A solid placed by ``<origin>``: its com moved into the link frame, tensor rotated."""
    return MassProperties.of(pure.transformed(solid.body(), xyz, mat3.matrix(rotation)))


def combine(parts: list[MassProperties]) -> MassProperties:
    """Several bodies as one, by the parallel-axis theorem about the common centre of mass."""
    return MassProperties.of(pure.combine([part.body() for part in parts]))


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
