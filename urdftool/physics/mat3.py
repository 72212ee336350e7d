"""3-vectors and 3x3 matrices as tuples, in pure Python (no numpy: ``urdftool check`` starts fast).

Enough for rules that place frames and judge inertia tensors: roll-pitch-yaw rotations,
products, and the eigenvalues of a symmetric matrix in closed form. Matrices are tuples of
three row tuples; any sequence of sequences (a numpy array too) is accepted as input.
"""

from __future__ import annotations

import math
import struct

from urdftool.numbers import power

Vector = tuple[float, float, float]
Matrix = tuple[Vector, Vector, Vector]

IDENTITY: Matrix = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
_THIRD_TURN = 2 * math.pi / 3


def placement(origin) -> tuple[Vector, Matrix]:
    """(xyz, R) of a :class:`urdftool.description.values.Origin`: its ``xyz`` as it is, a tuple
    of three floats (:func:`~urdftool.description.values.origin` reads it so)."""
    return origin.xyz, rpy_matrix(origin.rpy)


def vector(values) -> Vector:
    x, y, z = values
    return (float(x), float(y), float(z))


def matrix(rows) -> Matrix:
    (a, b, c), (d, e, f), (g, h, i) = rows
    return ((float(a), float(b), float(c)), (float(d), float(e), float(f)),
            (float(g), float(h), float(i)))


def diagonal(values) -> Matrix:
    a, b, c = values
    return ((float(a), 0.0, 0.0), (0.0, float(b), 0.0), (0.0, 0.0, float(c)))


def rpy_matrix(rpy) -> Matrix:
    """Rotation matrix of URDF roll-pitch-yaw (fixed axes x, y, z): Rz(y) Ry(p) Rx(r).
    An ``rpy`` of three +0.0 (absent, or written as zeros) gives the one :data:`NO_TURN`."""
    r, p, y = rpy
    if r == 0.0 and p == 0.0 and y == 0.0 and math.copysign(1.0, r) > 0 \
            and math.copysign(1.0, p) > 0 and math.copysign(1.0, y) > 0:
        return NO_TURN
    return _rpy_matrix(r, p, y)


