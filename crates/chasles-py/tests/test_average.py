"""`chasles.average`: the rigid mean against DIB, scipy's rotations and `chasles average`;
bi-invariance; robust means against outliers; batches, dtypes and bad input."""

import json

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import chasles
from test_blend import random_dqs


def noisy_poses(rng, n, sigma, outliers=0):
    """n poses near a random true pose (a random twist of deviation sigma on each), the
    last `outliers` of them replaced by random poses far away; and the true pose."""
    truth = random_dqs(rng)
    twists = rng.normal(scale=sigma, size=(n, 6))
    moves = chasles.dq_from_rt(chasles.quat_from_rotvec(twists[:, :3]), twists[:, 3:])
    poses = chasles.dq_mul(truth, moves)
    if outliers:
        poses[n - outliers :] = random_dqs(rng, outliers, spread=5.0)
    return poses, truth


def pose_distance(a, b):
    """The turn (radians) and the move between two poses, in quadrature."""
    ra, ta = chasles.dq_to_rt(a)
    rb, tb = chasles.dq_to_rt(b)
    turn = chasles.quat_angle(ra, rb)
    return float(np.hypot(turn, np.linalg.norm(ta - tb)))


def test_the_rigid_mean_is_dib_and_its_rotation_the_geodesic_mean(rng):
    x = random_dqs(rng, 40, 5, spread=2.0)
    x = chasles.dq_mul(x, random_dqs(rng, 40, 1))  # spread the rotations about a random one
    w = rng.uniform(0.1, 1.0, size=(40, 5))
    m, weights, distances, scale, iters, capped = chasles.average(x, w, full_output=True)
    dib = chasles.blend(x, w, "dib", precision=1.5e-10, max_iterations=200)
    same = np.minimum(np.abs(m - dib).max(axis=1), np.abs(m + dib).max(axis=1))
    assert same.max() < 1e-9
    assert np.allclose(weights, w / w.sum(axis=1, keepdims=True), rtol=1e-15, atol=0)
    assert np.isnan(scale).all() and not capped.any() and (iters >= 1).all()
    # scipy: the weighted sum of the rotations' logarithms about the mean's vanishes.
    for xi, wi, mi, di in zip(x, w, m, distances):
        r = Rotation.from_quat(xi[:, :4], scalar_first=True)
        rm = Rotation.from_quat(mi[:4], scalar_first=True)
        rel = (rm.inv() * r).as_rotvec()
        assert np.abs((wi[:, None] * rel).sum(axis=0)).max() < 1e-9
        # Each distance is the relative screw's turn and move, in quadrature (ℓ = 1).
        assert di.shape == (5,) and (di >= np.linalg.norm(rel, axis=1) - 1e-12).all()


def test_closed_forms():
    # A pure move and a pure turn from the identity: the mean is half of each, and each
    # pose's distance is half the move (in units) or half the turn (in radians).
    ident = chasles.dq_from_rt([1.0, 0, 0, 0], [0.0, 0, 0])
    moved = chasles.dq_from_rt([1.0, 0, 0, 0], [3.0, 4.0, 0])
    m, w, d, s, it, capped = chasles.average(np.stack([ident, moved]), full_output=True)
    r, t = chasles.dq_to_rt(m)
    assert np.abs(r - [1, 0, 0, 0]).max() < 1e-15 and np.abs(t - [1.5, 2.0, 0]).max() < 1e-12
    assert np.abs(d - 2.5).max() < 1e-12 and np.array_equal(w, [0.5, 0.5])
    turned = chasles.dq_from_rt(chasles.quat_from_axis_angle([0.0, 0, 1], 1.2), [0.0, 0, 0])
    m, w, d, s, it, capped = chasles.average(np.stack([ident, turned]), [1.0, 3.0], full_output=True)
    r, t = chasles.dq_to_rt(m)
    assert abs(chasles.quat_to_rotvec(r)[2] - 0.9) < 1e-12 and np.abs(t).max() < 1e-12
    assert np.abs(d - [0.9, 0.3]).max() < 1e-12


def test_the_mean_is_bi_invariant(rng):
    x = random_dqs(rng, 6, spread=1.5)
    g, h = random_dqs(rng), random_dqs(rng)
    m = chasles.average(x)
    moved = chasles.average(chasles.dq_mul(chasles.dq_mul(g, x), h))
    want = chasles.dq_mul(chasles.dq_mul(g, m), h)
    assert min(np.abs(moved - want).max(), np.abs(moved + want).max()) < 1e-9


@pytest.mark.parametrize("loss", ["huber", "tukey"])
def test_robust_means_ignore_outliers(rng, loss):
    poses, truth = noisy_poses(rng, 200, 0.02, outliers=40)
    inliers_mean = chasles.average(poses[:160])
    plain = chasles.average(poses)
    robust, w, d, s, iters, capped = chasles.average(poses, loss=loss, full_output=True)
    assert pose_distance(plain, truth) > 0.2
    assert pose_distance(robust, inliers_mean) < (0.02 if loss == "huber" else 1e-3)
    assert pose_distance(robust, truth) < 0.03
    assert not capped and np.isfinite(s) and s > 0
    if loss == "tukey":
        assert (w[160:] == 0).all() and (w[:160] > 0).all()
    assert abs(w.sum() - 1) < 1e-12


