"""Property tests of Affine: classification of isometries (§3.1), inverses, batched application.

Every isometry of the plane is the identity, a translation, a rotation, a reflection or a
glide reflection (Kaplan §3.1); hypothesis builds each kind from its defining data, and
random compositions of them, and checks that ``Affine.classify`` recovers the data.
"""

from __future__ import annotations

import math
from functools import reduce

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tilekit.errors import GeometryError
from tilekit.geometry import Affine, Isometry

coord = st.floats(-100, 100, allow_nan=False)
point = st.tuples(coord, coord)
# angles kept away from 0 and 2*pi so that rotations are not (numerically) translations
turn = st.floats(0.01, 2 * math.pi - 0.01)
direction = st.floats(0, math.pi)
offset = st.floats(0.01, 50).flatmap(lambda r: st.sampled_from([r, -r]))


def rebuild(iso: Isometry) -> np.ndarray:
    """The map described by a classification."""
    if iso.kind == "identity":
        return np.eye(3)
    if iso.kind == "translation":
        return Affine.translation(*iso.vector)
    if iso.kind == "rotation":
        return Affine.rotation(iso.angle, iso.centre)
    if iso.kind == "reflection":
        return Affine.reflection(iso.angle, iso.centre)
    if iso.kind == "glide reflection":
        return Affine.translation(*iso.vector) @ Affine.reflection(iso.angle, iso.centre)
    raise AssertionError(iso.kind)


def close(a: np.ndarray, b: np.ndarray, tol: float = 1e-6) -> bool:
    return bool(np.allclose(a, b, atol=tol))


@given(point)
def test_translation(v) -> None:
    m = Affine.translation(*v)
    iso = Affine.classify(m)
    if math.hypot(*v) < 1e-6:
        assert iso.kind == "identity"
    else:
        assert iso.kind == "translation"
        assert np.allclose(iso.vector, v, atol=1e-9)
    assert close(rebuild(iso), m)


@given(turn, point)
def test_rotation(theta, centre) -> None:
    """A rotation is classified with its angle (mod 2 pi) and its unique fixed point."""
    m = Affine.rotation(theta, centre)
    iso = Affine.classify(m)
    assert iso.kind == "rotation"
    assert abs(math.remainder(iso.angle - theta, 2 * math.pi)) < 1e-9
    assert np.allclose(iso.centre, centre, atol=1e-6)
    assert close(Affine.apply(m, np.array(iso.centre)), np.array(iso.centre))
    assert close(rebuild(iso), m)


@given(direction, point)
def test_reflection(phi, p) -> None:
    """A reflection's axis has the given direction (mod pi) and passes through the point."""
    m = Affine.reflection(phi, p)
    iso = Affine.classify(m)
    assert iso.kind == "reflection"
    assert abs(math.remainder(iso.angle - phi, math.pi)) < 1e-9
    u = np.array([math.cos(iso.angle), math.sin(iso.angle)])
    d = np.array(p) - np.array(iso.centre)
    assert abs(d[0] * u[1] - d[1] * u[0]) < 1e-6  # p lies on the classified axis
    assert close(m @ m, np.eye(3))
    assert close(rebuild(iso), m)


@given(direction, point, offset)
def test_glide_reflection(phi, p, g) -> None:
    """A reflection followed by a translation along its axis is a glide with that vector."""
    u = np.array([math.cos(phi), math.sin(phi)])
    m = Affine.translation(*(g * u)) @ Affine.reflection(phi, p)
    iso = Affine.classify(m)
    assert iso.kind == "glide reflection"
    assert np.allclose(iso.vector, g * u, atol=1e-6)
    # the square of a glide is the translation by twice its vector (§3.1)
    assert close(m @ m, Affine.translation(*(2 * g * u)))
    assert close(rebuild(iso), m)


def isometry_strategy() -> st.SearchStrategy[np.ndarray]:
    one = st.one_of(
        point.map(lambda v: Affine.translation(*v)),
        st.tuples(turn, point).map(lambda a: Affine.rotation(*a)),
        st.tuples(direction, point).map(lambda a: Affine.reflection(*a)),
    )
    return st.lists(one, min_size=1, max_size=5).map(lambda ms: reduce(np.matmul, ms, np.eye(3)))


@settings(max_examples=200)
@given(isometry_strategy())
def test_compositions_classify_and_rebuild(m) -> None:
    """Any composition is one of the five kinds, of the right handedness, rebuilt exactly."""
    iso = Affine.classify(m)
    det = Affine.determinant(m)
    if det > 0:
        assert iso.kind in ("identity", "translation", "rotation")
    else:
        assert iso.kind in ("reflection", "glide reflection")
    assert close(rebuild(iso), m, 1e-5)


@settings(max_examples=200)
@given(isometry_strategy())
def test_inverse_round_trips(m) -> None:
    inv = Affine.inverse(m)
    assert close(inv @ m, np.eye(3), 1e-9)
    assert close(m @ inv, np.eye(3), 1e-9)
    assert close(Affine.inverse(inv), m, 1e-9)


@given(st.lists(isometry_strategy(), min_size=1, max_size=6))
def test_batched_inverse_equals_looped(ms) -> None:
    batch = np.array(ms)
    assert close(Affine.inverse(batch), np.array([Affine.inverse(m) for m in ms]), 1e-9)


@given(
    st.lists(isometry_strategy(), min_size=1, max_size=6),
    st.lists(point, min_size=1, max_size=8),
)
def test_batched_apply_equals_looped(ms, pts) -> None:
    batch = np.array(ms)
    pts = np.array(pts, dtype=float)
    out = Affine.apply(batch, pts)
    assert out.shape == (len(ms), len(pts), 2)
    for k, m in enumerate(ms):
        assert close(out[k], Affine.apply(m, pts), 1e-9)
        assert close(out[k], (np.column_stack([pts, np.ones(len(pts))]) @ m.T)[:, :2], 1e-9)


@given(isometry_strategy(), isometry_strategy())
def test_handedness_multiplies(a, b) -> None:
    """Direct times opposite is opposite, opposite times opposite is direct (§3.1)."""
    assert np.sign(Affine.determinant(a @ b)) == np.sign(Affine.determinant(a)) * np.sign(Affine.determinant(b))


def test_order_of_rotations() -> None:
    assert Affine.classify(Affine.rotation(2 * math.pi / 6, (1, 2))).order == 6
    assert Affine.classify(Affine.rotation(-math.pi / 2)).order == 4
    assert Affine.classify(Affine.rotation(1.0)).order is None
    assert Affine.classify(Affine.reflection(0.3)).order is None


def test_classify_rejects_non_isometries() -> None:
    with pytest.raises(GeometryError, match="not an isometry"):
        Affine.classify(Affine.scaling(2.0))
    with pytest.raises(GeometryError, match="singular"):
        Affine.inverse(np.diag([1.0, 0.0, 1.0]))