def _rpy_matrix(r, p, y) -> Matrix:
    if math.isinf(r) or math.isinf(p) or math.isinf(y):
        return _UNDEFINED  # math.cos(inf) raises (a nan angle gives nan, as before)
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), \
        math.cos(y), math.sin(y)
    return ((cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
            (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
            (-sp, cp * sr, cp * cr))


_UNDEFINED: Matrix = ((math.nan,) * 3,) * 3  # the rotation of an infinite angle: unknown
NO_TURN: Matrix = _rpy_matrix(0.0, 0.0, 0.0)  # rpy 0 0 0: IDENTITY's values, one of them -0.0


def kept_by_no_turn(m) -> bool:
    """Whether ``R m R^T`` for R = NO_TURN (entries 1.0 and zeros of either sign) is ``m`` to
    the bit: every entry finite (0 * inf is nan) and none -0.0 (-0.0 + 0.0 is 0.0); each
    product and sum then adds zeros to a number that is not -0.0."""
    (a, b, c), (d, e, f), (g, h, i) = m
    if not math.isfinite(a + b + c + d + e + f + g + h + i):  # overflow: just not taken
        return False
    # -0.0's eight bytes anywhere (also across two numbers: then the products are just made)
    return _NEGATIVE_ZERO not in _NINE.pack(a, b, c, d, e, f, g, h, i)


_NINE = struct.Struct("<9d")
_NEGATIVE_ZERO = struct.pack("<d", -0.0)


# Written out term by term (no generators): rules call these hundreds of thousands of times on
# a large robot. Each sum is taken in index order, as before, so results are the same to the bit.

def apply(m, v) -> Vector:
    """The product ``m @ v``."""
    (a, b, c), (d, e, f), (g, h, i) = m
    x, y, z = v
    return (a * x + b * y + c * z, d * x + e * y + f * z, g * x + h * y + i * z)


def multiply(a, b) -> Matrix:
    """The product ``a @ b``."""
    (b00, b01, b02), (b10, b11, b12), (b20, b21, b22) = b
    (a00, a01, a02), (a10, a11, a12), (a20, a21, a22) = a
    return ((a00 * b00 + a01 * b10 + a02 * b20, a00 * b01 + a01 * b11 + a02 * b21,
             a00 * b02 + a01 * b12 + a02 * b22),
            (a10 * b00 + a11 * b10 + a12 * b20, a10 * b01 + a11 * b11 + a12 * b21,
             a10 * b02 + a11 * b12 + a12 * b22),
            (a20 * b00 + a21 * b10 + a22 * b20, a20 * b01 + a21 * b11 + a22 * b21,
             a20 * b02 + a21 * b12 + a22 * b22))


def transpose(m) -> Matrix:
    (a, b, c), (d, e, f), (g, h, i) = m
    return ((a, d, g), (b, e, h), (c, f, i))


def rotate(tensor, rotation) -> Matrix:
    """A tensor expressed in a frame rotated by ``rotation``: ``R T R^T`` (without the
    products for :data:`NO_TURN` where they give ``T`` back to the bit)."""
    if rotation is NO_TURN and kept_by_no_turn(tensor):
        return matrix(tensor)
    return multiply(multiply(rotation, tensor), transpose(rotation))


def add(a, b) -> Vector:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def scaled(m, factor: float) -> Matrix:
    (a, b, c), (d, e, f), (g, h, i) = m
    return ((a * factor, b * factor, c * factor), (d * factor, e * factor, f * factor),
            (g * factor, h * factor, i * factor))


def trace(m) -> float:
    return m[0][0] + m[1][1] + m[2][2]


def cross(a, b) -> Vector:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def eigvalsh(m) -> Vector:
    """Eigenvalues of a symmetric matrix, ascending (its lower triangle is read, as numpy does).

    Closed form, made robust as in Eberly's "A Robust Eigensolver for 3x3 Symmetric Matrices":
    ``B = (A - q I) / p`` (``q`` the mean eigenvalue, ``p`` their spread) has eigenvalues
    ``2 cos(phi + 2 k pi / 3)`` with ``cos(3 phi) = det(B) / 2``. That is exact for the
    eigenvalue farthest from the others, but a nearly repeated pair would come out split by
    ~1e-8; so the pair is taken from ``B`` restricted to the plane orthogonal to the isolated
    eigenvalue's eigenvector (a 2x2 problem). Accurate to a few ulps of the largest magnitude.

    Computed once per process for each lower triangle, as bits (the corpus's check asks 1,469
    times, of 530 matrices: the rules and the fixes ask again of each link's declared and
    computed tensors); the same bits in, the very same tuple out.
    """
    a00, a11, a22 = float(m[0][0]), float(m[1][1]), float(m[2][2])
    a10, a20, a21 = float(m[1][0]), float(m[2][0]), float(m[2][1])
    if a10 == 0 and a20 == 0 and a21 == 0:
        return tuple(sorted((a00, a11, a22)))
    key = _SIX.pack(a00, a11, a22, a10, a20, a21)  # (the bits: -0.0 is not 0.0 here)
    found = _EIGENVALUES.get(key)
    if found is None:
        if len(_EIGENVALUES) >= _EIGENVALUES_KEPT:
            _EIGENVALUES.clear()
        found = _EIGENVALUES[key] = _eigvalsh(a00, a11, a22, a10, a20, a21)
    return found


_SIX = struct.Struct("<6d")
_EIGENVALUES: dict[bytes, Vector] = {}  # the lower triangle's bytes -> its eigenvalues
_EIGENVALUES_KEPT = 4096  # (then forgotten at once: a process checks many robots)


def _eigvalsh(a00, a11, a22, a10, a20, a21) -> Vector:
    """:func:`eigvalsh` of a matrix with a product of inertia, from its lower triangle."""
    scale = max(abs(a00), abs(a11), abs(a22), abs(a10), abs(a20), abs(a21))
    a00, a11, a22, a10, a20, a21 = (v / scale for v in (a00, a11, a22, a10, a20, a21))
    q = (a00 + a11 + a22) / 3
    p = math.sqrt((power(a00 - q, 2) + power(a11 - q, 2) + power(a22 - q, 2)
                   + 2 * (a10 * a10 + a20 * a20 + a21 * a21)) / 6)
    if p == 0:
        return (q * scale,) * 3
    b = (((a00 - q) / p, a10 / p, a20 / p), (a10 / p, (a11 - q) / p, a21 / p),
         (a20 / p, a21 / p, (a22 - q) / p))
    half_det = (b[0][0] * (b[1][1] * b[2][2] - b[2][1] * b[2][1])
                - b[1][0] * (b[1][0] * b[2][2] - b[2][1] * b[2][0])
                + b[2][0] * (b[1][0] * b[2][1] - b[1][1] * b[2][0])) / 2
    phi = math.acos(min(max(half_det, -1.0), 1.0)) / 3
    low, middle, high = sorted(2 * math.cos(phi + k * _THIRD_TURN) for k in range(3))
    isolated = low if middle - low > high - middle else high
    rows = [(b[i][0] - (isolated if i == 0 else 0.0), b[i][1] - (isolated if i == 1 else 0.0),
             b[i][2] - (isolated if i == 2 else 0.0)) for i in range(3)]
    v = max((cross(rows[0], rows[1]), cross(rows[0], rows[2]), cross(rows[1], rows[2])),
            key=lambda c: dot(c, c))
    v = tuple(x / math.sqrt(dot(v, v)) for x in v)
    if abs(v[0]) > abs(v[1]):
        u = (-v[2] / math.hypot(v[0], v[2]), 0.0, v[0] / math.hypot(v[0], v[2]))
    else:
        u = (0.0, v[2] / math.hypot(v[1], v[2]), -v[1] / math.hypot(v[1], v[2]))
    w = cross(v, u)
    bu, bw = apply(b, u), apply(b, w)
    uu, ww, uw = dot(u, bu), dot(w, bw), dot(u, bw)
    mean, radius = (uu + ww) / 2, math.hypot((uu - ww) / 2, uw)
    moments = (dot(v, apply(b, v)), mean - radius, mean + radius)
    return tuple(sorted((q + p * e) * scale for e in moments))
