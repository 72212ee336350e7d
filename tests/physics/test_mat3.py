"""Pure-Python 3x3 math against numpy."""

from __future__ import annotations

import math

import numpy as np
import pytest

from urdftool.physics import mat3

RNG = np.random.default_rng(7)


def _close(ours, theirs, scale):
    assert np.max(np.abs(np.asarray(ours) - np.asarray(theirs))) <= 1e-9 * scale


def _random_symmetric(size: float) -> np.ndarray:
    m = RNG.normal(size=(3, 3)) * size
    return m + m.T


@pytest.mark.parametrize("size", [1e-9, 1e-3, 1.0, 1e4])
def test_eigvalsh_random_symmetric(size):
    for _ in range(500):
        m = _random_symmetric(size)
        expected = np.linalg.eigvalsh(m)
        _close(mat3.eigvalsh(m), expected, np.abs(expected).max())


def test_eigvalsh_repeated_and_degenerate():
    cases = [np.zeros((3, 3)), np.eye(3) * 2.5, np.diag([3.0, -1.0, 2.0]),
             np.diag([1.0, 1.0, 1.0 + 1e-12]), [[1, 2, 0], [2, 1, 0], [0, 0, 1]]]
    for _ in range(200):  # rotated tensors with two equal moments, and rank-deficient ones
        q, _ = np.linalg.qr(RNG.normal(size=(3, 3)))
        moments = RNG.choice([[1.0, 1.0, 2.0], [0.0, 0.0, 1.0], [1.0, 2.0, 2.0], [0.0, 1.0, 1.0],
                              [-1.0, 1e-12, 1.0]])
        cases.append(q @ np.diag(moments) @ q.T)
    for m in cases:
        m = np.asarray(m, dtype=float)
        expected = np.linalg.eigvalsh(m)
        _close(mat3.eigvalsh(m), expected, max(np.abs(expected).max(), 1e-300))


def test_eigvalsh_ascending_and_exact_for_diagonal():
    assert mat3.eigvalsh(mat3.diagonal([3e-4, 1e-4, 2e-4])) == (1e-4, 2e-4, 3e-4)


def test_eigvalsh_computes_each_lower_triangle_once_by_its_bits(monkeypatch):
    """The rules and fixes ask again of the same tensors (1,469 asks of 530 in the corpus):
    each lower triangle is computed once, the very same tuple returned; a zero of the other
    sign is other bits, computed on its own (never the result of its twin)."""
    computed = []
    computing = mat3._eigvalsh
    monkeypatch.setattr(mat3, "_eigvalsh", lambda *six: computed.append(six) or computing(*six))
    monkeypatch.setattr(mat3, "_EIGENVALUES", {})
    m = ((2e-3, 1e-4, 0.0), (1e-4, 3e-3, 2e-5), (0.0, 2e-5, 1e-3))
    first = mat3.eigvalsh(m)
    assert mat3.eigvalsh(np.array(m)) is first
    assert mat3.eigvalsh(tuple(reversed([row[::-1] for row in m]))) is not first  # other bits
    signed = ((2e-3, 1e-4, -0.0), (1e-4, 3e-3, 2e-5), (-0.0, 2e-5, 1e-3))
    assert mat3.eigvalsh(signed) == computing(2e-3, 3e-3, 1e-3, 1e-4, -0.0, 2e-5)
    assert len(computed) == 3, computed
    _close(first, np.linalg.eigvalsh(np.array(m)), 3e-3)


def test_eigvalsh_forgets_all_it_kept_when_full(monkeypatch):
    monkeypatch.setattr(mat3, "_EIGENVALUES", {})
    monkeypatch.setattr(mat3, "_EIGENVALUES_KEPT", 2)
    for k in range(3):
        mat3.eigvalsh(((1.0 + k, 0.5, 0.0), (0.5, 2.0, 0.0), (0.0, 0.0, 3.0)))
    assert len(mat3._EIGENVALUES) == 1


def test_rpy_products_and_rotation_match_numpy():
    for _ in range(100):
        rpy = RNG.uniform(-math.pi, math.pi, 3)
        r = mat3.rpy_matrix(rpy)
        rx = np.array([[1, 0, 0], [0, math.cos(rpy[0]), -math.sin(rpy[0])],
                       [0, math.sin(rpy[0]), math.cos(rpy[0])]])
        ry = np.array([[math.cos(rpy[1]), 0, math.sin(rpy[1])], [0, 1, 0],
                       [-math.sin(rpy[1]), 0, math.cos(rpy[1])]])
        rz = np.array([[math.cos(rpy[2]), -math.sin(rpy[2]), 0],
                       [math.sin(rpy[2]), math.cos(rpy[2]), 0], [0, 0, 1]])
        _close(r, rz @ ry @ rx, 1.0)
        tensor, v = _random_symmetric(1.0), RNG.normal(size=3)
        _close(mat3.rotate(tensor, r), np.array(r) @ tensor @ np.array(r).T, 10.0)
        _close(mat3.multiply(r, tensor), np.array(r) @ tensor, 10.0)
        _close(mat3.apply(r, v), np.array(r) @ v, 10.0)
        assert mat3.trace(tensor) == pytest.approx(np.trace(tensor), rel=1e-12, abs=1e-12)


def _bits(m) -> list[str]:
    """Each entry as its exact float text (tells -0.0 from 0.0, keeps nan)."""
    return [float(v).hex() for row in m for v in row]


SPECIAL = [0.0, -0.0, 1e-3, -2.5, 5e-324, -5e-324, 1e308, math.inf, -math.inf, math.nan]


def test_rpy_zero_is_the_one_no_turn_and_its_value():
    assert mat3.rpy_matrix((0.0, 0.0, 0.0)) is mat3.NO_TURN
    assert _bits(mat3.NO_TURN) == _bits(mat3._rpy_matrix(0.0, 0.0, 0.0))
    for rpy in [(-0.0, 0.0, 0.0), (0.0, -0.0, 0.0), (0.0, 0.0, -0.0), (0.0, 0.0, 1e-300)]:
        turned = mat3.rpy_matrix(rpy)  # -0.0 turns some zeros' signs: computed, not shared
        assert turned is not mat3.NO_TURN and _bits(turned) == _bits(mat3._rpy_matrix(*rpy))


def test_rotate_by_no_turn_is_the_product_to_the_bit():
    # the shortcut for rpy 0 0 0 gives what R T R^T gives, for -0.0, subnormals, inf and nan
    rng = np.random.default_rng(7)
    for _ in range(400):
        values = [float(v) for v in rng.choice(SPECIAL, 6)]
        tensor = ((values[0], values[1], values[2]), (values[1], values[3], values[4]),
                  (values[2], values[4], values[5]))
        product = mat3.multiply(mat3.multiply(mat3.NO_TURN, tensor),
                                mat3.transpose(mat3.NO_TURN))
        assert _bits(mat3.rotate(tensor, mat3.NO_TURN)) == _bits(product)


def test_an_infinite_angle_turns_into_nan_not_an_error():
    # math.cos(inf) raises ValueError: every inertial rule crashed on <origin rpy="inf 0 0">
    for rpy in ((math.inf, 0.0, 0.0), (0.0, -math.inf, 0.0), (0.1, 0.2, math.inf)):
        assert all(math.isnan(v) for row in mat3.rpy_matrix(rpy) for v in row)
    turned = mat3.rpy_matrix((math.nan, 0.0, 0.0))  # nan angles as before: cos(nan) is nan
    assert turned[0][0] == 1.0 and math.isnan(turned[0][1])
