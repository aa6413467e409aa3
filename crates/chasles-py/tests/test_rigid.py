"""`chasles.interpolate_rigid`: rigid curves against `chasles interp --rigid`, ScLERP,
the rotation curves they reduce to, and the polygon of pure translations; batches, times,
dtypes and bad input."""

import json

import numpy as np
import pytest

import chasles
from test_blend import random_dqs

METHODS = ["sclerp", "squad", "spring"]


def chained(keys):
    """The keys with each one's sign chosen next to the one before (as the curves take them)."""
    k = keys.copy()
    for i in range(1, len(k)):
        if np.dot(k[i, :4], k[i - 1, :4]) < 0:
            k[i] = -k[i]
    return k


@pytest.mark.parametrize("method", METHODS + ["screw"])
def test_the_curves_equal_the_cli(method, cli, tmp_path, rng):
    keys = random_dqs(rng, 5, spread=2.0)
    times = np.cumsum(rng.uniform(0.5, 2.0, size=5))
    path = tmp_path / "keys.json"
    path.write_text(json.dumps({"keys": [{"dq": list(k), "time": t} for k, t in zip(keys, times)]}))
    out = tmp_path / "curve.json"
    screw = {"energy": "screw", "length_scale": 2.0} if method == "screw" else {}
    name = "spring" if screw else method
    flags = ["--energy", "screw", "--length-scale", "2"] if screw else []
    cli("interp", "--rigid", "--method", name, *flags, "--keys", path, "--frames", "41", "--out", out)
    rows = json.loads(out.read_text())
    theirs_r = np.array([[r["w"], r["x"], r["y"], r["z"]] for r in rows])
    theirs_t = np.array([[r["tx"], r["ty"], r["tz"]] for r in rows])
    curve, t, key = chasles.interpolate_rigid(keys, name, 41, times=times, full_output=True, **screw)
    r, tr = chasles.dq_to_rt(curve)
    assert curve.shape == (41, 8)
    assert np.abs(r - theirs_r).max() < 1e-12 and np.abs(tr - theirs_t).max() < 1e-12
    assert np.abs(t - [row["t"] for row in rows]).max() < 1e-12
    assert list(key) == [row["key"] if row["key"] is not None else -1 for row in rows]
    # Every key is a frame, exactly (chained to one hemisphere).
    assert np.array_equal(curve[key >= 0], chained(keys))


def test_sclerp_is_sclerp_between_keys(rng):
    keys = chained(random_dqs(rng, 2, spread=3.0))
    curve = chasles.interpolate_rigid(keys, "sclerp", 9)
    want = chasles.sclerp(keys[0], keys[1], np.linspace(0, 1, 9))
    assert np.abs(curve - want).max() < 1e-12


@pytest.mark.parametrize("method", ["slerp", "squad"])
def test_keys_without_translation_give_the_rotation_curves(method, rng):
    q = chasles.quat_normalize(rng.normal(size=(4, 4)))
    keys = chasles.dq_from_rt(q, np.zeros((4, 3)))
    curve = chasles.interpolate_rigid(keys, "sclerp" if method == "slerp" else method, 31)
    rot = chasles.interpolate(q, method, 31, timing="uniform")
    sign = np.sign((curve[:, :4] * rot).sum(axis=1))[:, None]
    assert np.abs(curve[:, :4] - sign * rot).max() < 1e-12
    assert np.abs(curve[:, 4:]).max() < 1e-15


def test_keys_without_rotation_give_the_polygon_under_sclerp(rng):
    t = rng.normal(size=(4, 3))
    keys = chasles.dq_from_rt(np.tile([1.0, 0, 0, 0], (4, 1)), t)
    curve = chasles.interpolate_rigid(keys, "sclerp", 10)
    _, moved = chasles.dq_to_rt(curve)
    want = np.concatenate([t[0:1], np.linspace(t[0], t[1], 4)[1:], np.linspace(t[1], t[2], 4)[1:],
                           np.linspace(t[2], t[3], 4)[1:]])
    assert np.abs(moved - want).max() < 1e-12


