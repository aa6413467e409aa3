"""Conversions and quaternion algebra: scipy agreement to 1e-12, round trips, dtypes,
shapes, scalar_first, and every bad input raising ValueError."""

import numpy as np
import pytest

import chasles
from conftest import same_rotation, unit_quats

Rotation = pytest.importorskip("scipy.spatial.transform").Rotation

ORDERS = [
    a + b + c
    for a in "xyz"
    for b in "xyz"
    for c in "xyz"
    if a != b and b != c
]
ORDERS = ORDERS + [o.upper() for o in ORDERS]


def test_there_are_24_conventions():
    assert len(ORDERS) == 24 and len(set(ORDERS)) == 24


@pytest.mark.parametrize("order", ORDERS)
def test_euler_agrees_with_scipy(order, rng):
    n = 500
    proper = order[0].lower() == order[2].lower()
    angles = rng.uniform(-np.pi, np.pi, size=(n, 3))
    angles[:, 1] = rng.uniform(0.05, np.pi - 0.05, n) if proper else rng.uniform(-1.5, 1.5, n)
    ours = chasles.quat_from_euler(angles, order)
    theirs = Rotation.from_euler(order, angles).as_quat(scalar_first=True)
    assert same_rotation(ours, theirs) < 1e-12
    q = unit_quats(rng, n)
    back = chasles.quat_to_euler(q, order)
    expected = Rotation.from_quat(q, scalar_first=True).as_euler(order)
    assert np.abs(back - expected).max() < 1e-12
    # Round trip: angles in the ranges come back.
    assert np.abs(chasles.quat_to_euler(ours, order) - angles).max() < 1e-12


@pytest.mark.parametrize("order", ["xyz", "ZXZ"])
def test_euler_at_gimbal_lock_keeps_the_rotation(order):
    middle = 0.0 if order == "ZXZ" else np.pi / 2
    q = chasles.quat_from_euler([0.3, middle, 0.2], order)
    a = chasles.quat_to_euler(q, order)
    assert a[2] == 0.0
    assert same_rotation(chasles.quat_from_euler(a, order), q) < 1e-12


def test_matrices_agree_with_scipy(rng):
    q = unit_quats(rng, 400)
    m = chasles.quat_to_matrix(q)
    assert np.abs(m - Rotation.from_quat(q, scalar_first=True).as_matrix()).max() < 1e-12
    back = chasles.quat_from_matrix(m)
    assert same_rotation(back, q) < 1e-12
    assert (back[:, 0] >= 0).all()
    theirs = Rotation.from_matrix(m).as_quat(scalar_first=True)
    assert same_rotation(back, theirs) < 1e-12
    # 4x4 homogeneous rotations too; exact at 180 degrees.
    m4 = np.zeros((400, 4, 4))
    m4[:, :3, :3] = m
    m4[:, 3, 3] = 1
    assert same_rotation(chasles.quat_from_matrix(m4), q) < 1e-12
    assert np.array_equal(chasles.quat_from_matrix(np.diag([-1.0, -1.0, 1.0])), [0, 0, 0, 1])


def test_rotvecs_products_and_rotation_agree_with_scipy(rng):
    q, p = unit_quats(rng, 300), unit_quats(rng, 300)
    r, s = Rotation.from_quat(q, scalar_first=True), Rotation.from_quat(p, scalar_first=True)
    assert np.abs(chasles.quat_to_rotvec(q) - r.as_rotvec()).max() < 1e-12
    rv = rng.normal(size=(300, 3))
    assert same_rotation(chasles.quat_from_rotvec(rv), Rotation.from_rotvec(rv).as_quat(scalar_first=True)) < 1e-12
    assert same_rotation(chasles.quat_mul(q, p), (r * s).as_quat(scalar_first=True)) < 1e-12
    v = rng.normal(size=(300, 3))
    assert np.abs(chasles.rotate(q, v) - r.apply(v)).max() < 1e-12
    assert np.abs(chasles.quat_angle(q, p) - (r.inv() * s).magnitude()).max() < 1e-12
    assert same_rotation(chasles.quat_inv(q), r.inv().as_quat(scalar_first=True)) < 1e-12


