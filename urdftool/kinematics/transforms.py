"""Rigid transforms as numpy arrays, vectorised over leading dimensions.

Matrices are 4x4 homogeneous transforms (``[..., 4, 4]``); angles in [rad]; roll-pitch-yaw as URDF
writes them (R = Rz(yaw) Ry(pitch) Rx(roll)); quaternions (x, y, z, w) with w >= 0.
"""

from __future__ import annotations

import numpy as np


def from_xyz_rpy(xyz, rpy) -> np.ndarray:
    """The 4x4 transform of a URDF ``<origin xyz rpy>``."""
    matrix = np.eye(4)
    matrix[:3, :3] = rotation_from_rpy(np.asarray(rpy, dtype=float))
    matrix[:3, 3] = xyz
    return matrix


def from_origin(origin) -> np.ndarray:
    """The 4x4 transform of a :class:`urdftool.description.values.Origin`."""
    return from_xyz_rpy(origin.xyz, origin.rpy)


def too_far(origin: np.ndarray, low, high) -> str | None:
    """Why a part of a link is not placed, or None: the geometry whose bounds in its own frame
    are ``low``..``high`` [m], posed by ``origin`` (4x4, in the link), reaches past
    :data:`urdftool.numbers.MAX_COORDINATE` (a box 1e300 long, a sphere of radius 1e200, a
    mesh scaled by 1e30, an origin at 1e300): the one bound of collisions' and render's parts,
    which FCL and trimesh overflowed on (numpy's warnings, NaN corners, distances of inf)."""
    from urdftool.numbers import MAX_COORDINATE, number

    low, high = np.asarray(low, dtype=float), np.asarray(high, dtype=float)
    with np.errstate(all="ignore"):
        centre = origin[:3, :3] @ (low / 2 + high / 2) + origin[:3, 3]
        far = float((np.abs(centre) + np.abs(origin[:3, :3]) @ (high / 2 - low / 2)).max())
    if far < MAX_COORDINATE:  # (NaN is not)
        return None
    return (f"reaches {number(far)} m from its link's frame, past the {number(MAX_COORDINATE)} m "
            "urdftool places geometry within")


def rotation_from_rpy(rpy: np.ndarray) -> np.ndarray:
    """R = Rz(yaw) Ry(pitch) Rx(roll) for ``rpy[..., 3]``."""
    roll, pitch, yaw = rpy[..., 0], rpy[..., 1], rpy[..., 2]
    cr, sr, cp, sp, cy, sy = (np.cos(roll), np.sin(roll), np.cos(pitch), np.sin(pitch),
                              np.cos(yaw), np.sin(yaw))
    out = np.empty(rpy.shape[:-1] + (3, 3))
    out[..., 0, 0] = cy * cp
    out[..., 0, 1] = cy * sp * sr - sy * cr
    out[..., 0, 2] = cy * sp * cr + sy * sr
    out[..., 1, 0] = sy * cp
    out[..., 1, 1] = sy * sp * sr + cy * cr
    out[..., 1, 2] = sy * sp * cr - cy * sr
    out[..., 2, 0] = -sp
    out[..., 2, 1] = cp * sr
    out[..., 2, 2] = cp * cr
    return out


def rotations_about(axis, angles: np.ndarray) -> np.ndarray:
    """Rotation matrices ``[N, 3, 3]`` about the unit ``axis`` by ``angles[N]`` (Rodrigues)."""
    x, y, z = axis
    c, s = np.cos(angles), np.sin(angles)
    t = 1.0 - c
    out = np.empty(np.shape(angles) + (3, 3))
    out[..., 0, 0] = c + x * x * t
    out[..., 0, 1] = x * y * t - z * s
    out[..., 0, 2] = x * z * t + y * s
    out[..., 1, 0] = y * x * t + z * s
    out[..., 1, 1] = c + y * y * t
    out[..., 1, 2] = y * z * t - x * s
    out[..., 2, 0] = z * x * t - y * s
    out[..., 2, 1] = z * y * t + x * s
    out[..., 2, 2] = c + z * z * t
    return out