def test_batches_times_and_dtypes(rng):
    keys = random_dqs(rng, 3, 2, 4)
    times = np.array([0.0, 1.0, 3.0, 3.5])
    c = chasles.interpolate_rigid(keys, "squad", 20, times=times)
    assert c.shape == (3, 2, 20, 8)
    for i in range(3):
        for j in range(2):
            assert np.array_equal(c[i, j], chasles.interpolate_rigid(keys[i, j], "squad", 20, times=times))
    c32 = chasles.interpolate_rigid(keys.astype(np.float32), "sclerp", 20)
    assert c32.dtype == np.float32
    assert np.abs(c32 - chasles.interpolate_rigid(keys, "sclerp", 20)).max() < 1e-4
    assert chasles.interpolate_rigid(keys.astype(np.float32), times=times).dtype == np.float32
    # The split Spring's two problems: ℓ changes nothing; fewer steps, a coarser curve.
    split = chasles.interpolate_rigid(keys[0, 0], "spring", 20)
    assert np.array_equal(split, chasles.interpolate_rigid(keys[0, 0], "spring", 20, length_scale=5.0))
    rough, _, key = chasles.interpolate_rigid(
        keys[0, 0], "spring", 20, energy="screw", max_iterations=1, tolerance=0.5, full_output=True
    )
    screw = chasles.interpolate_rigid(keys[0, 0], "spring", 20, energy="screw")
    assert np.isfinite(rough).all() and np.array_equal(rough[key >= 0], screw[key >= 0])
    assert np.abs(rough - screw).max() > 1e-6  # one step stops short of the converged curve
    last = lambda a: np.concatenate([np.roll(a[..., :4], -1, axis=-1), np.roll(a[..., 4:], -1, axis=-1)], axis=-1)
    back = chasles.interpolate_rigid(last(keys), "squad", 20, times=times, scalar_first=False)
    assert np.array_equal(back, last(c))
    c2, t2, k2 = chasles.interpolate_rigid(keys, "squad", 20, times=times, full_output=True)
    assert np.array_equal(c2, c) and t2.shape == k2.shape == (3, 2, 20) and k2.dtype == np.int64


def test_bad_input_is_a_value_error_naming_it(rng):
    keys = random_dqs(rng, 3)
    bad = keys.copy()
    bad[1, :4] *= 3
    with pytest.raises(ValueError, match="key frame 1"):
        chasles.interpolate_rigid(bad)
    with pytest.raises(ValueError, match="unknown rigid method 'lerp'"):
        chasles.interpolate_rigid(keys, "lerp")
    with pytest.raises(ValueError, match="unknown energy 'bent'"):
        chasles.interpolate_rigid(keys, "spring", energy="bent")
    with pytest.raises(ValueError, match="Spring's"):
        chasles.interpolate_rigid(keys, "squad", length_scale=2.0)
    with pytest.raises(ValueError, match="max_frames"):
        chasles.interpolate_rigid(keys, frames=10**7)
    with pytest.raises(ValueError, match="frames"):
        chasles.interpolate_rigid(keys, frames=2)
    with pytest.raises(ValueError, match="frames must be at least"):
        chasles.interpolate_rigid(np.full((1, 8), np.nan), "spring", 0)
    with pytest.raises(ValueError, match="time"):
        chasles.interpolate_rigid(keys, times=[0.0, 1.0])
    with pytest.raises(ValueError, match=r"keys must have shape \(\.\.\., K, 8\)"):
        chasles.interpolate_rigid(np.ones((3, 4)))
    with pytest.raises(ValueError, match="time"):
        chasles.interpolate_rigid(keys, times=[0.0, 2.0, 1.0])
    with pytest.raises(ValueError, match="length"):
        chasles.interpolate_rigid(keys, "spring", length_scale=-1.0)