def test_round_trips(rng):
    q = unit_quats(rng, 200)
    axis, angle = chasles.quat_to_axis_angle(q)
    assert np.abs(chasles.quat_from_axis_angle(axis, angle) - q).max() < 1e-12
    assert np.abs(chasles.quat_exp(chasles.quat_log(q)) - q).max() < 1e-12
    half = chasles.quat_pow(q, 0.5)
    assert np.abs(chasles.quat_mul(half, half) - q).max() < 1e-12
    assert np.abs(chasles.quat_normalize(3.0 * q) - q).max() < 1e-15
    assert np.array_equal(chasles.quat_conj(chasles.quat_conj(q)), q)


def test_dual_quaternions_round_trip(rng):
    q, t = unit_quats(rng, 200), rng.normal(size=(200, 3))
    d = chasles.dq_from_rt(q, t)
    q2, t2 = chasles.dq_to_rt(d)
    assert np.abs(q2 - q).max() < 1e-15 and np.abs(t2 - t).max() < 1e-14
    m = chasles.dq_to_matrix(d)
    assert np.abs(m[:, :3, 3] - t).max() < 1e-14
    assert np.abs(m[:, :3, :3] - chasles.quat_to_matrix(q)).max() < 1e-15
    d2 = chasles.dq_from_matrix(m)
    assert same_rotation(d2[:, :4], q) < 1e-12
    assert np.abs(chasles.dq_to_rt(d2)[1] - t).max() < 1e-12
    p = rng.normal(size=(200, 3))
    moved = np.einsum("nij,nj->ni", m[:, :3, :3], p) + t
    assert np.abs(chasles.dq_transform(d, p) - moved).max() < 1e-12
    one = chasles.dq_mul(d, chasles.dq_inv(d))
    assert np.abs(one - [1, 0, 0, 0, 0, 0, 0, 0]).max() < 1e-12
    half = chasles.dq_pow(d, 0.5)
    assert np.abs(chasles.dq_mul(half, half) - d).max() < 1e-12
    axis, point, angle, slide = chasles.screw(d)
    again = chasles.dq_from_screw(axis, point, angle, slide)
    assert np.abs(again - d).max() < 1e-10
    assert np.abs(chasles.dq_normalize(2.5 * d) - d).max() < 1e-14


# Every function, with arguments of the shapes it takes: batched (2, 3) items.
def cases(rng, dtype):
    q = unit_quats(rng, 2, 3).astype(dtype)
    v = rng.normal(size=(2, 3, 3)).astype(dtype)
    d = chasles.dq_from_rt(q, v)
    t = rng.uniform(size=(2, 3)).astype(dtype)
    m = chasles.quat_to_matrix(q)
    m4 = chasles.dq_to_matrix(d)
    return [
        ("quat_from_euler", (v, "xyz"), (2, 3, 4)),
        ("quat_to_euler", (q, "ZYZ"), (2, 3, 3)),
        ("quat_from_matrix", (m,), (2, 3, 4)),
        ("quat_to_matrix", (q,), (2, 3, 3, 3)),
        ("quat_from_rotvec", (v,), (2, 3, 4)),
        ("quat_to_rotvec", (q,), (2, 3, 3)),
        ("quat_from_axis_angle", (v, t), (2, 3, 4)),
        ("quat_mul", (q, q), (2, 3, 4)),
        ("quat_conj", (q,), (2, 3, 4)),
        ("quat_inv", (q,), (2, 3, 4)),
        ("quat_normalize", (q,), (2, 3, 4)),
        ("quat_log", (q,), (2, 3, 4)),
        ("quat_exp", (q,), (2, 3, 4)),
        ("quat_pow", (q, t), (2, 3, 4)),
        ("quat_angle", (q, q), (2, 3)),
        ("rotate", (q, v), (2, 3, 3)),
        ("dq_from_rt", (q, v), (2, 3, 8)),
        ("dq_from_matrix", (m4,), (2, 3, 8)),
        ("dq_to_matrix", (d,), (2, 3, 4, 4)),
        ("dq_transform", (d, v), (2, 3, 3)),
        ("dq_mul", (d, d), (2, 3, 8)),
        ("dq_inv", (d,), (2, 3, 8)),
        ("dq_normalize", (d,), (2, 3, 8)),
        ("dq_pow", (d, t), (2, 3, 8)),
        ("slerp", (q, q[::-1], t), (2, 3, 4)),
        ("sclerp", (d, d[::-1], t), (2, 3, 8)),
    ]


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_shapes_and_dtypes_are_kept(rng, dtype):
    for name, args, shape in cases(rng, dtype):
        out = getattr(chasles, name)(*args)
        assert out.shape == shape, name
        assert out.dtype == dtype, name
        # The batch is the items one by one.
        one = getattr(chasles, name)(*[a[1, 2] if isinstance(a, np.ndarray) else a for a in args])
        assert np.allclose(one, out[1, 2], atol=1e-5), name
    axis, angle = chasles.quat_to_axis_angle(unit_quats(rng, 5).astype(dtype))
    assert axis.dtype == angle.dtype == dtype