def rpy_from_rotation(rotation: np.ndarray) -> np.ndarray:
    """Roll, pitch, yaw ``[..., 3]`` of rotation matrices ``[..., 3, 3]``."""
    r = rotation
    pitch = np.arctan2(-r[..., 2, 0], np.hypot(r[..., 0, 0], r[..., 1, 0]))
    roll = np.arctan2(r[..., 2, 1], r[..., 2, 2])
    yaw = np.arctan2(r[..., 1, 0], r[..., 0, 0])
    gimbal = np.hypot(r[..., 0, 0], r[..., 1, 0]) < 1e-12
    if np.any(gimbal):  # pitch = +-90 deg: put the whole rotation about z into yaw
        roll = np.where(gimbal, 0.0, roll)
        yaw = np.where(gimbal, np.arctan2(-r[..., 0, 1], r[..., 1, 1]), yaw)
    return np.stack([roll, pitch, yaw], axis=-1)


def quaternion_from_rotation(rotation: np.ndarray) -> np.ndarray:
    """Unit quaternions (x, y, z, w) with w >= 0 of rotation matrices ``[..., 3, 3]``."""
    r = rotation
    trace = r[..., 0, 0] + r[..., 1, 1] + r[..., 2, 2]
    # Squared magnitudes of each component, then signs from the off-diagonal terms of the largest
    candidates = np.stack([
        np.stack([1 + 2 * r[..., 0, 0] - trace, r[..., 0, 1] + r[..., 1, 0],
                  r[..., 0, 2] + r[..., 2, 0], r[..., 2, 1] - r[..., 1, 2]], -1),
        np.stack([r[..., 0, 1] + r[..., 1, 0], 1 + 2 * r[..., 1, 1] - trace,
                  r[..., 1, 2] + r[..., 2, 1], r[..., 0, 2] - r[..., 2, 0]], -1),
        np.stack([r[..., 0, 2] + r[..., 2, 0], r[..., 1, 2] + r[..., 2, 1],
                  1 + 2 * r[..., 2, 2] - trace, r[..., 1, 0] - r[..., 0, 1]], -1),
        np.stack([r[..., 2, 1] - r[..., 1, 2], r[..., 0, 2] - r[..., 2, 0],
                  r[..., 1, 0] - r[..., 0, 1], 1 + trace], -1),
    ], -2)
    diagonal = np.stack([candidates[..., i, i] for i in range(4)], -1)
    best = np.argmax(diagonal, axis=-1)
    chosen = np.take_along_axis(candidates, best[..., None, None], axis=-2)[..., 0, :]
    quaternion = chosen / np.linalg.norm(chosen, axis=-1, keepdims=True)
    return np.where(quaternion[..., 3:4] < 0, -quaternion, quaternion)


def invert(matrix: np.ndarray) -> np.ndarray:
    """Inverse of rigid transforms ``[..., 4, 4]``."""
    out = np.zeros_like(matrix)
    rotation_t = np.swapaxes(matrix[..., :3, :3], -1, -2)
    out[..., :3, :3] = rotation_t
    out[..., :3, 3] = -np.einsum("...ij,...j->...i", rotation_t, matrix[..., :3, 3])
    out[..., 3, 3] = 1.0
    return out


def rotation_angle_between(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Angle [rad] of the rotation taking ``a[..., 3, 3]`` to ``b``; accurate near zero.

    ``|| Ra - Rb ||_F = 2 sqrt(2) sin(angle / 2)``, which, unlike arccos of the trace, does not
    lose half the digits for tiny angles.
    """
    norm = np.linalg.norm(a - b, axis=(-2, -1))
    return 2.0 * np.arcsin(np.clip(norm / (2.0 * np.sqrt(2.0)), 0.0, 1.0))