@pytest.mark.parametrize(
    "loss,options",
    [(None, {}), ("huber", {}), ("tukey", {}), ("huber", {"tuning": 2.0, "length_scale": 0.5}),
     ("tukey", {"scale": 0.3, "max_iterations": 3})],
)
def test_the_means_equal_the_cli(loss, options, cli, tmp_path, rng):
    poses, _ = noisy_poses(rng, 30, 0.05, outliers=5)
    w = rng.uniform(0.5, 1.0, size=30)
    path = tmp_path / "poses.json"
    path.write_text(json.dumps({"poses": [{"dq": list(p)} for p in poses], "weights": list(w)}))
    args = ["average", "--input", path] + (["--robust", loss] if loss else [])
    for key, value in options.items():
        args += ["--" + key.replace("_", "-"), str(value)]
    out = json.loads(cli(*args))
    m, weights, distances, scale, iters, capped = chasles.average(
        poses, w, loss, full_output=True, **options
    )
    theirs = np.array(out["dq"])
    assert min(np.abs(m - theirs).max(), np.abs(m + theirs).max()) < 1e-12
    assert iters == out["iterations"]
    if loss:
        assert np.abs(weights - np.array(out["weights"])).max() < 1e-12
        assert np.abs(distances - np.array(out["distances"])).max() < 1e-12
        assert abs(scale - out["scale"]) < 1e-12


def test_batches_broadcast_and_keep_their_dtype(rng):
    x = random_dqs(rng, 3, 4, 6)
    w = rng.uniform(0.1, 1.0, size=6)
    m = chasles.average(x, w, "huber")
    assert m.shape == (3, 4, 8)
    for i in range(3):
        for j in range(4):
            assert np.array_equal(m[i, j], chasles.average(x[i, j], w, "huber"))
    m32 = chasles.average(x.astype(np.float32), w.astype(np.float32))
    assert m32.dtype == np.float32
    assert np.abs(m32 - chasles.average(x, w)).max() < 1e-4
    # float32 poses with float64 weights: float32, the weights read as it.
    assert chasles.average(x.astype(np.float32), w).dtype == np.float32
    # scipy's order: the same means, scalar last.
    last = lambda a: np.concatenate([np.roll(a[..., :4], -1, axis=-1), np.roll(a[..., 4:], -1, axis=-1)], axis=-1)
    assert np.array_equal(chasles.average(last(x), w, scalar_first=False), last(chasles.average(x, w)))
    # Weights broadcast against the batch: (4, 6) for (3, 4, 6, 8) poses.
    w2 = rng.uniform(0.1, 1.0, size=(4, 6))
    m2, ww, dd, ss, it, cap = chasles.average(x, w2, full_output=True)
    assert m2.shape == (3, 4, 8) and ww.shape == dd.shape == (3, 4, 6) and it.shape == (3, 4)
    assert np.array_equal(m2[2, 1], chasles.average(x[2, 1], w2[1]))
    # The cap: one update, flagged.
    _, _, _, _, it, cap = chasles.average(x[0, 0], max_iterations=1, full_output=True)
    assert it == 1 and cap


def test_bad_input_is_a_value_error_naming_it(rng):
    x = random_dqs(rng, 4)
    bad = x.copy()
    bad[2, 0] *= 2
    with pytest.raises(ValueError, match="pose 2"):
        chasles.average(bad)
    nan = x.copy()
    nan[1, 5] = np.nan
    with pytest.raises(ValueError, match="pose 1"):
        chasles.average(nan)
    with pytest.raises(ValueError, match="unknown loss 'cauchy'"):
        chasles.average(x, loss="cauchy")
    with pytest.raises(ValueError, match="robust mean's"):
        chasles.average(x, tuning=2.0)
    for key in ("tuning", "scale", "length_scale", "precision"):
        with pytest.raises(ValueError, match=f"{key} must be positive"):
            chasles.average(x, loss="tukey", **{key: -1.0})
    with pytest.raises(ValueError, match="max_iterations must be at most 10000"):
        chasles.average(x, max_iterations=10**6)
    with pytest.raises(ValueError, match=r"poses must have shape \(\.\.\., n, 8\)"):
        chasles.average(np.ones((4, 7)))
    with pytest.raises(ValueError, match="weight"):
        chasles.average(x, [1.0, -1.0, 1.0, 1.0])
    with pytest.raises(ValueError, match="no poses|at least one"):
        chasles.average(np.zeros((0, 8)))
    far = chasles.dq_from_rt(np.tile([1.0, 0, 0, 0], (3, 1)), [[0, 0, 0], [1e200, 0, 0], [0, 1e200, 0]])
    with pytest.raises(ValueError):
        chasles.average(far, loss="huber")