def test_lists_and_integers_give_float64_and_scalars_broadcast():
    q = chasles.quat_from_axis_angle([0, 0, 1], [0.0, np.pi / 2, np.pi])
    assert q.shape == (3, 4) and q.dtype == np.float64
    r = chasles.rotate(q, [1, 0, 0])
    assert np.allclose(r, [[1, 0, 0], [0, 1, 0], [-1, 0, 0]], atol=1e-12)
    # float32 arrays with Python numbers stay float32
    q32 = np.array([1, 0, 0, 0], dtype=np.float32)
    assert chasles.quat_pow(q32, 0.5).dtype == np.float32
    assert chasles.quat_pow(q32, np.float64(0.5)).dtype == np.float64


def test_scalar_first_false_is_scipys_order(rng):
    q = unit_quats(rng, 50)
    xyzw = np.roll(q, -1, axis=-1)
    assert np.array_equal(chasles.quat_to_matrix(xyzw, scalar_first=False), chasles.quat_to_matrix(q))
    e = chasles.quat_from_euler([0.1, 0.2, 0.3], "XYZ", scalar_first=False)
    assert np.allclose(e, Rotation.from_euler("XYZ", [0.1, 0.2, 0.3]).as_quat(), atol=1e-15)
    d = chasles.dq_from_rt(q, np.ones((50, 3)))
    d2 = chasles.dq_from_rt(xyzw, np.ones((50, 3)), scalar_first=False)
    assert np.allclose(d2[:, :4], xyzw) and np.allclose(d2[:, 4:], np.roll(d[:, 4:], -1, axis=-1))


def raises(fn, *args, match, **kw):
    with pytest.raises(ValueError, match=match):
        fn(*args, **kw)


