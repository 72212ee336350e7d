"""3-vectors and 3x3 matrices as tuples, in pure Python (no numpy: ``urdftool check`` starts fast).

Enough for rules that place frames and judge inertia tensors: roll-pitch-yaw rotations,
products, and the eigenvalues of a symmetric matrix in closed form. Matrices are tuples of
three row tuples; any sequence of sequences (a numpy array too) is accepted as input.
"""

from __future__ import annotations

import math

Vector = tuple[float, float, float]
Matrix = tuple[Vector, Vector, Vector]

IDENTITY: Matrix = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
_THIRD_TURN = 2 * math.pi / 3


def vector(values) -> Vector:
    return tuple(float(v) for v in values)


def matrix(rows) -> Matrix:
    return tuple(vector(row) for row in rows)


def diagonal(values) -> Matrix:
    a, b, c = values
    return ((float(a), 0.0, 0.0), (0.0, float(b), 0.0), (0.0, 0.0, float(c)))


def rpy_matrix(rpy) -> Matrix:
    """Rotation matrix of URDF roll-pitch-yaw (fixed axes x, y, z): Rz(y) Ry(p) Rx(r)."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), \
        math.cos(y), math.sin(y)
    return ((cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
            (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
            (-sp, cp * sr, cp * cr))


def apply(m, v) -> Vector:
    """The product ``m @ v``."""
    return tuple(m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2] for i in range(3))


def multiply(a, b) -> Matrix:
    """The product ``a @ b``."""
    return tuple(tuple(a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j]
                       for j in range(3)) for i in range(3))


def transpose(m) -> Matrix:
    return tuple(tuple(m[j][i] for j in range(3)) for i in range(3))


def rotate(tensor, rotation) -> Matrix:
    """A tensor expressed in a frame rotated by ``rotation``: ``R T R^T``."""
    return multiply(multiply(rotation, tensor), transpose(rotation))


def add(a, b) -> Vector:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def scaled(m, factor: float) -> Matrix:
    return tuple(tuple(v * factor for v in row) for row in m)


def trace(m) -> float:
    return m[0][0] + m[1][1] + m[2][2]


def eigvalsh(m) -> Vector:
    """Eigenvalues of a symmetric matrix, ascending (its lower triangle is read, as numpy does).

    Closed form (Smith 1961): the eigenvalues of ``B = (A - q I) / p`` are ``2 cos(phi + 2 k pi / 3)``
    with ``cos(3 phi) = det(B) / 2``, where ``q`` is the mean eigenvalue and ``p`` their spread.
    Accurate to a few ulps of the largest eigenvalue's magnitude.
    """
    a00, a11, a22 = float(m[0][0]), float(m[1][1]), float(m[2][2])
    a10, a20, a21 = float(m[1][0]), float(m[2][0]), float(m[2][1])
    if a10 == 0 and a20 == 0 and a21 == 0:
        return tuple(sorted((a00, a11, a22)))
    scale = max(abs(a00), abs(a11), abs(a22), abs(a10), abs(a20), abs(a21))
    a00, a11, a22, a10, a20, a21 = (v / scale for v in (a00, a11, a22, a10, a20, a21))
    q = (a00 + a11 + a22) / 3
    b00, b11, b22 = a00 - q, a11 - q, a22 - q
    p = math.sqrt((b00 * b00 + b11 * b11 + b22 * b22
                   + 2 * (a10 * a10 + a20 * a20 + a21 * a21)) / 6)
    if p == 0:
        return (q * scale,) * 3
    b00, b11, b22, b10, b20, b21 = (v / p for v in (b00, b11, b22, a10, a20, a21))
    half_det = (b00 * (b11 * b22 - b21 * b21) - b10 * (b10 * b22 - b21 * b20)
                + b20 * (b10 * b21 - b11 * b20)) / 2
    phi = math.acos(min(max(half_det, -1.0), 1.0)) / 3
    return tuple(sorted((q + 2 * p * math.cos(phi + k * _THIRD_TURN)) * scale for k in range(3)))