def test_bad_inputs_raise_value_error():
    z = [0.0, 0.0, 0.0, 0.0]
    nan = [np.nan, 0.0, 0.0, 1.0]
    for fn in (chasles.quat_to_euler,):
        raises(fn, z, "xyz", match="zero length")
        raises(fn, nan, "xyz", match="not finite")
    raises(chasles.quat_from_euler, [0, 0, 0], "xyx y", match="unknown Euler order")
    raises(chasles.quat_from_euler, [0, 0, 0], "xXy", match="unknown Euler order")
    raises(chasles.quat_from_euler, [0, 0, 0], "xxy", match="unknown Euler order")
    raises(chasles.quat_from_euler, [0, np.inf, 0], "xyz", match="not finite")
    raises(chasles.quat_from_euler, [0, 0], "xyz", match=r"angles must have shape \(\.\.\., 3\), got \(2,\)")
    raises(chasles.quat_to_matrix, np.zeros((5, 3)), match=r"q must have shape \(\.\.\., 4\), got \(5, 3\)")
    raises(chasles.quat_to_matrix, [z, [1, 0, 0, 0]], match=r"at index \(0,\): quaternion has zero length")
    raises(chasles.quat_from_matrix, np.diag([1.0, 1.0, -1.0]), match="not a rotation.*reflection")
    raises(chasles.quat_from_matrix, 2 * np.eye(3), match="not a rotation")
    raises(chasles.quat_from_matrix, np.eye(5), match=r"m must have shape \(\.\.\., 3, 3\)")
    raises(chasles.quat_mul, np.ones((2, 4)), np.ones((3, 4)), match="do not broadcast.*a \\(2,\\), b \\(3,\\)")
    raises(chasles.quat_log, z, match="zero length")
    raises(chasles.quat_log, nan, match="not finite")
    raises(chasles.quat_pow, z, 0.5, match="zero length")
    raises(chasles.quat_inv, z, match="zero length")
    raises(chasles.quat_normalize, nan, match="not finite")
    raises(chasles.rotate, z, [1, 0, 0], match="zero length")
    raises(chasles.quat_from_axis_angle, [0, 0, 0], 1.0, match="rotation axis has zero length")
    raises(chasles.quat_from_rotvec, [np.nan, 0, 0], match="not finite")
    raises(chasles.quat_to_rotvec, z, match="zero length")
    raises(chasles.quat_angle, z, [1, 0, 0, 0], match="zero length")
    raises(chasles.quat_to_euler, "abc", "xyz", match="q: cannot be read as an array of float64")
    raises(chasles.dq_from_rt, z, [0, 0, 0], match="zero length")
    raises(chasles.dq_from_rt, [1, 0, 0, 0], [0, np.nan, 0], match="translation is not finite")
    raises(chasles.dq_to_rt, np.zeros(8), match="zero length")
    raises(chasles.dq_from_matrix, np.diag([1.0, 1.0, 1.0, 2.0]), match="not a rigid")
    raises(chasles.dq_from_matrix, np.eye(3), match=r"m must have shape \(\.\.\., 4, 4\)")
    raises(chasles.dq_to_matrix, np.full(8, np.nan), match="not finite")
    raises(chasles.dq_transform, np.zeros(8), [0, 0, 0], match="zero length")
    raises(chasles.dq_inv, np.zeros(8), match="zero length")
    raises(chasles.dq_pow, np.zeros(8), 0.5, match="zero length")
    raises(chasles.screw, np.zeros(8), match="zero length")
    raises(chasles.dq_from_screw, [0, 0, 0], [0, 0, 0], 1.0, 0.0, match="screw axis")
    raises(chasles.slerp, z, [1, 0, 0, 0], 0.5, match="zero length")
    raises(chasles.slerp, [1, 0, 0, 0], [1, 0, 0, 0], np.nan, match="interpolation parameter is not finite")


def test_misaligned_and_strided_inputs_are_read(rng):
    q = unit_quats(rng, 10)
    raw = np.frombuffer(b"\0" + q.tobytes(), dtype=np.uint8)[1:]
    misaligned = raw.view(np.float64).reshape(10, 4)
    assert not misaligned.flags.aligned
    assert np.array_equal(chasles.quat_to_matrix(misaligned), chasles.quat_to_matrix(q))
    wide = np.zeros((10, 8))
    wide[:, ::2] = q
    assert np.array_equal(chasles.quat_conj(wide[:, ::2]), chasles.quat_conj(q))
    assert np.array_equal(chasles.quat_conj(q.T.copy().T), chasles.quat_conj(q))


def both_builds(fn, *args, **kw):
    """fn's result with the batch loops' AVX2 build (where the processor has AVX2) and with
    the baseline build."""
    native = chasles._chasles
    was = native._set_simd(True)
    try:
        wide = fn(*args, **kw)
        native._set_simd(False)
        base = fn(*args, **kw)
    finally:
        native._set_simd(was)
    return wide, base


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_batch_conversions_are_the_same_in_every_build_and_layout(rng, dtype):
    # Enough items for every thread's run, not a whole number of the library's blocks; the
    # AVX2 and baseline builds of the batch loops give the same bits, and so does a
    # broadcast call (item by item) or one item at a time.
    q = (unit_quats(rng, 5001) * rng.uniform(0.1, 10.0, size=(5001, 1))).astype(dtype)
    q[:50] = chasles.quat_from_euler(rng.uniform(-3, 3, size=(50, 3)) * [1, 0, 1] + [0, np.pi / 2, 0], "xyz")
    q[50:60, 1:3] = 0.0
    for order in ["xyz", "ZYZ", "yxy", "XZY"]:
        wide, base = both_builds(chasles.quat_to_euler, q, order)
        assert np.array_equal(wide, base), order
        assert np.array_equal(chasles.quat_to_euler(q[None], order)[0], wide)
        assert np.array_equal(chasles.quat_to_euler(q[1234], order), wide[1234])
        xyzw = np.roll(q, -1, axis=1)
        assert np.array_equal(chasles.quat_to_euler(xyzw, order, scalar_first=False), wide)
        # Against scipy: float64 to 1e-12; gimbal lock sets the third angle to 0 (scipy
        # agrees on the rotation there).
        if dtype == np.float64:
            ref = Rotation.from_quat(q[60:], scalar_first=True).as_euler(order)
            assert np.abs(wide[60:] - ref).max() < 1e-12, order
        if order == "xyz":
            assert (wide[:50, 2] == 0).all()
            back = chasles.quat_from_euler(wide[:50], order)
            assert same_rotation(back, q[:50] / np.linalg.norm(q[:50], axis=1, keepdims=True)) < 1e-5
    m = chasles.quat_to_matrix(q)
    wide, base = both_builds(chasles.quat_from_matrix, m)
    assert np.array_equal(wide, base)
    assert np.array_equal(chasles.quat_from_matrix(m[777]), wide[777])
    wide, base = both_builds(chasles.quat_to_matrix, q)
    assert np.array_equal(wide, base)
    assert np.array_equal(chasles.quat_to_matrix(q[4321]), wide[4321])


def test_batch_conversions_report_the_first_bad_item(rng):
    q = unit_quats(rng, 20000)
    q[15000] = 0.0
    q[17000] = np.nan
    raises(chasles.quat_to_euler, q, "xyz", match=r"at index \(15000,\): quaternion has zero length")
    raises(chasles.quat_to_matrix, q, match=r"at index \(15000,\): quaternion has zero length")
    m = chasles.quat_to_matrix(unit_quats(rng, 20000)).reshape(4, 5000, 3, 3)
    m[3, 10] = np.diag([1.0, 1.0, -1.0])
    m[2, 4000, 0, 0] = np.inf
    raises(chasles.quat_from_matrix, m, match=r"at index \(2, 4000\): rotation matrix is not finite")
    m[2, 4000, 0, 0] = 1.0
    raises(chasles.quat_from_matrix, m, match=r"at index \(2, 4000\): the matrix is not a rotation")
    m[2, 4000] = np.eye(3)
    raises(chasles.quat_from_matrix, m, match=r"at index \(3, 10\): the matrix is not a rotation: determinant")


def test_tiny_and_huge_quaternions_give_their_rotation():
    # |q|² subnormal (2/|q|² would overflow) or past the largest float: normalized first.
    quarter = chasles.quat_to_matrix([np.sqrt(0.5), 0.0, 0.0, np.sqrt(0.5)])
    for s in [1e-160, 1e-300, 1e160, 1e300]:
        q = np.array([[1.0, 0.0, 0.0, 1.0]] * 3) * s
        assert np.abs(chasles.quat_to_matrix(q) - quarter).max() < 1e-15, s
        assert np.abs(chasles.rotate(q[0], [1.0, 0.0, 0.0]) - [0.0, 1.0, 0.0]).max() < 1e-15, s
